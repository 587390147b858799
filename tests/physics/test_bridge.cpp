// Bridge chains in the system stepper (issue 26 §1, §5; physics/bridge.hpp): link springs act on both of their DOFs
// (a restrainer's peak opening against the energy closed form), the energy balance of the four-frame bridge with
// restrainers, hinge bearings, abutments (both backfill laws) and Q-Hyst frames closes and converges at second order
// in the step, and the builder's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <vector>

#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/workloads/workloads.hpp"
#include "pounding/physics/bridge.hpp"
#include "pounding/core/error.hpp"
#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/sampling/bridge.hpp"
#include "pounding/contact/restitution.hpp"

using namespace pounding;
using namespace pounding::physics;

namespace {

constexpr double kip = 4448.2216152605, inch = 0.0254;

// Muthukumar & DesRoches' four-frame bridge (seeds-models.md §4): frames 2880/7080/7080/2880 kips, periods 0.47 and
// 1.12 s, yield 774 / 1824 kips, 1/2 in hinge gaps, restrainers 200 kips/in and 840 kips (R2 half), 5 % hardening,
// slack = gap; hinge bearings 6 kips/in, 2.4 kips, 33 %. Abutments (not stated in the paper): `backfill` with
// k_p = 2600 kips/in after a 1 in gap, capacity 2000 kips, and a hinge bearing each.
BridgeSpec four_frames(Backfill backfill, bool qhyst) {
  BridgeSpec b;
  const double w[] = {2880, 7080, 7080, 2880}, T[] = {0.47, 1.12, 1.12, 0.47}, fy[] = {774, 1824, 1824, 774};
  for (int k = 0; k < 4; ++k) {
    BridgeFrame f;
    f.mass = w[k] * kip / 9.80665, f.period = T[k], f.zeta = 0.05, f.fy = fy[k] * kip, f.alpha = 0.0, f.qhyst = qhyst;
    if (!qhyst) f.alpha = 0.02;
    b.frames.push_back(f);
  }
  for (int k = 0; k < 3; ++k) {
    BridgeJoint j;
    j.gap = 0.5 * inch, j.kc = 888e3 / std::pow(1e-3, 1.5), j.e = 0.6;  // 888 kN/mm^1.5 (sphere rule, seeds §4)
    const double r = k == 1 ? 0.5 : 1.0;
    j.restrainer = model::TensionGap::Spec{r * 200 * kip / inch, r * 840 * kip, 0.05, 0.5 * inch, 1};
    j.bearing = BridgeBilinear{6 * kip / inch, 2.4 * kip, 0.33};
    b.joints.push_back(j);
  }
  for (BridgeAbutment* a : {&b.left, &b.right}) {
    a->backfill = backfill;
    a->epp = {2600 * kip / inch, 2000 * kip, 0.0, 1.0 * inch, 1};
    a->hyperbolic = {2600 * kip / inch, 2600 * kip / inch, 0.7, 2000 * kip, 1.0 * inch, 1};
    a->bearing = BridgeBilinear{6 * kip / inch, 2.4 * kip, 0.33};
  }
  return b;
}

struct Energy { double input, out, hysteretic, contact; int impacts; SystemResult r; };
Energy run_energy(const BridgeSpec& spec, int substeps, double scale) {
  const model::System S = bridge_system(spec);
  SystemBatch B;
  B.resize(S, 1);
  set_bridge(B, 0, spec);
  ContactModel hd;
  hd.law = ContactLaw::hertzdamp;
  const ContactModel groups[] = {hd};
  std::vector<double> ag = pounding::builtin_motion(0.01, 10.0);
  for (double& a : ag) a *= scale;
  KernelSettings ks;
  ks.substeps = substeps, ks.energy = true;
  Energy e{};
  run_system(B, groups, GroundMotion{0.01, ag, 0.0}, ks, e.r);
  double dissipated = 0;
  for (std::size_t k = 0; k < S.contacts().size(); ++k) dissipated += e.r.contact_energy[k], e.impacts += e.r.impact_count[k];
  e.input = e.r.e_input[0], e.hysteretic = e.r.e_hysteretic[0], e.contact = dissipated;
  e.out = e.r.e_kinetic[0] + e.r.e_strain[0] + e.r.e_viscous[0] + e.r.e_hysteretic[0] + e.r.e_contact_stored[0] + dissipated;
  return e;
}

}  // namespace

