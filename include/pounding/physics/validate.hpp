#pragma once
// Input checks of a batch, outside the kernel (architecture.md 2.4): the kernel keeps preconditions only;
// validate lists every problem, throw_first turns the first into InputError (pounding::run_batch does).
#include <string>
#include <vector>

#include "pounding/physics/batch.hpp"

namespace pounding::physics {

struct Problem {
  std::string what, where, fix;  // as InputError's three parts
};

// Settings, motion and Hertz exponent first, then every lane (the first bad lane's problems only).
std::vector<Problem> validate(const PairBatch& batch, const ContactModel& cm, const GroundMotion& motion,
                              const KernelSettings& settings);
// One lane's parameters for `stepper` and the law's traits (needs_stiffness, needs_restitution).
std::vector<Problem> validate_lane(const PairParams& p, const ContactModel& cm, Stepper stepper, std::size_t lane);
// Throws InputError for problems.front(); nothing when empty.
void throw_first(const std::vector<Problem>& problems);

}  // namespace pounding::physics
