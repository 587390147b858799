// Separations in metres and their two-stage bootstrap intervals, and the code rules (analysis/separation.hpp):
// the order statistic against a brute-force search, intervals that collapse for identical records and widen
// as records disagree, coverage of the interval on simulated studies with a known answer, independence of the
// thread count, and the rules against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <atomic>
#include <functional>
#include <random>

#include "pounding/analysis/separation.hpp"
#include "pounding/analysis/stats.hpp"
#include "pounding/core/progress.hpp"

using namespace pounding;
using namespace pounding::separation;

namespace {

// records x models demands: z = record effect a_k (spread x k) + model value b_m
Demands grid(std::size_t R, std::size_t M, double record_spread, double model_spread) {
  Demands d;
  d.records = R, d.models = M;
  for (std::size_t k = 0; k < R; ++k)
    for (std::size_t m = 0; m < M; ++m)
      d.z.push_back(0.2 + record_spread * static_cast<double>(k) + model_spread * static_cast<double>(m));
  return d;
}

double width(const Estimate& e) { return e.hi - e.lo; }

}  // namespace

TEST(Separation, OrderStatisticIsTheSmallestGapMeetingTheTarget) {
  std::mt19937_64 g(7);
  std::normal_distribution<double> n(0.3, 0.1);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> z(37 + trial * 11);
    for (double& v : z) v = n(g);
    for (double t : {0.0, 0.01, 0.05, 0.1, 0.5, 0.9}) {
      const double s = separation_at(z, t);
      EXPECT_LE(exceedance(z, s), t) << t;
      // brute force: every smaller candidate gap (each value, and just below s) exceeds the target
      double best = INFINITY;
      for (double c : z)
        if (exceedance(z, c) <= t) best = std::min(best, c);
      EXPECT_EQ(s, best) << "t " << t << " n " << z.size();
      EXPECT_GT(exceedance(z, std::nextafter(s, -INFINITY)), t);
    }
  }
  EXPECT_EQ(separation_at({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 0.1), 9.0);  // at most 1 of 10 above
  EXPECT_TRUE(std::isnan(separation_at({}, 0.1)));
}

TEST(Separation, IntervalCollapsesWhenEveryRecordIsACopyOfOneAndModelsAgree) {
  const Demands d = grid(10, 20, 0.0, 0.0);  // one deterministic pair, ten copies of one record
  const double targets[] = {0.1, 0.05}, gaps[] = {0.1, 0.3};
  const BootstrapResult b = bootstrap(d, targets, gaps, {.replicates = 500, .confidence = 0.95, .seed = 3});
  for (const Estimate& e : b.separation) {
    EXPECT_EQ(e.lo, e.hi);
    EXPECT_EQ(e.value, 0.2);
  }
  EXPECT_EQ(b.probability[0].lo, 1.0);
  EXPECT_EQ(b.probability[0].hi, 1.0);
  EXPECT_EQ(b.probability[1].lo, 0.0);
  EXPECT_EQ(b.probability[1].hi, 0.0);
}

TEST(Separation, IntervalWidensAsRecordsDisagree) {
  const double targets[] = {0.1};
  double last = -1;
  for (double spread : {0.0, 0.01, 0.02, 0.05}) {
    const BootstrapResult b = bootstrap(grid(15, 30, spread, 0.001), targets, {}, {.replicates = 800, .seed = 11});
    const double w = width(b.separation[0]);
    EXPECT_GT(w, last) << "record spread " << spread;
    EXPECT_LE(b.separation[0].lo, b.separation[0].value);
    EXPECT_GE(b.separation[0].hi, b.separation[0].value);
    last = w;
  }
  // with identical records only the models vary: the interval is the models' alone, much narrower than
  // with records 0.05 apart
  const double only_models = width(bootstrap(grid(15, 30, 0.0, 0.001), targets, {}, {.replicates = 800}).separation[0]);
  EXPECT_LT(only_models, 0.1 * last);
  EXPECT_GT(only_models, 0.0);
}

