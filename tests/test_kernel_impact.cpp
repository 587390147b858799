// Single impacts: Hertz theory for e = 1, effective restitution of every contact law against an independent
// reference (the two-mass impact ODE integrated here with Boost.Odeint's adaptive Dormand-Prince stepper,
// exit located by bisection on its dense output -- no kernel code), the calibrated law's target, the
// SciPy reference of tools/reference_restitution.py, and the equivalent-sphere Hertz stiffness.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include <boost/numeric/odeint.hpp>

#include "kernel_test_support.hpp"
#include "pounding/physics/single_impact.hpp"
#include "test_data.hpp"

namespace pounding {
namespace {

namespace odeint = boost::numeric::odeint;
using test::pi;

// Physical impact used throughout: unequal masses, the collide command's Hertz stiffness.
constexpr double m1 = 1.2e6, m2 = 0.8e6, meff = m1 * m2 / (m1 + m2), v0 = 0.7;
constexpr double kh = 2.808e10;       // N/m^1.5
constexpr double k_linear = 5.0e9;    // N/m (Kelvin)

// --------------------------------------------------------------------------------------------------
// The reference: x1, v1, x2, v2 of two free masses, x1 moving right at v0 and touching x2 at t = 0.
// F(delta, ddelta) >= 0 acts while delta > 0 (or delta = 0 and closing); after the exit both move freely.
using State = std::array<double, 4>;
using Force = std::function<double(double, double)>;

struct Reference {
  double e_effective, duration, peak_penetration;
};

Reference reference_impact(const Force& F) {
  auto rhs = [&](const State& x, State& dx, double) {
    const double d = x[0] - x[2], dd = x[1] - x[3];
    const double f = (d > 0.0 || (d == 0.0 && dd > 0.0)) ? std::max(0.0, F(d, dd)) : 0.0;
    dx[0] = x[1];
    dx[1] = -f / m1;
    dx[2] = x[3];
    dx[3] = f / m2;
  };
  auto stepper = odeint::make_dense_output(1e-14, 1e-12, odeint::runge_kutta_dopri5<State>());
  State x = {0.0, v0, 0.0, 0.0};
  const double tscale = std::pow(meff * v0 * v0 / kh, 0.4) / v0;  // Hertz time scale (~0.1 of the duration)
  stepper.initialize(x, 0.0, 1e-4 * tscale);
  double peak = 0.0;
  for (int n = 0; n < 1'000'000; ++n) {
    auto [t0, t1] = stepper.do_step(rhs);
    const State& s = stepper.current_state();
    const double d = s[0] - s[2];
    peak = std::max(peak, d);
    if (d <= 0.0 && t1 > 0.0) {
      // exit inside (t0, t1]: bisection on the dense output for delta = 0
      double lo = t0, hi = t1;
      State y;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        stepper.calc_state(mid, y);
        (y[0] - y[2] > 0.0 ? lo : hi) = mid;
      }
      // refine the peak between steps is unnecessary: the dense output is sampled below
      stepper.calc_state(hi, y);
      return {(y[3] - y[1]) / v0, hi, peak};
    }
    // sample the dense output inside the step for the peak penetration
    State y;
    for (int k = 1; k < 16; ++k) {
      stepper.calc_state(t0 + (t1 - t0) * k / 16.0, y);
      peak = std::max(peak, y[0] - y[2]);
    }
  }
  ADD_FAILURE() << "reference impact did not end";
  return {NAN, NAN, NAN};
}

// Law definitions written out from the papers (not the kernel's helpers).
double xibar_of(DampingLaw law, double e) {
  switch (law) {
    case DampingLaw::lankarani_nikravesh: return 3.0 * (1.0 - e * e) / 4.0;
    case DampingLaw::hunt_crossley: return 3.0 * (1.0 - e) / 2.0;
    case DampingLaw::flores: return 8.0 * (1.0 - e) / (5.0 * e);
    case DampingLaw::hu_guo: return 3.0 * (1.0 - e) / (2.0 * e);
    case DampingLaw::gonthier: return (1.0 - e * e) / e;
    case DampingLaw::calibrated:
    case DampingLaw::ye:            // written out from their paper below (ye_force, three_spring_force)
    case DampingLaw::three_spring: break;
  }
  return NAN;
}
Force hertzdamp_force(double xibar) {
  return [xibar](double d, double dd) { return kh * std::pow(d, 1.5) * (1.0 + xibar * dd / v0); };
}
Force kelvin_force(double e) {
  const double le = std::log(e), zeta = -le / std::sqrt(pi * pi + le * le);  // impact-stiffness paper eq. 3
  const double ck = 2.0 * zeta * std::sqrt(k_linear * meff);                 // eq. 2
  return [ck](double d, double dd) { return k_linear * d + ck * dd; };
}
Force jankowski_force(double e) {
  const double zeta = 9.0 * std::sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * pi - 16.0) + 16.0));  // eq. 5
  return [zeta](double d, double dd) {
    const double ch = 2.0 * zeta * std::sqrt(kh * std::sqrt(d) * meff);  // eq. 4, damper only while approaching
    return kh * std::pow(d, 1.5) + (dd > 0.0 ? ch * dd : 0.0);
  };
}

