#pragma once
// The time series of one lane of a system run (`pounding simulate --series` for buildings, isolated buildings, rows
// and bridges; the SDOF pair has kernel/batch.hpp's SeriesRecorder): every step of the central-difference system
// stepper, from the initial state (t = 0) to the end, one row per integration step.
//   u      [dof][step]  m       displacement relative to the DOF's support (the system's DOF order: body by body,
//                               an isolated body's base first)
//   a_abs  [dof][step]  m/s^2   absolute acceleration (relative + the DOF's support acceleration)
//   force  [element][step] N    contact force of each contact element (0 when open)
// The series' peaks are the run's peaks (peak_u, peak_acc, peak_force) at the same step, bit for bit.
#include <cstddef>
#include <span>
#include <vector>

#include "pounding/physics/system_batch.hpp"

namespace pounding::physics {

struct SystemSeries {
  std::size_t lane = 0;
  std::vector<double> t, ag;                  // s; m/s^2 (support 1)
  std::vector<std::vector<double>> u, a_abs;  // [dof][step]
  std::vector<std::vector<double>> force;     // [element][step]
  void clear() {
    t.clear(), ag.clear();
    for (auto* v : {&u, &a_abs, &force}) v->clear();
  }
};

// run_system (physics/system_batch.hpp) recording lane series.lane into `series` (cleared first). Central difference
// only, and a system other than the SDOF pair (InputError otherwise, naming --series); the results equal run_system's
// bit for bit.
void run_system_recorded(const SystemBatch& batch, std::span<const ContactModel> groups,
                         std::span<const GroundMotion> channels, const KernelSettings& settings, SystemResult& out,
                         SystemSeries& series);

}  // namespace pounding::physics
