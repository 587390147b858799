// Rezaeian & Der Kiureghian (2010) generator: the random numbers against their definitions (the C++
// standard's mt19937_64 check value, Boost's normal quantile), the marginals against their published
// moments, the envelope against the Gamma distribution it is defined by, records against their own
// model parameters, reproducibility, and the median spectrum against a real record of the same site.
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/random/mersenne_twister.hpp>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "pounding/core/error.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/motion/spectrum.hpp"
#include "pounding/motion/synthetic.hpp"
#include "test_data.hpp"

using namespace pounding;

namespace {

const std::string real_dir = testdata::real_records_dir();

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// E[g(nu)] for nu ~ N(mu, 1) by the trapezoid rule on [-10, 10] (error far below the checks).
template <class G>
double normal_expectation(G g, double mu = 0.0) {
  const int n = 4000;  // h = 0.005: the trapezoid rule is spectrally accurate for Gaussian weights
  const double a = -10, b = 10, h = (b - a) / n;
  double s = 0;
  for (int i = 0; i <= n; ++i) {
    const double z = a + i * h;
    const double w = (i == 0 || i == n) ? 0.5 : 1.0;
    s += w * g(mu + z) * std::exp(-0.5 * z * z);
  }
  return s * h / std::sqrt(2 * std::numbers::pi);
}

}  // namespace

TEST(SyntheticRandom, EngineIsTheStandardMt19937_64) {
  // C++ standard [rand.predef]: the 10000th output of a default-constructed mt19937_64.
  boost::random::mt19937_64 e;
  std::uint64_t x = 0;
  for (int i = 0; i < 10000; ++i) x = e();
  EXPECT_EQ(x, 9981545732273789042ULL);
}

TEST(SyntheticRandom, As241MatchesBoostNormalQuantile) {
  boost::math::normal_distribution<double> nd;
  for (double p : {1e-300, 1e-100, 1e-20, 1e-10, 1e-5, 0.001, 0.02425, 0.07, 0.075, 0.2, 0.4999, 0.5, 0.5001, 0.8,
                   0.925, 0.97575, 0.999, 1 - 1e-10}) {
    const double ref = boost::math::quantile(nd, p);
    EXPECT_NEAR(standard_normal_quantile(p), ref, 1e-14 * std::max(1.0, std::abs(ref))) << p;
  }
  EXPECT_EQ(standard_normal_quantile(0.5), 0.0);
}

TEST(SyntheticModel, MarginalsHaveThePublishedMoments) {
  // Mean and sd of theta = F^-1(Phi(nu)), nu ~ N(0, 1), must be the moments the marginals were given by
  // (R&DK 2010 Table 3 / issue 3): this checks Phi, the beta/gamma parameterisation and the quantiles.
  auto moments = [](auto theta) {
    const double m = normal_expectation([&](double nu) { return theta(nu); });
    const double m2 = normal_expectation([&](double nu) { return theta(nu) * theta(nu); });
    return std::pair{m, std::sqrt(m2 - m * m)};
  };
  auto th = [](int i) {
    return [i](double nu) {
      Normal6 v{0, 0, 0, 0, 0, 0};
      v[i] = nu;
      const ModelParams p = params_from_normal(v);
      const double out[6] = {p.arias_sg, p.d5_95, p.t_mid, p.f_mid_hz, p.f_slope_hz_s, p.zeta_f};
      return out[i];
    };
  };
  // lognormal Ia: mean exp(lambda + zeta^2/2)
  auto [ia_m, ia_s] = moments(th(0));
  const double lam = -4.354999117683, zet = 1.60818347313;
  EXPECT_NEAR(ia_m / std::exp(lam + zet * zet / 2), 1.0, 1e-4);
  EXPECT_NEAR(ia_s / (std::exp(lam + zet * zet / 2) * std::sqrt(std::exp(zet * zet) - 1)), 1.0, 1e-3);
  auto [d_m, d_s] = moments(th(1));
  EXPECT_NEAR(d_m, 17.3, 1e-3);
  EXPECT_NEAR(d_s, 9.31, 1e-3);
  auto [t_m, t_s] = moments(th(2));
  EXPECT_NEAR(t_m, 12.4, 1e-3);
  EXPECT_NEAR(t_s, 7.44, 1e-3);
  auto [f_m, f_s] = moments(th(3));
  EXPECT_NEAR(f_m, 5.87, 1e-3);
  EXPECT_NEAR(f_s, 3.11, 1e-3);
  auto [z_m, z_s] = moments(th(5));
  EXPECT_NEAR(z_m, 0.213, 1e-4);
  EXPECT_NEAR(z_s, 0.143, 1e-4);
  // the beta/gamma supports
  Normal6 lo{-9, -9, -9, -9, -9, -9}, hi{9, 9, 9, 9, 9, 9};
  EXPECT_GE(params_from_normal(lo).d5_95, 5.0);
  EXPECT_LE(params_from_normal(hi).d5_95, 45.0);
  EXPECT_GE(params_from_normal(lo).zeta_f, 0.02);
  EXPECT_LE(params_from_normal(hi).zeta_f, 1.0);
}

