// Google Benchmark of the report's separation bootstrap (src/analysis/separation.cpp, issue 27 item 1): the paper's
// 25 records x 30,976 models (774,400 demands) and 25 records x 4,000,000 models (10^8 demands), lognormal demands
// (record effect plus model noise), 3 targets and 12 gaps, B = 2000 replicates on 2 threads. `prepare` ranks the
// demands once (per-record sorts on 2 threads, a k-way merge); `replicates` is the bootstrap on the prepared demands.
// Run:
//   build/bench_separation --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "pounding/analysis/separation.hpp"

namespace {

using namespace pounding;

const separation::Demands& demands(std::size_t models) {
  static std::map<std::size_t, separation::Demands> cache;
  auto [it, fresh] = cache.try_emplace(models);
  if (fresh) {
    separation::Demands& d = it->second;
    d.records = 25, d.models = models;
    d.z.resize(d.records * d.models);
    std::mt19937_64 rng(27);
    std::normal_distribution<double> n01;
    for (std::size_t r = 0; r < d.records; ++r) {
      const double record = 0.4 * n01(rng);
      for (std::size_t m = 0; m < d.models; ++m) d.z[r * d.models + m] = std::exp(-1.2 + record + 0.3 * n01(rng));
    }
  }
  return it->second;
}

const double targets[] = {0.1, 0.05, 0.01};
const double gaps[] = {0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6, 0.8, 1.0};

void Prepare(benchmark::State& state) {
  const separation::Demands& d = demands(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(separation::prepare(d, 2));
  state.counters["demands"] = static_cast<double>(d.z.size());
}

void Replicates(benchmark::State& state) {
  const separation::Demands& d = demands(static_cast<std::size_t>(state.range(0)));
  const auto p = separation::prepare(d, 2);
  for (auto _ : state)
    benchmark::DoNotOptimize(separation::bootstrap(*p, targets, gaps, {.replicates = 2000, .seed = 1, .threads = 2}));
  state.counters["demands"] = static_cast<double>(d.z.size());
}

}  // namespace

BENCHMARK(Prepare)->Arg(30976)->Arg(4000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Replicates)->Arg(30976)->Arg(4000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
