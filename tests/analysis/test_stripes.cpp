// MSA and IDA pounding fragility per gap, record-cluster bootstrap, annual rates and the risk-targeted gap
// (analysis/stripes.hpp): recovery of a known lognormal model and the coverage of its intervals, MSA against
// linear IDA, Cornell's closed forms, the edge cases' statuses, and the bootstrap's independence of the
// thread count. Reference numbers: the research note fragility-and-codes.md, sections 1.4 and 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>

#include "pounding/analysis/stripes.hpp"

using namespace pounding;
using namespace pounding::stripes;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> log_levels(double lo, double hi, int n) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(lo * std::pow(hi / lo, static_cast<double>(i) / (n - 1)));
  return out;
}

// D[s][r][m] = level_s exp(mu + a_r + e_rm), a_r ~ N(0, sr^2), e_rm ~ N(0, sm^2): over records and models
// P(D > x | level) = Phi(ln(level / theta(x)) / beta) exactly, theta(x) = x exp(-mu), beta = sqrt(sr^2 + sm^2).
Demands lognormal_demands(std::size_t R, std::size_t M, std::vector<double> levels, double mu, double sr, double sm,
                          std::uint64_t seed) {
  Demands d;
  d.records = R, d.models = M, d.levels = std::move(levels);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01;
  std::vector<double> eps(R * M);
  for (std::size_t r = 0; r < R; ++r) {
    const double a = sr * n01(rng);
    for (std::size_t m = 0; m < M; ++m) eps[r * M + m] = mu + a + sm * n01(rng);
  }
  for (double level : d.levels)
    for (double e : eps) d.demand.push_back(level * std::exp(e));
  return d;
}

// The demands with record j deleted (the jackknife's reference: the data without it, not a weight of 0).
Demands without_record(const Demands& d, std::size_t j) {
  Demands dj;
  dj.levels = d.levels, dj.records = d.records - 1, dj.models = d.models;
  for (std::size_t st = 0; st < d.levels.size(); ++st)
    for (std::size_t r = 0; r < d.records; ++r)
      if (r != j)
        for (std::size_t m = 0; m < d.models; ++m) dj.demand.push_back(d.demand[(st * d.records + r) * d.models + m]);
  return dj;
}

Settings quick(int bootstrap, int threads = 2, std::uint64_t seed = 11) {
  Settings s;
  s.bootstrap = bootstrap, s.threads = threads, s.seed = seed;
  return s;
}

// Linear pairs: record r has IM im[r] at scale 1 and demand1 = im[r] / C1 with ln C1 ~ N(ln theta1, beta^2) iid
// (no record effect), so the capacity at gap x is C1 x.
struct LinearData {
  std::vector<double> im, demand1, cap;
  std::size_t models = 0;
};

LinearData linear_data(std::size_t R, std::size_t M, double theta1, double beta, std::uint64_t seed) {
  LinearData L;
  L.models = M;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> u(0.2, 0.6);
  for (std::size_t r = 0; r < R; ++r) {
    L.im.push_back(u(rng));
    L.cap.push_back(1e6);
    for (std::size_t m = 0; m < M; ++m) L.demand1.push_back(L.im[r] / (theta1 * std::exp(beta * n01(rng))));
  }
  return L;
}

// MSA demands of the same linear pairs: D at stripe level = level / im[r] x demand1 (exact linear scaling).
Demands linear_msa(const LinearData& L, std::vector<double> levels) {
  Demands d;
  d.records = L.im.size(), d.models = L.models, d.levels = std::move(levels);
  for (double level : d.levels)
    for (std::size_t i = 0; i < L.demand1.size(); ++i) d.demand.push_back(level / L.im[i / L.models] * L.demand1[i]);
  return d;
}

// Capacities of one record (models = n) censored at cap.
Capacities one_record(const std::vector<double>& c, double cap) {
  Capacities out{1, c.size(), c, {cap}};
  for (double& v : out.capacity)
    if (v > cap) v = kInf;
  return out;
}

bool covers(const Interval& i, double v) { return i.lo <= v && v <= i.hi; }

}  // namespace

// ---------------------------------------------------------------- IDA against the research note, 1.4

TEST(StripesIda, MomentsAndCensoredMleMatchTheResearchNote) {
  const std::vector<double> c{0.45, 0.62, 0.71, 0.78, 0.86, 0.95, 1.08, 1.21, 1.40, 1.73};
  const GapFragility m = fit_ida(one_record(c, 10.0), {}, quick(0), nullptr, 1.0);
  ASSERT_TRUE(m.fit.ok()) << m.note;
  EXPECT_NEAR(m.fit.fragility.theta, 0.912339, 1e-6);
  EXPECT_NEAR(m.fit.fragility.beta, 0.400317, 1e-6);  // divisor n - 1
  EXPECT_NE(m.note.find("moments"), std::string::npos);

  const GapFragility t = fit_ida(one_record(c, 1.2), {}, quick(0), nullptr, 1.0);  // 1.21, 1.40, 1.73 censored
  ASSERT_TRUE(t.fit.ok()) << t.note;
  EXPECT_NEAR(t.fit.fragility.theta, 0.934698, 1e-5);
  EXPECT_NEAR(t.fit.fragility.beta, 0.417307, 1e-5);
  EXPECT_NE(t.note.find("censored"), std::string::npos);

  // the same as ten records of one model each (cap per record)
  Capacities ten{10, 1, one_record(c, 1.2).capacity, std::vector<double>(10, 1.2)};
  const GapFragility t10 = fit_ida(ten, {}, quick(0), nullptr, 1.0);
  EXPECT_NEAR(t10.fit.fragility.theta, 0.934698, 1e-5);
  EXPECT_NEAR(t10.fit.fragility.beta, 0.417307, 1e-5);
}

TEST(StripesIda, ObservedTableCountsCapacitiesAtTheLevels) {
  const std::vector<double> c{0.45, 0.62, 0.71, 0.78, 0.86, 0.95, 1.08, 1.21, 1.40, 1.73};
  const std::vector<double> levels{0.5, 1.0, 1.5};
  const GapFragility g = fit_ida(one_record(c, 1.2), levels, quick(0), nullptr, 2.0);
  ASSERT_EQ(g.observed.size(), 3u);
  EXPECT_EQ(g.gap, 2.0);
  EXPECT_EQ(g.observed[0].n, 10);
  EXPECT_EQ(g.observed[0].z, 1);
  EXPECT_EQ(g.observed[1].z, 6);
  EXPECT_EQ(g.observed[2].z, 7);  // the censored ones are not counted as pounded
  EXPECT_NEAR(g.fitted[1], g.fit.fragility(1.0), 1e-15);
}

// ---------------------------------------------------------------- 1. recovery and coverage

