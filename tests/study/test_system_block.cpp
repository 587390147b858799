// Shear buildings in studies (study/system_block.hpp; docs/architecture.md §2.6.2, §2.6.4): the first-passage
// property of systems -- a 3- against a 5-storey building at six gaps, coupled (Hertzdamp at the three common
// floors) and uncoupled: a lane that does not touch has every observer bit-identical to the uncoupled run, and it
// touches exactly when D = max over levels of the uncoupled peak closing exceeds the gap; and a lane's bits do not
// depend on the other lanes of its batch (topology buckets, batch width).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <cstring>
#include <vector>

#include "pounding/study/system_block.hpp"

#include "../kernel_test_support.hpp"

namespace pounding {
namespace {

// Building b (0, 1) a shear building of `storeys` storeys (0: from the height) with the model's other defaults.
StructureModel shear_model(int storeys1, int storeys2) {
  StructureModel m;
  for (int b = 0; b < 2; ++b) {
    BuildingModel x = m.default_building();
    x.kind = StructureKind::shear;
    x.code.storeys = b == 0 ? storeys1 : storeys2;
    m.buildings[b] = x;
  }
  return m;
}

SampledStructure structure(double T, double h, double m, double zeta, double yield_drift_h) {
  SampledStructure s;
  s.T = T, s.h = h, s.m = m, s.zeta = zeta, s.alpha = 0.05;
  const Structure st = Structure::from_period(m, T, zeta);
  s.k = st.k, s.c = st.c, s.fy = st.k * yield_drift_h;
  return s;
}

// Lane i of a small population: periods, masses and heights that vary, d = 1 m (the gap ratio is the gap in m).
SampledPair pair(int i) {
  SampledPair p;
  p.s1 = structure(0.45 + 0.04 * i, 9.6 + 0.7 * i, 9e5 * (1 + 0.1 * i), 0.05, 0.02 * 9.6 / 6);
  p.s2 = structure(0.75 + 0.05 * i, 16.0 + 1.1 * i, 1.6e6 * (1 + 0.07 * i), 0.04, 0.02 * 16.0 / 6);
  p.d = 1.0;
  p.kh = 2.0e10;
  return p;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every per-DOF, per-spring and per-element observer of lane l equal bit for bit in a and b.
void expect_lane_identical(const model::System& sys, const physics::SystemResult& a, const physics::SystemResult& b,
                           std::size_t l, std::size_t w, const std::string& what) {
  const auto field = [&](const std::vector<double>& x, const std::vector<double>& y, std::size_t n, const char* name) {
    for (std::size_t i = 0; i < n; ++i)
      EXPECT_TRUE(same_bits(x[i * w + l], y[i * w + l])) << what << " " << name << "[" << i << "] " << x[i * w + l]
                                                          << " vs " << y[i * w + l];
  };
  const std::size_t nd = static_cast<std::size_t>(sys.ndof()), ns = sys.springs().size(), ne = sys.contacts().size();
  field(a.peak_u, b.peak_u, nd, "peak_u");
  field(a.peak_acc, b.peak_acc, nd, "peak_acc");
  field(a.final_u, b.final_u, nd, "final_u");
  field(a.final_v, b.final_v, nd, "final_v");
  field(a.peak_drift, b.peak_drift, ns, "peak_drift");
  field(a.peak_spring_force, b.peak_spring_force, ns, "peak_spring_force");
  field(a.peak_closing, b.peak_closing, ne, "peak_closing");
  field(a.t_peak_closing, b.t_peak_closing, ne, "t_peak_closing");
  EXPECT_EQ(a.status[l], b.status[l]) << what;
}

TEST(SystemBlock, FirstPassageThreeAgainstFiveStoreys) {
  const StructureModel model = shear_model(3, 5);
  SystemBlock block(model);
  constexpr std::size_t L = 6;
  std::vector<SampledPair> pairs;
  for (std::size_t i = 0; i < L; ++i) pairs.push_back(pair(static_cast<int>(i)));
  const LaneTopology t = lane_topology(model, pairs[0]);
  ASSERT_EQ(t.storeys[0], 3);
  ASSERT_EQ(t.storeys[1], 5);
  const model::System& sys = block.system(t);
  ASSERT_EQ(sys.contacts().size(), 3u);  // the three common floors
  ASSERT_FALSE(sys.is_sdof_pair());

  const std::vector<double> ag = test::two_tone(0.005, 8.0, 2.0, 1.4, 1.5, 2.9);
  const GroundMotion gm{0.005, ag, 0.0};
  KernelSettings ks;
  ks.substeps = 4;
  const ContactNumbers cn{0.65, 0.0};
  physics::SystemBatch batch;
  batch.resize(sys, L);
  for (std::size_t l = 0; l < L; ++l) block.set_lane(batch, l, pairs[l], t, 0.0, cn);
  ContactModel none = test::contact(ContactLaw::none), hertz = test::contact(ContactLaw::hertzdamp);
  physics::SystemResult free;
  physics::run_system(batch, std::vector<ContactModel>{none}, gm, ks, free);
  std::vector<double> D(L, -INFINITY);
  for (std::size_t l = 0; l < L; ++l) {
    ASSERT_EQ(free.status[l], 0);
    for (std::size_t e = 0; e < 3; ++e) D[l] = std::max(D[l], free.peak_closing[e * L + l]);
  }
  // the block's own uncoupled run gives the same D, u1, u2
  RunPeaks peaks;
  block.uncoupled(pairs, none, gm, ks, peaks);
  for (std::size_t l = 0; l < L; ++l) {
    EXPECT_TRUE(same_bits(peaks.closing[l], D[l])) << l;
    double u2 = 0;
    for (int d : sys.bodies()[1].dofs) u2 = std::max(u2, free.peak_u[static_cast<std::size_t>(d) * L + l]);
    EXPECT_TRUE(same_bits(peaks.u2[l], u2)) << l;
  }
  // six gaps around the lanes' D: some lanes touch at each middle gap, none at the largest
  const std::vector<double> sorted = [&] { auto x = D; std::sort(x.begin(), x.end()); return x; }();
  const std::vector<double> gaps{0.0, 0.5 * sorted[0], 0.5 * (sorted[1] + sorted[2]), 0.5 * (sorted[3] + sorted[4]),
                                 sorted[5] * (1 - 1e-12), 1.5 * sorted[5]};
  int touched = 0, free_lanes = 0;
  for (double g : gaps) {
    physics::SystemBatch cb = batch;
    for (std::size_t l = 0; l < L; ++l) block.set_lane(cb, l, pairs[l], t, g, cn);
    physics::SystemResult r;
    physics::run_system(cb, std::vector<ContactModel>{hertz}, gm, ks, r);
    for (std::size_t l = 0; l < L; ++l) {
      int impacts = 0;
      for (std::size_t e = 0; e < 3; ++e) impacts += r.impact_count[e * L + l];
      const bool touches = impacts > 0;
      EXPECT_EQ(touches, D[l] > g) << "gap " << g << " lane " << l << " D " << D[l];
      if (touches) {
        ++touched;
        continue;
      }
      ++free_lanes;
      expect_lane_identical(sys, free, r, l, L, "gap " + std::to_string(g) + " lane " + std::to_string(l));
    }
  }
  EXPECT_GE(touched, 10);
  EXPECT_GE(free_lanes, 10);
}

// Unequal storey heights (3.2 m and 3.5 m, 3 storeys each): the floors meet the neighbour's columns (model::
// shear_buildings, docs/floor-contact.md) -- five floor-to-column elements, one with the ground end of a column --
// and the probability scene stays exact: at every gap a lane pounds (coupled, Hertzdamp) exactly when D = max over
// the elements of the uncoupled peak closing exceeds it. Refused before (the storey heights had to be equal).
TEST(SystemBlock, FloorsAgainstColumnsFirstPassage) {
  StructureModel model = shear_model(3, 3);
  model.buildings[1].code.storey_height = 3.5;
  SystemBlock block(model);
  constexpr std::size_t L = 6;
  std::vector<SampledPair> pairs;
  for (std::size_t i = 0; i < L; ++i) pairs.push_back(pair(static_cast<int>(i)));
  const LaneTopology t = lane_topology(model, pairs[0]);
  const model::System& sys = block.system(t);
  std::vector<std::string> labels;
  for (const auto& c : sys.contacts()) labels.push_back(c.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"level 1/column 0-1", "column 1-2/level 1", "level 2/column 1-2",
                                              "column 2-3/level 2", "level 3/column 2-3"}));
  const std::vector<double> ag = test::two_tone(0.005, 6.0, 2.0, 1.4, 1.5, 2.9);
  const GroundMotion gm{0.005, ag, 0.0};
  KernelSettings ks;
  ks.substeps = 4;
  const ContactModel none = test::contact(ContactLaw::none), hertz = test::contact(ContactLaw::hertzdamp);
  RunPeaks free;
  block.uncoupled(pairs, none, gm, ks, free);
  std::vector<double> D(free.closing);
  std::sort(D.begin(), D.end());
  int touched = 0, apart = 0;
  std::vector<std::size_t> lanes(L);
  for (std::size_t l = 0; l < L; ++l) lanes[l] = l;
  for (double g : {0.5 * D[0], 0.5 * (D[1] + D[2]), 0.5 * (D[3] + D[4]), 1.5 * D[5]}) {
    RunPeaks r;
    block.coupled(pairs, lanes, g, hertz, ContactNumbers{0.65, 0.0}, gm, ks, r);
    for (std::size_t l = 0; l < L; ++l) {
      ASSERT_EQ(r.status[l], 0) << l;
      EXPECT_EQ(r.impact_count[l] > 0, free.closing[l] > g) << "gap " << g << " lane " << l;
      (r.impact_count[l] > 0 ? touched : apart) += 1;
      if (r.impact_count[l] == 0) {
        EXPECT_TRUE(same_bits(r.u1[l], free.u1[l]) && same_bits(r.u2[l], free.u2[l])) << l;
      }
    }
  }
  EXPECT_GE(touched, 6);
  EXPECT_GE(apart, 6);
}

// Mixed topologies (storeys from the sampled height): the block's buckets give each lane the numbers it gets
// alone, in any order.
TEST(SystemBlock, LaneBitsDoNotDependOnBucketsOrWidth) {
  const StructureModel model = shear_model(0, 0);  // storeys = round(h / 3.2)
  std::vector<SampledPair> pairs;
  for (int i = 0; i < 7; ++i) pairs.push_back(pair(i));
  std::vector<LaneTopology> tops;
  for (const auto& p : pairs) tops.push_back(lane_topology(model, p));
  ASSERT_NE(tops.front(), tops.back());  // more than one bucket
  const std::vector<double> ag = test::two_tone(0.005, 6.0, 2.5, 1.3, 1.5, 2.9);
  const GroundMotion gm{0.005, ag, 0.0};
  KernelSettings ks;
  ks.substeps = 4;
  const ContactModel none = test::contact(ContactLaw::none), hertz = test::contact(ContactLaw::hertzdamp);
  SystemBlock block(model);
  RunPeaks all, one, coupled_all, coupled_one;
  block.uncoupled(pairs, none, gm, ks, all);
  std::vector<std::size_t> lanes{6, 0, 3, 5};
  block.coupled(pairs, lanes, 0.01, hertz, ContactNumbers{0.65, 0.0}, gm, ks, coupled_all);
  int impacts = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    SystemBlock alone(model);
    alone.uncoupled(std::span<const SampledPair>(&pairs[i], 1), none, gm, ks, one);
    EXPECT_TRUE(same_bits(one.closing[0], all.closing[i]) && same_bits(one.u1[0], all.u1[i]) &&
                same_bits(one.u2[0], all.u2[i]))
        << i;
  }
  for (std::size_t j = 0; j < lanes.size(); ++j) {
    const std::size_t lane0 = 0;
    SystemBlock alone(model);
    alone.coupled(std::span<const SampledPair>(&pairs[lanes[j]], 1), std::span<const std::size_t>(&lane0, 1), 0.01,
                  hertz, ContactNumbers{0.65, 0.0}, gm, ks, coupled_one);
    EXPECT_EQ(coupled_one.impact_count[0], coupled_all.impact_count[j]) << j;
    EXPECT_TRUE(same_bits(coupled_one.peak_force[0], coupled_all.peak_force[j])) << j;
    EXPECT_TRUE(same_bits(coupled_one.u1[0], coupled_all.u1[j])) << j;
    impacts += coupled_all.impact_count[j];
  }
  EXPECT_GT(impacts, 0);
}

