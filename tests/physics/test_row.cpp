// Rows of buildings (issue 25 step 8; docs/architecture.md §2.8 "three masses in a row", "row symmetry";
// ../shared/research/systems-and-bridges.md §4): the row is model::shear_buildings of n sticks run by the same system
// stepper as every System -- no code of its own in the kernel. Checked against numbers we did not compute:
// T4.1's final velocities (SB §4), an independent SciPy solution of a pounding row (tools/reference_systems.py row:
// solve_ivp with event-located onsets, its own uncoupled run for the amplification), and the mirror symmetry of a
// symmetric row.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/contact/registry.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "system_reference.hpp"
#include "system_test_support.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

using namespace pounding;
using namespace pounding::physics;
using test::have_scipy;
using test::python;

namespace {


model::System row(const std::vector<int>& storeys) {
  std::vector<model::StickTopology> sticks(storeys.size());
  for (std::size_t b = 0; b < storeys.size(); ++b) sticks[b].storeys = storeys[b];
  return model::shear_buildings(sticks);
}

test::Stick stick(std::vector<double> m, std::vector<double> k, double a0 = 0.0, double a1 = 0.0) {
  test::Stick s;
  s.m = std::move(m), s.k = std::move(k), s.a0 = a0, s.a1 = a1;
  return s;
}

ContactModel law(ContactLaw l) {
  ContactModel cm;
  cm.law = l;
  return cm;
}

// One lane of row S: the sticks, every element's gap/kc/e, initial velocities per DOF, ground acceleration ag (m/s^2).
SystemResult run_row(const model::System& S, const std::vector<test::Stick>& sticks, double gap, double kc, double e,
                     const ContactModel& cm, const std::vector<double>& ag, double dt, int substeps,
                     const std::vector<double>& v0 = {}, double duration = 0.0) {
  SystemBatch B;
  B.resize(S, 1);
  for (std::size_t b = 0; b < sticks.size(); ++b) test::fill_stick(B, static_cast<int>(b), 0, sticks[b]);
  for (std::size_t k = 0; k < S.contacts().size(); ++k) B.gap[k] = gap, B.kc[k] = kc, B.e[k] = e;
  for (std::size_t d = 0; d < v0.size(); ++d) B.v0[d] = v0[d];
  KernelSettings ks;
  ks.substeps = substeps;
  const ContactModel groups[] = {cm};
  SystemResult r;
  run_system(B, groups, GroundMotion{dt, ag, duration}, ks, r);
  return r;
}

int dof(const model::System& S, int b, int floor) {
  return S.bodies()[static_cast<std::size_t>(b)].dofs[static_cast<std::size_t>(floor)];
}

}  // namespace

