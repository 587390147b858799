#pragma once
// The study's main job: work units (record, period pair, sample block) -> kernel -> per-model results ->
// checkpoint -> HDF5 results file. Orchestration only; MPI is behind pounding::parallel.
#include <chrono>
#include <functional>
#include <string>

#include "pounding/core/run_context.hpp"
#include "pounding/core/timing.hpp"
#include "pounding/parallel/executor.hpp"
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
  // Called on rank 0 after `analyse`, before the results are written: the report `pounding run` prints, rendered
  // from the complete results (their path set, wall_time_s NaN until known: "wall time nan s" in the text is
  // replaced by the written value), so its time is in the results' /timing. Adds the seconds of its separation
  // bootstrap to `bootstrap_s`. A stop (Cancelled) ends the run like a stop in the analysis.
  std::function<std::string(const results::Results&, const WorkHook& hook, double& bootstrap_s)> report;
  // Worker threads per rank (each with its own unit computer; the results do not depend on it): -1 takes the study's
  // [analysis] threads; 0 the automatic count (study_threads); > 0 that many on every rank.
  int threads = -1;
  double mpi_start_s = 0;  // the caller's MPI start-up (timing::Phase::mpi_start), measured before run_study
  // Where the wall time starts: the process's start for `pounding run` (main() starts the clock); a caller in a
  // longer-lived process (Python's Study.run) gives its own call's start -- the process's first call of
  // program_start() came at the run's end there, and the report read "wall time 0.00 s".
  std::chrono::steady_clock::time_point start = timing::program_start();
};

struct RunOutcome {
  int code = 0;     // 0 done, 3 done with too many excluded analyses, 130 interrupted
  std::string out;  // the results file (written when code is 0 or 3)
  std::string report;    // RunOptions::report's text (rank 0, code 0 or 3)
  timing::Times times;   // rank 0: this rank's phases and the maximum over the ranks, wall time to the write's end
  std::string html;      // [report] html = true: the HTML report to write from `out` (checked before any work)
};

// The worker threads per rank of a run: `requested` (RunOptions::threads, else the study's [analysis] threads) when
// > 0; 0: the CPUs of this process's affinity mask when the job is one rank, 1 when it has several (mpirun starts a
// rank per core: threads would oversubscribe). At most `units` (the units to compute; at least 1).
int study_threads(int requested, int ranks, std::size_t units);

// Returns the process exit code on every rank: 0 done, 3 done but too many analyses excluded (the results
// file and the report say so), 130 interrupted (checkpoint kept). Any error on any rank (bad input, resume
// checks, a failed unit, a failed checkpoint or results write) is thrown on every rank as InputError after
// the job has stopped; the caller prints it on rank 0 and exits 2. Messages and progress go to `ctx`.
RunOutcome run_study(const parallel::Session& session, const std::string& study_path, const RunOptions& options,
                     const RunContext& ctx);

}  // namespace pounding
