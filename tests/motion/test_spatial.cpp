// Spatially varying support motions (motion/spatial.hpp, issue 26 section 2): the coherency models and the
// Cholesky factor against the test vectors of ../shared/research/systems-and-bridges.md (T6.1-T6.3, T6.5), the
// NZS 1170.5 shape factor against table 3.1, and the generated motions: wave-passage delay in the lagged
// cross-correlation, estimated coherency against the model, mean response spectrum against the target,
// reproducibility, baseline, stop.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "pounding/core/error.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/spatial.hpp"
#include "pounding/motion/spectrum.hpp"

namespace pounding {
namespace {

using spatial::Coherency;
using spatial::CoherencyModel;
constexpr double two_pi = 2.0 * std::numbers::pi;

TEST(SpatialCoherency, MatchesPublishedFormsAtTheResearchVectors) {
  const double xi[3] = {50, 100, 200};
  // T6.1 Harichandran-Vanmarcke Event 20 (the exponent multiplies xi by 1 - A + alpha A)
  const double hv1[3] = {0.9511976853, 0.9053309855, 0.8216824639}, hv5[3] = {0.7387374711, 0.5605478905, 0.3525109158};
  Coherency hv;
  hv.model = CoherencyModel::harichandran_vanmarcke;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(spatial::lagged_coherency(hv, two_pi * 1, xi[i], 500), hv1[i], 1e-9);
    EXPECT_NEAR(spatial::lagged_coherency(hv, two_pi * 5, xi[i], 500), hv5[i], 1e-9);
  }
  // T6.2 Luco-Wong, alpha/v_s = 2.5e-4 s/m
  const double lw1[3] = {0.9938504834, 0.9756279042, 0.9060180558}, lw5[3] = {0.8570898111, 0.5396414858, 0.0848049725};
  Coherency lw;
  lw.model = CoherencyModel::luco_wong;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(spatial::lagged_coherency(lw, two_pi * 1, xi[i], 500), lw1[i], 1e-9);
    EXPECT_NEAR(spatial::lagged_coherency(lw, two_pi * 5, xi[i], 500), lw5[i], 1e-9);
  }
  // T6.3 Sobczyk, v_app = 500 m/s, the three loss levels
  const double sb[3][2][3] = {{{0.9844147634, 0.9391013674, 0.7777676792}, {0.9244652504, 0.7304026910, 0.2846095433}},
                              {{0.9690724263, 0.8819113783, 0.6049225628}, {0.8546359992, 0.5334880911, 0.0810025922}},
                              {{0.9391013674, 0.7777676792, 0.3659313069}, {0.7304026910, 0.2846095433, 0.0065614199}}};
  const spatial::CoherencyLoss levels[3] = {spatial::CoherencyLoss::low, spatial::CoherencyLoss::medium,
                                            spatial::CoherencyLoss::high};
  for (int b = 0; b < 3; ++b) {
    Coherency s;
    s.beta = spatial::sobczyk_beta(levels[b]);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(spatial::lagged_coherency(s, two_pi * 1, xi[i], 500), sb[b][0][i], 1e-9);
      EXPECT_NEAR(spatial::lagged_coherency(s, two_pi * 5, xi[i], 500), sb[b][1][i], 1e-9);
    }
  }
}

