#pragma once
// Separation of a pair in metres (or in ratios of the code gap d) from a study's demands, with intervals that
// include record-to-record variability, and the code separation rules in metres (issue 13).
//
// The demand of one analysis (record k, model m) is its peak closing z = max(u1 - u2) of the uncoupled
// motion: the pair touches at least once at gap g exactly when z > g (the motion before the first contact is
// the uncoupled one). Over the n ok analyses of a study:
//   P(g)            = #{z > g} / n                          (the continuous, empirical curve)
//   separation(t)   = the smallest g with P(g) <= t          = the (floor(t n) + 1)-th largest z
// (t a fraction). Both are exact order statistics: no grid, no interpolation.
//
// Intervals. A study's n analyses are not n independent draws: the same M models meet the same R records,
// and what varies most is the record. The bootstrap here is two-stage (Davison & Hinkley 1997, sec. 3.8;
// the "cluster bootstrap"): a replicate draws R records with replacement and, inside each drawn record, as many
// of its ok analyses as it has, with replacement; the statistic is recomputed on the pooled replicate, and the
// interval is the percentile interval of `replicates` replicates at `confidence` (type-7 quantiles of the
// sorted replicate values). The Wilson interval (stats.hpp) is the sampling error of the models under a fixed
// record set, and ignores record-to-record scatter.
//
// How a replicate is drawn without touching every analysis (issue 27, item 1). A record drawn d times contributes
// d M_k draws with replacement from its M_k ok analyses, i.e. (in distribution) one multinomial count vector over
// them with d M_k trials. The statistics only ask how many drawn values lie above a rank of the pooled sorted
// values, so the multinomial is revealed lazily on a fixed binary tree over the pooled ranks [0, N): a node
// [a, b) splits at m = a + (b - a) / 2, and the draws of record k in the node go above m with
// Binomial(c, (its values in [m, b)) / (its values in [a, b))) -- the conditional law of a multinomial, so every
// path down the tree gives exact multinomial counts. A separation (an order statistic) walks one path to its
// leaf; a probability at a gap reads the node whose split is the gap's rank. The cost per replicate is about
// (targets x log2 N + gaps) x (records drawn), not n: it does not grow with the models per record.
// Reproducibility: replicate b draws its records from a stream splitmix64-derived from (seed, b) and the
// binomial at (node, record) from a stream derived from (seed, b, node, record), so the replicate's counts are
// one fixed function of (seed, b) whatever was asked: every target and gap of every call sees the same
// replicates (the report's tables and CSV agree), and threads do not matter. The lognormal refit needs every
// drawn value (sums of ln z): it draws the models of each drawn record one by one from a third stream, O(n)
// per replicate, and only when BootstrapSettings::lognormal asks for it.
// Before issue 27 a replicate drew every analysis (O(n)): the same bootstrap distribution, other random
// numbers, so intervals moved by their Monte Carlo error (README, "Speed"; tests/analysis/test_separation.cpp
// checks the two against each other and the coverage).
//
// Targets finer than the records resolve (issue 23, item 2). With R records, a target t with floor(t R) = 0 asks
// for a demand that no record is expected to exceed: the empirical separation is then (nearly) the largest
// record's peak, and a finer target returns the same number. Beside it, a parametric estimate: the lognormal
// fitted to every ok demand, P(z > g) = (1 - p0) (1 - Phi((ln g - mu) / sigma)) with mu, sigma the maximum-
// likelihood mean and standard deviation (divisor n) of ln z over the positive demands and p0 the fraction of
// demands <= 0 (a pair that never closes), so separation_lognormal(t) = exp(mu + sigma Phi^-1(1 - t / (1 - p0)))
// (0 when t >= 1 - p0). Why this model: the peak demand of a structure under a record is lognormal in the
// PSDM tradition (Cornell et al. 2002), and with a record effect and a model effect both normal in ln z the
// pooled demand of a study is exactly lognormal, sigma^2 = sigma_record^2 + sigma_model^2; a fixed pair has only
// the record effect. Its interval is the same two-stage bootstrap (the same replicates, refitted), so it
// includes record-to-record variability. It extrapolates: a target beyond the records rests on the lognormal
// tail, and the report labels it so.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace pounding {
struct WorkHook;
}

