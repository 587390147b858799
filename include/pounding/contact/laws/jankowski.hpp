#pragma once
// F = kc delta^1.5 + c(delta) ddelta with c = cd delta^(1/4), the damper only while approaching
// (rc-buildings eqs 4-5: c_h = 2 zeta sqrt(kh sqrt(delta) meff)); always n = 3/2.
#include <cmath>

#include "pounding/contact/laws/hertz_power.hpp"

namespace pounding::contact {

struct Jankowski {
  static constexpr std::string_view name = "jankowski";
  static constexpr LawTraits traits{
      .needs_restitution = true, .stiffness_unit = "N/m^1.5", .restitution = RestitutionKind::approximate,
      .restitution_note = "Jankowski's damping ratio (rc-buildings eq. 5) delivers e within 0.01 (docs/accuracy.md)"};
  // measured h omega_c limits (physics/resolution.hpp; docs/resolution_limits.csv)
  static constexpr ResolutionLimits resolution{.central_difference = 0.099, .newmark = 0.092, .rk4 = 0.124,
                                               .rk4_located = 0.181, .nigam_jennings = 0.099};
  template <class T, class Exp>
  POUNDING_INLINE static T force(Kin<T> k, Params<T> p, State<T>, Exp, Shared<T>& sh, T& clamp) {
    const T zero(0.0);
    clamp = zero;
    T pw = Exp15{}.power(lane::max(k.d, zero), sh);
    T damp = lane::select(k.dd > zero, p.cd * lane::sqrt(sh.sq) * k.dd, zero);
    return lane::fma(p.kc, pw, damp);  // central difference's contraction, pinned for the scalar steppers too
  }
  template <class T, class Exp> POUNDING_INLINE static Tangent<T> tangent(Kin<T> k, Params<T> p, State<T>, Exp) {
    const T zero(0.0);
    T pw, dpw;
    hertz_power::pow_and_slope(k.d, 1.5, pw, dpw);
    const T dp = lane::max(k.d, zero);
    const T q = lane::map(dp, [](double x) { return x > 0.0 ? std::sqrt(std::sqrt(x)) : 0.0; });
    const auto app = k.dd > zero;
    // contractions pinned (lane::fma) so that one lane and a SIMD lane agree; F keeps the shape the scalar
    // Newmark stepper had (the damper's product fused onto kc pw while approaching)
    const T kpw = p.kc * pw, cq = p.cd * q;
    return {lane::select(app, lane::fma(cq, k.dd, kpw), kpw),
            lane::fma(p.kc, dpw, lane::select(app && dp > zero, p.cd * 0.25 * q / dp * k.dd, zero)),
            lane::select(app, cq, zero)};
  }
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(Kin<T> k, Params<T> p, State<T>, Exp, const Shared<T>& sh) {
    return Exp15{}.stiffness(k.d, p.kc, sh);
  }
  template <class T> POUNDING_INLINE static T stored_energy(T dp, T kc, double) { return hertz_power::stored(dp, kc, 1.5); }
  template <class T> POUNDING_INLINE static void on_onset(State<T>&, lane::mask_t<T>, T, double) {}
  static double damping_constant(const ContactModel&, double kc, double e, double meff) {
    return 2.0 * jankowski_zeta(e) * std::sqrt(kc * meff);
  }
};

}  // namespace pounding::contact
