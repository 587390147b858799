// Intensity measures (issue 14 part 1): PGA against Record::pga, PGV of a half-sine pulse in closed form,
// Sa of a suddenly applied constant acceleration (SD = 2 a0 / w^2 undamped) and of a harmonic steady state,
// Sa_avg as the geometric mean of the single-period Sa, linearity in amplitude, and the errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pounding/core/error.hpp"
#include "pounding/motion/intensity.hpp"
#include "pounding/motion/spectrum.hpp"
#include "pounding/motion/synthetic.hpp"

#include "input_error.hpp"

using namespace pounding;

namespace {

constexpr double pi = std::numbers::pi;

Record synthetic_record(std::uint64_t seed) {
  SynthOptions o;
  o.dt = 0.01;
  return synthesize(SiteParams{6.5, 20.0, 400.0, 0}, seed, o);
}

IntensityMeasure sa_at(double t, double zeta = 0.05) { return {ImMeasure::sa, {t}, zeta}; }

}  // namespace

TEST(Intensity, Names) {
  EXPECT_EQ(parse_im_measure("Sa_avg"), ImMeasure::sa_avg);
  EXPECT_EQ(to_string(ImMeasure::pgv), "PGV");
  const InputError e = testdata::input_error([] { parse_im_measure("SA"); });
  EXPECT_EQ(e.where(), "--measure");
  EXPECT_NE(e.fix().find("PGA, PGV, Sa or Sa_avg"), std::string::npos) << e.fix();
  EXPECT_STREQ(im_units(ImMeasure::pgv), "m/s");
  EXPECT_STREQ(im_units(ImMeasure::sa_avg), "g");
  EXPECT_EQ(describe(sa_at(1.0)), "Sa(1.00 s, 5 % damping), g");
  IntensityMeasure avg{ImMeasure::sa_avg, {0.2, 0.5, 1.0, 2.0}, 0.05};
  EXPECT_EQ(describe(avg), "Sa_avg over 4 periods 0.20-2.00 s (geometric mean of Sa, 5 % damping), g");
  EXPECT_EQ(describe({ImMeasure::pgv, {}, 0.05}), "PGV, m/s");
}

TEST(Intensity, PgaIsRecordPgaInG) {
  const Record r = synthetic_record(3);
  EXPECT_DOUBLE_EQ(intensity(r, {ImMeasure::pga, {}, 0.05}), r.pga() / g_accel);
}

TEST(Intensity, PgvOfHalfSinePulse) {
  // ag = A sin(pi t / tp) on [0, tp], 0 after: v(t) = -(A tp / pi)(cos(pi t / tp) - 1), peak 2 A tp / pi at tp.
  // The samples of a sine are not a piecewise-linear sine, so compare with the exact integral of the linear
  // interpolant: the trapezoid sum h sum (a_k + a_{k+1}) / 2 = h sum a_k (ends are 0), and the continuous
  // value to O(h^2) as a check of the closed form.
  const double A = 3.0, tp = 0.5, h = 0.001;
  Record r;
  r.dt = h;
  const int n = static_cast<int>(std::lround(tp / h));
  for (int k = 0; k <= n + 500; ++k) r.acc.push_back(k <= n ? A * std::sin(pi * k / n) : 0.0);
  double trapezoid = 0;
  for (int k = 0; k <= n; ++k) trapezoid += h * r.acc[k];
  const double v = intensity(r, {ImMeasure::pgv, {}, 0.05});
  EXPECT_NEAR(v, trapezoid, 1e-12);
  // h sum sin(pi k / n) = h cot(pi / 2n) exactly (a geometric sum)
  EXPECT_NEAR(v, A * h / std::tan(pi / (2.0 * n)), 1e-9);
  EXPECT_NEAR(v, 2 * A * tp / pi, 2 * A * tp / pi * (pi * pi / (12.0 * n * n)) * 1.01);
  EXPECT_DOUBLE_EQ(pgv(r), v);
}

TEST(Intensity, PgvOfConstantAccelerationIsExact) {
  // a linear interpolant that is exactly the signal: ag = a0 for T s gives v = a0 T.
  Record r;
  r.dt = 0.02;
  r.acc.assign(251, -1.5);  // 5 s
  EXPECT_NEAR(pgv(r), 1.5 * 5.0, 1e-12);
}

TEST(Intensity, SaOfStepOnUndampedOscillator) {
  // ag = a0 from rest, zeta = 0: u = (a0 / w^2)(1 - cos wt), SD = 2 a0 / w^2, Sa = w^2 SD / g = 2 a0 / g.
  // With T = 1 s and dt = 0.01 s the peak t = T/2 falls on a sample, so the value is exact to rounding.
  const double a0 = 2.0;
  Record r;
  r.dt = 0.01;
  r.acc.assign(1001, a0);
  EXPECT_NEAR(intensity(r, sa_at(1.0, 0.0)), 2 * a0 / g_accel, 1e-12);
  EXPECT_NEAR(intensity(r, sa_at(0.5, 0.0)), 2 * a0 / g_accel, 1e-12);  // t = 0.25 s is a sample too
}

