// Linear SDOF verification of every stepper: damped free vibration and harmonic forcing against the closed
// form, Nigam-Jennings against the matrix exponential of the augmented system (exact for piecewise-linear
// load), and each stepper's convergence order (elastic, bilinear with yielding, Hertz contact).
#include <gtest/gtest.h>

// Eigen's AVX-512 matrix exponential trips GCC 12's -Wmaybe-uninitialized inside the intrinsics headers.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "kernel_test_support.hpp"

namespace pounding {
namespace {

using test::all_steppers;
using test::pi;
using test::run_one;

// Exact one-step propagator of u'' + 2 zeta w u' + w^2 u = -p(t), p linear on [0, h], from the matrix
// exponential of the augmented system z = [u, v, p, p'] (z' = M z, p'' = 0).
struct ExactStep {
  Eigen::Matrix4d phi;
  double h;
  ExactStep(double w, double zeta, double h_) : h(h_) {
    Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
    M(0, 1) = 1.0;
    M(1, 0) = -w * w;
    M(1, 1) = -2.0 * zeta * w;
    M(1, 2) = -1.0;
    M(2, 3) = 1.0;
    phi = (M * h).exp();
  }
  void advance(double& u, double& v, double p0, double p1) const {
    const double s = (p1 - p0) / h;
    const double un = phi(0, 0) * u + phi(0, 1) * v + phi(0, 2) * p0 + phi(0, 3) * s;
    const double vn = phi(1, 0) * u + phi(1, 1) * v + phi(1, 2) * p0 + phi(1, 3) * s;
    u = un;
    v = vn;
  }
};

PairParams uncoupled_pair(double T1, double zeta1, double T2, double zeta2) {
  PairParams p;
  p.s1 = Structure::from_period(2.0e5, T1, zeta1);
  p.s2 = Structure::from_period(3.0e5, T2, zeta2);
  p.gap = 1.0e3;  // never closes
  return p;
}

// --------------------------------------------------------------------------------------------------
// 1. Damped free vibration: u = exp(-zeta w t) (u0 cos wd t + (v0 + zeta w u0)/wd sin wd t).
// Tolerances are the leading truncation errors at w h = 2 pi * 0.005 = 0.031 over 5 periods, with a
// margin of ~3: period error of the second-order schemes (w h)^2 / 12 per radian -> ~2.6e-3 of the
// amplitude after 31 rad; RK4 ~ (w h)^4; Nigam-Jennings is exact (round-off).
double free_vibration_tolerance(Stepper s) {
  switch (s) {
    case Stepper::central_difference: return 8e-3;
    case Stepper::newmark: return 8e-3;
    case Stepper::rk4: return 2e-7;
    case Stepper::nigam_jennings: return 1e-12;
  }
  return 0;
}

TEST(LinearSdof, DampedFreeVibrationMatchesClosedFormForEveryStepper) {
  const double T = 1.0, zeta = 0.05, u0 = 0.05, v0 = 0.2;
  const double w = 2 * pi / T, wd = w * std::sqrt(1 - zeta * zeta);
  PairParams p = uncoupled_pair(T, zeta, 1.7, 0.02);
  p.u1 = u0;
  p.v1 = v0;
  const std::vector<double> ag = {0.0, 0.0};
  for (Stepper st : all_steppers) {
    SeriesRecorder rec;
    run_one(p, test::contact(ContactLaw::none), ag, 0.005, 5.0, st, 1, false, &rec);
    ASSERT_EQ(rec.t.size(), 1001u);
    double err = 0, amp = 0;
    for (std::size_t j = 0; j < rec.t.size(); ++j) {
      const double t = rec.t[j];
      const double u = std::exp(-zeta * w * t) * (u0 * std::cos(wd * t) + (v0 + zeta * w * u0) / wd * std::sin(wd * t));
      err = std::max(err, std::abs(rec.u1[j] - u));
      amp = std::max(amp, std::abs(u));
      EXPECT_EQ(rec.u2[j], 0.0);  // structure 2 stays at rest
    }
    std::printf("free vibration %-18s max|u - exact| / max|u| = %.3e\n", std::string(to_string(st)).c_str(), err / amp);
    EXPECT_LT(err / amp, free_vibration_tolerance(st)) << to_string(st);
  }
}

// Harmonic ground motion ag = A sin(W t) from rest, full closed form (transient + steady state) of
// u'' + 2 zeta w u' + w^2 u = -A sin(W t):
//   u_p = P sin Wt + Q cos Wt, P = -A (w^2 - W^2)/D, Q = 2 A zeta w W / D, D = (w^2 - W^2)^2 + (2 zeta w W)^2,
//   u_h = exp(-zeta w t)(C1 cos wd t + C2 sin wd t), C1 = -Q, C2 = (zeta w C1 - W P)/wd.
// The record is sampled at 1 ms and linear in between: that interpolation alone differs from the sine by
// <= A (W dt)^2 / 8 = 8e-6 A, which bounds what RK4 and Nigam-Jennings can show here.
double harmonic_tolerance(Stepper s) {
  switch (s) {
    case Stepper::central_difference: return 2e-3;
    case Stepper::newmark: return 2e-3;
    case Stepper::rk4: return 5e-5;
    case Stepper::nigam_jennings: return 5e-5;
  }
  return 0;
}

TEST(LinearSdof, HarmonicForcingFromRestMatchesClosedFormForEveryStepper) {
  const double T = 0.8, zeta = 0.04, A = 2.0, W = 2 * pi * 1.5;
  const double w = 2 * pi / T, wd = w * std::sqrt(1 - zeta * zeta);
  const double D = (w * w - W * W) * (w * w - W * W) + (2 * zeta * w * W) * (2 * zeta * w * W);
  const double P = -A * (w * w - W * W) / D, Q = 2 * A * zeta * w * W / D;
  const double C1 = -Q, C2 = (zeta * w * C1 - W * P) / wd;
  auto exact = [&](double t) {
    return P * std::sin(W * t) + Q * std::cos(W * t) +
           std::exp(-zeta * w * t) * (C1 * std::cos(wd * t) + C2 * std::sin(wd * t));
  };
  const double dt = 0.001, dur = 6.0;
  std::vector<double> ag(6001);
  for (std::size_t j = 0; j < ag.size(); ++j) ag[j] = A * std::sin(W * dt * static_cast<double>(j));
  PairParams p = uncoupled_pair(T, zeta, 1.3, 0.05);
  for (Stepper st : all_steppers) {
    SeriesRecorder rec;
    run_one(p, test::contact(ContactLaw::none), ag, dt, dur, st, 1, false, &rec);
    ASSERT_EQ(rec.t.size(), ag.size());
    double err = 0, amp = 0;
    for (std::size_t j = 0; j < rec.t.size(); ++j) {
      EXPECT_DOUBLE_EQ(rec.t[j], dt * static_cast<double>(j));
      err = std::max(err, std::abs(rec.u1[j] - exact(rec.t[j])));
      amp = std::max(amp, std::abs(exact(rec.t[j])));
    }
    std::printf("harmonic       %-18s max|u - exact| / max|u| = %.3e\n", std::string(to_string(st)).c_str(), err / amp);
    EXPECT_GT(amp, 0.01);  // the response is not trivially zero
    EXPECT_LT(err / amp, harmonic_tolerance(st)) << to_string(st);
  }
}

// --------------------------------------------------------------------------------------------------
// 2. Nigam-Jennings exact to round-off.
TEST(NigamJennings, CoefficientsEqualMatrixExponential) {
  struct Case {
    double w, zeta, h;
  };
  const Case cases[] = {{2 * pi, 0.05, 0.01}, {2 * pi / 0.3, 0.02, 0.005}, {2 * pi / 3.0, 0.1, 0.02},
                        {12.0, 0.0, 0.01},    {5.0, 0.5, 0.05},            {40.0, 0.05, 0.001},
                        {2 * pi, 0.05, 0.25}, {1.0, 0.9, 0.1},
                        // long period, fine step (T = 3 s at 0.005 s / 10 substeps): w h = 1e-3
                        {2 * pi / 3.0, 0.05, 0.0005}, {2 * pi / 5.0, 0.02, 0.0001}};
  for (const Case& c : cases) {
    const NigamJennings nj = nigam_jennings(c.w, c.zeta, c.h);
    const ExactStep ex(c.w, c.zeta, c.h);
    // B columns: u1 = ... + b11 a0 + b12 a1, with the load slope (a1 - a0)/h
    const double ref[8] = {ex.phi(0, 0), ex.phi(0, 1), ex.phi(1, 0), ex.phi(1, 1),
                           ex.phi(0, 2) - ex.phi(0, 3) / c.h, ex.phi(0, 3) / c.h,
                           ex.phi(1, 2) - ex.phi(1, 3) / c.h, ex.phi(1, 3) / c.h};
    const double got[8] = {nj.a11, nj.a12, nj.a21, nj.a22, nj.b11, nj.b12, nj.b21, nj.b22};
    // Each coefficient is compared on its own scale: A in units of (1, h, w^2 h, 1), B in units of
    // (h^2, h^2, h, h) -- the sizes of the terms they multiply for a load of order 1.
    const double scale[8] = {1, c.h, c.w * c.w * c.h, 1, c.h * c.h, c.h * c.h, c.h, c.h};
    double worst = 0;
    for (int q = 0; q < 8; ++q) worst = std::max(worst, std::abs(got[q] - ref[q]) / scale[q]);
    std::printf("NJ coefficients w=%.3g zeta=%.2g h=%.3g: max scaled error %.2e\n", c.w, c.zeta, c.h, worst);
    EXPECT_LT(worst, 1e-12) << "w=" << c.w << " zeta=" << c.zeta << " h=" << c.h;
  }
}

TEST(NigamJennings, FullRunOnRandomPiecewiseLinearRecordIsExact) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> U(-4.0, 4.0);
  const double dt = 0.01;
  std::vector<double> ag(1501);
  for (double& a : ag) a = U(rng);
  PairParams p = uncoupled_pair(0.45, 0.05, 1.2, 0.02);
  p.u1 = 0.01, p.v1 = -0.05, p.u2 = -0.02, p.v2 = 0.03;
  for (int substeps : {1, 3}) {
    SeriesRecorder rec;
    BatchResult r = run_one(p, test::contact(ContactLaw::none), ag, dt, 0.0, Stepper::nigam_jennings, substeps,
                            false, &rec);
    ASSERT_EQ(r.status[0], 0);
    const double h = dt / substeps;
    const ExactStep e1(std::sqrt(p.s1.k / p.s1.m), p.s1.c / (2 * std::sqrt(p.s1.k * p.s1.m)), h);
    const ExactStep e2(std::sqrt(p.s2.k / p.s2.m), p.s2.c / (2 * std::sqrt(p.s2.k * p.s2.m)), h);
    double u1 = p.u1, v1 = p.v1, u2 = p.u2, v2 = p.v2;
    double err = 0, amp = 0;
    ASSERT_EQ(rec.u1.size(), (ag.size() - 1) * substeps + 1);
    for (std::size_t j = 0; j + 1 < rec.u1.size(); ++j) {
      const std::size_t r0 = j / substeps, q = j % substeps;
      const double a0 = ag[r0] + (ag[r0 + 1] - ag[r0]) * static_cast<double>(q) / substeps;
      const double a1 = ag[r0] + (ag[r0 + 1] - ag[r0]) * static_cast<double>(q + 1) / substeps;
      e1.advance(u1, v1, a0, a1);
      e2.advance(u2, v2, a0, a1);
      err = std::max({err, std::abs(rec.u1[j + 1] - u1), std::abs(rec.u2[j + 1] - u2)});
      amp = std::max({amp, std::abs(u1), std::abs(u2)});
    }
    std::printf("NJ full run (substeps %d): max|u - expm| / max|u| = %.2e over %zu steps\n", substeps, err / amp,
                rec.u1.size() - 1);
    EXPECT_LT(err / amp, 1e-12);
    EXPECT_GT(amp, 1e-3);
  }
}

// A long-period structure integrated with a fine step (T = 3 s, record at 0.005 s with 10 substeps: w h =
// 1e-3), the everyday case of a tall building in a study with substeps. Exact to round-off means exact
// here too; the closed-form B coefficients contain terms of size 2 zeta / (w^3 h) that cancel to O(h^2).
TEST(NigamJennings, LongPeriodFineStepStaysExact) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-3.0, 3.0);
  const double dt = 0.005;
  const int substeps = 10;
  std::vector<double> ag(801);
  for (double& a : ag) a = U(rng);
  PairParams p = uncoupled_pair(3.0, 0.05, 2.0, 0.05);
  SeriesRecorder rec;
  BatchResult r = run_one(p, test::contact(ContactLaw::none), ag, dt, 0.0, Stepper::nigam_jennings, substeps, false,
                          &rec);
  ASSERT_EQ(r.status[0], 0);
  const double h = dt / substeps;
  const ExactStep e1(2 * pi / 3.0, 0.05, h);
  double u1 = 0, v1 = 0, err = 0, amp = 0;
  for (std::size_t j = 0; j + 1 < rec.u1.size(); ++j) {
    const std::size_t r0 = j / substeps, q = j % substeps;
    const double a0 = ag[r0] + (ag[r0 + 1] - ag[r0]) * static_cast<double>(q) / substeps;
    const double a1 = ag[r0] + (ag[r0 + 1] - ag[r0]) * static_cast<double>(q + 1) / substeps;
    e1.advance(u1, v1, a0, a1);
    err = std::max(err, std::abs(rec.u1[j + 1] - u1));
    amp = std::max(amp, std::abs(u1));
  }
  std::printf("NJ long period T=3 s, h=0.5 ms: max|u - expm| / max|u| = %.2e\n", err / amp);
  // 8000 steps of round-off accumulate to at most ~8000 eps = 2e-12; 1e-11 leaves a margin of 5.
  EXPECT_LT(err / amp, 1e-11);
}

