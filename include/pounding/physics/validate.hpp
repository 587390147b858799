#pragma once
// Input checks of a batch, outside the kernel (architecture.md 2.4): the kernel keeps preconditions only;
// validate lists every problem, throw_first turns the first into InputError (pounding::run_batch does).
#include <span>
#include <string>
#include <vector>

#include "pounding/core/problem.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding::physics {

using Problem = pounding::Problem;  // core/problem.hpp (moved there so the model layer can list problems)

// Settings, motion and Hertz exponent first, then every lane (the first bad lane's problems only).
std::vector<Problem> validate(const PairBatch& batch, const ContactModel& cm, const GroundMotion& motion,
                              const KernelSettings& settings);
// One lane's parameters for `stepper` and the law's traits (needs_stiffness, needs_restitution).
std::vector<Problem> validate_lane(const PairParams& p, const ContactModel& cm, Stepper stepper, std::size_t lane);
// A batch of systems (docs/architecture.md §2.2.7): models[g] is contact group g's model. Settings, motion,
// groups and stepper first, then every lane (the first bad lane's problems only): masses > 0, dashpots >= 0,
// initial conditions finite, springs k > 0, fy > 0, 0 <= alpha < 1, gaps finite and >= 0, weights in [0, 1], kc
// and e per the group law's traits, the stereomechanical law with exactly one element, and -- for central
// difference (RK4) -- h omega_max < 2 (2.8) with the Gershgorin bound omega_max^2 <= max_i sum_j |K0_ij| / m_i,
// naming the substeps that satisfy it. The SDOF pair (System::is_sdof_pair()) gets exactly the PairBatch
// validation above (today's checks and messages). std::logic_error for a batch not sized for its system.
std::vector<Problem> validate(const SystemBatch& batch, std::span<const ContactModel> models,
                              const GroundMotion& motion, const KernelSettings& settings);
// The structure's highest circular frequency bound of one lane, Gershgorin on M^-1 K0 (initial spring stiffnesses,
// contact excluded): omega_max^2 <= max_i sum_j |K0_ij| / m_i, and the DOF where the bound is largest.
struct StructureFrequency {
  double omega_max;
  int dof;
};
StructureFrequency structure_omega_max(const SystemBatch& batch, std::size_t lane);
// The stepper's limit on h omega for the structure: 2 (central difference), 2.8 (RK4), infinity (the implicit and
// exact steppers).
double structure_step_limit(Stepper stepper);
// Throws InputError for problems.front(); nothing when empty.
void throw_first(const std::vector<Problem>& problems);

}  // namespace pounding::physics
