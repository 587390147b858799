// The bridge link laws of issue 26 §1 (model/hysteresis/bridge_links.hpp) against the test vectors of
// ../shared/research/systems-and-bridges.md §5 (computed there from the laws' definitions, not by this code): T5.1 the
// cable restrainer's path with its growing slack, T5.3 Caltrans SDC's abutment stiffness and capacity, T5.4 OpenSees'
// HyperbolicGapMaterial envelope, T5.5 Q-Hyst's defining cycle (Saiidi & Sozen 1979); the gap laws' bits at both lane
// types; Q-Hyst's small-loop rule and the traits (stays elastic / unscaled equivalent).
#ifndef POUNDING_BITS_NOT_CLAIMED
#error "POUNDING_BITS_NOT_CLAIMED is set by CMakeLists.txt"
#endif
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "pounding/model/hysteresis/registry.hpp"

using namespace pounding;
using model::GapSpring;

namespace {

// drives a gap law through the points, returning (force, gap after) at each
struct Pt { double f, gap; };
template <bool Hyp> std::vector<Pt> drive(const model::GapParams<double>& p, const std::vector<double>& path, double gap0) {
  std::vector<Pt> out;
  double s = gap0;
  for (double d : path) {
    const double f = GapSpring::force<Hyp>(p, d, s);
    out.push_back({f, s});
  }
  return out;
}

}  // namespace

// T5.1: n = 5 cables, L = 4 m: k_r = 1.234381e7 N/m, F_y = 8.690046e5 N, slack 0.0127 m, alpha = 0.05.
TEST(BridgeLinks, RestrainerPathT51) {
  const model::TensionGap::Spec spec{1.234381e7, 8.690046e5, 0.05, 0.0127, 1};
  const auto p = model::TensionGap::params(spec);
  const std::vector<double> path{0.0127, 0.05, 0.0831, 0.10, 0.06, 0.03, 0.11, 0.0};
  const std::vector<double> want{0.0, 4.604243e5, 8.690046e5, 8.794351e5, 3.856825e5, 1.536805e4, 8.856070e5, 0.0};
  const auto got = drive<false>(p, path, spec.slack);
  for (std::size_t i = 0; i < path.size(); ++i)
    EXPECT_NEAR(got[i].f, want[i], 2e-6 * 8.69e5 + 1e-9) << "opening " << path[i];
  EXPECT_NEAR(got[3].gap, 0.028755, 1e-6);  // slack after yielding at 0.10
  EXPECT_NEAR(got[6].gap, 0.038255, 1e-6);  // and at 0.11
  // in compression (the joint closing) a restrainer carries nothing
  double s = spec.slack;
  EXPECT_EQ(GapSpring::force<false>(p, -0.2, s), 0.0);
  // mirrored (side -1), the same law on -d
  model::TensionGap::Spec m = spec;
  m.side = -1;
  const auto q = drive<false>(model::TensionGap::params(m), {-0.0127, -0.05, -0.0831, -0.10, -0.06}, m.slack);
  EXPECT_NEAR(q[3].f, -8.794351e5, 2.0);
  EXPECT_NEAR(q[4].f, -3.856825e5, 2.0);
}

