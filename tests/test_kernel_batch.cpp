// Batch-level properties of the kernel: explicit-stepper instability is reported (not returned as numbers),
// first passage (contact and no-contact runs bit-identical up to the first impact), batch-width
// independence (width 1 and 256 give bit-identical lanes), and bad lane parameters rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "kernel_test_support.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"

namespace pounding {
namespace {

using test::all_steppers;
using test::run_one;

constexpr auto all_laws = contact::law_ids;

// Every double observer of lane i, in a fixed order.
std::vector<const std::vector<double>*> double_observers(const BatchResult& r) {
  return {&r.peak_u1,  &r.peak_u2,  &r.peak_closing, &r.t_peak_closing, &r.t_first_impact, &r.peak_force,
          &r.peak_penetration, &r.contact_energy, &r.contact_time, &r.peak_acc1, &r.peak_acc2, &r.final_u1,
          &r.final_v1, &r.final_u2, &r.final_v2, &r.e_input, &r.e_kinetic, &r.e_strain, &r.e_viscous,
          &r.e_hysteretic, &r.e_contact_stored};
}
const char* observer_names[] = {"peak_u1", "peak_u2", "peak_closing", "t_peak_closing", "t_first_impact",
                                "peak_force", "peak_penetration", "contact_energy", "contact_time", "peak_acc1",
                                "peak_acc2", "final_u1", "final_v1", "final_u2", "final_v2", "e_input",
                                "e_kinetic", "e_strain", "e_viscous", "e_hysteretic", "e_contact_stored"};

// --------------------------------------------------------------------------------------------------
// 8. Stability. Two 1 s frames meeting at 1 m/s relative speed through a linear contact spring; central
// difference is stable in contact only for h sqrt(kc / meff) < 2.
BatchResult stiff_contact_run(double omega_h, int substeps) {
  PairParams p;
  p.s1 = Structure::from_period(1.0e5, 1.0, 0.05);
  p.s2 = Structure::from_period(1.0e5, 1.0, 0.05);
  p.gap = 0.0;
  p.v1 = 0.5, p.v2 = -0.5;
  const double meff = 0.5e5, h = 0.01;  // h of one record step
  p.kc = (omega_h / h) * (omega_h / h) * meff;
  const std::vector<double> ag = {0.0, 0.0};
  return run_one(p, test::contact(ContactLaw::linear), ag, h, 5.0, Stepper::central_difference, substeps, true);
}

void expect_reported_not_returned(const BatchResult& r, const std::string& what) {
  EXPECT_NE(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok)) << what;
  const auto obs = double_observers(r);
  for (std::size_t q = 0; q < obs.size(); ++q) EXPECT_TRUE(std::isnan((*obs[q])[0])) << what << " " << observer_names[q];
  EXPECT_EQ(r.impact_count[0], -1) << what;
  EXPECT_EQ(r.clamp_count[0], -1) << what;
}

TEST(Stability, ExplicitStepperPastContactLimitIsReportedDiverged) {
  for (double wh : {2.5, 3.0, 5.0, 10.0, 100.0}) {
    const BatchResult r = stiff_contact_run(wh, 1);
    std::printf("w_c h = %5.1f: status %s\n", wh, std::string(to_string(static_cast<LaneStatus>(r.status[0]))).c_str());
    expect_reported_not_returned(r, "w_c h = " + std::to_string(wh));
    // the same problem with enough substeps (w_c h / s = 0.25) is a normal result
    const int s = static_cast<int>(std::ceil(wh / 0.25));
    const BatchResult ok = stiff_contact_run(wh, s);
    EXPECT_EQ(ok.status[0], static_cast<std::uint8_t>(LaneStatus::ok)) << wh;
    for (const auto* o : double_observers(ok)) {
      if (o == &ok.t_first_impact) continue;
      EXPECT_TRUE(std::isfinite((*o)[0]));
    }
    // 1 m/s into a 1 s frame: the displacements stay below v / omega = 0.08 m
    EXPECT_LT(ok.peak_u1[0], 0.1);
    EXPECT_GE(ok.impact_count[0], 1);
  }
}

// Just past the limit (w_c h = 2.1) the contact phase amplifies energy at every impact. Physically the
// frames cannot move more than ~0.08 m (1 m/s closing, T = 1 s, e = 1 at most); a run that reports metres
// of displacement from 25 kJ of initial kinetic energy has diverged, whether or not it reached the 10 m
// displacement limit.
TEST(Stability, MarginallyUnstableContactIsNotReturnedAsNumbers) {
  const BatchResult r = stiff_contact_run(2.1, 1);
  std::printf("w_c h = 2.1: status %s, peak_u1 %.3g m, energy now %.3g J (initial kinetic 2.5e4 J, no input)\n",
              std::string(to_string(static_cast<LaneStatus>(r.status[0]))).c_str(), r.peak_u1[0],
              r.e_kinetic[0] + r.e_strain[0] + r.e_contact_stored[0]);
  if (r.status[0] == static_cast<std::uint8_t>(LaneStatus::ok)) {
    // returned as numbers: then they must at least be physically possible
    EXPECT_LT(r.peak_u1[0], 0.1) << "unstable contact phase returned as a result (kernel issue)";
  } else {
    expect_reported_not_returned(r, "w_c h = 2.1");
  }
}

// --------------------------------------------------------------------------------------------------
// Random pairs for the batch tests: frames of 0.3-2 s, half of them bilinear, on a strong two-tone record.
std::vector<PairParams> random_pairs(std::size_t n, unsigned seed, double gap_lo, double gap_hi) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<PairParams> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    PairParams& p = v[i];
    p.s1 = Structure::from_period(1e5 * (1 + 4 * U(rng)), 0.3 + 1.2 * U(rng), 0.02 + 0.05 * U(rng));
    p.s2 = Structure::from_period(1e5 * (1 + 4 * U(rng)), 0.5 + 1.5 * U(rng), 0.02 + 0.05 * U(rng));
    if (U(rng) < 0.5) {
      p.s1.fy = p.s1.k * (0.01 + 0.03 * U(rng)), p.s1.alpha = 0.1 * U(rng);
      p.s2.fy = p.s2.k * (0.01 + 0.03 * U(rng)), p.s2.alpha = 0.1 * U(rng);
    }
    p.gap = gap_lo + (gap_hi - gap_lo) * U(rng);
    p.kc = 1e9 * (0.5 + U(rng));
    p.e = 0.4 + 0.6 * U(rng);
    if (i % 7 == 3) p.u1 = 0.01 * U(rng), p.v2 = -0.1 * U(rng);  // some lanes start moving
  }
  return v;
}

