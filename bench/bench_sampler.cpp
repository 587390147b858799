// Google Benchmark of the stochastic structure model: the paper's 30,976 models (11 x 11 period pairs x 256
// samples, one record's worth) drawn through StructureSampler::sample_block, as `pounding run` does per
// work unit. Counter "ns_per_model". Moved here from tests/sampling/test_sampler.cpp (SamplerStreams.
// ThirtyThousandModelsTiming, which could not fail): timings live in benchmarks, not in tests. Run:
//   build/bench_sampler --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "pounding/sampling/sampler.hpp"

namespace {

constexpr std::uint64_t seed = 20240917;  // studies/paper-structures.toml

void BM_sample_paper_models(benchmark::State& state) {
  using namespace pounding;
  const StructureSampler s(StructureModel{}, seed);
  std::vector<SampledPair> out(static_cast<std::size_t>(s.model().samples_per_pair));
  for (auto _ : state) {
    for (std::int64_t p = 0; p < s.model().period_pair_count(); ++p) {
      const SampleId id = s.model().pair_id(p);
      s.sample_block(id.i1, id.i2, 0, out);
      benchmark::DoNotOptimize(out.data());
    }
  }
  const double models = static_cast<double>(s.model().model_count());
  state.counters["ns_per_model"] =
      benchmark::Counter(models * static_cast<double>(state.iterations()) / 1e9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_sample_paper_models)->Unit(benchmark::kMillisecond);

// The stream key alone (four SplitMix64 rounds per sample identity).
void BM_stream_seed(benchmark::State& state) {
  using namespace pounding;
  std::int64_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(stream_seed(seed, structure_stream, SampleId{3, 7, i++}));
}
BENCHMARK(BM_stream_seed);

}  // namespace

BENCHMARK_MAIN();
