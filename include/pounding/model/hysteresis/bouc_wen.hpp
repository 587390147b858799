#pragma once
// The Bouc-Wen spring in its standard form (Wen 1976; Ismail, Ikhouane & Rodellar 2009; OpenSees'
// ElastomericBearingBoucWen with beta on the |du| term): F = alpha k u + (1 - alpha) k u_y z,
// u_y dz/du = A - |z|^eta (gamma + beta sgn(z du)); the initial tangent alpha k + (1 - alpha) k A (= k for A = 1),
// the characteristic strength Q = (1 - alpha) k u_y. Integrated as model/hysteresis/smooth.hpp says. A lead-rubber
// bearing (k1, k2, Qd) is k = k1, alpha = k2/k1, u_y = Qd / (k1 - k2) with A = 1 (research SB §2).
#include <cmath>
#include <limits>
#include <optional>
#include <string_view>

#include "pounding/model/hysteresis/smooth.hpp"

namespace pounding::model {

struct BoucWen {
  static constexpr std::string_view name = "bouc-wen";
  struct Spec {
    double k = 0.0, alpha = 0.0, uy = 0.0;  // N/m, ratio in [0, 1), m
    double a = 1.0, beta = 0.5, gamma = 0.5;
    int eta = 1;
  };
  template <class T> using Params = SmoothParams<T>;
  static Params<double> params(const Spec& s) {
    const double q = (1.0 - s.alpha) * s.k * s.uy;
    return {s.alpha * s.k, q, q, 0.0, s.a / s.uy, s.beta / s.uy, s.gamma / s.uy,
            std::pow(s.a / (s.beta + s.gamma), 1.0 / s.eta), static_cast<double>(s.eta), s.uy / (2.0 * s.a)};
  }
  // An isolator; packed as its Spec (k, alpha, u_y, A, beta, gamma, eta), its SpringSpec's k the initial tangent.
  static constexpr Roles roles{.isolator = true};
  static constexpr bool lane_stepper = false;
  static SpringSpec pack(const Spec& s) {
    return {Smooth::initial_tangent(params(s)), std::numeric_limits<double>::infinity(), 0.0,
            {s.k, s.alpha, s.uy, s.a, s.beta, s.gamma, static_cast<double>(s.eta)}};
  }
  static Spec unpack(const SpringSpec& s) {
    const auto& p = s.p;
    return {p[0], p[1], p[2], p[3], p[4], p[5], static_cast<int>(p[6])};
  }
  template <class Bad> static void problems(const SpringSpec& s, Bad&& bad) { Smooth::problems(params(unpack(s)), bad); }
  static double load(const SpringSpec& s, double d0, SpringRows& r) { return Smooth::load(params(unpack(s)), d0, r); }
  static double stored_energy(const SpringRows& r, double d, double f) { return Smooth::stored_energy(r, d, f); }
  static constexpr bool fast_path = false;
  template <bool WithEnergy, class T, class R>
  POUNDING_INLINE static T step(const R& r, const T& fo, const T& d, const T& dd, const T& rate, T& x) {
    return Smooth::step<WithEnergy, T>(r, fo, d, dd, rate, x);
  }
  // No elastic range: z moves from the first increment on.
  static bool stays_elastic(const Spec&, double, double) { return false; }
  // R(f u) = alpha k f u + (1 - alpha) k u_y z(f u / u_y) = f R(u; u_y / f): exact (z depends on u / u_y only).
  static std::optional<Spec> unscaled_equivalent(const Spec& s, double f) {
    Spec out = s;
    out.uy /= f;
    return out;
  }
};

}  // namespace pounding::model
