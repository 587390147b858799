// Rezaeian & Der Kiureghian (2010) site-based stochastic ground motions (see synthetic.hpp).
#include "pounding/motion/synthetic.hpp"

#include <boost/math/distributions/beta.hpp>
#include <boost/math/distributions/gamma.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/random/mersenne_twister.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pounding/core/error.hpp"

namespace pounding {

namespace {

// No promotion to long double inside Boost.Math: long double differs between x86 and other machines.
using Pol = boost::math::policies::policy<boost::math::policies::promote_double<false>,
                                          boost::math::policies::promote_float<false>>;

constexpr double two_pi = 2.0 * std::numbers::pi;

// Predictive-equation coefficients b1..b5 (issue 3 table; R&DK 2010 Table 4).
constexpr double B[6][5] = {
    {-1.844, -0.071, 2.944, -1.356, -0.265},  // Ia       (ln R, ln V)
    {-6.195, -0.703, 6.792, 0.219, -0.523},   // D5-95
    {-5.011, -0.345, 4.638, 0.348, -0.185},   // t_mid
    {2.253, -0.081, -1.810, -0.211, 0.012},   // f_mid
    {-2.489, 0.044, 2.408, 0.065, -0.081},    // f'
    {-0.258, -0.477, 0.905, -0.289, 0.316},   // zeta_f
};
constexpr double SD[6] = {0.65, 0.73, 0.66, 1.00, 0.96, 1.02};
constexpr double CORR[6][6] = {
    {1, -0.3555, 0.0066, -0.1545, 0.1341, -0.0078},
    {-0.3555, 1, 0.6729, -0.1303, -0.1576, -0.1958},
    {0.0066, 0.6729, 1, -0.2761, -0.1977, -0.2188},
    {-0.1545, -0.1303, -0.2761, 1, -0.2034, 0.2814},
    {0.1341, -0.1576, -0.1977, -0.2034, 1, -0.0137},
    {-0.0078, -0.1958, -0.2188, 0.2814, -0.0137, 1},
};

// Marginals (R&DK 2010 Table 3).
constexpr double IA_LAMBDA = -4.354999117683, IA_ZETA = 1.60818347313;
constexpr double TSE_A = 17.1, TSE_B = 6.77, TSE_C = 4.85, TSE_MIN = -2.0, TSE_MAX = 0.5;

struct ScaledBeta {
  double lo, hi, alpha, beta;
  // method of moments: mean and sd on [lo, hi]
  static ScaledBeta from_moments(double lo, double hi, double mean, double sd) {
    const double m = (mean - lo) / (hi - lo), v = (sd / (hi - lo)) * (sd / (hi - lo));
    const double s = m * (1 - m) / v - 1;
    return {lo, hi, m * s, (1 - m) * s};
  }
};
const ScaledBeta D595_DIST = ScaledBeta::from_moments(5.0, 45.0, 17.3, 9.31);
const ScaledBeta TMID_DIST = ScaledBeta::from_moments(0.5, 40.0, 12.4, 7.44);
const ScaledBeta ZETA_DIST = ScaledBeta::from_moments(0.02, 1.0, 0.213, 0.143);
constexpr double FMID_MEAN = 5.87, FMID_SD = 3.11;

// F^-1(Phi(nu)) evaluated on the side of the smaller tail probability, so large |nu| keeps its precision.
double beta_from_normal(const ScaledBeta& d, double nu) {
  boost::math::beta_distribution<double, Pol> dist(d.alpha, d.beta);
  const double x = nu <= 0 ? boost::math::quantile(dist, standard_normal_cdf(nu))
                           : boost::math::quantile(boost::math::complement(dist, standard_normal_cdf(-nu)));
  return d.lo + (d.hi - d.lo) * x;
}

double gamma_from_normal(double mean, double sd, double nu) {
  const double k = (mean / sd) * (mean / sd), theta = sd * sd / mean;
  boost::math::gamma_distribution<double, Pol> dist(k, theta);
  return nu <= 0 ? boost::math::quantile(dist, standard_normal_cdf(nu))
                 : boost::math::quantile(boost::math::complement(dist, standard_normal_cdf(-nu)));
}

double poly(const double* c, int n, double x) {
  double r = c[n - 1];
  for (int i = n - 2; i >= 0; --i) r = r * x + c[i];
  return r;
}

// One stream: Boost's mt19937_64 (fully specified) -> 53-bit uniforms in (0, 1) -> AS241 normals.
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed) : eng_(seed) {}
  double uniform() { return (static_cast<double>(eng_() >> 11) + 0.5) * 0x1.0p-53; }
  double normal() { return standard_normal_quantile(uniform()); }