TEST(SpatialCoherency, CholeskyOfTheCoherencyMatrixMatchesT65) {
  // T6.5: f = 2 Hz, x = 0, 100, 200 m, unit PSD, gamma_jk = rho_HV20 exp(-i w (x_j - x_k)/500)
  Coherency hv;
  hv.model = CoherencyModel::harichandran_vanmarcke;
  const double x[3] = {0, 100, 200}, w = two_pi * 2;
  std::vector<std::complex<double>> a(9);
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) a[j * 3 + k] = j == k ? 1.0 : spatial::coherency(hv, w, x[j], x[k], 500, true);
  const auto L = spatial::cholesky(a, 3);
  const double mag[3][3] = {{1, 0, 0}, {0.8301269703, 0.5575744014, 0}, {0.6955860844, 0.4532170072, 0.5574534453}};
  const double arg[3][3] = {{0, 0, 0}, {-2.5132741229, 0, 0}, {1.2566370614, -2.5132741229, 0}};
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k <= j; ++k) {
      EXPECT_NEAR(std::abs(L[j * 3 + k]), mag[j][k], 1e-9) << j << k;
      if (mag[j][k] > 0) {
        EXPECT_NEAR(std::arg(L[j * 3 + k]), arg[j][k], 1e-9) << j << k;
      }
    }
  // |gamma| = 1 (wave passage only) is rank one: the second column is zero, no NaN
  Coherency none;
  none.model = CoherencyModel::none;
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) a[j * 3 + k] = j == k ? 1.0 : spatial::coherency(none, w, x[j], x[k], 500, true);
  const auto R = spatial::cholesky(a, 3);
  for (const auto& v : R) EXPECT_TRUE(std::isfinite(v.real()) && std::isfinite(v.imag()));
  EXPECT_EQ(std::abs(R[4]), 0.0);
  EXPECT_NEAR(std::abs(R[3]), 1.0, 1e-12);
}

TEST(SpatialCoherency, HarichandranVanmarckeTakesTheUsersParameters) {
  // T6.1 Event 24 set (A = 0.626, alpha = 0.022, k = 19700 m, f0 = 2.02 Hz, b = 3.47), through the options as a
  // study or the command line gives them; the defaults stay Event 20.
  spatial::Request q;
  q.coherency = "harichandran-vanmarcke", q.soil = {"D"};
  q.hv_a = 0.626, q.hv_alpha = 0.022, q.hv_k = 19700, q.hv_f0 = 2.02, q.hv_b = 3.47;
  q.given = {"coherency", "soil", "hv_a", "hv_alpha", "hv_k", "hv_f0", "hv_b"};
  const spatial::Settings s = spatial::settings_from(q);
  const double xi[3] = {50, 100, 200};
  const double ev24_1[3] = {0.9434744706, 0.8919170227, 0.8019762650};
  const double ev24_5[3] = {0.7734308714, 0.6263098936, 0.4673460234};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(spatial::lagged_coherency(s.coherency, two_pi * 1, xi[i], 500), ev24_1[i], 1e-9);
    EXPECT_NEAR(spatial::lagged_coherency(s.coherency, two_pi * 5, xi[i], 500), ev24_5[i], 1e-9);
  }
  EXPECT_NE(s.coherency.describe().find("k = 19700 m"), std::string::npos) << s.coherency.describe();
  spatial::Request d;
  d.coherency = "harichandran-vanmarcke", d.soil = {"D"}, d.given = {"coherency", "soil"};
  EXPECT_NEAR(spatial::lagged_coherency(spatial::settings_from(d).coherency, two_pi * 5, 200, 500), 0.3525109158, 1e-9);
}