TEST(Separation, IntervalCoversTheTrueSeparationOnSimulatedStudies) {
  // z_km = a_k + e_km, a ~ N(0, 1) per record, e ~ N(0, 0.5^2): z ~ N(0, 1.25) and the true separation at t
  // is its (1 - t) quantile. Over 200 simulated studies of 40 records x 25 models the 90 % interval must
  // cover it in 80-97 % of the studies (the two-stage percentile bootstrap is close to nominal here).
  std::mt19937_64 g(2024);
  std::normal_distribution<double> a(0.0, 1.0), e(0.0, 0.5);
  const double t = 0.1, truth = std::sqrt(1.25) * 1.2815515655446004;  // z_0.9
  int covered = 0;
  const int studies = 200;
  for (int s = 0; s < studies; ++s) {
    Demands d;
    d.records = 40, d.models = 25;
    for (std::size_t k = 0; k < d.records; ++k) {
      const double ak = a(g);
      for (std::size_t m = 0; m < d.models; ++m) d.z.push_back(ak + e(g));
    }
    const double targets[] = {t};
    const BootstrapResult b =
        bootstrap(d, targets, {}, {.replicates = 400, .confidence = 0.9, .seed = static_cast<std::uint64_t>(s)});
    covered += b.separation[0].lo <= truth && truth <= b.separation[0].hi;
  }
  const double coverage = static_cast<double>(covered) / studies;
  std::printf("coverage of the 90 %% interval over %d studies: %.3f\n", studies, coverage);
  EXPECT_GE(coverage, 0.80);
  EXPECT_LE(coverage, 0.97);
}

TEST(Separation, ResultDoesNotDependOnThreadsAndIsSeeded) {
  const Demands d = grid(12, 17, 0.013, 0.004);
  const double targets[] = {0.2, 0.05}, gaps[] = {0.25, 0.3};
  auto run = [&](int threads, std::uint64_t seed) {
    return bootstrap(d, targets, gaps, {.replicates = 301, .confidence = 0.95, .seed = seed, .threads = threads});
  };
  const BootstrapResult a = run(1, 5), b = run(2, 5), c = run(7, 5), other = run(2, 6);
  bool differs = false;
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(a.separation[i].lo, b.separation[i].lo);
    EXPECT_EQ(a.separation[i].hi, c.separation[i].hi);
    EXPECT_EQ(a.probability[i].lo, c.probability[i].lo);
    EXPECT_EQ(a.probability[i].hi, b.probability[i].hi);
    differs |= a.separation[i].lo != other.separation[i].lo || a.separation[i].hi != other.separation[i].hi;
  }
  EXPECT_TRUE(differs) << "another seed gave the same replicates";
}

TEST(Separation, ExcludedAnalysesAreLeftOut) {
  Demands d = grid(3, 4, 0.1, 0.01);
  d.z[0] = NAN, d.z[5] = NAN;
  EXPECT_EQ(d.pooled().size(), 10u);
  EXPECT_EQ(d.record(1).size(), 3u);
  const double targets[] = {0.0};
  const BootstrapResult b = bootstrap(d, targets, {}, {.replicates = 50});
  EXPECT_EQ(b.separation[0].value, 0.2 + 0.2 + 0.03);  // the largest ok value
}

TEST(CodeRules, DdcCorrelationMatchesClosedForms) {
  // equal damping: the classical CQC coefficient
  for (double r : {0.5, 0.8, 1.0, 1.3, 2.0}) EXPECT_NEAR(ddc_rho(1.0, r, 0.05, 0.05), cqc_rho(r, 0.05), 1e-15);
  // equal periods: 2 sqrt(z1 z2) / (z1 + z2)
  EXPECT_NEAR(ddc_rho(1.2, 1.2, 0.05, 0.02), 2 * std::sqrt(0.05 * 0.02) / 0.07, 1e-15);
  // symmetric in the buildings
  EXPECT_NEAR(ddc_rho(1.0, 1.3, 0.05, 0.02), ddc_rho(1.3, 1.0, 0.02, 0.05), 1e-15);
  // unequal damping: the white-noise correlation of the two transfer functions, integrated by SciPy quad
  // (tests/python/test_ddc_scipy.py; the closed form with (z1 + (T2/T1) z2) gave 0.055913, 0.023121, 0.007087)
  EXPECT_NEAR(ddc_rho(1.0, 1.3, 0.05, 0.02), 0.0625339877320062, 1e-14);
  EXPECT_NEAR(ddc_rho(1.0, 1.5, 0.05, 0.02), 0.02745601028963657, 1e-14);
  EXPECT_NEAR(ddc_rho(1.0, 2.0, 0.05, 0.02), 0.00944983825673445, 1e-14);
  // swapping the damping ratios between the buildings gives the other value (the old code's for the first order)
  EXPECT_NEAR(ddc_rho(1.0, 1.5, 0.02, 0.05), 0.02312085077022021, 1e-14);
}