// The link-element paper's laws from its equations (rc-buildings-base-isolation-link-elements.txt; seeds-models.md
// 3.2), with kh the single spring: Ye (eq. 9) F = kh d^1.5 + zeta d^1.5 dd, zeta = 3 kh (1 - e) / (2 e v0);
// the three-spring link (eqs 12, 13, 20) F = 1.5 kh d^1.5 + zeta d^1.5 dd, zeta = 12 (1 - e) kh / (5 e v0).
Force ye_force(double e) {
  const double zeta = 3.0 * kh * (1.0 - e) / (2.0 * e * v0);
  return [zeta](double d, double dd) { return kh * std::pow(d, 1.5) + zeta * std::pow(d, 1.5) * dd; };
}
Force three_spring_force(double e) {
  const double zeta = 12.0 * (1.0 - e) * kh / (5.0 * e * v0);
  return [zeta](double d, double dd) { return 1.5 * kh * std::pow(d, 1.5) + zeta * std::pow(d, 1.5) * dd; };
}

constexpr DampingLaw fixed_laws[] = {DampingLaw::lankarani_nikravesh, DampingLaw::hunt_crossley, DampingLaw::flores,
                                     DampingLaw::hu_guo, DampingLaw::gonthier};
constexpr double e_values[] = {0.3, 0.5, 0.65, 0.8, 0.95};

