#pragma once
// Pounding fragility curves and risk from multiple-stripe analysis (MSA) and from IDA capacities (issue 14).
//
// MSA. Every record r is amplitude-scaled to each IM level (stripe s) and every sampled model m (a pair of
// buildings) is analysed without contact; the pair pounds at gap x exactly when its peak closing D > x. At a
// gap x the stripe s therefore has n_s = #{counted D} trials and z_s(x) = #{D > x} poundings, and the fit is
// Baker's MLE (fragility.hpp). The counts come from a StripeIndex: each (stripe, record) slice is sorted once,
// and a count at any x is a binary search. A bootstrap replicate is a vector of record multiplicities: its
// counts are the slices' counts times the multiplicities, never a copy of the data.
//
// IDA. The capacity of (record r, model m) is the IM at which the pair first touches. Without censoring the
// fit is by moments (Baker eqs. 2-3: theta = exp(mean ln C), beta = sample standard deviation of ln C with the
// divisor n - 1); when some capacities are right-censored (no contact up to the record's largest analysed IM
// cap[r]) it is the censored lognormal MLE (the research note, 1.1 "truncated IDA"), found by Newton's method
// in Olsen's parametrisation (delta, tau) = (mu / sigma, 1 / sigma), where the log-likelihood is concave.
// For linear pairs one run per record at scale 1 gives the capacity at every gap exactly:
// C = im[r] x / D1 (the peak closing scales linearly with the record), so theta(x) = x theta(1) and beta does
// not depend on x as long as nothing is censored (the research note, 1.5).
//
// Intervals: the percentile cluster bootstrap over records (the research note, 1.2): a replicate draws R
// records with replacement, and every model stays with its record. Replicate b uses its own SplitMix64 stream
// derived from (seed, b) (as separation.cpp does), and replicates are split over threads in contiguous
// blocks, so the results are bit-identical for any thread count. One replicate's record draws serve every gap
// (coherent intervals across gaps) and, with the same seed, fit_msa and risk_targeted_gap see the same draws.
//
// Replicates whose fit is not ok are kept, never dropped: each replicate contributes a *range* [lo, hi]
// known to contain its value (an ok fit: the point [v, v]), and the interval is
//   lo = type-7 quantile (1 - confidence)/2 of the replicates' lower ends,
//   hi = type-7 quantile (1 + confidence)/2 of the replicates' upper ends,
// which is the ordinary percentile interval when every replicate is ok and can only widen otherwise.
// Coverage (tests/analysis/test_stripes.cpp, simulated studies with a record effect): theta's interval is close
// to nominal (95 %: 0.93 with 30 records, 0.95 with 100); beta's runs short with few records (0.83 / 0.875 / 0.90
// with 30 / 50 / 100 records) because beta-hat and, more so, the replicates' beta are biased low by the finite
// record sample, so report the number of records beside it. Ranges:
//                   theta               beta       annual rate (rate_of below)
//   ok              [theta, theta]      [b, b]     the exact rate
//   no_pounding     [x_top, +inf]       [0, +inf]  [0, its upper bound]
//   all_pounded     [0, x_low]          [0, +inf]  [its lower bound, +inf]
//   separated       [bracket]           [0, 0]     [lambda_IM(bracket.hi), lambda_IM(bracket.lo)]
//   decreasing,
//   not_converged   [0, +inf]           [0, +inf]  [0, +inf]
// (x_low, x_top: the lowest and highest stripe level of that fit). The probability interval is
// probability_in_years of the rate interval's ends (the map is increasing).
//
// Annual rate of a fit at stripe levels x_low <= ... <= x_top (rate_of in stripes.cpp, used for the point
// estimate, the replicates and the risk-targeted gap alike):
//   ok            pounding_rate(hazard, fit.fragility), exact, with its tail share;
//   separated     a step fragility at the bracket's geometric mean: lambda_IM(sqrt(lo hi)) (flagged);
//   no_pounding   an upper bound: P <= bound (fit.bound, 1 - 0.05^(1/N)) up to x_top and P <= 1 above, so
//                 lambda_P <= bound lambda_IM(x_low) + (1 - bound) lambda_IM(x_top); pounding below the lowest
//                 stripe is neglected (stripes should start where P is ~0) (flagged);
//   all_pounded   a lower bound: P >= bound at and above x_low, lambda_P >= bound lambda_IM(x_low) (flagged);
//   decreasing,
//   not_converged NaN.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pounding/analysis/fragility.hpp"
#include "pounding/analysis/hazard.hpp"
#include "pounding/analysis/stats.hpp"
#include "pounding/core/progress.hpp"