// The message of a refused request, or "" when it is accepted.
std::string refusal(const spatial::Request& q) {
  try {
    spatial::settings_from(q);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SpatialCoherency, HarichandranVanmarckeAndSiteParametersAreRangeChecked) {
  const auto hv = [](const char* key, double v) {
    spatial::Request q;
    q.coherency = "harichandran-vanmarcke", q.soil = {"D"}, q.given = {"coherency", "soil", key};
    double* x = std::string(key) == "hv_a" ? &q.hv_a : std::string(key) == "hv_alpha" ? &q.hv_alpha
              : std::string(key) == "hv_k" ? &q.hv_k : std::string(key) == "hv_f0" ? &q.hv_f0 : &q.hv_b;
    *x = v;
    return refusal(q);
  };
  EXPECT_NE(hv("hv_a", 1.5).find("--hv-a"), std::string::npos) << hv("hv_a", 1.5);
  EXPECT_NE(hv("hv_a", 1.5).find("[0.001, 1]"), std::string::npos) << hv("hv_a", 1.5);
  EXPECT_NE(hv("hv_alpha", 0).find("--hv-alpha"), std::string::npos);
  EXPECT_NE(hv("hv_k", -5).find("--hv-k"), std::string::npos);
  EXPECT_NE(hv("hv_k", -5).find("m"), std::string::npos);
  EXPECT_NE(hv("hv_f0", 0).find("--hv-f0"), std::string::npos);
  EXPECT_NE(hv("hv_b", std::nan("")).find("--hv-b"), std::string::npos);
  EXPECT_EQ(hv("hv_a", 1.0), "");
  EXPECT_EQ(hv("hv_b", 3.47), "");
  // an HV parameter with another model is refused, not ignored
  spatial::Request q;
  q.loss = "high", q.soil = {"D"}, q.given = {"loss", "soil", "hv_k"};
  EXPECT_NE(refusal(q).find("--hv-k applies to coherency harichandran-vanmarcke only"), std::string::npos) << refusal(q);
  // site response: both lists, one value or one per support, in range
  spatial::Request site;
  site.loss = "high", site.soil = {"D"}, site.supports = 3, site.given = {"loss", "soil", "supports", "site_frequency"};
  site.site_frequency = {2.5, 1.0, 5.0};
  EXPECT_NE(refusal(site).find("--site-damping"), std::string::npos) << refusal(site);
  site.given.insert("site_damping");
  site.site_damping = {0.6, 0.4};
  EXPECT_NE(refusal(site).find("2 values of --site-damping for 3 supports"), std::string::npos) << refusal(site);
  site.site_damping = {0.6};
  EXPECT_EQ(refusal(site), "");
  site.site_frequency = {2.5, 0.0, 5.0};
  EXPECT_NE(refusal(site).find("--site-frequency = 0 is out of range"), std::string::npos) << refusal(site);
  site.site_frequency = {2.5, 1.0, 5.0}, site.site_damping = {0.6, 0.4, 3.0};
  EXPECT_NE(refusal(site).find("--site-damping = 3 is out of range"), std::string::npos) << refusal(site);
  // a study names the key and where it is
  spatial::OptionNames study;
  study.where = [](std::string_view key) { return fmt::format("s.toml:7 [records.motions].{}", key); };
  spatial::Request st;
  st.coherency = "harichandran-vanmarcke", st.soil = {"D"}, st.given = {"coherency", "soil", "hv_f0"}, st.hv_f0 = 500;
  try {
    spatial::settings_from(st, study);
    ADD_FAILURE() << "hv_f0 = 500 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hv_f0 = 500 is out of range"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("s.toml:7 [records.motions].hv_f0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("[0.01, 100] Hz"), std::string::npos) << e.what();
  }
}

TEST(SpatialCoherency, DerKiureghianSiteResponseMatchesT64) {
  // T6.4: Luco-Wong 2.5e-4 s/m, v_app = 500 m/s, xi_L = xi; site k (w_g = 5 pi, zeta_g = 0.6: f_g = 2.5 Hz), site l
  // (w_g = 2 pi, zeta_g = 0.4: 1 Hz). Here support 2 at xi (downstream) has site k, support 1 at 0 has site l, so
  // Gamma_21 = gamma_kl with theta_w = -w xi / v_app.
  const spatial::Site k{2.5, 0.6}, l{1.0, 0.4};
  EXPECT_NEAR(spatial::site_phase(k, l, two_pi * 1), 0.8244292455, 1e-9);
  EXPECT_NEAR(spatial::site_phase(k, l, two_pi * 5), 0.3597798082, 1e-9);
  EXPECT_EQ(spatial::site_phase(k, k, two_pi * 3), 0.0);
  EXPECT_NEAR(spatial::site_phase(l, k, two_pi * 1), -0.8244292455, 1e-9);
  spatial::Settings s;
  s.coherency.model = CoherencyModel::luco_wong;
  s.coherency.lw_a = 2.5e-4;
  s.velocity = 500;
  s.sites = {l, k};
  const std::complex<double> want[2][3] = {
      {{0.9748002034, 0.1936578087}, {0.8859122461, -0.4086677129}, {-0.1067058822, -0.8997124941}},
      {{-0.8022140950, -0.3017540224}, {0.5050905991, 0.1899905785}, {0.0793752806, 0.0298571296}}};
  const double f[2] = {1, 5}, xi[3] = {50, 100, 200};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 3; ++b) {
      s.positions = {0.0, xi[b]};
      const auto g = spatial::coherency_between(s, two_pi * f[a], 1, 0);
      EXPECT_NEAR(g.real(), want[a][b].real(), 1e-9) << f[a] << " Hz " << xi[b] << " m";
      EXPECT_NEAR(g.imag(), want[a][b].imag(), 1e-9) << f[a] << " Hz " << xi[b] << " m";
      EXPECT_EQ(spatial::coherency_between(s, two_pi * f[a], 0, 1), std::conj(g));  // Hermitian
    }
  // without sites the generator's Gamma is coherency() bit for bit (the shipped studies' motions do not change)
  s.sites.clear();
  EXPECT_EQ(spatial::coherency_between(s, two_pi * 2, 1, 0), spatial::coherency(s.coherency, two_pi * 2, 200, 0, 500, true));
}

TEST(SpatialCoherency, CholeskyWithSiteResponseMatchesTheNumpyReference) {
  // As T6.5 (HV Event 20, x = 0, 100, 200 m, 500 m/s, f = 2 Hz) with sites 2.5 Hz/0.6, 1 Hz/0.4, 5 Hz/0.3:
  //   python3 tools/reference_spatial.py factors --model harichandran-vanmarcke --positions 0,100,200 --f 2
  //           --site 2.5,0.6:1,0.4:5,0.3          (numpy.linalg.cholesky)
  // theta_s = arg H_j - arg H_k is a diagonal unitary similarity: |L| is T6.5's, arg L_jm gains arg H_j - arg H_m.
  spatial::Settings s;
  s.coherency.model = CoherencyModel::harichandran_vanmarcke;
  s.positions = {0, 100, 200};
  s.sites = {{2.5, 0.6}, {1.0, 0.4}, {5.0, 0.3}};
  const double w = two_pi * 2;
  std::vector<std::complex<double>> a(9);
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t k = 0; k < 3; ++k) a[j * 3 + k] = j == k ? 1.0 : spatial::coherency_between(s, w, j, k);
  const auto L = spatial::cholesky(a, 3);
  const double mag[3][3] = {{1, 0, 0}, {0.8301269703, 0.5575744014, 0}, {0.6955860844, 0.4532170072, 0.5574534453}};
  const double arg[3][3] = {{0, 0, 0}, {2.5775056922, 0, 0}, {1.6609152070, -0.9165904853, 0}};
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k <= j; ++k) {
      EXPECT_NEAR(std::abs(L[j * 3 + k]), mag[j][k], 1e-9) << j << k;
      EXPECT_NEAR(std::arg(L[j * 3 + k]), arg[j][k], 1e-9) << j << k;
    }
}

