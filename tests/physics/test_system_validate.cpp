// physics::validate(const SystemBatch&, ...) (docs/architecture.md §2.2.7, issue 25 step 2): every value problem
// of a lane, the group and stepper checks, the structure's highest frequency against central difference's
// limit with damping h^2 omega^2 + 4 h (2 zeta omega) < 4 (Gershgorin bounds; structure_step_max, checked against
// the spectral radius of the stepper's one-step matrix), and the SDOF pair's unchanged checks.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "kernel_test_support.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/physics/system_stepper.hpp"
#include "pounding/physics/validate.hpp"

namespace pounding::physics {
namespace {

using model::System;

// A 3-storey building left of a 5-storey one, level-major (test_system.cpp writes the same by hand), storey
// springs in DOF order, one element per common level.
System three_and_five() {
  System::Parts p;
  p.bodies.resize(2);
  p.bodies[0].label = "building1", p.bodies[1].label = "building2";
  int d = 0;
  for (int level = 1; level <= 5; ++level)
    for (int b = 0; b < 2; ++b)
      if (level <= (b == 0 ? 3 : 5)) {
        p.bodies[static_cast<std::size_t>(b)].dofs.push_back(d++);
        p.bodies[static_cast<std::size_t>(b)].heights.push_back(3.0 * level);
      }
  p.springs.resize(8);
  for (int b = 0; b < 2; ++b) {
    const model::Body& body = p.bodies[static_cast<std::size_t>(b)];
    for (std::size_t k = 0; k < body.dofs.size(); ++k)
      p.springs[static_cast<std::size_t>(body.dofs[k])] = {k == 0 ? model::ground : body.dofs[k - 1], body.dofs[k], 0,
                                                           model::SpringRole::storey, b, static_cast<int>(k) + 1};
  }
  p.bodies[1].storey_dashpots = true;
  for (int level = 1; level <= 3; ++level)
    p.contacts.push_back({{model::SideKind::point, 2 * level - 2, -1, 0},
                          {model::SideKind::point, 2 * level - 1, -1, 0}, 0, level, "level " + std::to_string(level)});
  p.groups.push_back({});
  return System::build(p);
}

// Uniform storeys m = 2e5 kg, k (N/m), Hertzdamp kc = 1e9, e = 0.6, gap 0.02 m, in `lanes` lanes.
SystemBatch uniform(const System& s, std::size_t lanes, double k = 3e8) {
  SystemBatch b;
  b.resize(s, lanes);
  for (double& m : b.m) m = 2e5;
  for (double& c : b.c_floor) c = 1e4;
  for (double& c : b.c_storey) c = 1e5;
  for (SpringSpec& sp : b.spring) sp = {k, 1e6, 0.05};
  for (double& g : b.gap) g = 0.02;
  for (double& kc : b.kc) kc = 1e9;
  for (double& e : b.e) e = 0.6;
  return b;
}

struct Fixture {
  System sys = three_and_five();
  std::vector<ContactModel> models{test::contact(ContactLaw::hertzdamp)};
  std::vector<double> ag = std::vector<double>(11, 0.0);
  GroundMotion gm{0.01, ag, 0.0};
  KernelSettings ks;
  std::vector<Problem> check(const SystemBatch& b) const { return validate(b, models, gm, ks); }
};

::testing::AssertionResult first_is(const std::vector<Problem>& ps, const std::string& what, const std::string& where) {
  if (ps.empty()) return ::testing::AssertionFailure() << "no problem";
  if (ps[0].what.find(what) == std::string::npos || ps[0].where.find(where) == std::string::npos)
    return ::testing::AssertionFailure() << "first problem: " << ps[0].what << " | " << ps[0].where << " | " << ps[0].fix;
  return ::testing::AssertionSuccess();
}

TEST(SystemValidate, GoodBatchPasses) {
  Fixture f;
  EXPECT_TRUE(f.check(uniform(f.sys, 4)).empty());
}

TEST(SystemValidate, EveryLaneValueIsChecked) {
  Fixture f;
  const std::size_t w = 4;
  auto at = [&](int i, std::size_t lane) { return SystemBatch::at(i, lane, w); };
  SystemBatch b = uniform(f.sys, w);
  b.m[at(7, 2)] = 0.0;  // building2's roof in lane 2
  EXPECT_TRUE(first_is(f.check(b), "m = 0 must be positive", "m (building2 floor 5, lane 2)"));
  b = uniform(f.sys, w), b.c_floor[at(4, 1)] = -1.0;
  EXPECT_TRUE(first_is(f.check(b), "c = -1 must be >= 0", "c (building1 floor 3, lane 1)"));
  b = uniform(f.sys, w), b.u0[at(0, 0)] = NAN;
  EXPECT_TRUE(first_is(f.check(b), "must be finite", "u0 (building1 floor 1, lane 0)"));
  b = uniform(f.sys, w), b.spring[at(3, 3)].k = 0.0;  // a system's storey needs k > 0 (the pair allows 0)
  EXPECT_TRUE(first_is(f.check(b), "k = 0 must be positive", "k (building2 storey 2, lane 3)"));
  b = uniform(f.sys, w), b.spring[at(3, 3)].fy = 0.0;
  EXPECT_TRUE(first_is(f.check(b), "fy = 0 must be positive", "fy (building2 storey 2, lane 3)"));
  b = uniform(f.sys, w), b.spring[at(6, 0)].alpha = 1.0;
  EXPECT_TRUE(first_is(f.check(b), "alpha = 1 is out of range", "alpha (building2 storey 4, lane 0)"));
  b = uniform(f.sys, w), b.c_storey[at(5, 0)] = -2.0;
  EXPECT_TRUE(first_is(f.check(b), "c_storey = -2 must be >= 0", "c_storey (building2 storey 3, lane 0)"));
  b = uniform(f.sys, w), b.gap[at(2, 1)] = INFINITY;
  EXPECT_TRUE(first_is(f.check(b), "gap = inf must be >= 0", "gap (contact 'level 3', lane 1)"));
  b = uniform(f.sys, w), b.weight[at(1, 1)] = 1.5;
  EXPECT_TRUE(first_is(f.check(b), "weight = 1.5 is out of range", "weight (contact 'level 2', lane 1)"));
  b = uniform(f.sys, w), b.kc[at(0, 2)] = 0.0;
  EXPECT_TRUE(first_is(f.check(b), "kc = 0 must be positive", "kc (contact 'level 1', lane 2)"));
  b = uniform(f.sys, w), b.e[at(0, 2)] = 0.0;
  EXPECT_TRUE(first_is(f.check(b), "e = 0 is out of range", "e (contact 'level 1', lane 2)"));
  // the law's traits decide: no contact law needs neither kc nor e
  f.models[0] = test::contact(ContactLaw::none);
  EXPECT_TRUE(f.check(b).empty());
}

// A model stands only where its roles allow (model/hysteresis/registry.hpp): a restrainer (a tension-gap link) as a
// storey spring is refused before a run, naming the spring, its role and the model; as a storey, bilinear is fine.
TEST(SystemValidate, AModelOutsideItsRolesIsRefused) {
  Fixture f;
  System::Parts p = f.sys.parts();
  p.springs[3].law = model::law_of<model::TensionGap>;
  const System wrong = System::build(p);
  const SystemBatch b = uniform(wrong, 4);
  const std::vector<Problem> ps = system_stepper_problems(b, f.models, f.ks);
  ASSERT_FALSE(ps.empty());
  EXPECT_NE(ps[0].what.find("spring 3 is a storey spring of the"), std::string::npos) << ps[0].what;
  EXPECT_NE(ps[0].what.find("which does not play that role"), std::string::npos) << ps[0].what;
  EXPECT_TRUE(system_stepper_problems(uniform(f.sys, 4), f.models, f.ks).empty());
}

TEST(SystemValidate, GroupsStepperAndLaws) {
  Fixture f;
  const SystemBatch b = uniform(f.sys, 2);
  f.models.push_back(test::contact(ContactLaw::linear));
  EXPECT_TRUE(first_is(f.check(b), "2 contact models for 1 contact groups", "contact groups"));
  f.models.pop_back();
  f.models[0] = test::contact(ContactLaw::stereomechanical);
  EXPECT_TRUE(first_is(f.check(b), "defined for one contact element, and the system has 3", "group 'pounding'"));
  f.models[0] = test::contact(ContactLaw::hertzdamp);
  f.models[0].n = 4.0;
  EXPECT_TRUE(first_is(f.check(b), "Hertz exponent n = 4 is out of range", "Hertz exponent n"));
  f.models[0].n = 1.5;
  f.ks.stepper = Stepper::nigam_jennings;  // Newmark and RK4 run systems (issue 25 step 5); NJ does not (D7)
  EXPECT_TRUE(first_is(f.check(b), "nigam-jennings integrates SDOF bodies only", "stepper"));
  f.ks.stepper = Stepper::central_difference;
  f.ks.substeps = 0;
  EXPECT_TRUE(first_is(f.check(b), "substeps = 0 must be >= 1", "substeps"));
}

// Uniform stick: Gershgorin gives omega_max^2 <= 4 k / m (an interior floor: 2k on the diagonal, k each side),
// above the true top mode 2 sqrt(k/m) sin(9 pi / 22) of the 5-storey stick (SB §1). With k = 3e9, m = 2e5:
// omega_max <= 244.95 rad/s; dt = 0.01 s gives h omega = 2.449 >= 2, and 2 substeps give 1.22 < 2.
TEST(SystemValidate, StructureFrequencyAgainstCentralDifference) {
  Fixture f;
  SystemBatch b = uniform(f.sys, 3, 3e9);
  for (std::size_t l = 0; l < 3; ++l)
    if (l != 1)
      for (int s = 0; s < 8; ++s) b.spring[SystemBatch::at(s, l, 3)].k = 3e8;  // lanes 0 and 2 are fine
  const std::vector<Problem> ps = f.check(b);
  ASSERT_TRUE(first_is(ps, "too long for the structure's highest frequency", "substeps (lane 1)"));
  EXPECT_NE(ps[0].what.find("244.949"), std::string::npos) << ps[0].what;
  EXPECT_NE(ps[0].what.find("largest at building1 floor 2"), std::string::npos) << ps[0].what;
  EXPECT_EQ(ps[0].fix, "give substeps >= 2 (or a smaller dt)");
  f.ks.substeps = 2;
  EXPECT_TRUE(f.check(b).empty());
  // the bound is above the true top frequency, and the true one would be stable at 1 substep only below 2/omega
  const double top = 2.0 * std::sqrt(3e9 / 2e5) * std::sin(9.0 * test::pi / 22.0);
  EXPECT_LT(top, std::sqrt(4.0 * 3e9 / 2e5));
  EXPECT_GT(0.01 * top, 2.0);  // so the refusal at 1 substep is no false alarm here
}

// The damped limit: building2's storey dashpots of c = 5e6 N s/m on k = 3e8, m = 2e5 (stiffness-proportional
// a1 = 1/60 s) leave h omega_max = 0.77 < 2 at dt = 0.01, the check without damping passed it; Gershgorin gives
// 2 zeta omega <= 4 c / m + the floor dashpot = 100.05 1/s and omega_max^2 <= 4 k / m, so h <= 2 / (C + sqrt(C^2 + 6000)) = 0.008827 s.
// No false alarm: the true top mode of the 5-storey stick (omega = 74.3 rad/s, 2 zeta omega = a1 omega^2 = 92 1/s)
// alone needs h < 0.0095 s.
TEST(SystemValidate, StoreyDashpotsShortenTheStableStep) {
  Fixture f;
  SystemBatch b = uniform(f.sys, 2);
  for (int s = 3; s < 8; ++s) b.c_storey[SystemBatch::at(s, 1, 2)] = 5e6;  // building2's storeys in lane 1
  const std::vector<Problem> ps = f.check(b);
  ASSERT_TRUE(first_is(ps, "too long for the structure's highest frequency and damping", "substeps (lane 1)"));
  EXPECT_NE(ps[0].what.find("h <= 0.008827 s"), std::string::npos) << ps[0].what;
  EXPECT_EQ(ps[0].fix, "give substeps >= 2 (or a smaller dt)");
  const double top = 2.0 * std::sqrt(3e8 / 2e5) * std::sin(9.0 * test::pi / 22.0), a1 = 5e6 / 3e8;
  const double x = a1 * top * top;
  EXPECT_LT(2.0 / (x + std::sqrt(x * x + top * top)), 0.01);  // the true top mode is unstable at 0.01 s too
  f.ks.substeps = 2;
  EXPECT_TRUE(f.check(b).empty());
}

// One DOF on a ground spring k = omega^2 m, damped by a floor dashpot or a storey dashpot c = 2 zeta omega m.
System one_dof(bool storey_dashpot) {
  System::Parts p;
  p.bodies.resize(1);
  p.bodies[0].label = "building1", p.bodies[0].dofs = {0}, p.bodies[0].heights = {3.0};
  p.bodies[0].storey_dashpots = storey_dashpot;
  p.springs.push_back({model::ground, 0, 0, model::SpringRole::storey, 0, 1});
  p.groups.push_back({});
  return System::build(p);
}

// The spectral radius of the system stepper's one-step matrix on (u, v, a) for one mode (the step of
// steppers/system_central_difference.hpp: vh = v + h/2 a, u += h vh, vp = vh + h/2 a, a = -omega^2 u - c vp,
// v = vh + h/2 a), written here from the step, not from the bound.
double radius(double h, double omega, double c) {
  Eigen::Matrix3d A;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d x = Eigen::Vector3d::Unit(k);
    const double vh = x[1] + h / 2 * x[2], u1 = x[0] + h * vh, vp = vh + h / 2 * x[2];
    const double a1 = -omega * omega * u1 - c * vp;
    A.col(k) << u1, vh + h / 2 * a1, a1;
  }
  return A.eigenvalues().cwiseAbs().maxCoeff();
}

// structure_step_max against the largest h with spectral radius <= 1 (bisection on the one-step matrix), for an
// SDOF where Gershgorin's bounds are exact (W = omega, C = 2 zeta omega): the bound IS the stability limit there.
TEST(SystemValidate, StepBoundIsTheDampedCentralDifferenceLimit) {
  for (const bool storey : {false, true})
    for (const auto& [omega, zeta] : {std::pair{6.0, 0.02}, {80.0, 0.05}, {500.0, 0.2}, {3000.0, 1.0}}) {
      const System sys = one_dof(storey);
      SystemBatch b;
      b.resize(sys, 1);
      b.m[0] = 2e5, b.spring[0] = {omega * omega * 2e5, 1e9, 0.0};
      (storey ? b.c_storey[0] : b.c_floor[0]) = 2.0 * zeta * omega * 2e5;
      const StructureStep s = structure_step_max(b, 0, Stepper::central_difference);
      const double c = 2.0 * zeta * omega;
      double lo = 0.0, hi = 10.0 / omega;
      for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (radius(mid, omega, c) <= 1.0 + 1e-12 ? lo : hi) = mid;
      }
      SCOPED_TRACE(::testing::Message() << "omega " << omega << " zeta " << zeta << (storey ? " storey" : " floor"));
      EXPECT_NEAR(s.h_max, lo, 1e-9 * lo);
      EXPECT_NEAR(s.omega_max, omega, 1e-12 * omega);
      EXPECT_NEAR(s.damping, c, 1e-12 * c);
      EXPECT_LE(radius(0.999 * s.h_max, omega, c), 1.0 + 1e-12);  // just inside: bounded
      EXPECT_GT(radius(1.001 * s.h_max, omega, c), 1.0 + 1e-6);   // just outside: grows
      EXPECT_LT(s.h_max, 2.0 / omega);  // damping shortens it below the undamped 2 / omega
      // the substeps it advises are the fewest that reach inside
      const double dt = 0.01, n = s.substeps(dt);
      EXPECT_LT(dt / n, s.h_max);
      if (n > 1) {
        EXPECT_GE(dt / (n - 1), s.h_max);
      }
    }
}

