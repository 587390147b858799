#pragma once
// F = kc delta + ck ddelta, clamped non-tensile (impact-stiffness paper eqs 1-3);
// ck = 2 xi sqrt(kc meff), xi = -ln e / sqrt(pi^2 + ln^2 e).
#include <cmath>

#include "pounding/contact/law.hpp"

namespace pounding::contact {

struct Kelvin {
  static constexpr std::string_view name = "kelvin";
  static constexpr LawTraits traits{
      .explicit_stiffness = true, .needs_restitution = true, .restitution = RestitutionKind::approximate,
      .restitution_note = "the damping ratio xi = -ln e / sqrt(pi^2 + ln^2 e) is exact for the tension-carrying "
                          "oscillator; the non-tensile contact ends early and delivers more than e at low e (0.675 "
                          "at 0.65, 0.397 at 0.3; docs/accuracy.md)",
      .duration = DurationForm::linear};
  // measured h omega_c limits (physics/resolution.hpp; docs/resolution_limits.csv)
  static constexpr ResolutionLimits resolution{.central_difference = 0.079, .newmark = 0.079, .rk4 = 0.114,
                                               .rk4_located = 0.174, .nigam_jennings = 0.079};
  template <class T, class Exp> POUNDING_INLINE static T force(Kin<T> k, Params<T> p, State<T>, Exp, Shared<T>&, T& clamp) {
    const T zero(0.0);
    T raw = lane::select(k.d > zero, lane::fma(p.cd, k.dd, p.kc * lane::max(k.d, zero)), zero);
    clamp = lane::select(raw < zero, T(1.0), zero);
    return lane::max(raw, zero);
  }
  template <class T, class Exp> POUNDING_INLINE static Tangent<T> tangent(Kin<T> k, Params<T> p, State<T>, Exp) {
    return {lane::fma(p.kc, k.d, p.cd * k.dd), p.kc, p.cd};
  }
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(Kin<T>, Params<T> p, State<T>, Exp, const Shared<T>&) { return p.kc; }
  template <class T> POUNDING_INLINE static T stored_energy(T dp, T kc, double) { return 0.5 * kc * dp * dp; }
  template <class T> POUNDING_INLINE static void on_onset(State<T>&, lane::mask_t<T>, T, double) {}
  static double damping_constant(const ContactModel&, double kc, double e, double meff) {
    return 2.0 * kelvin_damping_ratio(e) * std::sqrt(kc * meff);
  }
};

}  // namespace pounding::contact