TEST(SpatialCoherency, TableListsTheCoherencyUsed) {
  spatial::Settings s;
  s.coherency.model = CoherencyModel::luco_wong;
  s.positions = {0.0, 50.0, 200.0};
  const std::vector<double> f{1, 5};
  EXPECT_EQ(spatial::support_separations(s), (std::vector<double>{50, 150, 200}));
  const std::string t = spatial::coherency_table(s, f, std::vector<double>{50, 100, 200});
  EXPECT_NE(t.find("f_Hz"), std::string::npos);
  EXPECT_NE(t.find("0.9938504834"), std::string::npos) << t;  // T6.2, 1 Hz 50 m
  EXPECT_NE(t.find("0.0848049725"), std::string::npos) << t;  // T6.2, 5 Hz 200 m
  EXPECT_NE(t.find("-0.6283185307"), std::string::npos) << t; // theta_w, 1 Hz 50 m
  EXPECT_EQ(t.find("theta_s"), std::string::npos);
  s.sites = {{1.0, 0.4}, {2.5, 0.6}, {1.0, 0.4}};
  const std::string u = spatial::coherency_table(s, f, std::vector<double>{50});
  EXPECT_NE(u.find("theta_s_rad"), std::string::npos);
  EXPECT_NE(u.find("0.9748002034"), std::string::npos) << u;  // T6.4, 1 Hz 50 m: support 2 against support 1
  EXPECT_NE(u.find("0.8244292455"), std::string::npos) << u;
}