// Two equal undamped frames thrown apart (v0 = -v, +v) against an elastic restrainer with slack s: the link pulls
// both (each sees its force; before issue 26 the stepper refused link springs), and the peak opening 2x satisfies
// energy conservation m v^2 = k x^2 + kr (2x - s)^2 / 2 -- central difference conserves it to O(h^2).
TEST(Bridge, RestrainerPullsBothFramesPeakOpeningFromEnergy) {
  BridgeSpec b;
  for (int k = 0; k < 2; ++k) {
    BridgeFrame f;
    f.mass = 1e6, f.stiffness = 4e7, f.zeta = 0.0;
    b.frames.push_back(f);
  }
  BridgeJoint j;
  j.gap = 0.05, j.kc = 1e9, j.e = 1.0;
  j.restrainer = model::TensionGap::Spec{2e8, INFINITY, 0.0, 0.02, 1};
  b.joints.push_back(j);
  const model::System S = bridge_system(b);
  SystemBatch B;
  B.resize(S, 1);
  set_bridge(B, 0, b);
  const double v = 0.5;
  B.v0[0] = -v, B.v0[1] = v;
  ContactModel none;
  none.law = ContactLaw::none;
  const ContactModel groups[] = {none};
  // 0.2 s: the opening swing (the restrainer takes up its slack at 0.02 s and brings the frames back through zero
  // before 0.19 s); after it the frames swing freely towards each other (no contact law), to 0.079 m
  const std::vector<double> ag(41, 0.0);
  KernelSettings ks;
  ks.substeps = 20;
  SystemResult r;
  run_system(B, groups, GroundMotion{0.005, ag, 0.0}, ks, r);
  ASSERT_EQ(r.status[0], 0);
  // k x^2 + kr/2 (2x - s)^2 = m v^2: (k + 2 kr) x^2 - 2 kr s x + kr s^2 / 2 - m v^2 = 0
  const double m = 1e6, k = 4e7, kr = 2e8, s = 0.02;
  const double A = k + 2 * kr, Bq = -2 * kr * s, C = kr * s * s / 2 - m * v * v;
  const double x = (-Bq + std::sqrt(Bq * Bq - 4 * A * C)) / (2 * A);
  EXPECT_NEAR(r.peak_u[0], x, 1e-4 * x);
  EXPECT_NEAR(r.peak_u[1], x, 1e-4 * x);
  EXPECT_NEAR(r.peak_spring_force[2], kr * (2 * x - s), 2e-4 * kr * (2 * x - s));  // the restrainer (spring 2)
  EXPECT_NEAR(r.peak_drift[2], 2 * x, 1e-4 * x);
  // without the restrainer each frame swings freely, u = v sqrt(m / k) sin(omega t)
  BridgeSpec free = b;
  free.joints[0].restrainer.reset();
  const model::System F = bridge_system(free);
  SystemBatch BF;
  BF.resize(F, 1);
  set_bridge(BF, 0, free);
  BF.v0[0] = -v, BF.v0[1] = v;
  SystemResult rf;
  run_system(BF, groups, GroundMotion{0.005, ag, 0.0}, ks, rf);
  const double free_u = v * std::sqrt(m / k) * std::sin(std::sqrt(k / m) * 0.2);  // still rising at 0.2 s
  EXPECT_NEAR(rf.peak_u[0], free_u, 1e-4 * free_u);
  EXPECT_LT(r.peak_u[0], 0.5 * rf.peak_u[0]);
}

