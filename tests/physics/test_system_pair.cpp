// The SDOF pair as a system (docs/architecture.md §2.2.2, issue 25 step 2): lane l of a PairBatch is lane l of
// System::sdof_pair() in a SystemBatch, and back, bit for bit; a BatchResult goes through a SystemResult and
// back unchanged; SystemBatch / SystemResult sizing and fill values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "kernel_test_support.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding::physics {
namespace {

constexpr std::size_t lanes = 37;
constexpr double inf = std::numeric_limits<double>::infinity();

// Bit equality of two arrays (NaN payloads and signed zeros included).
template <class T> ::testing::AssertionResult same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << "sizes " << a.size() << " vs " << b.size();
  if (!a.empty() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) != 0)
    return ::testing::AssertionFailure() << "bits differ";
  return ::testing::AssertionSuccess();
}

// Every field random and distinct (a swapped field shows), with the special values a real batch holds.
PairBatch random_pairs(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  PairBatch b;
  b.resize(lanes);
  for (auto* v : {&b.m1, &b.k1, &b.c1, &b.fy1, &b.alpha1, &b.m2, &b.k2, &b.c2, &b.fy2, &b.alpha2, &b.gap, &b.kc, &b.e,
                  &b.u1_0, &b.v1_0, &b.u2_0, &b.v2_0})
    for (double& x : *v) x = u(rng);
  b.fy1[3] = inf, b.fy2[5] = inf, b.gap[7] = -0.0, b.kc[11] = std::numeric_limits<double>::quiet_NaN();
  b.m1[36] = std::numeric_limits<double>::denorm_min();
  return b;
}

TEST(SystemPair, PairBatchRoundTripIsBitIdentical) {
  const model::System pair = model::System::sdof_pair();
  const PairBatch b = random_pairs(25);
  const SystemBatch s = to_system(b, pair);
  EXPECT_EQ(s.system, &pair);
  EXPECT_EQ(s.width, lanes);
  const PairBatch back = to_pair_batch(s);
  EXPECT_TRUE(same_bits(back.m1, b.m1) && same_bits(back.k1, b.k1) && same_bits(back.c1, b.c1));
  EXPECT_TRUE(same_bits(back.fy1, b.fy1) && same_bits(back.alpha1, b.alpha1));
  EXPECT_TRUE(same_bits(back.m2, b.m2) && same_bits(back.k2, b.k2) && same_bits(back.c2, b.c2));
  EXPECT_TRUE(same_bits(back.fy2, b.fy2) && same_bits(back.alpha2, b.alpha2));
  EXPECT_TRUE(same_bits(back.gap, b.gap) && same_bits(back.kc, b.kc) && same_bits(back.e, b.e));
  EXPECT_TRUE(same_bits(back.u1_0, b.u1_0) && same_bits(back.v1_0, b.v1_0));
  EXPECT_TRUE(same_bits(back.u2_0, b.u2_0) && same_bits(back.v2_0, b.v2_0));
}

TEST(SystemPair, LaneOfThePairIsLaneOfTheSystem) {
  const model::System pair = model::System::sdof_pair();
  const PairBatch b = random_pairs(26);
  const SystemBatch s = to_system(b, pair);
  ASSERT_EQ(s.m.size(), 2 * lanes);
  EXPECT_TRUE(s.c_storey.empty());  // the pair has no storey dashpots
  for (std::size_t l = 0; l < lanes; ++l) {
    const PairParams p = b.get(l);
    EXPECT_EQ(s.m[SystemBatch::at(0, l, lanes)], p.s1.m);
    EXPECT_EQ(s.m[SystemBatch::at(1, l, lanes)], p.s2.m);
    EXPECT_EQ(s.c_floor[SystemBatch::at(0, l, lanes)], p.s1.c);
    EXPECT_EQ(s.c_floor[SystemBatch::at(1, l, lanes)], p.s2.c);
    const SpringSpec& s1 = s.spring[SystemBatch::at(0, l, lanes)];
    const SpringSpec& s2 = s.spring[SystemBatch::at(1, l, lanes)];
    EXPECT_EQ(s1.k, p.s1.k);
    EXPECT_EQ(s1.fy, p.s1.fy);
    EXPECT_EQ(s1.alpha, p.s1.alpha);
    EXPECT_EQ(s2.k, p.s2.k);
    EXPECT_EQ(s2.fy, p.s2.fy);
    EXPECT_EQ(s2.alpha, p.s2.alpha);
    EXPECT_EQ(s.gap[l], p.gap);
    EXPECT_EQ(s.e[l], p.e);
    EXPECT_EQ(s.weight[l], 0.0);
    EXPECT_EQ(s.u0[SystemBatch::at(1, l, lanes)], p.u2);
    EXPECT_EQ(s.v0[SystemBatch::at(0, l, lanes)], p.v1);
  }
}

TEST(SystemPair, AdaptersRefuseOtherSystems) {
  model::System::Parts p = model::System::sdof_pair().parts();
  p.bodies[0].storey_dashpots = true;
  const model::System other = model::System::build(p);
  PairBatch b;
  b.resize(2);
  EXPECT_THROW(to_system(b, other), std::logic_error);
  SystemBatch s;
  s.resize(other, 2);
  EXPECT_THROW(to_pair_batch(s), std::logic_error);
}

