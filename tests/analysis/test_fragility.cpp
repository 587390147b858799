// Lognormal fragility fits (include/pounding/analysis/fragility.hpp): Baker's (2015) worked MSA example, an
// exactly solvable two-stripe fit, recovery of known parameters from seeded simulated stripes, the data without
// a finite MLE (no pounding, all pounded, separation), input errors, and the IDA method-of-moments fit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "pounding/analysis/fragility.hpp"

using namespace pounding;

namespace {

std::vector<Stripe> stripes(const std::vector<double>& x, std::int64_t n, const std::vector<std::int64_t>& z) {
  std::vector<Stripe> s;
  for (std::size_t j = 0; j < x.size(); ++j) s.push_back({x[j], n, z[j]});
  return s;
}

TEST(Fragility, BakerWorkedExample) {  // research note 1.4, values computed with SciPy
  const auto s = stripes({0.2, 0.3, 0.4, 0.6, 0.7, 0.8, 0.9, 1.0}, 40, {0, 0, 0, 4, 6, 13, 12, 16});
  const FragilityFit fit = fit_fragility_msa(s);
  ASSERT_TRUE(fit.ok()) << fit.message;
  EXPECT_NEAR(fit.fragility.theta, 1.076116, 1e-5);
  EXPECT_NEAR(fit.fragility.beta, 0.429237, 1e-5);
  EXPECT_NEAR(fit.neg_log_likelihood, 10.797705, 1e-5);
  EXPECT_NEAR(fit.se_log_theta, 0.070974, 1e-5);  // expected information
  EXPECT_NEAR(fit.se_beta, 0.082104, 1e-5);
  EXPECT_NEAR(fit.fragility(0.6), 0.08676, 1e-5);
  EXPECT_NEAR(fit.fragility(1.0), 0.43215, 1e-5);
  EXPECT_LT(fit.iterations, 50);
}

TEST(Fragility, OrderAndPoolingDoNotMatter) {
  auto s = stripes({0.2, 0.3, 0.4, 0.6, 0.7, 0.8, 0.9, 1.0}, 40, {0, 0, 0, 4, 6, 13, 12, 16});
  std::vector<Stripe> shuffled(s.rbegin(), s.rend());
  shuffled.back() = {0.2, 15, 0};  // the stripe at 0.2 in two parts: 15 + 25 trials
  shuffled.push_back({0.2, 25, 0});
  const FragilityFit a = fit_fragility_msa(s), b = fit_fragility_msa(shuffled);
  ASSERT_TRUE(b.ok());
  EXPECT_NEAR(a.fragility.theta, b.fragility.theta, 1e-10);
  EXPECT_NEAR(a.fragility.beta, b.fragility.beta, 1e-10);
}

TEST(Fragility, TwoStripesFitExactly) {  // theta = sqrt(0.5 * 1), beta = ln 2 / (2 * 0.674490)
  const FragilityFit fit = fit_fragility_msa(stripes({0.5, 1.0}, 40, {10, 30}));
  ASSERT_TRUE(fit.ok());
  EXPECT_NEAR(fit.fragility.theta, std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(fit.fragility.beta, std::log(2.0) / (2 * 0.6744897501960817), 1e-9);
}

TEST(Fragility, RecoversKnownParametersFromSimulatedStripes) {
  const LognormalFragility truth{0.8, 0.5};
  std::mt19937_64 rng(20240614);
  std::vector<Stripe> s;
  for (int j = 0; j < 10; ++j) {
    const double x = 0.3 * std::pow(1.2, j);
    std::binomial_distribution<std::int64_t> bin(500, truth(x));
    s.push_back({x, 500, bin(rng)});
  }
  const FragilityFit fit = fit_fragility_msa(s);
  ASSERT_TRUE(fit.ok()) << fit.message;
  EXPECT_LT(std::abs(std::log(fit.fragility.theta / truth.theta)), 4 * fit.se_log_theta);
  EXPECT_LT(std::abs(fit.fragility.beta - truth.beta), 4 * fit.se_beta);
  EXPECT_LT(fit.se_log_theta, 0.03);  // the tolerance is tight enough to mean something
  EXPECT_LT(fit.se_beta, 0.04);
}

TEST(Fragility, NoPoundingIsReportedWithTheRuleOfThree) {
  const FragilityFit fit = fit_fragility_msa(stripes({0.2, 0.4, 0.8}, 40, {0, 0, 0}));
  EXPECT_EQ(fit.status, FragilityStatus::no_pounding);
  EXPECT_FALSE(fit.ok());
  EXPECT_NEAR(fit.bound, 1 - std::pow(0.05, 1.0 / 120), 1e-15);
  EXPECT_NEAR(fit.bound, 3.0 / 120, 2e-3);
}

TEST(Fragility, AllPoundedIsReported) {
  const FragilityFit fit = fit_fragility_msa(stripes({0.2, 0.4}, 40, {40, 40}));
  EXPECT_EQ(fit.status, FragilityStatus::all_pounded);
  EXPECT_NEAR(fit.bound, std::pow(0.05, 1.0 / 80), 1e-15);
}

TEST(Fragility, CompleteSeparationIsFlaggedWithItsBracket) {  // research note 1.3
  const FragilityFit fit = fit_fragility_msa(stripes({0.2, 0.4, 0.6, 0.8}, 40, {0, 0, 40, 40}));
  EXPECT_EQ(fit.status, FragilityStatus::separated);
  EXPECT_EQ(fit.bracket.lo, 0.4);
  EXPECT_EQ(fit.bracket.hi, 0.6);
  EXPECT_NE(fit.message.find("separated"), std::string::npos);
}

TEST(Fragility, QuasiCompleteSeparationIsFlagged) {  // 0/40, 20/40, 40/40: theta = 1, beta -> 0
  const FragilityFit fit = fit_fragility_msa(stripes({0.5, 1.0, 2.0}, 40, {0, 20, 40}));
  EXPECT_EQ(fit.status, FragilityStatus::separated);
  EXPECT_EQ(fit.bracket.lo, 1.0);
  EXPECT_EQ(fit.bracket.hi, 1.0);
  const FragilityFit one = fit_fragility_msa(stripes({0.5, 1.0}, 40, {0, 10}));
  EXPECT_EQ(one.status, FragilityStatus::separated);
}

TEST(Fragility, OverlapIsNotSeparation) {  // one all-zero stripe above a pounded one: a finite MLE
  const FragilityFit fit = fit_fragility_msa(stripes({0.5, 0.6, 1.0, 2.0}, 40, {0, 1, 0, 40}));
  EXPECT_TRUE(fit.ok()) << fit.message;
}

TEST(Fragility, DecreasingDataHaveNoFragility) {
  EXPECT_EQ(fit_fragility_msa(stripes({0.5, 1.0}, 40, {30, 10})).status, FragilityStatus::decreasing);
  EXPECT_EQ(fit_fragility_msa(stripes({0.5, 1.0}, 40, {40, 0})).status, FragilityStatus::decreasing);
}

TEST(Fragility, BadInputThrows) {
  EXPECT_THROW(fit_fragility_msa(stripes({0.0, 1.0}, 40, {0, 10})), std::invalid_argument);
  EXPECT_THROW(fit_fragility_msa(stripes({-1.0, 1.0}, 40, {0, 10})), std::invalid_argument);
  EXPECT_THROW(fit_fragility_msa(stripes({0.5, 1.0}, 40, {0, 41})), std::invalid_argument);
  EXPECT_THROW(fit_fragility_msa(stripes({0.5, 1.0}, 40, {-1, 10})), std::invalid_argument);
  EXPECT_THROW(fit_fragility_msa(stripes({0.5, 1.0}, 0, {0, 0})), std::invalid_argument);
  EXPECT_THROW(fit_fragility_msa(stripes({1.0}, 40, {10})), std::invalid_argument);
  EXPECT_THROW(fit_fragility_msa(stripes({1.0, 1.0}, 40, {10, 20})), std::invalid_argument);  // one level
  EXPECT_THROW(fit_fragility_msa(stripes({NAN, 1.0}, 40, {10, 20})), std::invalid_argument);
}

TEST(Fragility, MomentsFitOnBakersIdaExample) {  // research note 1.4
  const std::vector<double> c{0.45, 0.62, 0.71, 0.78, 0.86, 0.95, 1.08, 1.21, 1.40, 1.73};
  const LognormalFragility f = fit_fragility_moments(c);
  EXPECT_NEAR(f.theta, 0.912339, 1e-6);
  EXPECT_NEAR(f.beta, 0.400317, 1e-6);
}

TEST(Fragility, MomentsFitIsExactOnSymmetricData) {
  const double m = std::log(0.7), s = 0.3;
  const std::vector<double> c{std::exp(m - s), std::exp(m), std::exp(m + s)};
  const LognormalFragility f = fit_fragility_moments(c);
  EXPECT_NEAR(f.theta, 0.7, 1e-14);
  EXPECT_NEAR(f.beta, s, 1e-14);  // sqrt(2 s^2 / (3 - 1))
  EXPECT_THROW(fit_fragility_moments(std::vector<double>{1.0}), std::invalid_argument);
  EXPECT_THROW(fit_fragility_moments(std::vector<double>{1.0, 0.0}), std::invalid_argument);
}

TEST(Fragility, NormalCdfTails) {
  EXPECT_DOUBLE_EQ(normal_cdf(0), 0.5);
  EXPECT_NEAR(normal_cdf(1.959963984540054), 0.975, 1e-15);
  for (double u : {-5.0, -20.0, -29.9, -30.1, -35.0, -37.0})
    EXPECT_NEAR(log_normal_cdf(u), std::log(0.5 * std::erfc(-u / std::sqrt(2.0))), 1e-9 * std::abs(u * u)) << u;
  EXPECT_TRUE(std::isfinite(log_normal_cdf(-100.0)));
  EXPECT_NEAR(log_normal_cdf(-100.0), -5000 - std::log(100.0) - 0.5 * std::log(2 * M_PI), 1e-3);
  EXPECT_NEAR(log_normal_cdf(10.0), -7.619853024160527e-24, 1e-30);
}

}  // namespace
