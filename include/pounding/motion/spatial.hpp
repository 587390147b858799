#pragma once
// Spatially varying, spectrum-compatible support motions (issue 26 section 2): one acceleration history per
// support of a bridge, with the loss of coherency and the wave passage between supports, each compatible with
// a design spectrum. Formulas, sources and test vectors: ../shared/research/systems-and-bridges.md section 6.
//
// Simulation: Deodatis (1996), "Non-stationary stochastic vector processes: seismic ground motion
// applications", Probabilistic Engineering Mechanics 11(3):149-167 -- the spectral representation of an
// n-variate process with double-indexed frequencies, here uniformly modulated:
//   S(w) = D(w) Gamma(w) D(w),  D = diag(sqrt(G_j(w))),  Gamma_jk(w) = |gamma_jk(w)| exp(-i w (x_j - x_k)/v_app),
//   Gamma(w) = L(w) L(w)^H (lower-triangular Cholesky; S = H H^H with H = D L),
//   f_j(t) = A(t) sum_{m=1..j} sum_{l=0..N-1} sqrt(2 dw) sqrt(G_j(w_ml)) |L_jm(w_ml)| cos(w_ml t + arg L_jm(w_ml) + Phi_ml),
//   w_ml = l dw + m dw / n,   Phi_ml iid U[0, 2 pi) (one set for all supports j),
// summed with one FFT of length M per (j, m) (dw = 2 pi / (M dt)). G_j is the ONE-SIDED power spectral density
// (variance = int_0^inf G dw; Deodatis writes the two-sided S with a factor 2 in front, the same process). With
// the sign convention above a support downstream (x_k > x_j) receives the waves (x_k - x_j)/v_app later.
// Gamma_jk = |gamma| = 1 everywhere (no coherency loss) is singular: a pivot below 1e-10 of its diagonal makes
// its column zero, so pure wave passage is the same motion shifted in time.
//
// Spectrum compatibility: Deodatis' iteration on the auto-spectra, sample by sample with the same phases,
//   G_j^(i+1)(w) = G_j^(i)(w) [Sa_target,j(T) / PSA_j^(i)(T)]^2,  w = 2 pi / T,
// at the matching periods (ratio interpolated linearly in log w between them, held at the end values outside
// the band), until the largest |PSA/Sa - 1| over the band is <= tolerance or `iterations` updates were made.
// Because H = D L, the coherency (Gamma and its Cholesky factor) is untouched by the iteration. Starting PSD:
// G(w) = 4 zeta Sa(2 pi / w)^2 / (pi w r^2), r = 3 (the stationary response of an oscillator to white noise,
// sigma_a^2 = pi w G / (4 zeta), with a peak factor r); zero outside [f_min, f_max].
//
// Modulating function A(t): Jennings, Housner & Tsai (1968) -- (t / t1)^2 for t < t1 = rise, 1 up to
// t2 = rise + strong, exp(-decay (t - t2)) after. Baseline: every generated history (before each spectrum) is
// corrected by a(t) - A(t)(c0 + c1 t / T) with c0, c1 such that the velocity and the displacement at the end
// are zero (the integrals of records.hpp, linear acceleration between samples), so the ground displacements a
// multi-support analysis needs do not drift.
//
// Coherency models (|gamma| at separation xi >= 0 m, w in rad/s, f = w / 2 pi in Hz):
//   Sobczyk (1991), "Stochastic Wave Propagation", Elsevier/PWN: |gamma| = exp(-beta w xi^2 / v_app); beta =
//     0.0005 / 0.001 / 0.002 1/m as low / medium / high coherency loss ("highly / intermediately / weakly
//     correlated"), the sets used for bridge pounding by Bi, Hao & Chouw (e.g. EESD 40 (2011) 1027-1043) and
//     Chouw & Hao -- the group the bridge paper (Lindsay et al. 2011) belongs to. The bridge paper names neither
//     its coherency model nor its parameters (seeds-models.md 1.5): these sets are our choice (VERIFY the
//     values against the Bi-Hao-Chouw papers' PDFs).
//   Harichandran & Vanmarcke (1986), J. Eng. Mech. 112(2):154-174: rho = A exp(-2 xi (1 - A + alpha A)/(alpha
//     theta)) + (1 - A) exp(-2 xi (1 - A + alpha A)/theta), theta(f) = k [1 + (f/f0)^b]^(-1/2); SMART-1 Event 20:
//     A = 0.736, alpha = 0.147, k = 5210 m, f0 = 1.09 Hz, b = 2.78 (one published set: no loss levels).
//   Luco & Wong (1986), EESD 14(6):891-908: |gamma| = exp(-(a w xi)^2), a = alpha / v_s in s/m (2e-4 .. 3e-4).
//   none: |gamma| = 1 (wave passage only, or identical motions without it).
// The Harichandran-Vanmarcke parameters are the user's (hv_a, hv_alpha, hv_k, hv_f0, hv_b); the defaults are
// the Event 20 set above. T6.1 also lists the Event 24 set (A = 0.626, alpha = 0.022, k = 19700 m, f0 = 2.02 Hz,
// b = 3.47).
//
// Site response (Der Kiureghian 1996, "A coherency model for spatially varying ground motions", EESD
// 25(1):99-111): with a site filter per support, gamma_jk = |gamma(xi)| exp(i (theta_w + theta_s)),
//   theta_w = -w (x_j - x_k) / v_app (the wave passage above),
//   theta_s = atan2(Im H_j H_k*, Re H_j H_k*),  H(w) = (wg^2 + 2 i zg wg w) / (wg^2 - w^2 + 2 i zg wg w),
// wg = 2 pi f_g, the absolute-acceleration transfer function of the soil column (Kanai-Tajimi filter) at each
// support, in the same e^{+i w t} convention as the wave passage (the phase of j minus that of k). DK96 puts
// |H_k|^2 into the auto-PSD of support k as well; here each support's auto-PSD is its own target spectrum's
// (spectrum-compatible: the matching iteration would remove any |H_k|^2 to within its tolerance, and a site class
// per support already carries the amplification), so the site term changes the phase between the supports only.
// Randomness: the phases of realisation r are Phi_ml = 2 pi u, u from splitmix64 of a counter (key(seed, r) +
// m N + l) -- a pure function of (seed, r, m, l), so a realisation is the same bits whatever the order of work.
#include <atomic>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/core/enum_names.hpp"
#include "pounding/core/progress.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/records.hpp"

