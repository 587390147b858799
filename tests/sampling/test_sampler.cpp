// The stochastic structure model against things it did not compute itself: closed-form moments and CDFs
// of the (truncated) lognormal written out here with std::erfc, Kolmogorov-Smirnov and chi-square tests,
// published reference outputs of SplitMix64 and taus88 (and L'Ecuyer's own taus88 code), and exact identities of eqs (5)-(9).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/random/taus88.hpp>
#include <toml++/toml.h>

#include "pounding/core/error.hpp"
#include "pounding/sampling/sampler.hpp"

using namespace pounding;

namespace {

constexpr std::uint64_t kSeed = 20240917;
constexpr int kDraws = 100000;

double Phi(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

// Kolmogorov statistic D_n = sup |F_n - F| of data against cdf.
template <class Cdf>
double ks_statistic(std::vector<double> x, Cdf cdf) {
  std::sort(x.begin(), x.end());
  const double n = static_cast<double>(x.size());
  double d = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    double f = cdf(x[i]);
    d = std::max({d, (static_cast<double>(i) + 1) / n - f, f - static_cast<double>(i) / n});
  }
  return d;
}
// Asymptotic p-value of the Kolmogorov distribution, Stephens' small-n correction.
double ks_pvalue(double d, std::size_t n) {
  const double sn = std::sqrt(static_cast<double>(n));
  const double lambda = (sn + 0.12 + 0.11 / sn) * d;
  double q = 0;
  for (int k = 1; k < 100; ++k) q += 2.0 * ((k % 2) ? 1.0 : -1.0) * std::exp(-2.0 * k * k * lambda * lambda);
  return std::clamp(q, 0.0, 1.0);
}

double mean(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}
double variance(const std::vector<double>& x) {
  double m = mean(x), s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return s / static_cast<double>(x.size() - 1);
}
double correlation(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = mean(x), my = mean(y), sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

// 10^5 pairs of one period pair (i1, i2), samples 0..n-1.
std::vector<SampledPair> draw(const StructureSampler& s, std::int32_t i1, std::int32_t i2, int n = kDraws,
                              std::int64_t first = 0) {
  std::vector<SampledPair> out(static_cast<std::size_t>(n));
  s.sample_block(i1, i2, first, out);
  return out;
}

// Moments and variance-of-sample-variance from raw moments E[X^k], k = 1..4.
struct Moments {
  double mean, var, m4;
};
Moments from_raw(const double e[5]) {
  double mu = e[1];
  double var = e[2] - mu * mu;
  double m4 = e[4] - 4 * e[3] * mu + 6 * e[2] * mu * mu - 3 * mu * mu * mu * mu;
  return {mu, var, m4};
}

}  // namespace

// ------------------------------------------------------------------------------------- defaults and grid

TEST(SamplerModel, DefaultsAreThePapers) {
  StructureModel m;
  ASSERT_EQ(m.periods.size(), 11u);
  for (std::size_t i = 0; i < 11; ++i) EXPECT_NEAR(m.periods[i], 1.00 + 0.05 * static_cast<double>(i), 1e-15);
  EXPECT_EQ(m.periods[2], 1.1);  // the double a user typing 1.1 gets
  EXPECT_EQ(m.samples_per_pair, 256);
  EXPECT_EQ(m.model_count(), 30976);
  EXPECT_EQ(m.aspect_ratios, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(m.rho_mean, 1800.0);
  EXPECT_EQ(m.rho_cov, 0.068);
  EXPECT_EQ(m.mbar_mean, 0.6);
  EXPECT_EQ(m.mbar_cov, 0.2);
  EXPECT_EQ(m.mbar_min, 0.4);
  EXPECT_EQ(m.mbar_max, 0.8);
  EXPECT_EQ(m.zeta, 0.05);
  EXPECT_EQ(m.drift / m.ductility, 0.02 / 6);
  EXPECT_EQ(m.alpha, 0.05);
  EXPECT_EQ(m.code_gap_coefficient, 0.005);
  // 4000 psi concrete: E = 57000 sqrt(4000) psi, 1 psi = 6894.757 Pa.
  EXPECT_NEAR(m.contact_youngs_modulus, 57000 * std::sqrt(4000.0) * 6894.757, 0.01e9);
}

TEST(SamplerModel, HeightIntervalsFollowThePeriodHeightRule) {
  StructureModel m;
  for (double T : m.periods) {
    HeightInterval iv = height_interval(m, T);
    // eq. (6) solved for h with the exponent 4/3 written out
    EXPECT_NEAR(iv.lo, std::max(30.0, std::pow(T / 0.08, 4.0 / 3.0)), 1e-12);
    EXPECT_NEAR(iv.hi, std::min(50.0, std::pow(T / 0.05, 4.0 / 3.0)), 1e-12);
  }
  EXPECT_EQ(height_interval(m, 1.0).lo, 30.0);
  EXPECT_EQ(height_interval(m, 1.0).hi, 50.0);
  EXPECT_NEAR(height_interval(m, 1.5).lo, 49.81212, 1e-5);  // 18.75^(4/3): the narrowest interval
}

TEST(SamplerModel, EmptyHeightIntervalNamesTAndBounds) {
  StructureModel m;
  m.periods = {1.0, 1.6};  // (1.6 / 0.08)^(4/3) = 20^(4/3) = 54.288 m > 50 m
  try {
    StructureSampler s(m, kSeed);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("T = 1.6 s"), std::string::npos) << what;
    EXPECT_NE(what.find("54.2884"), std::string::npos) << what;
    EXPECT_NE(what.find("= 50 m"), std::string::npos) << what;
    EXPECT_NE(e.where().find("periods"), std::string::npos) << e.where();
  }
  // And from a study file: the line of the periods key.
  auto t = toml::parse("[structures]\nperiods = [1.0, 1.6]\n");
  try {
    parse_structure_model(*t["structures"].as_table(), "study.toml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.where().find("study.toml:2"), std::string::npos) << e.where();
    EXPECT_NE(std::string(e.what()).find("54.2884"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------------------------------------------- distributions

TEST(SamplerDistributions, RhoMeanCovAndLognormalShape) {
  StructureSampler s(StructureModel{}, kSeed);
  auto pairs = draw(s, 3, 7);
  std::vector<double> rho;
  for (const auto& p : pairs) rho.push_back(p.s1.rho);
  const double sig2 = std::log(1 + 0.068 * 0.068), mu = std::log(1800.0) - sig2 / 2;
  // raw moments of the lognormal: E[X^k] = exp(k mu + k^2 sigma^2 / 2)
  double e[5];
  for (int k = 0; k <= 4; ++k) e[k] = std::exp(k * mu + k * k * sig2 / 2);
  Moments th = from_raw(e);
  EXPECT_NEAR(th.mean, 1800.0, 1e-9);
  EXPECT_NEAR(std::sqrt(th.var) / th.mean, 0.068, 1e-12);
  const double n = kDraws, m = mean(rho), v = variance(rho);
  const double se_mean = std::sqrt(th.var / n), se_var = std::sqrt((th.m4 - th.var * th.var) / n);
  EXPECT_NEAR(m, 1800.0, 4.5 * se_mean);
  EXPECT_NEAR(v, th.var, 4.5 * se_var);
  std::printf("rho: mean %.3f (1800, se %.3f), CoV %.5f (0.068)\n", m, se_mean, std::sqrt(v) / m);
  double d = ks_statistic(rho, [&](double x) { return Phi((std::log(x) - mu) / std::sqrt(sig2)); });
  std::printf("rho: KS D = %.5f, p = %.3f\n", d, ks_pvalue(d, rho.size()));
  EXPECT_GT(ks_pvalue(d, rho.size()), 1e-3);
  // The paper's justification of mean and CoV: rho in [1600, 2000] with ~90 % confidence.
  double inside = 0;
  for (double r : rho) inside += (r >= 1600 && r <= 2000);
  EXPECT_NEAR(inside / n, Phi((std::log(2000.0) - mu) / std::sqrt(sig2)) - Phi((std::log(1600.0) - mu) / std::sqrt(sig2)),
              4.5 * std::sqrt(0.1 * 0.9 / n));
}

TEST(SamplerDistributions, MbarTruncatedLognormalMomentsAndCdf) {
  StructureSampler s(StructureModel{}, kSeed);
  auto pairs = draw(s, 5, 0);
  std::vector<double> mb;
  for (const auto& p : pairs) mb.push_back(p.s2.mbar);
  const double sig = std::sqrt(std::log(1 + 0.2 * 0.2)), mu = std::log(0.6) - sig * sig / 2;
  const double za = (std::log(0.4) - mu) / sig, zb = (std::log(0.8) - mu) / sig, Z = Phi(zb) - Phi(za);
  // Truncated lognormal: E[X^k | a <= X <= b] = exp(k mu + k^2 sigma^2/2) (Phi(zb - k sigma) - Phi(za - k sigma)) / Z
  double e[5];
  for (int k = 0; k <= 4; ++k)
    e[k] = std::exp(k * mu + k * k * sig * sig / 2) * (Phi(zb - k * sig) - Phi(za - k * sig)) / Z;
  EXPECT_NEAR(e[0], 1.0, 1e-15);
  Moments th = from_raw(e);
  const double n = kDraws, m = mean(mb), v = variance(mb);
  const double se_mean = std::sqrt(th.var / n), se_var = std::sqrt((th.m4 - th.var * th.var) / n);
  std::printf("mbar: mean %.5f (closed form %.5f, se %.5f), sd %.5f (closed form %.5f); parent mean 0.6 sd 0.12\n", m,
              th.mean, se_mean, std::sqrt(v), std::sqrt(th.var));
  EXPECT_NEAR(m, th.mean, 4.5 * se_mean);
  EXPECT_NEAR(v, th.var, 4.5 * se_var);
  // The truncation must be visible: the parent's variance 0.12^2 is well outside the band.
  EXPECT_GT(std::abs(v - 0.0144), 20 * se_var);
  EXPECT_GE(*std::min_element(mb.begin(), mb.end()), 0.4);
  EXPECT_LE(*std::max_element(mb.begin(), mb.end()), 0.8);
  double d = ks_statistic(mb, [&](double x) { return (Phi((std::log(x) - mu) / sig) - Phi(za)) / Z; });
  std::printf("mbar: KS D = %.5f against the truncated CDF, p = %.3f\n", d, ks_pvalue(d, mb.size()));
  EXPECT_GT(ks_pvalue(d, mb.size()), 1e-3);
}

TEST(SamplerDistributions, MbarTruncationInTheUpperTail) {
  // Both bounds far in the upper tail (za > 0): the sampler's upper-tail branch.
  StructureModel model;
  model.mbar_mean = 0.3;
  model.mbar_cov = 0.2;
  model.mbar_min = 0.45;
  model.mbar_max = 0.6;
  StructureSampler s(model, kSeed);
  auto pairs = draw(s, 0, 0, 20000);
  std::vector<double> mb;
  for (const auto& p : pairs) mb.push_back(p.s1.mbar);
  const double sig = std::sqrt(std::log(1.04)), mu = std::log(0.3) - sig * sig / 2;
  const double za = (std::log(0.45) - mu) / sig, zb = (std::log(0.6) - mu) / sig;
  ASSERT_GT(za, 0);
  auto Q = [](double x) { return 0.5 * std::erfc(x / std::numbers::sqrt2); };
  double d = ks_statistic(mb, [&](double x) { return (Q(za) - Q((std::log(x) - mu) / sig)) / (Q(za) - Q(zb)); });
  std::printf("mbar (upper-tail truncation, P = %.3g): KS D = %.5f, p = %.3f\n", Q(za) - Q(zb), d,
              ks_pvalue(d, mb.size()));
  EXPECT_GT(ks_pvalue(d, mb.size()), 1e-3);
  EXPECT_GE(*std::min_element(mb.begin(), mb.end()), 0.45);
  EXPECT_LE(*std::max_element(mb.begin(), mb.end()), 0.6);
}

TEST(SamplerDistributions, HeightUniformOnItsIntervalKS) {
  StructureModel model;
  StructureSampler s(model, kSeed);
  for (std::int32_t i : {0, 5, 10}) {
    auto pairs = draw(s, i, 10 - i);
    std::vector<double> h;
    for (const auto& p : pairs) h.push_back(p.s1.h);
    HeightInterval iv = height_interval(model, model.periods[static_cast<std::size_t>(i)]);
    double d = ks_statistic(h, [&](double x) { return (x - iv.lo) / (iv.hi - iv.lo); });
    std::printf("h at T = %.2f s on [%.4f, %.4f] m: KS D = %.5f (1%% critical %.5f), p = %.3f\n",
                model.periods[static_cast<std::size_t>(i)], iv.lo, iv.hi, d, 1.6276 / std::sqrt(double(kDraws)),
                ks_pvalue(d, h.size()));
    EXPECT_GT(ks_pvalue(d, h.size()), 1e-3);
    EXPECT_GE(*std::min_element(h.begin(), h.end()), iv.lo);
    EXPECT_LE(*std::max_element(h.begin(), h.end()), iv.hi);
  }
}

TEST(SamplerDistributions, AspectRatiosEqualInFrequency) {
  StructureSampler s(StructureModel{}, kSeed);
  auto pairs = draw(s, 2, 9);
  double count[3] = {0, 0, 0};
  for (const auto& p : pairs) {
    int j = static_cast<int>(p.s1.aspect) - 1;
    ASSERT_TRUE(j >= 0 && j < 3 && p.s1.aspect == j + 1.0) << p.s1.aspect;
    count[j] += 1;
    EXPECT_EQ(p.s1.r, p.s1.h / p.s1.aspect);
  }
  double expect = kDraws / 3.0, chi2 = 0;
  for (double c : count) chi2 += (c - expect) * (c - expect) / expect;
  double crit = quantile(boost::math::chi_squared(2), 0.999);
  std::printf("aspect 1/2/3: %.0f %.0f %.0f, chi2 = %.3f (0.1%% critical %.2f)\n", count[0], count[1], count[2], chi2,
              crit);
  EXPECT_LT(chi2, crit);
}

// ------------------------------------------------------------------------------------- exact identities

TEST(SamplerIdentities, EveryDerivedQuantityFollowsItsEquation) {
  StructureModel model;
  StructureSampler s(model, kSeed);
  const double pi = std::numbers::pi;
  for (std::int32_t i1 = 0; i1 < 11; ++i1)
    for (std::int32_t i2 = 0; i2 < 11; ++i2)
      for (const auto& p : draw(s, i1, i2, 64)) {
        for (const SampledStructure* st : {&p.s1, &p.s2}) {
          const double T = st->T;
          EXPECT_EQ(st->k, 4.0 * pi * pi * st->m / (T * T));                   // eq. (8), bit for bit
          EXPECT_NEAR(2 * pi * std::sqrt(st->m / st->k), T, 4e-16 * T);          // and back to T
          EXPECT_EQ(st->c, 2.0 * 0.05 * std::sqrt(st->k * st->m));              // eq. (9)
          EXPECT_EQ(st->m, st->mbar * st->rho * st->r * st->r * st->h);          // eq. (7)
          EXPECT_EQ(st->r, st->h / st->aspect);
          EXPECT_NEAR(st->fy / st->k, 0.02 * st->h / 6.0, 1e-15 * st->h);       // ductility 6 at 2 % drift
          EXPECT_EQ(st->alpha, 0.05);
          EXPECT_GE(st->h, 30.0);
          EXPECT_LE(st->h, 50.0);
          EXPECT_LE(0.05 * std::pow(st->h, 0.75), T * (1 + 1e-14));              // eq. (6)
          EXPECT_GE(0.08 * std::pow(st->h, 0.75), T * (1 - 1e-14));
        }
        EXPECT_EQ(p.s1.T, model.periods[static_cast<std::size_t>(i1)]);
        EXPECT_EQ(p.s2.T, model.periods[static_cast<std::size_t>(i2)]);
        EXPECT_EQ(p.d, 0.005 * (p.s1.h + p.s2.h));  // eq. (5)
        // Muthukumar eqs 11-13, written out here: R = (3 m / (4 pi rho))^(1/3), hm = (1 - nu^2) / E.
        const double R1 = std::cbrt(3 * p.s1.m / (4 * pi * 2400.0)), R2 = std::cbrt(3 * p.s2.m / (4 * pi * 2400.0));
        const double hm = (1 - 0.15 * 0.15) / 24.86e9;
        EXPECT_NEAR(p.kh, 4.0 / (3.0 * 2 * hm) * std::sqrt(R1 * R2 / (R1 + R2)), 1e-13 * p.kh);
      }
}

TEST(SamplerIdentities, PairParamsAndOptions) {
  StructureModel model;
  StructureSampler s(model, kSeed);
  SampledPair p = s.sample({4, 6, 17});
  PairParams pp = p.pair_params(0.3, 0.65);
  EXPECT_EQ(pp.gap, 0.3 * p.d);
  EXPECT_EQ(pp.kc, p.kh);
  EXPECT_EQ(pp.e, 0.65);
  EXPECT_EQ(pp.s1.m, p.s1.m);
  EXPECT_EQ(pp.s1.k, p.s1.k);
  EXPECT_EQ(pp.s1.c, p.s1.c);
  EXPECT_EQ(pp.s1.fy, p.s1.fy);
  EXPECT_EQ(pp.s2.alpha, p.s2.alpha);
  EXPECT_EQ(pp.s2.m, p.s2.m);
  EXPECT_EQ(pp.u1, 0.0);
  EXPECT_EQ(pp.v2, 0.0);
  // The kernel's own constructor agrees with the sampled k, c.
  Structure ref = Structure::from_period(p.s2.m, p.s2.T, 0.05);
  EXPECT_EQ(ref.k, p.s2.k);
  EXPECT_EQ(ref.c, p.s2.c);

  model.kh = 5.0e9;
  model.hysteresis = Hysteresis::elastic;
  StructureSampler s2(model, kSeed);
  SampledPair q = s2.sample({4, 6, 17});
  EXPECT_EQ(q.kh, 5.0e9);
  EXPECT_TRUE(std::isinf(q.s1.fy));
  EXPECT_EQ(q.s1.m, p.s1.m);  // the same structures: options do not move the stream
  EXPECT_EQ(q.s2.h, p.s2.h);
}

TEST(SamplerIdentities, GlobalIndexRoundTrip) {
  StructureSampler s(StructureModel{}, kSeed);
  for (std::int64_t g : {0L, 1L, 255L, 256L, 30975L, 12345L}) EXPECT_EQ(s.global_index(s.identity(g)), g);
  EXPECT_EQ(s.global_index({10, 10, 255}), 30975);
  EXPECT_EQ(s.identity(256 * 11 + 3), (SampleId{1, 0, 3}));
  EXPECT_THROW(s.sample({11, 0, 0}), std::out_of_range);
  EXPECT_THROW(s.sample({0, 0, -1}), std::out_of_range);
}

// ------------------------------------------------------------------------------------- reproducibility

TEST(SamplerStreams, PublishedReferenceOutputs) {
  // SplitMix64 (Vigna's splitmix64.c): state 0 -> first output 0xe220a8397b1dcdaf; state 1234567 -> the
  // sequence used by the xoshiro reference tests.
  EXPECT_EQ(splitmix64(0), 0xe220a8397b1dcdafULL);
  const std::uint64_t golden = 0x9e3779b97f4a7c15ULL, seq[] = {6457827717110365317ULL, 3203168211198807973ULL,
                                                               9817491932198370423ULL, 4593380528125082431ULL,
                                                               16408922859458223821ULL};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(splitmix64(1234567 + i * golden), seq[i]) << i;
  // taus88: the 10000th output of a default-constructed engine is 3535848941 (Boost.Random's own validation).
  boost::random::taus88 g;
  g.discard(9999);
  EXPECT_EQ(g(), 3535848941U);
}

namespace {
// L'Ecuyer's taus88 as published (Math. Comp. 65 (1996) 203-213, the C code of its figure 1).
struct Taus88Reference {
  std::uint32_t s1, s2, s3;
  std::uint32_t next() {
    std::uint32_t b = ((s1 << 13) ^ s1) >> 19;
    s1 = ((s1 & 4294967294U) << 12) ^ b;
    b = ((s2 << 2) ^ s2) >> 25;
    s2 = ((s2 & 4294967288U) << 4) ^ b;
    b = ((s3 << 3) ^ s3) >> 11;
    s3 = ((s3 & 4294967280U) << 17) ^ b;
    return s1 ^ s2 ^ s3;
  }
  double uniform() {  // 27 + 26 bits, (j + 1/2) 2^-53, as documented in sampler.cpp
    std::uint32_t a = next() >> 5, b = next() >> 6;
    return (a * 67108864.0 + b + 0.5) / 9007199254740992.0;
  }
};
}  // namespace

TEST(SamplerStreams, WholeChainAgainstReferenceTausworthe) {
  // stream_seed -> seed words (key low, key high, splitmix64(key) high) -> taus88 -> uniforms -> h, aspect, rho,
  // rebuilt here from L'Ecuyer's code and the documented transforms. At T = 1.00 s, h is uniform on [30, 50].
  StructureSampler s(StructureModel{}, kSeed);
  const double sig = std::sqrt(std::log(1 + 0.068 * 0.068)), mu = std::log(1800.0) - sig * sig / 2;
  boost::math::normal nd;  // default (long double) policy: an independent evaluation of the quantile
  for (std::int64_t j = 0; j < 200; ++j) {
    SampleId id{0, 0, j};
    const std::uint64_t key = stream_seed(kSeed, structure_stream, id), key2 = splitmix64(key);
    Taus88Reference ref{static_cast<std::uint32_t>(key), static_cast<std::uint32_t>(key >> 32),
                        static_cast<std::uint32_t>(key2 >> 32)};
    ASSERT_GT(ref.s1 >> 1, 0u);  // L'Ecuyer's seed conditions s1 > 1, s2 > 7, s3 > 15 (top bits nonzero)
    ASSERT_GT(ref.s2 >> 3, 0u);
    ASSERT_GT(ref.s3 >> 4, 0u);
    const double u_h = ref.uniform(), u_a = ref.uniform(), u_rho = ref.uniform();
    SampledPair p = s.sample(id);
    EXPECT_EQ(p.s1.h, 30.0 + (50.0 - 30.0) * u_h) << j;
    EXPECT_EQ(p.s1.aspect, 1.0 + std::floor(3 * u_a)) << j;
    EXPECT_NEAR(p.s1.rho, std::exp(mu + sig * quantile(nd, u_rho)), 1e-13 * 1800) << j;
  }
}

TEST(SamplerStreams, SameSeedSameNumbersAnyOrderOrBatch) {
  StructureModel model;
  StructureSampler a(model, kSeed), b(model, kSeed);
  auto ref = draw(a, 7, 2, 300);
  // batch widths 1, 7, 256 and reverse order, through a second sampler and the free function
  for (std::size_t width : {1u, 7u, 256u}) {
    std::vector<SampledPair> got(300);
    for (std::size_t start = 0; start < 300; start += width) {
      std::size_t w = std::min(width, 300 - start);
      b.sample_block(7, 2, static_cast<std::int64_t>(start), std::span<SampledPair>(got).subspan(start, w));
    }
    ASSERT_EQ(std::memcmp(got.data(), ref.data(), sizeof(SampledPair) * 300), 0) << "width " << width;
  }
  for (int j = 299; j >= 0; j -= 37) {
    SampledPair p = sample_pair(model, kSeed, structure_stream, {7, 2, j});
    EXPECT_EQ(std::memcmp(&p, &ref[static_cast<std::size_t>(j)], sizeof(SampledPair)), 0) << j;
  }
  // samples_per_pair only sets how many: sample 5 is the same whatever it is
  StructureModel small = model;
  small.samples_per_pair = 8;
  SampledPair p = StructureSampler(small, kSeed).sample({7, 2, 5});
  EXPECT_EQ(std::memcmp(&p, &ref[5], sizeof(SampledPair)), 0);
  // a different seed gives different structures
  SampledPair q = StructureSampler(model, kSeed + 1).sample({7, 2, 5});
  EXPECT_NE(q.s1.h, ref[5].s1.h);
  EXPECT_NE(q.s2.m, ref[5].s2.m);
}

TEST(SamplerStreams, ThreadsAndPartitionsGiveTheSameBits) {
  // Three workers take interleaved identities of all 121 pairs (as ranks with dynamic scheduling would);
  // the result equals the serial sweep bit for bit.
  StructureModel model;
  model.samples_per_pair = 16;
  const StructureSampler s(model, kSeed);
  const std::int64_t total = model.model_count();
  std::vector<SampledPair> serial(static_cast<std::size_t>(total)), parallel(serial.size());
  for (std::int64_t g = 0; g < total; ++g) serial[static_cast<std::size_t>(g)] = s.sample(s.identity(g));
  std::vector<std::thread> workers;
  for (int w = 0; w < 3; ++w)
    workers.emplace_back([&, w] {
      for (std::int64_t g = total - 1 - w; g >= 0; g -= 3) parallel[static_cast<std::size_t>(g)] = s.sample(s.identity(g));
    });
  for (auto& t : workers) t.join();
  EXPECT_EQ(std::memcmp(serial.data(), parallel.data(), sizeof(SampledPair) * serial.size()), 0);
}

TEST(SamplerStreams, StoredReferenceNumbers) {
  // Regression: the paper study's first model (seed 20240917, identity (0, 0, 0)), as dumped by
  // `pounding sample studies/paper-structures.toml` when the draw order was fixed. Relative 1e-13 allows
  // for last-bit differences of exp/log between C libraries; the uniforms themselves are exact.
  SampledPair p = StructureSampler(StructureModel{}, kSeed).sample({0, 0, 0});
  EXPECT_NEAR(p.s1.h, 39.761756214264139, 1e-13 * 50);
  EXPECT_NEAR(p.s2.h, 35.074582505280134, 1e-13 * 50);
  EXPECT_EQ(p.s1.aspect, 3.0);
  EXPECT_EQ(p.s2.aspect, 3.0);
  EXPECT_NEAR(p.s1.rho, 1768.806703100458, 1e-13 * 1800);
  EXPECT_NEAR(p.s2.rho, 1886.4532984437119, 1e-13 * 1800);
  EXPECT_NEAR(p.s1.mbar, 0.64827814304484943, 1e-13);
  EXPECT_NEAR(p.s2.mbar, 0.65436489632498496, 1e-13);
  EXPECT_NEAR(p.s1.m, 8009325.0636414755, 1e-12 * 8e6);
  EXPECT_NEAR(p.s2.m, 5918355.8334060488, 1e-12 * 6e6);
}

TEST(SamplerStreams, DifferentIdentitiesAreIndependent) {
  StructureModel model;
  StructureSampler s(model, kSeed), other_stream(model, kSeed, structure_stream + 1), other_seed(model, kSeed + 1);
  const int n = kDraws;
  auto u = [&](const SampledStructure& st, std::size_t pi) {  // the uniform behind h
    HeightInterval iv = s.heights(pi);
    return (st.h - iv.lo) / (iv.hi - iv.lo);
  };
  auto zrho = [&](const SampledStructure& st) { return (std::log(st.rho) - s.rho_mu()) / s.rho_sigma(); };
  auto base = draw(s, 0, 0, n);               // (0, 0, j)
  auto next = draw(s, 0, 0, n, n);            // (0, 0, n + j): different sample index
  auto swapped = draw(s, 1, 0, n);            // (1, 0, j) against (0, 1, j)
  auto straight = draw(s, 0, 1, n);
  auto stream2 = draw(other_stream, 0, 0, n);  // same identity, stream 2
  auto seed2 = draw(other_seed, 0, 0, n);      // same identity, seed + 1
  std::vector<double> x, y_next, y_stream, y_seed, y_s2, r1, r2, sw1, sw2, lag1, lag0;
  for (int j = 0; j < n; ++j) {
    x.push_back(u(base[j].s1, 0));
    y_next.push_back(u(next[j].s1, 0));
    y_stream.push_back(u(stream2[j].s1, 0));
    y_seed.push_back(u(seed2[j].s1, 0));
    y_s2.push_back(u(base[j].s2, 0));  // structure 2 of the same sample
    r1.push_back(zrho(base[j].s1));
    r2.push_back(zrho(base[j].s2));
    sw1.push_back(u(straight[j].s1, 0));
    sw2.push_back(u(swapped[j].s2, 0));  // structure 2 of (1, 0, j) has period index 0, like structure 1 of (0, 1, j)
    if (j > 0) {
      lag0.push_back(x[j - 1]);
      lag1.push_back(x[j]);  // neighbouring sample indices
    }
  }
  const double bound = 4.5 / std::sqrt(double(n));
  struct Case {
    const char* name;
    double r;
  } cases[] = {{"sample j vs n + j", correlation(x, y_next)},     {"sample j vs j + 1", correlation(lag0, lag1)},
               {"stream 1 vs 2", correlation(x, y_stream)},       {"seed vs seed + 1", correlation(x, y_seed)},
               {"h1 vs h2 in a pair", correlation(x, y_s2)},      {"rho1 vs rho2 in a pair", correlation(r1, r2)},
               {"(0,1,j).h1 vs (1,0,j).h2", correlation(sw1, sw2)}};
  for (const auto& c : cases) {
    std::printf("correlation %-26s %+.5f (bound %.5f)\n", c.name, c.r, bound);
    EXPECT_LT(std::abs(c.r), bound) << c.name;
  }
  // Beyond linear correlation: chi-square of the 10 x 10 joint histogram of neighbouring samples' uniforms.
  std::vector<double> cells(100, 0.0);
  for (std::size_t j = 0; j < lag0.size(); ++j)
    cells[std::min<std::size_t>(9, std::size_t(lag0[j] * 10)) * 10 + std::min<std::size_t>(9, std::size_t(lag1[j] * 10))] += 1;
  double chi2 = 0, e = lag0.size() / 100.0;
  for (double c : cells) chi2 += (c - e) * (c - e) / e;
  double crit = quantile(boost::math::chi_squared(99), 0.999);
  std::printf("joint histogram of neighbours: chi2 = %.2f (99 dof, 0.1%% critical %.2f)\n", chi2, crit);
  EXPECT_LT(chi2, crit);
}

// ------------------------------------------------------------------------------------- study file

namespace {
InputError parse_error_of(const std::string& text) {
  auto t = toml::parse(text, std::string_view("study.toml"));
  const toml::table* st = t["structures"].as_table();
  toml::table empty;
  try {
    parse_structure_model(st ? *st : empty, "study.toml");
    parse_study_seed(t, "study.toml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError("", "", "");
}
}  // namespace

TEST(SamplerStudyFile, PaperFileGivesTheDefaults) {
  const std::string path = std::string(POUNDING_SOURCE_DIR) + "/studies/paper-structures.toml";
  auto root = toml::parse_file(path);
  StructureModel m = parse_structure_model(*root["structures"].as_table(), path);
  StructureModel d;
  EXPECT_EQ(m.periods, d.periods);
  EXPECT_EQ(m.samples_per_pair, d.samples_per_pair);
  EXPECT_EQ(m.aspect_ratios, d.aspect_ratios);
  EXPECT_EQ(m.rho_mean, d.rho_mean);
  EXPECT_EQ(m.mbar_cov, d.mbar_cov);
  EXPECT_EQ(m.contact_youngs_modulus, d.contact_youngs_modulus);
  EXPECT_EQ(m.kh, 0.0);
  EXPECT_EQ(parse_study_seed(root, path), kSeed);
  // an empty table is the defaults too
  StructureModel e = parse_structure_model(toml::table{}, "x.toml");
  EXPECT_EQ(e.periods, d.periods);
}

TEST(SamplerStudyFile, ReadsSettings) {
  auto t = toml::parse("seed = 7\n[structures]\nperiods = [1.0, 1.2]\nsamples_per_pair = 10\naspect_ratios = [2]\n"
                       "rho_cov = 0\nhysteresis = \"elastic\"\nkh = 1e9\nzeta = 0.02\n");
  StructureModel m = parse_structure_model(*t["structures"].as_table(), "s.toml");
  EXPECT_EQ(m.periods, (std::vector<double>{1.0, 1.2}));
  EXPECT_EQ(m.samples_per_pair, 10);
  EXPECT_EQ(m.aspect_ratios, (std::vector<double>{2.0}));
  EXPECT_EQ(m.hysteresis, Hysteresis::elastic);
  EXPECT_EQ(m.kh, 1e9);
  EXPECT_EQ(parse_study_seed(t, "s.toml"), 7u);
  SampledPair p = StructureSampler(m, 7).sample({1, 0, 3});
  EXPECT_NEAR(p.s1.rho, 1800.0, 1e-9);  // CoV 0: the mean exactly
  EXPECT_EQ(p.s1.c, 2 * 0.02 * std::sqrt(p.s1.k * p.s1.m));
  auto g = toml::parse("[structures]\nperiod_min = 0.5\nperiod_max = 0.8\nperiod_step = 0.1\nheight_min = 5\n");
  EXPECT_EQ(parse_structure_model(*g["structures"].as_table(), "g.toml").periods,
            (std::vector<double>{0.5, 0.6, 0.7, 0.8}));
}

TEST(SamplerStudyFile, ErrorsNameFileLineKeyAndRange) {
  InputError e = parse_error_of("seed = 1\n[structures]\nzeta = 0.05\nrho_meen = 1800\n");
  EXPECT_NE(e.where().find("study.toml:4"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("rho_meen"), std::string::npos) << e.what();
  EXPECT_NE(e.fix().find("rho_mean"), std::string::npos) << e.what();  // lists the known keys

  e = parse_error_of("seed = 1\n[structures]\n\nmbar_cov = -0.1\n");
  EXPECT_NE(e.where().find("study.toml:4"), std::string::npos) << e.what();
  EXPECT_NE(e.where().find("mbar_cov"), std::string::npos) << e.what();
  EXPECT_NE(e.fix().find("(0, 2]"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nmbar_min = 0.8\nmbar_max = 0.5\n");
  EXPECT_NE(e.where().find("study.toml:3"), std::string::npos) << e.what();
  EXPECT_NE(e.fix().find("mbar_min = 0.8"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nzeta = \"five\"\n");
  EXPECT_NE(std::string(e.what()).find("must be a number"), std::string::npos) << e.what();
  EXPECT_NE(e.where().find("study.toml:2"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nperiods = [1.0]\nperiod_min = 1.0\n");
  EXPECT_NE(std::string(e.what()).find("both periods"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nperiod_step = 0.07\n");
  EXPECT_NE(std::string(e.what()).find("not an integer"), std::string::npos) << e.what();
  EXPECT_NE(e.where().find("study.toml:2"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nsamples_per_pair = 2.5\n");
  EXPECT_NE(std::string(e.what()).find("integer"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nhysteresis = \"plastic\"\n");
  EXPECT_NE(e.fix().find("bilinear"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nperiods = [1.2, 1.1]\n");
  EXPECT_NE(std::string(e.what()).find("increasing"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\ncontact_poisson = 0.5\n");
  EXPECT_NE(e.fix().find("[0, 0.5)"), std::string::npos) << e.what();

  e = parse_error_of("seed = 1\n[structures]\nperiod_min = 1.0\nperiod_max = 1.7\n");  // 1.6, 1.65, 1.7 too tall
  EXPECT_NE(e.where().find("study.toml:4"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("T = 1.55 s"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nseed = 3\n");
  EXPECT_NE(e.fix().find("top of the study file"), std::string::npos) << e.what();

  e = parse_error_of("[structures]\nzeta = 0.05\n");  // no seed
  EXPECT_NE(std::string(e.what()).find("no seed"), std::string::npos) << e.what();

  e = parse_error_of("seed = -3\n");
  EXPECT_NE(e.where().find("study.toml:1"), std::string::npos) << e.what();
}
