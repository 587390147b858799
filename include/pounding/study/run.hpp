#pragma once
// The study's main job: work units (record, period pair, sample block) -> kernel -> per-model results ->
// checkpoint -> HDF5 results file. Orchestration only; MPI is behind pounding::parallel.
#include <functional>
#include <string>

#include "pounding/parallel/executor.hpp"
#include "pounding/core/run_context.hpp"
#include "pounding/results/results.hpp"
#include "pounding/study/study.hpp"

namespace pounding {

struct RunOptions {
  std::string out;         // overrides the study's output path when out_given (--out "" is an error)
  bool out_given = false;
  bool resume = false;     // continue from <out>.ckpt
  bool force = false;      // discard whatever <out>.ckpt holds
  // Called on rank 0 with the complete results before they are written: the analyses of higher layers (the
  // fragility curves, hazard and risk-targeted separation of a fragility study, report/fragility.hpp) add their
  // groups here, so one results file holds them. An exception ends the run like any other error (the checkpoint
  // keeps the work).
  // `hook` carries the phase progress and the stop flag of the RunContext (RunContext::hook()): a long analysis
  // shows progress and honours a stop by throwing Cancelled (core/progress.hpp); the run then ends with 130 and
  // keeps the checkpoint, so --resume redoes only the analysis.
  std::function<void(results::Results&, const WorkHook& hook)> analyse;
};

struct RunOutcome {
  int code = 0;     // 0 done, 3 done with too many excluded analyses, 130 interrupted
  std::string out;  // the results file (written when code is 0 or 3)
};

// Returns the process exit code on every rank: 0 done, 3 done but too many analyses excluded (the results
// file and the report say so), 130 interrupted (checkpoint kept). Any error on any rank (bad input, resume
// checks, a failed unit, a failed checkpoint or results write) is thrown on every rank as InputError after
// the job has stopped; the caller prints it on rank 0 and exits 2. Messages and progress go to `ctx`.
RunOutcome run_study(const parallel::Session& session, const std::string& study_path, const RunOptions& options,
                     const RunContext& ctx);

}  // namespace pounding