// A frame pushed into an abutment wall (EPP backfill after the gap) and a frame pulled against the other one: the
// wall's link acts on its one DOF with the sign of its side.
TEST(Bridge, AbutmentResistsOnlyTowardsItsWall) {
  BridgeSpec b;
  BridgeFrame f;
  f.mass = 1e6, f.stiffness = 1e6, f.zeta = 0.0;
  b.frames = {f};
  b.right.backfill = Backfill::epp;
  b.right.epp = {1e9, INFINITY, 0.0, 0.01, 1};
  const model::System S = bridge_system(b);
  ASSERT_EQ(S.springs().size(), 2u);
  SystemBatch B;
  B.resize(S, 1);
  set_bridge(B, 0, b);
  B.v0[0] = 1.0;  // towards the right wall: bounces back from about the gap
  const std::vector<double> ag(101, 0.0);
  KernelSettings ks;
  ks.substeps = 50;
  SystemResult r;
  run_system(B, {}, GroundMotion{0.01, ag, 0.0}, ks, r);
  // the wall (k = 1e9) stops it within 1e6 * 1^2 = 1e9 x^2 + ...: x - gap ~ sqrt(m/kw) v = 0.0316
  // the wall (k_w = 1e9) stops it: 0.5 m v^2 = 0.5 k_w delta^2 (+ the frame's own spring, 1e-3 of it), F = k_w delta
  EXPECT_NEAR(r.peak_spring_force[1], 1e9 * std::sqrt(1e6 / 1e9), 2e-3 * 3.16e7);
  B.v0[0] = -0.5;  // away from it: nothing but the frame, u = -0.5 sin(t) (omega = 1 rad/s) over 1 s
  run_system(B, {}, GroundMotion{0.01, ag, 0.0}, ks, r);
  EXPECT_EQ(r.peak_spring_force[1], 0.0);
  EXPECT_NEAR(r.peak_u[0], 0.5 * std::sin(1.0), 1e-4);
}

// The four-frame bridge (Q-Hyst frames, restrainers, bearings, Hertzdamp joints, abutments) under the built-in
// motion scaled to 1.5: the energy balance (input = kinetic + strain + viscous + hysteretic + contact stored +
// contact dissipated) closes, its residual falls at second order with the step (links dissipate by the trapezoid
// rule), and every mechanism works (joints hit, restrainers yield, abutments engage).
TEST(Bridge, FourFrameEnergyBalanceConvergesSecondOrder) {
  for (Backfill bf : {Backfill::epp, Backfill::hyperbolic}) {
    const BridgeSpec spec = four_frames(bf, true);
    std::vector<double> res;
    for (int sub : {20, 40, 80}) {
      const Energy e = run_energy(spec, sub, 1.5);
      ASSERT_EQ(e.r.status[0], 0);
      res.push_back(std::abs(e.input - e.out) / e.input);
      std::printf("%s substeps %d: input %.6g J, hysteretic %.4g, contact %.4g, impacts %d, residual %.3g; frame peaks "
                  "%.4g %.4g %.4g %.4g m; restrainer peaks %.4g %.4g %.4g N; abutment backfill %.4g %.4g N\n",
                  bf == Backfill::epp ? "EPP" : "hyperbolic", sub, e.input, e.hysteretic, e.contact, e.impacts,
                  res.back(), e.r.peak_u[0], e.r.peak_u[1], e.r.peak_u[2], e.r.peak_u[3], e.r.peak_spring_force[4],
                  e.r.peak_spring_force[6], e.r.peak_spring_force[8], e.r.peak_spring_force[10], e.r.peak_spring_force[12]);
      if (sub == 20) {
        EXPECT_GT(e.impacts, 0);
        EXPECT_GT(e.hysteretic, 0.05 * e.input);
        EXPECT_GT(e.r.peak_spring_force[4] + e.r.peak_spring_force[6] + e.r.peak_spring_force[8], 0.0) << "restrainers";
        EXPECT_GT(e.r.peak_spring_force[10] + e.r.peak_spring_force[12], 0.0) << "abutments";
      }
    }
    EXPECT_LT(res[0], 2e-3);
    const double order = std::log2(res[1] / res[2]);
    std::printf("order %.2f\n", order);
    EXPECT_GT(order, 1.6);
  }
}

