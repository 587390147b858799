#pragma once
// The eighth contact law of ctest contact.registry_eighth_law (run.cmake): a linear spring, added the way a
// newcomer adds a law (this header, an entry in contact::Laws, an enumerator in ContactLaw). With
// -DEIGHTH_DECLARES_LIMITS it declares its resolution limits and must build; without, the registry must refuse it.
#include "pounding/contact/law.hpp"

namespace pounding::contact {

struct Eighth {
  static constexpr std::string_view name = "eighth";
  static constexpr LawTraits traits{.restitution = RestitutionKind::elastic, .duration = DurationForm::linear};
#ifdef EIGHTH_DECLARES_LIMITS
  static constexpr ResolutionLimits resolution{.central_difference = 0.3, .newmark = 0.2, .rk4 = 0.25,
                                               .rk4_located = 0.28, .nigam_jennings = 0.24};
#endif
  template <class T, class Exp> POUNDING_INLINE static T force(Kin<T> k, Params<T> p, State<T>, Exp, Shared<T>&, T& clamp) {
    clamp = T(0.0);
    return p.kc * lane::max(k.d, T(0.0));
  }
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