// The pair keeps today's validation: the same problems as the PairBatch's, and no frequency check (its stiff
// lanes are caught by the divergence guard in the run, as today).
TEST(SystemValidate, PairGetsTodaysChecks) {
  const System pair = System::sdof_pair();
  PairBatch pb;
  pb.resize(3);
  for (std::size_t l = 0; l < 3; ++l) {
    PairParams p;
    p.s1 = Structure::from_period(1e5, 0.5, 0.05);
    p.s2 = Structure::from_period(1e5, 0.001, 0.05);  // h omega = 62.8 at dt = 0.01: not refused for the pair
    p.gap = 0.01, p.kc = 1e9, p.e = 0.7;
    pb.set(l, p);
  }
  std::vector<double> ag(11, 0.0);
  GroundMotion gm{0.01, ag, 0.0};
  KernelSettings ks;
  const std::vector<ContactModel> models{test::contact(ContactLaw::hertzdamp)};
  EXPECT_TRUE(validate(to_system(pb, pair), models, gm, ks).empty());
  pb.gap[2] = -1.0, pb.k1[2] = 0.0;  // the pair allows k = 0
  const std::vector<Problem> want = validate(pb, models[0], gm, ks);
  ASSERT_EQ(want.size(), 1u);
  EXPECT_EQ(validate(to_system(pb, pair), models, gm, ks), want);
}

}  // namespace
}  // namespace pounding::physics
