#pragma once
// F = kc delta (muthukumar eq. 3); elastic, non-tensile by the delta > 0 gate.
#include "pounding/contact/law.hpp"

namespace pounding::contact {

struct Linear {
  static constexpr std::string_view name = "linear";
  static constexpr LawTraits traits{
      .explicit_stiffness = true, .restitution = RestitutionKind::elastic,
      .restitution_note = "the linear law has no damping: it delivers e = 1 whatever e is asked",
      .duration = DurationForm::linear};
  // measured h omega_c limits (physics/resolution.hpp; docs/resolution_limits.csv)
  static constexpr ResolutionLimits resolution{.central_difference = 0.304, .newmark = 0.214, .rk4 = 0.261,
                                               .rk4_located = 0.285, .nigam_jennings = 0.248};
  template <class T, class Exp> POUNDING_INLINE static T force(Kin<T> k, Params<T> p, State<T>, Exp, Shared<T>&, T& clamp) {
    clamp = T(0.0);
    return p.kc * lane::max(k.d, T(0.0));
  }
  // Newton sees the law without the gate (the active set decides activity)
  template <class T, class Exp> POUNDING_INLINE static Tangent<T> tangent(Kin<T> k, Params<T> p, State<T>, Exp) {
    return {p.kc * k.d, p.kc, T(0.0)};
  }
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(Kin<T>, Params<T> p, State<T>, Exp, const Shared<T>&) { return p.kc; }
  template <class T> POUNDING_INLINE static T stored_energy(T dp, T kc, double) { return 0.5 * kc * dp * dp; }
  template <class T> POUNDING_INLINE static void on_onset(State<T>&, lane::mask_t<T>, T, double) {}
  static double damping_constant(const ContactModel&, double, double, double) { return 0.0; }
};

}  // namespace pounding::contact
