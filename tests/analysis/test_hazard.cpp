// Hazard curves and the annual rate of pounding (include/pounding/analysis/hazard.hpp): the Cornell et al.
// (2002) closed form and the research note's numbers, the exact per-piece integral and the numerical one against
// it, log-log table interpolation (exact at the points, straight between, power-law beyond), the table errors,
// and P = 1 - exp(-lambda T) at small and large lambda T.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "pounding/analysis/hazard.hpp"

using namespace pounding;

namespace {

TEST(Hazard, ClosedFormMatchesTheResearchNote) {  // section 2: k0 = 4e-4, k = 2.5, theta = 0.8, beta = 0.5
  const LognormalFragility f{0.8, 0.5};
  const double lam = pounding_rate_closed_form(4e-4, 2.5, f);
  EXPECT_NEAR(lam, 1.526257e-3, 1e-9);
  EXPECT_NEAR(probability_in_years(lam, 50), 0.073474, 1e-6);
  const PoundingRate exact = pounding_rate(HazardCurve::power_law(4e-4, 2.5), f);
  EXPECT_NEAR(exact.rate / lam - 1, 0, 1e-12);
  EXPECT_EQ(exact.tail_share, 0);
}

struct Case {
  double k0, k, theta, beta;
};

TEST(Hazard, NumericalIntegralMatchesClosedForm) {
  for (const Case c : {Case{4e-4, 2.5, 0.8, 0.5}, Case{1e-3, 1.5, 0.3, 0.3}, Case{2e-5, 3.5, 1.7, 0.8},
                       Case{0.05, 2.0, 400.0, 0.6}, Case{1e-4, 1.0, 0.05, 0.15}}) {
    const LognormalFragility f{c.theta, c.beta};
    const HazardCurve h = HazardCurve::power_law(c.k0, c.k);
    const double closed = pounding_rate_closed_form(c.k0, c.k, f);
    NumericRateOptions o;
    o.x_lo = c.theta / 100, o.x_hi = c.theta * 100;
    const double numeric = pounding_rate_numeric(h, [&](double x) { return f(x); }, o).rate;
    EXPECT_NEAR(numeric / closed - 1, 0, 1e-6) << c.k0 << " " << c.k << " " << c.theta << " " << c.beta;
    EXPECT_NEAR(pounding_rate(h, f).rate / closed - 1, 0, 1e-12);
  }
}

TEST(Hazard, TableOfAPowerLawGivesTheClosedForm) {  // every segment and both tails have slope k
  std::vector<double> x, r;
  for (double v : {0.05, 0.1, 0.2, 0.5, 1.0, 2.0}) x.push_back(v), r.push_back(4e-4 * std::pow(v, -2.5));
  const HazardCurve h = HazardCurve::from_table(x, r);
  const LognormalFragility f{0.8, 0.5};
  const PoundingRate exact = pounding_rate(h, f);
  EXPECT_NEAR(exact.rate / 1.526257e-3 - 1, 0, 1e-6);
  EXPECT_GT(exact.tail_share, 0);
  EXPECT_LT(exact.tail_share, 0.1);
}

TEST(Hazard, NumericalIntegralMatchesExactOnAKinkedTable) {
  const std::vector<double> x{0.02, 0.1, 0.3, 0.6, 1.0, 1.5}, r{0.2, 2e-2, 3e-3, 6e-4, 1.2e-4, 2e-5};
  const HazardCurve h = HazardCurve::from_table(x, r);
  for (const LognormalFragility f : {LognormalFragility{0.4, 0.4}, LognormalFragility{1.2, 0.6}}) {
    const PoundingRate exact = pounding_rate(h, f);
    const PoundingRate numeric = pounding_rate_numeric(h, [&](double v) { return f(v); });
    EXPECT_NEAR(numeric.rate / exact.rate - 1, 0, 1e-6);
    EXPECT_NEAR(numeric.tail_share, exact.tail_share, 1e-6);
  }
}

TEST(Hazard, IdaCapacitiesNeedNoFit) {  // research note 2: mean of lambda(IM_c) and Cornell with MoM parameters
  const std::vector<double> c{0.45, 0.62, 0.71, 0.78, 0.86, 0.95, 1.08, 1.21, 1.40, 1.73};
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  double mean = 0;
  for (double v : c) mean += h.rate(v) / c.size();
  EXPECT_NEAR(mean, 7.842663e-4, 1e-9);
  EXPECT_NEAR(pounding_rate(h, fit_fragility_moments(c)).rate, 8.301588e-4, 1e-9);
}

TEST(Hazard, TableInterpolatesLogLog) {
  const std::vector<double> x{0.1, 0.2, 0.4, 1.0}, r{1e-2, 2e-3, 5e-4, 2e-5};
  const HazardCurve h = HazardCurve::from_table(x, r);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(h.rate(x[i]), r[i]);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {  // straight in (ln x, ln lambda)
    for (double t : {0.25, 0.5, 0.9}) {
      const double xm = std::exp((1 - t) * std::log(x[i]) + t * std::log(x[i + 1]));
      const double expect = std::exp((1 - t) * std::log(r[i]) + t * std::log(r[i + 1]));
      EXPECT_NEAR(h.rate(xm) / expect - 1, 0, 1e-12);
    }
  }
  // Beyond the table: the end segments continue as power laws.
  const double k_last = std::log(r[2] / r[3]) / std::log(x[3] / x[2]);
  EXPECT_NEAR(h.rate(3.0) / (r[3] * std::pow(3.0, -k_last)) - 1, 0, 1e-12);
  const double k_first = std::log(r[0] / r[1]) / std::log(x[1] / x[0]);
  EXPECT_NEAR(h.rate(0.01) / (r[0] * std::pow(0.1, -k_first)) - 1, 0, 1e-12);
  EXPECT_NEAR(HazardCurve::power_law(4e-4, 2.5).rate(0.5), 4e-4 * std::pow(0.5, -2.5), 1e-15);
}

TEST(Hazard, BadTablesThrow) {
  using V = std::vector<double>;
  EXPECT_THROW(HazardCurve::from_table(V{0.1, 0.2}, V{1e-2, 1e-2}), std::invalid_argument);   // flat
  EXPECT_THROW(HazardCurve::from_table(V{0.1, 0.2}, V{1e-3, 1e-2}), std::invalid_argument);   // increasing
  EXPECT_THROW(HazardCurve::from_table(V{0.2, 0.1}, V{1e-2, 1e-3}), std::invalid_argument);   // IMs decrease
  EXPECT_THROW(HazardCurve::from_table(V{0.1, 0.1}, V{1e-2, 1e-3}), std::invalid_argument);   // repeated IM
  EXPECT_THROW(HazardCurve::from_table(V{0.0, 0.1}, V{1e-2, 1e-3}), std::invalid_argument);   // IM 0
  EXPECT_THROW(HazardCurve::from_table(V{0.1, 0.2}, V{1e-2, 0.0}), std::invalid_argument);    // rate 0
  EXPECT_THROW(HazardCurve::from_table(V{0.1}, V{1e-2}), std::invalid_argument);              // one point
  EXPECT_THROW(HazardCurve::from_table(V{0.1, 0.2}, V{1e-2}), std::invalid_argument);         // lengths
  EXPECT_THROW(HazardCurve::power_law(0, 2), std::invalid_argument);
  EXPECT_THROW(HazardCurve::power_law(1e-3, -1), std::invalid_argument);
}

TEST(Hazard, ProbabilityInYears) {
  EXPECT_NEAR(probability_in_years(1e-12, 50) / 5e-11 - 1, 0, 1e-10);  // 1 - exp(-x) would lose every digit
  EXPECT_EQ(probability_in_years(0, 50), 0);
  EXPECT_EQ(probability_in_years(1.0, 50), 1 - std::exp(-50.0));
  EXPECT_EQ(probability_in_years(10.0, 50), 1.0);
  EXPECT_NEAR(probability_in_years(2.10721e-3, 50), 0.1, 1e-6);
  EXPECT_NEAR(rate_for_probability(0.10, 50), 2.10721e-3, 1e-8);
  EXPECT_NEAR(rate_for_probability(0.02, 50), 4.04054e-4, 1e-9);
  EXPECT_NEAR(rate_for_probability(0.01, 50), 2.01007e-4, 1e-9);
  EXPECT_THROW(probability_in_years(-1, 50), std::invalid_argument);
  EXPECT_THROW(rate_for_probability(1.0, 50), std::invalid_argument);
}

}  // namespace