// --------------------------------------------------------------------------------------------------
// 5. Hertz impact with e = 1. Hertz theory: delta_max = (5 meff v0^2 / (4 kh))^(2/5), duration
// c delta_max / v0 with c = 2 int_0^1 dx / sqrt(1 - x^(5/2)) = (4/5) B(2/5, 1/2) = 2.9432752 (computed here from
// std::tgamma; the rounded 2.9432 of textbooks is 2.6e-5 low). The kernel's contact time counts whole steps
// (20,000 per contact): central difference ends its count one step early (-5.0e-5), Newmark and RK4 agree to
// 3.3e-13. Measured: e - 1 at most 2.7e-10, delta_max at most 2.3e-9 from theory, the peak force at most 3.4e-9,
// energy lost at most 1.8e-10 of the impact energy; bounds 1.5x those (a tenth of a step for the duration) (README's verification list quotes them). Nigam-Jennings is left out: two free masses
// have k = 0, which it rejects.
TEST(HertzImpact, ElasticImpactMatchesHertzTheory) {
  const double dmax = std::pow(5.0 * meff * v0 * v0 / (4.0 * kh), 0.4);
  const double duration = 0.8 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9) * dmax / v0;
  // the reference ODE integrates the same problem independently: check the theory constants through it
  const Reference ref = reference_impact([](double d, double) { return kh * std::pow(d, 1.5); });
  EXPECT_NEAR(ref.e_effective, 1.0, 1e-9);
  EXPECT_NEAR(ref.peak_penetration / dmax, 1.0, 1e-7);
  EXPECT_NEAR(ref.duration / duration, 1.0, 1e-8);
  EXPECT_NEAR(hertz_peak_penetration(meff, v0, kh) / dmax, 1.0, 1e-12);
  EXPECT_NEAR(hertz_contact_duration(meff, v0, kh) / ref.duration, 1.0, 1e-8);

  struct Case {
    ContactModel cm;
    const char* name;
  };
  std::vector<Case> cases = {{test::contact(ContactLaw::hertz), "hertz"}};
  for (DampingLaw d : fixed_laws) cases.push_back({test::contact(ContactLaw::hertzdamp, d), "hertzdamp"});
  cases.push_back({test::contact(ContactLaw::hertzdamp, DampingLaw::calibrated), "hertzdamp calibrated"});
  for (Stepper st : {Stepper::central_difference, Stepper::newmark, Stepper::rk4}) {
    for (const Case& c : cases) {
      const ImpactResult r = single_impact(c.cm, st, 1.0, v0, m1, m2, kh, 20000);
      ASSERT_EQ(r.status, LaneStatus::ok);
      std::printf("e=1 %-22s %-18s e_eff-1 = %+.2e  dmax/theory-1 = %+.2e  duration/theory-1 = %+.2e  "
                  "Fmax/theory-1 = %+.2e  lost %.1e\n",
                  c.name, std::string(to_string(st)).c_str(), r.e_effective - 1.0, r.peak_penetration / dmax - 1.0,
                  r.duration / duration - 1.0, r.peak_force / (kh * std::pow(dmax, 1.5)) - 1.0,
                  r.energy_lost_fraction);
      const double steps = st == Stepper::central_difference ? 1.0 : 0.1;  // of the 20,000 per contact
      EXPECT_NEAR(r.e_effective, 1.0, 4e-10) << c.name << " " << to_string(st);
      EXPECT_NEAR(r.peak_penetration / dmax, 1.0, 3.5e-9) << c.name << " " << to_string(st);
      EXPECT_NEAR(r.duration / duration, 1.0, 1.5 * steps / 20000) << c.name << " " << to_string(st);
      EXPECT_NEAR(r.energy_lost_fraction, 0.0, 3e-10) << c.name << " " << to_string(st);
      EXPECT_NEAR(r.peak_force / (kh * std::pow(dmax, 1.5)), 1.0, 5e-9) << c.name << " " << to_string(st);
    }
  }
}

// --------------------------------------------------------------------------------------------------
// 6. Effective restitution of every law against the Odeint reference. The kernel runs 20000 RK4 (or
// central-difference) steps per contact; contact onset and exit fall inside a step. Tolerances: Hertzdamp
// 1e-7 (force continuous and smooth at onset; measured <= 3.3e-9), Jankowski 2e-5 (damping ~ delta^(1/4)
// with a switch at ddelta = 0; measured <= 5.3e-6), Kelvin 1e-4 (force jumps to ck v0 at onset, an O(h)
// = O(5e-5) error; measured <= 2.2e-5).
struct LawCase {
  std::string name;
  ContactModel cm;
  double kc;
  std::function<Force(double)> force;  // reference force for target e
};

std::vector<LawCase> law_cases() {
  std::vector<LawCase> v;
  for (DampingLaw d : fixed_laws)
    v.push_back({std::string(to_string(d)), test::contact(ContactLaw::hertzdamp, d), kh,
                 [d](double e) { return hertzdamp_force(xibar_of(d, e)); }});
  // the presets take the single spring kh; three-spring applies k_eq = 1.5 kh itself
  v.push_back({"ye", test::contact(ContactLaw::hertzdamp, DampingLaw::ye), kh, ye_force});
  v.push_back({"three-spring", test::contact(ContactLaw::hertzdamp, DampingLaw::three_spring), kh, three_spring_force});
  v.push_back({"kelvin", test::contact(ContactLaw::kelvin), k_linear, kelvin_force});
  v.push_back({"jankowski", test::contact(ContactLaw::jankowski), kh, jankowski_force});
  return v;
}