namespace pounding::separation {

// The demands of a study: z[k * models + m] (NaN where the analysis is excluded).
struct Demands {
  std::size_t records = 0, models = 0;
  std::vector<double> z;
  // z of the ok analyses of record k (NaN excluded), unsorted.
  std::vector<double> record(std::size_t k) const;
  std::vector<double> pooled() const;  // every ok analysis
};

// Fraction of `z` strictly above g; NaN when z is empty.
double exceedance(std::span<const double> z, double g);
// The smallest g with exceedance(z, g) <= t (t in [0, 1)); NaN when z is empty. Takes a copy (nth_element).
double separation_at(std::vector<double> z, double t);

// The lognormal fit above over `z` (NaN ignored): mu, sigma of ln z over the n_pos > 0 values, p0 = share <= 0.
struct LognormalFit {
  double mu = NAN, sigma = NAN, p0 = NAN;
  std::size_t n = 0, n_pos = 0;
  bool ok() const { return n_pos >= 2 && sigma > 0; }
  double separation(double t) const;  // the g with P(z > g) = t; NaN unless ok()
};
LognormalFit fit_lognormal(std::span<const double> z);

struct BootstrapSettings {
  int replicates = 2000;
  double confidence = 0.95;
  std::uint64_t seed = 0;
  int threads = 2;  // the result does not depend on it
  bool lognormal = false;  // also the lognormal separations (BootstrapResult::lognormal; an O(n) pass per replicate)
  const WorkHook* hook = nullptr;  // progress ("report: separation bootstrap", per replicate) and stop (Cancelled)
};

struct Estimate {
  double value = 0, lo = 0, hi = 0;  // the full-data value and its percentile interval
};

struct BootstrapResult {
  std::vector<Estimate> separation;   // per target fraction
  std::vector<Estimate> probability;  // per gap (fraction)
  std::vector<Estimate> lognormal;    // per target, with BootstrapSettings::lognormal (replicates refitted)
  LognormalFit fit;                   // the full-data lognormal (with BootstrapSettings::lognormal)
  int replicates = 0;
};

// The demands prepared once for any number of bootstrap calls: every record's ok values sorted, and each one's
// rank among the pooled values (ties ordered by record). O(n log n) once, with `threads` threads (at most 2^32 - 1
// ok analyses).
struct Prepared {
  std::size_t N = 0;                              // ok analyses
  std::vector<std::vector<double>> values;        // per record, its ok values ascending
  std::vector<std::vector<std::uint32_t>> ranks;  // per record, the pooled rank of each of its sorted values
  std::size_t bound(double g) const;              // pooled values <= g (the rank of the first value above g)
  double at(std::size_t i) const;                 // the pooled value of rank i < N
};
std::shared_ptr<const Prepared> prepare(const Demands& d, int threads = 2);
// The same from a function that fills record k's ok demands (no NaN, in model order, as Demands::record), called
// on the threads: a caller holding the analyses in another layout (the report: peaks, status, code gaps) ranks them
// without a copy of every demand first (800 MB at 10^8 analyses).
using RecordDemands = std::function<void(std::size_t record, std::vector<double>& values)>;
std::shared_ptr<const Prepared> prepare(std::size_t records, const RecordDemands& record, int threads = 2);

// Separations at `targets` (fractions) and probabilities at `gaps`, each with its two-stage interval. With
// replicates = 0 the intervals are the values themselves. A stop through s.hook throws Cancelled.
BootstrapResult bootstrap(const Prepared& p, std::span<const double> targets, std::span<const double> gaps,
                          const BootstrapSettings& s);
BootstrapResult bootstrap(const Demands& d, std::span<const double> targets, std::span<const double> gaps,
                          const BootstrapSettings& s);

// ---------------------------------------------------------------- from histograms (issue 27, item 5)
// [outputs] per_model = false keeps per record a histogram of z instead of the z themselves (study/reductions.hpp):
// counts[k * bins + b], bin 0 is z <= edges[0], bin b in 1..E-1 is (edges[b-1], edges[b]], bin E is z > edges[E-1]
// (E = edges.size(), bins = E + 1). A separation is then known to its bin: the value given is the bin's UPPER edge
// (the smallest edge with at most floor(t n) values above it: never below the exact order statistic, at most one
// bin width above it; +inf in the last bin). The interval is the same two-stage bootstrap as bootstrap() -- the
// same record draws for replicate b (the stream from (seed, b)) -- and, inside each drawn record, its d n_k draws
// revealed by counts on a binary tree over the bins (Binomial splits from a stream of (seed, b, node, record)), so
// the cost per replicate is targets x log2(bins) x records, whatever the models.
struct HistogramDemands {
  std::size_t records = 0;
  std::vector<double> edges;           // ascending
  std::vector<std::int64_t> counts;    // [records][edges.size() + 1]
  std::size_t bins() const { return edges.size() + 1; }
};
BootstrapResult bootstrap(const HistogramDemands& h, std::span<const double> targets, const BootstrapSettings& s);

// ---------------------------------------------------------------- code rules

// The CQC correlation of two oscillators with unequal damping (Der Kiureghian 1981, EESD 9(5)), r = omega2 / omega1
// = T1 / T2: 8 sqrt(z1 z2) (z1 + r z2) r^1.5 / ((1 - r^2)^2 + 4 z1 z2 r (1 + r^2) + 4 (z1^2 + z2^2) r^2). The damping
// ratio beside r belongs to the oscillator whose frequency is r's numerator; with r = T2 / T1 the factor would be
// (z2 + r z1) (issue 23, item 4: the other pairing is 16 % low at T2/T1 = 1.5, 25 % at 2). It is the white-noise
// correlation of the two oscillators' responses, integral Re(H1 conj H2) / sqrt(integral |H1|^2 integral |H2|^2),
// H_i = 1 / (omega_i^2 - omega^2 + 2 i z_i omega_i omega) (tests/python/test_ddc_scipy.py checks that with SciPy
// quad). Equals cqc_rho(r, z) when z1 = z2 = z.
double ddc_rho(double T1, double T2, double zeta1, double zeta2);

// The design values the rules combine: each building's peak displacement (m) and its period and damping.
struct DesignPair {
  double u1 = 0, u2 = 0, T1 = 0, T2 = 0, zeta1 = 0.05, zeta2 = 0.05;
  double code_gap = 0;  // the coefficient rule's gap, code_gap_coefficient (h1 + h2) (m)
};

struct Rule {
  std::string name, clause, formula;
  double gap = 0;  // m
};

// Standard 2800 (or the study's coefficient rule), ABS, SRSS, double difference (DDC), ASCE 7-16 sec. 12.12.3
// (same property: SRSS; separate lots: each set back by its own deltaM, so the sum) and EC8 sec. 4.4.2.7 (separate
// properties: the sum; same property: SRSS; x 0.7 where floor levels coincide), in this order. `coefficient` names the first row
// ("Standard 2800" at 0.005).
std::vector<Rule> code_rules(const DesignPair& p, double coefficient);
// The gaps of code_rules, in its order and from the same arithmetic (code_rules takes them from here), without the
// texts: a grid study's report evaluates the rules for each of up to 10^7 models.
inline constexpr std::size_t code_rule_count = 9;
std::array<double, code_rule_count> code_rule_gaps(const DesignPair& p);

}  // namespace pounding::separation
