// Newmark and RK4 on systems (physics/system_lane_stepper.hpp, issue 25 step 5): linear shear buildings against
// SciPy's lsim (tools/reference_systems.py, none of our code) with the convergence order measured; a 3- vs 5-storey
// pair pounding at its common levels: Newmark, RK4 and central difference against solve_ivp with event-located
// onsets and against each other as h halves; the energy balance of a yielding pounding history with each stepper;
// lanes independent of the batch; the refusals (Nigam-Jennings with storeys, laws the lane steppers do not run).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/core/error.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/system_lane_stepper.hpp"
#include "pounding/workloads/workloads.hpp"
#include "system_reference.hpp"
#include "system_test_support.hpp"
#include "test_data.hpp"

using namespace pounding;
using namespace pounding::physics;
using test::body_json;
using test::have_scipy;
using test::python;
using test::Reference;
using test::run_reference;
using test::el_centro;
using test::modal_stick;
using test::order;
using test::run_engine;
using test::stick;

namespace {


ContactModel hertzdamp() {
  ContactModel cm;
  cm.law = ContactLaw::hertzdamp;
  return cm;
}

// Largest |final u - lsim| over the floors of one stick at each grid.
std::vector<double> linear_errors(const model::System& S, const test::Stick& st, const std::vector<double>& ag, double dt,
                                  const std::vector<int>& grids, Stepper stepper, const Reference& R) {
  std::vector<double> err;
  const int n = static_cast<int>(st.m.size());
  for (int g : grids) {
    const SystemResult r = run_engine(S, {st}, ag, dt, g, 0, 0, 1, {}, stepper);
    EXPECT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok));
    double e_final = 0, e_peak = 0;
    for (int f = 1; f <= n; ++f) {
      const int dof = S.bodies()[0].dofs[static_cast<std::size_t>(f - 1)];
      const double pu = R.peak_u.at({g, 0, f}), fu = R.final_u.at({g, 0, f});
      e_peak = std::max(e_peak, std::abs(r.peak_u[static_cast<std::size_t>(dof)] - pu) / pu);
      e_final = std::max(e_final, std::abs(r.final_u[static_cast<std::size_t>(dof)] - fu));
    }
    err.push_back(e_final);
    std::printf("%s, %s damping, h = dt/%-3d peak |u| error %.3g (relative), final u error %.3g m\n",
                std::string(to_string(stepper)).c_str(), st.modal_zeta.empty() ? "Rayleigh" : "modal", g, e_peak, e_final);
  }
  return err;
}

}  // namespace

// A 5-storey non-uniform shear building under 10 s of El Centro, Rayleigh (floor and storey dashpots) and classical
// modal damping (a dense C: the Newton matrix's block full), against lsim: the final displacements' error falls at
// Newmark's second order (2 +- 0.2 per halving from dt/4: measured 1.68 (dt/2 -> dt/4, pre-asymptotic), 1.91-1.99) and
// RK4's fourth (4 +- 0.4: measured 3.71-4.06); at the finest grid the peak floor displacements within 1e-4 (Newmark) and 1e-6 (RK4).
TEST(SystemSteppers, LinearShearBuildingAgainstLsimWithTheOrderMeasured) {
  POUNDING_REQUIRE_REAL_RECORDS();
  if (!have_scipy()) POUNDING_SKIP_OR_FAIL("needs " + python() + " with numpy and scipy (tools/setup.sh)");
  double dt = 0;
  const std::vector<double> ag = el_centro(10.0, dt);
  const std::vector<int> grids{2, 4, 8, 16};
  const std::vector<double> m{2.5e5, 2.5e5, 2.4e5, 2.2e5, 1.8e5}, k{3.2e8, 3.0e8, 2.6e8, 2.2e8, 1.6e8};
  for (const test::Stick& st : {stick(m, k, 0.45, 0.003), modal_stick(m, k, {0.02, 0.05, 0.03})}) {
    const model::System S = test::shear_row({5}, st.modal_zeta.empty(), !st.modal_zeta.empty());
    const Reference R = run_reference(fmt::format(
        R"({{"mode": "linear", "dt": {:.17g}, "ag": [{:.17g}], "duration": {:.17g}, "substeps": [{}], "bodies": [{}], "contacts": []}})",
        dt, fmt::join(ag, ", "), dt * static_cast<double>(ag.size() - 1), fmt::join(grids, ", "), body_json(st)));
    for (Stepper stepper : {Stepper::newmark, Stepper::rk4}) {
      const std::vector<double> err = linear_errors(S, st, ag, dt, grids, stepper, R);
      const double want = stepper == Stepper::newmark ? 2.0 : 4.0;
      for (std::size_t i = 0; i + 1 < err.size(); ++i) {
        std::printf("  order %.3f\n", order(err[i], err[i + 1]));
        if (stepper == Stepper::rk4 || i >= 1) {  // Newmark at dt/2 is pre-asymptotic (measured 1.68, 1.91)
          EXPECT_NEAR(order(err[i], err[i + 1]), want, 0.1 * want) << to_string(stepper) << ", halving " << i;
        }
      }
      const SystemResult r = run_engine(S, {st}, ag, dt, grids.back(), 0, 0, 1, {}, stepper);
      for (int f = 1; f <= 5; ++f) {
        const double pu = R.peak_u.at({grids.back(), 0, f});
        EXPECT_NEAR(r.peak_u[static_cast<std::size_t>(S.bodies()[0].dofs[static_cast<std::size_t>(f - 1)])], pu,
                    (stepper == Stepper::newmark ? 1e-4 : 1e-6) * pu) << to_string(stepper) << " floor " << f;
      }
    }
  }
}

