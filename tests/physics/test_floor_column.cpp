// Floors against columns (issue 25 §3; docs/architecture.md §2.2.4, step 9; docs/floor-contact.md;
// ../shared/research/systems-and-bridges.md §3, T3.1): where a floor of one shear building faces the column between
// two floors of its neighbour, the element's column side is x = N1 u_lo + N2 u_hi with linear shape functions
// (N1 = 1 - xi, N2 = xi) and the contact force goes to the two floors with the same weights (work and momentum
// consistent). Checked against numbers we did not compute: T3.1's nodal forces, the floor-to-floor element (xi = 0
// and 1 give its bits), momentum, the energy balance converging with the step, and an independent SciPy solution
// (tools/reference_systems.py system with column sides: solve_ivp with event-located onsets).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "system_reference.hpp"
#include "system_test_support.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

using namespace pounding;
using namespace pounding::physics;
using test::body_json;
using test::have_scipy;
using test::python;
using test::Reference;
using test::run_reference;

namespace {

model::StickTopology stick(int n, double h) {
  model::StickTopology s;
  s.storeys = n;
  s.storey_heights = {h};
  return s;
}

test::Stick numbers(std::vector<double> m, std::vector<double> k, double a0 = 0.0, double a1 = 0.0) {
  test::Stick s;
  s.m = std::move(m), s.k = std::move(k), s.a0 = a0, s.a1 = a1;
  return s;
}

ContactModel law(ContactLaw l) {
  ContactModel cm;
  cm.law = l;
  return cm;
}

int element(const model::System& S, const std::string& label) {
  for (std::size_t e = 0; e < S.contacts().size(); ++e)
    if (S.contacts()[e].label == label) return static_cast<int>(e);
  ADD_FAILURE() << "no element " << label;
  return 0;
}

// A two-tone ground acceleration (m/s^2) of `seconds` at dt.
std::vector<double> two_tone(double seconds, double dt, double a1 = 3.0, double a2 = 2.0) {
  std::vector<double> ag;
  for (int i = 0; i * dt <= seconds + 1e-12; ++i) {
    const double t = i * dt;
    ag.push_back(a1 * std::sin(2 * std::numbers::pi * 1.5 * t) + a2 * std::sin(2 * std::numbers::pi * 0.7 * t));
  }
  return ag;
}

// Every observer of two results, bit for bit (NaN equal to NaN of the same bits).
template <class T>
void expect_bits(const std::vector<T>& a, const std::vector<T>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_EQ(std::memcmp(&a[i], &b[i], sizeof(T)), 0) << what << "[" << i << "]: " << a[i] << " vs " << b[i];
}
void expect_same(const SystemResult& a, const SystemResult& b) {
  expect_bits(a.peak_u, b.peak_u, "peak_u");
  expect_bits(a.peak_acc, b.peak_acc, "peak_acc");
  expect_bits(a.final_u, b.final_u, "final_u");
  expect_bits(a.final_v, b.final_v, "final_v");
  expect_bits(a.peak_drift, b.peak_drift, "peak_drift");
  expect_bits(a.peak_spring_force, b.peak_spring_force, "peak_spring_force");
  expect_bits(a.peak_closing, b.peak_closing, "peak_closing");
  expect_bits(a.t_peak_closing, b.t_peak_closing, "t_peak_closing");
  expect_bits(a.t_first_impact, b.t_first_impact, "t_first_impact");
  expect_bits(a.impact_count, b.impact_count, "impact_count");
  expect_bits(a.clamp_count, b.clamp_count, "clamp_count");
  expect_bits(a.peak_force, b.peak_force, "peak_force");
  expect_bits(a.peak_penetration, b.peak_penetration, "peak_penetration");
  expect_bits(a.contact_energy, b.contact_energy, "contact_energy");
  expect_bits(a.contact_time, b.contact_time, "contact_time");
  expect_bits(a.h_omega_contact, b.h_omega_contact, "h_omega_contact");
  expect_bits(a.status, b.status, "status");
  for (auto f : {&SystemResult::e_input, &SystemResult::e_kinetic, &SystemResult::e_strain, &SystemResult::e_viscous,
                 &SystemResult::e_hysteretic, &SystemResult::e_contact_stored})
    expect_bits(a.*f, b.*f, "energy");
}

}  // namespace

