// Response spectra: closed-form SDOF responses (step load, harmonic load from rest), a published
// spectrum (Chopra's El Centro 1940 NS values), an independent fine-step RK4 on a real record, and
// the definitions PSA = w^2 SD, PSV = w SD, PSA(0) = PGA.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "pounding/core/error.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/motion/spectrum.hpp"
#include "test_data.hpp"

using namespace pounding;

namespace {
const std::string real_dir = testdata::real_records_dir();
constexpr double pi = std::numbers::pi;
}  // namespace

TEST(SpectrumClosedForm, SuddenlyAppliedConstantAcceleration) {
  // u'' + 2 z w u' + w^2 u = -a0 from rest: u = -(a0/w^2)(1 - e^{-z w t}(cos wd t + z/sqrt(1-z^2) sin wd t)),
  // peak (a0/w^2)(1 + exp(-z pi / sqrt(1 - z^2))) at t = pi / wd (Chopra, Dynamics of Structures, 4.3).
  const double a0 = 2.0;
  Record r;
  r.dt = 0.01;
  r.acc.assign(1001, a0);  // 10 s
  for (double z : {0.0, 0.02, 0.05, 0.2}) {
    for (double T : {0.1, 0.37, 1.0, 2.5}) {
      const double w = 2 * pi / T;
      const double expect = a0 / (w * w) * (1 + std::exp(-z * pi / std::sqrt(1 - z * z)));
      // the sampled peak is within (pi/40)^2/2 = 0.3 % of the continuous one (spectrum.hpp)
      EXPECT_NEAR(peak_displacement(r, T, z) / expect, 1.0, 0.003) << "T " << T << " zeta " << z;
    }
  }
  // undamped, T = 1 s: the peak t = 0.5 s falls on a sample, so the recurrence's exactness shows
  EXPECT_NEAR(peak_displacement(r, 1.0, 0.0), 2 * a0 / std::pow(2 * pi, 2), 1e-12);
}

TEST(SpectrumClosedForm, HarmonicLoadFromRest) {
  // a(t) = A sin(W t) for 0 <= t <= te, then 0 (te on a zero of the sine, so the sampled record's
  // last segment matches). Exact u(t) (particular + homogeneous from rest, then
  // free vibration), its maximum on a fine grid, against the recurrence on the sampled sine (piecewise
  // linear with h = 1e-3 s: interpolation error ~ (W h)^2 / 12 < 1e-5).
  const double A = 3.0, W = 2 * pi * 1.25, h = 1e-3, te = 6.4;  // 8 whole cycles: a(te) = 0
  Record r;
  r.dt = h;
  for (int k = 0; k <= static_cast<int>(te / h + 0.5); ++k) r.acc.push_back(A * std::sin(W * k * h));
  for (double T : {0.3, 0.8, 1.0, 2.0}) {  // 0.8 s: resonance
    for (double z : {0.02, 0.05}) {
      const double w = 2 * pi / T, wd = w * std::sqrt(1 - z * z);
      const double Dl = (w * w - W * W) * (w * w - W * W) + (2 * z * w * W) * (2 * z * w * W);
      const double C = -A * (w * w - W * W) / Dl, D = A * 2 * z * w * W / Dl;
      const double E = -D, F = (z * w * E - C * W) / wd;
      auto u_forced = [&](double t) {
        return C * std::sin(W * t) + D * std::cos(W * t) + std::exp(-z * w * t) * (E * std::cos(wd * t) + F * std::sin(wd * t));
      };
      auto v_forced = [&](double t) {
        const double e = std::exp(-z * w * t);
        return C * W * std::cos(W * t) - D * W * std::sin(W * t) - z * w * e * (E * std::cos(wd * t) + F * std::sin(wd * t)) +
               e * wd * (-E * std::sin(wd * t) + F * std::cos(wd * t));
      };
      double peak = 0;
      for (double t = 0; t <= te; t += 1e-4) peak = std::max(peak, std::abs(u_forced(t)));
      const double ue = u_forced(te), ve = v_forced(te);
      for (double t = 0; t <= 2 * T; t += 1e-4) {
        const double u = std::exp(-z * w * t) * (ue * std::cos(wd * t) + (ve + z * w * ue) / wd * std::sin(wd * t));
        peak = std::max(peak, std::abs(u));
      }
      // peak sampled >= 2000 times per period here, so only the interpolation error remains
      EXPECT_NEAR(peak_displacement(r, T, z, 2000.0) / peak, 1.0, 2e-5) << "T " << T << " zeta " << z;
      EXPECT_NEAR(peak_displacement(r, T, z) / peak, 1.0, 3e-3) << "T " << T << " zeta " << z;
    }
  }
}