namespace {

// Three yielding-storey 3- vs 5-storey pairs (random +-15 % numbers, Rayleigh damping, Hertzdamp at the three
// common levels) as test_system_kernel's energy test builds them.
SystemBatch pair_3_5(const model::System& S, std::size_t width, double fy_scale, double gap) {
  SystemBatch B;
  B.resize(S, width);
  std::mt19937_64 rng(25);
  std::uniform_real_distribution<double> u(0.85, 1.15);
  for (std::size_t l = 0; l < width; ++l) {
    test::Stick a, b;
    a.m = {3.0e5 * u(rng), 3.0e5 * u(rng), 2.5e5 * u(rng)}, a.k = {4.0e8 * u(rng), 3.6e8 * u(rng), 3.0e8 * u(rng)};
    b.m = {2.5e5 * u(rng), 2.5e5, 2.5e5, 2.2e5, 2.0e5 * u(rng)};
    b.k = {2.6e8 * u(rng), 2.5e8, 2.3e8, 2.0e8 * u(rng), 1.6e8};
    test::rayleigh(a, 0.05 * u(rng), 16.0, 45.0), test::rayleigh(b, 0.05, 9.0, 26.0);
    for (std::size_t k = 0; k < a.k.size(); ++k) a.fy.push_back(fy_scale * a.k[k] * 0.012);
    for (std::size_t k = 0; k < b.k.size(); ++k) b.fy.push_back(fy_scale * b.k[k] * 0.015);
    a.alpha = b.alpha = 0.05;
    test::fill_stick(B, 0, l, a), test::fill_stick(B, 1, l, b);
    for (std::size_t e = 0; e < 3; ++e) {
      const std::size_t at = SystemBatch::at(static_cast<int>(e), l, width);
      B.gap[at] = gap * u(rng), B.kc[at] = 1.0e10 * u(rng), B.e[at] = 0.65;
    }
  }
  return B;
}

}  // namespace

