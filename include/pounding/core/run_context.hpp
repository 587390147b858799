#pragma once
// What a long job needs from its caller, instead of globals and console I/O in the library: where to say
// things, where to report progress, and whether to stop. The command line supplies a terminal logger, a
// progress bar and a flag set by SIGINT/SIGTERM (src/cli/commands/run.cpp); tests and Python supply their own.
#include <atomic>
#include <cstddef>
#include <functional>
#include <string>

#include "pounding/core/progress.hpp"

namespace pounding {

struct ProgressReport {
  std::size_t units_done = 0, units_total = 0;
  std::size_t units_at_start = 0;  // done before this run (resumed)
  double models_per_unit = 0.0;
  double elapsed_s = 0.0;          // since the work started
  bool final = false;              // every unit is done
};

struct RunContext {
  std::function<void(const std::string&)> info;                // one line for the user (rank 0 only)
  // once as the units start (units_done = units_at_start, elapsed 0), then after each finished unit (rank 0 only)
  std::function<void(const ProgressReport&)> progress;
  const std::atomic<bool>* cancel = nullptr;                   // raised: stop handing out work, keep progress
  // Progress of the phases after the units (the fragility fit's bootstrap, ...; core/progress.hpp), rank 0 only.
  std::function<void(const PhaseProgress&)> phase_progress;

  // What the analyses below the study layer get: the phase progress and the same stop flag.
  WorkHook hook() const { return WorkHook{phase_progress, cancel}; }

  void say(const std::string& line) const {
    if (info) info(line);
  }
  bool cancelled() const { return cancel && cancel->load(); }
};

}  // namespace pounding
