// The statistics of the study's tables (include/pounding/analysis/stats.hpp): the Wilson score interval against
// published and independently computed values, the cubic least-squares fit on exact and noisy data, the
// root finder on the fit, and the CQC correlation against its closed form and its known points.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "pounding/analysis/stats.hpp"

using namespace pounding;

namespace {

struct WilsonCase {
  std::int64_t k, n;
  double lo, hi;
};

}  // namespace

// Newcombe (1998), "Two-sided confidence intervals for the single proportion: comparison of seven methods",
// Stat. Med. 17:857-872, Table II, method 3 (score interval without continuity correction), 4 decimals.
TEST(Wilson, NewcombeTableII) {
  const WilsonCase cases[] = {
      {81, 263, 0.2553, 0.3662},
      {15, 148, 0.0624, 0.1605},
      {0, 20, 0.0000, 0.1611},
      {1, 29, 0.0061, 0.1718},
  };
  for (const auto& c : cases) {
    const Interval iv = wilson_interval(c.k, c.n);
    EXPECT_NEAR(iv.lo, c.lo, 0.5e-4) << c.k << "/" << c.n;
    EXPECT_NEAR(iv.hi, c.hi, 0.5e-4) << c.k << "/" << c.n;
  }
}

// scipy 1.10.1: scipy.stats.binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson").
TEST(Wilson, MatchesScipyToRounding) {
  const WilsonCase cases[] = {
      {81, 263, 0.2552885198782742, 0.36620957698280004},
      {1, 29, 0.006113214292762667, 0.17175521879320282},
      {29, 29, 0.8830302015002592, 1.0},
      {0, 10, 0.0, 0.27753279986288926},
      {5, 10, 0.236593090512564, 0.7634069094874361},
      {1, 1000, 0.00017654637062607809, 0.0056425585979579355},
      {15488, 30976, 0.4944322657263659, 0.5055677342736341},
  };
  for (const auto& c : cases) {
    const Interval iv = wilson_interval(c.k, c.n);
    EXPECT_NEAR(iv.lo, c.lo, 1e-12) << c.k << "/" << c.n;
    EXPECT_NEAR(iv.hi, c.hi, 1e-12) << c.k << "/" << c.n;
  }
}

// The interval's definition: its ends are the p where the score statistic |k/n - p| / sqrt(p (1 - p) / n)
// equals z (interior ends only; 0 and 1 are clipped ends).
TEST(Wilson, EndsSolveTheScoreEquation) {
  const double z = 1.959963984540054;
  for (auto [k, n] : {std::pair<std::int64_t, std::int64_t>{3, 17}, {50, 100}, {999, 1000}, {7, 30976}}) {
    const Interval iv = wilson_interval(k, n);
    const double phat = static_cast<double>(k) / static_cast<double>(n);
    for (double p : {iv.lo, iv.hi}) {
      const double score = std::abs(phat - p) / std::sqrt(p * (1 - p) / static_cast<double>(n));
      EXPECT_NEAR(score, z, 1e-9) << k << "/" << n << " at p = " << p;
    }
    EXPECT_LT(iv.lo, phat);
    EXPECT_GT(iv.hi, phat);
  }
  // a wider z widens it; no trials: the whole of [0, 1]
  const Interval i95 = wilson_interval(10, 40), i99 = wilson_interval(10, 40, 2.5758293035489004);
  EXPECT_LT(i99.lo, i95.lo);
  EXPECT_GT(i99.hi, i95.hi);
  const Interval none = wilson_interval(0, 0);
  EXPECT_EQ(none.lo, 0.0);
  EXPECT_EQ(none.hi, 1.0);
}

TEST(CubicFit, ExactCubicRecoversItsCoefficients) {
  const double c0 = 0.25, c1 = -1.5, c2 = 0.75, c3 = 2.0;
  std::vector<double> x, y;
  for (int i = 0; i <= 20; ++i) {
    const double xi = 0.1 + 0.07 * i;
    x.push_back(xi);
    y.push_back(c0 + c1 * xi + c2 * xi * xi + c3 * xi * xi * xi);
  }
  const CubicFit f = fit_cubic(x, y);
  EXPECT_NEAR(f.c[0], c0, 1e-11);
  EXPECT_NEAR(f.c[1], c1, 1e-11);
  EXPECT_NEAR(f.c[2], c2, 1e-11);
  EXPECT_NEAR(f.c[3], c3, 1e-11);
  EXPECT_NEAR(f.r2, 1.0, 1e-13);
  EXPECT_NEAR(f(0.5), c0 + c1 * 0.5 + c2 * 0.25 + c3 * 0.125, 1e-12);
  // four points determine the cubic: y = x^3 - 2x + 1 through x = 0, 1, 2, 3
  const std::vector<double> x4{0.0, 1.0, 2.0, 3.0}, y4{1.0, 0.0, 5.0, 22.0};
  const CubicFit g = fit_cubic(x4, y4);
  const double want[4] = {1.0, -2.0, 0.0, 1.0};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(g.c[i], want[i], 1e-12) << i;
}