// T3.1's geometry (SB §3): A (left) 4 storeys of 3.0 m, B (right) 3 of 3.5 m. Each floor below the neighbour's roof
// strikes its column: A's floors at 3, 6, 9 m B's columns at xi = 6/7, 5/7, 4/7 (the first one's lower end the
// ground), B's floors at 3.5, 7.0, 10.5 m A's at xi = 1/6, 1/3, 1/2; A's roof (12 m) is above B's and meets nothing.
// With a floor within the tolerance of a column end, the element is the floor-to-floor one.
TEST(FloorColumn, T31Topology) {
  const std::vector<model::StickTopology> ab{stick(4, 3.0), stick(3, 3.5)};
  const model::System S = model::shear_buildings(ab);
  // DOFs level-major: A1 0, B1 1, A2 2, B2 3, A3 4, B3 5, A4 6
  struct Want {
    std::string label;
    model::SideKind lk;
    int lp, lq;
    model::SideKind rk;
    int rp, rq;
    int level;
    double xi;
  };
  using model::SideKind;
  const std::vector<Want> want{
      {"level 1/column 0-1", SideKind::point, 0, -1, SideKind::interpolated, model::ground, 1, 1, 3.0 / 3.5},
      {"column 1-2/level 1", SideKind::interpolated, 0, 2, SideKind::point, 1, -1, 1, 0.5 / 3.0},
      {"level 2/column 1-2", SideKind::point, 2, -1, SideKind::interpolated, 1, 3, 2, 2.5 / 3.5},
      {"column 2-3/level 2", SideKind::interpolated, 2, 4, SideKind::point, 3, -1, 2, 1.0 / 3.0},
      {"level 3/column 2-3", SideKind::point, 4, -1, SideKind::interpolated, 3, 5, 3, 2.0 / 3.5},
      {"column 3-4/level 3", SideKind::interpolated, 4, 6, SideKind::point, 5, -1, 3, 0.5}};
  ASSERT_EQ(S.contacts().size(), want.size());
  for (std::size_t e = 0; e < want.size(); ++e) {
    const model::ContactElement& c = S.contacts()[e];
    EXPECT_EQ(c.label, want[e].label) << e;
    EXPECT_EQ(c.left.kind, want[e].lk) << e;
    EXPECT_EQ(c.left.p, want[e].lp) << e;
    EXPECT_EQ(c.right.kind, want[e].rk) << e;
    EXPECT_EQ(c.right.p, want[e].rp) << e;
    if (want[e].lk == SideKind::interpolated) {
      EXPECT_EQ(c.left.q, want[e].lq) << e;
    }
    if (want[e].rk == SideKind::interpolated) {
      EXPECT_EQ(c.right.q, want[e].rq) << e;
    }
    EXPECT_EQ(c.level, want[e].level) << e;
    EXPECT_NEAR(c.xi, want[e].xi, 1e-15) << e;
  }
  // only the lower roof (B's, 10.5 m, on A's column 3-4)
  const model::System top = model::shear_buildings(ab, 0.05, model::ContactLevels::top);
  ASSERT_EQ(top.contacts().size(), 1u);
  EXPECT_EQ(top.contacts()[0].label, "column 3-4/level 3");
  // 3.0 m against 3.02 m: within the tolerance the floors meet as floors (points), beyond it the columns
  const std::vector<model::StickTopology> near{stick(2, 3.0), stick(2, 3.02)};
  const model::System aligned = model::shear_buildings(near);
  for (const model::ContactElement& c : aligned.contacts())
    EXPECT_TRUE(c.left.kind == SideKind::point && c.right.kind == SideKind::point) << c.label;
  EXPECT_EQ(model::shear_buildings(near, 0.01).contacts().size(), 3u);  // 3.0 on 0-1, 3.02 on 1-2, 6.0 on 1-2; 6.04 above
}