// One storey each, no floor_mass / storey_stiffness: the SDOF pair's numbers (the study then runs the pair kernel).
TEST(SystemBlock, OneStoreyIsTheSdof) {
  const StructureModel model = shear_model(1, 1);
  const SampledPair p = pair(2);
  SystemBlock block(model);
  const LaneTopology t = lane_topology(model, p);
  const model::System& sys = block.system(t);
  ASSERT_TRUE(sys.is_sdof_pair());
  physics::SystemBatch b;
  b.resize(sys, 1);
  block.set_lane(b, 0, p, t, 0.3, ContactNumbers{0.65, 0.0});
  const PairBatch pb = physics::to_pair_batch(b);
  const PairParams want = p.pair_params(0.3, 0.65), got = pb.get(0);
  EXPECT_TRUE(same_bits(got.s1.m, want.s1.m) && same_bits(got.s1.k, want.s1.k) && same_bits(got.s1.c, want.s1.c) &&
              same_bits(got.s1.fy, want.s1.fy));
  EXPECT_TRUE(same_bits(got.s2.m, want.s2.m) && same_bits(got.s2.k, want.s2.k) && same_bits(got.s2.c, want.s2.c) &&
              same_bits(got.s2.fy, want.s2.fy));
  EXPECT_TRUE(same_bits(got.gap, want.gap) && same_bits(got.kc, want.kc) && same_bits(got.e, want.e));
}

