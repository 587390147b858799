#pragma once
// One tile through one stepper with one law and one structure model (default model::Registered): the run-time choices (Hertz exponent, energy) become template
// arguments here. Declared for every TU; defined in tile_runner_impl.hpp, which only the per-stepper
// instantiation TUs (src/physics/instantiate_<stepper>.cpp) and extension tests include.
#include "pounding/contact/model.hpp"
#include "pounding/kernel/tile.hpp"
#include "pounding/model/sdof.hpp"

namespace pounding::physics {

template <class Stepper, class Law, class Model = model::Registered>
void run_tile(kernel::Tile& T, const kernel::Context& C, const ContactModel& cm);

}  // namespace pounding::physics