TEST(CodeRules, GapsInMetres) {
  const DesignPair p{.u1 = 0.12, .u2 = 0.16, .T1 = 0.9, .T2 = 1.3, .zeta1 = 0.05, .zeta2 = 0.05, .code_gap = 0.35};
  const std::vector<Rule> rules = code_rules(p, 0.005);
  ASSERT_EQ(rules.size(), 9u);
  EXPECT_EQ(rules[0].name, "Standard 2800");
  EXPECT_EQ(rules[0].gap, 0.35);
  EXPECT_NEAR(rules[1].gap, 0.28, 1e-15);  // ABS
  EXPECT_NEAR(rules[2].gap, 0.20, 1e-15);  // SRSS 3-4-5
  const double rho = cqc_rho(1.3 / 0.9, 0.05);
  EXPECT_NEAR(rules[3].gap, std::sqrt(0.12 * 0.12 + 0.16 * 0.16 - 2 * rho * 0.12 * 0.16), 1e-15);
  EXPECT_LT(rules[3].gap, rules[2].gap);  // positively correlated: DDC below SRSS
  EXPECT_EQ(rules[4].gap, rules[2].gap);  // ASCE same property = SRSS
  EXPECT_EQ(rules[5].gap, rules[1].gap);  // ASCE separate lots = the sum
  EXPECT_EQ(rules[6].gap, rules[1].gap);  // EC8 separate properties = the sum
  EXPECT_EQ(rules[7].gap, rules[2].gap);  // EC8 same property = SRSS
  EXPECT_NEAR(rules[8].gap, 0.14, 1e-15);  // 0.7 SRSS
  EXPECT_NE(rules[4].clause.find("12.12.3"), std::string::npos);
  EXPECT_NE(rules[8].clause.find("4.4.2.7"), std::string::npos);
  EXPECT_EQ(code_rules(p, 0.01)[0].name, "coefficient rule");
  // the text-free gaps a grid report evaluates per model: the rules' own, in order
  ASSERT_EQ(rules.size(), code_rule_count);
  for (std::size_t j = 0; j < code_rule_count; ++j) EXPECT_EQ(code_rule_gaps(p)[j], rules[j].gap) << rules[j].name;
  // identical periods: rho = 1 and DDC = |u1 - u2|
  const DesignPair same{.u1 = 0.12, .u2 = 0.16, .T1 = 1.0, .T2 = 1.0, .zeta1 = 0.05, .zeta2 = 0.05, .code_gap = 0.3};
  EXPECT_NEAR(code_rules(same, 0.005)[3].gap, 0.04, 1e-12);
}

TEST(Separation, CurveBandIsConsistentWithThePointValues) {
  Demands d = grid(9, 13, 0.02, 0.003);
  d.z[7] = d.z[8];  // ties
  std::vector<double> gaps;
  for (int i = 0; i <= 60; ++i) gaps.push_back(0.15 + 0.005 * i);
  const double targets[] = {0.3, 0.1, 0.02};
  const BootstrapResult b = bootstrap(d, targets, gaps, {.replicates = 400, .seed = 9});
  const std::vector<double> z = d.pooled();
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    EXPECT_EQ(b.probability[i].value, exceedance(z, gaps[i]));
    EXPECT_LE(b.probability[i].lo, b.probability[i].value + 1e-12);
    EXPECT_GE(b.probability[i].hi, b.probability[i].value - 1e-12);
    if (i) {
      EXPECT_LE(b.probability[i].hi, b.probability[i - 1].hi);  // the band falls with the gap
    }
  }
  for (std::size_t t = 0; t < 3; ++t) EXPECT_EQ(b.separation[t].value, separation_at(z, targets[t]));
  EXPECT_EQ(b.probability.front().hi, 1.0);  // below every value
}