// --------------------------------------------------------------------------------------------------
// 3. Convergence order. The record is sampled at dt and piecewise linear; substeps 1, 2, 4, 8 integrate
// the same forcing with h = dt/s, so the errors are against one exact (or much finer) solution.
struct Convergence {
  std::vector<double> err;  // per substep count
  std::vector<double> order;  // log2(err[i] / err[i+1])
};

double history_error(const SeriesRecorder& rec, int substeps, const std::vector<double>& ref1,
                     const std::vector<double>& ref2) {
  double e = 0;
  for (std::size_t j = 0; j < ref1.size(); ++j) {
    const std::size_t i = j * static_cast<std::size_t>(substeps);
    e = std::max({e, std::abs(rec.u1[i] - ref1[j]), std::abs(rec.u2[i] - ref2[j])});
  }
  return e;
}

// Runs substeps 1, 2, 4, 8 and measures the max displacement error at the record samples.
Convergence measure(const PairParams& p, const ContactModel& cm, const std::vector<double>& ag, double dt,
                    Stepper st, const std::vector<double>& ref1, const std::vector<double>& ref2) {
  Convergence c;
  for (int s : {1, 2, 4, 8}) {
    SeriesRecorder rec;
    BatchResult r = run_one(p, cm, ag, dt, 0.0, st, s, false, &rec);
    // ran (ok, or coarse: the convergence study starts at under-resolved steps on purpose)
    EXPECT_TRUE(r.status[0] == 0 || r.status[0] == static_cast<std::uint8_t>(LaneStatus::coarse));
    c.err.push_back(history_error(rec, s, ref1, ref2));
  }
  for (std::size_t i = 0; i + 1 < c.err.size(); ++i) c.order.push_back(std::log2(c.err[i] / c.err[i + 1]));
  return c;
}

