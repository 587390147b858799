#pragma once
// Named, deterministic workloads shared by `pounding bench`, the Google Benchmark and examples.
#include <cstddef>
#include <vector>

#include "pounding/physics/batch.hpp"

namespace pounding {

// Built-in ground motion: deterministic, 0.4 g peak, a sine sweep 0.3 -> 3 Hz under a
// smooth build-up/decay envelope (the `simulate` example when no --record is given).
std::vector<double> builtin_motion(double dt, double duration);

// The kernel benchmark's batch: `width` bilinear pairs (T1, T2 in [1, 1.5] s, masses around 1e7 kg,
// heights 30-50 m, yield at 2 % drift / 6, alpha 0.05, 5 % damping), gap 0.3 x 0.005 (h1 + h2),
// equivalent-sphere Hertz stiffness, e = 0.65. Parameters vary per lane with a fixed formula.
PairBatch benchmark_batch(std::size_t width);

}  // namespace pounding
