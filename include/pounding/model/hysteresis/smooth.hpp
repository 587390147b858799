#pragma once
// The smooth hysteretic spring shared by the Bouc-Wen bearing and the friction pendulum (issue 25 §2, step 7;
// ../shared/research/systems-and-bridges.md §2): F = k d + Q(v) z, with
//   Q(v) = Q_fast - (Q_fast - Q_slow) exp(-rate |v|)   (Constantinou, Mokha & Reinhorn 1990; Q_fast = Q_slow: constant)
//   dz/du = (A - |z|^eta (gamma + beta sgn(z du))) / u_y   (Wen 1976; beta on the |du| term, as OpenSees)
// v the deformation rate (the stepper's velocity predictor), eta an integer in [1, max_eta].
//
// Integration over one step's increment du (rate independent): with sigma = sgn du, xi = |du| and w = sigma z the
// equation is dw/dxi = g(w) = (A - |w|^eta (gamma + beta sgn w)) / u_y, which only increases w (up to z_max =
// (A / (beta + gamma))^(1/eta)). One exponential Rosenbrock-Euler step (Hochbruck, Ostermann & Schweitzer 2009,
// order 2 for smooth g): w1 = w0 + xi phi(-J xi) g(w0), J = g'(w0), phi(x) = (1 - e^-x) / x = -expm1(-x) / x, then
// w1 <= z_max. It is exact for eta = 1 between the zero crossings of z (g is linear there), and unconditionally
// stable on the loading branch and on unloading with beta >= gamma (J <= 0), so a yield displacement of a fraction
// of a millimetre needs no sub-steps for stability (accuracy still wants xi small against u_y: the tests show
// second-order convergence with dt). lane::expm1 keeps a double lane and a SIMD lane bit-equal.
// Energy: the hysteretic part's work by the trapezoid rule, 0.5 (Q0 z0 + Q1 z1) du, minus the change of its
// recoverable part S = Q z^2 u_y / (2 A) (the energy of the initial elastic slope A Q / u_y), so that
// e_hysteretic (dissipated) + e_strain (k d^2/2 + S) is the spring's work.
#include <cmath>

#include "pounding/kernel/lane.hpp"
#include "pounding/model/hysteresis/spring_spec.hpp"