 private:
  boost::random::mt19937_64 eng_;
};

std::array<double, 36> cholesky_lower() {
  std::array<double, 36> S = error_covariance(), L{};
  for (int j = 0; j < 6; ++j) {
    double d = S[j * 6 + j];
    for (int k = 0; k < j; ++k) d -= L[j * 6 + k] * L[j * 6 + k];
    L[j * 6 + j] = std::sqrt(d);
    for (int i = j + 1; i < 6; ++i) {
      double s = S[i * 6 + j];
      for (int k = 0; k < j; ++k) s -= L[i * 6 + k] * L[j * 6 + k];
      L[i * 6 + j] = s / L[j * 6 + j];
    }
  }
  return L;
}

// Critically damped high-pass oscillator u'' + 2 wc u' + wc^2 u = x, Newmark beta = 1/4, gamma = 1/2;
// returns u'' (Chopra, Dynamics of Structures, Table 5.4.2, incremental form).
std::vector<double> highpass(const std::vector<double>& x, double dt, double fc_hz) {
  const double wc = two_pi * fc_hz, m = 1.0, c = 2.0 * wc, k = wc * wc;
  const double beta = 0.25, gamma = 0.5;
  const double kh = k + gamma / (beta * dt) * c + m / (beta * dt * dt);
  const double ca = m / (beta * dt) + gamma / beta * c;
  const double cb = m / (2 * beta) + dt * (gamma / (2 * beta) - 1) * c;
  std::vector<double> out(x.size());
  double u = 0, v = 0, a = x.empty() ? 0.0 : x[0];
  if (!x.empty()) out[0] = a;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double dp = (x[i] - x[i - 1]) + ca * v + cb * a;
    const double du = dp / kh;
    const double dv = gamma / (beta * dt) * du - gamma / beta * v + dt * (1 - gamma / (2 * beta)) * a;
    const double da = du / (beta * dt * dt) - v / (beta * dt) - a / (2 * beta);
    u += du, v += dv, a += da;
    out[i] = a;
  }
  return out;
}

}  // namespace

void validate(const SiteParams& s, const std::string& where) {
  auto bad = [&](const char* key, double v, const char* range) {
    throw InputError(fmt::format("{} = {} is outside the synthetic model's range {}", key, v, range), where,
                     fmt::format("give {} in {}", key, range));
  };
  if (!(s.M >= 4.0 && s.M <= 9.0)) bad("M", s.M, "[4, 9]");
  if (!(s.R_km > 0.0 && s.R_km <= 500.0)) bad("R_km", s.R_km, "(0, 500] km");
  if (!(s.vs30 >= 50.0 && s.vs30 <= 3000.0)) bad("vs30", s.vs30, "[50, 3000] m/s");
  if (s.F != 0 && s.F != 1) bad("F", s.F, "{0 (strike-slip), 1 (reverse)}");
}

