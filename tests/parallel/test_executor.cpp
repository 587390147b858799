// The executor on one rank (include/pounding/parallel/executor.hpp): units are computed and delivered in
// the order given, payloads arrive unchanged, a raised stop flag ends the run between units, and an error
// in compute or on_result reaches the caller. Started without mpirun, so the MPI build takes its
// one-rank path and the serial build its only one.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "pounding/parallel/executor.hpp"

using namespace pounding;

namespace {

parallel::Payload bytes_of(std::size_t unit) {
  parallel::Payload p(unit % 5);  // payloads of different sizes, including none
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<std::byte>(unit * 7 + i);
  return p;
}

const parallel::DoneFn no_done;  // one rank: no worker reports a unit

parallel::Session& session() {
  static int argc = 0;
  static char** argv = nullptr;
  static parallel::Session s(argc, argv);
  return s;
}

}  // namespace

TEST(SerialExecutor, OneRankWithoutMpirun) {
  EXPECT_EQ(session().rank(), 0);
  EXPECT_EQ(session().size(), 1);
  EXPECT_TRUE(session().root());
  EXPECT_FALSE(session().mpi());
  std::string s = "unchanged";
  session().broadcast(s);
  EXPECT_EQ(s, "unchanged");
}

TEST(SerialExecutor, RunsUnitsInOrderAndDeliversTheirPayloads) {
  const std::vector<std::size_t> todo = {7, 2, 9, 0, 4};
  std::vector<std::size_t> computed, delivered;
  int ticks = 0;
  const std::atomic<bool> stop{false};
  const bool done = parallel::run_units(
      session(), todo,
      [&](std::size_t u) {
        computed.push_back(u);
        return bytes_of(u);
      },
      [&](std::size_t u, parallel::Payload&& p) {
        EXPECT_EQ(p, bytes_of(u)) << "unit " << u;
        delivered.push_back(u);
      },
      no_done, [&] { ++ticks; }, stop);
  EXPECT_TRUE(done);
  EXPECT_EQ(computed, todo);
  EXPECT_EQ(delivered, todo);
  EXPECT_EQ(ticks, 5);
}

TEST(SerialExecutor, StopFlagEndsTheRunBetweenUnits) {
  std::atomic<bool> stop{false};
  std::vector<std::size_t> delivered;
  const bool done = parallel::run_units(
      session(), {1, 2, 3, 4}, bytes_of,
      [&](std::size_t u, parallel::Payload&&) {
        delivered.push_back(u);
        if (u == 2) stop = true;  // SIGINT while unit 2 is stored
      },
      no_done, [] {}, stop);
  EXPECT_FALSE(done);
  EXPECT_EQ(delivered, (std::vector<std::size_t>{1, 2}));
  // raised before the start: nothing is computed
  int computed = 0;
  EXPECT_FALSE(parallel::run_units(
      session(), {1}, [&](std::size_t u) { return ++computed, bytes_of(u); }, [](std::size_t, parallel::Payload&&) {},
      no_done, [] {}, stop));
  EXPECT_EQ(computed, 0);
  // an empty list is complete
  const std::atomic<bool> never{false};
  EXPECT_TRUE(parallel::run_units(session(), {}, bytes_of, [](std::size_t, parallel::Payload&&) {}, no_done, [] {}, never));
}

TEST(SerialExecutor, ErrorsReachTheCaller) {
  const std::atomic<bool> stop{false};
  std::vector<std::size_t> delivered;
  auto store = [&](std::size_t u, parallel::Payload&&) { delivered.push_back(u); };
  EXPECT_THROW(parallel::run_units(
                   session(), {1, 2, 3},
                   [](std::size_t u) {
                     if (u == 2) throw std::runtime_error("unit 2 failed");
                     return bytes_of(u);
                   },
                   store, no_done, [] {}, stop),
               std::exception);
  EXPECT_EQ(delivered, (std::vector<std::size_t>{1}));
  EXPECT_THROW(parallel::run_units(
                   session(), {1}, bytes_of, [](std::size_t, parallel::Payload&&) { throw std::runtime_error("disk"); },
                   no_done, [] {}, stop),
               std::exception);
  int calls = 0;
  session().agree([&] { ++calls; });
  EXPECT_EQ(calls, 1);
}