PairBatch to_batch(const std::vector<PairParams>& v) {
  PairBatch b;
  b.resize(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) b.set(i, v[i]);
  return b;
}

// --------------------------------------------------------------------------------------------------
// 9. First passage. Up to the first impact the contact law has done nothing, so the run must be the
// uncoupled run bit for bit; hence "at least one impact at gap g" == "uncoupled peak closing > g" (contact is
// delta = u1 - u2 - g > 0, strictly). Gaps are set per lane at and around the uncoupled peak closing P,
// down to the last bit (P itself, and the doubles either side of it), plus fixed gaps.
TEST(FirstPassage, ContactRunEqualsUncoupledRunUntilFirstImpact) {
  const double dt = 0.01;
  const std::vector<double> ag = test::two_tone(dt, 6.0, 1.5, 0.9, 1.2, 1.9);
  std::vector<PairParams> base = random_pairs(64, 11, 0.0, 0.0);
  for (auto& p : base) p.u1 = p.v2 = 0.0;
  GroundMotion gm{dt, ag, 0.0};
  for (Stepper st : all_steppers) {
    KernelSettings ks;
    ks.stepper = st;
    ks.substeps = 2;
    BatchResult free;
    {
      std::vector<PairParams> v = base;
      for (auto& p : v) p.gap = 1e3;
      run_batch(to_batch(v), test::contact(ContactLaw::none), gm, ks, free);
    }
    for (ContactLaw law : {ContactLaw::hertzdamp, ContactLaw::kelvin, ContactLaw::stereomechanical}) {
      const ContactModel cm = test::contact(law);
      int mismatches = 0, impacting = 0, total = 0;
      for (int g = 0; g < 8; ++g) {
        std::vector<PairParams> v = base;
        for (std::size_t i = 0; i < v.size(); ++i) {
          const double P = free.peak_closing[i];
          const double gaps[8] = {0.5 * P, P * (1 - 1e-9), std::nextafter(P, 0.0), P, std::nextafter(P, 1.0),
                                  1.5 * P, 0.02, 0.05};
          v[i].gap = std::max(gaps[g], 0.0);
        }
        BatchResult r;
        run_batch(to_batch(v), cm, gm, ks, r);
        for (std::size_t i = 0; i < v.size(); ++i) {
          // coarse (under-resolved contact, numbers returned) is a run; first passage holds for it too
          if (r.status[i] != 0 && r.status[i] != static_cast<std::uint8_t>(LaneStatus::coarse)) {
            ADD_FAILURE() << to_string(st) << " " << to_string(law) << " lane " << i << " gap case " << g
                          << ": status " << to_string(static_cast<LaneStatus>(r.status[i])) << " (gap "
                          << v[i].gap << ", kc " << v[i].kc << ", e " << v[i].e << ")";
            continue;
          }
          const bool hit = r.impact_count[i] > 0, passed = free.peak_closing[i] > v[i].gap;
          ++total;
          impacting += hit;
          if (hit != passed) {
            ++mismatches;
            if (mismatches <= 3)
              ADD_FAILURE() << to_string(st) << " " << to_string(law) << " lane " << i << " gap case " << g
                            << ": impacts " << r.impact_count[i] << ", uncoupled peak closing - gap = "
                            << free.peak_closing[i] - v[i].gap;
          }
          // before any impact the observers are the uncoupled ones
          if (!hit) {
            const std::string where = std::string(to_string(st)) + " " + std::string(to_string(law)) + " lane " +
                                      std::to_string(i) + " gap case " + std::to_string(g);
            if (st == Stepper::newmark) {
              // Newton stops at a relative increment of 1e-10; an iterate that touches (gap = P exactly) takes
              // another path to the same converged state, equal to within that tolerance, not bit for bit.
              EXPECT_NEAR(r.final_u1[i], free.final_u1[i], 1e-9 * std::abs(free.peak_u1[i])) << where;
              EXPECT_NEAR(r.final_v2[i], free.final_v2[i], 1e-9 * std::abs(free.final_v2[i]) + 1e-12) << where;
              EXPECT_NEAR(r.peak_closing[i], free.peak_closing[i], 1e-9 * free.peak_closing[i]) << where;
            } else {
              EXPECT_EQ(r.peak_closing[i], free.peak_closing[i]) << where;
              EXPECT_EQ(r.final_u1[i], free.final_u1[i]) << where;
              EXPECT_EQ(r.final_v2[i], free.final_v2[i]) << where;
            }
          }
        }
      }
      std::printf("%-18s %-16s %d lane-gaps, %d impacting, %d mismatches with uncoupled first passage\n",
                  std::string(to_string(st)).c_str(), std::string(to_string(law)).c_str(), total, impacting,
                  mismatches);
      EXPECT_EQ(mismatches, 0) << to_string(st) << " " << to_string(law);
      EXPECT_GT(impacting, total / 4);
      EXPECT_LT(impacting, total);
    }
  }
}

