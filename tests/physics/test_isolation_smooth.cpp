// The smooth isolators of issue 25 step 7 in the system stepper (docs/architecture.md §2.10 step 7): a 3-storey
// building on a friction pendulum and on a Bouc-Wen bearing under a sine pulse against an independent SciPy solution
// (tools/reference_systems.py smooth: solve_ivp of the same equations, none of our code), with the convergence of
// peaks, residual displacement and hysteretic energy as the step falls, and the energy balance of a pounding history
// with a friction-pendulum base against a moat wall converging with the step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

using namespace pounding;
using namespace pounding::physics;

namespace {

std::string python() {
  const char* p = std::getenv("POUNDING_PYTHON");
  return p && *p ? p : "/usr/bin/python3";
}
bool have_scipy() { return std::system((python() + " -c 'import numpy, scipy' 2>/dev/null").c_str()) == 0; }

const double g = 9.80665, pi = std::acos(-1.0);

// "key [S] [i] value" lines -> key -> "S i" -> value
std::map<std::string, std::map<std::string, double>> reference(const std::string& json) {
  testdata::TempDir tmp("smooth-scipy");
  const std::string in = tmp.file("in.json"), out = tmp.file("out.txt");
  std::ofstream(in) << json;
  const std::string cmd = python() + " " + testdata::source_dir() + "/tools/reference_systems.py smooth " + in + " " + out;
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::map<std::string, std::map<std::string, double>> R;
  std::ifstream f(out);
  std::string line;
  while (std::getline(f, line)) {
    const auto a = line.find(' '), b = line.rfind(' ');
    R[line.substr(0, a)][a == b ? "" : line.substr(a + 1, b - a - 1)] = std::stod(line.substr(b + 1));
  }
  return R;
}

model::System isolated(int law, bool moat = false) {
  std::vector<model::StickTopology> t(1);
  t[0].storeys = 3, t[0].isolated = true, t[0].moat = moat, t[0].isolator_law = law;
  return model::shear_buildings(t);
}

ShearSpec superstructure() {  // the link-element paper's BI building (SM §3.1): 3 x 300 t, 98.1 MN/m, 5 %
  ShearSpec s;
  s.floor_mass = {3.0e5};
  s.storey_stiffness = {9.81e7};
  s.zeta = 0.05;
  return s;
}

IsolationSpec pendulum(double uy) {  // R = 2 m (T = 2.84 s), mu 0.05 -> 0.10 at a = 20 s/m (T2.3)
  IsolationSpec i;
  i.bearing = Bearing::friction_pendulum, i.base_mass = 3.0e5, i.radius = 2.0, i.mu_slow = 0.05, i.mu_fast = 0.10;
  i.rate = 20.0, i.uy = uy;
  return i;
}

IsolationSpec bouc_wen() {  // the lead-rubber numbers of test_isolation's balance, eta = 2, beta 0.9, gamma 0.1
  IsolationSpec i;
  i.bearing = Bearing::bouc_wen, i.base_mass = 3.0e5, i.k1 = 1.2e8, i.k2 = 1.2e7, i.qd = 6.0e5;
  i.bw_beta = 0.9, i.bw_gamma = 0.1, i.bw_eta = 2;
  return i;
}

std::vector<double> pulse(double dt, double amp, double period, double cycles, double duration) {
  std::vector<double> ag(static_cast<std::size_t>(std::lround(duration / dt)) + 1, 0.0);
  for (std::size_t i = 0; i < ag.size(); ++i) {
    const double t = static_cast<double>(i) * dt;
    if (t < cycles * period) ag[i] = amp * std::sin(2 * pi * t / period);
  }
  return ag;
}

struct Errors {
  double peak = 0, residual = 0, energy = 0;
};

// The engine at h = dt/S for each S against the reference on the same grids; prints and returns the errors.
std::vector<Errors> compare(const IsolationSpec& iso, const std::string& bearing_json, const std::vector<int>& subs) {
  const model::System S = isolated(isolator_law(iso.bearing));
  SystemBatch B;
  B.resize(S, 1);
  const IsolationNumbers n = set_isolated_building(B, 0, 0, superstructure(), iso);
  const double dt = 0.01, duration = 6.0;
  const std::vector<double> ag = pulse(dt, 3.0, 1.5, 2.0, duration);
  auto R = reference(fmt::format(
      R"({{"m_base": {:.17g}, "m": [{:.17g}], "k": [{:.17g}], "a0": {:.17g}, "a1": {:.17g}, "bearing": {}, )"
      R"("dt": {:.17g}, "ag": [{:.17g}], "duration": {:.17g}, "substeps": [{}]}})",
      n.m_base, fmt::join(n.super.m, ", "), fmt::join(n.super.k, ", "), n.super.rayleigh.a0, n.super.rayleigh.a1,
      bearing_json, dt, fmt::join(ag, ", "), duration, fmt::join(subs, ", ")));
  std::vector<Errors> out;
  const ContactModel none[] = {ContactModel{ContactLaw::none}};
  for (int sub : subs) {
    KernelSettings ks;
    ks.substeps = sub, ks.energy = true;
    SystemResult r;
    run_system(B, none, GroundMotion{dt, ag, 0.0}, ks, r);
    EXPECT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok));
    Errors e;
    for (int i = 0; i < 4; ++i) {
      const double ref = R["peak_u"][fmt::format("{} {}", sub, i)];
      e.peak = std::max(e.peak, std::abs(r.peak_u[static_cast<std::size_t>(S.bodies()[0].dofs[static_cast<std::size_t>(i)])] - ref) / ref);
    }
    const double res = R["final_u"][fmt::format("{} 0", sub)], peak0 = R["peak_u"][fmt::format("{} 0", sub)];
    e.residual = std::abs(r.final_u[0] - res) / peak0;  // against the peak: the residual itself may be near zero
    e.energy = std::abs(r.e_hysteretic[0] - R["e_hysteretic"][""]) / R["e_hysteretic"][""];
    std::printf("h = dt/%d: base peak %.6g m (scipy %.6g), residual %.6g m (scipy %.6g), e_hysteretic %.6g J (scipy "
                "%.6g); errors: peaks %.3g, residual %.3g, energy %.3g\n", sub, r.peak_u[0], peak0, r.final_u[0], res,
                r.e_hysteretic[0], R["e_hysteretic"][""], e.peak, e.residual, e.energy);
    out.push_back(e);
  }
  return out;
}