// T5.3: Caltrans SDC for w = 12 m, h = 2.0 m (exact unit conversions): K_abut = 4.112835e8 N/m, P_bw = 6.854726e6 N;
// then the EPP backfill law: nothing inside the gap, K_abut past it, capped at P_bw, the gap grows after yield.
TEST(BridgeLinks, CaltransAbutmentT53AndEppBackfill) {
  const model::CaltransAbutment a = model::caltrans_abutment(12.0, 2.0);
  EXPECT_NEAR(a.k, 4.112835e8, 1e-6 * 4.112835e8);
  EXPECT_NEAR(a.p_bw, 6.854726e6, 1e-6 * 6.854726e6);
  const model::CompressionGap::Spec spec{a.k, a.p_bw, 0.0, 0.05, -1};  // a wall on the left: resists d < -0.05
  const auto p = model::CompressionGap::params(spec);
  const auto got = drive<false>(p, {-0.04, -0.06, -0.08, -0.07, -0.0, -0.075}, spec.gap);
  // the spring force f acts -f on the frame (model/system.hpp): a wall on the left pushes it right, f = -F
  EXPECT_EQ(got[0].f, 0.0);
  EXPECT_NEAR(got[1].f, -a.k * 0.01, 1e-6 * a.k * 0.01);
  EXPECT_NEAR(got[2].f, -a.p_bw, 1e-6 * a.p_bw);            // capped
  const double s = 0.08 - a.p_bw / a.k;                       // the soil stays pushed: gap s
  EXPECT_NEAR(got[2].gap, s, 1e-12);
  EXPECT_NEAR(got[3].f, -a.k * (0.07 - s), 1e-6 * a.p_bw);   // unloading at K_abut
  EXPECT_EQ(got[4].f, 0.0);
  EXPECT_NEAR(got[5].f, -std::max(0.0, a.k * (0.075 - s)), 1e-6 * a.p_bw);
  double away = spec.gap;
  EXPECT_EQ(GapSpring::force<false>(p, 0.3, away), 0.0);  // moving away from the wall: nothing
}

// T5.4: HyperbolicGapMaterial's recommended values per metre of wall: K_max 20300 kN/m, K_ur = K_max, R_f 0.7, F_ult
// 326 kN, gap 2.54 cm; wall displacement -> force per metre.
TEST(BridgeLinks, HyperbolicAbutmentT54) {
  const model::HyperbolicGap::Spec spec{2.03e7, 2.03e7, 0.7, 3.26e5, 0.0254, 1};
  const auto p = model::HyperbolicGap::params(spec);
  const std::vector<double> path{0.0254, 0.03, 0.0354, 0.05, 0.1018};
  const std::vector<double> want{0.0, 77783.6603, 141375.774, 240979.978, 358163.900};
  const auto got = drive<true>(p, path, spec.gap);
  for (std::size_t i = 0; i < path.size(); ++i) EXPECT_NEAR(got[i].f, want[i], 1e-3) << "displacement " << path[i];
  // F_ult is reached 0.0535304 m past the gap: F_ult / (K_max (1 - R_f))
  double s = spec.gap;
  EXPECT_NEAR(GapSpring::force<true>(p, 0.0254 + 0.0535304, s), 3.26e5, 1.0);
  // unloading at K_ur from the envelope, then the reload returns to it
  s = spec.gap;
  const double f1 = GapSpring::force<true>(p, 0.05, s);
  const double f2 = GapSpring::force<true>(p, 0.045, s);
  EXPECT_NEAR(f1 - f2, 2.03e7 * 0.005, 1e-6 * f1);
  EXPECT_NEAR(GapSpring::force<true>(p, 0.05, s), f1, 1e-9 * f1);
  const double delta = 0.06 - 0.0254;  // and past it, the envelope again
  EXPECT_NEAR(GapSpring::force<true>(p, 0.06, s), delta / (1 / 2.03e7 + 0.7 * delta / 3.26e5), 1e-6 * f1);
}