// The reference table (also printed): law -> e target -> e effective.
const std::map<std::string, std::map<double, double>>& reference_table() {
  static const auto table = [] {
    std::map<std::string, std::map<double, double>> t;
    for (const LawCase& c : law_cases())
      for (double e : e_values) t[c.name][e] = reference_impact(c.force(e)).e_effective;
    return t;
  }();
  return table;
}

TEST(Restitution, EveryLawMatchesIndependentReference) {
  for (DampingLaw d : fixed_laws)
    for (double e : e_values) EXPECT_DOUBLE_EQ(hertzdamp_xibar(d, e), xibar_of(d, e)) << to_string(d);
  const auto& ref = reference_table();
  for (const LawCase& c : law_cases()) {
    const double tol = c.cm.law == ContactLaw::kelvin ? 1e-4 : c.cm.law == ContactLaw::jankowski ? 2e-5 : 1e-7;
    for (double e : e_values) {
      const double r = ref.at(c.name).at(e);
      for (Stepper st : {Stepper::rk4, Stepper::central_difference}) {
        const ImpactResult k = single_impact(c.cm, st, e, v0, m1, m2, c.kc, 20000);
        ASSERT_EQ(k.status, LaneStatus::ok);
        std::printf("%-20s e=%.2f  reference %.9f  kernel(%s) %.9f  diff %+.2e\n", c.name.c_str(), e, r,
                    std::string(to_string(st)).c_str(), k.e_effective, k.e_effective - r);
        EXPECT_NEAR(k.e_effective, r, tol) << c.name << " e=" << e << " " << to_string(st);
        // energy lost = (1 - e_eff^2) of the relative kinetic energy meff v0^2 / 2
        EXPECT_NEAR(k.energy_lost, 0.5 * meff * v0 * v0 * (1.0 - k.e_effective * k.e_effective),
                    1e-6 * 0.5 * m1 * v0 * v0);
      }
    }
  }
}