TEST(SyntheticModel, TwoSidedExponentialQuantileInvertsItsDensity) {
  // density c e^(b x) on [-2, 0), c e^(-a x) on [0, 0.5]; integrate it numerically up to x(F) and get F back.
  const double a = 17.1, b = 6.77, c = 4.85;
  for (double F : {0.001, 0.1, 0.3, 0.5, 0.7, 0.7164, 0.75, 0.9, 0.99, 0.9999}) {
    const double x = two_sided_exponential_quantile(F, a, b, c, -2.0, 0.5);
    const int n = 200000;
    double s = 0, h = (x + 2.0) / n;
    for (int i = 0; i < n; ++i) {
      const double t = -2.0 + (i + 0.5) * h;
      s += (t < 0 ? c * std::exp(b * t) : c * std::exp(-a * t)) * h;
    }
    EXPECT_NEAR(s, F, 2e-6) << "F = " << F << " x = " << x;
    EXPECT_GE(x, -2.0);
    EXPECT_LE(x, 0.5);
  }
}

TEST(SyntheticModel, PredictiveMeansAtTheReferenceSite) {
  // At M = 7, R = 25 km, V = 750 m/s the regressors are M/7 = 1, ln(R/25) = ln(V/750) = 0 (Ia) and
  // R/25 = V/750 = 1 (the rest): mu = b1 + b2 F + b3 [+ b4 + b5]; numbers from the table.
  Normal6 mu = predictive_mean({7.0, 25.0, 750.0, 0});
  EXPECT_NEAR(mu[0], -1.844 + 2.944, 1e-12);
  EXPECT_NEAR(mu[1], -6.195 + 6.792 + 0.219 - 0.523, 1e-12);
  EXPECT_NEAR(mu[2], -5.011 + 4.638 + 0.348 - 0.185, 1e-12);
  EXPECT_NEAR(mu[3], 2.253 - 1.810 - 0.211 + 0.012, 1e-12);
  EXPECT_NEAR(mu[4], -2.489 + 2.408 + 0.065 - 0.081, 1e-12);
  EXPECT_NEAR(mu[5], -0.258 + 0.905 - 0.289 + 0.316, 1e-12);
  Normal6 mr = predictive_mean({7.0, 25.0, 750.0, 1});
  EXPECT_NEAR(mr[0] - mu[0], -0.071, 1e-12);
  EXPECT_NEAR(mr[5] - mu[5], -0.477, 1e-12);
  // Ia: ln(R/25) and ln(V/750) terms
  Normal6 m2 = predictive_mean({7.0, 25.0 * std::exp(1.0), 750.0 * std::exp(1.0), 0});
  EXPECT_NEAR(m2[0] - mu[0], -1.356 - 0.265, 1e-12);
  // the median Ia at that site: exp(lambda + zeta mu_1)
  EXPECT_NEAR(median_params({7.0, 25.0, 750.0, 0}).arias_sg, std::exp(-4.354999117683 + 1.60818347313 * 1.1), 1e-12);
}

TEST(SyntheticModel, CorrelatedErrorsHaveThePublishedCovariance) {
  const double sd[6] = {0.65, 0.73, 0.66, 1.00, 0.96, 1.02};
  const double rho[6][6] = {{1, -0.3555, 0.0066, -0.1545, 0.1341, -0.0078}, {-0.3555, 1, 0.6729, -0.1303, -0.1576, -0.1958},
                            {0.0066, 0.6729, 1, -0.2761, -0.1977, -0.2188}, {-0.1545, -0.1303, -0.2761, 1, -0.2034, 0.2814},
                            {0.1341, -0.1576, -0.1977, -0.2034, 1, -0.0137}, {-0.0078, -0.1958, -0.2188, 0.2814, -0.0137, 1}};
  // L L^T is the covariance exactly: take z = unit vectors, eps = L e_k are the columns of L.
  double LLt[6][6] = {};
  std::vector<Normal6> cols;
  for (int k = 0; k < 6; ++k) {
    Normal6 e{0, 0, 0, 0, 0, 0};
    e[k] = 1;
    cols.push_back(correlated_errors(e));
  }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) LLt[i][j] += cols[k][i] * cols[k][j];
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(LLt[i][j], sd[i] * sd[j] * rho[i][j], 1e-12) << i << "," << j;
}