TEST(StripesMsa, RecoversAKnownLognormalFragility) {
  const double mu = -0.2, sr = 0.3, sm = 0.4, beta = 0.5;
  const Demands d = lognormal_demands(40, 400, log_levels(0.2, 5.0, 10), mu, sr, sm, 3);
  const std::vector<double> gaps{0.5, 1.0};
  const std::vector<GapFragility> f = fit_msa(d, gaps, quick(1000), nullptr);
  ASSERT_EQ(f.size(), 2u);
  for (const GapFragility& g : f) {
    ASSERT_TRUE(g.fit.ok()) << g.note;
    const double theta = g.gap * std::exp(-mu);
    // the cluster bootstrap's standard errors (the binomial ones ignore the record effect)
    const double se_log_theta = std::log(g.theta_ci.hi / g.theta_ci.lo) / (2 * 1.96);
    const double se_beta = (g.beta_ci.hi - g.beta_ci.lo) / (2 * 1.96);
    EXPECT_GT(se_log_theta, g.fit.se_log_theta);  // clustering widens it
    EXPECT_LT(std::abs(std::log(g.fit.fragility.theta / theta)), 3 * se_log_theta) << g.gap;
    EXPECT_LT(std::abs(g.fit.fragility.beta - beta), 3 * se_beta) << g.gap;
    EXPECT_EQ(g.replicates, 1000);
    EXPECT_EQ(g.replicates_failed, 0);
    EXPECT_EQ(g.observed.size(), 10u);
    for (std::size_t s = 0; s < g.observed.size(); ++s) EXPECT_EQ(g.observed[s].n, 40 * 400);
  }
}

// 100 simulated studies with a known fragility: the 95 % record-bootstrap intervals cover theta in roughly 95 %
// of them ([0.85, 0.99]; an interval that ignores the record effect, the binomial Wald one, covers ~30 %).
// beta's percentile interval runs short with few records: beta-hat is biased low by the finite record sample
// (the between-record variance of R records is (R - 1)/R of the truth) and a replicate, with fewer distinct
// records, more so, so the truth falls above the interval. Measured over 400 studies (this design, M = 40):
// beta 0.83 / 0.875 / 0.90 with 30 / 50 / 100 records, theta 0.93 / 0.94 / 0.95. Hence 60 records here and the
// band [0.80, 0.99] for beta (the header documents the shortfall).
TEST(StripesMsa, BootstrapIntervalsCoverTheTruth) {
  const double mu = 0.1, sr = 0.3, sm = 0.35, beta = std::hypot(sr, sm);
  const std::vector<double> gaps{1.0};
  int theta_hits = 0, beta_hits = 0, wald_hits = 0;
  const int studies = 100;
  for (int k = 0; k < studies; ++k) {
    const Demands d = lognormal_demands(60, 40, log_levels(0.2, 6.0, 8), mu, sr, sm, 1000 + static_cast<std::uint64_t>(k));
    const GapFragility g = fit_msa(d, gaps, quick(400, 2, 77 + static_cast<std::uint64_t>(k)), nullptr)[0];
    ASSERT_TRUE(g.fit.ok()) << g.note;
    const double theta = std::exp(-mu);
    theta_hits += covers(g.theta_ci, theta);
    beta_hits += covers(g.beta_ci, beta);
    wald_hits += std::abs(std::log(g.fit.fragility.theta / theta)) < 1.96 * g.fit.se_log_theta;
  }
  const double ct = theta_hits / static_cast<double>(studies), cb = beta_hits / static_cast<double>(studies);
  EXPECT_GE(ct, 0.85);
  EXPECT_LE(ct, 0.99);
  EXPECT_GE(cb, 0.80);
  EXPECT_LE(cb, 0.99);
  EXPECT_LT(wald_hits, theta_hits);  // the binomial interval is too narrow for clustered trials
  std::printf("coverage: theta %.2f, beta %.2f, binomial Wald theta %.2f\n", ct, cb, wald_hits / double(studies));
}

// ---------------------------------------------------------------- 2. linear equivalence

// With iid capacities (no record effect) the binomial standard errors of the MSA fit are valid, and linear IDA
// uses every capacity (it is the more efficient estimator), so Var(MSA - IDA) <= Var(MSA): 3 MSA standard
// errors is a 3-sigma bound on the difference. Here n = 50,000, 3 se is ~1.5 % on theta and ~3 % on beta.
TEST(StripesLinear, MsaAgreesWithLinearIda) {
  const LinearData L = linear_data(25, 2000, 0.8, 0.45, 5);
  const std::vector<double> levels = log_levels(0.1, 5.0, 12);
  const std::vector<double> gaps{0.5, 1.0, 2.0};
  const std::vector<GapFragility> msa = fit_msa(linear_msa(L, levels), gaps, quick(0), nullptr);
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    const GapFragility ida = fit_ida(linear_capacities(L.im, L.demand1, L.models, gaps[i], L.cap), levels, quick(0),
                                     nullptr, gaps[i]);
    ASSERT_TRUE(msa[i].fit.ok() && ida.fit.ok());
    const LognormalFragility a = msa[i].fit.fragility, b = ida.fit.fragility;
    EXPECT_LT(std::abs(std::log(a.theta / b.theta)), 3 * msa[i].fit.se_log_theta) << gaps[i];
    EXPECT_LT(std::abs(a.beta - b.beta), 3 * msa[i].fit.se_beta) << gaps[i];
    EXPECT_LT(msa[i].fit.se_log_theta, 0.006);  // so the bound above is tight (~1.5 % on theta)
    // MSA observes exactly the empirical CDF of the linear capacities at its levels
    for (std::size_t s = 0; s < levels.size(); ++s) EXPECT_EQ(msa[i].observed[s].z, ida.observed[s].z);
  }
}

TEST(StripesLinear, IdaThetaScalesWithTheGapAndBetaDoesNot) {
  const LinearData L = linear_data(25, 300, 0.8, 0.45, 6);
  const GapFragility one = fit_ida(linear_capacities(L.im, L.demand1, L.models, 1.0, L.cap), {}, quick(0), nullptr, 1.0);
  std::vector<double> c1;
  for (std::size_t i = 0; i < L.demand1.size(); ++i) c1.push_back(L.im[i / L.models] / L.demand1[i]);
  const LognormalFragility mom = fit_fragility_moments(c1);
  EXPECT_NEAR(one.fit.fragility.theta, mom.theta, 1e-12 * mom.theta);
  EXPECT_NEAR(one.fit.fragility.beta, mom.beta, 1e-12);
  for (double x : {0.3, 0.7, 2.5, 11.0}) {
    const GapFragility g = fit_ida(linear_capacities(L.im, L.demand1, L.models, x, L.cap), {}, quick(0), nullptr, x);
    ASSERT_TRUE(g.fit.ok());
    EXPECT_NEAR(g.fit.fragility.theta, x * one.fit.fragility.theta, 1e-12 * x * one.fit.fragility.theta) << x;
    EXPECT_NEAR(g.fit.fragility.beta, one.fit.fragility.beta, 1e-12) << x;
  }
}

// ---------------------------------------------------------------- 3. hazard