double standard_normal_quantile(double p) {
  // Wichura (1988), Algorithm AS241 PPND16, Applied Statistics 37:477-484.
  static constexpr double a[8] = {3.3871328727963666080e0,     1.3314166789178437745e+2,
                                  1.9715909503065514427e+3,    1.3731693765509461125e+4,
                                  4.5921953931549871457e+4,    6.7265770927008700853e+4,
                                  3.3430575583588128105e+4,    2.5090809287301226727e+3};
  static constexpr double b[8] = {1.0,
                                  4.2313330701600911252e+1,    6.8718700749205790830e+2,
                                  5.3941960214247511077e+3,    2.1213794301586595867e+4,
                                  3.9307895800092710610e+4,    2.8729085735721942674e+4,
                                  5.2264952788528545610e+3};
  static constexpr double c[8] = {1.42343711074968357734e0,    4.63033784615654529590e0,
                                  5.76949722146069140550e0,    3.64784832476320460504e0,
                                  1.27045825245236838258e0,    2.41780725177450611770e-1,
                                  2.27238449892691845833e-2,   7.74545014278341407640e-4};
  static constexpr double d[8] = {1.0,
                                  2.05319162663775882187e0,    1.67638483018380384940e0,
                                  6.89767334985100004550e-1,   1.48103976427480074590e-1,
                                  1.51986665636164571966e-2,   5.47593808499534494600e-4,
                                  1.05075007164441684324e-9};
  static constexpr double e[8] = {6.65790464350110377720e0,    5.46378491116411436990e0,
                                  1.78482653991729133580e0,    2.96560571828504891230e-1,
                                  2.65321895265761230930e-2,   1.24266094738807843860e-3,
                                  2.71155556874348757815e-5,   2.01033439929228813265e-7};
  static constexpr double f[8] = {1.0,
                                  5.99832206555887937690e-1,   1.36929880922735805310e-1,
                                  1.48753612908506148525e-2,   7.86869131145613259100e-4,
                                  1.84631831751005468180e-5,   1.42151175831644588870e-7,
                                  2.04426310338993978564e-15};
  if (!(p > 0.0 && p < 1.0)) {
    if (p == 0.0) return -INFINITY;
    if (p == 1.0) return INFINITY;
    return NAN;
  }
  const double q = p - 0.5;
  if (std::abs(q) <= 0.425) {
    const double r = 0.180625 - q * q;
    return q * poly(a, 8, r) / poly(b, 8, r);
  }
  double r = std::sqrt(-std::log(q < 0 ? p : 1.0 - p));
  double v;
  if (r <= 5.0) {
    r -= 1.6;
    v = poly(c, 8, r) / poly(d, 8, r);
  } else {
    r -= 5.0;
    v = poly(e, 8, r) / poly(f, 8, r);
  }
  return q < 0 ? -v : v;
}

double standard_normal_cdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

double two_sided_exponential_quantile(double F, double a, double b, double c, double xmin, double xmax) {
  // density c e^(b x) on [xmin, 0), c e^(-a x) on [0, xmax] (issue 3 / R&DK 2010 Table 3)
  const double F0 = (c / b) * (1.0 - std::exp(b * xmin));
  double x = F < F0 ? std::log(F * b / c + std::exp(b * xmin)) / b
                    : -std::log((F0 - F) * a / c + 1.0) / a;
  if (!(x <= xmax)) x = xmax;  // the published a, b, c integrate to 0.99998: F -> 1 lands just past xmax
  return std::max(x, xmin);
}

std::array<double, 36> error_covariance() {
  std::array<double, 36> S{};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) S[i * 6 + j] = SD[i] * SD[j] * CORR[i][j];
  return S;
}

Normal6 correlated_errors(const Normal6& z) {
  static const std::array<double, 36> L = cholesky_lower();
  Normal6 eps{};
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k <= i; ++k) eps[i] += L[i * 6 + k] * z[k];
  return eps;
}

Normal6 predictive_mean(const SiteParams& s) {
  Normal6 mu{};
  const double F = s.F, m = s.M / 7.0;
  mu[0] = B[0][0] + B[0][1] * F + B[0][2] * m + B[0][3] * std::log(s.R_km / 25.0) + B[0][4] * std::log(s.vs30 / 750.0);
  for (int i = 1; i < 6; ++i)
    mu[i] = B[i][0] + B[i][1] * F + B[i][2] * m + B[i][3] * (s.R_km / 25.0) + B[i][4] * (s.vs30 / 750.0);
  return mu;
}

ModelParams params_from_normal(const Normal6& nu) {
  ModelParams p;
  p.arias_sg = std::exp(IA_LAMBDA + IA_ZETA * nu[0]);  // lognormal: F^-1(Phi(nu)) = exp(lambda + zeta nu)
  p.d5_95 = beta_from_normal(D595_DIST, nu[1]);
  p.t_mid = beta_from_normal(TMID_DIST, nu[2]);
  p.f_mid_hz = gamma_from_normal(FMID_MEAN, FMID_SD, nu[3]);
  // Phi(nu) for the two-sided exponential (its CDF is not symmetric, so no complement trick is needed:
  // F close to 1 maps to x close to xmax, where the quantile is flat).
  p.f_slope_hz_s = two_sided_exponential_quantile(standard_normal_cdf(nu[4]), TSE_A, TSE_B, TSE_C, TSE_MIN, TSE_MAX);
  p.zeta_f = beta_from_normal(ZETA_DIST, nu[5]);
  return p;
}