TEST(SyntheticModel, EnvelopeReproducesIaDurationAndTmidExactly) {
  for (auto [ia, d, tm] : {std::tuple{0.0128, 17.3, 12.4}, {0.2, 8.0, 6.0}, {0.02, 30.0, 10.0}, {0.5, 5.0, 20.0}}) {
    const Envelope env = solve_envelope(ia, d, tm);
    boost::math::gamma_distribution<double> G(env.shape(), 1.0 / env.rate());
    EXPECT_NEAR(boost::math::cdf(G, tm), 0.45, 1e-10);
    EXPECT_NEAR(boost::math::quantile(G, 0.95) - boost::math::quantile(G, 0.05), d, 1e-9 * d);
    // Ia = pi/(2 g) int q^2 dt, in s*g: divide by g. Midpoint rule on a fine grid (q^2 is smooth).
    const double T = boost::math::quantile(G, 1 - 1e-12), h = T / 400000;
    double s = 0;
    for (int i = 0; i < 400000; ++i) {
      const double q = env((i + 0.5) * h);
      s += q * q * h;
    }
    EXPECT_NEAR(std::numbers::pi / (2 * g_accel) * s / g_accel / ia, 1.0, 1e-4) << "k = " << env.shape();
  }
  EXPECT_THROW(solve_envelope(-1, 10, 5), InputError);
}

TEST(SyntheticRecords, ReproduceTheirOwnIaDurationAndTmid) {
  // E[x(t)^2] = q(t)^2 by construction, so over many seeds the realised Ia, D5-95 and t_mid scatter
  // around the model's values. Each check: |sample mean - model| <= 4 standard errors of the sample
  // mean (a false alarm 1 time in 16000) + a stated systematic allowance:
  //  - Ia without high-pass: 1 % (the integral of the linear-between-samples signal is below
  //    sum a^2 dt by ~(1 - rho_1)/3 < 1 %);
  //  - Ia with the 0.1 Hz high-pass: 5 %, because R&DK's filter h has unit gain at zero frequency and
  //    the high-pass removes that low-frequency part (measured: 2.3 % of Ia for these parameters);
  //  - D5-95 and t_mid: 2 % (D5-95 of one realisation is a nonlinear functional of a noisy Husid
  //    curve; over 400 seeds its mean sits 1.1 % below the model's, t_mid's 0.4 % above).
  const ModelParams p{0.05, 12.0, 9.0, 4.0, -0.15, 0.3};
  auto stats = [](const std::vector<double>& v) {
    double m = 0, var = 0;
    for (double x : v) m += x / v.size();
    for (double x : v) var += (x - m) * (x - m) / (v.size() - 1);
    return std::pair{m, std::sqrt(var / v.size())};
  };
  for (double hp : {0.0, 0.1}) {
    SynthOptions o;
    o.highpass_hz = hp;
    o.dt = 0.005;
    std::vector<double> ia, d, tm;
    for (std::uint64_t seed = 1; seed <= 60; ++seed) {
      const Measures m = measure(simulate(p, seed, o));
      ia.push_back(m.arias_sg()), d.push_back(m.d5_95()), tm.push_back(m.t45);
    }
    const auto [ia_m, ia_se] = stats(ia);
    const auto [d_m, d_se] = stats(d);
    const auto [t_m, t_se] = stats(tm);
    std::printf("high-pass %.1f Hz, 60 records: Ia %.5f +- %.5f (model %.5f, %+.2f %%); D5-95 %.3f +- %.3f (12, %+.2f %%);"
                " t_mid %.3f +- %.3f (9, %+.2f %%)\n",
                hp, ia_m, ia_se, p.arias_sg, 100 * (ia_m / p.arias_sg - 1), d_m, d_se, 100 * (d_m / 12 - 1), t_m, t_se,
                100 * (t_m / 9 - 1));
    EXPECT_NEAR(ia_m, p.arias_sg, 4 * ia_se + (hp > 0 ? 0.05 : 0.01) * p.arias_sg);
    EXPECT_NEAR(d_m, p.d5_95, 4 * d_se + 0.02 * p.d5_95);
    EXPECT_NEAR(t_m, p.t_mid, 4 * t_se + 0.02 * p.t_mid);
  }
}