TEST(StripesHazard, AnnualRateIsCornellsClosedForm) {
  // ten capacities whose moments are exactly theta = 0.8, beta = 0.5
  std::vector<double> z{-1.3, -0.8, -0.5, -0.2, 0.0, 0.1, 0.3, 0.6, 0.9, 1.4};
  const double mean = std::accumulate(z.begin(), z.end(), 0.0) / 10;
  double ss = 0;
  for (double v : z) ss += (v - mean) * (v - mean);
  std::vector<double> c;
  for (double v : z) c.push_back(0.8 * std::exp(0.5 * (v - mean) / std::sqrt(ss / 9)));
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const GapFragility g = fit_ida(one_record(c, 100.0), {}, quick(0), &h, 1.0);
  ASSERT_TRUE(g.fit.ok());
  EXPECT_NEAR(g.fit.fragility.theta, 0.8, 1e-12);
  EXPECT_NEAR(g.fit.fragility.beta, 0.5, 1e-12);
  EXPECT_TRUE(g.has_hazard);
  EXPECT_NEAR(g.annual_rate, 1.526257e-3, 1e-6 * 1.526257e-3);
  EXPECT_NEAR(g.probability, 0.073474, 1e-6);
  EXPECT_EQ(g.tail_share, 0.0);

  // MSA: the rate of the fitted fragility, and its interval contains it
  const Demands d = lognormal_demands(30, 200, log_levels(0.2, 5.0, 8), 0.0, 0.3, 0.4, 9);
  const double gap = 0.8;
  const GapFragility m = fit_msa(d, std::span<const double>(&gap, 1), quick(300), &h)[0];
  ASSERT_TRUE(m.fit.ok());
  const LognormalFragility f = m.fit.fragility;
  const double cornell = 4e-4 * std::pow(f.theta, -2.5) * std::exp(2.5 * 2.5 * f.beta * f.beta / 2);
  EXPECT_NEAR(m.annual_rate, cornell, 1e-9 * cornell);
  EXPECT_NEAR(m.probability, -std::expm1(-cornell * 50), 1e-12);
  EXPECT_LT(m.rate_lo, m.annual_rate);
  EXPECT_GT(m.rate_hi, m.annual_rate);
  EXPECT_NEAR(m.probability_hi, -std::expm1(-m.rate_hi * 50), 1e-15);
}

TEST(StripesHazard, TableHazardCarriesTheTailShare) {
  const std::vector<double> im{0.1, 0.3, 1.0}, rate{1e-2, 1e-3, 1e-4};
  const HazardCurve h = HazardCurve::from_table(im, rate);
  const Demands d = lognormal_demands(20, 100, log_levels(0.1, 3.0, 8), 0.0, 0.3, 0.4, 10);
  const double gap = 1.0;
  const GapFragility g = fit_msa(d, std::span<const double>(&gap, 1), quick(0), &h)[0];
  ASSERT_TRUE(g.fit.ok());
  const PoundingRate want = pounding_rate(h, g.fit.fragility);
  EXPECT_EQ(g.annual_rate, want.rate);
  EXPECT_EQ(g.tail_share, want.tail_share);
  EXPECT_GT(g.tail_share, 0.0);
}

// ---------------------------------------------------------------- 4. risk-targeted gap

TEST(StripesTarget, LinearIdaMatchesTheClosedForm) {
  const LinearData L = linear_data(25, 300, 0.8, 0.45, 12);
  std::vector<double> c1;
  for (std::size_t i = 0; i < L.demand1.size(); ++i) c1.push_back(L.im[i / L.models] / L.demand1[i]);
  const LognormalFragility f1 = fit_fragility_moments(c1);
  const double k0 = 4e-4, k = 2.5;
  const HazardCurve h = HazardCurve::power_law(k0, k);
  for (double target : {2.01007e-4, 4.04054e-4, 2.10721e-3}) {
    const double closed = std::pow(k0 * std::exp(k * k * f1.beta * f1.beta / 2) / target, 1 / k) / f1.theta;
    const TargetGap t = risk_targeted_gap_linear_ida(L.im, L.demand1, L.models, L.cap, h, target, quick(200));
    ASSERT_EQ(t.status, "ok") << t.note;
    EXPECT_NEAR(t.gap, closed, 1e-6 * closed) << target;
    EXPECT_LE(t.rate, target);
    EXPECT_LE(t.lo, t.gap);
    EXPECT_GE(t.hi, t.gap);
    EXPECT_EQ(t.replicates, 200);
  }
}

TEST(StripesTarget, MsaRateMeetsTheTargetAndDecreasesAroundIt) {
  const Demands d = lognormal_demands(25, 400, log_levels(0.05, 4.0, 10), 0.0, 0.3, 0.4, 13);
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const double target = 2.10721e-3;  // 10 % in 50 years
  const TargetGap t = risk_targeted_gap(d, h, target, quick(200));
  ASSERT_EQ(t.status, "ok") << t.note;
  EXPECT_LE(t.rate, target);
  EXPECT_NEAR(t.rate, target, 2e-3 * target);  // lambda_P is a step function with 100,000 steps
  const std::vector<double> around{t.gap / (1 + 2e-8), t.gap};
  const RateCurve at = rate_curve(d, h, around, 50);
  EXPECT_GT(at.rate[0], target);
  EXPECT_LE(at.rate[1], target);
  EXPECT_EQ(at.rate[1], t.rate);
  // non-increasing on either side
  const RateCurve c = rate_curve(d, h, log_levels(t.gap / 3, t.gap * 3, 41), 50);
  for (std::size_t i = 1; i < c.rate.size(); ++i) EXPECT_LE(c.rate[i], c.rate[i - 1]) << c.gap[i];
  EXPECT_NEAR(c.probability[20], -std::expm1(-c.rate[20] * 50), 1e-15);
  EXPECT_LT(t.lo, t.gap);
  EXPECT_GT(t.hi, t.gap);
  EXPECT_EQ(t.replicates_below + t.replicates_above, 0);
  // a 1 % in 50 years target needs a larger gap
  const TargetGap t1 = risk_targeted_gap(d, h, 2.01007e-4, quick(0));
  EXPECT_GT(t1.gap, t.gap);
}