TEST(Bridge, CheckRefusesBadNumbers) {
  BridgeSpec b = four_frames(Backfill::epp, true);
  EXPECT_TRUE(check_bridge(b).empty());
  b.frames[1].mass = -1;
  b.joints[0].gap = -0.1;
  b.joints.pop_back();
  const std::vector<Problem> p = check_bridge(b);
  ASSERT_GE(p.size(), 3u);
  bool mass = false, gap = false, joints = false;
  for (const Problem& x : p) {
    mass = mass || x.where == "frames[2] mass";
    gap = gap || x.where == "joints[1] gap";
    joints = joints || x.where == "joints";
  }
  EXPECT_TRUE(mass && gap && joints);
}

namespace {
// Every SystemResult array, element by element, as bytes.
int differing(const SystemResult& a, const SystemResult& b) {
  int n = 0;
  auto cmp = [&](const auto& x, const auto& y) {
    if (x.size() != y.size()) return void(n += 1000);
    for (std::size_t i = 0; i < x.size(); ++i) n += std::memcmp(&x[i], &y[i], sizeof(x[i])) != 0;
  };
  cmp(a.peak_u, b.peak_u), cmp(a.peak_acc, b.peak_acc), cmp(a.final_u, b.final_u), cmp(a.final_v, b.final_v);
  cmp(a.peak_drift, b.peak_drift), cmp(a.peak_spring_force, b.peak_spring_force), cmp(a.peak_closing, b.peak_closing);
  cmp(a.t_peak_closing, b.t_peak_closing), cmp(a.t_first_impact, b.t_first_impact), cmp(a.impact_count, b.impact_count);
  cmp(a.clamp_count, b.clamp_count), cmp(a.peak_force, b.peak_force), cmp(a.peak_penetration, b.peak_penetration);
  cmp(a.contact_energy, b.contact_energy), cmp(a.contact_time, b.contact_time), cmp(a.status, b.status);
  cmp(a.e_input, b.e_input), cmp(a.e_kinetic, b.e_kinetic), cmp(a.e_strain, b.e_strain), cmp(a.e_viscous, b.e_viscous);
  cmp(a.e_hysteretic, b.e_hysteretic), cmp(a.e_contact_stored, b.e_contact_stored);
  return n;
}
SystemResult run_channels(const BridgeSpec& spec, const std::vector<std::vector<double>>& records, int substeps) {
  const model::System S = bridge_system(spec);
  SystemBatch B;
  B.resize(S, 3);  // three lanes: the second and third with other frame masses (lanes stay independent)
  for (std::size_t l = 0; l < 3; ++l) {
    BridgeSpec x = spec;
    for (BridgeFrame& f : x.frames) f.mass *= 1.0 + 0.1 * static_cast<double>(l);
    set_bridge(B, l, x);
  }
  ContactModel hd;
  hd.law = ContactLaw::hertzdamp;
  const ContactModel groups[] = {hd};
  std::vector<GroundMotion> gm;
  for (const auto& r : records) gm.push_back(GroundMotion{0.01, r, 0.0});
  KernelSettings ks;
  ks.substeps = substeps, ks.energy = true;
  SystemResult out;
  run_system(B, groups, std::span<const GroundMotion>(gm), ks, out);
  return out;
}
}  // namespace

