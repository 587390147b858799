// Spatially varying, spectrum-compatible support motions: see spatial.hpp for the method and its sources.
#include "pounding/motion/spatial.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pounding/core/error.hpp"
#include "pounding/core/random.hpp"
#include "pounding/motion/spectrum.hpp"

namespace pounding::spatial {

namespace {

using cplx = std::complex<double>;
constexpr double two_pi = 2.0 * std::numbers::pi;

// In-place radix-2 FFT with the +i sign: x[p] <- sum_l x[l] exp(+2 pi i l p / M) (unnormalised). Twiddles are
// computed directly (std::polar of the exact angle), never by recurrence.
void fft_plus(std::vector<cplx>& x, const std::vector<cplx>& twiddle) {
  const std::size_t n = x.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(x[i], x[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const std::size_t half = len / 2, stride = n / len;
    for (std::size_t i = 0; i < n; i += len)
      for (std::size_t k = 0; k < half; ++k) {
        const cplx u = x[i + k], v = x[i + k + half] * twiddle[k * stride];
        x[i + k] = u + v;
        x[i + k + half] = u - v;
      }
  }
}

// U[0, 1) from a counter: 53 high bits of splitmix64.
double uniform(std::uint64_t key, std::uint64_t counter) {
  return static_cast<double>(splitmix64(key + counter) >> 11) * 0x1.0p-53;
}

std::uint64_t realisation_key(std::uint64_t seed, std::uint64_t index) {
  return splitmix64(splitmix64(seed) ^ splitmix64(index ^ 0x5350415449414cULL));  // "SPATIAL"
}

// The integrals of records.hpp (linear acceleration between samples): final velocity and displacement.
std::pair<double, double> end_velocity_displacement(const std::vector<double>& a, double h) {
  double v = 0.0, u = 0.0;
  for (std::size_t k = 0; k + 1 < a.size(); ++k) {
    u += h * v + h * h * (a[k] / 3.0 + a[k + 1] / 6.0);
    v += h * (a[k] + a[k + 1]) / 2.0;
  }
  return {v, u};
}

// a - A(t)(c0 + c1 t/T) with zero velocity and displacement at the end (spatial.hpp).
void baseline_correct(std::vector<double>& a, const std::vector<double>& env, double h) {
  const std::size_t n = a.size();
  std::vector<double> e1(n);
  const double T = h * static_cast<double>(n - 1);
  for (std::size_t k = 0; k < n; ++k) e1[k] = env[k] * (h * static_cast<double>(k)) / T;
  const auto [va, ua] = end_velocity_displacement(a, h);
  const auto [v0, u0] = end_velocity_displacement(env, h);
  const auto [v1, u1] = end_velocity_displacement(e1, h);
  const double det = v0 * u1 - v1 * u0;
  if (!(std::abs(det) > 0.0)) return;
  const double c0 = (va * u1 - v1 * ua) / det, c1 = (v0 * ua - va * u0) / det;
  for (std::size_t k = 0; k < n; ++k) a[k] -= c0 * env[k] + c1 * e1[k];
}

// Linear interpolation in log w of the ratios r_i at w_i (w_i decreasing with i as T_i increases), held outside.
double ratio_at(double w, const std::vector<double>& w_i, const std::vector<double>& r_i) {
  const std::size_t n = w_i.size();
  if (w >= w_i.front()) return r_i.front();
  if (w <= w_i.back()) return r_i.back();
  std::size_t k = 1;
  while (k + 1 < n && w_i[k] > w) ++k;  // w_i[k-1] > w >= w_i[k]
  const double x = (std::log(w) - std::log(w_i[k - 1])) / (std::log(w_i[k]) - std::log(w_i[k - 1]));
  return r_i[k - 1] + x * (r_i[k] - r_i[k - 1]);
}

}  // namespace

// ---- coherency ----
double sobczyk_beta(CoherencyLoss loss) {
  switch (loss) {
    case CoherencyLoss::low: return 0.0005;
    case CoherencyLoss::medium: return 0.001;
    case CoherencyLoss::high: return 0.002;
  }
  return 0.001;
}

std::string Coherency::describe() const {
  switch (model) {
    case CoherencyModel::sobczyk:
      return fmt::format("Sobczyk (1991): |gamma| = exp(-beta w xi^2 / v_app), beta = {:g} 1/m", beta);
    case CoherencyModel::harichandran_vanmarcke:
      return fmt::format("Harichandran & Vanmarcke (1986): A = {:g}, alpha = {:g}, k = {:g} m, f0 = {:g} Hz, b = {:g}",
                         hv_a, hv_alpha, hv_k, hv_f0, hv_b);
    case CoherencyModel::luco_wong:
      return fmt::format("Luco & Wong (1986): |gamma| = exp(-(a w xi)^2), a = alpha/v_s = {:g} s/m", lw_a);
    case CoherencyModel::none: return "none: |gamma| = 1";
  }
  return "";
}

double lagged_coherency(const Coherency& c, double w, double xi, double v_app) {
  switch (c.model) {
    case CoherencyModel::sobczyk: return std::exp(-c.beta * w * xi * xi / v_app);
    case CoherencyModel::harichandran_vanmarcke: {
      const double f = w / two_pi;
      const double theta = c.hv_k / std::sqrt(1.0 + std::pow(f / c.hv_f0, c.hv_b));
      const double e = 2.0 * xi * (1.0 - c.hv_a + c.hv_alpha * c.hv_a);
      return c.hv_a * std::exp(-e / (c.hv_alpha * theta)) + (1.0 - c.hv_a) * std::exp(-e / theta);
    }
    case CoherencyModel::luco_wong: {
      const double x = c.lw_a * w * xi;
      return std::exp(-x * x);
    }
    case CoherencyModel::none: return 1.0;
  }
  return 1.0;
}

std::complex<double> coherency(const Coherency& c, double w, double xj, double xk, double v_app, bool wave_passage) {
  const double mag = lagged_coherency(c, w, std::abs(xj - xk), v_app);
  if (!wave_passage) return {mag, 0.0};
  return std::polar(mag, -w * (xj - xk) / v_app);
}

std::complex<double> site_transfer(const Site& site, double w) {
  const double wg = two_pi * site.frequency;
  const cplx num(wg * wg, 2.0 * site.damping * wg * w);
  return num / cplx(wg * wg - w * w, 2.0 * site.damping * wg * w);
}

double site_phase(const Site& j, const Site& k, double w) {
  const cplx h = site_transfer(j, w) * std::conj(site_transfer(k, w));
  return std::atan2(h.imag(), h.real());  // DK96: atan2, not atan (the phase may pass pi/2)
}

std::complex<double> coherency_between(const Settings& s, double w, std::size_t j, std::size_t k) {
  const double xj = s.positions[j], xk = s.positions[k];
  if (s.sites.empty()) return coherency(s.coherency, w, xj, xk, s.velocity, s.wave_passage);
  const double mag = lagged_coherency(s.coherency, w, std::abs(xj - xk), s.velocity);
  const double theta_w = s.wave_passage ? -w * (xj - xk) / s.velocity : 0.0;
  return std::polar(mag, theta_w + site_phase(s.sites[j], s.sites[k], w));
}

std::vector<double> support_separations(const Settings& s) {
  std::vector<double> d;
  for (std::size_t j = 0; j < s.positions.size(); ++j)
    for (std::size_t k = 0; k < j; ++k) d.push_back(std::abs(s.positions[j] - s.positions[k]));
  std::sort(d.begin(), d.end());
  d.erase(std::unique(d.begin(), d.end()), d.end());
  return d;
}

std::string coherency_table(const Settings& s, std::span<const double> frequencies, std::span<const double> distances) {
  const auto shown = [](double x) { return std::abs(x) < 5e-11 ? 0.0 : x; };  // no "-0.0000000000" for a rounding residue
  std::string t = fmt::format("# coherency: {}\n", s.coherency.describe());
  t += s.wave_passage ? fmt::format("# wave passage: apparent velocity {:g} m/s, theta_w = -2 pi f xi / v_app (the "
                                    "downstream point against the upstream one)\n",
                                    s.velocity)
                      : "# no wave passage: theta_w = 0\n";
  t += "# gamma = |gamma| exp(i theta_w)\n";
  t += fmt::format("{:>10}  {:>10}  {:>12}  {:>13}  {:>13}  {:>13}\n", "f_Hz", "xi_m", "abs_gamma", "theta_w_rad",
                   "re_gamma", "im_gamma");
  for (double f : frequencies)
    for (double xi : distances) {
      const double w = two_pi * f;
      const double mag = lagged_coherency(s.coherency, w, xi, s.velocity);
      const double theta_w = s.wave_passage ? -w * xi / s.velocity : 0.0;
      const cplx g = std::polar(mag, theta_w);
      t += fmt::format("{:>10g}  {:>10g}  {:>12.10f}  {:>13.10f}  {:>13.10f}  {:>13.10f}\n", f, xi, mag, shown(theta_w),
                       shown(g.real()), shown(g.imag()));
    }
  if (s.sites.empty()) return t;
  t += "#\n# site response (Der Kiureghian 1996): gamma_jk = |gamma(xi)| exp(i (theta_w + theta_s)), theta_s = "
       "arg(H_j conj(H_k)), between the supports (j downstream of k, xi = x_j - x_k)\n";
  for (std::size_t j = 0; j < s.sites.size(); ++j)
    t += fmt::format("# support {} at {:g} m: f_g = {:g} Hz (w_g = {:.6g} rad/s), zeta_g = {:g}\n", j + 1,
                     s.positions[j], s.sites[j].frequency, two_pi * s.sites[j].frequency, s.sites[j].damping);
  t += fmt::format("{:>3}  {:>3}  {:>10}  {:>10}  {:>12}  {:>13}  {:>13}  {:>13}  {:>13}\n", "j", "k", "f_Hz", "xi_m",
                   "abs_gamma", "theta_w_rad", "theta_s_rad", "re_gamma", "im_gamma");
  for (double f : frequencies)
    for (std::size_t j = 1; j < s.positions.size(); ++j)
      for (std::size_t k = 0; k < j; ++k) {
        const double w = two_pi * f;
        const cplx g = coherency_between(s, w, j, k);
        const double theta_w = s.wave_passage ? -w * (s.positions[j] - s.positions[k]) / s.velocity : 0.0;
        t += fmt::format("{:>3}  {:>3}  {:>10g}  {:>10g}  {:>12.10f}  {:>13.10f}  {:>13.10f}  {:>13.10f}  {:>13.10f}\n",
                         j + 1, k + 1, f, s.positions[j] - s.positions[k], std::abs(g), shown(theta_w),
                         shown(site_phase(s.sites[j], s.sites[k], w)), shown(g.real()), shown(g.imag()));
      }
  return t;
}

std::vector<std::complex<double>> cholesky(std::span<const std::complex<double>> a, std::size_t n) {
  std::vector<cplx> L(n * n, cplx{0.0, 0.0});
  for (std::size_t j = 0; j < n; ++j) {
    double d = a[j * n + j].real();
    for (std::size_t k = 0; k < j; ++k) d -= std::norm(L[j * n + k]);
    if (!(d > 1e-10 * a[j * n + j].real())) continue;  // rank-deficient: the column stays zero
    const double ljj = std::sqrt(d);
    L[j * n + j] = ljj;
    for (std::size_t i = j + 1; i < n; ++i) {
      cplx s = a[i * n + j];
      for (std::size_t k = 0; k < j; ++k) s -= L[i * n + k] * std::conj(L[j * n + k]);
      L[i * n + j] = s / ljj;
    }
  }
  return L;
}

double Envelope::operator()(double t) const {
  if (t < rise) return (t / rise) * (t / rise);
  if (t <= rise + strong) return 1.0;
  return std::exp(-decay * (t - rise - strong));
}

// ---- settings ----
std::vector<double> matching_periods(const Settings& s) {
  if (!s.match_periods.empty()) return s.match_periods;
  std::vector<double> T(30);
  for (std::size_t i = 0; i < T.size(); ++i)
    T[i] = 0.05 * std::pow(4.0 / 0.05, static_cast<double>(i) / static_cast<double>(T.size() - 1));
  return T;
}

Grid grid_of(const Settings& s) {
  Grid g;
  g.steps = static_cast<std::size_t>(std::llround(s.duration / s.dt)) + 1;
  g.fft = 1;
  while (g.fft < 2 * g.steps) g.fft <<= 1;
  g.d_omega = two_pi / (static_cast<double>(g.fft) * s.dt);
  // w_ml = (l + m/n) dw < 2 pi f_max for every m <= n: l dw + dw <= 2 pi f_max
  g.n_freq = static_cast<std::size_t>(std::floor(two_pi * s.f_max / g.d_omega));
  g.n_freq = std::min(g.n_freq, g.fft / 2 - 1);
  return g;
}

// ---- simulation ----
namespace {

struct Generator {
  const Settings& s;
  std::size_t n;
  Grid g;
  std::vector<double> env;          // A(t_p)
  std::vector<cplx> twiddle;        // exp(+2 pi i k / M), k < M/2
  std::vector<double> omega;        // w_ml at [m * N + l]
  std::vector<cplx> L;              // Cholesky of Gamma(w_ml) at [(m * N + l) * n * n + j * n + k]
  std::vector<double> w_match;      // 2 pi / T_i
  std::vector<double> T_match;
  std::vector<std::vector<double>> target_psa;  // m/s^2, per support, at T_match