// The 3- vs 5-storey pair of SystemScipy.PoundingPairAgainstSolveIvp (elastic Rayleigh-damped storeys, Hertzdamp
// at its three common levels, 8 s of El Centro) with Newmark, RK4 and central difference against solve_ivp with
// event-located onsets: each stepper's worst peak-floor error (printed; measured at dt/10 .. dt/80: CD 1.2e-3 ..
// 1.8e-5, Newmark 1.4e-3 .. 2.2e-5, RK4 2.3e-5 .. 8.4e-7) is within 2e-3 at dt/80 and the impact count per level
// (7, 15, 19) equals the reference's there; no lane diverges (coarse allowed at dt/10); the steppers converge to each
// other at second order (the largest difference between any two falls by >= 2.5 per halving from dt/20: measured
// 2.6e-3, 6.4e-4, 1.6e-4, 4.0e-5, order 2.0).
TEST(SystemSteppers, PoundingPairConvergesAcrossSteppers) {
  POUNDING_REQUIRE_REAL_RECORDS();
  if (!have_scipy()) POUNDING_SKIP_OR_FAIL("needs " + python() + " with numpy and scipy (tools/setup.sh)");
  const test::PoundingPairCase c = test::pounding_pair_case();
  const double dt = c.dt, gap = c.gap, kc = c.kc, e = c.e;
  const std::vector<double>& ag = c.ag;
  const std::vector<int>& grids = c.grids;
  const std::vector<test::Stick>& sticks = c.sticks;
  const model::System& S = c.S;
  const Reference& R = c.R;
  const ContactModel groups[] = {hertzdamp()};
  const Stepper steppers[] = {Stepper::central_difference, Stepper::newmark, Stepper::rk4};
  std::vector<double> spread;
  for (int g : grids) {
    std::vector<std::vector<double>> peaks;
    for (Stepper st : steppers) {
      const SystemResult r = run_engine(S, sticks, ag, dt, g, gap, kc, e, groups, st);
      EXPECT_NE(r.status[0], static_cast<std::uint8_t>(LaneStatus::diverged)) << to_string(st) << " h = dt/" << g;
      if (g >= 20) {
        EXPECT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok)) << to_string(st) << " h = dt/" << g;
      }
      double ed = 0;
      peaks.emplace_back();
      for (int b = 0; b < 2; ++b)
        for (int f = 1; f <= (b == 0 ? 3 : 5); ++f) {
          const int dof = S.bodies()[static_cast<std::size_t>(b)].dofs[static_cast<std::size_t>(f - 1)];
          const double pu = R.peak_u.at({g, b, f}), x = r.peak_u[static_cast<std::size_t>(dof)];
          ed = std::max(ed, std::abs(x - pu) / pu);
          peaks.back().push_back(x);
        }
      std::printf("%-18s h = dt/%-3d peak |u| error %.3g (worst floor), impacts %d %d %d (reference %d %d %d)\n",
                  std::string(to_string(st)).c_str(), g, ed, r.impact_count[0], r.impact_count[1], r.impact_count[2],
                  R.impacts.at(0), R.impacts.at(1), R.impacts.at(2));
      if (g != grids.back()) continue;
      EXPECT_LT(ed, 2e-3) << to_string(st);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(r.impact_count[static_cast<std::size_t>(k)], R.impacts.at(k)) << to_string(st) << " level " << k + 1;
    }
    double w = 0;
    for (std::size_t a = 0; a < peaks.size(); ++a)
      for (std::size_t b = a + 1; b < peaks.size(); ++b)
        for (std::size_t k = 0; k < peaks[a].size(); ++k) w = std::max(w, std::abs(peaks[a][k] - peaks[b][k]) / peaks[a][k]);
    spread.push_back(w);
    std::printf("h = dt/%-3d largest difference between two steppers %.3g\n", g, w);
  }
  for (std::size_t i = 1; i + 1 < spread.size(); ++i) {
    std::printf("  spread order %.2f\n", order(spread[i], spread[i + 1]));
    EXPECT_GT(spread[i] / spread[i + 1], 2.5) << "halving " << i;
  }
}