// Multi-support input (issue 26 §2): the four-frame bridge with each frame on its own pier (channels 0-3) and the
// abutments on the outer piers' channels, every channel given the same record, gives the uniform-excitation result
// (one channel) to the last bit in every observer and energy term of three lanes -- the cross-channel kinematics add
// exactly zero. Fails before issue 26 §2 (more than one channel was refused).
TEST(Bridge, IdenticalSupportMotionsReproduceUniformInputBitForBit) {
  const BridgeSpec uniform = four_frames(Backfill::hyperbolic, true);
  BridgeSpec multi = uniform;
  for (int k = 0; k < 4; ++k) multi.frames[static_cast<std::size_t>(k)].support = k;
  multi.left.support = 0, multi.right.support = 3;
  ASSERT_EQ(multi.channels(), 4);
  std::vector<double> ag = pounding::builtin_motion(0.01, 10.0);
  for (double& a : ag) a *= 1.5;
  const SystemResult one = run_channels(uniform, {ag}, 20);
  const SystemResult four = run_channels(multi, {ag, ag, ag, ag}, 20);
  ASSERT_EQ(one.status[0], 0);
  EXPECT_GT(one.impact_count[0], 0);
  EXPECT_EQ(differing(one, four), 0);
}

// Total-displacement kinematics: two stiff frames (T = 0.05 s) on two supports, the second record delayed by 0.25 s
// (wave passage), joined by a soft linear link: the frames barely move relative to their piers, so the link's
// deformation follows the supports' differential displacement ug2 - ug1 (integrated here independently, trapezoid and
// Simpson-free cumulative sums of the same baseline-corrected form) -- its peak within 2 %. The energy balance with the
// supports' work through the link closes.
TEST(Bridge, CrossSupportLinkFollowsTheDifferentialGroundDisplacement) {
  BridgeSpec b;
  for (int k = 0; k < 2; ++k) {
    BridgeFrame f;
    f.mass = 1e6, f.period = 0.05, f.zeta = 0.05, f.support = k;
    b.frames.push_back(f);
  }
  BridgeJoint j;
  j.gap = 10.0, j.kc = 1e9, j.e = 1.0;  // never closes
  j.bearing = BridgeBilinear{1e5, INFINITY, 0.0};
  b.joints.push_back(j);
  const double dt = 0.01;
  const std::vector<double> a1 = pounding::builtin_motion(dt, 8.0);
  std::vector<double> a2(a1.size(), 0.0);
  for (std::size_t k = 25; k < a1.size(); ++k) a2[k] = a1[k - 25];
  const SystemResult r = run_channels(b, {a1, a2}, 10);
  ASSERT_EQ(r.status[0], 0);
  // ground displacements on the record grid (the schedule's linear interpolation integrates exactly the same way)
  auto disp = [&](const std::vector<double>& a) {
    std::vector<double> v(a.size(), 0.0), u(a.size(), 0.0);
    for (std::size_t k = 0; k + 1 < a.size(); ++k)
      v[k + 1] = v[k] + 0.5 * dt * (a[k] + a[k + 1]), u[k + 1] = u[k] + dt * v[k] + dt * dt * (2 * a[k] + a[k + 1]) / 6;
    const double T = dt * static_cast<double>(a.size() - 1), vT = v.back(), uT = u.back();
    const double c0 = -2 * vT / T + 6 * uT / (T * T), c1 = 6 * vT / (T * T) - 12 * uT / (T * T * T);
    for (std::size_t k = 0; k < a.size(); ++k) {
      const double t = dt * static_cast<double>(k);
      u[k] -= c0 * t * t / 2 + c1 * t * t * t / 6;
    }
    return u;
  };
  const std::vector<double> u1 = disp(a1), u2 = disp(a2);
  double peak = 0;
  for (std::size_t k = 0; k < u1.size(); ++k) peak = std::max(peak, std::abs(u2[k] - u1[k]));
  ASSERT_GT(peak, 0.01);
  const std::size_t w = 3;  // run_channels' lanes
  EXPECT_NEAR(r.peak_drift[SystemBatch::at(2, 0, w)], peak, 0.02 * peak) << "link deformation vs ug2 - ug1";
  EXPECT_LT(r.peak_u[SystemBatch::at(0, 0, w)], 0.05 * peak);
  const double out = r.e_kinetic[0] + r.e_strain[0] + r.e_viscous[0] + r.e_hysteretic[0] + r.e_contact_stored[0];
  EXPECT_NEAR(r.e_input[0], out, 1e-3 * std::abs(r.e_input[0]) + 1e-6) << "input " << r.e_input[0];
  // one record for a two-channel system is refused
  const model::System S = bridge_system(b);
  SystemBatch B;
  B.resize(S, 1);
  set_bridge(B, 0, b);
  SystemResult x;
  EXPECT_THROW(run_system(B, {}, GroundMotion{dt, a1, 0.0}, KernelSettings{}, x), InputError);
}

