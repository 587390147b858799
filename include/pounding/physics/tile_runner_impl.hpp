#pragma once
#include "pounding/contact/law.hpp"
#include "pounding/physics/tile_runner.hpp"

namespace pounding::physics {

template <class Stepper, class Law, class Model>
void run_tile(kernel::Tile& T, const kernel::Context& C, const ContactModel& cm) {
  const bool energy = C.settings->energy;
  auto go = [&](auto exp) {
    if (energy)
      Stepper::template run<Law, decltype(exp), true, Model>(T, C, exp);
    else
      Stepper::template run<Law, decltype(exp), false, Model>(T, C, exp);
  };
  if constexpr (Law::traits.uses_exponent) {
    if (cm.n == 1.5)
      go(contact::Exp15{});
    else
      go(contact::RuntimeExponent{cm.n});
  } else {
    go(contact::Exp15{});  // the law does not read n
  }
}

}  // namespace pounding::physics