TEST(SpectrumPublished, ChopraElCentro1940Deformations) {
  // Chopra, Dynamics of Structures, Fig. 6.4.1 (El Centro 1940 NS, PGA 0.319 g, zeta = 2 %):
  // D = 2.67, 5.97, 7.47 in for Tn = 0.5, 1, 2 s (printed to 3 figures: +-0.2 %; the file is the
  // Peknold digitization, which may differ slightly from Chopra's: 1 % allowed).
  POUNDING_REQUIRE_REAL_RECORDS();
  const Record r = read_record(real_dir + "/ImperialValley_1940_ElCentro_NS_Peknold1559pts.AT2");
  const std::vector<double> T{0.5, 1.0, 2.0};
  const Spectrum s = response_spectrum(r, T, 0.02);
  const double inch = 0.0254;
  EXPECT_NEAR(s.sd[0] / inch / 2.67, 1.0, 0.01);
  EXPECT_NEAR(s.sd[1] / inch / 5.97, 1.0, 0.01);
  EXPECT_NEAR(s.sd[2] / inch / 7.47, 1.0, 0.01);
  // and the pseudo-accelerations Chopra lists, A/g = 1.09, 0.610, 0.191
  EXPECT_NEAR(s.psa[0] / g_accel / 1.09, 1.0, 0.01);
  EXPECT_NEAR(s.psa[1] / g_accel / 0.610, 1.0, 0.01);
  EXPECT_NEAR(s.psa[2] / g_accel / 0.191, 1.0, 0.01);
}

TEST(SpectrumIndependent, FineStepRk4OnARealRecord) {
  // Classical RK4 with h = dt/200 on the same piecewise-linear ground motion (and the same one-period
  // free-vibration tail) agrees with the exact recurrence to RK4's truncation error.
  POUNDING_REQUIRE_REAL_RECORDS();
  Record r = read_record(real_dir + "/LomaPrieta_1989_Capitola_000.txt");
  r.acc.resize(2001);  // first 10 s keep the test fast
  for (double T : {0.2, 1.0, 3.0}) {
    const double z = 0.05, w = 2 * pi / T;
    const int sub = 200;
    const double h = r.dt / sub;
    const std::size_t tail = static_cast<std::size_t>(std::ceil(T / r.dt)) + 1, n = r.acc.size();
    double u = 0, v = 0, peak = 0;
    for (std::size_t k = 0; k + 1 < n + tail; ++k) {
      const double a0 = k < n ? r.acc[k] : 0.0, a1 = k + 1 < n ? r.acc[k + 1] : 0.0;
      auto ag = [&](double s) { return a0 + (a1 - a0) * s / r.dt; };
      auto f = [&](double s, double uu, double vv) { return -ag(s) - 2 * z * w * vv - w * w * uu; };
      for (int j = 0; j < sub; ++j) {
        const double s = j * h;
        const double k1u = v, k1v = f(s, u, v);
        const double k2u = v + 0.5 * h * k1v, k2v = f(s + 0.5 * h, u + 0.5 * h * k1u, v + 0.5 * h * k1v);
        const double k3u = v + 0.5 * h * k2v, k3v = f(s + 0.5 * h, u + 0.5 * h * k2u, v + 0.5 * h * k2v);
        const double k4u = v + h * k3v, k4v = f(s + h, u + h * k3u, v + h * k3v);
        u += h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
        peak = std::max(peak, std::abs(u));
      }
    }
    // the same sampling instants (sub-steps of dt/200): only RK4's truncation error remains
    // (RK4 truncation error ~(w h)^4 plus rounding over 4e5 steps: < 1e-7)
    EXPECT_NEAR(peak_displacement(r, T, z, 200.0 * T / r.dt) / peak, 1.0, 1e-7) << "T " << T;
    EXPECT_NEAR(peak_displacement(r, T, z) / peak, 1.0, 3e-3) << "T " << T;
  }
}

TEST(SpectrumDefinitions, PseudoQuantitiesPgaAndLinearity) {
  Record r;
  r.dt = 0.01;
  for (int k = 0; k < 1500; ++k) r.acc.push_back(std::sin(0.07 * k) * std::exp(-0.002 * k) + 0.3 * std::cos(0.31 * k));
  const std::vector<double> T{0.0, 0.05, 0.5, 4.0};
  const Spectrum s = response_spectrum(r, T, 0.05);
  EXPECT_DOUBLE_EQ(s.psa[0], r.pga());
  for (std::size_t i = 1; i < T.size(); ++i) {
    const double w = 2 * pi / T[i];
    EXPECT_DOUBLE_EQ(s.psv[i], w * s.sd[i]);
    EXPECT_DOUBLE_EQ(s.psa[i], w * w * s.sd[i]);
  }
  Record r2 = r;
  for (double& a : r2.acc) a *= -2.5;
  const Spectrum s2 = response_spectrum(r2, T, 0.05);
  for (std::size_t i = 0; i < T.size(); ++i) EXPECT_NEAR(s2.psa[i], 2.5 * s.psa[i], 1e-12 * s.psa[i]);
  // very short period: the oscillator follows the ground, PSA -> PGA
  const std::vector<double> Ts{0.002};
  EXPECT_NEAR(response_spectrum(r, Ts, 0.05).psa[0] / r.pga(), 1.0, 0.01);
  EXPECT_THROW(response_spectrum(r, T, 1.0), InputError);
  EXPECT_THROW(response_spectrum(r, std::vector<double>{-1.0}, 0.05), InputError);
  EXPECT_EQ(default_periods().size(), 101u);
}