// Energy balance of yielding 3- vs 5-storey pairs pounding at three levels with Newmark and with RK4: input =
// kinetic + strain + viscous + hysteretic + contact stored + contact dissipated, every term present; the residual is
// below 1e-4 of the input at dt/5 and 1e-6 at dt/40 and falls by >= 3 per halving from dt/10 (the energy integrals
// are trapezoidal: second order for both steppers; measured Newmark 2.4e-5, 5.7e-6, 1.2e-6, 3.1e-7; RK4 1.3e-6,
// 2.3e-6, 2.0e-7, 4.5e-8).
TEST(SystemSteppers, EnergyBalanceOfAPoundingHistory) {
  const model::System S = test::shear_row({3, 5}, true);
  const SystemBatch B = pair_3_5(S, 2, 0.6, 0.01);
  const std::vector<double> ag = pounding::builtin_motion(0.01, 12.0);
  const ContactModel groups[] = {hertzdamp()};
  for (Stepper stepper : {Stepper::newmark, Stepper::rk4}) {
    std::vector<double> worst;
    for (int sub : {5, 10, 20, 40}) {
      KernelSettings ks;
      ks.substeps = sub, ks.energy = true, ks.stepper = stepper;
      SystemResult r;
      run_system(B, groups, GroundMotion{0.01, ag, 0.0}, ks, r);
      double w = 0;
      for (std::size_t l = 0; l < B.width; ++l) {
        EXPECT_NE(r.status[l], static_cast<std::uint8_t>(LaneStatus::diverged)) << to_string(stepper) << " substeps " << sub;
        double dissipated = 0;
        for (int e = 0; e < 3; ++e) dissipated += r.contact_energy[SystemBatch::at(e, l, B.width)];
        const double out = r.e_kinetic[l] + r.e_strain[l] + r.e_viscous[l] + r.e_hysteretic[l] + r.e_contact_stored[l] +
                           dissipated;
        w = std::max(w, std::abs(r.e_input[l] - out) / r.e_input[l]);
        EXPECT_GT(r.e_hysteretic[l], 0.01 * r.e_input[l]) << "the storeys must yield";
        EXPECT_GT(dissipated, 1e-4 * r.e_input[l]) << "the impacts must dissipate";
        EXPECT_GT(r.e_viscous[l], 0.01 * r.e_input[l]);
      }
      worst.push_back(w);
      std::printf("%s h = dt/%-3d largest |residual| / input %.3g\n", std::string(to_string(stepper)).c_str(), sub, w);
    }
    for (std::size_t i = 1; i + 1 < worst.size(); ++i) EXPECT_GT(worst[i] / worst[i + 1], 3.0) << to_string(stepper) << " halving " << i;
    EXPECT_LT(worst.front(), 1e-4) << to_string(stepper);
    EXPECT_LT(worst.back(), 1e-6) << to_string(stepper);
  }
}

// A lane's results do not depend on the batch: 5 lanes together and each alone give identical bits.
TEST(SystemSteppers, LanesAreIndependentOfTheBatch) {
  const model::System S = test::shear_row({3, 5}, true);
  const SystemBatch B = pair_3_5(S, 5, 0.6, 0.005);
  const std::vector<double> ag = pounding::builtin_motion(0.01, 4.0);
  const ContactModel groups[] = {hertzdamp()};
  for (Stepper stepper : {Stepper::newmark, Stepper::rk4}) {
    KernelSettings ks;
    ks.substeps = 4, ks.energy = true, ks.stepper = stepper;
    SystemResult all;
    run_system(B, groups, GroundMotion{0.01, ag, 0.0}, ks, all);
    int impacts = 0;
    for (std::size_t l = 0; l < B.width; ++l) {
      SystemBatch one;
      one.resize(S, 1);
      auto take = [&](auto& dst, const auto& src) {
        const std::size_t rows = src.size() / B.width;
        for (std::size_t k = 0; k < rows; ++k) dst[k] = src[k * B.width + l];
      };
      take(one.m, B.m), take(one.c_floor, B.c_floor), take(one.c_storey, B.c_storey), take(one.spring, B.spring);
      take(one.gap, B.gap), take(one.weight, B.weight), take(one.kc, B.kc), take(one.e, B.e);
      take(one.u0, B.u0), take(one.v0, B.v0);
      SystemResult r;
      run_system(one, groups, GroundMotion{0.01, ag, 0.0}, ks, r);
      for (int j = 0; j < 8; ++j) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(r.peak_u[static_cast<std::size_t>(j)]),
                  std::bit_cast<std::uint64_t>(all.peak_u[SystemBatch::at(j, l, B.width)])) << to_string(stepper);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(r.final_v[static_cast<std::size_t>(j)]),
                  std::bit_cast<std::uint64_t>(all.final_v[SystemBatch::at(j, l, B.width)])) << to_string(stepper);
      }
      EXPECT_EQ(std::bit_cast<std::uint64_t>(r.e_input[0]), std::bit_cast<std::uint64_t>(all.e_input[l]));
      for (int e = 0; e < 3; ++e) impacts += all.impact_count[SystemBatch::at(e, l, B.width)];
    }
    EXPECT_GT(impacts, 0) << "the lanes must pound";
  }
}

