// The floor of the stick path's memory traffic (issue 25 §7: what limits ns per DOF-step at 5-20 storeys). Per DOF
// and step the stick walk (include/pounding/physics/steppers/system_central_difference.hpp, stick_walk) loads 15 rows
// of W lanes -- U, Vel, A; the storey spring's FS, K, AK, QY, KP, CS; the observers PD, PF; CF, IM; the observers
// PA, PU -- and stores 8: FS, PD, PF, A, Vel, PA, PU and the next step's U. This benchmark does exactly that traffic
// over the same chunk layout (rows of W lanes per DOF, the time loop inside the chunk loop, 256 lanes) with one or
// two cheap operations per value and no physics, no contact elements, no guard: a time no implementation that keeps
// these rows and observers can beat. Compare its ns_per_dof_step with `pounding bench --storeys N --substeps 2`
// (2N DOFs) on the same core, interleaved (README "Speed", issue 25 §7). Run:
//   taskset -c 1 build/bench_stick_floor --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdlib>
#include <memory>

#include "pounding/kernel/lane.hpp"

namespace {

using pounding::simd::V;
constexpr int W = pounding::simd::W;
constexpr int rows = 15;  // the rows one DOF's walk touches
constexpr int lanes = 256, steps = 16000;

void BM_floor(benchmark::State& state) {
  const int ndof = static_cast<int>(state.range(0));
  const int chunks = lanes / W;
  const std::size_t n = static_cast<std::size_t>(chunks) * ndof * rows * W;
  std::unique_ptr<double, decltype(&std::free)> pool(static_cast<double*>(std::aligned_alloc(64, n * sizeof(double))),
                                                     &std::free);
  for (std::size_t i = 0; i < n; ++i) pool.get()[i] = 0.5;
  for (auto _ : state) {
    for (int c = 0; c < chunks; ++c) {
      double* base = pool.get() + static_cast<std::size_t>(c) * ndof * rows * W;
      for (int t = 0; t < steps; ++t) {
        V below(0.0);
        for (int j = 0; j < ndof; ++j) {
          double* p = base + static_cast<std::size_t>(j) * rows * W;
          auto ld = [p](int r) { return V(p + r * W, pounding::simd::stdx::vector_aligned); };
          auto st = [p](const V& v, int r) { v.copy_to(p + r * W, pounding::simd::stdx::vector_aligned); };
          const V u = ld(0), v = ld(1), a = ld(2), fs = ld(3), k = ld(4), ak = ld(5), qy = ld(6), kp = ld(7), cs = ld(8);
          const V pd = ld(9), pf = ld(10), cf = ld(11), im = ld(12), pa = ld(13), pu = ld(14);
          const V d = u - below;
          const V f = pounding::lane::min(pounding::lane::max(fs + k * d, -qy), qy) + ak * kp + cs * v;
          const V na = -(f + cf * v) * im, nv = v + a * 1e-3;
          st(f, 3), st(pounding::lane::max(pd, pounding::lane::abs(d)), 9);
          st(pounding::lane::max(pf, pounding::lane::abs(f)), 10);
          st(na * 1e-9, 2), st(nv * 0.999999, 1), st(pounding::lane::max(pa, pounding::lane::abs(na)), 13);
          st(pounding::lane::max(pu, pounding::lane::abs(u)), 14), st(u + nv * 1e-6, 0);
          below = u;
        }
      }
    }
    benchmark::DoNotOptimize(pool.get());
    benchmark::ClobberMemory();
  }
  const double dof_steps = static_cast<double>(lanes) * steps * ndof;
  // seconds per 1e9 DOF-steps, printed as "s": ns per DOF-step
  state.counters["ns_per_dof_step"] = benchmark::Counter(dof_steps * static_cast<double>(state.iterations()) / 1e9,
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

// 2N DOFs: the pairs of 5, 10 and 20 storeys of `pounding bench --storeys N`
BENCHMARK(BM_floor)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