// T5.5: Q-Hyst k0 = 1e8 N/m, F_y = 2e5 N, alpha = 0.05, its defining cycle (the unloading stiffness
// k0 sqrt(d_y / d_m) = 5.773503e7 after d_m = 6 mm; reloading aimed at the other side's peak).
TEST(BridgeLinks, QHystDefiningCycleT55) {
  const model::QHyst::Spec spec{1e8, 2e5, 0.05, 0.5};
  const auto p = model::QHyst::params(spec);
  model::QHystState st = model::QHyst::initial(p);
  const std::vector<double> path{0.002, 0.006, 0.003, -0.002, -0.004, -0.001, 0.0, 0.003, 0.006, 0.008};
  const std::vector<double> want{2.0e5, 2.2e5, 46794.92, -2.0e5, -2.1e5, -36794.92, 12540.68, 116270.3, 2.2e5, 2.3e5};
  double d = 0.0, f = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    f = model::QHyst::step(p, st, d, path[i], f);
    d = path[i];
    EXPECT_NEAR(f, want[i], 0.05 + 1e-6 * std::abs(want[i])) << "u = " << path[i];
    if (i == 2) EXPECT_NEAR(model::QHyst::unloading_stiffness(p, st), 5.773503e7, 1e-7 * 5.773503e7);
  }
  // the same path in 1000 small increments per leg: the law is rate independent and its branches are straight
  model::QHystState fine = model::QHyst::initial(p);
  d = 0.0, f = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double from = d;
    for (int k = 1; k <= 1000; ++k) {
      const double to = from + (path[i] - from) * k / 1000.0;
      f = model::QHyst::step(p, fine, d, to, f);
      d = to;
    }
    EXPECT_NEAR(f, want[i], 0.05 + 1e-6 * std::abs(want[i])) << "fine path, u = " << path[i];
  }
}

// Rule 4: a reversal on an unloading branch before the force reaches zero retraces k_u to the reversal point and
// resumes the branch it left (here the primary curve).
TEST(BridgeLinks, QHystSmallLoopRetracesTheUnloadingSlope) {
  const auto p = model::QHyst::params({1e8, 2e5, 0.05, 0.5});
  model::QHystState st = model::QHyst::initial(p);
  double f = model::QHyst::step(p, st, 0.0, 0.006, 0.0);
  f = model::QHyst::step(p, st, 0.006, 0.004, f);
  EXPECT_NEAR(f, 2.2e5 - 5.773503e7 * 0.002, 1.0);
  f = model::QHyst::step(p, st, 0.004, 0.005, f);  // back up on k_u
  EXPECT_NEAR(f, 2.2e5 - 5.773503e7 * 0.001, 1.0);
  f = model::QHyst::step(p, st, 0.005, 0.007, f);  // past the reversal point: the primary curve
  EXPECT_NEAR(f, 2.25e5, 1e-6);
  // before yield the law is linear both ways (k_u = k0)
  model::QHystState e = model::QHyst::initial(p);
  double g = model::QHyst::step(p, e, 0.0, 0.0015, 0.0);
  g = model::QHyst::step(p, e, 0.0015, -0.001, g);
  EXPECT_NEAR(g, -1e5, 1e-6);
}

// The gap laws give the same bits at T = double and T = simd::V on random states and deformations (Q-Hyst runs
// its scalar update per lane in the stepper: the same code at both).
TEST(BridgeLinks, GapLawsBitEqualAtBothLaneTypes) {
  if (*POUNDING_BITS_NOT_CLAIMED) GTEST_SKIP() << "no identical-bits claim in this build: " << POUNDING_BITS_NOT_CLAIMED;
  using V = simd::V;
  constexpr int W = simd::W;
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int differ = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    for (int hyp = 0; hyp < 2; ++hyp) {
      alignas(64) double k[W], c1[W], c2[W], sd[W], g0[W], d[W], s[W], fd[W], sdn[W];
      for (int j = 0; j < W; ++j) {
        model::GapParams<double> p;
        if (hyp) p = model::HyperbolicGap::params({1e7 * (0.1 + u(g)), 2e7 * (0.6 + u(g)), 0.3 + 0.7 * u(g), 1e5 * (0.1 + u(g)), 0.05 * u(g), u(g) < 0.5 ? -1 : 1});
        else p = model::TensionGap::params({1e7 * (0.1 + u(g)), 1e5 * (0.1 + u(g)), 0.2 * u(g), 0.05 * u(g), u(g) < 0.5 ? -1 : 1});
        k[j] = p.k, c1[j] = p.c1, c2[j] = p.c2, sd[j] = p.side, g0[j] = p.gap0;
        d[j] = 0.3 * (2 * u(g) - 1), s[j] = p.gap0 + 0.02 * u(g);
        sdn[j] = s[j];
        fd[j] = hyp ? GapSpring::force<true>(p, d[j], sdn[j]) : GapSpring::force<false>(p, d[j], sdn[j]);
      }
      auto ld = [](const double* x) { return V(x, simd::stdx::vector_aligned); };
      const model::GapParams<V> pv{ld(k), ld(c1), ld(c2), ld(sd), ld(g0)};
      V sv = ld(s);
      const V fv = hyp ? GapSpring::force<true, V>(pv, ld(d), sv) : GapSpring::force<false, V>(pv, ld(d), sv);
      for (int j = 0; j < W; ++j) {
        const double a = fv[j], b = sv[j];
        if (std::memcmp(&a, &fd[j], 8) != 0 || std::memcmp(&b, &sdn[j], 8) != 0) ++differ;
      }
    }
  }
  EXPECT_EQ(differ, 0);
}

