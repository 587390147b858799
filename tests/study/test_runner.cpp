// The two runners (study/runner.hpp) on one block of SDOF pairs: every RunPeaks field of uncoupled, rerun_uncoupled
// and coupled bit for bit (run_system hands an SDOF pair System to the pair kernel), at_factors to 1e-10 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "pounding/sampling/sampler.hpp"
#include "pounding/study/runner.hpp"

#include "../kernel_test_support.hpp"

namespace pounding {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The study: SDOF pairs (the pair runner's kind), yielding, Hertzdamp at three gap ratios, the impacts scene.
Study study() {
  return parse_study("seed = 7\nscene = \"impacts\"\n[records]\nsuite = \"builtin\"\n[structures]\nsamples_per_pair = 2\n"
                     "[gaps]\nratios = [0.05, 0.2, 0.5]\n[contact]\nlaw = \"hertzdamp\"\ne = 0.65\n",
                     "runner.toml");
}

// Every RunPeaks field the two runners fill of `a` and `b`, lane by lane, bit for bit.
void expect_same(const RunPeaks& a, const RunPeaks& b, const std::string& what) {
  ASSERT_EQ(a.status.size(), b.status.size()) << what;
  ASSERT_EQ(a.buildings, b.buildings) << what;
  ASSERT_EQ(a.u.size(), b.u.size()) << what;
  const auto each = [&](const std::vector<double>& x, const std::vector<double>& y, const char* name) {
    ASSERT_EQ(x.size(), y.size()) << what << " " << name;
    for (std::size_t i = 0; i < x.size(); ++i)
      EXPECT_TRUE(same_bits(x[i], y[i])) << what << " " << name << "[" << i << "] " << x[i] << " vs " << y[i];
  };
  EXPECT_EQ(a.status, b.status) << what;
  each(a.u1, b.u1, "u1"), each(a.u2, b.u2, "u2"), each(a.closing, b.closing, "closing"), each(a.u, b.u, "u");
  each(a.peak_force, b.peak_force, "peak_force"), each(a.t_first_impact, b.t_first_impact, "t_first_impact");
  each(a.h_omega_contact, b.h_omega_contact, "h_omega_contact");
  EXPECT_EQ(a.impact_count, b.impact_count) << what;
  EXPECT_EQ(a.restitution_outside, b.restitution_outside) << what;
  EXPECT_EQ(a.substeps, b.substeps) << what;
}

TEST(Runner, PairAndSystemRunnersAgreeOnSdofPairs) {
  const Study s = study();
  WorkPlan plan;
  plan.impacts = true, plan.ida = true, plan.gaps = s.gap_ratios.size();  // ida: the system keeps its springs
  const StructureSampler sampler(s.structures, s.seed);
  std::vector<SampledPair> block(12);
  sampler.sample_block(3, 7, 0, block);
  const auto pair = make_pair_runner(s, plan), system = make_system_runner(s, plan);
  pair->load(block), system->load(block);
  EXPECT_TRUE(pair->layout().empty());
  EXPECT_TRUE(system->layout().empty());

  Record rec;
  rec.dt = 0.01, rec.acc = test::two_tone(0.01, 12.0, 3.5, 1.3, 2.5, 2.9);
  const UnitMotion m{GroundMotion{rec.dt, rec.acc, rec.duration() + 2.0}, {}};
  KernelSettings ks;
  ks.substeps = 8;
  RunPeaks a, b;
  pair->uncoupled(m, ks, a), system->uncoupled(m, ks, b);
  expect_same(a, b, "uncoupled");
  std::size_t touched = 0, ok = 0;
  for (std::size_t i = 0; i < block.size(); ++i) ok += a.status[i] == 0, touched += a.closing[i] > s.gap_at(0, block[i]);
  ASSERT_EQ(ok, block.size());
  ASSERT_GT(touched, 2u);  // the coupled runs below have impacts

  const std::vector<std::size_t> some{1, 4, 5, 10};
  RunPeaks ra, rb;
  pair->rerun_uncoupled(some, m, ks, ra), system->rerun_uncoupled(some, m, ks, rb);
  expect_same(ra, rb, "rerun_uncoupled");
  for (std::size_t j = 0; j < some.size(); ++j) EXPECT_TRUE(same_bits(ra.closing[j], a.closing[some[j]])) << j;

  for (std::size_t g = 0; g < s.gap_ratios.size(); ++g) {
    std::vector<std::size_t> lanes;
    for (std::size_t i = 0; i < block.size(); ++i)
      if (a.closing[i] > s.gap_at(g, block[i])) lanes.push_back(i);
    RunPeaks ca, cb;
    pair->coupled(lanes, s.gap_ratios[g], m, ks, ca), system->coupled(lanes, s.gap_ratios[g], m, ks, cb);
    expect_same(ca, cb, "coupled at gap " + std::to_string(g));
    if (g == 0) {
      ASSERT_FALSE(lanes.empty());
      EXPECT_GT(ca.impact_count[0], 0);
    }
  }

  for (std::size_t i = 0; i < block.size(); ++i)
    for (double ratio : {1.0, 1.5, 4.0, 40.0})
      EXPECT_EQ(pair->scales_linearly(a, i, ratio, ks.displacement_limit),
                system->scales_linearly(b, i, ratio, ks.displacement_limit)) << i << " " << ratio;

  // the IDA's bisection step: the pair runs each spring's unscaled equivalent on the record, the System the scaled
  // record; entries 2 and 3 share one lane and factor (the System runs it once)
  const std::vector<LaneFactor> entries{{0, 0.7}, {3, 1.9}, {3, 1.9}, {6, 2.6}, {11, 4.1}};
  FactorPeaks fa, fb;
  pair->at_factors(entries, rec, 2.0, ks, fa), system->at_factors(entries, rec, 2.0, ks, fb);
  ASSERT_EQ(fa.closing.size(), entries.size());
  ASSERT_EQ(fb.closing.size(), entries.size());
  for (std::size_t j = 0; j < entries.size(); ++j) {
    EXPECT_EQ(fa.excluded[j], 0) << j;
    EXPECT_EQ(fb.excluded[j], 0) << j;
    EXPECT_NEAR(fa.closing[j], fb.closing[j], 1e-10 * std::abs(fb.closing[j])) << j;
    EXPECT_EQ(fa.ran[j], 1) << j;
    EXPECT_EQ(fb.ran[j], j == 2 ? 0 : 1) << j;
  }
}

}  // namespace
}  // namespace pounding