void print(const char* what, Stepper st, const Convergence& c) {
  std::printf("%-22s %-18s err(h..h/8) = %.2e %.2e %.2e %.2e  order = %.2f %.2f %.2f\n", what,
              std::string(to_string(st)).c_str(), c.err[0], c.err[1], c.err[2], c.err[3], c.order[0], c.order[1],
              c.order[2]);
}

void reference_by_fine_run(const PairParams& p, const ContactModel& cm, const std::vector<double>& ag, double dt,
                           int substeps, std::vector<double>& r1, std::vector<double>& r2) {
  SeriesRecorder rec;
  BatchResult r = run_one(p, cm, ag, dt, 0.0, Stepper::rk4, substeps, false, &rec);
  ASSERT_EQ(r.status[0], 0);
  r1.clear(), r2.clear();
  for (std::size_t j = 0; j < ag.size(); ++j) {
    r1.push_back(rec.u1[j * substeps]);
    r2.push_back(rec.u2[j * substeps]);
  }
}

TEST(ConvergenceOrder, ElasticSmoothForcing) {
  const double dt = 0.02;
  const std::vector<double> ag = test::two_tone(dt, 4.0);
  PairParams p = uncoupled_pair(0.6, 0.05, 0.9, 0.03);
  // exact reference: matrix exponential per record step
  std::vector<double> r1 = {0.0}, r2 = {0.0};
  {
    const ExactStep e1(2 * pi / 0.6, 0.05, dt), e2(2 * pi / 0.9, 0.03, dt);
    double u1 = 0, v1 = 0, u2 = 0, v2 = 0;
    for (std::size_t j = 0; j + 1 < ag.size(); ++j) {
      e1.advance(u1, v1, ag[j], ag[j + 1]);
      e2.advance(u2, v2, ag[j], ag[j + 1]);
      r1.push_back(u1);
      r2.push_back(u2);
    }
  }
  const double amp = std::max(*std::max_element(r1.begin(), r1.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }),
                              0.0);
  (void)amp;
  const ContactModel none = test::contact(ContactLaw::none);
  for (Stepper st : {Stepper::central_difference, Stepper::newmark}) {
    Convergence c = measure(p, none, ag, dt, st, r1, r2);
    print("elastic", st, c);
    for (double q : c.order) EXPECT_NEAR(q, 2.0, 0.15) << to_string(st);
  }
  {
    Convergence c = measure(p, none, ag, dt, Stepper::rk4, r1, r2);
    print("elastic", Stepper::rk4, c);
    for (double q : c.order) EXPECT_NEAR(q, 4.0, 0.2) << "rk4";
  }
  {
    Convergence c = measure(p, none, ag, dt, Stepper::nigam_jennings, r1, r2);
    print("elastic", Stepper::nigam_jennings, c);
    // exact on piecewise-linear load: only round-off, which the closed-form coefficients amplify by about
    // 2 zeta / (w h)^3 ~ 5e3 at h = dt/8 (see CoefficientsEqualMatrixExponential); RK4's error here is 5e-9.
    for (double e : c.err) EXPECT_LT(e / 0.05, 1e-11) << "nigam-jennings is exact on piecewise-linear load";
  }
}

