// The smooth hysteresis models of issue 25 step 7 (model/hysteresis/{smooth,bouc_wen,friction_pendulum}.hpp) against
// closed forms (../shared/research/systems-and-bridges.md §2, T2.2, T2.3): Bouc-Wen's monotonic loading from rest
// (eta = 1: z = 1 - exp(-u/u_y), exact for the exponential update; eta = 2: tanh(u/u_y), second order in the step),
// the exact steady-cycle dissipation EDC, the friction pendulum's mu(v) and its loop under an imposed sinusoid against
// the rigid-plastic plateau mu W sgn(v) + W u / R as u_y -> 0 (the smoothed stick-slip converging to Coulomb), the
// update's bits at both lane types, and the traits (no elastic range; the exact unscaled equivalents).
#ifndef POUNDING_BITS_NOT_CLAIMED
#error "POUNDING_BITS_NOT_CLAIMED is set by CMakeLists.txt"
#endif
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "pounding/model/hysteresis/registry.hpp"

using namespace pounding;
using model::BoucWen;
using model::FrictionPendulum;
using model::Smooth;
using model::SmoothParams;

namespace {

const double pi = std::acos(-1.0);

// z along an imposed path u[0..n] from z = 0; returns z at the end and the loop area of F over the last `tail` steps
struct Path {
  double z = 0.0, area = 0.0, f = 0.0;
};
Path drive(const SmoothParams<double>& p, const std::vector<double>& u, double dt, std::size_t tail) {
  Path r;
  double h0 = 0.0, f0 = p.k * u[0];
  for (std::size_t s = 1; s < u.size(); ++s) {
    const double du = u[s] - u[s - 1];
    const double z1 = Smooth::z_next(p, r.z, du);
    double h1 = 0.0;
    const double f1 = Smooth::restoring(p, z1, u[s], du / dt, h1);
    if (s + tail >= u.size()) r.area += 0.5 * (f0 + f1) * du;
    r.z = z1, h0 = h1, f0 = f1;
  }
  r.f = f0;
  (void)h0;
  return r;
}
std::vector<double> ramp(double to, int n) {
  std::vector<double> u(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) u[static_cast<std::size_t>(i)] = to * i / n;
  return u;
}
std::vector<double> sine(double D, int per_cycle, int cycles) {
  std::vector<double> u(static_cast<std::size_t>(per_cycle * cycles) + 1);
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = D * std::sin(2 * pi * static_cast<double>(i) / per_cycle);
  return u;
}
// T2.2's bearing: k_init 10 MN/m, alpha 0.1 (Q 100 kN, k2 1 MN/m, u_y = 1/90 m)
BoucWen::Spec t22(int eta, double beta, double gamma) { return {1.0e7, 0.1, 1.0 / 90.0, 1.0, beta, gamma, eta}; }

}  // namespace

// eta = 1 from rest: z = 1 - exp(-u/u_y) exactly (the update is the exact solution while z keeps its sign), to 1e-14
// even with steps of 2 mm = 0.18 u_y (T2.2's ramp; backward Euler gives 0.8089 there, the exact value 0.834701112).
TEST(SmoothHysteresis, BoucWenMonotonicEtaOneIsExact) {
  const auto p = BoucWen::params(t22(1, 0.5, 0.5));
  const Path r = drive(p, ramp(0.02, 10), 1.0, 0);
  EXPECT_NEAR(r.z, 1.0 - std::exp(-0.02 * 90.0), 1e-14);
  EXPECT_NEAR(r.z, 0.834701112, 1e-9);
}

// eta = 2 from rest: z = tanh(u/u_y) (T2.2: tanh(1.8) = 0.946806013); the error falls as the step squared.
TEST(SmoothHysteresis, BoucWenMonotonicEtaTwoConvergesSecondOrder) {
  const auto p = BoucWen::params(t22(2, 0.5, 0.5));
  std::vector<double> err;
  for (int n : {20, 40, 80, 160}) {
    err.push_back(std::abs(drive(p, ramp(0.02, n), 1.0, 0).z - std::tanh(1.8)));
    std::printf("ramp in %d steps: |z - tanh(1.8)| = %.3g\n", n, err.back());
  }
  for (std::size_t i = 0; i + 1 < err.size(); ++i) {
    const double order = std::log2(err[i] / err[i + 1]);
    EXPECT_NEAR(order, 2.0, 0.3) << "halving " << i;
  }
  EXPECT_LT(err.back(), 1e-5);
}

