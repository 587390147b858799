// Hazard curves and the annual rate of pounding (include/pounding/analysis/hazard.hpp).
#include "pounding/analysis/hazard.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace pounding {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// c times the antiderivative of Phi((u - mu)/beta) k e^{-ku} du, without c:
//   A(u) = -e^{-ku} Phi((u - mu)/beta) + e^{-k mu + k^2 beta^2/2} Phi((u - mu + k beta^2)/beta),
// A(-inf) = 0, A(+inf) = e^{-k mu + k^2 beta^2/2}; evaluated in logs so neither term overflows.
double antiderivative(double u, double k, double mu, double beta) {
  const double shift = -k * mu + 0.5 * k * k * beta * beta;
  if (u == -kInf) return 0.0;
  if (u == kInf) return std::exp(shift);
  const double first = std::exp(-k * u + log_normal_cdf((u - mu) / beta));
  const double second = std::exp(shift + log_normal_cdf((u - mu + k * beta * beta) / beta));
  return second - first;
}

// integral of P(e^u) k c e^{-ku} du over [ua, ub] of one piece.
double integrate_piece(const HazardCurve::Piece& p, const std::function<double(double)>& frag, double tol) {
  using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
  if (p.ub == kInf) {  // s = e^{-k (u - ua)} in (0, 1]: c e^{-k ua} * integral_0^1 P(exp(ua - ln s / k)) ds
    auto f = [&](double s) { return s <= 0 ? frag(kInf) : frag(std::exp(p.ua - std::log(s) / p.k)); };
    return p.c * std::exp(-p.k * p.ua) * GK::integrate(f, 0.0, 1.0, 15, tol);
  }
  if (p.ua == -kInf) {  // v = ub - u in [0, inf): c k e^{-k ub} * integral P(exp(ub - v)) e^{kv} dv
    auto f = [&](double v) {
      const double pv = frag(std::exp(p.ub - v));
      return pv == 0 ? 0.0 : pv * std::exp(p.k * v);
    };
    return p.c * p.k * std::exp(-p.k * p.ub) * GK::integrate(f, 0.0, kInf, 15, tol);
  }
  auto f = [&](double u) { return frag(std::exp(u)) * p.k * p.c * std::exp(-p.k * u); };
  return GK::integrate(f, p.ua, p.ub, 15, tol);
}

// The pieces of the hazard cut at the grid points inside them.
std::vector<HazardCurve::Piece> refine(const HazardCurve& h, const NumericRateOptions& o) {
  double lo = o.x_lo, hi = o.x_hi;
  if (lo <= 0 || hi <= 0) {
    lo = 1e-3, hi = 1e3;
    if (h.is_table()) lo = std::exp(h.pieces().front().ub), hi = std::exp(h.pieces().back().ua);
  }
  if (!(hi > lo) || o.per_decade < 1) throw std::invalid_argument("pounding_rate_numeric: bad grid options");
  const double ulo = std::log(lo), uhi = std::log(hi);
  const int n = std::max(1, static_cast<int>(std::ceil(o.per_decade * (uhi - ulo) / std::log(10.0))));
  std::vector<double> grid;
  for (int i = 0; i <= n; ++i) grid.push_back(ulo + (uhi - ulo) * i / n);
  std::vector<HazardCurve::Piece> out;
  for (const HazardCurve::Piece& p : h.pieces()) {
    double a = p.ua;
    for (double g : grid)
      if (g > a && g < p.ub) out.push_back({a, g, p.c, p.k, p.tail}), a = g;
    out.push_back({a, p.ub, p.c, p.k, p.tail});
  }
  return out;
}

void check_positive(double v, const char* what) {
  if (!std::isfinite(v) || v <= 0) throw std::invalid_argument(what);
}

}  // namespace

HazardCurve HazardCurve::power_law(double k0, double k) {
  check_positive(k0, "hazard: power law needs k0 > 0");
  check_positive(k, "hazard: power law needs k > 0");
  HazardCurve h;
  h.lx_ = {0.0};
  h.ll_ = {std::log(k0)};
  h.raw_ = {k0};
  h.pieces_ = {{-kInf, 0.0, k0, k, false}, {0.0, kInf, k0, k, false}};
  return h;
}