void expect_converging(const std::vector<Errors>& e, double tol) {
  ASSERT_EQ(e.size(), 3u);
  EXPECT_LT(e.back().peak, tol);
  EXPECT_LT(e.back().residual, tol);
  EXPECT_LT(e.back().energy, tol);
  for (std::size_t i = 0; i + 1 < e.size(); ++i) {
    std::printf("orders (halving %zu): peaks %.2f, residual %.2f, energy %.2f\n", i, std::log2(e[i].peak / e[i + 1].peak),
                std::log2(e[i].residual / e[i + 1].residual), std::log2(e[i].energy / e[i + 1].energy));
    EXPECT_GT(e[i].peak / e[i + 1].peak, 2.5) << "halving " << i;
    EXPECT_GT(e[i].energy / e[i + 1].energy, 2.5) << "halving " << i;
  }
}

}  // namespace

// Friction pendulum (W = g M_total = 11.77 MN, R = 2 m, mu(v) from 0.05 to 0.10, u_y = 2 mm) under a 3 m/s2 sine
// pulse of period 1.5 s (two cycles, then free motion to 6 s): peak base and floor displacements, the residual base
// displacement and the hysteretic energy within 1e-5 of SciPy at h = dt/40 (measured 1.2e-7, 7e-8, 2.1e-7), the
// errors falling by more than 2.5 per halving of h (measured orders 2.2-2.5, then 1.5-1.9 from dt/20 to dt/40: the
// velocity reversals, where the z equation's right side has a kink inside a step, cost part of the second order).
TEST(IsolationSmooth, FrictionPendulumAgainstScipy) {
  if (!have_scipy()) POUNDING_SKIP_OR_FAIL("needs " + python() + " with numpy and scipy (tools/setup.sh)");
  const double W = g * 1.2e6;
  const std::string bearing = fmt::format(
      R"({{"k": {:.17g}, "q_slow": {:.17g}, "q_fast": {:.17g}, "rate": 20, "uy": 0.002, "A": 1, "beta": 0.5, )"
      R"("gamma": 0.5, "eta": 2}})", W / 2.0, 0.05 * W, 0.10 * W);
  expect_converging(compare(pendulum(0.002), bearing, {10, 20, 40}), 1e-5);
}

