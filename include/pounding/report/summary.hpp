#pragma once
// Text summaries of kernel results: one `name: value` per line (SI units in the names).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pounding/contact/model.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/model/system.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding {

std::string format_summary(const BatchResult& r, std::size_t lane, const ContactModel& cm, const PairParams& p,
                           const Record& rec, const KernelSettings& ks);

// One building of a system run as the outputs describe it (per floor / per storey, bottom first).
// A base-isolated building's bearing (issue 25 §2): its kind, base mass, isolator {k, fy, alpha} (fy inf: linear),
// the linear bearing's dashpot and the periods of the isolated building with the isolator's initial stiffness.
struct IsolationReport {
  std::string bearing;
  double base_mass = 0, k = 0, fy = 0, alpha = 0, c_base = 0;
  std::vector<double> periods;
  // the smooth bearings' own numbers (name with units, value), printed as <label>_bearing_<name>
  std::vector<std::pair<std::string, double>> law_numbers;
};

// periods / modal_damping: of the fixed-base superstructure for an isolated building (its Rayleigh's modes)
struct BuildingReport {
  std::string label;
  std::vector<double> floor_levels, floor_mass, storey_stiffness, storey_yield, periods, modal_damping;
  std::optional<IsolationReport> isolation;
  std::vector<int> rayleigh_modes;  // Rayleigh damping's two modes (i, j: zeta exactly there); empty: none (SDOF, modal)
};

// A run of one lane of a system (`pounding simulate`): what it was and every observer.
struct SystemRunReport {
  const model::System* system = nullptr;
  const physics::SystemResult* result = nullptr;
  // the same run without pounding (contact law none): when given, the outputs add the amplification per floor,
  // coupled peak / uncoupled peak of displacement, drift and absolute acceleration (issue 25 §3)
  const physics::SystemResult* uncoupled = nullptr;
  std::size_t lane = 0;
  const Record* record = nullptr;
  const KernelSettings* settings = nullptr;
  const ContactModel* contact = nullptr;
  double e_target = 1.0, gap = 0.0, analysis_duration = 0.0;
  std::vector<double> contact_stiffness;  // per element
  std::vector<double> contact_gap;        // per element (m): empty -> `gap` for every element
  std::vector<BuildingReport> buildings;  // one per body
  // per spring: a name for each link spring (restrainers, bearings, abutments: issue 26), printed with its peak force
  // and deformation; empty (or an empty name) for none
  std::vector<std::string> spring_labels;
};

// `name: value` lines (lists space-separated), per building, per level, then the totals and the energy terms.
std::string format_system_summary(const SystemRunReport& run);
// One JSON object (report/json.hpp): peak_u<b>, peak_drift<b>, peak_abs_acc<b>_g (lists, one per floor from the
// first), levels (one object per contact element: level, label, impacts, peak_force, ...), the totals, energies.
std::string format_system_json(const SystemRunReport& run);

}  // namespace pounding