HazardCurve HazardCurve::from_table(std::span<const double> im, std::span<const double> rate) {
  if (im.size() != rate.size()) throw std::invalid_argument("hazard: IM and rate columns differ in length");
  if (im.size() < 2) throw std::invalid_argument("hazard: a table needs at least 2 points");
  HazardCurve h;
  h.table_ = true;
  for (std::size_t i = 0; i < im.size(); ++i) {
    check_positive(im[i], "hazard: IMs must be > 0");
    check_positive(rate[i], "hazard: rates must be > 0");
    if (i > 0 && !(im[i] > im[i - 1])) throw std::invalid_argument("hazard: IMs must be strictly increasing");
    if (i > 0 && !(rate[i] < rate[i - 1])) throw std::invalid_argument("hazard: rates must be strictly decreasing");
    h.lx_.push_back(std::log(im[i]));
    h.ll_.push_back(std::log(rate[i]));
    h.raw_.push_back(rate[i]);
  }
  const std::size_t m = im.size();
  auto piece = [&](std::size_t i, double ua, double ub, bool tail) {
    const double k = (h.ll_[i] - h.ll_[i + 1]) / (h.lx_[i + 1] - h.lx_[i]);
    return Piece{ua, ub, std::exp(h.ll_[i] + k * h.lx_[i]), k, tail};
  };
  h.pieces_.push_back(piece(0, -kInf, h.lx_[0], true));
  for (std::size_t i = 0; i + 1 < m; ++i) h.pieces_.push_back(piece(i, h.lx_[i], h.lx_[i + 1], false));
  h.pieces_.push_back(piece(m - 2, h.lx_[m - 1], kInf, true));
  return h;
}

double HazardCurve::rate(double x) const {
  if (!(x > 0)) throw std::invalid_argument("hazard: rate(x) needs x > 0");
  const double u = std::log(x);
  for (std::size_t i = 0; i < lx_.size(); ++i)
    if (u == lx_[i]) return raw_[i];  // exact at the table's points
  const auto it = std::find_if(pieces_.begin(), pieces_.end(), [&](const Piece& p) { return u <= p.ub; });
  return it->c * std::exp(-it->k * u);
}

PoundingRate pounding_rate(const HazardCurve& hazard, const LognormalFragility& f) {
  check_positive(f.theta, "pounding_rate: theta must be > 0");
  if (!(f.beta >= 0) || !std::isfinite(f.beta)) throw std::invalid_argument("pounding_rate: beta must be >= 0");
  if (f.beta == 0) {
    const double u = std::log(f.theta);
    const bool tail = hazard.pieces().front().tail && (u < hazard.pieces().front().ub || u > hazard.pieces().back().ua);
    return {hazard.rate(f.theta), tail ? 1.0 : 0.0};
  }
  const double mu = std::log(f.theta);
  double total = 0, tails = 0;
  for (const HazardCurve::Piece& p : hazard.pieces()) {
    const double v = p.c * (antiderivative(p.ub, p.k, mu, f.beta) - antiderivative(p.ua, p.k, mu, f.beta));
    total += v;
    if (p.tail) tails += v;
  }
  return {total, total > 0 ? tails / total : 0.0};
}

RateShares rate_shares(const HazardCurve& hazard, const LognormalFragility& f, double x_low, double x_top) {
  const PoundingRate all = pounding_rate(hazard, f);  // validates f
  if (!(x_low > 0) || !(x_top >= x_low) || !std::isfinite(x_top)) throw std::invalid_argument("rate_shares: 0 < x_low <= x_top");
  if (!(all.rate > 0)) return {};
  const double ul = std::log(x_low), ut = std::log(x_top), mu = std::log(f.theta);
  if (f.beta == 0) return {mu < ul ? 1.0 : 0.0, mu > ut ? 1.0 : 0.0};
  double below = 0, above = 0;
  for (const HazardCurve::Piece& p : hazard.pieces()) {
    auto part = [&](double a, double b) {
      return b > a ? p.c * (antiderivative(b, p.k, mu, f.beta) - antiderivative(a, p.k, mu, f.beta)) : 0.0;
    };
    below += part(p.ua, std::min(p.ub, ul));
    above += part(std::max(p.ua, ut), p.ub);
  }
  return {std::clamp(below / all.rate, 0.0, 1.0), std::clamp(above / all.rate, 0.0, 1.0)};
}

PoundingRate pounding_rate_numeric(const HazardCurve& hazard, const std::function<double(double)>& fragility,
                                   const NumericRateOptions& options) {
  double total = 0, tails = 0;
  for (const HazardCurve::Piece& p : refine(hazard, options)) {
    const double v = integrate_piece(p, fragility, options.tolerance);
    total += v;
    if (p.tail) tails += v;
  }
  return {total, total > 0 ? tails / total : 0.0};
}

double pounding_rate_closed_form(double k0, double k, const LognormalFragility& f) {
  return k0 * std::pow(f.theta, -k) * std::exp(0.5 * k * k * f.beta * f.beta);
}

double probability_in_years(double rate, double years) {
  if (!(rate >= 0) || !(years >= 0)) throw std::invalid_argument("probability_in_years: needs rate, years >= 0");
  return -std::expm1(-rate * years);
}

double rate_for_probability(double p, double years) {
  if (!(p >= 0 && p < 1) || !(years > 0)) throw std::invalid_argument("rate_for_probability: needs 0 <= p < 1, years > 0");
  return -std::log1p(-p) / years;
}

}  // namespace pounding
