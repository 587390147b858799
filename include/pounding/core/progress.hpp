#pragma once
// Progress and stop for the long loops below the study layer (the fragility fit's bootstrap and jackknife, the
// risk-targeted gap's replicates, ...), without globals and without signals: the caller hands a WorkHook in
// (through the analysis' settings), the loop counts its steps on a Meter, and a raised stop flag ends the loop
// within one step -- the Meter then throws Cancelled, which the caller (study/run.cpp) turns into "interrupted,
// checkpoint kept, exit 130". The analysis layer only sees an atomic flag and a callback.
//
//   WorkHook hook{report_line, &stop_flag};
//   Meter m(&hook, "fit: fragility bootstrap", B, "replicates");
//   parallel_blocks(B, T, [&](size_t first, size_t last) { for (b = first; b < last; ++b) { if (!m.step()) return; ... } });
//   m.finish();  // throws Cancelled if a stop came; else one final report
//
// A null hook costs one branch per step. The callback is called by one thread at a time, at most every 250 ms
// (plus once at the end of a phase that took longer than that), from whichever worker thread counted the step.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

namespace pounding {

struct PhaseProgress {
  std::string phase;      // e.g. "fit: fragility bootstrap"
  std::string unit;       // what is counted: "replicates", "records", ...
  std::size_t done = 0, total = 0;
  double elapsed_s = 0.0;  // since the phase began
  bool final = false;      // the phase is complete
};

// A stop was asked for (WorkHook::cancel raised) while a Meter counted.
class Cancelled : public std::runtime_error {
 public:
  explicit Cancelled(const std::string& phase) : std::runtime_error("stopped on request during " + phase), phase_(phase) {}
  const std::string& phase() const { return phase_; }

 private:
  std::string phase_;
};

struct WorkHook {
  std::function<void(const PhaseProgress&)> progress;  // may be empty
  const std::atomic<bool>* cancel = nullptr;            // may be null

  bool cancelled() const { return cancel && cancel->load(std::memory_order_relaxed); }
  // Throws Cancelled(phase) when the stop flag is raised (for the checks between phases).
  void check(const std::string& phase) const {
    if (cancelled()) throw Cancelled(phase);
  }
};

class Meter {
 public:
  // hook may be null (no progress, no stop).
  Meter(const WorkHook* hook, std::string phase, std::size_t total, std::string unit = "replicates");
  Meter(const Meter&) = delete;
  Meter& operator=(const Meter&) = delete;

  // n more steps done; thread-safe. Returns false once a stop is asked for: end the loop (and call finish()).
  bool step(std::size_t n = 1);
  // Whether a stop was asked for (without counting).
  bool stopped() const { return hook_ && hook_->cancelled(); }
  // After the loop (on the calling thread, after the workers joined): throws Cancelled if a stop was asked
  // for, else reports the phase complete (when it was long enough to have reported at all).
  void finish();

 private:
  void report(bool final);
  const WorkHook* hook_;
  std::string phase_, unit_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::atomic<bool> reported_{false};
  std::chrono::steady_clock::time_point t0_;
  std::atomic<std::int64_t> next_ns_{0};  // the next report's time, ns since t0_
  std::mutex mutex_;
};

}  // namespace pounding