// Threads (issue 28): every unit computed once, on a thread index below the count, each thread's state used by one
// thread at a time; every payload delivered once on the calling thread; threads = 1 is the plain loop.
TEST(ThreadedExecutor, EveryUnitOnceEachThreadItsOwnState) {
  std::vector<std::size_t> todo(200);
  for (std::size_t i = 0; i < todo.size(); ++i) todo[i] = (i * 37) % 200;
  constexpr int T = 3;
  std::atomic<int> busy[T] = {0, 0, 0};
  std::atomic<int> computed{0}, overlaps{0};
  std::vector<int> per_thread(T, 0);  // written only by its own thread
  std::vector<std::size_t> delivered;
  const auto caller = std::this_thread::get_id();
  const std::atomic<bool> never{false};
  int ticks = 0;
  const bool done = parallel::run_units(
      session(), todo,
      [&](std::size_t u, int t) {
        EXPECT_TRUE(t >= 0 && t < T);
        if (busy[t]++ != 0) ++overlaps;
        ++per_thread[static_cast<std::size_t>(t)], ++computed;
        std::this_thread::sleep_for(std::chrono::microseconds(50 * (u % 4)));
        --busy[t];
        return bytes_of(u);
      },
      T,
      [&](std::size_t u, parallel::Payload&& p) {
        EXPECT_EQ(std::this_thread::get_id(), caller);
        EXPECT_EQ(p, bytes_of(u)) << "unit " << u;
        delivered.push_back(u);
      },
      no_done, [&] { ++ticks; }, never);
  EXPECT_TRUE(done);
  EXPECT_EQ(overlaps.load(), 0);
  EXPECT_EQ(computed.load(), 200);
  EXPECT_EQ(ticks, 200);
  std::sort(delivered.begin(), delivered.end());
  std::vector<std::size_t> want = todo;
  std::sort(want.begin(), want.end());
  EXPECT_EQ(delivered, want);
  // one thread: the plain loop, in the order given
  std::vector<std::size_t> order;
  EXPECT_TRUE(parallel::run_units(
      session(), {5, 1, 3}, [](std::size_t u, int t) -> parallel::Payload {
        EXPECT_EQ(t, 0);
        return bytes_of(u);
      }, 1,
      [&](std::size_t u, parallel::Payload&&) { order.push_back(u); }, no_done, [] {}, never));
  EXPECT_EQ(order, (std::vector<std::size_t>{5, 1, 3}));
}

TEST(ThreadedExecutor, StopAndErrorsEndTheRunWithinAUnit) {
  std::vector<std::size_t> todo(1000);
  for (std::size_t i = 0; i < todo.size(); ++i) todo[i] = i;
  std::atomic<bool> stop{false};
  std::atomic<int> computed{0};
  std::size_t delivered = 0;
  const auto slow = [&](std::size_t u, int) {
    ++computed;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    return bytes_of(u);
  };
  EXPECT_FALSE(parallel::run_units(
      session(), todo, slow, 2,
      [&](std::size_t, parallel::Payload&&) {
        if (++delivered == 10) stop = true;
      },
      no_done, [] {}, stop));
  // the units queued when the stop came are not computed: at most 2 threads x 2 in flight after the 10th
  EXPECT_LE(computed.load(), 10 + 4);
  EXPECT_EQ(delivered, static_cast<std::size_t>(computed.load()));
  // an error in compute reaches the caller; nothing after it is stored
  const std::atomic<bool> never{false};
  EXPECT_THROW(parallel::run_units(
                   session(), todo,
                   [&](std::size_t u, int t) {
                     if (u == 50) throw std::runtime_error("unit 50 failed");
                     return slow(u, t);
                   },
                   3, [](std::size_t, parallel::Payload&&) {}, no_done, [] {}, never),
               std::runtime_error);
  EXPECT_LT(computed.load(), 14 + 50 + 8);  // the units after the failure's window were never started
  // an error in on_result too
  EXPECT_THROW(parallel::run_units(
                   session(), {1, 2, 3}, slow, 2,
                   [](std::size_t, parallel::Payload&&) { throw std::runtime_error("disk"); }, no_done, [] {}, never),
               std::runtime_error);
}