// Issue 23, item 3: lambda_P(gap) never rises. Stripes that stop below the demands' upper tail: at large gaps the fit
// is extrapolated far above the top stripe, then no analysis pounds and the no_pounding bound (P = 1 above the top
// stripe) takes over; the fits' own rates rise there, the curve does not.
TEST(StripesTarget, RateCurveNeverRisesWithTheGap) {
  const Demands d = lognormal_demands(12, 60, log_levels(0.05, 0.4, 5), 0.0, 0.35, 0.45, 31);
  const StripeIndex ix(d, 1);
  for (const HazardCurve& h : {HazardCurve::power_law(4e-4, 2.5),
                               HazardCurve::from_table(std::vector<double>{0.01, 0.1, 1.0, 3.0},
                                                       std::vector<double>{0.5, 2e-2, 3e-4, 2e-5})}) {
    const RateCurve c = rate_curve(ix, h, log_levels(0.01, 1.5 * ix.max_positive(), 400), 50);
    int rises = 0;
    for (std::size_t i = 1; i < c.gap.size(); ++i) {
      rises += c.rate_fitted[i] > c.rate_fitted[i - 1];
      EXPECT_LE(c.rate[i], c.rate[i - 1]) << c.gap[i];
      EXPECT_LE(c.rate[i], c.rate_fitted[i]) << c.gap[i];
      EXPECT_LE(c.probability[i], c.probability[i - 1]) << c.gap[i];
    }
    EXPECT_GT(rises, 0) << "the case no longer makes the fits' own rates rise: the test checks nothing";
    EXPECT_EQ(c.rate.front(), c.rate_fitted.front());
    // the shares beyond the stripes are fractions; where nothing pounds, the bound's part above the top stripe
    for (std::size_t i = 0; i < c.gap.size(); ++i) {
      EXPECT_GE(c.share_below[i], 0.0);
      EXPECT_LE(c.share_below[i] + c.share_above[i], 1.0 + 1e-12);
    }
    const RateCurve end = rate_curve(ix, h, std::vector<double>{1.01 * ix.max_positive()}, 50);
    EXPECT_NEAR(end.share_above[0], h.rate(0.4) / end.rate_fitted[0], 1e-12);
  }
  // non_increasing: any order in, the running minimum in ascending gap order out, NaN kept
  const std::vector<double> g{0.3, 0.1, 0.2, 0.4, 0.5}, r{2.0, 5.0, 4.0, NAN, 3.0};
  EXPECT_EQ(non_increasing(g, r)[0], 2.0);
  EXPECT_EQ(non_increasing(g, r)[2], 4.0);
  EXPECT_TRUE(std::isnan(non_increasing(g, r)[3]));
  EXPECT_EQ(non_increasing(g, r)[4], 2.0);
}

// rate_shares against a plain trapezoid integral of Phi((u - mu)/beta) k k0 e^{-ku} du over each region.
TEST(StripesHazard, SharesBeyondTheStripesAreTheIntegralsThere) {
  const double k0 = 4e-4, k = 2.5, theta = 0.8, beta = 0.5, lo = 0.2, hi = 1.2;
  const HazardCurve h = HazardCurve::power_law(k0, k);
  const LognormalFragility f{theta, beta};
  auto integral = [&](double a, double b) {
    const int n = 200000;
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
      const double u = a + (b - a) * i / n;
      const double v = normal_cdf((u - std::log(theta)) / beta) * k * k0 * std::exp(-k * u);
      sum += (i == 0 || i == n ? 0.5 : 1.0) * v;
    }
    return sum * (b - a) / n;
  };
  const double total = pounding_rate_closed_form(k0, k, f);
  const RateShares s = rate_shares(h, f, lo, hi);
  EXPECT_NEAR(s.below, integral(std::log(lo) - 12, std::log(lo)) / total, 1e-7);
  EXPECT_NEAR(s.above, integral(std::log(hi), std::log(hi) + 12) / total, 1e-7);
  EXPECT_GT(s.above, 0.1);
  EXPECT_GT(s.below, 1e-4);
  EXPECT_EQ(rate_shares(h, LognormalFragility{3.0, 0.0}, lo, hi).above, 1.0);  // a step above the stripes
}

TEST(StripesTarget, OutOfRangeStatuses) {
  const Demands d = lognormal_demands(10, 50, log_levels(0.05, 4.0, 8), 0.0, 0.3, 0.4, 14);
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  // the stripes end at 4.0, lambda_IM(4) = 1.25e-5: a target below it cannot be shown
  const TargetGap above = risk_targeted_gap(d, h, 1e-9, quick(50));
  EXPECT_EQ(above.status, "above range");
  EXPECT_EQ(above.gap, above.range_hi);
  EXPECT_EQ(above.replicates_above, 50);
  EXPECT_EQ(above.hi, kInf);
  EXPECT_NE(above.note.find("beyond"), std::string::npos);
  const TargetGap below = risk_targeted_gap(d, h, 1e6, quick(50));
  EXPECT_EQ(below.status, "below range");
  EXPECT_EQ(below.gap, below.range_lo);
  EXPECT_EQ(below.lo, 0.0);
  EXPECT_NE(below.note.find("at most"), std::string::npos);

  LinearData L = linear_data(10, 50, 0.8, 0.45, 15);
  std::fill(L.cap.begin(), L.cap.end(), 0.5);  // the records analysed only up to IM 0.5
  const TargetGap capped = risk_targeted_gap_linear_ida(L.im, L.demand1, L.models, L.cap, h, 1e-6, quick(20));
  EXPECT_EQ(capped.status, "above range");
  EXPECT_THROW(risk_targeted_gap(d, h, 0.0, quick(0)), std::invalid_argument);
}

// ---------------------------------------------------------------- 5. edge cases

TEST(StripesEdge, NoPoundingAllPoundedSeparatedDecreasing) {
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  Demands d;
  d.records = 4, d.models = 5, d.levels = {0.2, 0.4, 0.6, 0.8};
  d.demand.assign(4 * 4 * 5, 0.0);
  const std::vector<double> gaps{1.0};
  const GapFragility none = fit_msa(d, gaps, quick(30), &h)[0];
  EXPECT_EQ(none.fit.status, FragilityStatus::no_pounding);
  const double pb = 1 - std::pow(0.05, 1.0 / 80);
  EXPECT_NEAR(none.fit.bound, pb, 1e-15);
  EXPECT_NEAR(none.annual_rate, pb * h.rate(0.2) + (1 - pb) * h.rate(0.8), 1e-15);
  EXPECT_NE(none.note.find("upper bound"), std::string::npos);
  EXPECT_EQ(none.replicates_failed, 30);
  EXPECT_EQ(none.theta_ci.hi, kInf);
  EXPECT_EQ(none.rate_lo, 0.0);
  EXPECT_TRUE(std::isnan(none.fitted[0]));

  std::fill(d.demand.begin(), d.demand.end(), 10.0);
  const GapFragility all = fit_msa(d, gaps, quick(30), &h)[0];
  EXPECT_EQ(all.fit.status, FragilityStatus::all_pounded);
  EXPECT_NEAR(all.annual_rate, all.fit.bound * h.rate(0.2), 1e-15);
  EXPECT_EQ(all.rate_hi, kInf);
  EXPECT_EQ(all.theta_ci.lo, 0.0);
  EXPECT_NE(all.note.find("lower bound"), std::string::npos);

  // D = 0 at 0.2 and 0.4, D = 2 at 0.6 and 0.8: theta in (0.4, 0.6), beta -> 0
  for (std::size_t i = 0; i < d.demand.size(); ++i) d.demand[i] = i / 20 < 2 ? 0.0 : 2.0;
  const GapFragility sep = fit_msa(d, gaps, quick(30), &h)[0];
  EXPECT_EQ(sep.fit.status, FragilityStatus::separated);
  EXPECT_EQ(sep.fit.bracket.lo, 0.4);
  EXPECT_EQ(sep.fit.bracket.hi, 0.6);
  EXPECT_NEAR(sep.annual_rate, h.rate(std::sqrt(0.24)), 1e-15);
  EXPECT_EQ(sep.theta_ci.lo, 0.4);
  EXPECT_EQ(sep.theta_ci.hi, 0.6);
  EXPECT_EQ(sep.beta_ci.hi, 0.0);
  EXPECT_NE(sep.note.find("step"), std::string::npos);

  // pounding that falls with IM: no lognormal fragility, no rate
  for (std::size_t i = 0; i < d.demand.size(); ++i) d.demand[i] = (i % 5 < 4 - i / 20) ? 2.0 : 0.0;
  const GapFragility dec = fit_msa(d, gaps, quick(30), &h)[0];
  EXPECT_EQ(dec.fit.status, FragilityStatus::decreasing);
  EXPECT_TRUE(std::isnan(dec.annual_rate));
  EXPECT_TRUE(std::isnan(dec.probability));
  EXPECT_EQ(dec.rate_hi, kInf);

  for (const GapFragility* g : {&none, &all, &sep, &dec}) {
    EXPECT_FALSE(g->fit.ok());
    for (double p : g->fitted) EXPECT_TRUE(std::isnan(p));
  }
}

