#pragma once
// Newmark (average acceleration, Newton) and RK4 for every system the lane steppers run (issue 25 step 5,
// docs/architecture.md §2.4.2, §2.4.3): one lane at a time in doubles, the whole record per lane, so a lane's
// results depend only on its own inputs (not on the batch width or the lane order). The SDOF pair keeps the pair
// kernel's Newmark and RK4 (physics::run_system sends it there); central difference keeps the dynamic layout.
//
// Newmark: predictor u + h v + h^2/2 a; per Newton iterate a = c4 (x - u) - (4/h) v - a_old, v = c2 (x - u) - v_old,
// residual r = M (a + ag) + C v + q_springs(x) + sum_e g_e F_e; the Newton matrix
// J = c4 M + c2 C + K_t + sum_active g g' (dF/dd + c2 dF/ddot) in a banded LDL' without pivoting (half-bandwidth
// from the topology: 2 for a pair of sticks with floor-to-floor contacts; a body with dense modal C makes its block
// full); convergence on sum |du| <= tol sum |x| + 1e-19; per element the pair's active set (at most one activation
// per step, at most 4 passes).
// RK4: stage derivatives from the committed state with the springs' return map; per element the pair's rule: a step
// that starts out of contact is taken with the element inactive, and redone with it active (v0 latched at its first
// stage in contact) when it ends penetrating.
// Runs bilinear springs (storeys, linear and lead-rubber bearings), any force contact law, point, interpolated
// (floor against column) and wall sides, floor, storey and dense modal dashpots, one ground-motion channel;
// lane_stepper_problems names what it does not run.
#include <span>
#include <vector>

#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/validate.hpp"

namespace pounding::physics {

// What the lane steppers cannot run (each a Problem with the fix): springs of a law other than bilinear, the
// stereomechanical law, several ground-motion channels, an e(v0) curve, located onsets, a series recorder.
std::vector<Problem> lane_stepper_problems(const SystemBatch& batch, std::span<const ContactModel> groups,
                                           const KernelSettings& settings);

// Runs every lane of `batch` with settings.stepper (newmark or rk4); validation is the caller's.
void run_lane_stepper(const SystemBatch& batch, std::span<const ContactModel> groups, const GroundMotion& motion,
                      const KernelSettings& settings, SystemResult& out);

// The half-bandwidth of the Newton matrix of `system` (the largest |i - j| over DOFs that a spring, dashpot, dense
// damping block or contact element couples).
int newton_bandwidth(const model::System& system);

}  // namespace pounding::physics