namespace pounding::stripes {

// MSA demands D[s][r][m], stripe-major: demand[(s * records + r) * models + m], already divided by each
// model's gap unit (the code gap d for gaps given as ratios of d; 1 for gaps in metres). NaN = not counted
// (a diverged or excluded analysis, or record r dropped from stripe s because its scale factor exceeded
// max_scale).
struct Demands {
  std::vector<double> levels;  // IM level of each stripe, > 0 (any order; equal levels are pooled by the fit)
  std::size_t records = 0, models = 0;
  std::vector<double> demand;  // levels.size() * records * models values
};

// The sorted slices behind fit_msa, risk_targeted_gap and rate_curve: counts at any gap by binary search. Build
// it once and pass it to their StripeIndex overloads when a study asks for several of them (the sort of 7.7 M
// demands is ~0.25 s on 2 cores).
class StripeIndex {
 public:
  // Validates (see fit_msa) and sorts each (stripe, record) slice; `threads` share the sorting.
  explicit StripeIndex(const Demands& demands, int threads = 1);
  std::size_t stripes() const { return levels_.size(); }
  std::size_t records() const { return records_; }
  double level(std::size_t s) const { return levels_[s]; }
  // Counted analyses of slice (s, r), and how many of them are <= x (an upper_bound position).
  std::int64_t counted(std::size_t s, std::size_t r) const;
  std::size_t at_or_below(std::size_t s, std::size_t r, double x) const;
  // The same, searched only between two known positions (first <= result <= last).
  std::size_t at_or_below(std::size_t slice, double x, std::size_t first, std::size_t last) const;
  // Stripes at gap x (n_s = sum_r w_r counted, z_s = sum_r w_r #{D > x}) for multiplicities w (empty: all 1);
  // stripes with n_s = 0 are left out.
  std::vector<Stripe> stripes_at(double x, std::span<const int> multiplicity = {}) const;
  double min_positive() const { return min_positive_; }  // smallest finite positive demand (NaN if none)
  double max_positive() const { return max_positive_; }  // largest finite positive demand