namespace pounding::model {

inline constexpr int smooth_max_eta = 8;

// Per-lane constants of one smooth spring.
template <class T> struct SmoothParams {
  T k, q_slow, q_fast, rate;  // N/m, N, N, s/m
  T a_uy, b_uy, g_uy;         // A / u_y, beta / u_y, gamma / u_y (1/m)
  T z_max;                    // (A / (beta + gamma))^(1/eta)
  T eta;                      // integer exponent as a double
  T uy_2a;                    // u_y / (2 A): S = Q z^2 u_y / (2 A)
};

struct Smooth {
  // Q(v)
  template <class T> POUNDING_INLINE static T strength(const SmoothParams<T>& p, T v) {
    return p.q_fast - (p.q_fast - p.q_slow) * lane::exp(-p.rate * lane::abs(v));
  }
  // z after the increment du from z0
  template <class T> POUNDING_INLINE static T z_next(const SmoothParams<T>& p, T z0, T du) {
    const T one(1.0), zero(0.0);
    const T sigma = lane::select(du < zero, -one, one);
    const T w0 = sigma * z0, xi = lane::abs(du), aw = lane::abs(w0);
    T pw = one;  // |w|^(eta - 1), by multiplication (exact bits at both lane types)
    for (int k = 1; k < smooth_max_eta; ++k) pw = lane::select(T(static_cast<double>(k)) < p.eta, pw * aw, pw);
    const T sw = lane::select(w0 < zero, -one, one);
    const T c = lane::select(w0 < zero, p.g_uy - p.b_uy, p.g_uy + p.b_uy);
    const T g = p.a_uy - (pw * aw) * c;
    const T x = ((c * p.eta) * (pw * sw)) * xi;  // -J xi
    const T phi = lane::select(x == zero, one, -lane::expm1(-x) / x);
    const T w1 = lane::min(lane::fma(xi * phi, g, w0), p.z_max);
    return sigma * w1;
  }
  // The force at d with the new z and the strength at rate v; the hysteretic part Q z is returned in h.
  template <class T> POUNDING_INLINE static T restoring(const SmoothParams<T>& p, T z1, T d, T v, T& h) {
    h = strength(p, v) * z1;
    return lane::fma(p.k, d, h);
  }
  // Dissipated energy of the step: h0 = Q0 z0 (the committed force minus k d0), h1 = Q1 z1.
  template <class T> POUNDING_INLINE static T dissipated(const SmoothParams<T>& p, T h0, T z0, T h1, T z1, T du) {
    return T(0.5) * (h0 + h1) * du - (h1 * z1 - h0 * z0) * p.uy_2a;
  }
  // The SpringSpec's k of a smooth spring: its initial tangent k + max(Q_slow, Q_fast) A / u_y (what validation and
  // the structure's omega_max read); fy = inf, alpha = 0.
  static double initial_tangent(const SmoothParams<double>& p) {
    return p.k + (p.q_fast > p.q_slow ? p.q_fast : p.q_slow) * p.a_uy;
  }
  // The constants' checks (the registry's trait problems): k >= 0, Q_slow > 0, Q_fast >= 0, rate >= 0, A / u_y > 0,
  // beta + gamma > 0, z_max finite and > 0, eta an integer in [1, smooth_max_eta], u_y / (2 A) > 0.
  template <class Bad> static void problems(const SmoothParams<double>& p, Bad&& bad) {
    using std::isfinite;
    const bool ok = isfinite(p.k) && p.k >= 0 && isfinite(p.q_slow) && p.q_slow > 0 && isfinite(p.q_fast) &&
                    p.q_fast >= 0 && isfinite(p.rate) && p.rate >= 0 && isfinite(p.a_uy) && p.a_uy > 0 &&
                    isfinite(p.b_uy) && isfinite(p.g_uy) && p.b_uy + p.g_uy > 0 && isfinite(p.z_max) && p.z_max > 0 &&
                    p.eta >= 1 && p.eta <= smooth_max_eta && p.eta == std::floor(p.eta) && isfinite(p.uy_2a) &&
                    p.uy_2a > 0;
    if (!ok)
      bad("smooth", "the smooth hysteresis constants (k {}, Q_slow {}, Q_fast {}, rate {}, A/u_y {}, beta/u_y {}, "
          "gamma/u_y {}, eta {}) are not valid", "build them with BoucWen::params or FrictionPendulum::params from a valid spec",
          p.k, p.q_slow, p.q_fast, p.rate, p.a_uy, p.b_uy, p.g_uy, p.eta);
  }
  // The system stepper's rows (k, Q_slow, Q_fast, rate, A/u_y, beta/u_y, gamma/u_y, z_max, eta, u_y/(2A), z): a
  // smooth spring starts at z = 0, its force at rest in d0 is k d0. The recoverable energy from the rows.
  static double load(const SmoothParams<double>& p, double d0, SpringRows& r) {
    r[0] = p.k, r[1] = p.q_slow, r[2] = p.q_fast, r[3] = p.rate, r[4] = p.a_uy, r[5] = p.b_uy;
    r[6] = p.g_uy, r[7] = p.z_max, r[8] = p.eta, r[9] = p.uy_2a;
    return p.k * d0;
  }
  static double stored_energy(const SpringRows& r, double d, double f) {
    SmoothParams<double> p{};
    p.k = r[0], p.uy_2a = r[9];
    return strain_energy(p, d, f - p.k * d, r[10]);
  }
  // The system stepper's step: z over the increment dd, Q at the predicted rate (rows as load writes them; z in the
  // last); the dissipation in x (WithEnergy).
  template <bool WithEnergy, class T, class R>
  POUNDING_INLINE static T step(const R& r, const T& fo, const T& d, const T& dd, const T& rate, T& x) {
    const SmoothParams<T> p{r.get(0), r.get(1), r.get(2), r.get(3), r.get(4),
                            r.get(5), r.get(6), r.get(7), r.get(8), r.get(9)};
    const T z0 = r.get(10), z1 = z_next<T>(p, z0, dd);
    T h1;
    const T f = restoring<T>(p, z1, d, rate, h1);
    if constexpr (WithEnergy) x = dissipated<T>(p, lane::fma(-p.k, d - dd, fo), z0, h1, z1, dd);
    r.set(10, z1);
    return f;
  }
  // Recoverable energy k d^2 / 2 + Q z^2 u_y / (2 A), h = Q z.
  static double strain_energy(const SmoothParams<double>& p, double d, double h, double z) {
    return 0.5 * p.k * d * d + h * z * p.uy_2a;
  }
};

}  // namespace pounding::model
