#pragma once
// Named, deterministic workloads shared by `pounding bench`, the Google Benchmark and examples.
#include <cstddef>
#include <string>
#include <vector>

#include "pounding/model/system.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding {

// Built-in ground motion: deterministic, 0.4 g peak, a sine sweep 0.3 -> 3 Hz under a
// smooth build-up/decay envelope (the `simulate` example when no --record is given).
std::vector<double> builtin_motion(double dt, double duration);

// The kernel benchmark's batch: `width` bilinear pairs (T1, T2 in [1, 1.5] s, masses around 1e7 kg,
// heights 30-50 m, yield at 2 % drift / 6, alpha 0.05, 5 % damping), gap 0.3 x 0.005 (h1 + h2),
// equivalent-sphere Hertz stiffness, e = 0.65. Parameters vary per lane with a fixed formula.
PairBatch benchmark_batch(std::size_t width);

// The system benchmark (`pounding bench --storeys N`): two N-storey shear buildings side by side, DOFs level-major,
// Rayleigh floor and storey dashpots, one point-point element at every floor in one group (N = 1: the SDOF pair's
// structure).
// modal: classical modal damping (DampingForm::dense, 5 % in every mode) instead of Rayleigh (for N > 1).
model::System shear_pair_system(int storeys, bool modal = false);
// `width` lanes of it: storey masses 2.5e5 kg x [0.8, 1.2], uniform storey stiffness giving T1 = 0.1 N s x [1, 1.5]
// (left) and 0.13 N s x [1, 1.5] (right), 5 % Rayleigh damping on modes 1 and 2, bilinear storeys yielding at
// 1 % drift of 3.2 m with alpha 0.05, gap 0.3 x 0.005 x (H1 + H2) x [1, 2], kc 2e9 N/m^1.5 x [0.8, 1.2], e = 0.65
// (varied per lane with the same low-discrepancy rule as benchmark_batch).
physics::SystemBatch shear_pair_batch(const model::System& system, std::size_t width);

// `pounding bench --storeys N --isolation B`: the same pair with building 1 base-isolated (a base mass at level 0 on
// bearing B: "lead-rubber", "friction-pendulum" or "bouc-wen") and building 2 fixed, Hertzdamp at the common floors,
// no moat. Lanes: floors 2.5e5 kg x [0.8, 1.2], storeys 9.81e7 N/m x N/3 x [1, 1.5] (left), the fixed building as
// shear_pair_batch's right one in spirit (T1 0.13 N s x [1, 1.5]); base 2.5e5 kg; lead-rubber / Bouc-Wen k1 = 10 k2,
// k2 from T_iso = 2.5 s on the total mass, Qd = 0.05 W; friction pendulum R = 1.55 m (T 2.5 s), mu 0.05 -> 0.10 at
// 20 s/m, u_y 0.5 mm; gap 0.1 m x [1, 2], kc 2e9 N/m^1.5 x [0.8, 1.2], e = 0.65.
model::System isolated_pair_system(int storeys, const std::string& bearing);
physics::SystemBatch isolated_pair_batch(const model::System& system, std::size_t width, const std::string& bearing);

}  // namespace pounding
