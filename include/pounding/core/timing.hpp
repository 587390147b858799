#pragma once
// Where a run's wall time goes (issue 27, item 2). One number per phase, each as rank 0's seconds and the largest
// over the ranks; `pounding run` stores them in the results' /timing group, prints them in one line at the end
// and as a table with --timings (README, "What a run prints"; docs/results-format.md, /timing).
//
// The clock starts at the process's start (program_start(): main() calls it first), so the wall time covers MPI
// start-up, reading the study and records, the units, the analysis and the report -- everything the user waits
// for. Phases are not exclusive: `units` is the work phase's wall time and `compute`, `reduce`, `checkpoint` are
// the parts of it spent computing units, storing results and writing each rank's own checkpoint file (unit records
// appended, or with [outputs] per_model = false snapshots of the folded counts);
// `bootstrap` is the part of `report` spent in the separation bootstrap.
#include <array>
#include <chrono>
#include <cstddef>
#include <string_view>

namespace pounding::timing {

enum class Phase : std::size_t {
  mpi_start, inputs, structures, units, compute, reduce, checkpoint, analysis, report, bootstrap, results_write
};
inline constexpr std::size_t phase_count = 11;
inline constexpr std::array<std::string_view, phase_count> phase_names{
    "mpi_start", "inputs", "structures", "units", "compute", "reduce", "checkpoint", "analysis", "report",
    "bootstrap", "results_write"};
inline constexpr std::array<std::string_view, phase_count> phase_meanings{
    "MPI start-up (MPI_Init, ranks and size)",
    "reading the study, the records read or synthesised (and selected or scaled), the checkpoint opened",
    "the structure sampler and the unit computer set up (the samples themselves are drawn inside compute)",
    "the work phase: every unit computed, gathered and checkpointed (wall time)",
    "computing units on this rank (inside units), summed over the rank's worker threads: with T busy threads about "
    "T times units",
    "storing the units' results (inside units): rank 0 the units it computed, in the result arrays; with [outputs] "
    "per_model = false every rank folds its own units into its reductions",
    "writing this rank's checkpoint file (inside units): with per-model outputs appending each unit it computed and "
    "flushing every 5 s and at the end; with [outputs] per_model = false saving a snapshot of its folded counts "
    "every 5 s and at the end",
    "the analyses after the units (a fragility study's fit, hazard; rank 0)",
    "the Markdown report that pounding run prints (rank 0; the results file's bulk is written beside it on another "
    "thread)",
    "the separation bootstrap inside the report (rank 0)",
    "writing the results file, the part after the report (rank 0: the bulk not done beside the report, then the "
    "header's end and the groups; not in the file's own /timing, which is written by it)"};

struct Times {
  std::array<double, phase_count> rank0{}, max{};  // s
  double wall = 0;                                  // s, program start to the last phase measured
  double& operator[](Phase p) { return rank0[static_cast<std::size_t>(p)]; }
  double operator[](Phase p) const { return rank0[static_cast<std::size_t>(p)]; }
};

// The process's start (the first call; main() calls it before anything else).
inline std::chrono::steady_clock::time_point program_start() {
  static const std::chrono::steady_clock::time_point t = std::chrono::steady_clock::now();
  return t;
}
inline double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Adds the seconds of its lifetime to `sink`.
class Stopwatch {
 public:
  explicit Stopwatch(double& sink) : sink_(sink), t0_(std::chrono::steady_clock::now()) {}
  ~Stopwatch() { sink_ += seconds_since(t0_); }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  double& sink_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace pounding::timing
