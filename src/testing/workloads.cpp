#include "pounding/testing/workloads.hpp"

#include <cmath>
#include <numbers>

#include "pounding/contact/model.hpp"
#include "pounding/motion/records.hpp"

namespace pounding {

std::vector<double> builtin_motion(double dt, double duration) {
  const std::size_t n = static_cast<std::size_t>(std::lround(duration / dt)) + 1;
  std::vector<double> a(n);
  const double f0 = 0.3, f1 = 3.0, Tsw = duration;
  double peak = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double t = static_cast<double>(i) * dt;
    double env = std::pow(t / (0.25 * duration), 2) * std::exp(2.0 * (1.0 - t / (0.25 * duration)));
    double phase = 2.0 * std::numbers::pi * (f0 * t + 0.5 * (f1 - f0) * t * t / Tsw);
    a[i] = env * std::sin(phase);
    peak = std::max(peak, std::abs(a[i]));
  }
  for (double& x : a) x *= 0.4 * g_accel / peak;
  return a;
}

PairBatch benchmark_batch(std::size_t width) {
  PairBatch b;
  b.resize(width);
  for (std::size_t i = 0; i < width; ++i) {
    double s = std::fmod(0.6180339887498949 * static_cast<double>(i + 1), 1.0);  // low-discrepancy in [0,1)
    double r = std::fmod(0.7548776662466927 * static_cast<double>(i + 1), 1.0);
    double T1 = 1.0 + 0.5 * s, T2 = 1.0 + 0.5 * r;
    double h1 = 30.0 + 20.0 * s, h2 = 30.0 + 20.0 * r;
    double m1 = 1.0e7 * (0.8 + 0.4 * r), m2 = 1.0e7 * (0.8 + 0.4 * s);
    Structure s1 = Structure::from_period(m1, T1, 0.05), s2 = Structure::from_period(m2, T2, 0.05);
    s1.fy = s1.k * 0.02 * h1 / 6.0, s1.alpha = 0.05;
    s2.fy = s2.k * 0.02 * h2 / 6.0, s2.alpha = 0.05;
    PairParams p;
    p.s1 = s1, p.s2 = s2;
    p.gap = 0.3 * 0.005 * (h1 + h2);
    p.kc = hertz_stiffness_spheres(m1, m2, 2400.0, 24.86e9, 0.15);
    p.e = 0.65;
    b.set(i, p);
  }
  return b;
}

}  // namespace pounding