// The steady cycle +-0.25 m (3rd cycle) against the exact EDC (T2.2): eta = 1, beta = gamma = 0.5: 4 Q (D - 1.25 u_y)
// = 94444.4444 J; eta = 2: 95126.3396 J; within 2e-5 at 8000 steps per cycle, and closer at 16000 than at 4000.
TEST(SmoothHysteresis, BoucWenCycleDissipationIsTheClosedForm) {
  struct Case { int eta; double exact; };
  for (const Case c : {Case{1, 94444.4444}, Case{2, 95126.3396}}) {
    const auto p = BoucWen::params(t22(c.eta, 0.5, 0.5));
    double e4 = 0, e16 = 0;
    for (int n : {4000, 8000, 16000}) {
      const double area = drive(p, sine(0.25, n, 3), 1.0, static_cast<std::size_t>(n)).area;
      std::printf("eta %d, %d steps per cycle: EDC %.4f J (exact %.4f)\n", c.eta, n, area, c.exact);
      if (n == 8000) EXPECT_NEAR(area, c.exact, 2e-5 * c.exact);
      (n == 4000 ? e4 : e16) = std::abs(area - c.exact);
    }
    EXPECT_LT(e16, e4);
  }
}

// T2.3: mu(v) of mu_max 0.10, mu_min 0.05, a = 20 s/m at v = 0.01, 0.05, 0.1, 0.2, 0.5; W = 1 MN, R = 2 m, sliding
// (z = 1) at u = 0.1 m, v = 0.2 m/s: F = 149084.218 N.
TEST(SmoothHysteresis, FrictionPendulumVelocityLaw) {
  const auto p = FrictionPendulum::params({1.0e6, 2.0, 0.05, 0.10, 20.0, 1e-4});
  const double v[] = {0.0, 0.01, 0.05, 0.1, 0.2, 0.5};
  const double mu[] = {0.05, 0.0590634623, 0.0816060279, 0.0932332358, 0.0990842181, 0.0999977300};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(Smooth::strength(p, v[i]) / 1e6, mu[i], 1e-10) << "v = " << v[i];
  double h = 0;
  EXPECT_NEAR(Smooth::restoring(p, 1.0, 0.1, 0.2, h), 149084.218, 1e-3);
  EXPECT_NEAR(2 * pi * std::sqrt(2.0 / 9.80665), 2.83749123, 1e-8);  // T = 2 pi sqrt(R/g)
}

// The smoothed stick-slip tends to Coulomb: under u = D sin(wt) (D = 0.1 m, constant mu = 0.06, W = 1 MN, R = 2 m) the
// force on the sliding branches approaches mu W sgn(v) + W u / R and the loop's area the rigid-plastic 4 mu W D, the
// error of both proportional to u_y (halving u_y halves it, within 15%).
TEST(SmoothHysteresis, FrictionPendulumConvergesToCoulombAsUyVanishes) {
  const double W = 1e6, R = 2.0, mu = 0.06, D = 0.1;
  std::vector<double> area_err, plateau_err;
  for (double uy : {4e-3, 2e-3, 1e-3, 5e-4}) {
    const auto p = FrictionPendulum::params({W, R, mu, mu, 0.0, uy});
    const int n = 40000;
    const auto u = sine(D, n, 2);
    double z = 0, worst = 0, area = 0, f0 = p.k * u[0];
    for (std::size_t s = 1; s < u.size(); ++s) {
      const double du = u[s] - u[s - 1];
      z = Smooth::z_next(p, z, du);
      double h = 0;
      const double f = Smooth::restoring(p, z, u[s], du, h);
      if (s > static_cast<std::size_t>(n)) {
        area += 0.5 * (f0 + f) * du;
        // sliding branches: away from the reversals (|u| < 0.8 D)
        if (std::abs(u[s]) < 0.8 * D) worst = std::max(worst, std::abs(f - (mu * W * (du > 0 ? 1 : -1) + W / R * u[s])));
      }
      f0 = f;
    }
    area_err.push_back(std::abs(area - 4 * mu * W * D) / (4 * mu * W * D));
    plateau_err.push_back(worst / (mu * W));
    std::printf("u_y = %.1e m: EDC %.2f J (Coulomb %.2f), relative %.3g; plateau error %.3g mu W\n", uy, area,
                4 * mu * W * D, area_err.back(), plateau_err.back());
  }
  for (std::size_t i = 0; i + 1 < area_err.size(); ++i) {
    EXPECT_NEAR(area_err[i] / area_err[i + 1], 2.0, 0.3) << "EDC, halving u_y " << i;
    EXPECT_LT(plateau_err[i + 1], plateau_err[i]);
  }
  EXPECT_LT(area_err.back(), 0.01);
  EXPECT_LT(plateau_err.back(), 1e-3);
}