// e(v0) in the system stepper (issue 26 §3, KernelSettings::restitution at a joint's onset): two frames on soft
// piers meet once at a joint at approach velocities 0.5, 1.5 and 3 m/s (one lane each); with the calibrated damping
// law each impact delivers the curve's e(v0) (the bridge paper's eq. 15, lindsay2011: 0.956, 0.878, 0.716 --
// different enough that a constant e would fail), and the impact at 0.5 m/s lies outside the preset's valid range
// (0.99-3.13 m/s) and is counted. A constant curve e(v) = 0.65 runs as e = 0.65 (same impacts, velocities to 1e-9).
TEST(Bridge, JointImpactDeliversTheRestitutionOfItsApproachVelocity) {
  BridgeSpec b;
  for (int k = 0; k < 2; ++k) {
    BridgeFrame f;
    f.mass = 1e6, f.stiffness = 1e3, f.zeta = 0.0;  // piers too soft to matter over 0.2 s
    b.frames.push_back(f);
  }
  BridgeJoint j;
  j.gap = 0.0, j.kc = 1e9, j.e = 0.65;
  b.joints.push_back(j);
  const model::System S = bridge_system(b);
  const double vs[] = {0.5, 1.5, 3.0};
  const auto run = [&](const contact::RestitutionCurve* curve, SystemResult& r) {
    SystemBatch B;
    B.resize(S, 3);
    for (std::size_t l = 0; l < 3; ++l) {
      set_bridge(B, l, b);
      B.v0[SystemBatch::at(0, l, 3)] = 0.5 * vs[l], B.v0[SystemBatch::at(1, l, 3)] = -0.5 * vs[l];
    }
    ContactModel cm;
    cm.law = ContactLaw::hertzdamp, cm.damping = DampingLaw::calibrated;
    const ContactModel groups[] = {cm};
    const std::vector<double> ag(41, 0.0);
    KernelSettings ks;
    ks.substeps = 100;
    std::optional<HertzdampRestitution> hook;
    if (curve) ks.restitution = &hook.emplace(*curve, cm).hook;
    run_system(B, groups, GroundMotion{0.005, ag, 0.0}, ks, r);
  };
  contact::RestitutionCurve lindsay;
  ASSERT_TRUE(contact::restitution_preset("lindsay2011", lindsay));
  SystemResult r;
  run(&lindsay, r);
  for (std::size_t l = 0; l < 3; ++l) {
    ASSERT_EQ(r.status[l], 0);
    ASSERT_EQ(r.impact_count[l], 1) << l;
    const double v1 = r.final_v[SystemBatch::at(0, l, 3)], v2 = r.final_v[SystemBatch::at(1, l, 3)];
    const double delivered = (v2 - v1) / vs[l];
    EXPECT_NEAR(delivered, lindsay(vs[l]), 1e-5) << "v0 = " << vs[l];
    EXPECT_EQ(r.restitution_outside[l], l == 0 ? 1 : 0) << l;
  }
  EXPECT_GT(lindsay(0.5) - lindsay(3.0), 0.2);  // the test tells e(v0) from a constant e
  contact::RestitutionCurve constant;
  constant.coefficients = {0.65};
  SystemResult rc, re;
  run(&constant, rc);
  run(nullptr, re);
  for (std::size_t l = 0; l < 3; ++l) {
    EXPECT_EQ(rc.impact_count[l], re.impact_count[l]);
    for (int d = 0; d < 2; ++d)
      EXPECT_NEAR(rc.final_v[SystemBatch::at(d, l, 3)], re.final_v[SystemBatch::at(d, l, 3)], 1e-9) << l << " " << d;
    EXPECT_EQ(re.restitution_outside[l], 0);
  }
}