// Issue 23, item 2: the lognormal beside the order statistic. ln z = {0, 1, 2}: mu = 1, sigma = sqrt(2/3) (maximum
// likelihood, divisor n); P(z > g) = 1 - Phi((ln g - mu) / sigma), so the median is e and the 1 - Phi(1) target is
// exp(mu + sigma); a demand <= 0 is a point mass at 0 that scales the target by 1 / (1 - p0).
TEST(SeparationLognormal, FitAndQuantilesInClosedForm) {
  const double z[] = {1.0, std::exp(1.0), std::exp(2.0), NAN};
  const LognormalFit f = fit_lognormal(z);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f.n, 3u);
  EXPECT_NEAR(f.mu, 1.0, 1e-15);
  EXPECT_NEAR(f.sigma, std::sqrt(2.0 / 3.0), 1e-15);
  EXPECT_EQ(f.p0, 0.0);
  const double tail1 = 0.15865525393145707;  // 1 - Phi(1)
  EXPECT_NEAR(f.separation(0.5), std::exp(1.0), 1e-12);
  EXPECT_NEAR(f.separation(tail1), std::exp(1.0 + std::sqrt(2.0 / 3.0)), 1e-12);
  const double z0[] = {1.0, std::exp(1.0), std::exp(2.0), 0.0};
  const LognormalFit g = fit_lognormal(z0);
  EXPECT_EQ(g.p0, 0.25);
  EXPECT_NEAR(g.separation(0.75 * tail1), std::exp(1.0 + std::sqrt(2.0 / 3.0)), 1e-12);
  EXPECT_EQ(g.separation(0.8), 0.0);  // more than the positive demands' share: no gap needed
  EXPECT_FALSE(fit_lognormal(std::span<const double>(z, 1)).ok());
}

// The lognormal rides on the same replicates: the empirical results keep their bits, the lognormal's value is the
// full-data fit, and a target finer than the records still moves the lognormal (the order statistic cannot).
TEST(SeparationLognormal, SameReplicatesAndFinerTargetsMove) {
  Demands d;
  d.records = 20, d.models = 1;  // a fixed pair: one demand per record
  for (std::size_t k = 0; k < d.records; ++k) d.z.push_back(std::exp(-2.0 + 0.1 * static_cast<double>(k)));
  const double targets[] = {0.1, 0.01, 0.001}, gaps[] = {0.2, 0.4};
  BootstrapSettings s{.replicates = 400, .confidence = 0.95, .seed = 3, .threads = 2};
  const BootstrapResult a = bootstrap(d, targets, gaps, s);
  s.lognormal = true;
  const BootstrapResult b = bootstrap(d, targets, gaps, s);
  ASSERT_EQ(b.lognormal.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(a.separation[i].value, b.separation[i].value);
    EXPECT_EQ(a.separation[i].lo, b.separation[i].lo);
    EXPECT_EQ(a.separation[i].hi, b.separation[i].hi);
    EXPECT_EQ(b.lognormal[i].value, fit_lognormal(d.z).separation(targets[i]));
    EXPECT_LT(b.lognormal[i].lo, b.lognormal[i].value);
    EXPECT_GT(b.lognormal[i].hi, b.lognormal[i].value);
  }
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(a.probability[i].hi, b.probability[i].hi);
  EXPECT_EQ(b.separation[1].value, b.separation[2].value);  // 1 % and 0.1 % of 20 records: the largest
  EXPECT_EQ(b.separation[2].value, d.z.back());
  EXPECT_GT(b.lognormal[2].value, b.lognormal[1].value);
}

