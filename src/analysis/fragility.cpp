// Lognormal fragility fits (include/pounding/analysis/fragility.hpp).
#include "pounding/analysis/fragility.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <boost/math/distributions/normal.hpp>

namespace pounding {

namespace {

constexpr double kTailSwitch = -30.0;  // below it, the asymptotic series of Phi (erfc would underflow at -38)

// 1 - 1/u^2 + 3/u^4 - 15/u^6 + 105/u^8: Phi(u) = phi(u) / (-u) * series, u -> -infinity.
double tail_series(double u) {
  const double v = 1.0 / (u * u);
  return 1.0 - v * (1.0 - 3.0 * v * (1.0 - 5.0 * v * (1.0 - 7.0 * v)));
}

// Mills-type ratio phi(u) / Phi(u), stable for all u.
double phi_over_cdf(double u) {
  if (u < kTailSwitch) return -u / tail_series(u);
  const double phi = std::exp(-0.5 * u * u) / std::sqrt(2.0 * std::numbers::pi);
  return phi / normal_cdf(u);
}

struct Pooled {
  std::vector<double> x;  // ln level, increasing
  std::vector<double> level;
  std::vector<double> n, z;
};

Pooled validate_and_pool(std::span<const Stripe> stripes) {
  std::vector<Stripe> s(stripes.begin(), stripes.end());
  for (const Stripe& t : s) {
    if (!std::isfinite(t.level) || t.level <= 0) throw std::invalid_argument("fragility: stripe level must be > 0");
    if (t.n < 1) throw std::invalid_argument("fragility: stripe must have n >= 1 trials");
    if (t.z < 0 || t.z > t.n) throw std::invalid_argument("fragility: stripe needs 0 <= z <= n");
  }
  std::sort(s.begin(), s.end(), [](const Stripe& a, const Stripe& b) { return a.level < b.level; });
  Pooled p;
  for (const Stripe& t : s) {
    if (!p.level.empty() && p.level.back() == t.level) {
      p.n.back() += static_cast<double>(t.n);
      p.z.back() += static_cast<double>(t.z);
      continue;
    }
    p.level.push_back(t.level);
    p.x.push_back(std::log(t.level));
    p.n.push_back(static_cast<double>(t.n));
    p.z.push_back(static_cast<double>(t.z));
  }
  if (p.level.size() < 2) throw std::invalid_argument("fragility: need at least 2 distinct IM levels");
  return p;
}

std::string describe(const char* what, double a, double b) {
  std::ostringstream os;
  os.precision(6);
  os << what << a;
  if (!std::isnan(b)) os << ", " << b;
  return os.str();
}

// The cases without a finite MLE; returns true (and fills `fit`) when one applies.
bool classify_degenerate(const Pooled& p, FragilityFit& fit) {
  const std::size_t m = p.level.size();
  double trials = 0, hits = 0;
  for (std::size_t j = 0; j < m; ++j) trials += p.n[j], hits += p.z[j];
  if (hits == 0) {
    fit.status = FragilityStatus::no_pounding;
    fit.bound = 1.0 - std::pow(0.05, 1.0 / trials);
    fit.message = describe("no pounding observed; 95 % upper bound on P at the highest level: ", fit.bound, NAN);
    return true;
  }
  if (hits == trials) {
    fit.status = FragilityStatus::all_pounded;
    fit.bound = std::pow(0.05, 1.0 / trials);
    fit.message = describe("pounding in every trial; 95 % lower bound on P at the lowest level: ", fit.bound, NAN);
    return true;
  }
  std::size_t first = 0;
  while (p.z[first] == 0) ++first;  // exists: hits > 0
  const bool mixed = p.z[first] < p.n[first];
  for (std::size_t j = first + 1; j < m; ++j)
    if (p.z[j] < p.n[j]) return false;
  fit.status = FragilityStatus::separated;
  fit.bracket = mixed ? Interval{p.level[first], p.level[first]} : Interval{p.level[first - 1], p.level[first]};
  fit.message = describe("separated data (beta -> 0): no finite MLE; theta in ", fit.bracket.lo, fit.bracket.hi);
  return true;
}

struct Score {
  double ll = 0;
  std::array<double, 2> g{};
  std::array<double, 3> info{};  // I00, I01, I11
};

Score score(const Pooled& p, double a, double c) {
  Score s;
  for (std::size_t j = 0; j < p.x.size(); ++j) {
    const double eta = a + c * p.x[j];
    const double n = p.n[j], z = p.z[j];
    s.ll += z * log_normal_cdf(eta) + (n - z) * log_normal_cdf(-eta);
    const double mp = phi_over_cdf(eta), mm = phi_over_cdf(-eta);
    const double gj = z * mp - (n - z) * mm;
    const double w = n * mp * mm;  // n phi^2 / (Phi (1 - Phi))
    s.g[0] += gj, s.g[1] += gj * p.x[j];
    s.info[0] += w, s.info[1] += w * p.x[j], s.info[2] += w * p.x[j] * p.x[j];
  }
  return s;
}

// Weighted least squares on the empirical probits (z + 1/2) / (n + 1): the scoring's start.
std::array<double, 2> start_values(const Pooled& p) {
  const boost::math::normal_distribution<double> nd;
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t j = 0; j < p.x.size(); ++j) {
    const double y = boost::math::quantile(nd, (p.z[j] + 0.5) / (p.n[j] + 1.0));
    const double w = p.n[j];
    sw += w, sx += w * p.x[j], sy += w * y, sxx += w * p.x[j] * p.x[j], sxy += w * p.x[j] * y;
  }
  const double det = sw * sxx - sx * sx;
  double c = det > 0 ? (sw * sxy - sx * sy) / det : 0;
  if (!(c > 0)) c = 1.0;
  return {(sy - c * sx) / sw, c};
}

double binomial_constants(const Pooled& p) {
  double s = 0;
  for (std::size_t j = 0; j < p.n.size(); ++j)
    s += std::lgamma(p.n[j] + 1) - std::lgamma(p.z[j] + 1) - std::lgamma(p.n[j] - p.z[j] + 1);
  return s;
}

void fill_result(const Pooled& p, double a, double c, const Score& s, FragilityFit& fit) {
  const double det = s.info[0] * s.info[2] - s.info[1] * s.info[1];
  const double v00 = s.info[2] / det, v01 = -s.info[1] / det, v11 = s.info[0] / det;
  // (ln theta, beta) = (-a / c, 1 / c): gradients (-1/c, a/c^2) and (0, -1/c^2).
  const double ga0 = -1.0 / c, ga1 = a / (c * c), gb1 = -1.0 / (c * c);
  fit.status = FragilityStatus::ok;
  fit.fragility = {std::exp(-a / c), 1.0 / c};
  fit.se_log_theta = std::sqrt(ga0 * ga0 * v00 + 2 * ga0 * ga1 * v01 + ga1 * ga1 * v11);
  fit.se_beta = std::abs(gb1) * std::sqrt(v11);
  fit.neg_log_likelihood = -(s.ll + binomial_constants(p));
  fit.message = "converged";
  // A maximum far outside the stripes can overflow or underflow theta (e.g. a median many decades below the lowest
  // level, where everything pounds): never an "ok" fit with theta 0 or infinite.
  const double lo = p.level.front(), hi = p.level.back();
  if (!(std::isfinite(fit.fragility.theta) && fit.fragility.theta > 1e-6 * lo && fit.fragility.theta < 1e6 * hi &&
        std::isfinite(fit.fragility.beta) && fit.fragility.beta > 0)) {
    fit.status = FragilityStatus::not_converged;
    std::ostringstream m;
    m << "the likelihood's maximum lies far outside the stripes (theta = " << fit.fragility.theta
      << ", beta = " << fit.fragility.beta << "): no fit; add stripes where P is between 0 and 1";
    fit.message = m.str();
  }
}

}  // namespace

