#pragma once
// Site-based stochastic ground motions: Rezaeian & Der Kiureghian (2010), "Simulation of synthetic
// ground motions for specified earthquake and site characteristics", EESD 39:1155-1180.
//
//   x(t) = q(t) * sum_i s_i(t) u_i,   u_i iid N(0,1) at t_i = i dt,
//   s_i(t) = h[t - t_i] / sqrt(sum_{t_j <= t} h[t - t_j]^2),
//   h(t - tau) = w_f(tau)/sqrt(1 - z_f^2) exp(-z_f w_f(tau)(t - tau)) sin(w_f(tau) sqrt(1 - z_f^2)(t - tau)),
//   w_f(tau) = w_mid + w'(tau - t_mid)   (floored at 2 pi f_min: the linear law turns negative late in
//                                         long records with steep negative w'; R&DK's filter needs w_f > 0)
//   q(t) = a1 t^(a2 - 1) exp(-a3 t)      (gamma envelope: q^2 is a Gamma(2 a2 - 1, 1/(2 a3)) density shape)
// followed by a critically damped high-pass oscillator at 0.1 Hz, u'' + 2 w_c u' + w_c^2 u = x, whose
// acceleration u'' is the motion (Newmark average acceleration).
//
// Since every s_i(t) is normalised, E[x(t)^2] = q(t)^2 and the model's Arias intensity is
// Ia = pi/(2 g) int q^2 dt. D5-95 and t_mid are the 5-95 % and 45 % points of int q^2.
//
// Cost: the sum is evaluated with one complex recurrence per impulse (h of impulse i is Im of
// c_i rho_i^m, rho_i = exp((-z_f + i sqrt(1 - z_f^2)) w_i dt)), and an impulse leaves the sum once its
// envelope exp(-z_f w_i (t - t_i)) has decayed below `truncation` (1e-10): O(N L) with L the filter's
// memory in steps (a few hundred for typical parameters), at most O(N^2 / 2).
//
// Randomness: Boost's mt19937_64 seeded with the seed; uniforms from its 53 high bits; normals by
// Wichura's AS241 inverse CDF (one uniform each). No std:: distribution is used, so a seed gives the
// same record with any standard library.
#include <array>
#include <cstdint>
#include <string>

#include "pounding/motion/records.hpp"

namespace pounding {

struct SiteParams {
  double M = 0.0;     // moment magnitude
  double R_km = 0.0;  // rupture distance, km
  double vs30 = 0.0;  // m/s
  int F = 0;          // 0 strike-slip, 1 reverse or reverse-oblique
};
// Throws InputError (naming `where` and the key) unless 4 <= M <= 9, 0 < R <= 500 km, 50 <= Vs30 <= 3000
// m/s and F is 0 or 1.
void validate(const SiteParams& s, const std::string& where);

// The model's six physical parameters.
struct ModelParams {
  double arias_sg = 0;      // Ia, s*g
  double d5_95 = 0;         // s
  double t_mid = 0;         // s (time of 45 % Ia)
  double f_mid_hz = 0;      // w_mid / 2 pi
  double f_slope_hz_s = 0;  // w' / 2 pi
  double zeta_f = 0;
};

using Normal6 = std::array<double, 6>;

// Predictive equations in standard-normal space: mu_i for (Ia, D5-95, t_mid, f_mid, f', zeta_f).
Normal6 predictive_mean(const SiteParams& s);
// theta_i = F_i^-1(Phi(nu_i)) with the published marginals.
ModelParams params_from_normal(const Normal6& nu);
// Model parameters at eps = 0 (the median of each parameter).
ModelParams median_params(const SiteParams& s);
// Correlated errors: eps = L z with L the Cholesky factor of diag(sd) C diag(sd).
Normal6 correlated_errors(const Normal6& z);
// The error covariance (row-major 6x6), for tests.
std::array<double, 36> error_covariance();

// Marginal inverse CDFs (exposed for tests).
double standard_normal_quantile(double p);  // Wichura AS241 (PPND16), |rel err| < 1e-15
double standard_normal_cdf(double x);
double two_sided_exponential_quantile(double F, double a, double b, double c, double xmin, double xmax);

// The gamma envelope that reproduces (Ia, D5-95, t_mid) exactly: q(t) = a1 t^(a2-1) exp(-a3 t), q in m/s^2.
struct Envelope {
  double a1 = 0, a2 = 0, a3 = 0;
  double operator()(double t) const;
  double shape() const { return 2 * a2 - 1; }  // of the Gamma density q^2 / int q^2
  double rate() const { return 2 * a3; }
  double quantile(double p) const;  // time at which int_0^t q^2 reaches the fraction p
};
Envelope solve_envelope(double arias_sg, double d5_95, double t_mid);

struct SynthOptions {
  double dt = 0.01;             // s
  double duration = 0.0;        // s; 0: until int q^2 reaches 99.95 % (at least t95 + 5 s)
  double f_min_hz = 0.3;        // floor of the filter frequency
  double highpass_hz = 0.1;     // corner of the critically damped high-pass oscillator; 0 disables it
  double pga_g = 0.0;           // > 0: scale the final record to this PGA
  double truncation = 1e-10;    // an impulse leaves the sum when its envelope decays below this
};

// Simulates one record for given model parameters; `seed` drives the white noise u_i only.
Record simulate(const ModelParams& p, std::uint64_t seed, const SynthOptions& o = {});
// Site-based: draws eps (6 normals, correlated) and then the white noise from one stream of `seed`.
Record synthesize(const SiteParams& site, std::uint64_t seed, const SynthOptions& o = {});
// The model parameters synthesize() uses for (site, seed).
ModelParams sample_params(const SiteParams& site, std::uint64_t seed);

}  // namespace pounding
