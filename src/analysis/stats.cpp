// Binomial intervals, the cubic fit of probability against gap ratio and the CQC correlation (analysis/stats.hpp).
#include "pounding/analysis/stats.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pounding {

Interval wilson_interval(std::int64_t k, std::int64_t n, double z) {
  if (n <= 0) return {0.0, 1.0};
  return wilson_interval_effective(static_cast<double>(k) / static_cast<double>(n), static_cast<double>(n), z);
}

Interval wilson_interval_effective(double p, double nn, double z) {
  if (!(nn > 0)) return {0.0, 1.0};
  const double z2 = z * z;
  const double den = 1.0 + z2 / nn;
  const double centre = (p + z2 / (2.0 * nn)) / den;
  const double half = z * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn)) / den;
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

ClusteredInterval wilson_clustered(std::span<const double> hits, std::span<const double> sizes, double z) {
  if (hits.size() != sizes.size()) throw std::invalid_argument("wilson_clustered: hits and sizes differ in length");
  double k = 0, n = 0, C = 0;
  for (std::size_t c = 0; c < hits.size(); ++c)
    if (sizes[c] > 0) k += hits[c], n += sizes[c], ++C;
  if (!(n > 0)) return {{0.0, 1.0}, 0.0};
  const double p = k / n;
  double n_eff = C;
  if (p > 0.0 && p < 1.0 && C > 1) {
    double v = 0;
    for (std::size_t c = 0; c < hits.size(); ++c)
      if (sizes[c] > 0) v += (hits[c] - p * sizes[c]) * (hits[c] - p * sizes[c]);
    v *= C / (C - 1) / (n * n);
    n_eff = std::clamp(v > 0 ? p * (1 - p) / v : n, C, n);
  }
  return {wilson_interval_effective(p, n_eff, z), n_eff};
}

CubicFit fit_cubic(std::span<const double> x, std::span<const double> y) {
  if (x.size() != y.size() || x.size() < 4) throw std::invalid_argument("fit_cubic needs >= 4 points");
  const Eigen::Index n = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd A(n, 4);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    double xi = x[static_cast<std::size_t>(i)];
    A(i, 0) = 1.0, A(i, 1) = xi, A(i, 2) = xi * xi, A(i, 3) = xi * xi * xi;
    b(i) = y[static_cast<std::size_t>(i)];
  }
  Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  CubicFit f;
  for (int k = 0; k < 4; ++k) f.c[static_cast<std::size_t>(k)] = c(k);
  double mean = b.mean(), ss_tot = (b.array() - mean).square().sum(), ss_res = (A * c - b).squaredNorm();
  f.r2 = ss_tot > 0 ? 1.0 - ss_res / ss_tot : 1.0;
  return f;
}

std::optional<double> solve_fit(const CubicFit& f, double target, double lo, double hi) {
  const int n = 2000;
  double xa = lo, ya = f(lo) - target;
  if (ya == 0.0) return lo;
  for (int i = 1; i <= n; ++i) {
    double xb = lo + (hi - lo) * i / n, yb = f(xb) - target;
    if ((ya > 0) != (yb > 0) || yb == 0.0) {
      for (int it = 0; it < 100; ++it) {
        double xm = 0.5 * (xa + xb), ym = f(xm) - target;
        if ((ya > 0) == (ym > 0)) xa = xm, ya = ym;
        else xb = xm;
      }
      return 0.5 * (xa + xb);
    }
    xa = xb, ya = yb;
  }
  return std::nullopt;
}

double cqc_rho(double r, double z) {
  double num = 8.0 * z * z * (1.0 + r) * std::pow(r, 1.5);
  double den = (1.0 - r * r) * (1.0 - r * r) + 4.0 * z * z * r * (1.0 + r) * (1.0 + r);
  return num / den;
}

}  // namespace pounding
