#pragma once
// The public entry of the kernel: a batch of pairs (kernel/batch.hpp), a contact model (contact/model.hpp)
// and run_batch, which validates every lane (physics/validate.hpp; bad input -> InputError naming the lane)
// and runs the stepper chosen in the settings.
#include "pounding/contact/model.hpp"
#include "pounding/kernel/batch.hpp"

namespace pounding {

// Stepper names from the stepper registry (physics/steppers/registry.hpp).
Stepper parse_stepper(std::string_view name);  // throws InputError naming the allowed values
std::string_view to_string(Stepper s);

// Runs every lane of `batch` through `motion` in lockstep. `out` is resized to the batch width.
void run_batch(const PairBatch& batch, const ContactModel& contact, const GroundMotion& motion,
               const KernelSettings& settings, BatchResult& out);

}  // namespace pounding