double normal_cdf(double u) { return 0.5 * std::erfc(-u / std::numbers::sqrt2); }

double log_normal_cdf(double u) {
  if (u < kTailSwitch)
    return -0.5 * u * u - std::log(-u) - 0.5 * std::log(2.0 * std::numbers::pi) + std::log(tail_series(u));
  if (u < 0) return std::log(normal_cdf(u));
  return std::log1p(-normal_cdf(-u));
}

double LognormalFragility::operator()(double x) const {
  if (!(x > 0)) return 0.0;
  if (beta == 0) return x >= theta ? 1.0 : 0.0;
  return normal_cdf(std::log(x / theta) / beta);
}

const char* to_string(FragilityStatus s) {
  switch (s) {
    case FragilityStatus::ok: return "ok";
    case FragilityStatus::no_pounding: return "no_pounding";
    case FragilityStatus::all_pounded: return "all_pounded";
    case FragilityStatus::separated: return "separated";
    case FragilityStatus::decreasing: return "decreasing";
    case FragilityStatus::not_converged: return "not_converged";
  }
  return "?";
}

FragilityFit fit_fragility_msa(std::span<const Stripe> stripes) {
  const Pooled p = validate_and_pool(stripes);
  FragilityFit fit;
  if (classify_degenerate(p, fit)) return fit;
  auto [a, c] = start_values(p);
  Score s = score(p, a, c);
  for (int it = 1; it <= 200; ++it) {
    fit.iterations = it;
    const double det = s.info[0] * s.info[2] - s.info[1] * s.info[1];
    const double da = (s.info[2] * s.g[0] - s.info[1] * s.g[1]) / det;
    const double dc = (s.info[0] * s.g[1] - s.info[1] * s.g[0]) / det;
    double t = 1.0;
    Score next = score(p, a + da, c + dc);
    while (!(next.ll >= s.ll - 1e-12 * std::abs(s.ll)) && t > 1e-10) {
      t *= 0.5;
      next = score(p, a + t * da, c + t * dc);
    }
    a += t * da, c += t * dc, s = next;
    if (!std::isfinite(a) || !std::isfinite(c) || std::abs(c) > 1e8) break;
    if (std::abs(t * da) + std::abs(t * dc) <= 1e-12 * (1.0 + std::abs(a) + std::abs(c))) {
      if (c <= 0) {
        fit.status = FragilityStatus::decreasing;
        fit.message = "the best probit fit decreases with IM: no lognormal fragility";
        return fit;
      }
      fill_result(p, a, c, s, fit);
      return fit;
    }
  }
  fit.status = c < 0 ? FragilityStatus::decreasing : FragilityStatus::not_converged;
  fit.message = c < 0 ? "pounding decreases with IM: no lognormal fragility" : "the MLE did not converge";
  return fit;
}

LognormalFragility fit_fragility_moments(std::span<const double> capacities) {
  if (capacities.size() < 2) throw std::invalid_argument("fragility: need at least 2 capacities");
  double sum = 0;
  for (double c : capacities) {
    if (!std::isfinite(c) || c <= 0) throw std::invalid_argument("fragility: capacities must be > 0");
    sum += std::log(c);
  }
  const double mean = sum / static_cast<double>(capacities.size());
  double ss = 0;
  for (double c : capacities) ss += (std::log(c) - mean) * (std::log(c) - mean);
  return {std::exp(mean), std::sqrt(ss / static_cast<double>(capacities.size() - 1))};
}

}  // namespace pounding
