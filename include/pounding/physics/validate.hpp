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
// and e per the group law's traits, the stereomechanical law with exactly one element, and h < the structure's
// longest stable step (structure_step_max below: damped for central difference), naming the substeps that satisfy it. The SDOF pair (System::is_sdof_pair()) gets exactly the PairBatch
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
// Gershgorin's bound on M^-1 C of one lane (floor dashpots, a floor dashpot to an isolated base in both rows, storey
// dashpots, the dense rows of classical modal damping): max over DOFs of sum_j |C_ij| / m_i. Every mode n of classical damping has 2 zeta_n omega_n <= it.
double structure_damping_bound(const SystemBatch& batch, std::size_t lane);
// The longest stable integration step of one lane's structure (contact excluded: it is guarded during the run), THE
// bound that physics::validate, pounding simulate and the studies check. Central difference as the system stepper
// runs it (damping forces on the predicted velocity v + h a) is stable for a mode when h^2 omega^2 + 4 h (2 zeta
// omega) < 4 (tools/stability_damped_cd.py: the spectral radius of its one-step matrix); with omega <= W
// (structure_omega_max) and 2 zeta omega <= C (structure_damping_bound) it holds for every mode of classical
// (Rayleigh) damping when h < 2 / (C + sqrt(C^2 + W^2)) = 2 (sqrt(C^2 + W^2) - C) / W^2 -- 2 / W undamped. Other
// steppers: structure_step_limit / W (damping left out), infinity for the unconditionally stable ones.
struct StructureStep {
  double h_max;      // s; the step is stable when h < h_max
  double omega_max;  // W, rad/s
  double damping;    // C, 1/s (0 for steppers other than central difference)
  int dof;           // where W's bound is largest
  // the fewest substeps n with dt / n < h_max
  double substeps(double dt) const;
};
StructureStep structure_step_max(const SystemBatch& batch, std::size_t lane, Stepper stepper);
// Throws InputError for problems.front(); nothing when empty.
void throw_first(const std::vector<Problem>& problems);

}  // namespace pounding::physics