ModelParams median_params(const SiteParams& s) { return params_from_normal(predictive_mean(s)); }

double Envelope::operator()(double t) const {
  if (!(t > 0)) return 0.0;
  return std::exp(std::log(a1) + (a2 - 1.0) * std::log(t) - a3 * t);
}

double Envelope::quantile(double p) const { return boost::math::gamma_p_inv(shape(), p, Pol()) / rate(); }

Envelope solve_envelope(double arias_sg, double d5_95, double t_mid) {
  if (!(arias_sg > 0) || !(d5_95 > 0) || !(t_mid > 0) || !std::isfinite(arias_sg + d5_95 + t_mid))
    throw InputError(fmt::format("envelope needs Ia, D5-95, t_mid > 0 (got {}, {}, {})", arias_sg, d5_95, t_mid),
                     "synthetic model", "give positive parameters");
  // For q^2 ~ Gamma(k, 1/rate): D5-95 / t_mid = (G_k^-1(.95) - G_k^-1(.05)) / G_k^-1(.45) depends on k
  // alone and falls monotonically from +inf (k -> 0) to 0 (k -> inf): bisection on ln k.
  auto ratio = [](double k) -> double {
    const double q45 = boost::math::gamma_p_inv(k, 0.45, Pol());
    if (!(q45 > 0)) return static_cast<double>(INFINITY);
    return double((boost::math::gamma_p_inv(k, 0.95, Pol()) - boost::math::gamma_p_inv(k, 0.05, Pol())) / q45);
  };
  const double target = d5_95 / t_mid;
  double lo = std::log(0.02), hi = std::log(1e6);
  if (ratio(std::exp(lo)) < target)
    throw InputError(fmt::format("D5-95 / t_mid = {} is too large for a gamma envelope", target), "synthetic model",
                     "use a shorter D5-95 or a later t_mid");
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ratio(std::exp(mid)) > target ? lo : hi) = mid;
  }
  const double k = std::exp(0.5 * (lo + hi));
  const double rate = boost::math::gamma_p_inv(k, 0.45, Pol()) / t_mid;
  Envelope env;
  env.a2 = 0.5 * (k + 1.0);
  env.a3 = 0.5 * rate;
  // Ia [s g] = pi/2 int (q/g)^2 dt = pi/(2 g^2) a1^2 Gamma(k) / rate^k
  env.a1 = g_accel * std::exp(0.5 * (std::log(2.0 * arias_sg / std::numbers::pi) + k * std::log(rate) -
                                     boost::math::lgamma(k, Pol())));
  return env;
}