// Frames as short shear sticks (issue 26 §1): a uniform stick frame of n levels (m per level, k per storey) has the
// closed-form modes of a uniform shear cantilever, omega_j = 2 sqrt(k/m) sin((2j - 1) pi / (2 (2n + 1))); a frame
// given by its period gets T1 = period; the System puts the frame's levels frame-major (deck last), the joint, the
// restrainer and the abutments on the decks, and Rayleigh's storey dashpots on the stick's storeys.
TEST(Bridge, StickFrameModesAreTheUniformStickClosedForm) {
  BridgeFrame f;
  f.storeys = 4, f.mass = 1.2e6, f.stiffness = 3.5e8, f.height = 8.0;
  const ShearNumbers num = frame_numbers(f);
  ASSERT_EQ(num.modes.omega.size(), 4u);
  for (int j = 1; j <= 4; ++j) {
    const double want = 2.0 * std::sqrt(3.5e8 / 1.2e6) * std::sin((2 * j - 1) * M_PI / (2.0 * (2 * 4 + 1)));
    EXPECT_NEAR(num.modes.omega[static_cast<std::size_t>(j - 1)], want, 1e-12 * want) << "mode " << j;
  }
  EXPECT_DOUBLE_EQ(frame_mass(f), 4 * 1.2e6);
  BridgeFrame g = f;
  g.stiffness = 0.0, g.period = 0.8;
  EXPECT_NEAR(frame_period(g), 0.8, 1e-12);
  for (double k : frame_numbers(g).k) EXPECT_DOUBLE_EQ(k, frame_numbers(g).k[0]);  // uniform profile

  BridgeSpec b = four_frames(Backfill::epp, false);
  b.frames[1].storeys = 3, b.frames[1].mass /= 3.0;  // frame 2: three levels of a third of its mass each
  b.frames[2].storeys = 2, b.frames[2].storey_mass = {0.2 * b.frames[2].mass, 0.8 * b.frames[2].mass};
  ASSERT_TRUE(check_bridge(b).empty());
  const BridgeIndex x = bridge_index(b);
  EXPECT_EQ(x.deck, (std::vector<int>{0, 3, 5, 6}));
  const model::System S = bridge_system(b);
  ASSERT_EQ(S.ndof(), 7u);
  EXPECT_EQ(S.bodies()[1].dofs, (std::vector<int>{1, 2, 3}));
  EXPECT_NEAR(S.bodies()[1].heights.back(), b.frames[1].height, 1e-12);
  for (std::size_t e = 0; e < 3; ++e) {
    EXPECT_EQ(S.contacts()[e].left.p, x.deck[e]);
    EXPECT_EQ(S.contacts()[e].right.p, x.deck[e + 1]);
  }
  for (std::size_t j = 0; j < 3; ++j) {
    const model::Spring& r = S.springs()[static_cast<std::size_t>(x.restrainer[j])];
    EXPECT_EQ(r.i, x.deck[j]);
    EXPECT_EQ(r.j, x.deck[j + 1]);
  }
  EXPECT_EQ(S.springs()[static_cast<std::size_t>(x.right_backfill)].j, 6);
  SystemBatch B;
  B.resize(S, 1);
  set_bridge(B, 0, b);
  EXPECT_DOUBLE_EQ(B.m[4] + B.m[5], frame_mass(b.frames[2]));
  EXPECT_GT(B.c_storey[2], 0.0);  // Rayleigh's stiffness part on the stick's storeys
  EXPECT_EQ(B.c_storey[0], 0.0);  // none on an SDOF frame
  EXPECT_NEAR(frame_period(b.frames[1]), 1.12, 1e-12);
}