// T3.1's numbers (SB §3): B's floor 2 (7.0 m) against A's column between floors 2 and 3 (xi = 1/3), u_A2 = 0.030,
// u_A3 = 0.045, u_B2 = 0.030 m, gap 0, Hertz k_h = 1e10 N/m^1.5: linear u_c = 0.035, delta = 5e-3 m, F = 3535533.906 N
// -> A2 -2357022.604 N, A3 -1178511.302 N, B2 +3535533.906 N; cubic ([contact] shape_functions = "cubic") F =
// 2425148.306 N -> A2 -1796406.153 N, A3 -628742.153 N. Unit floor masses and storey springs of 1e-6 N/m (their
// forces ~1e-8 N): the first step's accelerations are the nodal forces; the run's peak |a| is the first (the floors
// separate). The struck column's fixed-end shears at xi = 1/3 (SB §3's cubic N): 20/27 and 7/27 of F.
TEST(FloorColumn, T31NodalForcesAreTheShapeFunctionsOfTheContactForce) {
  const std::vector<model::StickTopology> ab{stick(4, 3.0), stick(3, 3.5)};
  const model::System S = model::shear_buildings(ab);
  const int e = element(S, "column 2-3/level 2");
  const int a2 = 2, a3 = 4, b2 = 3;
  struct Want {
    model::ShapeFunctions shape;
    double n2, F, fa2, fa3;
  };
  // linear N = (2/3, 1/3); cubic N = (0.740740741, 0.259259259): u_c = 0.0338888889, delta = 3.888888889e-3
  for (const Want& w : {Want{model::ShapeFunctions::linear, 1.0 / 3.0, 3535533.906, 2357022.604, 1178511.302},
                        Want{model::ShapeFunctions::cubic, 7.0 / 27.0, 2425148.306, 1796406.153, 628742.153}}) {
    SCOPED_TRACE(w.shape == model::ShapeFunctions::linear ? "linear" : "cubic");
    SystemBatch B;
    B.resize(S, 1);
    test::fill_stick(B, 0, 0, numbers({1, 1, 1, 1}, {1e-6, 1e-6, 1e-6, 1e-6}));
    test::fill_stick(B, 1, 0, numbers({1, 1, 1}, {1e-6, 1e-6, 1e-6}));
    set_contacts(B, 0, 10.0, 1e10, 1.0, {}, w.shape);
    B.gap[static_cast<std::size_t>(e)] = 0.0;
    EXPECT_NEAR(B.weight[static_cast<std::size_t>(e)], w.n2, 1e-15);
    B.u0[a2] = 0.030, B.u0[a3] = 0.045, B.u0[b2] = 0.030;
    KernelSettings ks;
    ks.substeps = 1;
    const ContactModel groups[] = {law(ContactLaw::hertz)};
    SystemResult r;
    run_system(B, groups, GroundMotion{1e-8, std::vector<double>(3, 0.0), 0.0}, ks, r);
    ASSERT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok));
    EXPECT_NEAR(r.peak_force[static_cast<std::size_t>(e)], w.F, 1e-3);
    EXPECT_NEAR(r.peak_acc[a2], w.fa2, 1e-3);
    EXPECT_NEAR(r.peak_acc[a3], w.fa3, 1e-3);
    EXPECT_NEAR(r.peak_acc[b2], w.F, 1e-3);
    EXPECT_LT(r.final_v[a2], 0.0);  // A's floors pushed left, B's right
    EXPECT_LT(r.final_v[a3], 0.0);
    EXPECT_GT(r.final_v[b2], 0.0);
    for (int d : {0, 1, 5, 6}) EXPECT_LT(r.peak_acc[static_cast<std::size_t>(d)], 1e-6) << "DOF " << d;
  }
  for (double xi : {0.0, 1.0}) EXPECT_EQ(model::column_weight(xi, model::ShapeFunctions::cubic), xi);  // ends exact
  const ColumnShear v = column_shear_per_force(1.0 / 3.0);
  EXPECT_NEAR(v.below, 0.740740741, 1e-9);
  EXPECT_NEAR(v.above, 0.259259259, 1e-9);
  EXPECT_NEAR(v.below * 2425148.306, 1796406.153, 1e-2);  // T3.1's cubic nodal forces: the same weights
  EXPECT_NEAR(v.above * 2425148.306, 628742.153, 1e-2);
  for (double xi : {0.0, 0.1, 0.5, 0.9, 1.0}) {  // F b^2 (h + 2a) / h^3 and F a^2 (h + 2b) / h^3, h = 3, a = 3 xi
    const double h = 3.0, a = h * xi, b = h - a;
    EXPECT_NEAR(column_shear_per_force(xi).below, b * b * (h + 2 * a) / (h * h * h), 1e-15);
    EXPECT_NEAR(column_shear_per_force(xi).above, a * a * (h + 2 * b) / (h * h * h), 1e-15);
  }
}