TEST(Intensity, SaOfHarmonicSteadyState) {
  // ag = A sin(W t), ramped in and out, 100 s: the steady amplitude
  // A / sqrt((w^2 - W^2)^2 + (2 zeta w W)^2), sampled within 0.3 % (spectrum.hpp) and by the transient's rest.
  const double A = 1.0, Tw = 0.7, zeta = 0.2, T = 1.0, dt = 0.005;
  const double W = 2 * pi / Tw, w = 2 * pi / T;
  Record r;
  r.dt = dt;
  // 30 s cosine ramps in and out keep both ends quasi-static (an abrupt end leaves the oscillator in free
  // vibration from wherever it stood; SciPy's lsim puts the overshoot of 10 s ramps at 0.44 %, of 30 s at 0.03 %)
  for (int k = 0; k <= 20000; ++k) {
    const double t = k * dt, edge = std::min(t, 100 - t);
    const double ramp = edge < 30 ? 0.5 * (1 - std::cos(pi * edge / 30)) : 1.0;
    r.acc.push_back(ramp * A * std::sin(W * t));
  }
  const double u = A / std::sqrt(std::pow(w * w - W * W, 2) + std::pow(2 * zeta * w * W, 2));
  const double expect = w * w * u / g_accel;
  EXPECT_NEAR(intensity(r, sa_at(T, zeta)) / expect, 1.0, 0.003);  // the sampled peak is within 0.3 % below
}

TEST(Intensity, SaAvgIsGeometricMean) {
  const Record r = synthetic_record(5);
  const std::vector<double> T{0.2, 0.35, 0.6, 1.0, 1.7, 3.0};
  double ln = 0;
  for (double t : T) ln += std::log(intensity(r, sa_at(t)));
  EXPECT_NEAR(intensity(r, {ImMeasure::sa_avg, T, 0.05}), std::exp(ln / T.size()), 1e-14);
  // and Sa agrees with the response spectrum
  const Spectrum s = response_spectrum(r, T, 0.05);
  for (std::size_t j = 0; j < T.size(); ++j) EXPECT_DOUBLE_EQ(intensity(r, sa_at(T[j])), s.psa[j] / g_accel);
}

TEST(Intensity, LinearInAmplitude) {
  const Record r = synthetic_record(7);
  Record r37 = r;
  for (double& a : r37.acc) a *= 3.7;
  for (const IntensityMeasure& im : {IntensityMeasure{ImMeasure::pga, {}, 0.05}, IntensityMeasure{ImMeasure::pgv, {}, 0.05},
                                     sa_at(0.8), sa_at(2.5, 0.02),
                                     IntensityMeasure{ImMeasure::sa_avg, {0.2, 0.5, 1.0, 2.0}, 0.05}}) {
    const double a = intensity(r, im), b = intensity(r37, im);
    EXPECT_NEAR(b / (3.7 * a), 1.0, 1e-12) << describe(im);
    EXPECT_NEAR(scale_to_level(a, 3.7 * a), 3.7, 1e-15);
  }
}

TEST(Intensity, InvalidInputsThrow) {
  const Record r = synthetic_record(1);
  auto where = [&](const IntensityMeasure& im) { return testdata::input_error([&] { intensity(r, im); }).where(); };
  EXPECT_EQ(where({ImMeasure::sa, {}, 0.05}), "--period");
  EXPECT_EQ(where({ImMeasure::sa, {0.5, 1.0}, 0.05}), "--period");
  EXPECT_EQ(where({ImMeasure::sa, {0.0}, 0.05}), "--period");
  EXPECT_EQ(where({ImMeasure::sa, {-1.0}, 0.05}), "--period");
  EXPECT_EQ(where({ImMeasure::sa, {NAN}, 0.05}), "--period");
  EXPECT_EQ(where({ImMeasure::sa_avg, {1.0}, 0.05}), "--periods");
  EXPECT_EQ(where({ImMeasure::sa_avg, {1.0, 1.0}, 0.05}), "--periods");
  EXPECT_EQ(where({ImMeasure::pga, {1.0}, 0.05}), "--period");
  EXPECT_EQ(where({ImMeasure::sa, {1.0}, 1.0}), "--damping");
  EXPECT_EQ(where({ImMeasure::sa, {1.0}, -0.01}), "--damping");
  EXPECT_THROW(intensity(Record{}, {ImMeasure::pga, {}, 0.05}), InputError);
  EXPECT_THROW(scale_to_level(0.0, 1.0), InputError);
  EXPECT_THROW(scale_to_level(1.0, -1.0), InputError);
  EXPECT_NO_THROW(validate(IntensityMeasure{ImMeasure::sa_avg, {0.2, 2.0}, 0.0}));
}