// Bouc-Wen (k1 120 MN/m, k2 12 MN/m, Qd 600 kN: alpha 0.1, u_y 5.56 mm; eta 2, beta 0.9, gamma 0.1), same pulse:
// within 1e-5 at dt/40 (measured 3e-7), orders 2.0-2.6 then 1.6-1.9.
TEST(IsolationSmooth, BoucWenAgainstScipy) {
  if (!have_scipy()) POUNDING_SKIP_OR_FAIL("needs " + python() + " with numpy and scipy (tools/setup.sh)");
  const double uy = 6.0e5 / (1.2e8 - 1.2e7);
  const std::string bearing = fmt::format(
      R"({{"k": 1.2e7, "q_slow": 6e5, "q_fast": 6e5, "rate": 0, "uy": {:.17g}, "A": 1, "beta": 0.9, "gamma": 0.1, )"
      R"("eta": 2}})", uy);
  expect_converging(compare(bouc_wen(), bearing, {10, 20, 40}), 1e-5);
}

// A friction-pendulum base (u_y 0.5 mm) against its moat walls 0.06 m away (Hertzdamp, kh 5e9, e 0.6) under the pulse
// scaled to hit them: the energy balance (input = kinetic + strain + viscous + hysteretic + contact stored + contact
// dissipated) closes better as h falls: residual below 1e-4 of the input at dt/80 and falling by > 3 per halving
// (measured 2.6e-5, 6.5e-6, 1.6e-6: second order).
TEST(IsolationSmooth, PendulumMoatEnergyBalanceConverges) {
  const model::System S = isolated(model::law_of<model::FrictionPendulum>, true);
  SystemBatch B;
  B.resize(S, 1);
  set_isolated_building(B, 0, 0, superstructure(), pendulum(5e-4));
  set_moat(B, 0, 0, 0.06, 0.06, 5e9, 0.6);
  ContactModel hd;
  hd.law = ContactLaw::hertzdamp;
  const ContactModel groups[] = {ContactModel{ContactLaw::none}, hd};
  const std::vector<double> ag = pulse(0.01, 4.0, 1.5, 2.0, 6.0);
  std::vector<double> res;
  for (int sub : {20, 40, 80}) {
    KernelSettings ks;
    ks.substeps = sub, ks.energy = true;
    SystemResult r;
    run_system(B, groups, GroundMotion{0.01, ag, 0.0}, ks, r);
    ASSERT_EQ(r.status[0], static_cast<std::uint8_t>(LaneStatus::ok));
    double dissipated = 0;
    for (std::size_t e = 0; e < S.contacts().size(); ++e) dissipated += r.contact_energy[e];
    const double out = r.e_kinetic[0] + r.e_strain[0] + r.e_viscous[0] + r.e_hysteretic[0] + r.e_contact_stored[0] +
                       dissipated;
    res.push_back(std::abs(r.e_input[0] - out) / r.e_input[0]);
    std::printf("h = dt/%d: input %.6g J, hysteretic %.6g, viscous %.4g, contact %.4g, moat impacts %d/%d, base peak "
                "%.4g m; residual %.3g of the input\n", sub, r.e_input[0], r.e_hysteretic[0], r.e_viscous[0],
                dissipated, r.impact_count[0], r.impact_count[1], r.peak_u[0], res.back());
    EXPECT_GT(r.impact_count[0] + r.impact_count[1], 0) << "the moat must be hit";
    EXPECT_GT(r.e_hysteretic[0], 0.2 * r.e_input[0]) << "the pendulum must slide";
  }
  EXPECT_LT(res.back(), 1e-4);
  for (std::size_t i = 0; i + 1 < res.size(); ++i) EXPECT_GT(res[i] / res[i + 1], 3.0) << "halving " << i;
}