// The link-element paper's presets (issue 25 section 3): V16 (seeds-models.md 3.2, class A, 1e-4): zeta v / k on the
// single spring k is 3.5 / 1.5 / 0.6429 / 0.1667 for Ye and 5.6 / 2.4 / 1.0286 / 0.2667 for the three-spring law at
// e = 0.3 / 0.5 / 0.7 / 0.9 (xibar x stiffness factor here). One free impact against the paper's force written out
// (Odeint): the restitution (Restitution.EveryLawMatchesIndependentReference) and here the peak penetration, which
// only the stiffness factor sets (the restitution of a Hertzdamp impact is scale-free: it depends on xibar alone).
// What they deliver: the paper derives each zeta so that one impact returns e (eq. 10 = eq. 17); measured, Ye
// delivers Hu-Guo's e (the same xibar, bit for bit) and the three-spring law Flores's (xibar 8 (1 - e) / (5 e) on
// k_eq), both within 0.05 of the e asked over e = 0.3 .. 0.95 (their promise, `pounding collide`'s e_law).
TEST(Restitution, LinkElementPresetsMatchThePaper) {
  const double cr[] = {0.3, 0.5, 0.7, 0.9};
  const double ye[] = {3.5, 1.5, 0.6429, 0.1667}, three[] = {5.6, 2.4, 1.0286, 0.2667};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(hertzdamp_xibar(DampingLaw::ye, cr[i]) * damping_law(DampingLaw::ye).stiffness_factor, ye[i], 1e-4);
    EXPECT_NEAR(hertzdamp_xibar(DampingLaw::three_spring, cr[i]) * damping_law(DampingLaw::three_spring).stiffness_factor,
                three[i], 1e-4);
  }
  for (double e : e_values) {
    const Reference ry = reference_impact(ye_force(e)), r3 = reference_impact(three_spring_force(e));
    const ImpactResult y = single_impact(test::contact(ContactLaw::hertzdamp, DampingLaw::ye), Stepper::rk4, e, v0, m1,
                                         m2, kh, 20000);
    const ImpactResult t = single_impact(test::contact(ContactLaw::hertzdamp, DampingLaw::three_spring), Stepper::rk4,
                                         e, v0, m1, m2, kh, 20000);
    const ImpactResult hg = single_impact(test::contact(ContactLaw::hertzdamp, DampingLaw::hu_guo), Stepper::rk4, e,
                                          v0, m1, m2, kh, 20000);
    const ImpactResult fl = single_impact(test::contact(ContactLaw::hertzdamp, DampingLaw::flores), Stepper::rk4, e,
                                          v0, m1, m2, kh, 20000);
    std::printf("e=%.2f  ye: e_eff %.6f (ref %.6f) dmax/ref-1 %+.1e   three-spring: e_eff %.6f (ref %.6f) "
                "dmax/ref-1 %+.1e  dmax(three)/dmax(flores) %.6f\n",
                e, y.e_effective, ry.e_effective, y.peak_penetration / ry.peak_penetration - 1.0, t.e_effective,
                r3.e_effective, t.peak_penetration / r3.peak_penetration - 1.0, t.peak_penetration / fl.peak_penetration);
    // measured: at most 4.5e-8 (ye) and 9.4e-8 (three-spring) from the reference; without the 1.5 the three-spring
    // penetration would be 1.5^(2/5) - 1 = 18 % off
    EXPECT_NEAR(y.peak_penetration / ry.peak_penetration, 1.0, 1.5e-7) << "ye e=" << e;
    EXPECT_NEAR(t.peak_penetration / r3.peak_penetration, 1.0, 1.5e-7) << "three-spring e=" << e;
    // k_eq = 1.5 k: the penetration of the same impact shrinks by 1.5^(-2/5) against Flores on k
    EXPECT_NEAR(t.peak_penetration / fl.peak_penetration, std::pow(1.5, -0.4), 1e-6) << "three-spring e=" << e;
    EXPECT_EQ(y.e_effective, hg.e_effective) << "ye is hu-guo's xibar on k, e=" << e;
    EXPECT_NEAR(t.e_effective, fl.e_effective, 1e-7) << "three-spring delivers flores's e, e=" << e;
    EXPECT_NEAR(y.e_effective, e, 0.05) << "ye e=" << e;
    EXPECT_NEAR(t.e_effective, e, 0.05) << "three-spring e=" << e;
  }
}

// The calibrated law returns its target over e in [0.3, 0.95]: through the kernel (rk4, 20,000 steps) to 1.2e-10
// and through the independent reference ODE to 2.5e-11 (measured; README quotes 1.2e-10; bounds 1.5x).
TEST(Restitution, CalibratedLawHitsItsTarget) {
  const ContactModel cm = test::contact(ContactLaw::hertzdamp, DampingLaw::calibrated);
  double worst_kernel = 0, worst_ref = 0;
  for (int i = 0; i <= 13; ++i) {
    const double e = 0.3 + 0.05 * i;
    const double xi = calibrated_xibar(e);
    const double ref = reference_impact(hertzdamp_force(xi)).e_effective;
    const ImpactResult k = single_impact(cm, Stepper::rk4, e, v0, m1, m2, kh, 20000);
    ASSERT_EQ(k.status, LaneStatus::ok);
    EXPECT_NEAR(ref, e, 4e-11) << "calibrated xibar(" << e << ") = " << xi;
    EXPECT_NEAR(k.e_effective, e, 1.8e-10) << "kernel, e = " << e;
    worst_kernel = std::max(worst_kernel, std::abs(k.e_effective - e));
    worst_ref = std::max(worst_ref, std::abs(ref - e));
  }
  std::printf("calibrated law: max |e_eff - e| kernel %.2e, reference ODE %.2e (e = 0.30 .. 0.95)\n", worst_kernel,
              worst_ref);
}