// The time series themselves, lane by lane: bit-identical strictly before the first impact, and the
// first impact at the first step where the uncoupled closing exceeds the gap.
TEST(FirstPassage, SeriesBitIdenticalUntilFirstImpact) {
  const double dt = 0.01;
  const std::vector<double> ag = test::two_tone(dt, 6.0, 1.5, 0.9, 1.2, 1.9);
  const std::vector<PairParams> v = random_pairs(16, 5, 0.005, 0.04);
  GroundMotion gm{dt, ag, 0.0};
  for (Stepper st : all_steppers) {
    for (ContactLaw law : {ContactLaw::hertzdamp, ContactLaw::kelvin, ContactLaw::stereomechanical}) {
      int checked = 0;
      for (std::size_t lane = 0; lane < v.size(); ++lane) {
        SeriesRecorder a, b;
        KernelSettings ks;
        ks.stepper = st;
        ks.substeps = 2;
        BatchResult ra, rb;
        ks.series = &a;
        a.lane = lane;
        run_batch(to_batch(v), test::contact(ContactLaw::none), gm, ks, ra);
        ks.series = &b;
        b.lane = lane;
        run_batch(to_batch(v), test::contact(law), gm, ks, rb);
        ASSERT_EQ(a.t.size(), b.t.size());
        const double t1 = rb.t_first_impact[lane];
        std::size_t first_passage = a.t.size();
        for (std::size_t j = 0; j < a.t.size(); ++j)
          if (a.u1[j] - a.u2[j] - v[lane].gap > 0.0) {
            first_passage = j;
            break;
          }
        if (rb.status[lane] != 0 && rb.status[lane] != static_cast<std::uint8_t>(LaneStatus::coarse)) {
          ADD_FAILURE() << to_string(st) << " " << to_string(law) << " lane " << lane << ": status "
                        << to_string(static_cast<LaneStatus>(rb.status[lane]));
          continue;
        }
        if (std::isnan(t1)) {
          EXPECT_EQ(first_passage, a.t.size()) << to_string(st) << " " << to_string(law) << " lane " << lane
                                               << ": uncoupled closing passes the gap, no impact recorded";
          continue;
        }
        ++checked;
        ASSERT_LT(first_passage, a.t.size());
        EXPECT_EQ(a.t[first_passage], t1) << to_string(st) << " " << to_string(law) << " lane " << lane;
        std::size_t j = 0;
        for (; j < a.t.size() && a.t[j] < t1; ++j)
          if (a.u1[j] != b.u1[j] || a.u2[j] != b.u2[j] || a.v1[j] != b.v1[j] || a.v2[j] != b.v2[j] ||
              a.fs1[j] != b.fs1[j] || a.fs2[j] != b.fs2[j] || b.force[j] != 0.0)
            break;
        EXPECT_FALSE(j < a.t.size() && a.t[j] < t1)
            << to_string(st) << " " << to_string(law) << " lane " << lane << ": series differ at t = " << a.t[j]
            << " before the first impact at " << t1 << " (u1 " << a.u1[j] << " vs " << b.u1[j] << ")";
      }
      EXPECT_GE(checked, 4) << to_string(st) << " " << to_string(law);
    }
  }
}