TEST(Nzs1170, ShapeFactorMatchesTable31) {
  // NZS 1170.5:2004 table 3.1 (modal/numerical integration column), two decimals as printed
  const double T[] = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5};
  const double A[] = {1.00, 2.35, 2.35, 2.35, 1.89, 1.60, 1.40, 1.24, 1.12, 1.03, 0.95, 0.70, 0.53, 0.42, 0.35, 0.26, 0.20, 0.16};
  const double C[] = {1.33, 2.93, 2.93, 2.93, 2.36, 2.00, 1.74, 1.55, 1.41, 1.29, 1.19, 0.88, 0.66, 0.53, 0.44, 0.32, 0.25, 0.20};
  const double D[] = {1.12, 3.00, 3.00, 3.00, 3.00, 3.00, 2.84, 2.53, 2.29, 2.09, 1.93, 1.43, 1.07, 0.86, 0.71, 0.52, 0.40, 0.32};
  const double E[] = {1.12, 3.00, 3.00, 3.00, 3.00, 3.00, 3.00, 3.00, 3.00, 3.00, 3.00, 2.21, 1.66, 1.33, 1.11, 0.81, 0.62, 0.49};
  for (std::size_t i = 0; i < std::size(T); ++i) {
    EXPECT_NEAR(nzs1170_ch(Nzs1170Site::A, T[i]), A[i], 0.0051) << T[i];
    EXPECT_EQ(nzs1170_ch(Nzs1170Site::B, T[i]), nzs1170_ch(Nzs1170Site::A, T[i]));
    EXPECT_NEAR(nzs1170_ch(Nzs1170Site::C, T[i]), C[i], 0.0051) << T[i];
    EXPECT_NEAR(nzs1170_ch(Nzs1170Site::D, T[i]), D[i], 0.0051) << T[i];
    EXPECT_NEAR(nzs1170_ch(Nzs1170Site::E, T[i]), E[i], 0.0051) << T[i];
  }
  const DesignSpectrum d(Nzs1170Spectrum{Nzs1170Site::D, 0.4, 1.3});
  EXPECT_DOUBLE_EQ(d.sa(0.3), 3.0 * 0.4 * 1.3);
  EXPECT_THROW(DesignSpectrum(Nzs1170Spectrum{Nzs1170Site::C, 0.05, 1.0}), InputError);
  EXPECT_THROW(DesignSpectrum(Nzs1170Spectrum{Nzs1170Site::C, 0.4, 2.5}), InputError);
  EXPECT_EQ(parse_nzs1170_site("d"), Nzs1170Site::D);
  EXPECT_FALSE(parse_nzs1170_site("F"));
}

spatial::Settings two_supports(spatial::CoherencyLoss loss = spatial::CoherencyLoss::high) {
  spatial::Settings s;
  s.positions = {0.0, 100.0};
  s.velocity = 500.0;
  s.coherency.beta = spatial::sobczyk_beta(loss);
  s.targets.emplace_back(Nzs1170Spectrum{Nzs1170Site::D, 0.4, 1.0});
  s.dt = 0.01;
  s.duration = 20.0;
  s.seed = 26;
  return s;
}

