// The system stepper (central difference, dynamic layout): both energy variants of the tile loop and the element
// function of every registered law x exponent form. One TU, so the pair's instantiation units keep their size.
#include "pounding/contact/registry.hpp"
#include "pounding/physics/steppers/system_central_difference.hpp"

namespace pounding::kernel::sys {

template void run_tile<true>(const Pool&, int, const Run&);
template void run_tile<false>(const Pool&, int, const Run&);

GroupFn group_runner(ContactLaw law, double n) {
  return contact::visit_law(law, [n]<class Law>() -> GroupFn {
    if constexpr (Law::traits.uses_exponent)
      if (n != 1.5) return &group_elements<Law, contact::RuntimeExponent>;
    return &group_elements<Law, contact::Exp15>;
  });
}

}  // namespace pounding::kernel::sys
