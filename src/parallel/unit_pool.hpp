#pragma once
// The threads of one rank (private to src/parallel): `threads` workers, each computing units through its own
// compute(unit, thread) -- the study gives every thread its own UnitComputer -- and handing the payloads back to the
// thread that owns the pool (the only one that stores results, checkpoints and talks MPI). Results come back in
// completion order; the caller stores them by unit id, so what it builds does not depend on the order.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "pounding/parallel/executor.hpp"

namespace pounding::parallel {

class UnitPool {
 public:
  struct Done {
    std::size_t unit = 0;
    Payload payload;
    std::exception_ptr error;  // compute threw (payload empty)
  };

  UnitPool(const ThreadComputeFn& compute, int threads);
  ~UnitPool();  // drops the queued units, waits for the running ones
  UnitPool(const UnitPool&) = delete;
  UnitPool& operator=(const UnitPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()); }
  void submit(std::size_t unit);
  // units submitted and not yet taken back (queued, running or finished)
  std::size_t in_flight() const { return in_flight_; }
  // Takes back the units not yet started (a stop or a failure), in submission order.
  std::vector<std::size_t> drop_queued();
  // A finished unit: waits up to `wait` for one (nullopt: none finished in time, or nothing in flight).
  std::optional<Done> take(std::chrono::microseconds wait);
  // Waits for a finished unit (nullopt only when nothing is in flight).
  std::optional<Done> take();

 private:
  void work(int thread);

  const ThreadComputeFn& compute_;
  std::mutex m_;
  std::condition_variable queued_cv_, done_cv_;
  std::deque<std::size_t> queue_;
  std::deque<Done> done_;
  bool closing_ = false;
  std::size_t in_flight_ = 0;  // owner thread only
  std::vector<std::thread> workers_;
};

// run_units on one rank with threads > 1 (both executors).
// Whether a unit's error is a stop inside it (StopRequested): the unit is still to do, not a failure.
bool is_stop(const std::exception_ptr& error);

bool run_units_threaded(const std::vector<std::size_t>& todo, const ThreadComputeFn& compute, int threads,
                        const ResultFn& on_result, const TickFn& tick, const std::atomic<bool>& stop);

}  // namespace pounding::parallel