namespace {

Record simulate_with(const ModelParams& p, NormalStream& rng, const SynthOptions& o) {
  require_positive(o.dt, "dt (synthetic)");
  const Envelope env = solve_envelope(p.arias_sg, p.d5_95, p.t_mid);
  double T = o.duration;
  if (!(T > 0)) T = std::max(env.quantile(0.9995), env.quantile(0.95) + 5.0);
  const auto n = static_cast<std::size_t>(std::ceil(T / o.dt - 1e-9)) + 1;
  if (n > 20'000'000) throw InputError("synthetic record longer than 2e7 samples", "synthetic model", "use a larger dt");

  const double zeta = std::clamp(p.zeta_f, 0.0, 1.0 - 1e-6);
  const double sq = std::sqrt(1.0 - zeta * zeta);
  const double w_min = two_pi * o.f_min_hz;
  const double w_mid = two_pi * p.f_mid_hz, w_slope = two_pi * p.f_slope_hz_s;
  const double log_tol = -std::log(o.truncation);

  std::vector<double> u(n), w(n), zr(n), zi(n), rr(n), ri(n), x(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) u[i] = rng.normal();
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = static_cast<double>(i) * o.dt;
    w[i] = std::max(w_mid + w_slope * (tau - p.t_mid), w_min);
    const double decay = std::exp(-zeta * w[i] * o.dt), ph = w[i] * sq * o.dt;
    rr[i] = decay * std::cos(ph);
    ri[i] = decay * std::sin(ph);
  }
  std::size_t lo = 0;
  for (std::size_t k = 0; k < n; ++k) {
    // impulses i < k: advance to lag m = k - i and accumulate h and h^2 (h = Im z)
    double num = 0.0, den = 0.0;
    for (std::size_t i = lo; i < k; ++i) {
      const double a = zr[i] * rr[i] - zi[i] * ri[i];
      const double b = zr[i] * ri[i] + zi[i] * rr[i];
      zr[i] = a, zi[i] = b;
      num += u[i] * b;
      den += b * b;
    }
    if (den > 0) x[k] = env(static_cast<double>(k) * o.dt) * num / std::sqrt(den);
    // impulse k enters at lag 0 (h = 0 there)
    zr[k] = w[k] / sq, zi[k] = 0.0;
    while (lo < k && zeta * w[lo] * static_cast<double>(k + 1 - lo) * o.dt > log_tol) ++lo;
  }
  Record rec;
  rec.dt = o.dt;
  rec.acc = o.highpass_hz > 0 ? highpass(x, o.dt, o.highpass_hz) : std::move(x);
  if (o.pga_g > 0) {
    const double s = o.pga_g * g_accel / rec.pga();
    for (double& a : rec.acc) a *= s;
    rec.meta["scale_to_pga"] = fmt::format("{:.6g}", s);
  }
  rec.meta["format"] = "SYNTHETIC_RDK2010";
  rec.meta["units"] = "m/s2";
  rec.meta["Ia_sg"] = fmt::format("{:.6g}", p.arias_sg);
  rec.meta["D5_95_s"] = fmt::format("{:.6g}", p.d5_95);
  rec.meta["t_mid_s"] = fmt::format("{:.6g}", p.t_mid);
  rec.meta["f_mid_hz"] = fmt::format("{:.6g}", p.f_mid_hz);
  rec.meta["f_slope_hz_s"] = fmt::format("{:.6g}", p.f_slope_hz_s);
  rec.meta["zeta_f"] = fmt::format("{:.6g}", p.zeta_f);
  rec.meta["envelope"] = fmt::format("a1={:.6g} a2={:.6g} a3={:.6g}", env.a1, env.a2, env.a3);
  return rec;
}

}  // namespace

Record simulate(const ModelParams& p, std::uint64_t seed, const SynthOptions& o) {
  NormalStream rng(seed);
  Record r = simulate_with(p, rng, o);
  r.name = fmt::format("rdk2010-seed{}", seed);
  r.source = fmt::format("synthetic:rdk2010:seed={}", seed);
  r.meta["seed"] = fmt::format("{}", seed);
  return r;
}

ModelParams sample_params(const SiteParams& site, std::uint64_t seed) {
  NormalStream rng(seed);
  Normal6 z;
  for (double& v : z) v = rng.normal();
  const Normal6 eps = correlated_errors(z), mu = predictive_mean(site);
  Normal6 nu;
  for (int i = 0; i < 6; ++i) nu[i] = mu[i] + eps[i];
  return params_from_normal(nu);
}

Record synthesize(const SiteParams& site, std::uint64_t seed, const SynthOptions& o) {
  validate(site, "synthetic site");
  NormalStream rng(seed);
  Normal6 z;
  for (double& v : z) v = rng.normal();  // the first six normals of the stream: the parameter errors
  const Normal6 eps = correlated_errors(z), mu = predictive_mean(site);
  Normal6 nu;
  for (int i = 0; i < 6; ++i) nu[i] = mu[i] + eps[i];
  Record r = simulate_with(params_from_normal(nu), rng, o);
  r.name = fmt::format("rdk2010-M{}-R{}-V{}-F{}-seed{}", site.M, site.R_km, site.vs30, site.F, seed);
  r.source = fmt::format("synthetic:rdk2010:M={},R={},Vs30={},F={},seed={}", site.M, site.R_km, site.vs30, site.F, seed);
  r.meta["seed"] = fmt::format("{}", seed);
  r.meta["M"] = fmt::format("{}", site.M);
  r.meta["R_km"] = fmt::format("{}", site.R_km);
  r.meta["vs30"] = fmt::format("{}", site.vs30);
  r.meta["F"] = fmt::format("{}", site.F);
  return r;
}

}  // namespace pounding