// --------------------------------------------------------------------------------------------------
// 10. Batch width 1 and 256 (and a ragged 37) give bit-identical lanes, every stepper and contact law.
// Number of observers in which lane ia of a and lane ib of b differ (bitwise); the first few are reported.
int lane_differences(const BatchResult& a, std::size_t ia, const BatchResult& b, std::size_t ib,
                     const std::string& what, int& reported) {
  int n = 0;
  const auto oa = double_observers(a), ob = double_observers(b);
  for (std::size_t q = 0; q < oa.size(); ++q) {
    const double x = (*oa[q])[ia], y = (*ob[q])[ib];
    if (std::memcmp(&x, &y, sizeof x) != 0) {
      ++n;
      if (reported++ < 4) ADD_FAILURE() << what << " " << observer_names[q] << ": " << x << " vs " << y;
    }
  }
  n += a.impact_count[ia] != b.impact_count[ib];
  n += a.clamp_count[ia] != b.clamp_count[ib];
  n += a.status[ia] != b.status[ib];
  return n;
}

TEST(BatchWidth, Width1And256GiveBitIdenticalLanes) {
  const double dt = 0.01;
  const std::vector<double> ag = test::two_tone(dt, 2.0, 4.0, 1.3, 3.0, 2.9);
  const std::vector<PairParams> v = random_pairs(256, 99, 0.0, 0.03);
  const PairBatch wide = to_batch(v);
  GroundMotion gm{dt, ag, 0.0};
  for (Stepper st : all_steppers) {
    for (ContactLaw law : all_laws) {
      KernelSettings ks;
      ks.stepper = st;
      ks.substeps = 2;
      ks.energy = true;
      const ContactModel cm = test::contact(law);
      BatchResult rw, r37;
      run_batch(wide, cm, gm, ks, rw);
      int impacting = 0, lanes_differing = 0, reported = 0;
      const std::string what = std::string(to_string(st)) + " " + std::string(to_string(law));
      for (std::size_t i = 0; i < v.size(); ++i) {
        BatchResult r1;
        run_batch(to_batch({v[i]}), cm, gm, ks, r1);
        impacting += rw.impact_count[i] > 0;
        lanes_differing += lane_differences(r1, 0, rw, i, what + " width 1 vs 256, lane " + std::to_string(i), reported) > 0;
      }
      // lanes 200..236 as a batch of 37 (a ragged SIMD tail, different positions in the tile)
      std::vector<PairParams> sub(v.begin() + 200, v.begin() + 237);
      run_batch(to_batch(sub), cm, gm, ks, r37);
      int lanes37 = 0;
      for (std::size_t i = 0; i < sub.size(); ++i)
        lanes37 += lane_differences(r37, i, rw, 200 + i, what + " width 37 vs 256, lane " + std::to_string(i), reported) > 0;
      std::printf("%-36s lanes differing: width 1 vs 256: %3d/256, width 37 vs 256: %2d/37\n", what.c_str(),
                  lanes_differing, lanes37);
      EXPECT_EQ(lanes_differing, 0) << what;
      EXPECT_EQ(lanes37, 0) << what;
      if (law != ContactLaw::none) {
        EXPECT_GT(impacting, 32) << to_string(st) << " " << to_string(law);
      }
    }
  }
}