// A real pair run's result (NaN first-impact times, counts, statuses, energies) through the system's result.
TEST(SystemPair, BatchResultRoundTripIsIdentical) {
  PairBatch b;
  b.resize(lanes);
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t l = 0; l < lanes; ++l) {
    PairParams p;
    p.s1 = Structure::from_period(1e5 * (1 + u(rng)), 0.3 + u(rng), 0.05, l % 3 == 0 ? 2e5 : inf, 0.1);
    p.s2 = Structure::from_period(2e5 * (1 + u(rng)), 0.5 + u(rng), 0.05);
    p.gap = l % 4 == 0 ? 1.0 : 0.02 * u(rng);  // every 4th lane never touches
    p.kc = 1e9;
    p.e = 0.65;
    b.set(l, p);
  }
  const std::vector<double> ag = test::two_tone(0.01, 6.0, 4.0, 1.1, 3.0, 2.7);
  GroundMotion gm{0.01, ag, 6.0};
  KernelSettings ks;
  ks.energy = true;
  ks.substeps = 4;
  BatchResult r;
  run_batch(b, test::contact(ContactLaw::hertzdamp), gm, ks, r);
  std::size_t touched = 0, untouched = 0;
  for (std::size_t l = 0; l < lanes; ++l) (r.impact_count[l] > 0 ? touched : untouched)++;
  ASSERT_GT(touched, 0u);
  ASSERT_GT(untouched, 0u);  // NaN first-impact times among them

  const SystemResult s = from_pair_result(r);
  EXPECT_EQ(s.width, lanes);
  EXPECT_TRUE(same_bits(std::vector<double>(s.peak_drift.begin(), s.peak_drift.begin() + lanes), r.peak_u1));
  EXPECT_TRUE(same_bits(std::vector<double>(s.peak_drift.begin() + lanes, s.peak_drift.end()), r.peak_u2));
  for (double f : s.peak_spring_force) EXPECT_TRUE(std::isnan(f));
  const BatchResult back = to_pair_result(s);
  EXPECT_TRUE(same_bits(back.peak_u1, r.peak_u1) && same_bits(back.peak_u2, r.peak_u2));
  EXPECT_TRUE(same_bits(back.peak_closing, r.peak_closing) && same_bits(back.t_peak_closing, r.t_peak_closing));
  EXPECT_TRUE(same_bits(back.t_first_impact, r.t_first_impact) && same_bits(back.impact_count, r.impact_count));
  EXPECT_TRUE(same_bits(back.peak_force, r.peak_force) && same_bits(back.peak_penetration, r.peak_penetration));
  EXPECT_TRUE(same_bits(back.contact_energy, r.contact_energy) && same_bits(back.contact_time, r.contact_time));
  EXPECT_TRUE(same_bits(back.peak_acc1, r.peak_acc1) && same_bits(back.peak_acc2, r.peak_acc2));
  EXPECT_TRUE(same_bits(back.clamp_count, r.clamp_count) && same_bits(back.status, r.status));
  EXPECT_TRUE(same_bits(back.h_omega_contact, r.h_omega_contact));
  EXPECT_TRUE(same_bits(back.final_u1, r.final_u1) && same_bits(back.final_v1, r.final_v1));
  EXPECT_TRUE(same_bits(back.final_u2, r.final_u2) && same_bits(back.final_v2, r.final_v2));
  EXPECT_TRUE(same_bits(back.e_input, r.e_input) && same_bits(back.e_kinetic, r.e_kinetic));
  EXPECT_TRUE(same_bits(back.e_strain, r.e_strain) && same_bits(back.e_viscous, r.e_viscous));
  EXPECT_TRUE(same_bits(back.e_hysteretic, r.e_hysteretic) && same_bits(back.e_contact_stored, r.e_contact_stored));
}

TEST(SystemPair, ResizeFillsWhatIsNotComputedWithNaN) {
  model::System::Parts p = model::System::sdof_pair().parts();
  p.bodies[1].storey_dashpots = true;
  const model::System sys = model::System::build(p);
  SystemBatch b;
  b.resize(sys, 3);
  EXPECT_EQ(b.c_storey.size(), 6u);  // [spring][lane] once a body has storey dashpots
  EXPECT_EQ(b.spring[4].fy, inf);
  EXPECT_EQ(b.e[2], 1.0);
  SystemResult r;
  r.resize(sys, 3);
  EXPECT_EQ(r.peak_u.size(), 6u);
  EXPECT_EQ(r.peak_drift.size(), 6u);
  EXPECT_EQ(r.peak_force.size(), 3u);
  EXPECT_EQ(r.status.size(), 3u);
  EXPECT_EQ(r.peak_u[5], 0.0);
  EXPECT_TRUE(std::isnan(r.t_first_impact[1]));
  EXPECT_TRUE(std::isnan(r.e_input[0]) && std::isnan(r.e_contact_stored[2]));
}

}  // namespace
}  // namespace pounding::physics