namespace pounding::spatial {

enum class CoherencyModel : std::uint8_t { sobczyk, harichandran_vanmarcke, luco_wong, none };
inline constexpr EnumName<CoherencyModel> coherency_model_names[] = {
    {CoherencyModel::sobczyk, "sobczyk"},
    {CoherencyModel::harichandran_vanmarcke, "harichandran-vanmarcke"},
    {CoherencyModel::luco_wong, "luco-wong"},
    {CoherencyModel::none, "none"}};
constexpr const auto& enum_names(CoherencyModel) { return coherency_model_names; }

enum class CoherencyLoss : std::uint8_t { low, medium, high };
inline constexpr EnumName<CoherencyLoss> coherency_loss_names[] = {
    {CoherencyLoss::low, "low"}, {CoherencyLoss::medium, "medium"}, {CoherencyLoss::high, "high"}};
constexpr const auto& enum_names(CoherencyLoss) { return coherency_loss_names; }

struct Coherency {
  CoherencyModel model = CoherencyModel::sobczyk;
  double beta = 0.001;  // Sobczyk, 1/m
  double hv_a = 0.736, hv_alpha = 0.147, hv_k = 5210.0, hv_f0 = 1.09, hv_b = 2.78;  // HV Event 20 (k m, f0 Hz)
  double lw_a = 2.5e-4;  // Luco-Wong alpha / v_s, s/m
  std::string describe() const;  // the model, its parameters and its source, one line
};
// A support's soil filter (Der Kiureghian 1996): predominant frequency f_g (Hz, wg = 2 pi f_g) and damping zeta_g.
struct Site {
  double frequency = 2.5;  // Hz
  double damping = 0.6;
};
// H(w) of the site (absolute acceleration over bedrock acceleration), w in rad/s.
std::complex<double> site_transfer(const Site& site, double w);
// theta_s = atan2(Im H_j H_k*, Re H_j H_k*) in rad (0 for the same site).
double site_phase(const Site& j, const Site& k, double w);
// Sobczyk's beta for a loss level (high loss = weak correlation = the largest beta).
double sobczyk_beta(CoherencyLoss loss);
// |gamma| at circular frequency w (rad/s), separation xi >= 0 (m), apparent velocity v_app (m/s, Sobczyk only).
double lagged_coherency(const Coherency& c, double w, double xi, double v_app);
// gamma_jk with the wave passage term exp(-i w (x_j - x_k)/v_app) (none when wave_passage is false).
std::complex<double> coherency(const Coherency& c, double w, double xj, double xk, double v_app, bool wave_passage);
// Lower-triangular L with L L^H = a (n x n Hermitian positive semi-definite, row-major); a pivot at or below
// 1e-10 times its diagonal entry of a makes that column zero (rank-deficient a, e.g. |gamma| = 1).
std::vector<std::complex<double>> cholesky(std::span<const std::complex<double>> a, std::size_t n);

// Jennings, Housner & Tsai (1968) modulating function.
struct Envelope {
  double rise = 2.0;    // t1, s
  double strong = 8.0;  // t2 - t1, s
  double decay = 0.5;   // 1/s
  double operator()(double t) const;
};

struct Settings {
  std::vector<double> positions;  // m, support j at x_j along the direction of propagation (at least 2)
  double velocity = 500.0;        // apparent wave velocity, m/s
  bool wave_passage = true;
  Coherency coherency;
  std::vector<Site> sites;              // one per support (Der Kiureghian's site response), or none (no site term)
  std::vector<DesignSpectrum> targets;  // one for every support, or one for all
  double damping = 0.05;                // of the target and of the matched spectra
  double dt = 0.01, duration = 20.0;    // s
  Envelope envelope;
  double f_min = 0.1, f_max = 25.0;     // Hz, band of the simulated PSD
  std::vector<double> match_periods;    // s, increasing (at least 2); empty: 30 log-spaced from 0.05 to 4 s
  int iterations = 10;                  // spectrum-matching updates at most (0: no matching)
  double tolerance = 0.10;              // largest |PSA / Sa - 1| over the band that ends the iteration
  std::uint64_t seed = 1;
  const DesignSpectrum& target(std::size_t support) const { return targets.size() == 1 ? targets[0] : targets[support]; }
};
// Gamma_jk(w) of the generator: coherency() of supports j and k, times exp(i theta_s) with site response.
std::complex<double> coherency_between(const Settings& s, double w, std::size_t j, std::size_t k);
// How a message names an option: `pounding motions`' --key-name (no `where`), or a study's
// [records.motions] key with its file:line (`where(key)`). Keys are the study's names (f_max, wave_passage, ...);
// on the command line f_max is --f-max and wave_passage is --no-wave-passage.
struct OptionNames {
  std::function<std::string(std::string_view key)> where;  // empty: the command line
  std::string name(std::string_view key) const;            // "--f-max" or "f_max"
  std::string at(std::string_view key) const;              // where an error points
};

// The user's options before any check: the options of `pounding motions` and the keys of a study's
// [records.motions] (defaults as documented there), and which of them were given. settings_from makes the
// Settings and runs every check of both (ranges and combinations: ONE set of messages), then validate().
struct Request {
  int supports = 2, match_points = 30, iterations = 10, realisations = 20, first = 1;
  double spacing = 100, velocity = 500, beta = 0, luco_wong_a = 2.5e-4, z = 0.4, r = 1.0, damping = 0.05, dt = 0.01,
         duration = 20, rise = 2, strong = 8, decay = 0.5, f_min = 0.1, f_max = 25, tolerance = 0.1;
  double hv_a = 0.736, hv_alpha = 0.147, hv_k = 5210.0, hv_f0 = 1.09, hv_b = 2.78;  // Coherency's defaults
  std::vector<double> positions, match_range{0.05, 4.0};
  std::vector<double> site_frequency, site_damping;  // Hz and ratio: one for all supports or one per support
  std::string coherency = "sobczyk", loss, spectrum = "nzs1170.5", spectrum_file;
  std::vector<std::string> soil;  // one site class for every support, or one per support
  bool wave_passage = true;
  std::uint64_t seed = 1;
  std::set<std::string, std::less<>> given;  // the keys the user gave
  bool has(std::string_view key) const { return given.find(key) != given.end(); }
};
Settings settings_from(const Request& r, const OptionNames& names = {});
// Throws InputError naming the setting (its command-line option or study key) and the allowed range.
void validate(const Settings& s, const OptionNames& names = {});
// One line naming the method and every setting (the README of `pounding motions`, a study's report).
std::string describe(const Settings& s);
// match_periods or its default.
std::vector<double> matching_periods(const Settings& s);

// The coherency the generator uses, as a table (`pounding motions --coherency-table`, the README of its folder):
// the model at frequencies f (Hz) and separations xi (m) -- |gamma|, theta_w = -2 pi f xi / v_app (the downstream
// point against the upstream one), gamma -- and, with site response, Gamma_jk of every pair of supports j > k
// (j downstream) with theta_s. Lines starting with '#' describe; then a header with units and one row per value.
std::string coherency_table(const Settings& s, std::span<const double> frequencies, std::span<const double> distances);
// The default separations of the table: every distinct distance between two supports.
std::vector<double> support_separations(const Settings& s);

// The frequency grid: dw = 2 pi / (M dt), N frequencies l = 0 .. N-1 (w_ml < 2 pi f_max), M >= 2 x steps.
struct Grid {
  std::size_t steps = 0, fft = 0, n_freq = 0;
  double d_omega = 0.0;
};
Grid grid_of(const Settings& s);

struct Realisation {
  std::uint64_t index = 0;
  std::vector<Record> supports;  // acc in m/s^2, one per support
  std::vector<double> misfit;    // per support: largest |PSA / Sa - 1| over the band (after the last update)
  std::vector<int> updates;      // per support: spectrum-matching updates made
};

// Realisation `index` (its phases depend on (seed, index) only). A raised hook stop ends the iteration early;
// the caller's Meter then throws Cancelled (see simulate_all).
Realisation simulate(const Settings& s, std::uint64_t index, const WorkHook* hook = nullptr);
// Realisations first .. first + count - 1, with progress ("motions: realisations") and stop: throws Cancelled.
std::vector<Realisation> simulate_all(const Settings& s, std::uint64_t first, std::size_t count,
                                      const WorkHook* hook = nullptr);

}  // namespace pounding::spatial