// tools/reference_restitution.py (SciPy DOP853, scale-free problem) against the Odeint reference
// (dimensional two-mass problem); skipped when no python3 with SciPy is found.
std::string run_capture(const std::string& cmd, int& rc) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  if (!p) {
    rc = -1;
    return out;
  }
  char buf[512];
  while (std::fgets(buf, sizeof buf, p.get())) out += buf;
  rc = pclose(p.release());
  return out;
}

TEST(Restitution, ScipyReferenceAgreesWithOdeintReference) {
  const std::string script = testdata::source_dir() + "/tools/reference_restitution.py";
  std::string out;
  for (const char* py : {"/usr/bin/python3", "python3"}) {
    int rc = 0;
    out = run_capture(std::string(py) + " -c 'import scipy' 2>/dev/null && " + py + " " + script + " --csv", rc);
    if (rc == 0 && !out.empty()) break;
    out.clear();
  }
  if (out.empty()) POUNDING_SKIP_OR_FAIL("needs python3 with SciPy (Debian: python3-scipy; tools/setup.sh installs it)");
  const auto& ref = reference_table();
  std::istringstream in(out);
  std::string line;
  int compared = 0;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string law, f;
    std::getline(ls, law, ',');
    double e, param, ee;
    std::getline(ls, f, ',');
    e = std::stod(f);
    std::getline(ls, f, ',');
    param = std::stod(f);
    std::getline(ls, f, ',');
    ee = std::stod(f);
    if (law == "calibrated") {
      // SciPy's brentq calibration against the kernel's calibrated_xibar
      EXPECT_NEAR(calibrated_xibar(e) / param, 1.0, 1e-6) << "e = " << e;
      EXPECT_NEAR(ee, e, 1e-9);
      ++compared;
      continue;
    }
    ASSERT_TRUE(ref.count(law)) << law;
    EXPECT_NEAR(ee, ref.at(law).at(e), 1e-8) << law << " e=" << e;
    ++compared;
  }
  EXPECT_EQ(compared, 40);
}

// --------------------------------------------------------------------------------------------------
// 12. Equivalent-sphere Hertz stiffness (muthukumar eqs 11-13): spheres of radius 4.92 m and 6.2 m of
// 150 lb/ft^3 concrete, E of 4000 psi concrete = 57000 sqrt(4000) psi, nu = 0.15 -> kh = 888 kN/mm^1.5.
TEST(HertzStiffness, EquivalentSpheresReproduceMuthukumar) {
  const double rho = 2402.8;                                 // kg/m^3
  const double E = 57000.0 * std::sqrt(4000.0) * 6894.757;   // Pa
  const double r1 = 4.92, r2 = 6.2;
  const double mass1 = rho * 4.0 / 3.0 * pi * r1 * r1 * r1, mass2 = rho * 4.0 / 3.0 * pi * r2 * r2 * r2;
  const double k = hertz_stiffness_spheres(mass1, mass2, rho, E, 0.15);
  const double paper = 888.0e3 / std::pow(1e-3, 1.5);  // 888 kN/mm^1.5 in N/m^1.5
  std::printf("equivalent-sphere kh = %.4e N/m^1.5 = %.1f kN/mm^1.5 (paper 888)\n", k, k * std::pow(1e-3, 1.5) / 1e3);
  EXPECT_NEAR(k / paper, 1.0, 0.01);
  // Hertz's two-sphere stiffness written out: kh = 4/3 E* sqrt(R), 1/E* = 2 (1 - nu^2)/E, R = R1 R2/(R1 + R2)
  const double Estar = E / (2.0 * (1.0 - 0.15 * 0.15)), R = r1 * r2 / (r1 + r2);
  EXPECT_NEAR(k / (4.0 / 3.0 * Estar * std::sqrt(R)), 1.0, 1e-12);
}

}  // namespace
}  // namespace pounding