// T4.1 (SB §4): three equal masses at zero gaps, no springs, mass 1 moving at v0 toward 2 (which touches 3): the final
// velocities / v0 are (-0.0709523537, 0.0764030391, 0.9945493146) with Hertz contacts and (-0.1302616951,
// 0.1502295694, 0.9800321256) with linear ones, for any m, k_h, v0. The row's storeys are springs of 1e-12 N/m (the
// system needs one under every floor; over the 0.05 s run their impulse is ~1e-15 m v0), no damping. Central
// difference at h = 2.5e-7 s (~ 1/4000 of the linear contact time, ~ 1/35000 of the Hertz one) gives the velocities
// to 1e-6 (measured: at most 1.5e-8) and keeps momentum to 1e-12 (the contact forces are equal and opposite).
TEST(Row, ThreeMassesInARowT4_1) {
  const model::System S = row({1, 1, 1});
  ASSERT_EQ(S.contacts().size(), 2u);
  EXPECT_EQ(S.contacts()[0].label, "1|2 level 1");
  EXPECT_EQ(S.contacts()[1].label, "2|3 level 1");
  struct Case {
    ContactLaw law;
    double want[3];
  };
  for (const Case& c : {Case{ContactLaw::hertz, {-0.0709523537, 0.0764030391, 0.9945493146}},
                        Case{ContactLaw::linear, {-0.1302616951, 0.1502295694, 0.9800321256}}}) {
    for (auto [m, kc, v0] : {std::tuple{1.0, 1.0e6, 1.0}, std::tuple{7.5, 3.0e7, 0.4}}) {
      const std::vector<test::Stick> sticks(3, stick({m}, {1e-12}));
      const std::vector<double> ag(51, 0.0);  // 0.05 s of no ground motion at dt 1e-3
      std::vector<double> v(3, 0.0);
      v[static_cast<std::size_t>(dof(S, 0, 0))] = v0;
      const SystemResult r = run_row(S, sticks, 0.0, kc, 1.0, law(c.law), ag, 1e-3, 4000, v, 0.05);
      ASSERT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok));
      double p = 0, err = 0;
      for (int b = 0; b < 3; ++b) {
        const double vb = r.final_v[static_cast<std::size_t>(dof(S, b, 0))] / v0;
        p += vb;
        err = std::max(err, std::abs(vb - c.want[b]));
        EXPECT_NEAR(vb, c.want[b], 1e-6) << to_string(c.law) << " mass " << b + 1 << ", m " << m << ", kc " << kc;
      }
      EXPECT_NEAR(p, 1.0, 1e-12) << "momentum, " << to_string(c.law);
      std::printf("%s m %g kc %g v0 %g: max |v/v0 - T4.1| %.2e, momentum %.15f\n", std::string(to_string(c.law)).c_str(), m, kc, v0,
                  err, p);
    }
  }
}

