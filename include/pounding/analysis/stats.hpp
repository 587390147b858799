#pragma once
// Statistics for the study's tables: binomial intervals, the cubic fit of probability versus gap ratio,
// the CQC correlation used by the double-difference separation rule.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

namespace pounding {

struct Interval {
  double lo = 0, hi = 0;
};
// 95 % Wilson score interval for k successes out of n (z = 1.959963984540054).
Interval wilson_interval(std::int64_t k, std::int64_t n, double z = 1.959963984540054);
// The same score interval at an observed fraction p with an effective sample size n (not necessarily p n
// successes of n trials: e.g. n independent records behind a fraction of their analyses).
Interval wilson_interval_effective(double p, double n, double z = 1.959963984540054);
// The Wilson interval of a share whose 0/1 outcomes come in clusters (e.g. a record's polarities and models), from the
// clusters' successes `hits` and sizes `sizes`: Wilson at the observed fraction p with Kish's effective sample size
// n_eff = n / DEFF (Kish 1965 §5.4; Korn & Graubard 1998), DEFF from the cluster totals (v_clu = C/(C-1) sum_c
// (y_c - p m_c)^2 / n^2 against v_srs = p (1 - p) / n), n_eff clipped to [C, n]; n_eff = C when p is 0 or 1 or C = 1.
// The same estimator as tools/pounding_plots.py wilson_clustered.
struct ClusteredInterval {
  Interval w;
  double n_eff = 0;
};
ClusteredInterval wilson_clustered(std::span<const double> hits, std::span<const double> sizes,
                                   double z = 1.959963984540054);

// Least-squares polynomial y = c3 x^3 + c2 x^2 + c1 x + c0 (solved with Eigen's QR) and its R^2.
struct CubicFit {
  std::array<double, 4> c{};  // c[0] + c[1] x + c[2] x^2 + c[3] x^3
  double r2 = 0;
  double operator()(double x) const { return ((c[3] * x + c[2]) * x + c[1]) * x + c[0]; }
};
CubicFit fit_cubic(std::span<const double> x, std::span<const double> y);
// Smallest x in [lo, hi] where the fit equals `target` (bisection on a sign change found by scanning),
// or nothing when the fit does not cross it there.
std::optional<double> solve_fit(const CubicFit& f, double target, double lo, double hi);

// CQC modal correlation for equal damping z and frequency ratio r = omega1/omega2:
// rho = 8 z^2 (1 + r) r^1.5 / ((1 - r^2)^2 + 4 z^2 r (1 + r)^2).
double cqc_rho(double r, double z);

}  // namespace pounding
