#pragma once
// The end of a run: the analyses excluded from the probabilities, and the Results (results/results.hpp) of a
// finished study -- provenance, settings (visit_settings), records, sampled models and the tally's fields.
#include <cstdint>
#include <span>
#include <memory>
#include <string>
#include <vector>

#include "pounding/contact/model.hpp"
#include "pounding/model/system.hpp"
#include "pounding/results/results.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/tally.hpp"

namespace pounding {

// Analyses excluded from the probabilities (diverged or non-finite), and whether they are too many to trust
// the results: a whole record lost, or more than [analysis] max_excluded_fraction of all analyses.
struct Exclusions {
  std::int64_t excluded = 0, total = 0;
  std::string verdict;  // empty when acceptable; otherwise the banner's text
  physics::CoarseSummary coarse;  // the resolution guard (impacts scene); excluded above unless [analysis] coarse = "keep"
};
// The impacts scene's coupled analyses against the resolution guard (the tally's impacts/status and h_omega_contact).
physics::CoarseSummary coarse_summary(const Study& study, const WorkPlan& plan, const Tally& tally,
                                      const std::vector<StudyRecord>& records);
Exclusions count_exclusions(const Study& study, const WorkPlan& plan, const Tally& tally,
                            const std::vector<StudyRecord>& records);

// Every setting of the study as /settings/<section>/<key> entries (booleans as 0/1 integers).
results::Settings settings_of(const Study& study);

// /system of a study whose System is not the SDOF pair (format 3, architecture.md 2.6.3): the topology of `system`
// as plain tables -- per building, DOF, spring (with its hysteresis model's name), contact element (sides, the
// interpolated side's weight xi from the System's heights, level, height, label) and group (`groups[g]`: the
// group's ContactModel, one per System group as run_system gets them). `gap_offsets`: each element's offset (m)
// added to the study gap (the whole gap for a group that is not study_gap); empty: 0. The SDOF pair (and an empty
// System) gives an empty table: the study writes format 2. std::logic_error when `groups` or `gap_offsets` do
// not match the System. Put it in WorkPlan::system before the plan's fields (plan.hpp).
results::SystemTable system_table(const model::System& system, std::span<const ContactModel> groups,
                                  std::span<const double> gap_offsets = {});
// The per-floor and per-element extents of `system` (results::Extents; empty for the SDOF pair).
results::Extents extents_of(const model::System& system);

class SpilledColumns;

struct RunFacts {
  std::string build;  // this_build().build
  int ranks = 1;
  double wall_time_s = 0;
};
// Takes the tally's fields (the tally is left empty). A fragility study's stripes give the fields their leading
// [stripes] dimension and the /intensity group; plan.system (not empty: format 3) becomes /system. A tally of
// Reductions gives the reductions' results (/reductions, no models), unless `spilled` is given ([outputs] per_model =
// "stream"): then the per-model results, their fields read from the checkpoint by `spilled` (study/spill.hpp).
results::Results make_results(const Study& study, const std::vector<StudyRecord>& records, const WorkPlan& plan,
                              Tally& tally, const Exclusions& ex, const RunFacts& facts, const StripePlan& stripes = {},
                              const std::shared_ptr<const SpilledColumns>& spilled = {});
// /intensity: the measure, the levels, each record's IM, and (stripes) the factors and dropped records.
results::Group intensity_group(const Study& study, const StripePlan& stripes);

}  // namespace pounding
