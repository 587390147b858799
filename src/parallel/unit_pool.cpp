// The worker threads of one rank: each computes units through its own compute function and hands them back.
#include "unit_pool.hpp"

#include "pounding/core/error.hpp"

#include <utility>

namespace pounding::parallel {

UnitPool::UnitPool(const ThreadComputeFn& compute, int threads) : compute_(compute) {
  workers_.reserve(static_cast<std::size_t>(threads));
  for (int t = 0; t < threads; ++t) workers_.emplace_back([this, t] { work(t); });
}

UnitPool::~UnitPool() {
  {
    std::lock_guard lock(m_);
    closing_ = true;
    queue_.clear();
  }
  queued_cv_.notify_all();
  for (auto& w : workers_) w.join();
}

void UnitPool::submit(std::size_t unit) {
  {
    std::lock_guard lock(m_);
    queue_.push_back(unit);
  }
  ++in_flight_;
  queued_cv_.notify_one();
}

std::vector<std::size_t> UnitPool::drop_queued() {
  std::lock_guard lock(m_);
  std::vector<std::size_t> back(queue_.begin(), queue_.end());
  queue_.clear();
  in_flight_ -= back.size();
  return back;
}

std::optional<UnitPool::Done> UnitPool::take(std::chrono::microseconds wait) {
  if (in_flight_ == 0) return std::nullopt;
  std::unique_lock lock(m_);
  if (!done_cv_.wait_for(lock, wait, [&] { return !done_.empty(); })) return std::nullopt;
  Done d = std::move(done_.front());
  done_.pop_front();
  --in_flight_;
  return d;
}

std::optional<UnitPool::Done> UnitPool::take() {
  if (in_flight_ == 0) return std::nullopt;
  std::unique_lock lock(m_);
  done_cv_.wait(lock, [&] { return !done_.empty(); });
  Done d = std::move(done_.front());
  done_.pop_front();
  --in_flight_;
  return d;
}

void UnitPool::work(int thread) {
  for (;;) {
    std::size_t unit = 0;
    {
      std::unique_lock lock(m_);
      queued_cv_.wait(lock, [&] { return closing_ || !queue_.empty(); });
      if (closing_) return;
      unit = queue_.front();
      queue_.pop_front();
    }
    Done d;
    d.unit = unit;
    try {
      d.payload = compute_(unit, thread);
    } catch (...) {
      d.error = std::current_exception();
    }
    {
      std::lock_guard lock(m_);
      done_.push_back(std::move(d));
    }
    done_cv_.notify_one();
  }
}

// One rank's units on `threads` threads (threads > 1): at most 2 threads units handed to the pool at a time, so a
// stop or an error leaves within a unit's time (the queued ones are dropped, the running ones finish and are
// stored unless a unit failed). on_result and tick run on the calling thread.
bool is_stop(const std::exception_ptr& error) {
  if (!error) return false;
  try {
    std::rethrow_exception(error);
  } catch (const StopRequested&) {
    return true;
  } catch (...) {
    return false;
  }
}

bool run_units_threaded(const std::vector<std::size_t>& todo, const ThreadComputeFn& compute, int threads,
                        const ResultFn& on_result, const TickFn& tick, const std::atomic<bool>& stop) {
  UnitPool pool(compute, threads);
  std::size_t next = 0, stored = 0;
  std::exception_ptr failed;
  const std::size_t window = 2 * static_cast<std::size_t>(threads);
  for (;;) {
    if (stop.load() || failed) pool.drop_queued();
    else
      while (next < todo.size() && pool.in_flight() < window) pool.submit(todo[next++]);
    std::optional<UnitPool::Done> d = pool.take();
    if (!d) break;
    if (failed) continue;  // nothing more is stored after a failure
    if (is_stop(d->error)) continue;  // stopped inside the unit: still to do (the run reports itself stopped)
    if (d->error) {
      failed = d->error;
      continue;
    }
    try {
      on_result(d->unit, std::move(d->payload));
      ++stored;
      tick();
    } catch (...) {
      failed = std::current_exception();
    }
  }
  if (failed) std::rethrow_exception(failed);
  return stored == todo.size();
}

}  // namespace pounding::parallel
