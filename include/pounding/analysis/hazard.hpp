#pragma once
// Seismic hazard curves and the annual rate of pounding (issue 14).
//
//   lambda_P = integral of P(pound | x) |d lambda_IM(x)|,   P_T = 1 - exp(-lambda_P T) (Poisson).
//
// A hazard curve is a chain of power laws lambda(x) = c x^-k in u = ln x:
//   * power_law(k0, k): lambda(x) = k0 x^-k for all x > 0;
//   * from_table(im, rate): straight lines in (ln x, ln lambda) between the points (exact at the points).
//     Beyond the table the end segments are extended as power laws to x -> 0 and x -> infinity (the research
//     note, section 2): no truncation, and the share of lambda_P from the extrapolated tails is reported so a
//     caller can warn when it is not small (say > 1 %).
// With a lognormal fragility each power-law piece integrates in closed form, so pounding_rate() has no
// quadrature error; over a single power law it is Cornell et al. (2002): lambda_P = k0 theta^-k exp(k^2 beta^2/2).
// pounding_rate_numeric() takes any fragility P(x) (a tabulated one, say): adaptive Gauss-Kronrod on a log grid
// of `per_decade` pieces per decade over [x_lo, x_hi] split at the table's points, and the tails beyond by
// substitutions that make them finite-range (upper) or half-infinite with a decaying integrand (lower).
#include <functional>
#include <span>
#include <vector>

#include "pounding/analysis/fragility.hpp"

namespace pounding {

class HazardCurve {
 public:
  // Throws std::invalid_argument unless k0 > 0 and k > 0 (finite).
  static HazardCurve power_law(double k0, double k);
  // Throws std::invalid_argument unless there are >= 2 points, the IMs are > 0 and strictly increasing and the
  // rates are > 0 and strictly decreasing (all finite), and im and rate have the same length.
  static HazardCurve from_table(std::span<const double> im, std::span<const double> rate);

  double rate(double x) const;  // annual rate of IM > x; x > 0

  // One power-law piece lambda = c x^-k on ln x in [ua, ub] (ua may be -inf, ub +inf).
  struct Piece {
    double ua, ub, c, k;
    bool tail;  // an extrapolated end segment beyond the table (never for a power law)
  };
  const std::vector<Piece>& pieces() const { return pieces_; }
  bool is_table() const { return table_; }

 private:
  std::vector<double> lx_, ll_, raw_;  // ln x, ln lambda and lambda at the points
  std::vector<Piece> pieces_;
  bool table_ = false;
};

struct PoundingRate {
  double rate = 0;        // lambda_P, per year
  double tail_share = 0;  // fraction of lambda_P from beyond the table (0 for a power law)
};

// Exact for a lognormal fragility (beta = 0: the step, lambda_P = lambda(theta)).
PoundingRate pounding_rate(const HazardCurve& hazard, const LognormalFragility& fragility);

struct NumericRateOptions {
  double x_lo = 0, x_hi = 0;  // grid range; 0 = the table's range, or [1e-3, 1e3] for a power law
  int per_decade = 20;
  double tolerance = 1e-10;   // relative, per piece
};
// Any fragility with P(0+) = 0, 0 <= P <= 1, increasing.
PoundingRate pounding_rate_numeric(const HazardCurve& hazard, const std::function<double(double)>& fragility,
                                   const NumericRateOptions& options = {});

// The shares of pounding_rate(hazard, fragility).rate from IM below x_low and above x_top (a fragility study's lowest
// and highest stripe: where the fitted curve is extrapolated rather than fitted to data), exact like the rate
// itself; beta = 0 puts the whole rate where theta lies. Throws as pounding_rate does, or unless 0 < x_low <= x_top.
struct RateShares {
  double below = 0, above = 0;
};
RateShares rate_shares(const HazardCurve& hazard, const LognormalFragility& fragility, double x_low, double x_top);

// Cornell, Jalayer, Hamburger & Foutch (2002): k0 theta^-k exp(k^2 beta^2 / 2).
double pounding_rate_closed_form(double k0, double k, const LognormalFragility& fragility);

// 1 - exp(-rate * years), computed as -expm1 so small rate * years keeps its digits. Throws for rate < 0 or
// years < 0.
double probability_in_years(double rate, double years);
// The inverse: -ln(1 - p) / years for p in [0, 1), years > 0.
double rate_for_probability(double p, double years);

}  // namespace pounding
