#pragma once
// Threads on one process (layer 0): contiguous blocks of an index range, one per thread. The results of every
// caller are independent of the thread count (each index is computed alone, reductions run in index order after).
#include <sched.h>

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace pounding {

// The CPUs this process may run on: its affinity mask (an MPI rank bound to one core gets 1), else the machine's.
inline int available_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n > 0) return n;
  }
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// requested > 0: that many; 0: available_cpus(). Never more than the work items, never fewer than 1.
inline int thread_count(int requested, std::size_t work) {
  const int t = std::max(1, requested > 0 ? requested : available_cpus());
  return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(t), std::max<std::size_t>(1, work)));
}

// f(first, last) on contiguous blocks of [0, n), one per thread (at most n threads; one block runs on the caller's
// thread). f must not throw on the other threads: catch inside and report per index.
template <class F>
void parallel_blocks(std::size_t n, int threads, F&& f) {
  const std::size_t T = std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), n);
  if (T <= 1) {
    f(std::size_t{0}, n);
    return;
  }
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < T; ++t) pool.emplace_back([&f, n, t, T] { f(n * t / T, n * (t + 1) / T); });
  try {
    f(0, n / T);
  } catch (...) {  // joined before the error leaves (the other blocks must not throw)
    for (auto& th : pool) th.join();
    throw;
  }
  for (auto& th : pool) th.join();
}

}  // namespace pounding
