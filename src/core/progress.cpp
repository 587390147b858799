// Progress and stop for the long loops below the study layer, through the caller's WorkHook.
#include "pounding/core/progress.hpp"

#include <utility>

namespace pounding {

namespace {
constexpr std::int64_t kReportEveryNs = 250'000'000;  // 4 reports a second at most (the terminal throttles further)
}

Meter::Meter(const WorkHook* hook, std::string phase, std::size_t total, std::string unit)
    : hook_(hook), phase_(std::move(phase)), unit_(std::move(unit)), total_(total), t0_(std::chrono::steady_clock::now()) {
  next_ns_.store(kReportEveryNs, std::memory_order_relaxed);
  if (hook_) hook_->check(phase_);
}

bool Meter::step(std::size_t n) {
  if (!hook_) return true;
  if (hook_->cancelled()) return false;
  done_.fetch_add(n, std::memory_order_relaxed);
  if (hook_->progress) {
    const std::int64_t now =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0_).count();
    std::int64_t next = next_ns_.load(std::memory_order_relaxed);
    if (now >= next && next_ns_.compare_exchange_strong(next, now + kReportEveryNs)) report(false);
  }
  return true;
}

void Meter::finish() {
  if (!hook_) return;
  if (hook_->cancelled()) throw Cancelled(phase_);
  if (hook_->progress && reported_.load()) report(true);
}

void Meter::report(bool final) {
  std::lock_guard<std::mutex> lock(mutex_);
  PhaseProgress p;
  p.phase = phase_, p.unit = unit_, p.total = total_, p.final = final;
  p.done = final ? total_ : std::min(done_.load(std::memory_order_relaxed), total_);
  p.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  reported_.store(true);
  hook_->progress(p);
}

}  // namespace pounding