// xi -> 0 and xi -> 1: an element whose column side sits at the column's end (N2 = 0 at its lower floor, N2 = 1 at its
// upper one) is the floor-to-floor element bit for bit -- every observer and energy term of three lanes with
// Hertzdamp pounding under a two-tone record, with the column on the left and on the right.
TEST(FloorColumn, XiAtAColumnEndIsTheFloorToFloorElementBitForBit) {
  const std::vector<model::StickTopology> ab{stick(3, 3.0), stick(3, 3.0)};
  const model::System P = model::shear_buildings(ab);  // DOFs A1 0, B1 1, A2 2, B2 3, A3 4, B3 5
  ASSERT_EQ(P.contacts().size(), 3u);
  ASSERT_EQ(P.contacts()[1].label, "level 2");
  struct Variant {
    const char* name;
    bool left;
    int p, q;
    double xi;
  };
  const std::vector<double> ag = two_tone(4.0, 0.01);
  std::vector<test::Stick> sticks{numbers({2e5, 2e5, 1.8e5}, {3e8, 2.8e8, 2.5e8}, 0.4, 0.002),
                                  numbers({2.2e5, 2e5, 2e5}, {1.2e8, 1.1e8, 1e8}, 0.3, 0.003)};
  auto run = [&](const model::System& S) {
    SystemBatch B;
    B.resize(S, 3);
    for (std::size_t l = 0; l < 3; ++l) {
      for (int b = 0; b < 2; ++b) test::fill_stick(B, b, l, sticks[static_cast<std::size_t>(b)]);
      set_contacts(B, l, 0.004 + 0.006 * static_cast<double>(l), 1e10, 0.65);
    }
    KernelSettings ks;
    ks.substeps = 10;
    ks.energy = true;
    const ContactModel groups[] = {law(ContactLaw::hertzdamp)};
    SystemResult r;
    run_system(B, groups, GroundMotion{0.01, ag, 0.0}, ks, r);
    return r;
  };
  const SystemResult want = run(P);
  int impacts = 0;
  for (std::int32_t c : want.impact_count) impacts += c;
  EXPECT_GT(want.impact_count[SystemBatch::at(1, 0, 3)], 0) << "level 2 must pound";
  for (const Variant& v : {Variant{"B's column 2-3 at xi = 0", false, 3, 5, 0.0}, Variant{"B's column 1-2 at xi = 1", false, 1, 3, 1.0},
                           Variant{"A's column 2-3 at xi = 0", true, 2, 4, 0.0}, Variant{"A's column 1-2 at xi = 1", true, 0, 2, 1.0}}) {
    model::System::Parts parts = P.parts();
    model::ContactElement& c = parts.contacts[1];
    (v.left ? c.left : c.right) = {model::SideKind::interpolated, v.p, v.q, 0};
    c.xi = v.xi;
    const model::System Q = model::System::build(parts);
    SCOPED_TRACE(v.name);
    expect_same(run(Q), want);
  }
  std::printf("%d impacts over 3 lanes and 3 levels, each variant bit for bit\n", impacts);
}