TEST(StripesEdge, ExcludedAnalysesAndDroppedRecords) {
  Demands d = lognormal_demands(6, 20, log_levels(0.2, 3.0, 5), 0.0, 0.3, 0.4, 16);
  // record 2 dropped from the top stripe (scale factor too large), one analysis diverged in stripe 0
  for (std::size_t m = 0; m < 20; ++m) d.demand[(4 * 6 + 2) * 20 + m] = NAN;
  d.demand[3] = NAN;
  const double gap = 1.0;
  const GapFragility g = fit_msa(d, std::span<const double>(&gap, 1), quick(100), nullptr)[0];
  ASSERT_EQ(g.observed.size(), 5u);
  EXPECT_EQ(g.observed[0].n, 119);
  EXPECT_EQ(g.observed[4].n, 100);
  EXPECT_TRUE(g.fit.ok()) << g.note;

  // a stripe where every analysis is excluded is left out; with one stripe left there is no fit
  Demands e = d;
  std::fill(e.demand.begin(), e.demand.begin() + 6 * 20 * 4, NAN);
  const GapFragility one = fit_msa(e, std::span<const double>(&gap, 1), quick(10), nullptr)[0];
  EXPECT_EQ(one.observed.size(), 1u);
  EXPECT_EQ(one.fit.status, FragilityStatus::not_converged);
  EXPECT_EQ(one.replicates_failed, 10);

  EXPECT_THROW(fit_msa(Demands{{1.0}, 1, 1, {0.5}}, std::span<const double>(&gap, 1), quick(0), nullptr),
               std::invalid_argument);
  Demands bad = d;
  bad.demand.pop_back();
  EXPECT_THROW(fit_msa(bad, std::span<const double>(&gap, 1), quick(0), nullptr), std::invalid_argument);
}

TEST(StripesEdge, IdaCensoredEverywhereAndTooFew) {
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const GapFragility none = fit_ida(Capacities{2, 3, std::vector<double>(6, kInf), {1.5, 2.0}}, std::vector<double>{0.5}, quick(20), &h, 1.0);
  EXPECT_EQ(none.fit.status, FragilityStatus::no_pounding);
  const double pb = 1 - std::pow(0.05, 1.0 / 6);
  EXPECT_NEAR(none.annual_rate, pb * h.rate(0.5) + (1 - pb) * h.rate(1.5), 1e-15);
  EXPECT_EQ(none.replicates_failed, 20);

  const GapFragility few = fit_ida(Capacities{1, 3, {0.7, NAN, NAN}, {2.0}}, {}, quick(0), &h, 1.0);
  EXPECT_EQ(few.fit.status, FragilityStatus::not_converged);
  EXPECT_TRUE(std::isnan(few.annual_rate));
  EXPECT_THROW(fit_ida(Capacities{1, 2, {0.7, 0.8}, {kInf}}, {}, quick(0), &h, 1.0), std::invalid_argument);
  EXPECT_THROW(linear_capacities(std::vector<double>{0.3}, std::vector<double>{0.1, 0.2}, 2, 0.0,
                                 std::vector<double>{1.0}),
               std::invalid_argument);
}

TEST(StripesEdge, LinearCapacitiesCensorAtTheCap) {
  const std::vector<double> im{0.4}, d1{0.1, 0.0, -0.2, NAN, 0.5}, cap{1.0};
  const Capacities c = linear_capacities(im, d1, 5, 0.2, cap);
  EXPECT_NEAR(c.capacity[0], 0.8, 1e-15);  // 0.4 * 0.2 / 0.1
  EXPECT_EQ(c.capacity[1], kInf);          // never closes
  EXPECT_EQ(c.capacity[2], kInf);
  EXPECT_TRUE(std::isnan(c.capacity[3]));
  EXPECT_NEAR(c.capacity[4], 0.16, 1e-15);
  EXPECT_EQ(linear_capacities(im, d1, 5, 0.3, cap).capacity[0], kInf);  // 1.2 > cap
}

// ---------------------------------------------------------------- 6. reproducibility

TEST(StripesBootstrap, IndependentOfThreadsAndDependentOnSeed) {
  const Demands d = lognormal_demands(12, 60, log_levels(0.1, 4.0, 8), 0.0, 0.3, 0.4, 17);
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const std::vector<double> gaps{0.5, 1.0, 2.0};
  const auto a = fit_msa(d, gaps, quick(300, 1), &h), b = fit_msa(d, gaps, quick(300, 2), &h),
             c = fit_msa(d, gaps, quick(300, 3), &h), e = fit_msa(d, gaps, quick(300, 2, 12), &h);
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    for (const auto* x : {&b, &c}) {
      EXPECT_EQ(a[g].theta_ci.lo, (*x)[g].theta_ci.lo);
      EXPECT_EQ(a[g].theta_ci.hi, (*x)[g].theta_ci.hi);
      EXPECT_EQ(a[g].beta_ci.lo, (*x)[g].beta_ci.lo);
      EXPECT_EQ(a[g].beta_ci.hi, (*x)[g].beta_ci.hi);
      EXPECT_EQ(a[g].rate_lo, (*x)[g].rate_lo);
      EXPECT_EQ(a[g].rate_hi, (*x)[g].rate_hi);
    }
    EXPECT_NE(a[g].theta_ci.lo, e[g].theta_ci.lo);
  }
  // a replicate's record draws do not depend on the other gaps asked for
  const double one_gap = 1.0;
  const GapFragility alone = fit_msa(d, std::span<const double>(&one_gap, 1), quick(300, 2), &h)[0];
  EXPECT_EQ(alone.theta_ci.lo, a[1].theta_ci.lo);
  EXPECT_EQ(alone.rate_hi, a[1].rate_hi);

  const TargetGap t1 = risk_targeted_gap(d, h, 2.10721e-3, quick(100, 1)),
                  t2 = risk_targeted_gap(d, h, 2.10721e-3, quick(100, 2)),
                  t3 = risk_targeted_gap(d, h, 2.10721e-3, quick(100, 2, 99));
  EXPECT_EQ(t1.gap, t2.gap);
  EXPECT_EQ(t1.lo, t2.lo);
  EXPECT_EQ(t1.hi, t2.hi);
  EXPECT_NE(t1.lo, t3.lo);

  const LinearData L = linear_data(12, 40, 0.8, 0.45, 18);
  const Capacities cap = linear_capacities(L.im, L.demand1, L.models, 1.0, L.cap);
  const GapFragility i1 = fit_ida(cap, {}, quick(200, 1), &h, 1.0), i2 = fit_ida(cap, {}, quick(200, 2), &h, 1.0);
  EXPECT_EQ(i1.theta_ci.lo, i2.theta_ci.lo);
  EXPECT_EQ(i1.beta_ci.hi, i2.beta_ci.hi);
  EXPECT_EQ(i1.rate_lo, i2.rate_lo);
  const TargetGap l1 = risk_targeted_gap_linear_ida(L.im, L.demand1, L.models, L.cap, h, 4.04054e-4, quick(100, 1)),
                  l2 = risk_targeted_gap_linear_ida(L.im, L.demand1, L.models, L.cap, h, 4.04054e-4, quick(100, 2));
  EXPECT_EQ(l1.lo, l2.lo);
  EXPECT_EQ(l1.hi, l2.hi);
}