// --------------------------------------------------------------------------------------------------
// 11. Bad lane parameters: run_batch throws InputError naming the parameter (any lane, not only the first).
TEST(BadInput, RunBatchRejectsNonPhysicalLaneParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  PairParams good;
  good.s1 = Structure::from_period(1e5, 0.5, 0.05);
  good.s2 = Structure::from_period(1e5, 0.8, 0.05);
  good.gap = 0.01, good.kc = 1e9, good.e = 0.65;
  struct Bad {
    const char* name;
    std::function<void(PairParams&)> f;
  };
  const Bad bads[] = {
      {"m1", [](PairParams& p) { p.s1.m = 0; }},          {"m2", [](PairParams& p) { p.s2.m = -1; }},
      {"m1", [&](PairParams& p) { p.s1.m = nan; }},       {"m2", [&](PairParams& p) { p.s2.m = inf; }},
      {"k1", [](PairParams& p) { p.s1.k = -1; }},         {"k2", [&](PairParams& p) { p.s2.k = nan; }},
      {"c1", [](PairParams& p) { p.s1.c = -1; }},         {"c2", [&](PairParams& p) { p.s2.c = nan; }},
      {"fy1", [](PairParams& p) { p.s1.fy = 0; }},        {"fy2", [](PairParams& p) { p.s2.fy = -5; }},
      {"fy1", [&](PairParams& p) { p.s1.fy = nan; }},     {"alpha1", [](PairParams& p) { p.s1.alpha = 1.0; }},
      {"alpha2", [](PairParams& p) { p.s2.alpha = -0.1; }}, {"alpha1", [&](PairParams& p) { p.s1.alpha = nan; }},
      {"gap", [](PairParams& p) { p.gap = -0.01; }},      {"gap", [&](PairParams& p) { p.gap = nan; }},
      {"gap", [&](PairParams& p) { p.gap = inf; }},       {"kc", [](PairParams& p) { p.kc = 0; }},
      {"kc", [&](PairParams& p) { p.kc = nan; }},         {"e", [](PairParams& p) { p.e = 0; }},
      {"e", [](PairParams& p) { p.e = 1.01; }},           {"e", [&](PairParams& p) { p.e = nan; }},
  };
  const std::vector<double> ag = {0.0, 0.1, 0.0};
  GroundMotion gm{0.01, ag, 0.0};
  KernelSettings ks;
  for (const Bad& b : bads) {
    std::vector<PairParams> v(3, good);
    b.f(v[1]);
    BatchResult r;
    try {
      run_batch(to_batch(v), test::contact(ContactLaw::hertzdamp), gm, ks, r);
      ADD_FAILURE() << "no InputError for bad " << b.name;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.where()).find(b.name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("lane 1"), std::string::npos) << e.what();
    }
  }
  // run settings and the record
  std::vector<PairParams> v(2, good);
  BatchResult r;
  KernelSettings ks0;
  ks0.substeps = 0;
  EXPECT_THROW(run_batch(to_batch(v), test::contact(ContactLaw::hertzdamp), gm, ks0, r), InputError);
  for (double dt : {0.0, -0.01, nan}) {
    GroundMotion g{dt, ag, 0.0};
    EXPECT_THROW(run_batch(to_batch(v), test::contact(ContactLaw::hertzdamp), g, ks, r), InputError) << dt;
  }
  // a good batch runs
  EXPECT_NO_THROW(run_batch(to_batch(v), test::contact(ContactLaw::hertzdamp), gm, ks, r));
}

}  // namespace
}  // namespace pounding
