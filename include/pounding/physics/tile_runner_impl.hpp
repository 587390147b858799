#pragma once
// The definition of run_tile, included only by the per-stepper instantiation units and by tests that run a
// law or model outside the registry.
#include "pounding/contact/law.hpp"
#include "pounding/contact/registry.hpp"
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

// run_tile<Stepper, L> for every registered law L: `template struct RegisteredLawRunners<S, contact::Laws>;`
// in src/physics/instantiate_<stepper>.cpp instantiates the whole row, so a new law needs no edit there.
template <class Stepper, class Laws> struct RegisteredLawRunners;
template <class Stepper, class... Ls> struct RegisteredLawRunners<Stepper, TypeList<Ls...>> {
  using Fn = void (*)(kernel::Tile&, const kernel::Context&, const ContactModel&);
  static constexpr Fn runners[] = {&run_tile<Stepper, Ls>...};
};

}  // namespace pounding::physics