// Traits: linear (zero force) until the slack or gap is taken up, or up to d_y for Q-Hyst; unscaled_equivalent
// exact along a path: F(f d; spec) = f F(d; spec').
TEST(BridgeLinks, Traits) {
  static_assert(model::law_of<model::TensionGap> >= 0 && model::law_of<model::QHyst> >= 0);  // registered
  const model::TensionGap::Spec r{1.2e7, 8.7e5, 0.05, 0.0127, 1};
  EXPECT_TRUE(model::TensionGap::stays_elastic(r, 0.012, 1.0));
  EXPECT_FALSE(model::TensionGap::stays_elastic(r, 0.013, 1.0));
  const model::QHyst::Spec q{1e8, 2e5, 0.05, 0.5};
  EXPECT_TRUE(model::QHyst::stays_elastic(q, 0.0019, 1.0));
  EXPECT_FALSE(model::QHyst::stays_elastic(q, 0.0021, 1.0));
  const double f = 0.37;
  std::vector<double> path;
  for (int i = 0; i <= 800; ++i) path.push_back(0.09 * std::sin(2 * 3.14159265358979 * i / 400) + 0.01 * std::sin(7.0 * i / 400));
  {  // restrainer
    const auto a = model::TensionGap::params(r), b = model::TensionGap::params(*model::TensionGap::unscaled_equivalent(r, f));
    double sa = r.slack, sb = r.slack / f;
    for (double d : path) {
      const double fa = GapSpring::force<false>(a, f * d, sa), fb = GapSpring::force<false>(b, d, sb);
      ASSERT_NEAR(fa, f * fb, 1e-8 * 8.7e5) << d;
    }
  }
  {  // hyperbolic
    const model::HyperbolicGap::Spec h{2.03e7, 2.5e7, 0.7, 3.26e5, 0.0254, 1};
    const auto a = model::HyperbolicGap::params(h), b = model::HyperbolicGap::params(*model::HyperbolicGap::unscaled_equivalent(h, f));
    double sa = h.gap, sb = h.gap / f;
    for (double d : path) {
      const double fa = GapSpring::force<true>(a, f * d, sa), fb = GapSpring::force<true>(b, d, sb);
      ASSERT_NEAR(fa, f * fb, 1e-8 * 3.26e5) << d;
    }
  }
  {  // Q-Hyst
    const auto a = model::QHyst::params(q), b = model::QHyst::params(*model::QHyst::unscaled_equivalent(q, f));
    model::QHystState sa = model::QHyst::initial(a), sb = model::QHyst::initial(b);
    double da = 0, db = 0, fa = 0, fb = 0;
    for (double d : path) {
      fa = model::QHyst::step(a, sa, da, f * d * 0.1, fa), da = f * d * 0.1;
      fb = model::QHyst::step(b, sb, db, d * 0.1, fb), db = d * 0.1;
      ASSERT_NEAR(fa, f * fb, 1e-8 * 2e5) << d;
    }
  }
}