// Bilinear springs that yield repeatedly. The yield kinks (stiffness k -> alpha k at first yield) are not
// located inside a step, so every stepper is at best second order: a kink costs O(h^2) per event.
TEST(ConvergenceOrder, BilinearWithYielding) {
  const double dt = 0.02;
  const std::vector<double> ag = test::two_tone(dt, 4.0);
  PairParams p = uncoupled_pair(0.6, 0.05, 0.9, 0.03);
  p.s1.fy = 0.4 * p.s1.k * 0.03, p.s1.alpha = 0.1;  // peak elastic displacement ~0.05 m: yields at 0.012 m
  p.s2.fy = 0.4 * p.s2.k * 0.06, p.s2.alpha = 0.05;
  const ContactModel none = test::contact(ContactLaw::none);
  std::vector<double> r1, r2;
  reference_by_fine_run(p, none, ag, dt, 512, r1, r2);
  for (Stepper st : all_steppers) {
    Convergence c = measure(p, none, ag, dt, st, r1, r2);
    print("bilinear", st, c);
    // second order up to the jitter of kinks falling at different places inside a step
    EXPECT_GT(c.order[1] + c.order[2], 2 * 1.6) << to_string(st);
    EXPECT_LT(c.err[3], c.err[0] / 20) << to_string(st);
  }
}