// Sum over lags of a_j(t) a_k(t + lag), normalised.
std::vector<double> cross_correlation(const std::vector<double>& a, const std::vector<double>& b, int max_lag) {
  std::vector<double> c(2 * max_lag + 1, 0.0);
  for (int lag = -max_lag; lag <= max_lag; ++lag)
    for (int t = 0; t < static_cast<int>(a.size()); ++t) {
      const int u = t + lag;
      if (u >= 0 && u < static_cast<int>(b.size())) c[lag + max_lag] += a[t] * b[u];
    }
  return c;
}

int lag_of_peak(const spatial::Settings& s, int realisations) {
  const int max_lag = 100;
  std::vector<double> sum(2 * max_lag + 1, 0.0);
  for (int r = 0; r < realisations; ++r) {
    const auto rz = spatial::simulate(s, r);
    const auto c = cross_correlation(rz.supports[0].acc, rz.supports[1].acc, max_lag);
    for (std::size_t i = 0; i < c.size(); ++i) sum[i] += c[i];
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < sum.size(); ++i)
    if (sum[i] > sum[best]) best = i;
  return static_cast<int>(best) - max_lag;
}

TEST(SpatialMotions, LaggedCrossCorrelationPeaksAtTheWavePassageDelay) {
  // 100 m at 500 m/s: support 2 lags support 1 by 0.2 s = 20 steps (exact within one step, medium loss, 8
  // realisations summed, matched spectra)
  auto s = two_supports(spatial::CoherencyLoss::medium);
  s.iterations = 3;
  EXPECT_EQ(lag_of_peak(s, 8), 20);
  s.velocity = 250.0;  // 0.4 s
  EXPECT_EQ(lag_of_peak(s, 8), 40);
  s.wave_passage = false;
  EXPECT_EQ(lag_of_peak(s, 8), 0);
}

// Smoothed-periodogram estimate of |gamma_12| at frequency f (Hz): the strong phase (envelope = 1) of support 1
// and the same window of support 2 shifted by the wave-passage delay (lagged coherency), Hann-tapered; cross-
// and auto-periodograms averaged over the realisations and over the DFT bins within +-bw Hz of f.
std::complex<double> estimated_cross(const std::vector<spatial::Realisation>& rs, const spatial::Settings& s, double f,
                                     double bw) {
  const int shift = static_cast<int>(std::lround((s.positions[1] - s.positions[0]) / s.velocity / s.dt));
  const int t0 = static_cast<int>(std::lround(s.envelope.rise / s.dt));
  const int len = static_cast<int>(std::lround(s.envelope.strong / s.dt)) - shift;
  const double df = 1.0 / (len * s.dt);
  std::complex<double> s12 = 0;
  double s11 = 0, s22 = 0;
  for (int bin = static_cast<int>(std::ceil((f - bw) / df)); bin * df <= f + bw; ++bin)
    for (const auto& r : rs) {
      std::complex<double> X1 = 0, X2 = 0;
      for (int p = 0; p < len; ++p) {
        const double hann = 0.5 - 0.5 * std::cos(two_pi * p / (len - 1));
        const auto e = std::polar(hann, -two_pi * bin * p / len);
        X1 += r.supports[0].acc[t0 + p] * e;
        X2 += r.supports[1].acc[t0 + p + shift] * e;
      }
      s12 += X1 * std::conj(X2);
      s11 += std::norm(X1);
      s22 += std::norm(X2);
    }
  return s12 / std::sqrt(s11 * s22);
}
double estimated_coherency(const std::vector<spatial::Realisation>& rs, const spatial::Settings& s, double f, double bw) {
  return std::abs(estimated_cross(rs, s, f, bw));
}

