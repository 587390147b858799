// The rk4 stepper with every registered law (one TU per stepper: architecture.md 2.4).
#include "pounding/physics/steppers/registry.hpp"
#include "pounding/physics/tile_runner_impl.hpp"

namespace pounding::physics {

template struct RegisteredLawRunners<kernel::Rk4, contact::Laws>;

}  // namespace pounding::physics