// Hertz contact (n = 3/2, e = 1): contact onset and exit are not located inside a step.
TEST(ConvergenceOrder, HertzContact) {
  const double dt = 0.01;
  const std::vector<double> ag = test::two_tone(dt, 4.0);
  PairParams p = uncoupled_pair(0.6, 0.05, 0.9, 0.03);
  p.gap = 0.02;
  p.kc = 5.0e8;  // contact lasting ~0.1 s: 10 to 80 steps per contact
  const ContactModel hz = test::contact(ContactLaw::hertz);
  std::vector<double> r1, r2;
  reference_by_fine_run(p, hz, ag, dt, 1024, r1, r2);
  {
    BatchResult r = run_one(p, hz, ag, dt, 0.0, Stepper::rk4, 8);
    std::printf("Hertz case: %d impacts, peak force %.3g N, peak penetration %.3g m\n", r.impact_count[0],
                r.peak_force[0], r.peak_penetration[0]);
    ASSERT_GE(r.impact_count[0], 2);
  }
  for (Stepper st : all_steppers) {
    Convergence c = measure(p, hz, ag, dt, st, r1, r2);
    print("hertz contact", st, c);
    EXPECT_GT(c.order[1] + c.order[2], 2 * 1.6) << to_string(st);
    EXPECT_LT(c.err[3], c.err[0] / 20) << to_string(st);
  }
}

}  // namespace
}  // namespace pounding
