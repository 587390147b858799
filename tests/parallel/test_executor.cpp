// The executor on one rank (include/pounding/parallel/executor.hpp): units are computed and delivered in
// the order given, payloads arrive unchanged, a raised stop flag ends the run between units, and an error
// in compute or on_result reaches the caller. Started without mpirun, so the MPI build takes its
// one-rank path and the serial build its only one.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

#include "pounding/parallel/executor.hpp"

using namespace pounding;

namespace {

parallel::Payload bytes_of(std::size_t unit) {
  parallel::Payload p(unit % 5);  // payloads of different sizes, including none
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<std::byte>(unit * 7 + i);
  return p;
}

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
      [&] { ++ticks; }, stop);
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
      [] {}, stop);
  EXPECT_FALSE(done);
  EXPECT_EQ(delivered, (std::vector<std::size_t>{1, 2}));
  // raised before the start: nothing is computed
  int computed = 0;
  EXPECT_FALSE(parallel::run_units(
      session(), {1}, [&](std::size_t u) { return ++computed, bytes_of(u); }, [](std::size_t, parallel::Payload&&) {},
      [] {}, stop));
  EXPECT_EQ(computed, 0);
  // an empty list is complete
  const std::atomic<bool> never{false};
  EXPECT_TRUE(parallel::run_units(session(), {}, bytes_of, [](std::size_t, parallel::Payload&&) {}, [] {}, never));
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
                   store, [] {}, stop),
               std::exception);
  EXPECT_EQ(delivered, (std::vector<std::size_t>{1}));
  EXPECT_THROW(parallel::run_units(
                   session(), {1}, bytes_of, [](std::size_t, parallel::Payload&&) { throw std::runtime_error("disk"); },
                   [] {}, stop),
               std::exception);
  int calls = 0;
  session().agree([&] { ++calls; });
  EXPECT_EQ(calls, 1);
}
