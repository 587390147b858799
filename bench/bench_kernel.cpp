// Google Benchmark of the batch kernel: ns per pair-step (counter "ns_per_pair_step") for each
// stepper x contact law at batch widths 1, 16, 256, 1024, bilinear pairs, 40 s record at 0.005 s
// (workload 'kernel-bilinear', see include/pounding/workloads/workloads.hpp). Run:
//   build/bench_kernel --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <vector>

#include "pounding/contact/registry.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/workloads/workloads.hpp"

namespace {

void BM_kernel(benchmark::State& state, pounding::Stepper stepper, pounding::ContactLaw law) {
  using namespace pounding;
  const std::size_t width = static_cast<std::size_t>(state.range(0));
  static const std::vector<double> ag = builtin_motion(0.005, 40.0);
  GroundMotion gm{0.005, ag, 0.0};
  PairBatch b = benchmark_batch(width);
  ContactModel cm;
  cm.law = law;
  KernelSettings ks;
  ks.stepper = stepper;
  BatchResult r;
  for (auto _ : state) {
    run_batch(b, cm, gm, ks, r);
    benchmark::DoNotOptimize(r.peak_closing.data());
  }
  const double pair_steps = static_cast<double>(width) * static_cast<double>(ag.size() - 1);
  // kIsRate | kInvert reports seconds per unit; with units of 1e9 pair-steps the number printed (with an
  // "s" suffix by Google Benchmark) is ns per pair-step
  state.counters["ns_per_pair_step"] = benchmark::Counter(
      pair_steps * static_cast<double>(state.iterations()) / 1e9,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void register_all() {
  using pounding::ContactLaw;
  using pounding::Stepper;
  for (Stepper s : {Stepper::central_difference, Stepper::newmark, Stepper::rk4, Stepper::nigam_jennings}) {
    for (ContactLaw law : pounding::contact::law_ids) {
      std::string name = std::string("kernel/") + std::string(pounding::to_string(s)) + "/" +
                         std::string(pounding::to_string(law));
      auto* b = benchmark::RegisterBenchmark(name.c_str(), BM_kernel, s, law);
      b->Arg(1)->Arg(16)->Arg(256)->Arg(1024)->Unit(benchmark::kMillisecond);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