// On data that no cubic fits exactly, least squares leaves a residual orthogonal to 1, x, x^2 and x^3
// (the normal equations), and R^2 = 1 - SS_res / SS_tot.
TEST(CubicFit, NoisyDataSatisfyTheNormalEquations) {
  std::vector<double> x, y;
  for (int i = 0; i < 25; ++i) {
    const double xi = 0.05 * i;
    x.push_back(xi);
    y.push_back(std::exp(-xi) + 0.01 * std::sin(37.0 * xi));
  }
  const CubicFit f = fit_cubic(x, y);
  double ss_res = 0, mean = 0, ss_tot = 0;
  for (double v : y) mean += v / static_cast<double>(y.size());
  for (int p = 0; p < 4; ++p) {
    double dot = 0;
    for (std::size_t i = 0; i < x.size(); ++i) dot += (y[i] - f(x[i])) * std::pow(x[i], p);
    EXPECT_NEAR(dot, 0.0, 1e-12) << "x^" << p;
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    ss_res += (y[i] - f(x[i])) * (y[i] - f(x[i]));
    ss_tot += (y[i] - mean) * (y[i] - mean);
  }
  EXPECT_NEAR(f.r2, 1.0 - ss_res / ss_tot, 1e-12);
  EXPECT_LT(f.r2, 1.0);
  EXPECT_GT(f.r2, 0.99);
}

TEST(CubicFit, RejectsTooFewOrMismatchedPoints) {
  const std::vector<double> three{0.0, 1.0, 2.0}, four{0.0, 1.0, 2.0, 3.0};
  EXPECT_THROW(fit_cubic(three, three), std::invalid_argument);
  EXPECT_THROW(fit_cubic(four, three), std::invalid_argument);
}

TEST(SolveFit, FindsTheFirstCrossingOrNone) {
  // (x - 0.3)(x - 2)(x + 1) = x^3 - 1.3 x^2 - 1.7 x + 0.6
  CubicFit f;
  f.c = {0.6, -1.7, -1.3, 1.0};
  auto r = solve_fit(f, 0.0, 0.0, 1.0);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, 0.3, 1e-12);
  r = solve_fit(f, 0.0, 0.0, 3.0);  // the smallest of 0.3 and 2
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, 0.3, 1e-12);
  r = solve_fit(f, 0.0, 1.0, 3.0);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, 2.0, 1e-12);
  EXPECT_FALSE(solve_fit(f, 0.0, 0.5, 1.5).has_value());  // negative throughout
  EXPECT_EQ(solve_fit(f, f(0.25), 0.25, 1.0), 0.25);     // the target at the left end
}

// rho = 8 z^2 (1 + r) r^1.5 / ((1 - r^2)^2 + 4 z^2 r (1 + r)^2) (Der Kiureghian 1981, equal damping).
TEST(Cqc, KnownPointsAndSymmetry) {
  for (double z : {0.02, 0.05, 0.2}) EXPECT_NEAR(cqc_rho(1.0, z), 1.0, 1e-15) << z;  // equal frequencies
  // closed form evaluated independently (Python 3, double precision)
  EXPECT_NEAR(cqc_rho(0.5, 0.05), 0.01848645179572674, 1e-15);
  EXPECT_NEAR(cqc_rho(0.9, 0.05), 0.4730276832384835, 1e-14);
  EXPECT_NEAR(cqc_rho(0.8, 0.02), 0.030815751627904106, 1e-15);
  // the correlation depends on the pair, not the order: rho(r) = rho(1/r); it falls off the diagonal
  for (double r : {0.3, 0.7, 0.95})
    EXPECT_NEAR(cqc_rho(r, 0.05), cqc_rho(1.0 / r, 0.05), 1e-14) << r;
  EXPECT_GT(cqc_rho(0.95, 0.05), cqc_rho(0.9, 0.05));
  EXPECT_GT(cqc_rho(0.9, 0.05), cqc_rho(0.5, 0.05));
  EXPECT_EQ(cqc_rho(0.0, 0.05), 0.0);
}

// Issue 23, item 8: Wilson at a fraction with an effective n (the independent records of a fixed pair).
TEST(Stats, WilsonEffectiveEqualsWilsonForCountsAndWidensWithFewerRecords) {
  const Interval a = wilson_interval(2, 85), b = wilson_interval_effective(2.0 / 85.0, 85.0);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
  // 2.35 % of 3400 analyses (SciPy: [1.89, 2.92] %) against 2.35 % of 85 records
  const Interval analyses = wilson_interval(80, 3400), records = wilson_interval_effective(80.0 / 3400.0, 85.0);
  EXPECT_NEAR(100 * analyses.lo, 1.89, 0.01);
  EXPECT_GT(records.hi - records.lo, 4 * (analyses.hi - analyses.lo));
  EXPECT_NEAR(100 * records.lo, 0.648, 0.001);  // scipy binomtest(2, 85).proportion_ci(method="wilson"): 0.00648
  EXPECT_NEAR(100 * records.hi, 8.179, 0.001);  //   and 0.08179 (2 / 85 = 80 / 3400)
}