TEST(SpatialMotions, EstimatedCoherencyOfManyRealisationsMatchesTheModel) {
  // Sobczyk high loss (beta = 0.002 1/m), 100 m, 500 m/s: |gamma| = exp(-0.04 w) -- 0.78 at 1 Hz, 0.29 at 5 Hz.
  // 60 realisations, no spectrum matching (pure Deodatis; matching scales each sample's auto-spectra and leaves
  // Gamma alone, see the next test). The estimate over nu = 60 x (bins in +-0.3 Hz, ~5) ~ 300 averaged periodograms
  // has the bias E|g^|^2 ~ |g|^2 + (1 - |g|^2)^2 / nu (Bendat & Piersol): at |g| = 0.29 it adds 0.005, the
  // Hann window's leakage across the steep model adds less; tolerance 0.05 absolute.
  auto s = two_supports(spatial::CoherencyLoss::high);
  s.iterations = 0;
  const auto rs = spatial::simulate_all(s, 0, 60);
  for (double f : {1.0, 2.0, 3.0, 4.0, 5.0}) {
    const double model = spatial::lagged_coherency(s.coherency, two_pi * f, 100.0, 500.0);
    EXPECT_NEAR(estimated_coherency(rs, s, f, 0.3), model, 0.05) << f << " Hz";
  }
  // and the estimator tells the loss levels apart (the test can fail): low loss is 0.90 at 3 Hz, high 0.47
  auto low = two_supports(spatial::CoherencyLoss::low);
  low.iterations = 0;
  const auto rl = spatial::simulate_all(low, 0, 60);
  const double model_low = spatial::lagged_coherency(low.coherency, two_pi * 3.0, 100.0, 500.0);
  EXPECT_NEAR(estimated_coherency(rl, low, 3.0, 0.3), model_low, 0.05);
  EXPECT_GT(std::abs(estimated_coherency(rl, low, 3.0, 0.3) - estimated_coherency(rs, s, 3.0, 0.3)), 0.3);
}

TEST(SpatialMotions, SiteResponseShiftsThePhaseBetweenSupports) {
  // Der Kiureghian's site term in generated motions: support 1 on a stiff site (2.5 Hz, 0.6), support 2 on a soft
  // one (1 Hz, 0.4), Luco-Wong 2.5e-4 s/m (|gamma| 0.98-0.63 at 1-5 Hz over 100 m). Once the wave passage is
  // shifted out, the phase of the estimated cross-spectrum X1 X2* is theta_s(1, 2) = arg H_1 H_2* (+0.82 rad at 1 Hz,
  // +0.36 at 5 Hz); without sites it is 0 (the test can fail). 40 realisations, no matching.
  auto s = two_supports();
  s.coherency.model = CoherencyModel::luco_wong;
  s.iterations = 0;
  s.sites = {{2.5, 0.6}, {1.0, 0.4}};
  const auto rs = spatial::simulate_all(s, 0, 40);
  auto plain = s;
  plain.sites.clear();
  const auto rp = spatial::simulate_all(plain, 0, 40);
  for (double f : {1.0, 2.0, 3.0, 5.0}) {
    const double want = spatial::site_phase(s.sites[0], s.sites[1], two_pi * f);
    EXPECT_NEAR(std::arg(estimated_cross(rs, s, f, 0.3)), want, 0.08) << f << " Hz";
    EXPECT_NEAR(std::arg(estimated_cross(rp, plain, f, 0.3)), 0.0, 0.08) << f << " Hz";
    EXPECT_NEAR(std::abs(estimated_cross(rs, s, f, 0.3)),
                spatial::lagged_coherency(s.coherency, two_pi * f, 100.0, 500.0), 0.05) << f << " Hz";
  }
  // support 1 leads the factorisation (L_11 = 1): its motion is the same with or without the site term
  EXPECT_EQ(rs[0].supports[0].acc, rp[0].supports[0].acc);
}

