#pragma once
// Stability of the explicit treatment of contact, written once for both lane types: the law's linearised
// contact stiffness k_lin gives omega = sqrt(k_lin / meff); omega h above the stepper's limit (kernel/guard.hpp:
// limit2_*) amplifies every contact step, so the stepper marks the lane diverged (1) instead of returning numbers.
#include "pounding/contact/law.hpp"
#include "pounding/kernel/lane.hpp"

namespace pounding::contact {

template <class Law, class T, class Exp>
POUNDING_INLINE lane::mask_t<T> unstable(Kin<T> k, Params<T> p, State<T> s, Exp n, const Shared<T>& sh, T h2_meff,
                                         double limit2) {
  const T klin = Law::template linear_stiffness<T>(k, p, s, n, sh);
  return (k.d > T(0.0)) && (klin * h2_meff > T(limit2));
}

}  // namespace pounding::contact