  explicit Generator(const Settings& settings) : s(settings), n(settings.positions.size()), g(grid_of(settings)) {
    env.resize(g.steps);
    for (std::size_t p = 0; p < g.steps; ++p) env[p] = s.envelope(s.dt * static_cast<double>(p));
    twiddle.resize(g.fft / 2);
    for (std::size_t k = 0; k < twiddle.size(); ++k)
      twiddle[k] = std::polar(1.0, two_pi * static_cast<double>(k) / static_cast<double>(g.fft));
    const std::size_t N = g.n_freq;
    omega.resize(n * N);
    L.resize(n * N * n * n);
    std::vector<cplx> gamma(n * n);
    for (std::size_t m = 0; m < n; ++m)
      for (std::size_t l = 0; l < N; ++l) {
        const double w = (static_cast<double>(l) + static_cast<double>(m + 1) / static_cast<double>(n)) * g.d_omega;
        omega[m * N + l] = w;
        for (std::size_t j = 0; j < n; ++j)
          for (std::size_t k = 0; k < n; ++k)
            gamma[j * n + k] = j == k ? cplx{1.0, 0.0} : coherency_between(s, w, j, k);
        const auto f = cholesky(gamma, n);
        std::copy(f.begin(), f.end(), L.begin() + static_cast<std::ptrdiff_t>((m * N + l) * n * n));
      }
    T_match = matching_periods(s);
    for (double t : T_match) w_match.push_back(two_pi / t);
    target_psa.resize(n);
    for (std::size_t j = 0; j < n; ++j)
      for (double t : T_match) target_psa[j].push_back(s.target(j).sa(t) * g_accel);
  }