// ---------------------------------------------------------------- issue 27, item 1: the bootstrap on the rank tree
namespace {

// The two-stage bootstrap as it was before issue 27 (and as its definition reads): R records drawn with
// replacement, inside each as many of its ok analyses as it has, drawn one by one; the statistics of the pooled
// replicate by sorting. O(n) per replicate, written here independently of separation.cpp (std::mt19937_64).
struct Direct {
  std::vector<std::vector<double>> sep, prob;  // [statistic][replicate]
};
Direct direct_bootstrap(const Demands& d, std::span<const double> targets, std::span<const double> gaps, int B,
                        std::uint64_t seed) {
  std::mt19937_64 g(seed);
  Direct out;
  out.sep.resize(targets.size()), out.prob.resize(gaps.size());
  std::vector<std::vector<double>> rec;
  for (std::size_t k = 0; k < d.records; ++k) rec.push_back(d.record(k));
  for (int b = 0; b < B; ++b) {
    std::vector<double> z;
    for (std::size_t i = 0; i < d.records; ++i) {
      const auto& r = rec[std::uniform_int_distribution<std::size_t>(0, d.records - 1)(g)];
      for (std::size_t j = 0; j < r.size(); ++j) z.push_back(r[std::uniform_int_distribution<std::size_t>(0, r.size() - 1)(g)]);
    }
    if (z.empty()) continue;
    std::sort(z.begin(), z.end(), std::greater<>());  // descending: z[j] has j values above or equal
    for (std::size_t t = 0; t < targets.size(); ++t) {
      const auto j = static_cast<std::size_t>(std::floor(targets[t] * static_cast<double>(z.size())));
      out.sep[t].push_back(z[std::min(j, z.size() - 1)]);
    }
    for (std::size_t i = 0; i < gaps.size(); ++i)
      out.prob[i].push_back(static_cast<double>(std::count_if(z.begin(), z.end(), [&](double v) { return v > gaps[i]; })) /
                            static_cast<double>(z.size()));
  }
  return out;
}

double type7(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double h = static_cast<double>(v.size() - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  return lo + 1 >= v.size() ? v.back() : v[lo] + (h - static_cast<double>(lo)) * (v[lo + 1] - v[lo]);
}

Demands lumpy_study(std::size_t R, std::size_t M, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::normal_distribution<double> a(0.0, 0.4), e(0.0, 0.25);
  Demands d;
  d.records = R, d.models = M;
  for (std::size_t k = 0; k < R; ++k) {
    const double ak = a(g);
    for (std::size_t m = 0; m < M; ++m) d.z.push_back(std::round(1000 * std::exp(-1.5 + ak + e(g))) / 1000);  // ties (values on a 0.001 grid)
  }
  d.z[3] = NAN, d.z[M + 1] = NAN;
  for (std::size_t m = 0; m < M; ++m) d.z[2 * M + m] = NAN;  // a record without an ok analysis
  return d;
}

}  // namespace

// The rank-tree replicates have the direct bootstrap's distribution: at three confidence levels (six quantiles of
// each statistic's replicate distribution) the two agree within their Monte Carlo error (8 % of the 95 % interval's
// width; the standard error of a difference is about 1.5 % at 4000 replicates each).
TEST(SeparationBootstrap, HasTheDirectTwoStageBootstrapsDistribution) {
  const Demands d = lumpy_study(14, 60, 5);
  const double targets[] = {0.3, 0.1, 0.05, 0.01}, gaps[] = {0.1, 0.2, 0.3, 0.5, 0.8};
  const int B = 4000;
  const Direct ref = direct_bootstrap(d, targets, gaps, B, 77);
  for (double conf : {0.5, 0.8, 0.95}) {
    const BootstrapResult b = bootstrap(d, targets, gaps, {.replicates = B, .confidence = conf, .seed = 21});
    const double a = 0.5 * (1 - conf);
    auto check = [&](const Estimate& e, const std::vector<double>& r, const char* what, std::size_t i) {
      const double width = type7(r, 0.975) - type7(r, 0.025);
      EXPECT_NEAR(e.lo, type7(r, a), 0.08 * width + 0.001) << what << " " << i << " conf " << conf;
      EXPECT_NEAR(e.hi, type7(r, 1 - a), 0.08 * width + 0.001) << what << " " << i << " conf " << conf;
    };
    for (std::size_t t = 0; t < 4; ++t) check(b.separation[t], ref.sep[t], "target", t);
    for (std::size_t i = 0; i < 5; ++i) check(b.probability[i], ref.prob[i], "gap", i);
  }
}

// Replicate b's counts are one function of (seed, b): a statistic's interval is the same bits whatever else the
// call asks for (the report's Markdown tables and its CSV agree), with one thread or several.
TEST(SeparationBootstrap, EveryCallSeesTheSameReplicates) {
  const Demands d = lumpy_study(11, 40, 9);
  const auto p = prepare(d);
  const double targets[] = {0.2, 0.05, 0.01}, gaps[] = {0.05, 0.15, 0.25, 0.4, 1e9, -1};
  const BootstrapSettings s{.replicates = 300, .seed = 4, .threads = 2};
  const BootstrapResult all = bootstrap(*p, targets, gaps, s);
  for (std::size_t t = 0; t < 3; ++t) {
    const BootstrapResult one = bootstrap(*p, std::span(targets + t, 1), {}, {.replicates = 300, .seed = 4, .threads = 1});
    EXPECT_EQ(one.separation[0].lo, all.separation[t].lo);
    EXPECT_EQ(one.separation[0].hi, all.separation[t].hi);
  }
  for (std::size_t i = 0; i < 6; ++i) {
    const BootstrapResult one = bootstrap(d, {}, std::span(gaps + i, 1), {.replicates = 300, .seed = 4, .threads = 3});
    EXPECT_EQ(one.probability[0].lo, all.probability[i].lo) << i;
    EXPECT_EQ(one.probability[0].hi, all.probability[i].hi) << i;
  }
  EXPECT_EQ(all.probability[4].hi, 0.0);  // above every value
  EXPECT_EQ(all.probability[5].lo, 1.0);  // below every value
}

// Progress per replicate under the phase "report: separation bootstrap", and a raised stop ends the loop with
// Cancelled (before issue 27 the bootstrap had no hook: the report's bootstrap ran on after a stop).
TEST(SeparationBootstrap, ReportsProgressAndHonoursAStop) {
  const Demands d = lumpy_study(9, 30, 2);
  const double targets[] = {0.1};
  std::atomic<bool> stop{false};
  std::string phase;
  WorkHook hook{[&](const PhaseProgress& p) { phase = p.phase; }, &stop};
  BootstrapSettings s{.replicates = 200, .seed = 1, .threads = 2};
  s.hook = &hook;
  EXPECT_NO_THROW(bootstrap(d, targets, {}, s));
  stop = true;
  EXPECT_THROW(bootstrap(d, targets, {}, s), Cancelled);
  EXPECT_TRUE(phase.empty() || phase == "report: separation bootstrap") << phase;
}

// The pooled ranks (a k-way merge cut at pivots, one part per thread) are the positions in the pooled values
// sorted by (value, record), whatever the thread count -- ties across records included.
TEST(SeparationBootstrap, RanksAreThePooledOrderForAnyThreadCount) {
  const Demands d = lumpy_study(13, 37, 4);
  std::vector<std::pair<double, std::size_t>> all;
  for (std::size_t k = 0; k < d.records; ++k)
    for (double v : d.record(k)) all.push_back({v, k});
  std::sort(all.begin(), all.end());
  for (int threads : {1, 2, 3, 7}) {
    const auto p = prepare(d, threads);
    ASSERT_EQ(p->N, all.size());
    std::vector<int> seen(all.size(), 0);
    for (std::size_t k = 0; k < d.records; ++k)
      for (std::size_t j = 0; j < p->values[k].size(); ++j) {
        const std::uint32_t r = p->ranks[k][j];
        ASSERT_LT(r, all.size());
        EXPECT_EQ(all[r].first, p->values[k][j]) << threads;
        EXPECT_EQ(all[r].second, k) << threads;
        ++seen[r];
      }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; })) << threads;
  }
}