TEST(StripesIndex, CountsAreBinarySearchesOfTheSortedSlices) {
  const Demands d = lognormal_demands(5, 37, log_levels(0.2, 2.0, 4), 0.0, 0.3, 0.4, 19);
  const StripeIndex ix(d, 2);
  const std::vector<int> w{2, 0, 1, 0, 2};
  for (double x : {0.05, 0.3, 1.0, 3.0}) {
    const std::vector<Stripe> st = ix.stripes_at(x, w);
    ASSERT_EQ(st.size(), 4u);
    for (std::size_t s = 0; s < 4; ++s) {
      std::int64_t n = 0, z = 0;
      for (std::size_t r = 0; r < 5; ++r)
        for (std::size_t m = 0; m < 37; ++m) n += w[r], z += w[r] * (d.demand[(s * 5 + r) * 37 + m] > x);
      EXPECT_EQ(st[s].n, n);
      EXPECT_EQ(st[s].z, z);
    }
  }
  // the StripeIndex overloads give what the Demands ones do
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const std::vector<double> gaps{0.5, 1.5};
  const auto a = fit_msa(d, gaps, quick(50), &h), b = fit_msa(ix, gaps, quick(50), &h);
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    EXPECT_EQ(a[g].fit.fragility.theta, b[g].fit.fragility.theta);
    EXPECT_EQ(a[g].rate_hi, b[g].rate_hi);
  }
  EXPECT_EQ(risk_targeted_gap(d, h, 1e-3, quick(20)).hi, risk_targeted_gap(ix, h, 1e-3, quick(20)).hi);
  EXPECT_EQ(rate_curve(d, h, gaps, 50).rate, rate_curve(ix, h, gaps, 50).rate);
  double lo = kInf, hi = 0;
  for (double v : d.demand) lo = std::min(lo, v), hi = std::max(hi, v);
  EXPECT_EQ(ix.min_positive(), lo);
  EXPECT_EQ(ix.max_positive(), hi);
}

// The bisection IDA's risk-targeted gap: ln lambda linear in the gap between the study's gaps. With rates exactly
// lambda(x) = a exp(-b x) the interpolation is exact: x* = ln(a / target) / b; each replicate is interpolated the
// same way; the range statuses when the target lies outside the listed gaps.
// Rates a exp(-b x) at the gaps, and B = 5 replicates whose rates are c_b times them at every gap: each replicate's
// root is exactly ln(c_b a / target) / b, and at confidence 0.5 the type-7 quartiles of 5 sorted roots are the
// 2nd and 4th.
TEST(StripesTargetAtGaps, InterpolatesLnRateExactlyAndFlagsTheRange) {
  const double a = 0.05, b = 3.0;
  const std::vector<double> c{2.0, 0.5, 1.0, 1.25, 0.8};
  std::vector<GapFragility> fits;
  for (double x : {0.25, 0.5, 1.0, 1.5, 2.0}) {
    GapFragility g;
    g.gap = x, g.has_hazard = true;
    g.annual_rate = a * std::exp(-b * x);
    for (double cb : c) g.replicate_rate_lo.push_back(cb * g.annual_rate), g.replicate_rate_hi.push_back(cb * g.annual_rate);
    fits.push_back(g);
  }
  std::swap(fits[0], fits[3]);  // any order
  const double target = 4.0e-4;
  const TargetGap t = risk_targeted_gap_at_gaps(fits, target, 0.5);
  EXPECT_EQ(t.status, "ok");
  EXPECT_NEAR(t.gap, std::log(a / target) / b, 1e-12);
  EXPECT_NEAR(t.lo, std::log(0.8 * a / target) / b, 1e-12);
  EXPECT_NEAR(t.hi, std::log(1.25 * a / target) / b, 1e-12);
  EXPECT_EQ(t.replicates, 5);
  EXPECT_EQ(t.replicates_below + t.replicates_above, 0);
  // a failed fit of replicate 3 (c = 1.25, root 1.684) at gap 2.0: its rate range [0, inf] there makes its root
  // the range [1.71 (the lower ends reach 0 at 2.0), +inf]: the upper quartile of the upper ends moves up to the
  // next root (c = 2), the lower quartile stays
  for (GapFragility& g : fits)
    if (g.gap == 2.0) g.replicate_rate_lo[3] = 0.0, g.replicate_rate_hi[3] = INFINITY;
  const TargetGap f = risk_targeted_gap_at_gaps(fits, target, 0.5);
  EXPECT_NEAR(f.gap, t.gap, 1e-15);
  EXPECT_NEAR(f.hi, std::log(2.0 * a / target) / b, 1e-12);
  EXPECT_NEAR(f.lo, t.lo, 1e-12);
  const TargetGap below = risk_targeted_gap_at_gaps(fits, 0.1, 0.95);
  EXPECT_EQ(below.status, "below range");
  EXPECT_EQ(below.gap, 0.25);
  EXPECT_GE(below.replicates_below, 3);
  const TargetGap above = risk_targeted_gap_at_gaps(fits, 1e-9, 0.95);
  EXPECT_EQ(above.status, "above range");
  EXPECT_EQ(above.gap, 2.0);
  EXPECT_TRUE(std::isinf(above.hi));
  EXPECT_EQ(above.replicates_above, 4);  // replicate 3's lower ends reach 0 at gap 2.0
  fits[2].replicate_rate_hi.pop_back();  // replicates that do not line up across the gaps: no interval
  EXPECT_TRUE(std::isnan(risk_targeted_gap_at_gaps(fits, target, 0.95).lo));
  EXPECT_THROW(risk_targeted_gap_at_gaps(fits, 0.0, 0.95), std::invalid_argument);
  EXPECT_THROW(risk_targeted_gap_at_gaps(fits, target, 1.0), std::invalid_argument);
  fits[1].has_hazard = false;
  EXPECT_THROW(risk_targeted_gap_at_gaps(fits, target, 0.95), std::invalid_argument);
}