 private:
  std::vector<double> levels_;
  std::size_t records_ = 0;
  std::vector<double> sorted_;        // the finite demands, slice by slice, ascending inside each
  std::vector<std::size_t> offset_;   // slice (s * R + r) spans [offset_[i], offset_[i + 1])
  double min_positive_ = NAN, max_positive_ = NAN;
};

// IDA capacities at ONE gap: capacity[r * models + m] = the IM at which model m first touches under record r;
// +inf = no contact up to the record's largest analysed IM cap[r] (right-censored there); NaN = excluded.
// A finite capacity above cap[r] is treated as censored at cap[r].
struct Capacities {
  std::size_t records = 0, models = 0;
  std::vector<double> capacity;  // records * models
  std::vector<double> cap;       // per record, finite and > 0
};

// Capacities of linear pairs at gap x from one run per record at scale 1: capacity = im[r] x / demand1[r*M+m]
// (im: the records' own IM at scale 1, > 0). demand1 <= 0 (the pair never closes) and capacities above cap[r]
// are +inf (censored); NaN demand stays NaN. Throws std::invalid_argument on sizes that do not match, im or
// cap not finite and > 0, or x not finite and > 0.
Capacities linear_capacities(std::span<const double> im, std::span<const double> demand1, std::size_t models,
                             double x, std::span<const double> cap);

struct Settings {
  int bootstrap = 2000;      // replicates B; 0: no intervals (they are NaN)
  double confidence = 0.95;  // of the percentile intervals, in (0, 1)
  std::uint64_t seed = 1;    // the replicates' streams derive from it
  double years = 50;         // of probability = 1 - exp(-rate years)
  int threads = 0;           // 0: std::thread::hardware_concurrency(); the results do not depend on it
  // Progress of the bootstrap and jackknife loops, and a stop (core/progress.hpp): with the stop flag raised the
  // loops end within one replicate and the call throws Cancelled. Null: neither. The results do not depend on it.
  const WorkHook* hook = nullptr;
};

struct GapFragility {
  double gap = 0;                   // x, in the demands' gap unit
  FragilityFit fit;                 // point estimate (MSA: Baker MLE; IDA: moments, or the censored MLE when any
                                    //   capacity is censored; IDA fits leave se_* and neg_log_likelihood at 0)
  Interval theta_ci{NAN, NAN};      // percentile cluster bootstrap over records (ranges for failed replicates,
  Interval beta_ci{NAN, NAN};       //   see the top of this header); NaN without replicates
  int replicates = 0;               // B
  int replicates_failed = 0;        // replicates whose fit was not ok (kept, as ranges)
  std::vector<Stripe> observed;     // per stripe with counted analyses: level, n, z (IDA: at the levels given,
                                    //   n = counted capacities, z = those <= level; censored ones count as not
                                    //   pounded, also at levels above their cap)
  std::vector<double> fitted;       // the fitted P at each observed level (NaN unless fit.ok())
  bool has_hazard = false;          // the rate fields below are set only with a hazard curve
  double annual_rate = NAN;         // rate_of(fit) (see the top): exact for ok, else a flagged bound or NaN
  double rate_lo = NAN, rate_hi = NAN;                      // its bootstrap interval
  double probability = NAN;                                 // 1 - exp(-annual_rate years)
  double probability_lo = NAN, probability_hi = NAN;        // from rate_lo, rate_hi
  double tail_share = 0;            // share of annual_rate from the hazard table's extrapolated tails (ok only)
  double share_below = 0;           // share of annual_rate from IM below the lowest stripe (ok: the fitted curve
  double share_above = 0;           //   extrapolated; no_pounding / all_pounded: the bound's part) / above the highest
  std::string note;                 // the fit's message, and what a bound means when the rate is one
  std::vector<double> replicate_rate_lo, replicate_rate_hi;  // with a hazard: each replicate's rate range (B each),
                                    //   in replicate order; risk_targeted_gap_at_gaps joins them across gaps
  std::vector<double> jackknife_rate;  // with a hazard: the rate without record j (R values; NaN when that fit has
                                    //   no exact rate); risk_targeted_gap_at_gaps' jackknife
  double rate_jack_lo = NAN, rate_jack_hi = NAN;  // jackknife-t interval of ln annual_rate (ok fits; NaN when any
  double probability_jack_lo = NAN, probability_jack_hi = NAN;  //   jackknife_rate is not > 0): see TargetGap
};

// One GapFragility per gap (any order, > 0 finite). hazard may be null. Throws std::invalid_argument for
// inconsistent sizes, levels not finite and > 0, fewer than 2 stripes, bad settings.
std::vector<GapFragility> fit_msa(const Demands& demands, std::span<const double> gaps, const Settings& settings,
                                  const HazardCurve* hazard);
std::vector<GapFragility> fit_msa(const StripeIndex& index, std::span<const double> gaps, const Settings& settings,
                                  const HazardCurve* hazard);

// The IDA fit of capacities at one gap (reported in GapFragility::gap). `levels` only fill observed/fitted
// and give x_low for the no_pounding bound (may be empty). Fewer than 2 counted capacities: not_converged;
// every capacity censored: no_pounding, bound 1 - 0.05^(1/N) on P up to the smallest cap.
GapFragility fit_ida(const Capacities& capacities, std::span<const double> levels, const Settings& settings,
                     const HazardCurve* hazard, double gap);

struct TargetGap {
  double gap = NAN;             // x*: ok: the smallest gap with lambda_P(x) <= lambda_target; "below range": the
                                //   smallest gap searched (x* is at most it); "above range": the largest (x* is
                                //   beyond it)
  double lo = NAN, hi = NAN;    // percentile interval (replicates below range span [0, range_lo], above range
                                //   [range_hi, +inf])
  double lambda_target = 0;     // per year
  double rate = NAN;            // lambda_P(gap) of the point estimate
  double range_lo = NAN, range_hi = NAN;  // the gaps searched
  int replicates = 0, replicates_below = 0, replicates_above = 0;
  // Jackknife over records (status ok only): x*_(j) without record j (R solves), se = the jackknife standard error
  // of ln x*, sqrt((R - 1)/R sum (ln x*_(j) - mean)^2), and the interval x* exp(-+ t se), t the Student quantile
  // ((1 + confidence)/2, R - 1 degrees of freedom). NaN when R < 3 or some x*_(j) leaves the gaps searched. Why:
  // with few records the percentile bootstrap runs short for a separation that hangs on beta (the bootstrap of a
  // variance-type statistic underestimates its spread, ~13 % in sd at 25 records); the jackknife's variance is
  // not biased low that way (Efron & Stein 1981). Simulated studies with a known answer (test_stripes,
  // StripesTarget.DISABLED_CoverageExperiment): 25 records, 95 %: bootstrap 0.86, jackknife 0.92, the union 0.92
  // (the truth above its upper end 10 %, 5.5 %, 5.5 %); 60 records 0.915, 0.935, 0.945.
  double jack_se = NAN, jack_lo = NAN, jack_hi = NAN;
  double advice = NAN;          // max(hi, jack_hi): the separation to advise (hi alone without a jackknife)
  std::string status;           // "ok", "below range", "above range"
  std::string note;
};

// MSA: the smallest x with lambda_P(x) <= lambda_target, lambda_P(x) = rate_of(fit of the counts at x), over the
// continuum of gaps in [smallest, largest] finite positive demand: lambda_P is evaluated on 32 log-spaced gaps,
// the first that meets the target is taken and the step before it is bisected on ln x to 1e-8 relative
// (lambda_P is a step function of x; the result is the upper end of the final bracket, which meets the target).
// An evaluation without a rate (decreasing / not converged fit) counts as not meeting the target. Each
// replicate solves its own lambda_P(x) the same way. Throws std::invalid_argument for lambda_target not > 0.
TargetGap risk_targeted_gap(const Demands& demands, const HazardCurve& hazard, double lambda_target,
                            const Settings& settings);
TargetGap risk_targeted_gap(const StripeIndex& index, const HazardCurve& hazard, double lambda_target,
                            const Settings& settings);

// Linear IDA: as above with the fit of linear_capacities(im, demand1, models, x, cap) at each x (moments while
// nothing is censored: theta(x) = x theta(1), so with a power-law hazard x* has Cornell's closed form). Range
// searched: [1e-3 times the smallest positive demand1 (every counted pair touches at scale <= 1e-3), the
// largest gap at which any pair touches within its cap, max cap[r] demand1 / im[r]].
TargetGap risk_targeted_gap_linear_ida(std::span<const double> im, std::span<const double> demand1,
                                       std::size_t models, std::span<const double> cap, const HazardCurve& hazard,
                                       double lambda_target, const Settings& settings);

// Bisection IDA of yielding pairs: capacities, hence rates, exist only at the study's gaps, so x* is interpolated
// with ln lambda_P linear in x between the two listed gaps whose point rates bracket lambda_target (lambda_P falls
// as x grows; a rate of 0 is interpolated linearly). The interval is the same interpolation in each of the fits'
// bootstrap replicates: the fits must come from one Settings (same seed and B), so replicate b drew the same records
// at every gap; replicate b's rates at the gaps (their ranges when a fit failed: the lower ends give the root's
// lower end, the upper ends its upper end) are interpolated the same way, its root is a range like the MSA
// replicates' ([0, smallest gap] below range, [largest gap, +inf] above), and the interval is their percentile
// interval (a joint interval, as the MSA one). Without replicates (B = 0, or fits with different B) lo and hi are
// NaN. Fits without a finite rate are skipped. Status "ok"; "below range" when the smallest listed gap already
// meets the target (x* at most it); "above range" when the largest does not (x* beyond it). Throws
// std::invalid_argument for lambda_target not > 0 or fits without a hazard.
TargetGap risk_targeted_gap_at_gaps(std::span<const GapFragility> fits, double lambda_target, double confidence);

// lambda_P and P(years) of the MSA point estimates on a gap grid (the "lambda versus separation" plot).
// rate_fitted: rate_of(fit) at each gap (bounds for the degenerate fits, NaN when there is no rate); it can rise with
// the gap, because each gap has its own fit and two fitted curves can cross (mostly where they are extrapolated
// beyond the stripes: a median far above the top stripe, a bound that takes P = 1 above it after a fitted gap).
// rate: non_increasing(gap, rate_fitted), the curve to use: every analysis that exceeds a gap exceeds every smaller
// one, so lambda_P(x) <= lambda_P(x') for x > x', and an estimate at x above the one at a smaller x' (better
// supported: more analyses pound there) is held at it. The risk-targeted gap (the smallest x whose rate_fitted
// meets the target) is the same on either curve. share_below / share_above: of rate_fitted, from IM below the
// lowest / above the highest stripe.
struct RateCurve {
  std::vector<double> gap, rate, probability;
  std::vector<double> rate_fitted, share_below, share_above;
};
RateCurve rate_curve(const Demands& demands, const HazardCurve& hazard, std::span<const double> gaps,
                     double years);
RateCurve rate_curve(const StripeIndex& index, const HazardCurve& hazard, std::span<const double> gaps, double years);

// The running minimum of rate over the gaps in ascending order (any order given; NaN rates stay NaN and lower
// nothing): the largest non-increasing function of the gap that is nowhere above rate.
std::vector<double> non_increasing(std::span<const double> gaps, std::span<const double> rate);

}  // namespace pounding::stripes