// The fragility studies' shortcut is the model trait SystemBlock::scales_linearly (each spring's registered
// stays_elastic at its scaled peak deformation): where it answers true the run on the scaled record gives the
// anchor's peaks times the ratio (to rounding); a yielding storey far beyond yield, a friction-pendulum bearing (no
// elastic range), a moat wall, gap offsets and a block run without keep_springs answer false.
TEST(SystemBlock, ScalesLinearlyIsTheModelTrait) {
  const std::vector<double> ag = test::two_tone(0.005, 6.0, 2.5, 1.3, 1.5, 2.9);
  KernelSettings ks;
  ks.substeps = 4;
  const ContactModel none = test::contact(ContactLaw::none);
  std::vector<SampledPair> pairs;
  for (int i = 0; i < 5; ++i) pairs.push_back(pair(i));
  const auto check = [&](const StructureModel& model, double ratio, bool want_any_true, const char* what,
                         double amplitude = 1.0) {
    SystemBlock block(model);
    block.keep_springs(true);
    RunPeaks a, b;
    std::vector<double> base(ag), scaled(ag);
    for (double& x : base) x *= amplitude;
    for (double& x : scaled) x = ratio * (amplitude * x);
    block.uncoupled(pairs, none, GroundMotion{0.005, base, 0.0}, ks, a);
    block.uncoupled(pairs, none, GroundMotion{0.005, scaled, 0.0}, ks, b);
    int yes = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (!block.scales_linearly(a, i, ratio, 10.0)) continue;
      ++yes;
      EXPECT_NEAR(b.closing[i], ratio * a.closing[i], 1e-12 * std::abs(b.closing[i])) << what << " lane " << i;
      EXPECT_NEAR(b.u1[i], ratio * a.u1[i], 1e-12 * b.u1[i]) << what << " lane " << i;
      EXPECT_NEAR(b.u2[i], ratio * a.u2[i], 1e-12 * b.u2[i]) << what << " lane " << i;
    }
    EXPECT_EQ(yes > 0, want_any_true) << what << ": " << yes << " lanes scale";
    SystemBlock plain(model);  // without keep_springs: nothing is known, nothing scales
    plain.uncoupled(pairs, none, GroundMotion{0.005, ag, 0.0}, ks, a);
    EXPECT_FALSE(plain.scales_linearly(a, 0, ratio, 10.0)) << what;
    block.uncoupled(pairs, none, GroundMotion{0.005, base, 0.0}, ks, a);
    EXPECT_FALSE(block.scales_linearly(a, 0, 0.99, 10.0)) << what << ": a ratio below 1 (the anchor is the lowest run)";
  };
  StructureModel elastic = shear_model(3, 5);
  for (BuildingModel& b : elastic.buildings) b.hysteresis = Hysteresis::elastic;
  check(elastic, 2.7, true, "linear storeys");
  check(shear_model(3, 5), 1.2, true, "bilinear storeys below yield", 0.02);
  check(shear_model(3, 5), 1.2, false, "bilinear storeys beyond yield", 0.5);
  check(shear_model(3, 5), 60.0, false, "bilinear storeys, far beyond yield");
  StructureModel fp = elastic;
  fp.buildings[0].isolated = true;
  fp.buildings[0].isolation.bearing = physics::Bearing::friction_pendulum;
  fp.buildings[0].isolation.radius = 2.0, fp.buildings[0].isolation.mu_slow = 0.05;
  fp.buildings[0].isolation.mu_fast = 0.05;
  check(fp, 1.5, false, "friction-pendulum bearing");
  StructureModel lin = elastic;
  lin.buildings[0].isolated = true;
  lin.buildings[0].isolation.bearing = physics::Bearing::linear;
  lin.buildings[0].isolation.k_eff = 2e6, lin.buildings[0].isolation.zeta_eff = 0.1;
  check(lin, 1.5, true, "linear bearing");
  StructureModel moat = lin;
  moat.buildings[0].moat = true, moat.buildings[0].moat_gap = 5.0;
  check(moat, 1.5, false, "a moat wall");
  SystemBlock offsets(elastic, test::contact(ContactLaw::hertzdamp), 0.65, model::ContactLevels::common, {0.01});
  offsets.keep_springs(true);
  RunPeaks a;
  offsets.uncoupled(pairs, none, GroundMotion{0.005, ag, 0.0}, ks, a);
  EXPECT_FALSE(offsets.scales_linearly(a, 0, 1.5, 10.0)) << "gap offsets";
}

}  // namespace
}  // namespace pounding