// Row symmetry (§2.8): (a) three identical buildings under one record at equal gaps move as one: they never touch,
// and every floor's peaks equal the uncoupled run's bit for bit; (b) a symmetric row A-B-A is its own mirror image
// once the ground motion changes sign (x -> -x maps the row under ag onto the row under -ag), so building 1 under ag
// and building 3 under -ag have the same peaks per floor, and mirrored joints the same impacts and peak forces, to
// round-off (the interior building sums its two contact forces in the other order).
TEST(Row, IdenticalBuildingsNeverTouchAndASymmetricRowMirrors) {
  std::vector<double> ag;
  const double dt = 0.01;
  for (int i = 0; i <= 600; ++i) {
    const double t = i * dt;
    ag.push_back(4.0 * std::sin(2 * std::numbers::pi * 0.9 * t) * std::exp(-0.4 * t) + 1.5 * std::sin(7.3 * t));
  }
  ContactModel hd = law(ContactLaw::hertzdamp);
  // (a)
  {
    const model::System S = row({3, 3, 3});
    test::Stick a = stick({2.5e5, 2.5e5, 2.0e5}, {3.0e8, 2.6e8, 2.0e8});
    test::rayleigh(a, 0.05, 2 * std::numbers::pi / 0.5, 2 * std::numbers::pi / 0.18);
    const SystemResult c = run_row(S, {a, a, a}, 0.0, 1e10, 0.65, hd, ag, dt, 10);
    const SystemResult u = run_row(S, {a, a, a}, 0.0, 1e10, 0.65, law(ContactLaw::none), ag, dt, 10);
    for (std::size_t e = 0; e < S.contacts().size(); ++e) EXPECT_EQ(c.impact_count[e], 0) << S.contacts()[e].label;
    for (int f = 0; f < 3; ++f)
      for (int b = 0; b < 3; ++b) {
        const auto x = static_cast<std::size_t>(dof(S, b, f)), x0 = static_cast<std::size_t>(dof(S, 0, f));
        EXPECT_EQ(c.peak_u[x], u.peak_u[x]) << "building " << b + 1 << " floor " << f + 1;
        EXPECT_EQ(c.peak_u[x], c.peak_u[x0]) << "building " << b + 1 << " floor " << f + 1;
      }
  }
  // (b) A (3 storeys, stiff) - B (5 storeys, soft) - A
  const model::System S = row({3, 5, 3});
  test::Stick A = stick({3.0e5, 3.0e5, 2.5e5}, {4.0e8, 3.6e8, 3.0e8}, 0.7, 0.0015);
  test::Stick Bs = stick({2.5e5, 2.5e5, 2.5e5, 2.2e5, 2.0e5}, {2.6e8, 2.5e8, 2.3e8, 2.0e8, 1.6e8}, 0.4, 0.003);
  std::vector<double> neg(ag.size());
  for (std::size_t i = 0; i < ag.size(); ++i) neg[i] = -ag[i];
  const SystemResult p = run_row(S, {A, Bs, A}, 0.01, 1e10, 0.65, hd, ag, dt, 20);
  const SystemResult q = run_row(S, {A, Bs, A}, 0.01, 1e10, 0.65, hd, neg, dt, 20);
  int impacts = 0;
  for (std::size_t e = 0; e < S.contacts().size(); ++e) impacts += p.impact_count[e];
  EXPECT_GE(impacts, 4) << "the row must pound";
  double worst = 0;
  for (int f = 0; f < 3; ++f) {
    const auto l = static_cast<std::size_t>(dof(S, 0, f)), r = static_cast<std::size_t>(dof(S, 2, f));
    EXPECT_NEAR(p.peak_u[l], q.peak_u[r], 1e-9 * p.peak_u[l]) << "floor " << f + 1;
    EXPECT_NEAR(p.peak_u[r], q.peak_u[l], 1e-9 * p.peak_u[r]) << "floor " << f + 1;
    worst = std::max(worst, std::abs(p.peak_u[l] - q.peak_u[r]) / p.peak_u[l]);
  }
  for (int f = 0; f < 5; ++f) {
    const auto m = static_cast<std::size_t>(dof(S, 1, f));
    EXPECT_NEAR(p.peak_u[m], q.peak_u[m], 1e-9 * p.peak_u[m]) << "interior floor " << f + 1;
  }
  // elements: level k joint 1|2 is 2k, joint 2|3 is 2k + 1 (level order, joints left to right)
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(S.contacts()[2 * k].label, fmt::format("1|2 level {}", k + 1));
    EXPECT_EQ(p.impact_count[2 * k], q.impact_count[2 * k + 1]) << "level " << k + 1;
    EXPECT_EQ(p.impact_count[2 * k + 1], q.impact_count[2 * k]) << "level " << k + 1;
    if (p.impact_count[2 * k] > 0) {
      EXPECT_NEAR(p.peak_force[2 * k], q.peak_force[2 * k + 1], 1e-9 * p.peak_force[2 * k]) << "level " << k + 1;
    }
  }
  std::printf("mirror: %d impacts, worst relative difference of mirrored end-building peaks %.2e\n", impacts, worst);
}