// The interpolated gap of the bisection IDA against the continuum search of linear IDA on the same linear pairs
// (risk_targeted_gap_linear_ida, itself checked against the closed form above): fit_ida at 41 gaps close together
// around x*, same Settings, so every replicate draws the same records in both; the joint interval must match the
// continuum's to the interpolation error (ln lambda is linear in ln x here, not in x: ~1e-4 at this spacing).
TEST(StripesTargetAtGaps, DenseGapsReproduceTheContinuumInterval) {
  LinearData L = linear_data(20, 150, 0.8, 0.45, 21);
  std::mt19937_64 rng(22);
  std::normal_distribution<double> n01;
  for (std::size_t r = 0; r < L.im.size(); ++r) {  // a record effect, so that the interval is a real one
    const double e = std::exp(0.3 * n01(rng));
    for (std::size_t m = 0; m < L.models; ++m) L.demand1[r * L.models + m] *= e;
  }
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const double target = 4.04054e-4;
  const Settings s = quick(300);
  const TargetGap cont = risk_targeted_gap_linear_ida(L.im, L.demand1, L.models, L.cap, h, target, s);
  ASSERT_EQ(cont.status, "ok") << cont.note;
  std::vector<GapFragility> fits;
  for (int i = 0; i <= 40; ++i) {
    const double x = cont.gap * std::exp(-0.5 + i * 0.025);
    fits.push_back(fit_ida(linear_capacities(L.im, L.demand1, L.models, x, L.cap), {}, s, &h, x));
  }
  const TargetGap at = risk_targeted_gap_at_gaps(fits, target, s.confidence);
  ASSERT_EQ(at.status, "ok") << at.note;
  ASSERT_GT(cont.lo, fits.front().gap);
  ASSERT_LT(cont.hi, fits.back().gap);
  EXPECT_NEAR(at.gap, cont.gap, 2e-4 * cont.gap);
  EXPECT_NEAR(at.lo, cont.lo, 2e-4 * cont.lo);
  EXPECT_NEAR(at.hi, cont.hi, 2e-4 * cont.hi);
  EXPECT_LT(cont.lo, 0.95 * cont.gap);  // a real interval, not a point
  std::printf("x* %.6f [%.6f, %.6f] continuum, %.6f [%.6f, %.6f] interpolated\n", cont.gap, cont.lo, cont.hi, at.gap,
              at.lo, at.hi);
}

// The jackknife of the risk-targeted gap (MSA, weights with record j at 0) against deleting record j from the data
// and solving again without a bootstrap: the same x*_(j), hence the same standard error and interval.
TEST(StripesTarget, JackknifeEqualsDeletingEachRecord) {
  const Demands d = lognormal_demands(12, 60, log_levels(0.1, 5.0, 9), 0.1, 0.3, 0.35, 31);
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const double target = 4.04054e-4;
  const TargetGap t = risk_targeted_gap(d, h, target, quick(100));
  ASSERT_EQ(t.status, "ok") << t.note;
  std::vector<double> ln;
  for (std::size_t j = 0; j < d.records; ++j) {
    const Demands dj = without_record(d, j);
    const TargetGap tj = risk_targeted_gap(dj, h, target, quick(0));
    ASSERT_EQ(tj.status, "ok");
    ln.push_back(std::log(tj.gap));
  }
  double mean = 0, ss = 0;
  for (double v : ln) mean += v / 12.0;
  for (double v : ln) ss += (v - mean) * (v - mean);
  const double se = std::sqrt(11.0 / 12.0 * ss);
  const double q = 2.200985160082949;  // Student t, 11 degrees of freedom, 0.975 (scipy.stats.t.ppf)
  // each x*_(j) is the end of a bisection to 1e-8 relative, on its own search grid when the record is deleted
  EXPECT_NEAR(t.jack_se, se, 1e-8);
  EXPECT_NEAR(t.jack_lo, t.gap * std::exp(-q * se), 1e-7 * t.gap);
  EXPECT_NEAR(t.jack_hi, t.gap * std::exp(q * se), 1e-7 * t.gap);
  EXPECT_EQ(t.advice, std::max(t.hi, t.jack_hi));
  EXPECT_GT(t.jack_se, 0.01);
}

// The per-gap rate's jackknife (MSA): record j's leave-one-out rate equals fit_msa on the data without record j,
// and the interval is exp(ln rate -+ t se) with t the Student quantile (11 degrees of freedom).
TEST(StripesMsa, RateJackknifeEqualsDeletingEachRecord) {
  const Demands d = lognormal_demands(12, 60, log_levels(0.1, 5.0, 9), 0.1, 0.3, 0.35, 33);
  const HazardCurve h = HazardCurve::power_law(4e-4, 2.5);
  const std::vector<double> gaps{0.6, 1.2};
  const std::vector<GapFragility> f = fit_msa(d, gaps, quick(50), &h);
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    ASSERT_TRUE(f[g].fit.ok());
    ASSERT_EQ(f[g].jackknife_rate.size(), 12u);
    std::vector<double> ln;
    for (std::size_t j = 0; j < d.records; ++j) {
      const Demands dj = without_record(d, j);
      const double want = fit_msa(dj, std::vector<double>{gaps[g]}, quick(0), &h)[0].annual_rate;
      EXPECT_NEAR(f[g].jackknife_rate[j], want, 1e-12 * want) << g << " " << j;
      ln.push_back(std::log(want));
    }
    double mean = 0, ss = 0;
    for (double v : ln) mean += v / 12.0;
    for (double v : ln) ss += (v - mean) * (v - mean);
    const double se = std::sqrt(11.0 / 12.0 * ss), q = 2.200985160082949;  // scipy.stats.t.ppf(0.975, 11)
    EXPECT_NEAR(f[g].rate_jack_hi, f[g].annual_rate * std::exp(q * se), 1e-9 * f[g].annual_rate);
    EXPECT_NEAR(f[g].rate_jack_lo, f[g].annual_rate * std::exp(-q * se), 1e-9 * f[g].annual_rate);
    EXPECT_NEAR(f[g].probability_jack_hi, 1 - std::exp(-f[g].rate_jack_hi * 50), 1e-15);
    EXPECT_GT(se, 0.05);
  }
}