// Momentum and energy of a floor-to-column impact: B's floor (4.5 m, 1 m/s towards A) strikes A's column between its
// floors at 3 and 6 m (xi = 1/2), Hertzdamp e = 0.65, no ground motion, storey springs of 1e-9 N/m. The contact forces
// on A's two floors sum to the force on B's: momentum is kept to 1e-12. The energy balance (initial kinetic energy =
// kinetic + strain + contact stored + dissipated at the end) closes to round-off at every step (measured 5e-16 to
// 5e-15: the contact's work is the trapezoid of the same increments the nodal forces move, so the bookkeeping is
// exact), and the outcome converges with h at central difference's second order: the change of B's rebound velocity
// falls by more than 3 per halving of h. A second run strikes the column's ground end (B's floor at 2 m on A's column
// 0-1, the support takes N1 F): the balance closes the same way; momentum is not kept (the support's impulse) and
// converges at second order too.
TEST(FloorColumn, MomentumAndEnergyBalanceConvergeWithTheStep) {
  struct Case {
    double hb, xi;
    const char* label;
    bool ground;
  };
  for (const Case& c : {Case{4.5, 0.5, "column 1-2/level 1", false}, Case{2.0, 2.0 / 3.0, "column 0-1/level 1", true}}) {
    const std::vector<model::StickTopology> ab{stick(3, 3.0), stick(1, c.hb)};
    const model::System S = model::shear_buildings(ab);
    const int e = element(S, c.label);
    EXPECT_NEAR(S.contacts()[static_cast<std::size_t>(e)].xi, c.xi, 1e-15);
    const int b1 = S.bodies()[1].dofs[0];
    std::vector<double> errors, rebound, momentum;
    for (int substeps : {50, 100, 200, 400}) {
      SystemBatch B;
      B.resize(S, 1);
      test::fill_stick(B, 0, 0, numbers({2e5, 1.5e5, 1e5}, {1e-9, 1e-9, 1e-9}));
      test::fill_stick(B, 1, 0, numbers({1.2e5}, {1e-9}));
      set_contacts(B, 0, 5.0, 1e10, 0.65);
      B.gap[static_cast<std::size_t>(e)] = 0.0;
      B.v0[static_cast<std::size_t>(b1)] = -1.0;
      KernelSettings ks;
      ks.substeps = substeps;
      ks.energy = true;
      const ContactModel groups[] = {law(ContactLaw::hertzdamp)};
      SystemResult r;
      run_system(B, groups, GroundMotion{0.01, std::vector<double>(11, 0.0), 0.0}, ks, r);  // 0.1 s
      ASSERT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok));
      EXPECT_EQ(r.impact_count[static_cast<std::size_t>(e)], 1);
      double p = 0, dissipated = 0;
      for (int d = 0; d < S.ndof(); ++d) p += B.m[static_cast<std::size_t>(d)] * r.final_v[static_cast<std::size_t>(d)];
      for (double x : r.contact_energy) dissipated += x;
      const double e0 = 0.5 * 1.2e5;
      const double e1 = r.e_kinetic[0] + r.e_strain[0] + r.e_viscous[0] + r.e_hysteretic[0] + r.e_contact_stored[0] +
                        dissipated - r.e_input[0];
      errors.push_back(std::abs(e1 - e0) / e0);
      rebound.push_back(r.final_v[static_cast<std::size_t>(b1)]), momentum.push_back(p);
      EXPECT_LT(errors.back(), 1e-12) << c.label << " energy balance at h = dt/" << substeps;
      if (!c.ground) {
        EXPECT_NEAR(p, -1.2e5, 1.2e5 * 1e-12) << "momentum at h = dt/" << substeps;
      } else {
        EXPECT_GT(std::abs(p + 1.2e5), 1e3) << "the support takes a share";
      }
      EXPECT_GT(dissipated, 0.1 * e0);  // e = 0.65: about 1 - e^2 of the approach's energy
      std::printf("%s h = dt/%d: energy balance %.3e, momentum %.15g, dissipated %.4g J\n", c.label, substeps,
                  errors.back(), p, dissipated);
    }
    for (std::size_t i = 0; i + 2 < rebound.size(); ++i) {
      const double q = std::abs(rebound[i] - rebound[i + 1]) / std::abs(rebound[i + 1] - rebound[i + 2]);
      std::printf("%s: rebound velocity change ratio %.2f per halving\n", c.label, q);
      EXPECT_GT(q, 3.0) << c.label << ": halving " << i;
      if (c.ground) {
        EXPECT_GT(std::abs(momentum[i] - momentum[i + 1]) / std::abs(momentum[i + 1] - momentum[i + 2]), 3.0) << i;
      }
    }
    EXPECT_GT(rebound.back(), 0.0) << c.label << ": B's floor bounces back";
  }
}

namespace {

// A side of element `c` in the reference's terms: a floor [body, floor] or a column {"column": [body, lo, hi], "xi"}.
std::string side_json(const model::System& S, const model::Side& s, double xi) {
  auto where = [&](int dof, int& body, int& floor) {
    for (std::size_t b = 0; b < S.bodies().size(); ++b)
      for (std::size_t k = 0; k < S.bodies()[b].dofs.size(); ++k)
        if (S.bodies()[b].dofs[k] == dof) body = static_cast<int>(b), floor = static_cast<int>(k) + 1;
  };
  int b = 0, f = 0;
  where(s.kind == model::SideKind::point ? s.p : s.q, b, f);
  if (s.kind == model::SideKind::point) return fmt::format("[{}, {}]", b, f);
  return fmt::format(R"({{"column": [{}, {}, {}], "xi": {:.17g}}})", b, f - 1, f, xi);
}

}  // namespace