// "Three masses in a row" under ground motion (§2.8, step 8): a row of 2-, 3- and 2-storey Rayleigh-damped buildings
// pounding with Hertzdamp at every common floor under a decaying two-tone ground motion, against
// tools/reference_systems.py row (solve_ivp DOP853 with event-located onsets, none of our code): peak floor
// displacements within 1e-3 at h = dt/80, impact counts per element equal, and each building's amplification
// (coupled / uncoupled peak over its floors, the reference's own uncoupled run) within 1e-3. Needs /usr/bin/python3
// with numpy and scipy: skipped without them (a failure under CI=true).
TEST(Row, PoundingRowAgainstSolveIvp) {
  if (!have_scipy()) POUNDING_SKIP_OR_FAIL("needs " + python() + " with numpy and scipy (tools/setup.sh)");
  const double dt = 0.01, gap = 0.004, kc = 5.0e9, e = 0.65;
  std::vector<double> ag;
  for (int i = 0; i <= 400; ++i) {
    const double t = i * dt;
    ag.push_back(5.0 * std::sin(2 * std::numbers::pi * 1.1 * t) * std::exp(-0.5 * t) + 2.0 * std::sin(9.0 * t));
  }
  const std::vector<test::Stick> sticks{stick({3.0e5, 2.5e5}, {4.0e8, 3.0e8}, 0.7, 0.0015),
                                        stick({2.5e5, 2.5e5, 2.0e5}, {2.0e8, 1.8e8, 1.5e8}, 0.4, 0.003),
                                        stick({2.0e5, 2.0e5}, {6.0e8, 5.0e8}, 0.9, 0.001)};
  const model::System S = row({2, 3, 2});
  ASSERT_EQ(S.contacts().size(), 4u);  // levels 1 and 2 at both joints
  auto body = [](const test::Stick& s) {
    return fmt::format(R"({{"m": [{:.17g}], "k": [{:.17g}], "a0": {:.17g}, "a1": {:.17g}}})", fmt::join(s.m, ", "),
                       fmt::join(s.k, ", "), s.a0, s.a1);
  };
  const int g = 80;
  testdata::TempDir tmp("row-scipy");
  const std::string in = tmp.file("in.json"), out = tmp.file("out.txt");
  std::ofstream(in) << fmt::format(
      R"({{"dt": {:.17g}, "ag": [{:.17g}], "duration": {:.17g}, "substeps": [{}], "bodies": [{}, {}, {}], "gap": {}, "kc": {}, "n": 1.5, "e": {}, "v0_min": 0.001}})",
      dt, fmt::join(ag, ", "), dt * static_cast<double>(ag.size() - 1), g, body(sticks[0]), body(sticks[1]),
      body(sticks[2]), gap, kc, e);
  const std::string cmd = python() + " " + testdata::source_dir() + "/tools/reference_systems.py row " + in + " " + out;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::map<std::tuple<int, int>, double> peak_u;
  std::map<int, int> impacts;
  std::map<int, double> amplification;
  std::ifstream f(out);
  for (std::string line; std::getline(f, line);) {
    std::istringstream s(line);
    std::string key;
    int a = 0, b = 0, c = 0;
    double v = 0;
    s >> key;
    if (key == "peak_u") s >> a >> b >> c >> v, peak_u[{b, c}] = v;
    if (key == "impacts") s >> a >> b, impacts[a] = b;
    if (key == "amplification") s >> a >> b >> v, amplification[b] = v;
  }
  ContactModel hd = law(ContactLaw::hertzdamp);
  const SystemResult r = run_row(S, sticks, gap, kc, e, hd, ag, dt, g);
  const SystemResult u = run_row(S, sticks, gap, kc, e, law(ContactLaw::none), ag, dt, g);
  ASSERT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok));
  int total = 0;
  for (std::size_t k = 0; k < S.contacts().size(); ++k) {
    EXPECT_EQ(r.impact_count[k], impacts.at(static_cast<int>(k))) << S.contacts()[k].label;
    total += r.impact_count[k];
    std::printf("%s: %d impacts (reference %d)\n", S.contacts()[k].label.c_str(), r.impact_count[k],
                impacts.at(static_cast<int>(k)));
  }
  EXPECT_GE(total, 4) << "the row must pound";
  for (int b = 0; b < 3; ++b) {
    double cu = 0, uu = 0;
    const auto& dofs = S.bodies()[static_cast<std::size_t>(b)].dofs;
    for (std::size_t fl = 0; fl < dofs.size(); ++fl) {
      const double x = r.peak_u[static_cast<std::size_t>(dofs[fl])], want = peak_u.at({b, static_cast<int>(fl) + 1});
      EXPECT_NEAR(x, want, 1e-3 * want) << "building " << b + 1 << " floor " << fl + 1;
      cu = std::max(cu, x), uu = std::max(uu, u.peak_u[static_cast<std::size_t>(dofs[fl])]);
    }
    EXPECT_NEAR(cu / uu, amplification.at(b), 1e-3 * amplification.at(b)) << "building " << b + 1;
    std::printf("building %d: amplification %.6f (reference %.6f)\n", b + 1, cu / uu, amplification.at(b));
  }
}