// The bisection IDA's jackknife: leave-one-out rates c_j a exp(-b x) at every gap give x*_(j) = ln(c_j a/target)/b.
TEST(StripesTargetAtGaps, JackknifeInterpolatesEachLeaveOneOutCurve) {
  const double a = 0.05, b = 3.0, target = 4.0e-4;
  const std::vector<double> c{0.9, 1.1, 1.0, 1.3, 0.7};
  std::vector<GapFragility> fits;
  for (double x : {0.25, 0.5, 1.0, 1.5, 2.0}) {
    GapFragility g;
    g.gap = x, g.has_hazard = true, g.annual_rate = a * std::exp(-b * x);
    for (double cj : c) g.jackknife_rate.push_back(cj * g.annual_rate);
    fits.push_back(g);
  }
  const TargetGap t = risk_targeted_gap_at_gaps(fits, target, 0.95);
  ASSERT_EQ(t.status, "ok");
  double mean = 0, ss = 0;
  std::vector<double> ln;
  for (double cj : c) ln.push_back(std::log(std::log(cj * a / target) / b)), mean += ln.back() / 5.0;
  for (double v : ln) ss += (v - mean) * (v - mean);
  EXPECT_NEAR(t.jack_se, std::sqrt(4.0 / 5.0 * ss), 1e-12);
  EXPECT_NEAR(t.jack_hi, t.gap * std::exp(2.776445105197793 * t.jack_se), 1e-12);  // t(0.975, 4 df)
  EXPECT_TRUE(std::isnan(t.hi));  // no bootstrap replicates given
  EXPECT_EQ(t.advice, t.jack_hi);
  fits[2].jackknife_rate[3] = NAN;  // a leave-one-out fit without a rate: no jackknife
  EXPECT_TRUE(std::isnan(risk_targeted_gap_at_gaps(fits, target, 0.95).jack_se));
}

// Coverage of the risk-targeted gap's intervals over simulated studies with a known answer (x* from Cornell's
// closed form). Slow (about a minute); run by hand:
//   build/test_stripes --gtest_also_run_disabled_tests --gtest_filter='StripesTarget.DISABLED_CoverageExperiment'
// 2026-11-25, 200 studies each: 25 records: bootstrap 0.860 (truth above 0.100), jackknife 0.920 (0.055), union
// 0.920 (0.055); sd of ln x-hat 0.0732 against a mean bootstrap se 0.0634 and jackknife se 0.0666. 60 records:
// 0.915 (0.070), 0.935 (0.055), 0.945 (0.045).
TEST(StripesTarget, DISABLED_CoverageExperiment) {
  const double mu = 0.1, sr = 0.3, sm = 0.35, beta = std::hypot(sr, sm);
  const double k0 = 4e-4, k = 2.5, target = 4.04054e-4;
  const HazardCurve h = HazardCurve::power_law(k0, k);
  const double truth = std::pow(k0 * std::exp(k * k * beta * beta / 2) / target, 1 / k) * std::exp(mu);
  for (int R : {25, 60}) {
    int n = 0, hit[3] = {0, 0, 0}, above[3] = {0, 0, 0};
    double sl = 0, sl2 = 0, sb = 0, sj = 0;
    for (int s = 0; s < 200; ++s) {
      const Demands d = lognormal_demands(static_cast<std::size_t>(R), 40, log_levels(0.2, 6.0, 10), mu, sr, sm,
                                          5000 + static_cast<std::uint64_t>(s));
      const TargetGap t = risk_targeted_gap(d, h, target, quick(400, 2, 99 + static_cast<std::uint64_t>(s)));
      if (t.status != "ok" || std::isnan(t.jack_se)) continue;
      ++n;
      const Interval iv[3] = {{t.lo, t.hi}, {t.jack_lo, t.jack_hi}, {std::fmin(t.lo, t.jack_lo), t.advice}};
      for (int i = 0; i < 3; ++i) hit[i] += covers(iv[i], truth), above[i] += truth > iv[i].hi;
      sl += std::log(t.gap), sl2 += std::log(t.gap) * std::log(t.gap);
      sb += (std::log(t.hi) - std::log(t.lo)) / 3.92, sj += t.jack_se;
    }
    const double m = sl / n;
    std::printf("R %d, %d studies: coverage (truth above) bootstrap %.3f (%.3f), jackknife %.3f (%.3f), union %.3f (%.3f); "
                "sd of ln x-hat %.4f, mean bootstrap se %.4f, mean jackknife se %.4f\n",
                R, n, hit[0] / double(n), above[0] / double(n), hit[1] / double(n), above[1] / double(n),
                hit[2] / double(n), above[2] / double(n), std::sqrt(sl2 / n - m * m), sb / n, sj / n);
  }
}

// Coverage of the per-gap annual rate's intervals, the same design (truth: Cornell's closed form at each gap); run
// by hand like the one above (2 s). 2026-11-25, 200 studies: 25 records: bootstrap 0.860 at both gaps (truth above
// 0.105), jackknife 0.905 / 0.895 (0.065 / 0.075); 60 records: bootstrap 0.905 (0.080), jackknife 0.920 / 0.935.
TEST(StripesMsa, DISABLED_RateCoverageExperiment) {
  const double mu = 0.1, sr = 0.3, sm = 0.35, beta = std::hypot(sr, sm);
  const double k0 = 4e-4, k = 2.5;
  const HazardCurve h = HazardCurve::power_law(k0, k);
  const std::vector<double> gaps{0.7, 1.4};
  for (int R : {25, 60}) {
    int n = 0, hit[2] = {0, 0}, above[2] = {0, 0}, hitj[2] = {0, 0}, abovej[2] = {0, 0}, hitu[2] = {0, 0}, aboveu[2] = {0, 0};
    for (int s = 0; s < 200; ++s) {
      const Demands d = lognormal_demands(static_cast<std::size_t>(R), 40, log_levels(0.2, 6.0, 10), mu, sr, sm,
                                          5000 + static_cast<std::uint64_t>(s));
      const std::vector<GapFragility> f = fit_msa(d, gaps, quick(400, 2, 99 + static_cast<std::uint64_t>(s)), &h);
      for (std::size_t g = 0; g < gaps.size(); ++g) {
        const double truth = k0 * std::pow(gaps[g] * std::exp(-mu), -k) * std::exp(k * k * beta * beta / 2);
        if (!f[g].fit.ok()) continue;
        ++n;
        hit[g] += f[g].rate_lo <= truth && truth <= f[g].rate_hi;
        above[g] += truth > f[g].rate_hi;
        hitj[g] += f[g].rate_jack_lo <= truth && truth <= f[g].rate_jack_hi;
        abovej[g] += truth > f[g].rate_jack_hi;
        hitu[g] += std::fmin(f[g].rate_lo, f[g].rate_jack_lo) <= truth && truth <= std::fmax(f[g].rate_hi, f[g].rate_jack_hi);
        aboveu[g] += truth > std::fmax(f[g].rate_hi, f[g].rate_jack_hi);
      }
    }
    std::printf("R %d: rate coverage gap 0.7 %.3f (truth above %.3f), gap 1.4 %.3f (%.3f), %d fits\n", R,
                hit[0] / 200.0, above[0] / 200.0, hit[1] / 200.0, above[1] / 200.0, n);
    std::printf("   jackknife %.3f (%.3f), %.3f (%.3f); union %.3f (%.3f), %.3f (%.3f)\n", hitj[0] / 200.0, abovej[0] / 200.0,
                hitj[1] / 200.0, abovej[1] / 200.0, hitu[0] / 200.0, aboveu[0] / 200.0, hitu[1] / 200.0, aboveu[1] / 200.0);
  }
}