// A one-level frame is today's SDOF frame bit for bit: k = m (2 pi / T)^2, c = 2 zeta sqrt(k m) as a floor dashpot
// (not the shear building's Structure::from_period), DOF k = frame k, spring k its storey -- and a chain of them runs
// to the same bits whether or not a stick frame shares the batch's layout.
TEST(Bridge, OneLevelStickIsTheSdofFrameBitForBit) {
  const BridgeSpec b = four_frames(Backfill::hyperbolic, true);
  const model::System S = bridge_system(b);
  SystemBatch B;
  B.resize(S, 1);
  set_bridge(B, 0, b);
  for (int k = 0; k < 4; ++k) {
    const BridgeFrame& f = b.frames[static_cast<std::size_t>(k)];
    const double w = 2.0 * M_PI / f.period, kf = f.mass * w * w;
    EXPECT_EQ(S.bodies()[static_cast<std::size_t>(k)].dofs, std::vector<int>{k});
    EXPECT_EQ(B.m[static_cast<std::size_t>(k)], f.mass);
    EXPECT_EQ(B.c_floor[static_cast<std::size_t>(k)], 2.0 * f.zeta * std::sqrt(kf * f.mass));
    EXPECT_EQ(B.spring[static_cast<std::size_t>(k)].k, kf);
    EXPECT_EQ(S.spring_below(k), k);
  }
  BridgeSpec mixed = b;
  mixed.frames[3].storeys = 1;  // explicitly one level: the same chain
  const std::vector<double> ag = pounding::builtin_motion(0.01, 10.0);
  EXPECT_EQ(differing(run_channels(b, {ag}, 20), run_channels(mixed, {ag}, 20)), 0);
}

// A sampled stick frame in a study (sampling/bridge.hpp): the model draws the frame's total mass and T1; the lane's
// frame scales every level mass by m / m0 and every storey stiffness by (m / m0) (T0 / T)^2, so its T1 and total mass
// are the drawn ones and its mass distribution (mode shapes) stays; a one-level frame takes the drawn m and T as before.
TEST(Bridge, SampledStickFrameHasTheDrawnPeriodAndMass) {
  BridgeModel m;
  m.spec = four_frames(Backfill::epp, false);
  BridgeFrame& f = m.spec.frames[1];
  f.storeys = 3, f.storey_mass = {1.0e6, 1.0e6, 2.0e6}, f.period = 1.0;
  ASSERT_TRUE(check_bridge(m.spec).empty());
  m.period_cov = 0.2, m.mass_cov = 0.1, m.reference_gap = 0.5 * inch, m.offsets.assign(3, 0.0);
  const std::vector<double> u = {0.3, 0.7, 0.9, 0.15, 0.4, 0.6, 0.2, 0.8};
  const SampledPair p = bridge_pair(m, SampleId{}, u);
  const BridgeSpec lane = lane_bridge(m, p, m.reference_gap);
  const SampledStructure& s = p.structure(1);
  EXPECT_NE(s.T, 1.0);
  EXPECT_NE(s.m, 4.0e6);
  EXPECT_NEAR(frame_period(lane.frames[1]), s.T, 1e-12 * s.T);
  EXPECT_NEAR(frame_mass(lane.frames[1]), s.m, 1e-9 * s.m);
  ASSERT_EQ(lane.frames[1].storey_mass.size(), 3u);
  EXPECT_NEAR(lane.frames[1].storey_mass[2] / lane.frames[1].storey_mass[0], 2.0, 1e-14);
  EXPECT_EQ(lane.frames[0].mass, p.structure(0).m);  // one level: the drawn numbers themselves
  EXPECT_EQ(lane.frames[0].stiffness, p.structure(0).k);
}
