#pragma once
// No contact element: the uncoupled pair.
#include "pounding/contact/law.hpp"

namespace pounding::contact {

struct None {
  static constexpr std::string_view name = "none";
  static constexpr LawTraits traits{.has_force = false, .needs_stiffness = false,
                                    .restitution = RestitutionKind::elastic,
                                    .restitution_note = "no contact element: the bodies pass through each other"};
  template <class T, class Exp> POUNDING_INLINE static T force(Kin<T>, Params<T>, State<T>, Exp, Shared<T>&, T& clamp) {
    clamp = T(0.0);
    return T(0.0);
  }
  template <class T, class Exp> POUNDING_INLINE static Tangent<T> tangent(Kin<T>, Params<T>, State<T>, Exp) {
    return {T(0.0), T(0.0), T(0.0)};
  }
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(Kin<T>, Params<T>, State<T>, Exp, const Shared<T>&) { return T(0.0); }
  template <class T> POUNDING_INLINE static T stored_energy(T, T, double) { return T(0.0); }
  template <class T> POUNDING_INLINE static void on_onset(State<T>&, lane::mask_t<T>, T, double) {}
  static double damping_constant(const ContactModel&, double, double, double) { return 0.0; }
};

}  // namespace pounding::contact