TEST(SyntheticRecords, SameSeedSameBitsDifferentSeedDifferentRecord) {
  const SiteParams s{6.9, 15.2, 288.62, 1};
  const Record a = synthesize(s, 42), b = synthesize(s, 42), c = synthesize(s, 43);
  ASSERT_EQ(a.acc.size(), b.acc.size());
  EXPECT_EQ(0, std::memcmp(a.acc.data(), b.acc.data(), a.acc.size() * sizeof(double)));
  EXPECT_NE(a.acc, c.acc);
  EXPECT_TRUE(a.synthetic());
  // with the PGA option the record is scaled exactly
  SynthOptions o;
  o.pga_g = 0.51;
  EXPECT_NEAR(synthesize(s, 42, o).pga() / g_accel, 0.51, 1e-12);
}

TEST(SyntheticRecords, GoldenValuesGuardAgainstSilentChanges) {
  // Stored from this implementation (commit that introduced it). A change here changes every
  // study's synthetic inputs: update deliberately, never to make the test pass.
  const Record r = synthesize({6.9, 15.2, 288.62, 1}, 7);
  const ModelParams p = sample_params({6.9, 15.2, 288.62, 1}, 7);
  EXPECT_EQ(r.acc.size(), 5374u);
  EXPECT_NEAR(p.arias_sg, 0.57337433138631044, 1e-13);
  EXPECT_NEAR(p.d5_95, 23.584609822307829, 1e-11);
  EXPECT_NEAR(p.t_mid, 8.1992683019261996, 1e-11);
  EXPECT_NEAR(p.f_mid_hz, 9.827613195127018, 1e-11);
  EXPECT_NEAR(p.f_slope_hz_s, -0.27915278379801939, 1e-13);
  EXPECT_NEAR(p.zeta_f, 0.05006797868571302, 1e-13);
  EXPECT_NEAR(r.acc[100], 1.1254588319310637, 1e-9);
  EXPECT_NEAR(r.acc[r.acc.size() / 2], -0.51572438358508121, 1e-9);
  EXPECT_NEAR(r.pga(), 4.6094590001161908, 1e-9);
}

TEST(SyntheticRecords, MedianSpectrumNearTheRealRecordOfTheSameSite) {
  POUNDING_REQUIRE_REAL_RECORDS();
  const std::vector<double> T{0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0};
  struct Case {
    const char* file;
    SiteParams site;
  };
  const Case cases[] = {{"LomaPrieta_1989_Capitola_000.txt", {6.9, 15.2, 288.62, 1}},
                        {"SuperstitionHills_1987_PoeRoadTemp_270.txt", {6.5, 11.1, 316.64, 0}},
                        {"Landers_1992_Coolwater_TR.txt", {7.3, 19.7, 352.98, 0}},
                        {"Kocaeli_1999_Duzce_270.txt", {7.5, 15.3, 281.86, 0}}};
  for (const Case& c : cases) {
    const Record real = read_record(real_dir + "/" + c.file);
    const Spectrum sr = response_spectrum(real, T, 0.05);
    std::vector<std::vector<double>> sims(T.size());
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
      const Spectrum s = response_spectrum(synthesize(c.site, 1000 + seed), T, 0.05);
      for (std::size_t i = 0; i < T.size(); ++i) sims[i].push_back(s.psa[i]);
    }
    double log_sum = 0, worst = 0;
    std::printf("%s:", c.file);
    for (std::size_t i = 0; i < T.size(); ++i) {
      const double r = median(sims[i]) / sr.psa[i];
      std::printf(" T=%.2f:%.2f", T[i], r);
      log_sum += std::log(r);
      worst = std::max(worst, std::abs(std::log(r)));
    }
    const double gm = std::exp(log_sum / T.size());
    std::printf("\n  geometric-mean ratio %.3f, worst factor %.2f\n", gm, std::exp(worst));
    // One recording sits off the median of its site by the GMPE's total sigma, sigma_lnSa ~ 0.6-0.7
    // (NGA-West2); a factor 4 at any period is ~2 sigma, and the mean of ln ratio over 9 correlated
    // periods (factor 1.6) ~0.7 sigma. Measured: worst factor 3.05 (Capitola, T = 1.5 s), geometric
    // means 0.69-1.31.
    EXPECT_LT(std::exp(worst), 4.0);
    EXPECT_GT(gm, 1 / 1.6);
    EXPECT_LT(gm, 1.6);
  }
}