namespace {
std::string refusal(const SystemBatch& B, std::span<const ContactModel> groups, const KernelSettings& ks) {
  const std::vector<double> ag = pounding::builtin_motion(0.01, 1.0);
  SystemResult r;
  try {
    run_system(B, groups, GroundMotion{0.01, ag, 0.0}, ks, r);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

// One clear error for what the lane steppers do not run, and Nigam-Jennings refusing multi-DOF bodies (D7).
TEST(SystemSteppers, RefusesWhatTheyDoNotRun) {
  const model::System S = test::shear_row({3, 5}, true);
  const SystemBatch B = pair_3_5(S, 1, 1.0, 0.01);
  const ContactModel groups[] = {hertzdamp()};
  KernelSettings ks;
  ks.stepper = Stepper::nigam_jennings;
  const std::string nj = refusal(B, groups, ks);
  EXPECT_NE(nj.find("nigam-jennings integrates SDOF bodies only (building1 has 3 floors)"), std::string::npos) << nj;
  EXPECT_NE(nj.find("use central-difference, newmark or rk4"), std::string::npos) << nj;
  for (Stepper st : {Stepper::newmark, Stepper::rk4}) {
    ks.stepper = st;
    EXPECT_EQ(refusal(B, groups, ks), "") << to_string(st);
    ContactModel sm;
    sm.law = ContactLaw::stereomechanical;
    const ContactModel one[] = {sm};
    const model::System P = test::shear_row({2, 2}, true);
    SystemBatch b2;
    b2.resize(P, 1);
    EXPECT_NE(refusal(b2, one, ks).find("stereomechanical"), std::string::npos);
    ks.locate_contact = st == Stepper::rk4;
    if (ks.locate_contact) {
      EXPECT_NE(refusal(B, groups, ks).find("located contact onsets"), std::string::npos);
    }
    ks.locate_contact = false;
  }
  // an isolated building on a friction pendulum: its smooth law is refused by name
  model::StickTopology a, b;
  a.storeys = b.storeys = 3, a.storey_heights = b.storey_heights = {3.0};
  a.isolated = true, a.isolator_law = model::law_of<model::FrictionPendulum>;
  const model::StickTopology t[] = {a, b};
  const model::System iso = model::shear_buildings(t);
  SystemBatch ib;
  ib.resize(iso, 1);
  ks.stepper = Stepper::newmark;
  const std::vector<Problem> pr = lane_stepper_problems(ib, groups, ks);
  ASSERT_EQ(pr.size(), 1u);
  const std::string fp = pr[0].what + " | " + pr[0].where + " | " + pr[0].fix;
  EXPECT_NE(fp.find("friction-pendulum"), std::string::npos) << fp;
  EXPECT_NE(fp.find("central-difference"), std::string::npos) << fp;
}

namespace {

// Peak |u| of every DOF and peak force of every element of lane 0 with `stepper` at `substeps`.
SystemResult run_kind(const SystemBatch& B, std::span<const ContactModel> groups, const std::vector<double>& ag,
                      Stepper stepper, int substeps) {
  KernelSettings ks;
  ks.stepper = stepper, ks.substeps = substeps;
  SystemResult r;
  run_system(B, groups, GroundMotion{0.01, ag, 0.0}, ks, r);
  return r;
}

// The largest relative difference of peak |u| (every DOF) and of the element peak forces above 1 % of the largest.
double peaks_apart(const SystemResult& a, const SystemResult& b) {
  double w = 0, fmax = 0;
  for (std::size_t j = 0; j < a.peak_u.size(); ++j) w = std::max(w, std::abs(a.peak_u[j] - b.peak_u[j]) / a.peak_u[j]);
  for (double f : a.peak_force) fmax = std::max(fmax, f);
  for (std::size_t e = 0; e < a.peak_force.size(); ++e)
    if (a.peak_force[e] > 0.01 * fmax) w = std::max(w, std::abs(a.peak_force[e] - b.peak_force[e]) / a.peak_force[e]);
  return w;
}

}  // namespace

// The body kinds beside plain sticks converge to central difference with Newmark and RK4: (a) floors against
// columns (a 4-storey building of 3 m storeys beside a 3-storey one of 4 m: interpolated sides with xi weights, the
// column's share on the floors below and above); (b) building 1 base-isolated on a lead-rubber bearing inside moat
// walls (wall sides, a bilinear isolator, floor dashpots referencing the base) pounding building 2 and the walls. Each
// pounds (impacts on a column element / on a moat wall); at h = dt/40 each stepper's peak floor displacements and peak
// element forces are within 1 % of central difference's at dt/80, and the difference falls as h halves.
TEST(SystemSteppers, ColumnSidesAndMoatWallsConvergeToCentralDifference) {
  const std::vector<double> ag = pounding::builtin_motion(0.01, 8.0);
  ShearSpec a, b;
  a.floor_mass = {3.0e5}, a.period = 0.5, a.zeta = 0.05;
  b.floor_mass = {2.5e5}, b.period = 0.8, b.zeta = 0.05;
  for (int kind = 0; kind < 2; ++kind) {
    model::StickTopology t1, t2;
    t1.storeys = kind == 0 ? 4 : 3, t1.storey_heights = {3.0};
    t2.storeys = 3, t2.storey_heights = {kind == 0 ? 4.0 : 3.0};
    if (kind == 1) t1.isolated = true, t1.moat = true, t1.isolator_law = model::law_of<model::BilinearKinematic>;
    const model::StickTopology tops[] = {t1, t2};
    const model::System S = model::shear_buildings(tops);
    SystemBatch B;
    B.resize(S, 1);
    if (kind == 0) {
      set_shear_building(B, 0, 0, a);
    } else {
      IsolationSpec iso;
      iso.bearing = Bearing::lead_rubber, iso.base_mass = 3.0e5, iso.k1 = 6.0e7, iso.k2 = 6.0e6, iso.qd = 1.5e5;
      set_isolated_building(B, 0, 0, a, iso);
      set_moat(B, 0, 0, 0.02, 0.02, 2.0e9, 0.65);
    }
    set_shear_building(B, 0, 1, b);
    set_contacts(B, 0, 0.004, 2.0e9, 0.65);
    std::vector<ContactModel> groups(S.groups().size(), hertzdamp());
    bool column = false;
    for (const model::ContactElement& ce : S.contacts())
      column = column || ce.left.kind == model::SideKind::interpolated || ce.right.kind == model::SideKind::interpolated;
    EXPECT_EQ(column, kind == 0);
    const SystemResult ref = run_kind(B, groups, ag, Stepper::central_difference, 80);
    int struck = 0;
    for (std::size_t e = 0; e < S.contacts().size(); ++e) {
      const model::ContactElement& ce = S.contacts()[e];
      const bool special = kind == 0 ? (ce.left.kind == model::SideKind::interpolated || ce.right.kind == model::SideKind::interpolated)
                                     : (ce.left.kind == model::SideKind::wall || ce.right.kind == model::SideKind::wall);
      if (special) struck += ref.impact_count[e];
    }
    EXPECT_GT(struck, 0) << (kind == 0 ? "no floor struck a column" : "the base never struck the moat");
    for (Stepper st : {Stepper::newmark, Stepper::rk4}) {
      const double d20 = peaks_apart(ref, run_kind(B, groups, ag, st, 20));
      const double d40 = peaks_apart(ref, run_kind(B, groups, ag, st, 40));
      std::printf("%s, %s: apart from CD at dt/80 by %.3g (dt/20), %.3g (dt/40); %d impacts on %s\n",
                  kind == 0 ? "floor against column" : "isolated in a moat", std::string(to_string(st)).c_str(), d20, d40,
                  struck, kind == 0 ? "columns" : "moat walls");
      EXPECT_LT(d40, 0.01) << to_string(st) << " kind " << kind;
      EXPECT_LT(d40, d20) << to_string(st) << " kind " << kind;
    }
  }
}