TEST(SpatialMotions, MeanResponseSpectrumMatchesTheTarget) {
  // NZS 1170.5 class D, Z = 0.4, R = 1, 10 realisations x 2 supports matched over 0.05-4 s: the mean PSA over
  // the 20 records within 10 % of the target at 25 periods 0.1-3 s (not the matching grid).
  auto s = two_supports(spatial::CoherencyLoss::medium);
  const auto rs = spatial::simulate_all(s, 0, 10);
  std::vector<double> T;
  for (int i = 0; i < 25; ++i) T.push_back(0.1 * std::pow(30.0, i / 24.0));
  std::vector<double> mean(T.size(), 0.0);
  for (const auto& r : rs)
    for (const auto& rec : r.supports) {
      const auto sp = response_spectrum(rec, T, 0.05);
      for (std::size_t i = 0; i < T.size(); ++i) mean[i] += sp.psa[i] / g_accel / 20.0;
    }
  for (std::size_t i = 0; i < T.size(); ++i) EXPECT_NEAR(mean[i] / s.targets[0].sa(T[i]), 1.0, 0.10) << T[i] << " s";
  // without the iteration the starting PSD misses the target by more than that somewhere (the test can fail)
  s.iterations = 0;
  const auto r0 = spatial::simulate(s, 0);
  double worst = 0;
  for (const auto& rec : r0.supports) {
    const auto sp = response_spectrum(rec, T, 0.05);
    for (std::size_t i = 0; i < T.size(); ++i) worst = std::max(worst, std::abs(sp.psa[i] / g_accel / s.targets[0].sa(T[i]) - 1));
  }
  EXPECT_GT(worst, 0.10);
}

TEST(SpatialMotions, SameSeedSameBitsInAnyOrder) {
  auto s = two_supports();
  s.iterations = 2;
  const auto all = spatial::simulate_all(s, 0, 4);
  const auto third = spatial::simulate(s, 3);
  const auto again = spatial::simulate_all(s, 3, 1);
  for (std::size_t j = 0; j < 2; ++j) {
    EXPECT_EQ(all[3].supports[j].acc, third.supports[j].acc);
    EXPECT_EQ(again[0].supports[j].acc, third.supports[j].acc);
    EXPECT_NE(all[2].supports[j].acc, third.supports[j].acc);
  }
  s.seed = 27;
  EXPECT_NE(spatial::simulate(s, 3).supports[0].acc, third.supports[0].acc);
}

TEST(SpatialMotions, GroundVelocityAndDisplacementEndAtZero) {
  auto s = two_supports();
  s.iterations = 2;
  const auto r = spatial::simulate(s, 5);
  for (const auto& rec : r.supports) {
    const Measures m = measure(rec);
    double v = 0, u = 0;
    for (std::size_t k = 0; k + 1 < rec.acc.size(); ++k) {
      u += rec.dt * v + rec.dt * rec.dt * (rec.acc[k] / 3 + rec.acc[k + 1] / 6);
      v += rec.dt * (rec.acc[k] + rec.acc[k + 1]) / 2;
    }
    EXPECT_LT(std::abs(v), 1e-9 * m.pgv);
    EXPECT_LT(std::abs(u), 1e-9 * m.pgd);
    EXPECT_GT(m.pga, 0.5);  // m/s^2: a real motion (NZS D, Z = 0.4: PGA ~ 0.45 g)
  }
}

TEST(SpatialMotions, StopIsHonouredAndBadSettingsRefused) {
  auto s = two_supports();
  std::atomic<bool> stop{true};
  WorkHook hook;
  hook.cancel = &stop;
  EXPECT_THROW(spatial::simulate_all(s, 0, 5, &hook), Cancelled);
  auto bad = s;
  bad.positions = {0.0, 0.0};
  EXPECT_THROW(spatial::validate(bad), InputError);
  bad = s;
  bad.f_max = 60;  // above Nyquist at dt = 0.01
  EXPECT_THROW(spatial::validate(bad), InputError);
  bad = s;
  bad.velocity = 0;
  EXPECT_THROW(spatial::validate(bad), InputError);
}

}  // namespace
}  // namespace pounding
