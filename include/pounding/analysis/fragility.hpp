#pragma once
// Lognormal fragility curves P(pound | IM = x) = Phi(ln(x / theta) / beta) (issue 14).
//
// Multiple-stripe analysis (Baker 2015, Earthquake Spectra 31(1), eq. 11): stripe j has IM level x_j, n_j
// trials and z_j poundings; theta and beta maximise the binomial likelihood
//   l = sum_j [ln C(n_j, z_j) + z_j ln Phi(u_j) + (n_j - z_j) ln Phi(-u_j)],  u_j = ln(x_j / theta) / beta.
// The fit is the probit GLM P = Phi(alpha + gamma ln x) (theta = exp(-alpha / gamma), beta = 1 / gamma),
// whose log-likelihood is concave: Fisher scoring (IRLS) with step halving from a weighted least-squares
// start on the empirical probits, stopped when the step is below 1e-12 relative and the score is ~0.
// Stripes with z = 0 or z = n are kept (they carry information).
//
// Data without a finite MLE (Albert & Anderson 1984) are reported, never fitted into garbage numbers:
//   no_pounding     every z_j = 0: `bound` is the one-sided 95 % upper bound 1 - 0.05^(1/N) of P at the
//                   highest level (N = all trials, "rule of three");
//   all_pounded     every z_j = n_j: `bound` is the lower bound 0.05^(1/N) of P at the lowest level;
//   separated       (quasi-)complete separation: sorted by level, the stripes are all-zero, then at most one
//                   mixed stripe, then all-pounded (beta -> 0); `bracket` holds theta's range (lo, hi);
//   decreasing      the best fit has gamma <= 0 (P falls with IM): no lognormal fragility;
//   not_converged   scoring did not converge in 200 iterations.
// Only status ok carries a meaningful `fragility`. Stripes at equal levels are pooled.
#include <cstdint>
#include <span>
#include <string>

#include "pounding/analysis/stats.hpp"

namespace pounding {

// Standard normal CDF Phi and ln Phi (ln Phi is accurate far into the lower tail, u < -38 included).
double normal_cdf(double u);
double log_normal_cdf(double u);

struct LognormalFragility {
  double theta = 1;  // median, IM units
  double beta = 0;   // log standard deviation; 0 is a step at theta
  double operator()(double x) const;
};

struct Stripe {
  double level = 0;     // IM level x_j > 0
  std::int64_t n = 0;   // trials, >= 1
  std::int64_t z = 0;   // poundings, 0 <= z <= n
};

enum class FragilityStatus { ok, no_pounding, all_pounded, separated, decreasing, not_converged };
const char* to_string(FragilityStatus s);

struct FragilityFit {
  FragilityStatus status = FragilityStatus::not_converged;
  LognormalFragility fragility;  // valid only when ok()
  double se_log_theta = 0;       // standard errors from the expected information (binomial; too narrow
  double se_beta = 0;            //   when trials share records, see the research note 1.2)
  double neg_log_likelihood = 0; // -l including the binomial constants (ok only)
  int iterations = 0;
  Interval bracket;              // separated: theta lies in [lo, hi]
  double bound = 0;              // no_pounding / all_pounded: the one-sided 95 % bound on P
  std::string message;           // what happened, for a report
  bool ok() const { return status == FragilityStatus::ok; }
};

// Maximum-likelihood MSA fit. Throws std::invalid_argument for levels <= 0 or not finite, n < 1, z outside
// [0, n], or fewer than 2 distinct levels.
FragilityFit fit_fragility_msa(std::span<const Stripe> stripes);

// IDA / capacity fit by the method of moments (Baker 2015 eqs. 2-3): theta = exp(mean ln c),
// beta = sample standard deviation of ln c (divisor n - 1). Throws std::invalid_argument for fewer than 2
// capacities or any capacity <= 0 or not finite.
LognormalFragility fit_fragility_moments(std::span<const double> capacities);

}  // namespace pounding