// The update and the strength give the same bits at T = double and T = simd::V on random states and increments
// (z across [-1.1, 1.1], du from 1e-9 to 0.05 m of both signs, eta 1..8, v to 2 m/s).
TEST(SmoothHysteresis, BitEqualAtBothLaneTypes) {
  if (*POUNDING_BITS_NOT_CLAIMED) GTEST_SKIP() << "no identical-bits claim in this build: " << POUNDING_BITS_NOT_CLAIMED;
  using V = simd::V;
  constexpr int W = simd::W;
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int differ = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    alignas(64) double z[W], du[W], v[W], eta[W], zd[W], qd[W];
    SmoothParams<double> ps[W];
    for (int j = 0; j < W; ++j) {
      BoucWen::Spec s{1e7 * (0.1 + u(g)), 0.5 * u(g), 1e-4 + 0.02 * u(g), 0.5 + u(g), 0.1 + u(g), 0.0, 1 + static_cast<int>(8 * u(g)) % 8};
      s.gamma = (2 * u(g) - 1) * s.beta;
      ps[j] = BoucWen::params(s);
      ps[j].rate = 30 * u(g), ps[j].q_fast = ps[j].q_slow * (1 + u(g));
      z[j] = 2.2 * u(g) - 1.1, du[j] = (u(g) < 0.5 ? -1 : 1) * std::pow(10.0, -9 + 7.7 * u(g)), v[j] = 4 * u(g) - 2;
      eta[j] = ps[j].eta;
      zd[j] = Smooth::z_next(ps[j], z[j], du[j]);
      qd[j] = Smooth::strength(ps[j], v[j]);
    }
    auto col = [&](auto get) {
      alignas(64) double x[W];
      for (int j = 0; j < W; ++j) x[j] = get(ps[j]);
      return V(x, simd::stdx::vector_aligned);
    };
    const SmoothParams<V> pv{col([](auto& p) { return p.k; }),     col([](auto& p) { return p.q_slow; }),
                             col([](auto& p) { return p.q_fast; }), col([](auto& p) { return p.rate; }),
                             col([](auto& p) { return p.a_uy; }),   col([](auto& p) { return p.b_uy; }),
                             col([](auto& p) { return p.g_uy; }),   col([](auto& p) { return p.z_max; }),
                             col([](auto& p) { return p.eta; }),    col([](auto& p) { return p.uy_2a; })};
    (void)eta;
    const V zv = Smooth::z_next<V>(pv, V(z, simd::stdx::vector_aligned), V(du, simd::stdx::vector_aligned));
    const V qv = Smooth::strength<V>(pv, V(v, simd::stdx::vector_aligned));
    for (int j = 0; j < W; ++j)
      if (std::memcmp(&zd[j], &static_cast<const double&>(zv[j]), 8) != 0 || qd[j] != qv[j]) ++differ;
  }
  EXPECT_EQ(differ, 0);
}

// Traits: no elastic range; unscaled_equivalent exact: F(f u; spec) = f F(u; spec') along a random-ish path.
TEST(SmoothHysteresis, Traits) {
  static_assert(model::law_of<BoucWen> >= 0 && model::law_of<FrictionPendulum> >= 0);  // registered
  const BoucWen::Spec bw = t22(2, 0.7, 0.3);
  const FrictionPendulum::Spec fp{1e6, 2.0, 0.05, 0.10, 20.0, 5e-4};
  EXPECT_FALSE(BoucWen::stays_elastic(bw, 0.0, 1.0));
  EXPECT_FALSE(FrictionPendulum::stays_elastic(fp, 0.0, 1.0));
  const double f = 0.37;
  std::vector<double> path = sine(0.05, 400, 2), scaled = path;
  for (std::size_t i = 0; i < path.size(); ++i) path[i] += 0.01 * std::sin(7.0 * i / 400), scaled[i] = f * path[i];
  for (int which = 0; which < 2; ++which) {
    const auto p = which == 0 ? BoucWen::params(bw) : FrictionPendulum::params(fp);
    const auto q = which == 0 ? BoucWen::params(*BoucWen::unscaled_equivalent(bw, f))
                              : FrictionPendulum::params(*FrictionPendulum::unscaled_equivalent(fp, f));
    const double dt = 0.005;
    const Path a = drive(p, scaled, dt, 0), b = drive(q, path, dt, 0);
    EXPECT_NEAR(a.f, f * b.f, 1e-9 * std::abs(a.f)) << (which == 0 ? "Bouc-Wen" : "friction pendulum");
  }
}