  // Starting one-sided PSD of support j at every w_ml (spatial.hpp).
  std::vector<double> initial_psd(std::size_t j) const {
    std::vector<double> G(omega.size(), 0.0);
    constexpr double r = 3.0;
    for (std::size_t i = 0; i < omega.size(); ++i) {
      const double w = omega[i], f = w / two_pi;
      if (f < s.f_min || f > s.f_max) continue;
      const double sa = s.target(j).sa(two_pi / w) * g_accel;
      G[i] = 4.0 * s.damping * sa * sa / (std::numbers::pi * w * r * r);
    }
    return G;
  }

  // f_j(t_p) for one support from its PSD and the phases exp(i Phi_ml); baseline-corrected.
  std::vector<double> history(std::size_t j, const std::vector<double>& G, const std::vector<cplx>& phase) const {
    const std::size_t N = g.n_freq, M = g.fft;
    std::vector<double> y(g.steps, 0.0);
    std::vector<cplx> z(M);
    const double scale = std::sqrt(2.0 * g.d_omega);
    for (std::size_t m = 0; m <= j; ++m) {
      std::fill(z.begin(), z.end(), cplx{0.0, 0.0});
      for (std::size_t l = 0; l < N; ++l) {
        const std::size_t i = m * N + l;
        if (G[i] <= 0.0) continue;
        z[l] = scale * std::sqrt(G[i]) * L[i * n * n + j * n + m] * phase[i];
      }
      fft_plus(z, twiddle);
      // exp(i m' dw t_p / n), m' = m + 1: the double-indexed offset
      const double step = static_cast<double>(m + 1) / static_cast<double>(n) * g.d_omega * s.dt;
      for (std::size_t p = 0; p < g.steps; ++p) y[p] += (std::polar(1.0, step * static_cast<double>(p)) * z[p]).real();
    }
    for (std::size_t p = 0; p < g.steps; ++p) y[p] *= env[p];
    baseline_correct(y, env, s.dt);
    return y;
  }
};

}  // namespace

namespace {

Realisation simulate_with(const Generator& gen, std::uint64_t index, const WorkHook* hook) {
  const Settings& s = gen.s;
  const std::size_t n = gen.n, N = gen.g.n_freq;
  const std::uint64_t key = realisation_key(s.seed, index);
  std::vector<cplx> phase(n * N);
  for (std::size_t i = 0; i < phase.size(); ++i) phase[i] = std::polar(1.0, two_pi * uniform(key, i));
  Realisation out;
  out.index = index;
  out.supports.resize(n);
  out.misfit.assign(n, 0.0);
  out.updates.assign(n, 0);
  // Each support's matching needs only its own row of H = D L (its PSD and the shared phases), so the
  // supports iterate independently.
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<double> G = gen.initial_psd(j);
    Record rec;
    rec.dt = s.dt;
    rec.name = fmt::format("r{:03}_s{:02}", index + 1, j + 1);
    rec.source = fmt::format("synthetic:spatial seed {} realisation {} support {}", s.seed, index + 1, j + 1);
    for (int it = 0;; ++it) {
      rec.acc = gen.history(j, G, phase);
      const Spectrum sp = response_spectrum(rec, gen.T_match, s.damping);
      std::vector<double> ratio(gen.T_match.size());
      double worst = 0.0;
      for (std::size_t i = 0; i < ratio.size(); ++i) {
        ratio[i] = gen.target_psa[j][i] / sp.psa[i];
        worst = std::max(worst, std::abs(sp.psa[i] / gen.target_psa[j][i] - 1.0));
      }
      out.misfit[j] = worst;
      out.updates[j] = it;
      if (it >= s.iterations || worst <= s.tolerance || (hook && hook->cancelled())) break;
      for (std::size_t i = 0; i < G.size(); ++i) {
        const double r = ratio_at(gen.omega[i], gen.w_match, ratio);
        G[i] *= r * r;
      }
    }
    out.supports[j] = std::move(rec);
  }
  return out;
}

}  // namespace

Realisation simulate(const Settings& s, std::uint64_t index, const WorkHook* hook) {
  validate(s);
  return simulate_with(Generator(s), index, hook);
}

std::vector<Realisation> simulate_all(const Settings& s, std::uint64_t first, std::size_t count, const WorkHook* hook) {
  validate(s);
  const Generator gen(s);
  Meter meter(hook, "motions: realisations", count, "realisations");
  std::vector<Realisation> out;
  out.reserve(count);
  for (std::size_t r = 0; r < count; ++r) {
    if (meter.stopped()) break;
    out.push_back(simulate_with(gen, first + r, hook));
    if (!meter.step()) break;
  }
  meter.finish();
  return out;
}

}  // namespace pounding::spatial