// Against an independent SciPy solution (tools/reference_systems.py system with column sides: its own assembly, the
// contact force on each side's floors with the side's weights, solve_ivp DOP853 with event-located onsets): A 3
// storeys of 3.0 m and B 2 of 3.5 m (Rayleigh-damped elastic storeys) pounding with Hertzdamp at four floor-to-column
// elements -- A's floors at 3 and 6 m on B's columns 0-1 (the ground end) and 1-2, B's at 3.5 and 7 m on A's columns
// 1-2 and 2-3 -- under 3 s of a two-tone ground motion: at h = dt/80 the peak floor displacements within 1e-3, the
// impact count per element equal, the peak force per element within 1e-3 (sampled on the engine's grid; measured 6e-6); the
// peak displacements converge at second order (2 +- 0.4 over the first halving).
TEST(FloorColumn, AgainstSolveIvp) {
  if (!have_scipy()) POUNDING_SKIP_OR_FAIL("needs " + python() + " with numpy and scipy (tools/setup.sh)");
  const double dt = 0.01;
  const std::vector<double> ag = two_tone(3.0, dt, 4.0, 3.0);
  const std::vector<int> grids{20, 40, 80};
  const double gap = 0.002, kc = 1.0e10, e = 0.65;
  const std::vector<test::Stick> sticks{numbers({3.0e5, 3.0e5, 2.5e5}, {4.0e8, 3.6e8, 3.0e8}, 0.7, 0.0015),
                                        numbers({2.5e5, 2.0e5}, {1.0e8, 0.8e8}, 0.4, 0.003)};
  const std::vector<model::StickTopology> ab{stick(3, 3.0), stick(2, 3.5)};
  const model::System S = model::shear_buildings(ab);
  ASSERT_EQ(S.contacts().size(), 4u);
  std::string contacts;
  for (std::size_t k = 0; k < S.contacts().size(); ++k) {
    const model::ContactElement& c = S.contacts()[k];
    contacts += fmt::format(R"({}{{"left": {}, "right": {}, "gap": {}, "kc": {}, "n": 1.5, "e": {}, "v0_min": 0.001}})",
                            k ? ", " : "", side_json(S, c.left, c.xi), side_json(S, c.right, c.xi), gap, kc, e);
  }
  const Reference R = run_reference(fmt::format(
      R"({{"mode": "nonlinear", "dt": {:.17g}, "ag": [{:.17g}], "duration": {:.17g}, "substeps": [{}], "bodies": [{}, {}], "contacts": [{}]}})",
      dt, fmt::join(ag, ", "), dt * static_cast<double>(ag.size() - 1), fmt::join(grids, ", "), body_json(sticks[0]),
      body_json(sticks[1]), contacts));
  const ContactModel groups[] = {law(ContactLaw::hertzdamp)};
  std::vector<double> e_disp;
  int total = 0;
  for (int g : grids) {
    SystemBatch B;
    B.resize(S, 1);
    for (int b = 0; b < 2; ++b) test::fill_stick(B, b, 0, sticks[static_cast<std::size_t>(b)]);
    set_contacts(B, 0, gap, kc, e);
    KernelSettings ks;
    ks.substeps = g;
    SystemResult r;
    run_system(B, groups, GroundMotion{dt, ag, 0.0}, ks, r);
    ASSERT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok)) << "h = dt/" << g;
    double ed = 0;
    for (int b = 0; b < 2; ++b)
      for (int f = 1; f <= (b == 0 ? 3 : 2); ++f) {
        const int dof = S.bodies()[static_cast<std::size_t>(b)].dofs[static_cast<std::size_t>(f - 1)];
        const double pu = R.peak_u.at({g, b, f}), x = r.peak_u[static_cast<std::size_t>(dof)];
        ed = std::max(ed, std::abs(x - pu) / pu);
        if (g == grids.back()) {
          EXPECT_NEAR(x, pu, 1e-3 * pu) << "building " << b + 1 << " floor " << f;
        }
      }
    e_disp.push_back(ed);
    std::printf("h = dt/%-3d peak |u| error %.3g (relative, worst floor)\n", g, ed);
    if (g != grids.back()) continue;
    for (std::size_t k = 0; k < S.contacts().size(); ++k) {
      const int n = R.impacts.at(static_cast<int>(k));
      EXPECT_EQ(r.impact_count[k], n) << S.contacts()[k].label;
      if (n > 0) {
        const double pf = R.peak_force.at({g, static_cast<int>(k)});
        EXPECT_NEAR(r.peak_force[k], pf, 1e-3 * pf) << S.contacts()[k].label;
        std::printf("%-20s %d impacts (reference %d), peak force %.6g N (reference %.6g N)\n",
                    S.contacts()[k].label.c_str(), r.impact_count[k], n, r.peak_force[k], pf);
      }
      total += n;
    }
  }
  std::printf("observed order of the peak |u| error: %.2f, %.2f\n", std::log2(e_disp[0] / e_disp[1]),
              std::log2(e_disp[1] / e_disp[2]));
  EXPECT_NEAR(std::log2(e_disp[0] / e_disp[1]), 2.0, 0.4);
  EXPECT_GE(total, 3) << "the buildings must pound at floor-to-column elements";
}
