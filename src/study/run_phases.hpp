// The phases of a study run (run.cpp's run_study) that live in files of their own: inputs, checkpoint, finish.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/core/run_context.hpp"
#include "pounding/core/timing.hpp"
#include "pounding/parallel/executor.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/histories.hpp"
#include "pounding/study/intensity.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/study/run.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/tally.hpp"
#include "pounding/study/target_spectrum.hpp"

namespace pounding::study_run {

// ---- phase 1: the inputs, identical on every rank -------------------------------------------------
struct Inputs {
  Study study;
  std::string out, out_where;
  std::vector<StudyRecord> records;
  StripePlan stripes;  // a fragility study's stripes (none otherwise)
  std::optional<StudySelection> selection;  // [records] select: the records chosen to [target_spectrum]
  std::vector<HistoryChoice> histories;     // [outputs] histories: the named analyses (worst N: after the units)
  bool stopped = false;  // a stop while the records were made (every rank agrees: it is in the exchanged shares)
};

// Test-only fault injection (POUNDING_INJECT_FAULT; run.cpp): throws when `phase` is the one named for `rank`.
void inject_fault(std::string_view phase, int rank);

// run_inputs.cpp: the study and records on every rank, outputs checked, the checkpoint locked (rank 0).
Inputs load_inputs(const parallel::Session& session, const std::string& study_path, const RunOptions& opt,
                   std::optional<Checkpoint>& ckpt, const RunContext& ctx);
// the work plan: the units, their lanes and the fields they fill
WorkPlan plan_work(const Inputs& in);
// rank 0 says what runs: the study, records, models, units, structures, scale-factor warnings
void announce(const parallel::Session& session, const Inputs& in, const WorkPlan& L, const RunContext& ctx);

// run_checkpoint.cpp: the key of the study, records and build; the checkpoint opened (the units that remain);
// a rank's flush; the save after an error; the seconds between flushes.
CheckpointKey checkpoint_key(const Inputs& in, const WorkPlan& L);
std::vector<std::size_t> open_checkpoint(const parallel::Session& session, const RunOptions& opt, const Inputs& in,
                                         const WorkPlan& L, std::optional<Checkpoint>& ckpt, const CheckpointKey& key,
                                         Tally& tally, const RunContext& ctx);
void sync_checkpoint(Checkpoint& c, const Tally& tally);
void save_after_error(Checkpoint* ckpt, const Tally& tally) noexcept;
double checkpoint_interval_s();

// run_finish.cpp: the checkpoint removed once the run is complete; the results file, report and exit code.
void remove_checkpoint(Checkpoint& main);
int finish(const parallel::Session& session, const Inputs& in, const WorkPlan& L, Checkpoint* ckpt, Tally& tally,
           const CheckpointKey& key, double wall, const RunContext& ctx, const RunOptions& opt, timing::Times& T,
           std::size_t units_resumed, int threads, std::string& report);

}  // namespace pounding::study_run
