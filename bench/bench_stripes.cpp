// Google Benchmark of the MSA fragility library (src/analysis/stripes.cpp) at the issue-14 scale: S = 10
// stripes, R = 25 records, M = 30,976 models (7.7 M demands), 6 gaps with B = 2000 record-bootstrap
// replicates, and the risk-targeted gap with its 2000 replicates, on 2 threads. The demands follow a lognormal
// model (record effect plus model noise). Run:
//   build/bench_stripes --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "pounding/analysis/stripes.hpp"

namespace {

using namespace pounding;

const stripes::Demands& paper_scale_demands() {
  static const stripes::Demands d = [] {
    stripes::Demands out;
    out.records = 25, out.models = 30976;
    for (int s = 0; s < 10; ++s) out.levels.push_back(0.1 * std::pow(1.45, s));  // 0.1 .. 2.8
    std::mt19937_64 rng(20240917);
    std::normal_distribution<double> n01;
    std::vector<double> eps(out.records * out.models);
    for (std::size_t r = 0; r < out.records; ++r) {
      const double record = 0.3 * n01(rng);
      for (std::size_t m = 0; m < out.models; ++m) eps[r * out.models + m] = record + 0.4 * n01(rng);
    }
    for (double level : out.levels)
      for (double e : eps) out.demand.push_back(level * std::exp(e));
    return out;
  }();
  return d;
}

stripes::Settings settings() {
  stripes::Settings s;
  s.bootstrap = 2000, s.threads = 2, s.seed = 7;
  return s;
}

void BM_fit_msa_6_gaps(benchmark::State& state) {
  const stripes::Demands& d = paper_scale_demands();
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const std::vector<double> gaps{0.25, 0.5, 0.75, 1.0, 1.5, 2.0};
  for (auto _ : state) benchmark::DoNotOptimize(stripes::fit_msa(d, gaps, settings(), &h));
}
BENCHMARK(BM_fit_msa_6_gaps)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_risk_targeted_gap(benchmark::State& state) {
  const stripes::Demands& d = paper_scale_demands();
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  for (auto _ : state) benchmark::DoNotOptimize(stripes::risk_targeted_gap(d, h, 2.10721e-3, settings()));
}
BENCHMARK(BM_risk_targeted_gap)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_stripe_index(benchmark::State& state) {
  const stripes::Demands& d = paper_scale_demands();
  for (auto _ : state) benchmark::DoNotOptimize(stripes::StripeIndex(d, 2));
}
BENCHMARK(BM_stripe_index)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
