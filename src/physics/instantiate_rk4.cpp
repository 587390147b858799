// The rk4 stepper with every registered law (one TU per stepper: architecture.md 2.4).
#include "pounding/physics/steppers/registry.hpp"
#include "pounding/physics/tile_runner_impl.hpp"

namespace pounding::physics {

using kernel::Rk4;
template void run_tile<Rk4, contact::None>(kernel::Tile&, const kernel::Context&, const ContactModel&);
template void run_tile<Rk4, contact::Linear>(kernel::Tile&, const kernel::Context&, const ContactModel&);
template void run_tile<Rk4, contact::Kelvin>(kernel::Tile&, const kernel::Context&, const ContactModel&);
template void run_tile<Rk4, contact::Hertz>(kernel::Tile&, const kernel::Context&, const ContactModel&);
template void run_tile<Rk4, contact::Hertzdamp>(kernel::Tile&, const kernel::Context&, const ContactModel&);
template void run_tile<Rk4, contact::Jankowski>(kernel::Tile&, const kernel::Context&, const ContactModel&);
template void run_tile<Rk4, contact::Stereomechanical>(kernel::Tile&, const kernel::Context&, const ContactModel&);
static_assert(contact::Laws::size == 7, "instantiate every registered law above");

}  // namespace pounding::physics
