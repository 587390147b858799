#pragma once
// The friction pendulum (single concave surface, small angles; research SB §2, Zayas, Low & Mahin 1990; Constantinou,
// Mokha & Reinhorn 1990): F = (W / R) u + mu(v) W z, mu(v) = mu_fast - (mu_fast - mu_slow) exp(-rate |v|), z the
// Bouc-Wen "viscoplastic" smoothing of sgn(v) with yield displacement u_y (A = 1, beta = gamma = 0.5, eta = 2: on
// loading z = tanh(u / u_y), unloading on the elastic slope mu W / u_y), which tends to the rigid-plastic Coulomb
// slider as u_y -> 0. W is the constant weight on the bearing (vertical motion and uplift not modelled); T = 2 pi
// sqrt(R / g) for the pendulum alone.
#include <limits>
#include <optional>
#include <string_view>

#include "pounding/model/hysteresis/smooth.hpp"

namespace pounding::model {

struct FrictionPendulum {
  static constexpr std::string_view name = "friction-pendulum";
  static constexpr double beta = 0.5, gamma = 0.5;
  static constexpr int eta = 2;
  struct Spec {
    double weight = 0.0, radius = 0.0;        // N, m
    double mu_slow = 0.0, mu_fast = 0.0;      // friction at v = 0 and v -> inf
    double rate = 0.0;                        // s/m
    double uy = 0.0;                          // m, the smoothing's yield displacement
  };
  template <class T> using Params = SmoothParams<T>;
  static Params<double> params(const Spec& s) {
    return {s.weight / s.radius, s.mu_slow * s.weight, s.mu_fast * s.weight, s.rate, 1.0 / s.uy, beta / s.uy,
            gamma / s.uy, 1.0, static_cast<double>(eta), s.uy / 2.0};
  }
  // An isolator; packed as its Spec (W, R, mu_slow, mu_fast, rate, u_y), its SpringSpec's k the initial tangent.
  static constexpr Roles roles{.isolator = true};
  static constexpr bool lane_stepper = false;
  static SpringSpec pack(const Spec& s) {
    return {Smooth::initial_tangent(params(s)), std::numeric_limits<double>::infinity(), 0.0,
            {s.weight, s.radius, s.mu_slow, s.mu_fast, s.rate, s.uy}};
  }
  static Spec unpack(const SpringSpec& s) {
    const auto& p = s.p;
    return {p[0], p[1], p[2], p[3], p[4], p[5]};
  }
  template <class Bad> static void problems(const SpringSpec& s, Bad&& bad) { Smooth::problems(params(unpack(s)), bad); }
  static double load(const SpringSpec& s, double d0, SpringRows& r) { return Smooth::load(params(unpack(s)), d0, r); }
  static double stored_energy(const SpringRows& r, double d, double f) { return Smooth::stored_energy(r, d, f); }
  static constexpr bool fast_path = false;
  template <bool WithEnergy, class T, class R>
  POUNDING_INLINE static T step(const R& r, const T& fo, const T& d, const T& dd, const T& rate, T& x) {
    return Smooth::step<WithEnergy, T>(r, fo, d, dd, rate, x);
  }
  static bool stays_elastic(const Spec&, double, double) { return false; }
  // R(f u, f v) = f R(u, v; mu / f, rate f, u_y / f): z depends on u / u_y, mu(f v) / f is the law with mu / f and
  // rate f. Exact; the equivalent's friction may exceed what a user could give (f < 1).
  static std::optional<Spec> unscaled_equivalent(const Spec& s, double f) {
    Spec out = s;
    out.mu_slow /= f, out.mu_fast /= f, out.rate *= f, out.uy /= f;
    return out;
  }
};

}  // namespace pounding::model
