// Fragility and risk from MSA demands and IDA capacities, with record-cluster bootstrap intervals.
// See include/pounding/analysis/stripes.hpp.
#include "pounding/analysis/stripes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include "pounding/core/parallel_for.hpp"
#include "pounding/core/progress.hpp"
#include "pounding/core/random.hpp"

namespace pounding::stripes {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kGridPoints = 32;          // the risk-targeted gap's scan (stripes.hpp)
constexpr double kBisection = 1e-8;      // relative width of the final bracket on x
constexpr double kLinearLowFactor = 1e-3;  // linear IDA: range_lo = this times the smallest positive demand1

// ---------------------------------------------------------------- reproducible replicates

// SplitMix64 as a counter-based generator; index draws by the multiply-shift map (bias < n / 2^64). The same
// stream as separation.cpp's two-stage bootstrap.
struct Stream {
  std::uint64_t state;
  std::size_t below(std::size_t n) {
    const std::uint64_t r = splitmix64(state);
    state += 0x9e3779b97f4a7c15ULL;
    return static_cast<std::size_t>((static_cast<unsigned __int128>(r) * n) >> 64);
  }
};

// Replicate b's record multiplicities: R draws with replacement from its own stream (seed, b).
std::vector<int> draw_records(std::uint64_t seed, int b, std::size_t records) {
  Stream g{splitmix64(splitmix64(seed) ^ static_cast<std::uint64_t>(b))};
  std::vector<int> w(records, 0);
  for (std::size_t i = 0; i < records; ++i) ++w[g.below(records)];
  return w;
}


void check_settings(const Settings& s) {
  if (s.bootstrap < 0 || !(s.confidence > 0 && s.confidence < 1) || !(s.years >= 0) || !std::isfinite(s.years))
    throw std::invalid_argument("stripes: bootstrap >= 0, confidence in (0, 1) and years >= 0 are required");
}

// ---------------------------------------------------------------- percentile intervals of ranges

struct Range {
  double lo = 0, hi = kInf;
};

// Type-7 quantile of ascending values that may hold +inf.
double quantile7(const std::vector<double>& v, double p) {
  if (v.empty()) return NAN;
  const double h = static_cast<double>(v.size() - 1) * p;
  const auto i = static_cast<std::size_t>(std::floor(h));
  if (i + 1 >= v.size()) return v.back();
  const double a = v[i], b = v[i + 1], f = h - static_cast<double>(i);
  if (a == b || f == 0) return a;
  if (std::isinf(b)) return b;
  return a + f * (b - a);
}

// stripes.hpp: the lower quantile of the lower ends and the upper quantile of the upper ends.
Interval percentile_interval(const std::vector<Range>& r, double confidence) {
  if (r.empty()) return {NAN, NAN};
  std::vector<double> lo(r.size()), hi(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) lo[i] = r[i].lo, hi[i] = r[i].hi;
  std::sort(lo.begin(), lo.end());
  std::sort(hi.begin(), hi.end());
  const double a = 0.5 * (1.0 - confidence);
  return {quantile7(lo, a), quantile7(hi, 1.0 - a)};
}

// ---------------------------------------------------------------- what a fit says about theta, beta and the rate

Range theta_range(const FragilityFit& f, double x_low, double x_top) {
  switch (f.status) {
    case FragilityStatus::ok: return {f.fragility.theta, f.fragility.theta};
    case FragilityStatus::no_pounding: return {x_top, kInf};
    case FragilityStatus::all_pounded: return {0, x_low};
    case FragilityStatus::separated: return {f.bracket.lo, f.bracket.hi};
    default: return {0, kInf};
  }
}

Range beta_range(const FragilityFit& f) {
  if (f.ok()) return {f.fragility.beta, f.fragility.beta};
  if (f.status == FragilityStatus::separated) return {0, 0};
  return {0, kInf};
}

struct RateValue {
  double value = NAN;
  Range range;
  double tail = 0;
  double below = 0, above = 0;  // shares of value from IM below the lowest / above the highest stripe
};

// The annual rate of a fit whose stripes span [x_low, x_top] (stripes.hpp, "Annual rate of a fit").
RateValue rate_of(const FragilityFit& f, const HazardCurve& h, double x_low, double x_top) {
  switch (f.status) {
    case FragilityStatus::ok: {
      if (!(f.fragility.theta > 0 && std::isfinite(f.fragility.theta))) return {};  // defensive: never thrown in a thread
      const PoundingRate r = pounding_rate(h, f.fragility);
      const RateShares b = rate_shares(h, f.fragility, x_low, x_top);
      return {r.rate, {r.rate, r.rate}, r.tail_share, b.below, b.above};
    }
    case FragilityStatus::separated: {
      const double v = h.rate(std::sqrt(f.bracket.lo) * std::sqrt(f.bracket.hi));
      return {v, {h.rate(f.bracket.hi), h.rate(f.bracket.lo)}, 0};
    }
    case FragilityStatus::no_pounding: {
      const double v = f.bound * h.rate(x_low) + (1.0 - f.bound) * h.rate(x_top);
      return {v, {0, v}, 0, 0, h.rate(x_top) / v};  // P <= 1 above x_top gives lambda(x_top) of it
    }
    case FragilityStatus::all_pounded: {
      const double v = f.bound * h.rate(x_low);
      return {v, {v, kInf}, 0, 0, h.rate(x_top) / h.rate(x_low)};
    }
    default: return {};
  }
}

std::string rate_note(FragilityStatus s) {
  switch (s) {
    case FragilityStatus::separated: return "rate of a step fragility at the bracket's geometric mean";
    case FragilityStatus::no_pounding:
      return "rate is an upper bound (P <= bound up to the top level, 1 above; below the lowest level neglected)";
    case FragilityStatus::all_pounded: return "rate is a lower bound (P >= bound from the lowest level up)";
    case FragilityStatus::ok: return "";
    default: return "no rate without a fitted fragility";
  }
}

std::pair<double, double> level_span(const std::vector<Stripe>& s) {
  double lo = kInf, hi = 0;
  for (const Stripe& t : s) lo = std::min(lo, t.level), hi = std::max(hi, t.level);
  return {lo, hi};
}

double probability_or_nan(double rate, double years) {
  return std::isnan(rate) ? NAN : probability_in_years(rate, years);
}

// The point estimate's rate fields.
void set_rate(GapFragility& g, const HazardCurve* h, double x_low, double x_top, double years) {
  if (!h) return;
  g.has_hazard = true;
  const RateValue r = rate_of(g.fit, *h, x_low, x_top);
  g.annual_rate = r.value;
  g.tail_share = r.tail;
  g.share_below = r.below, g.share_above = r.above;
  g.probability = probability_or_nan(r.value, years);
  if (const std::string n = rate_note(g.fit.status); !n.empty()) g.note += "; " + n;
}

// One replicate's contribution to a GapFragility's intervals.
struct ReplicateFit {
  Range theta, beta, rate;
  bool failed = false;
};

ReplicateFit replicate_fit(const FragilityFit& f, const HazardCurve* h, double x_low, double x_top) {
  ReplicateFit r{theta_range(f, x_low, x_top), beta_range(f), {}, !f.ok()};
  if (h) r.rate = rate_of(f, *h, x_low, x_top).range;
  return r;
}

// The intervals of one gap from its replicates (all B of them, failed ones as ranges).
void set_intervals(GapFragility& g, const std::vector<ReplicateFit>& reps, const Settings& s) {
  g.replicates = static_cast<int>(reps.size());
  if (reps.empty()) return;
  std::vector<Range> theta, beta, rate;
  for (const ReplicateFit& r : reps) {
    theta.push_back(r.theta), beta.push_back(r.beta), rate.push_back(r.rate);
    g.replicates_failed += r.failed;
    if (g.has_hazard) g.replicate_rate_lo.push_back(r.rate.lo), g.replicate_rate_hi.push_back(r.rate.hi);
  }
  g.theta_ci = percentile_interval(theta, s.confidence);
  g.beta_ci = percentile_interval(beta, s.confidence);
  if (!g.has_hazard) return;
  const Interval ri = percentile_interval(rate, s.confidence);
  g.rate_lo = ri.lo, g.rate_hi = ri.hi;
  g.probability_lo = probability_or_nan(ri.lo, s.years);
  g.probability_hi = probability_or_nan(ri.hi, s.years);
}

// Jackknife-t interval of ln v from the leave-one-out values ln_j (stripes.hpp): {se, lo, hi} of v = exp(centre);
// NaN when fewer than 3 or any NaN.
struct Jackknife {
  double se = NAN, lo = NAN, hi = NAN;
};
Jackknife jackknife_log(const std::vector<double>& ln, double centre, double confidence) {
  const auto R = static_cast<double>(ln.size());
  if (ln.size() < 3 || !std::isfinite(centre) ||
      std::any_of(ln.begin(), ln.end(), [](double v) { return !std::isfinite(v); }))
    return {};
  double mean = 0, ss = 0;
  for (double v : ln) mean += v;
  mean /= R;
  for (double v : ln) ss += (v - mean) * (v - mean);
  Jackknife j;
  j.se = std::sqrt((R - 1.0) / R * ss);
  const double q = boost::math::quantile(boost::math::students_t(R - 1.0), 0.5 * (1.0 + confidence));
  j.lo = std::exp(centre - q * j.se), j.hi = std::exp(centre + q * j.se);
  return j;
}

// The rate's jackknife interval of an ok fit from its jackknife_rate (stripes.hpp, GapFragility).
void set_rate_jackknife(GapFragility& g, const Settings& s) {
  if (!g.fit.ok() || !(g.annual_rate > 0)) return;
  std::vector<double> ln;
  for (double v : g.jackknife_rate) ln.push_back(v > 0 ? std::log(v) : NAN);
  const Jackknife j = jackknife_log(ln, std::log(g.annual_rate), s.confidence);
  g.rate_jack_lo = j.lo, g.rate_jack_hi = j.hi;
  g.probability_jack_lo = probability_or_nan(j.lo, s.years), g.probability_jack_hi = probability_or_nan(j.hi, s.years);
}

// ---------------------------------------------------------------- MSA counting

FragilityFit fit_stripes(const std::vector<Stripe>& s) {
  try {
    return fit_fragility_msa(s);
  } catch (const std::invalid_argument&) {  // fewer than 2 levels left (a replicate without some stripes)
    FragilityFit f;
    f.status = FragilityStatus::not_converged;
    f.message = "fewer than 2 stripes with counted analyses";
    return f;
  }
}

// at_or_below positions of every slice at x (for the records with w_r > 0; w empty: all), searched between the
// positions lo and hi when given.
void positions_at(const StripeIndex& ix, double x, const std::size_t* lo, const std::size_t* hi,
                  std::span<const int> w, std::size_t* out) {
  const std::size_t S = ix.stripes(), R = ix.records();
  for (std::size_t s = 0; s < S; ++s)
    for (std::size_t r = 0; r < R; ++r) {
      if (!w.empty() && w[r] == 0) continue;
      const std::size_t i = s * R + r;
      out[i] = lo ? ix.at_or_below(i, x, lo[i], hi[i])
                  : ix.at_or_below(i, x, 0, static_cast<std::size_t>(ix.counted(s, r)));
    }
}

std::vector<Stripe> stripes_from(const StripeIndex& ix, const std::size_t* pos, std::span<const int> w) {
  const std::size_t S = ix.stripes(), R = ix.records();
  std::vector<Stripe> out;
  out.reserve(S);
  for (std::size_t s = 0; s < S; ++s) {
    std::int64_t n = 0, z = 0;
    for (std::size_t r = 0; r < R; ++r) {
      const std::int64_t m = w.empty() ? 1 : w[r];
      if (m == 0) continue;
      const std::int64_t c = ix.counted(s, r);
      n += m * c;
      z += m * (c - static_cast<std::int64_t>(pos[s * R + r]));
    }
    if (n > 0) out.push_back({ix.level(s), n, z});
  }
  return out;
}

GapFragility msa_point(const StripeIndex& ix, double gap, const std::size_t* pos, const HazardCurve* h,
                       double years) {
  GapFragility g;
  g.gap = gap;
  g.observed = stripes_from(ix, pos, {});
  g.fit = fit_stripes(g.observed);
  g.note = g.fit.message;
  for (const Stripe& s : g.observed) g.fitted.push_back(g.fit.ok() ? g.fit.fragility(s.level) : NAN);
  const auto [x_low, x_top] = level_span(g.observed);
  set_rate(g, h, x_low, x_top, years);
  return g;
}

void msa_bootstrap(const StripeIndex& ix, const std::vector<std::size_t>& pos, const Settings& s,
                   const HazardCurve* h, std::vector<GapFragility>& out) {
  const std::size_t G = out.size(), SR = ix.stripes() * ix.records(), B = static_cast<std::size_t>(s.bootstrap);
  std::vector<ReplicateFit> reps(B * G);
  Meter boot(s.hook, "fit: fragility bootstrap", B, "replicates");
  parallel_blocks(B, thread_count(s.threads, B), [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b < last; ++b) {
      if (!boot.step()) return;
      const std::vector<int> w = draw_records(s.seed, static_cast<int>(b), ix.records());
      for (std::size_t g = 0; g < G; ++g) {
        const std::vector<Stripe> st = stripes_from(ix, &pos[g * SR], w);
        const auto [x_low, x_top] = level_span(st);
        reps[b * G + g] = replicate_fit(fit_stripes(st), h, x_low, x_top);
      }
    }
  });
  boot.finish();
  std::vector<ReplicateFit> one(B);
  for (std::size_t g = 0; g < G; ++g) {
    for (std::size_t b = 0; b < B; ++b) one[b] = reps[b * G + g];
    set_intervals(out[g], one, s);
  }
  if (!h) return;
  const std::size_t R = ix.records();
  for (GapFragility& g : out) g.jackknife_rate.assign(R, NAN);
  Meter jack(s.hook, "fit: fragility jackknife", R, "records");
  parallel_blocks(R, thread_count(s.threads, R), [&](std::size_t first, std::size_t last) {
    for (std::size_t j = first; j < last; ++j) {
      if (!jack.step()) return;
      std::vector<int> w(R, 1);
      w[j] = 0;
      for (std::size_t g = 0; g < G; ++g) {
        const std::vector<Stripe> st = stripes_from(ix, &pos[g * SR], w);
        const auto [x_low, x_top] = level_span(st);
        if (const FragilityFit f = fit_stripes(st); f.ok()) out[g].jackknife_rate[j] = rate_of(f, *h, x_low, x_top).value;
      }
    }
  });
  jack.finish();
  for (GapFragility& g : out) set_rate_jackknife(g, s);
}

// ---------------------------------------------------------------- IDA: log capacities with censoring

// Per record the ascending finite log capacities at gap 1 (centred: ln C - y0) with prefix sums, the count
// censored at every gap, and ln cap - y0. At gap x (t = ln x) a capacity is exp(y + y0 + t) and censored when
// y > ln cap - y0 - t.
struct LogCapacities {
  std::size_t records = 0;
  double y0 = 0;
  std::vector<double> y, s1, s2;       // y by record; s1, s2: prefix sums per record (n_r + 1 entries each)
  std::vector<std::size_t> offset;     // record r: y[offset[r] .. offset[r + 1]), prefix at offset[r] + r
  std::vector<std::int64_t> always;    // censored at every gap
  std::vector<double> log_cap;         // ln cap[r] - y0
  double min_cap = kInf;               // smallest cap of a record with counted capacities
};

// y_rm = ln(capacity at gap 1): NaN excluded, +inf censored at every gap.
LogCapacities make_log_capacities(const std::vector<double>& y_raw, std::size_t models, std::span<const double> cap) {
  LogCapacities L;
  L.records = cap.size();
  double sum = 0;
  std::size_t n = 0;
  for (double v : y_raw)
    if (std::isfinite(v)) sum += v, ++n;
  L.y0 = n ? sum / static_cast<double>(n) : 0.0;
  L.offset.push_back(0);
  for (std::size_t r = 0; r < L.records; ++r) {
    std::int64_t always = 0;
    const std::size_t begin = L.y.size();
    for (std::size_t m = 0; m < models; ++m) {
      const double v = y_raw[r * models + m];
      if (std::isfinite(v)) L.y.push_back(v - L.y0);
      else if (v == kInf) ++always;
    }
    std::sort(L.y.begin() + static_cast<std::ptrdiff_t>(begin), L.y.end());
    L.offset.push_back(L.y.size());
    L.always.push_back(always);
    L.log_cap.push_back(std::log(cap[r]) - L.y0);
    if (L.y.size() > begin || always > 0) L.min_cap = std::min(L.min_cap, cap[r]);
  }
  for (std::size_t r = 0; r < L.records; ++r) {
    double a = 0, b = 0;
    L.s1.push_back(0), L.s2.push_back(0);
    for (std::size_t i = L.offset[r]; i < L.offset[r + 1]; ++i) L.s1.push_back(a += L.y[i]), L.s2.push_back(b += L.y[i] * L.y[i]);
  }
  return L;
}

// The weighted sufficient statistics at t = ln x: uncensored count and sums (centred frame), censored groups.
struct CensoredSample {
  double n = 0, n_u = 0, s1 = 0, s2 = 0;
  std::vector<std::pair<double, double>> censored;  // (threshold in the centred frame, weight)
};

CensoredSample sample_at(const LogCapacities& L, double t, std::span<const int> w) {
  CensoredSample c;
  for (std::size_t r = 0; r < L.records; ++r) {
    const double m = w.empty() ? 1.0 : static_cast<double>(w[r]);
    if (m == 0) continue;
    const double threshold = L.log_cap[r] - t;
    const auto first = L.y.begin() + static_cast<std::ptrdiff_t>(L.offset[r]);
    const auto last = L.y.begin() + static_cast<std::ptrdiff_t>(L.offset[r + 1]);
    const auto u = static_cast<std::size_t>(std::upper_bound(first, last, threshold) - first);
    const std::size_t p = L.offset[r] + r;
    const double censored = static_cast<double>(L.offset[r + 1] - L.offset[r] - u + static_cast<std::size_t>(L.always[r]));
    c.n_u += m * static_cast<double>(u), c.s1 += m * L.s1[p + u], c.s2 += m * L.s2[p + u];
    c.n += m * (static_cast<double>(u) + censored);
    if (censored > 0) c.censored.push_back({threshold, m * censored});
  }
  return c;
}

// phi(v) / Phi(v), stable in both tails.
double mills(double v) { return std::exp(-0.5 * v * v - 0.5 * std::log(2.0 * std::numbers::pi) - log_normal_cdf(v)); }

struct Olsen {
  double ll = 0, g0 = 0, g1 = 0, h00 = 0, h01 = 0, h11 = 0;
};

// Censored normal log-likelihood in (delta, tau) = (mu / sigma, 1 / sigma) with gradient and Hessian (concave).
Olsen olsen(const CensoredSample& c, double d, double t) {
  Olsen o;
  o.ll = c.n_u * std::log(t) - 0.5 * (t * t * c.s2 - 2 * t * d * c.s1 + c.n_u * d * d);
  o.g0 = t * c.s1 - c.n_u * d;
  o.g1 = c.n_u / t - t * c.s2 + d * c.s1;
  o.h00 = -c.n_u, o.h01 = c.s1, o.h11 = -c.n_u / (t * t) - c.s2;
  for (const auto& [thr, k] : c.censored) {
    const double v = d - t * thr, h = mills(v), hp = -h * (v + h);
    o.ll += k * log_normal_cdf(v);
    o.g0 += k * h, o.g1 -= k * h * thr;
    o.h00 += k * hp, o.h01 -= k * hp * thr, o.h11 += k * hp * thr * thr;
  }
  return o;
}

// Newton with step halving on the concave Olsen log-likelihood; false when it does not converge.
bool censored_mle(const CensoredSample& c, double& mu, double& sigma) {
  double sd = 1.0, mean = c.n_u > 0 ? c.s1 / c.n_u : 0.0;
  if (c.n_u >= 2) sd = std::sqrt(std::max(1e-12, (c.s2 - c.n_u * mean * mean) / (c.n_u - 1)));
  double d = mean / sd, t = 1.0 / sd;
  Olsen o = olsen(c, d, t);
  for (int it = 0; it < 200; ++it) {
    const double det = o.h00 * o.h11 - o.h01 * o.h01;
    if (!(det > 0) || !std::isfinite(det)) return false;
    const double dd = -(o.h11 * o.g0 - o.h01 * o.g1) / det, dt = -(o.h00 * o.g1 - o.h01 * o.g0) / det;
    double step = 1.0;
    while (t + step * dt <= 0) step *= 0.5;
    Olsen next = olsen(c, d + step * dd, t + step * dt);
    while (!(next.ll >= o.ll - 1e-12 * std::abs(o.ll)) && step > 1e-12) {
      step *= 0.5;
      next = olsen(c, d + step * dd, t + step * dt);
    }
    d += step * dd, t += step * dt, o = next;
    if (std::abs(step * dd) + std::abs(step * dt) <= 1e-13 * (1 + std::abs(d) + std::abs(t))) {
      mu = d / t, sigma = 1.0 / t;
      return std::isfinite(mu) && std::isfinite(sigma);
    }
  }
  return false;
}

// The IDA fit of a sample at gap x (capacities at x are exp(y + y0) x).
FragilityFit fit_capacity_sample(const CensoredSample& c, double y0, double x) {
  FragilityFit f;
  if (c.n < 2) {
    f.status = FragilityStatus::not_converged;
    f.message = "fewer than 2 counted capacities";
    return f;
  }
  if (c.n_u == 0) {
    f.status = FragilityStatus::no_pounding;
    f.bound = 1.0 - std::pow(0.05, 1.0 / c.n);
    f.message = "every capacity censored (no contact up to the caps); 95 % upper bound on P up to the smallest cap";
    return f;
  }
  double mu = 0, sigma = 0;
  if (c.censored.empty()) {
    mu = c.s1 / c.n;
    sigma = std::sqrt(std::max(0.0, (c.s2 - c.n * mu * mu) / (c.n - 1)));
    f.message = "method of moments (beta with the divisor n - 1)";
  } else if (censored_mle(c, mu, sigma)) {
    f.message = "right-censored lognormal MLE";
  } else {
    f.status = FragilityStatus::not_converged;
    f.message = "the censored MLE did not converge";
    return f;
  }
  f.status = FragilityStatus::ok;
  f.fragility = {std::exp(mu + y0) * x, sigma};
  return f;
}

void check_caps(std::span<const double> cap) {
  for (double c : cap)
    if (!std::isfinite(c) || c <= 0) throw std::invalid_argument("stripes: every cap[r] must be finite and > 0");
}

std::vector<double> log_linear_capacities(std::span<const double> im, std::span<const double> demand1,
                                          std::size_t models) {
  if (im.size() * models != demand1.size() || models == 0)
    throw std::invalid_argument("stripes: demand1 must hold im.size() * models values");
  std::vector<double> y(demand1.size());
  for (std::size_t r = 0; r < im.size(); ++r) {
    if (!std::isfinite(im[r]) || im[r] <= 0) throw std::invalid_argument("stripes: every im[r] must be finite and > 0");
    for (std::size_t m = 0; m < models; ++m) {
      const double d = demand1[r * models + m];
      y[r * models + m] = std::isnan(d) ? NAN : d <= 0 ? kInf : std::log(im[r] / d);
    }
  }
  return y;
}

// ---------------------------------------------------------------- the risk-targeted gap

struct Solution {
  double x = NAN;
  int where = 0;  // 0 ok, -1 below range, +1 above range
};

std::vector<double> log_grid(double lo, double hi) {
  std::vector<double> g(kGridPoints);
  for (int i = 0; i < kGridPoints; ++i)
    g[static_cast<std::size_t>(i)] = std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * i / (kGridPoints - 1));
  g.front() = lo, g.back() = hi;
  return g;
}

// The scan-then-bisect of stripes.hpp; rate(x, a, b) with x in [grid[a], grid[b]] (a = b at a grid point).
template <class Rate>
Solution solve_target(const std::vector<double>& grid, double target, Rate&& rate) {
  const auto meets = [&](double v) { return v <= target; };  // NaN: does not meet it
  if (meets(rate(grid[0], 0, 0))) return {grid[0], -1};
  for (std::size_t k = 1; k < grid.size(); ++k) {
    if (!meets(rate(grid[k], k, k))) continue;
    double lo = grid[k - 1], hi = grid[k];
    while (hi > lo * (1.0 + kBisection)) {
      const double mid = std::sqrt(lo) * std::sqrt(hi);
      if (mid <= lo || mid >= hi) break;
      (meets(rate(mid, k - 1, k)) ? hi : lo) = mid;
    }
    return {hi, 0};
  }
  return {grid.back(), 1};
}

// The jackknife interval of a target gap from ln x*_(j), j = 1..R (stripes.hpp, TargetGap); any NaN: none.
void set_jackknife(TargetGap& t, const std::vector<double>& ln, double confidence) {
  const Jackknife j = jackknife_log(ln, std::log(t.gap), confidence);
  t.jack_se = j.se, t.jack_lo = j.lo, t.jack_hi = j.hi;
}

void set_advice(TargetGap& t) { t.advice = std::fmax(t.hi, t.jack_hi); }  // a NaN end is ignored

// Point estimate and bootstrap of a target gap; rate_for(w) makes the rate(x, a, b) of multiplicities w.
template <class RateFor>
TargetGap target_gap(std::size_t records, double lo, double hi, double target, const Settings& s, RateFor&& rate_for) {
  TargetGap out;
  out.lambda_target = target, out.range_lo = lo, out.range_hi = hi;
  const std::vector<double> grid = log_grid(lo, hi);
  {
    auto rate = rate_for(std::vector<int>(records, 1));
    const Solution p = solve_target(grid, target, rate);
    out.gap = p.x;
    out.rate = rate(p.x, 0, grid.size() - 1);
    out.status = p.where == 0 ? "ok" : p.where < 0 ? "below range" : "above range";
  }
  const auto B = static_cast<std::size_t>(s.bootstrap);
  std::vector<Range> reps(B);
  std::vector<int> where(B);
  Meter boot(s.hook, "fit: risk-targeted gap bootstrap", B, "replicates");
  parallel_blocks(B, thread_count(s.threads, B), [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b < last; ++b) {
      if (!boot.step()) return;
      const Solution r = solve_target(grid, target, rate_for(draw_records(s.seed, static_cast<int>(b), records)));
      where[b] = r.where;
      reps[b] = r.where == 0 ? Range{r.x, r.x} : r.where < 0 ? Range{0, lo} : Range{hi, kInf};
    }
  });
  boot.finish();
  out.replicates = s.bootstrap;
  for (int w : where) out.replicates_below += w < 0, out.replicates_above += w > 0;
  if (B) {
    const Interval i = percentile_interval(reps, s.confidence);
    out.lo = i.lo, out.hi = i.hi;
  }
  if (out.status == "ok" && records >= 3) {
    std::vector<double> ln(records, NAN);
    Meter jack(s.hook, "fit: risk-targeted gap jackknife", records, "records");
    parallel_blocks(records, thread_count(s.threads, records), [&](std::size_t first, std::size_t last) {
      for (std::size_t j = first; j < last; ++j) {
        if (!jack.step()) return;
        std::vector<int> w(records, 1);
        w[j] = 0;
        const Solution r = solve_target(grid, target, rate_for(std::move(w)));
        if (r.where == 0) ln[j] = std::log(r.x);
      }
    });
    jack.finish();
    set_jackknife(out, ln, s.confidence);
  }
  set_advice(out);
  return out;
}

std::string describe_target(const TargetGap& t) {
  std::ostringstream os;
  os.precision(6);
  if (t.status == "below range")
    os << "the target is met already at the smallest gap searched, " << t.range_lo << ": x* is at most it";
  else if (t.status == "above range")
    os << "the rate exceeds the target up to the largest gap searched, " << t.range_hi
       << ": x* lies beyond it (the analyses do not reach far enough)";
  else
    os << "lambda_P(x*) = " << t.rate << " per year (target " << t.lambda_target << ")";
  os << "; " << t.replicates_below << " replicates below range and " << t.replicates_above << " above, of "
     << t.replicates;
  return os.str();
}

}  // namespace

// ---------------------------------------------------------------- StripeIndex

StripeIndex::StripeIndex(const Demands& d, int threads) : levels_(d.levels), records_(d.records) {
  const std::size_t S = d.levels.size(), R = d.records, M = d.models;
  if (S < 2 || R == 0 || M == 0 || d.demand.size() != S * R * M)
    throw std::invalid_argument("stripes: need >= 2 levels, records and models > 0 and levels * records * models demands");
  for (double l : d.levels)
    if (!std::isfinite(l) || l <= 0) throw std::invalid_argument("stripes: every stripe level must be finite and > 0");
  offset_.assign(S * R + 1, 0);
  for (std::size_t i = 0; i < S * R; ++i) {
    std::size_t n = 0;
    for (std::size_t m = 0; m < M; ++m) n += !std::isnan(d.demand[i * M + m]);
    offset_[i + 1] = offset_[i] + n;
  }
  sorted_.resize(offset_.back());
  double lo = kInf, hi = 0;
  for (std::size_t i = 0, k = 0; i < S * R * M; ++i) {
    const double v = d.demand[i];
    if (std::isnan(v)) continue;
    sorted_[k++] = v;
    if (std::isfinite(v) && v > 0) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  if (hi > 0) min_positive_ = lo, max_positive_ = hi;
  parallel_blocks(S * R, thread_count(threads, S * R), [this](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i)
      std::sort(sorted_.begin() + static_cast<std::ptrdiff_t>(offset_[i]), sorted_.begin() + static_cast<std::ptrdiff_t>(offset_[i + 1]));
  });
}

std::int64_t StripeIndex::counted(std::size_t s, std::size_t r) const {
  const std::size_t i = s * records_ + r;
  return static_cast<std::int64_t>(offset_[i + 1] - offset_[i]);
}

std::size_t StripeIndex::at_or_below(std::size_t s, std::size_t r, double x) const {
  return at_or_below(s * records_ + r, x, 0, static_cast<std::size_t>(counted(s, r)));
}

std::size_t StripeIndex::at_or_below(std::size_t slice, double x, std::size_t first, std::size_t last) const {
  const double* base = sorted_.data() + offset_[slice];
  return static_cast<std::size_t>(std::upper_bound(base + first, base + last, x) - base);
}

std::vector<Stripe> StripeIndex::stripes_at(double x, std::span<const int> w) const {
  if (!w.empty() && w.size() != records_) throw std::invalid_argument("stripes: one multiplicity per record");
  std::vector<std::size_t> pos(levels_.size() * records_, 0);
  positions_at(*this, x, nullptr, nullptr, w, pos.data());
  return stripes_from(*this, pos.data(), w);
}

// ---------------------------------------------------------------- public functions

Capacities linear_capacities(std::span<const double> im, std::span<const double> demand1, std::size_t models, double x,
                             std::span<const double> cap) {
  if (!std::isfinite(x) || x <= 0) throw std::invalid_argument("stripes: the gap x must be finite and > 0");
  if (cap.size() != im.size()) throw std::invalid_argument("stripes: one cap per record");
  check_caps(cap);
  const std::vector<double> y = log_linear_capacities(im, demand1, models);
  Capacities c{im.size(), models, std::vector<double>(y.size()), std::vector<double>(cap.begin(), cap.end())};
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double v = std::isfinite(y[i]) ? std::exp(y[i]) * x : y[i];
    c.capacity[i] = v > cap[i / models] ? kInf : v;
  }
  return c;
}

std::vector<GapFragility> fit_msa(const Demands& d, std::span<const double> gaps, const Settings& s,
                                  const HazardCurve* hazard) {
  check_settings(s);
  for (double g : gaps)
    if (!std::isfinite(g) || g <= 0) throw std::invalid_argument("stripes: every gap must be finite and > 0");
  return fit_msa(StripeIndex(d, thread_count(s.threads, d.levels.size() * d.records)), gaps, s, hazard);
}

std::vector<GapFragility> fit_msa(const StripeIndex& ix, std::span<const double> gaps, const Settings& s,
                                  const HazardCurve* hazard) {
  check_settings(s);
  for (double g : gaps)
    if (!std::isfinite(g) || g <= 0) throw std::invalid_argument("stripes: every gap must be finite and > 0");
  const std::size_t SR = ix.stripes() * ix.records();
  std::vector<std::size_t> pos(gaps.size() * SR);
  std::vector<GapFragility> out;
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    positions_at(ix, gaps[g], nullptr, nullptr, {}, &pos[g * SR]);
    out.push_back(msa_point(ix, gaps[g], &pos[g * SR], hazard, s.years));
  }
  msa_bootstrap(ix, pos, s, hazard, out);
  return out;
}

GapFragility fit_ida(const Capacities& c, std::span<const double> levels, const Settings& s, const HazardCurve* hazard,
                     double gap) {
  check_settings(s);
  if (c.capacity.size() != c.records * c.models || c.cap.size() != c.records || c.models == 0)
    throw std::invalid_argument("stripes: capacities need records * models values and one cap per record");
  check_caps(c.cap);
  std::vector<double> y(c.capacity.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double v = c.capacity[i];
    if (v <= 0) throw std::invalid_argument("stripes: capacities must be > 0");
    y[i] = std::isnan(v) || v == kInf ? v : std::log(v);
  }
  const LogCapacities L = make_log_capacities(y, c.models, c.cap);
  GapFragility g;
  g.gap = gap;
  g.fit = fit_capacity_sample(sample_at(L, 0, {}), L.y0, 1.0);
  g.note = g.fit.message;
  for (double level : levels) {
    Stripe st{level, 0, 0};
    for (std::size_t i = 0; i < c.capacity.size(); ++i) {
      const double v = c.capacity[i];
      st.n += !std::isnan(v);
      st.z += std::isfinite(v) && v <= c.cap[i / c.models] && v <= level;
    }
    g.observed.push_back(st);
    g.fitted.push_back(g.fit.ok() ? g.fit.fragility(level) : NAN);
  }
  const double x_top = L.min_cap, x_low = levels.empty() ? x_top : std::min(x_top, *std::min_element(levels.begin(), levels.end()));
  set_rate(g, hazard, x_low, x_top, s.years);
  std::vector<ReplicateFit> reps(static_cast<std::size_t>(s.bootstrap));
  Meter boot(s.hook, fmt::format("fit: IDA bootstrap at gap {:g}", gap), reps.size(), "replicates");
  parallel_blocks(reps.size(), thread_count(s.threads, reps.size()), [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b < last; ++b) {
      if (!boot.step()) return;
      const std::vector<int> w = draw_records(s.seed, static_cast<int>(b), c.records);
      reps[b] = replicate_fit(fit_capacity_sample(sample_at(L, 0, w), L.y0, 1.0), hazard, x_low, x_top);
    }
  });
  boot.finish();
  set_intervals(g, reps, s);
  if (hazard) {
    g.jackknife_rate.assign(c.records, NAN);
    Meter jack(s.hook, fmt::format("fit: IDA jackknife at gap {:g}", gap), c.records, "records");
    parallel_blocks(c.records, thread_count(s.threads, c.records), [&](std::size_t first, std::size_t last) {
      for (std::size_t j = first; j < last; ++j) {
        if (!jack.step()) return;
        std::vector<int> w(c.records, 1);
        w[j] = 0;
        const FragilityFit f = fit_capacity_sample(sample_at(L, 0, w), L.y0, 1.0);
        if (f.ok()) g.jackknife_rate[j] = rate_of(f, *hazard, x_low, x_top).value;
      }
    });
    jack.finish();
    set_rate_jackknife(g, s);
  }
  return g;
}

TargetGap risk_targeted_gap(const Demands& d, const HazardCurve& hazard, double target, const Settings& s) {
  check_settings(s);
  if (!(target > 0) || !std::isfinite(target)) throw std::invalid_argument("stripes: lambda_target must be > 0");
  return risk_targeted_gap(StripeIndex(d, thread_count(s.threads, d.levels.size() * d.records)), hazard, target, s);
}

TargetGap risk_targeted_gap(const StripeIndex& ix, const HazardCurve& hazard, double target, const Settings& s) {
  check_settings(s);
  if (!(target > 0) || !std::isfinite(target)) throw std::invalid_argument("stripes: lambda_target must be > 0");
  if (std::isnan(ix.min_positive())) throw std::invalid_argument("stripes: no positive demand to search gaps over");
  const std::size_t SR = ix.stripes() * ix.records();
  const std::vector<double> grid = log_grid(ix.min_positive(), ix.max_positive());
  std::vector<std::size_t> grid_pos(grid.size() * SR);
  for (std::size_t k = 0; k < grid.size(); ++k) positions_at(ix, grid[k], nullptr, nullptr, {}, &grid_pos[k * SR]);
  TargetGap out = target_gap(ix.records(), grid.front(), grid.back(), target, s, [&](std::vector<int> w) {
    return [&ix, &hazard, &grid_pos, SR, w = std::move(w), pos = std::vector<std::size_t>(SR)](
               double x, std::size_t a, std::size_t b) mutable {
      const std::size_t* p = &grid_pos[a * SR];
      if (a != b) positions_at(ix, x, &grid_pos[a * SR], &grid_pos[b * SR], w, pos.data()), p = pos.data();
      const std::vector<Stripe> st = stripes_from(ix, p, w);
      const auto [x_low, x_top] = level_span(st);
      return rate_of(fit_stripes(st), hazard, x_low, x_top).value;
    };
  });
  out.note = describe_target(out);
  return out;
}

namespace {

// The smallest x at which the piecewise ln-linear interpolant of (x[i], rate[i]) reaches `target` (rate falls with
// x): -1 when rate[0] already does, +inf when none does.
double interpolated_crossing(std::span<const double> x, std::span<const double> rate, double target) {
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (!(rate[j] <= target)) continue;
    if (j == 0) return -1.0;
    const double r0 = rate[j - 1], r1 = rate[j];
    if (std::isinf(r0)) return x[j];  // an unbounded rate range (a failed replicate's upper end): the interval's end
    const double t = r1 > 0 ? (std::log(r0) - std::log(target)) / (std::log(r0) - std::log(r1)) : (r0 - target) / (r0 - r1);
    return x[j - 1] + t * (x[j] - x[j - 1]);
  }
  return INFINITY;
}

// The bootstrap interval of risk_targeted_gap_at_gaps (stripes.hpp): replicate b's root from the fits' replicate b.
void joint_interval(const std::vector<const GapFragility*>& f, const std::vector<double>& x, double target,
                    double confidence, TargetGap& t) {
  const std::size_t B = f.front()->replicate_rate_lo.size();
  for (const GapFragility* g : f)
    if (g->replicate_rate_lo.size() != B || g->replicate_rate_hi.size() != B) return;
  if (B == 0) return;
  std::vector<Range> reps(B);
  std::vector<double> lo(f.size()), hi(f.size());
  for (std::size_t b = 0; b < B; ++b) {
    for (std::size_t j = 0; j < f.size(); ++j) lo[j] = f[j]->replicate_rate_lo[b], hi[j] = f[j]->replicate_rate_hi[b];
    const double a = interpolated_crossing(x, lo, target), c = interpolated_crossing(x, hi, target);
    reps[b] = {a < 0 ? 0.0 : std::isinf(a) ? x.back() : a, c < 0 ? x.front() : c};
    t.replicates_below += c < 0, t.replicates_above += std::isinf(a);
  }
  t.replicates = static_cast<int>(B);
  const Interval i = percentile_interval(reps, confidence);
  t.lo = i.lo, t.hi = i.hi;
}

// The jackknife of risk_targeted_gap_at_gaps: the gaps' leave-one-record-out rates interpolated the same way.
void jackknife_at_gaps(const std::vector<const GapFragility*>& f, const std::vector<double>& x, double target,
                       double confidence, TargetGap& t) {
  const std::size_t R = f.front()->jackknife_rate.size();
  for (const GapFragility* g : f)
    if (g->jackknife_rate.size() != R) return;
  std::vector<double> ln(R, NAN), rate(f.size());
  for (std::size_t j = 0; j < R; ++j) {
    for (std::size_t k = 0; k < f.size(); ++k) rate[k] = f[k]->jackknife_rate[j];
    if (std::any_of(rate.begin(), rate.end(), [](double v) { return std::isnan(v); })) return;
    const double r = interpolated_crossing(x, rate, target);
    if (r > 0 && std::isfinite(r)) ln[j] = std::log(r);
  }
  set_jackknife(t, ln, confidence);
}

}  // namespace

TargetGap risk_targeted_gap_at_gaps(std::span<const GapFragility> fits, double lambda_target, double confidence) {
  if (!(lambda_target > 0) || !std::isfinite(lambda_target))
    throw std::invalid_argument("risk_targeted_gap_at_gaps: lambda_target must be finite and > 0");
  if (!(confidence > 0 && confidence < 1)) throw std::invalid_argument("risk_targeted_gap_at_gaps: confidence in (0, 1)");
  std::vector<const GapFragility*> f;
  for (const GapFragility& g : fits) {
    if (!g.has_hazard) throw std::invalid_argument("risk_targeted_gap_at_gaps: a fit without a hazard");
    if (std::isfinite(g.annual_rate)) f.push_back(&g);
  }
  std::sort(f.begin(), f.end(), [](const GapFragility* a, const GapFragility* b) { return a->gap < b->gap; });
  TargetGap t;
  t.lambda_target = lambda_target;
  if (f.size() < 2) {
    t.status = "not found";
    t.note = "fewer than two gaps have an annual rate: give more gap ratios, or stripes that bracket the medians";
    return t;
  }
  std::vector<double> x, rate;
  for (const GapFragility* g : f) x.push_back(g->gap), rate.push_back(g->annual_rate);
  t.range_lo = x.front(), t.range_hi = x.back();
  const double p = interpolated_crossing(x, rate, lambda_target);
  joint_interval(f, x, lambda_target, confidence, t);
  const std::string where = fmt::format("interpolated (ln lambda linear in the gap) between the study's gaps {:g} ... {:g}: "
                                        "the bisection IDA gives capacities only at the listed gaps; the interval "
                                        "interpolates each bootstrap replicate the same way",
                                        x.front(), x.back());
  if (p < 0) {
    t.gap = x.front(), t.status = "below range", t.rate = rate.front();
    t.note = fmt::format("the smallest gap, {:g}, already meets the target: add smaller gap ratios ({})", x.front(), where);
  } else if (std::isinf(p)) {
    t.gap = x.back(), t.status = "above range", t.rate = rate.back();
    t.note = fmt::format("even the largest gap, {:g}, has a rate above the target: add larger gap ratios ({})", x.back(), where);
  } else {
    t.gap = p, t.status = "ok", t.rate = lambda_target;
    t.note = where;
    jackknife_at_gaps(f, x, lambda_target, confidence, t);
  }
  set_advice(t);
  return t;
}

TargetGap risk_targeted_gap_linear_ida(std::span<const double> im, std::span<const double> demand1, std::size_t models,
                                       std::span<const double> cap, const HazardCurve& hazard, double target,
                                       const Settings& s) {
  check_settings(s);
  if (!(target > 0) || !std::isfinite(target)) throw std::invalid_argument("stripes: lambda_target must be > 0");
  if (cap.size() != im.size()) throw std::invalid_argument("stripes: one cap per record");
  check_caps(cap);
  const LogCapacities L = make_log_capacities(log_linear_capacities(im, demand1, models), models, cap);
  double lo = kInf, hi = 0;
  for (std::size_t i = 0; i < demand1.size(); ++i)
    if (const double d1 = demand1[i]; std::isfinite(d1) && d1 > 0)
      lo = std::min(lo, d1), hi = std::max(hi, cap[i / models] * d1 / im[i / models]);
  if (!(hi > 0)) throw std::invalid_argument("stripes: no positive demand to search gaps over");
  lo *= kLinearLowFactor;
  TargetGap out = target_gap(im.size(), lo, hi, target, s, [&](std::vector<int> w) {
    return [&L, &hazard, w = std::move(w)](double x, std::size_t, std::size_t) {
      const FragilityFit f = fit_capacity_sample(sample_at(L, std::log(x), w), L.y0, x);
      return rate_of(f, hazard, L.min_cap, L.min_cap).value;
    };
  });
  out.note = describe_target(out);
  return out;
}

RateCurve rate_curve(const Demands& d, const HazardCurve& hazard, std::span<const double> gaps, double years) {
  return rate_curve(StripeIndex(d, 1), hazard, gaps, years);
}

RateCurve rate_curve(const StripeIndex& ix, const HazardCurve& hazard, std::span<const double> gaps, double years) {
  RateCurve c;
  for (double g : gaps) {
    const std::vector<Stripe> st = ix.stripes_at(g);
    const auto [x_low, x_top] = level_span(st);
    const RateValue r = rate_of(fit_stripes(st), hazard, x_low, x_top);
    c.gap.push_back(g), c.rate_fitted.push_back(r.value), c.share_below.push_back(r.below), c.share_above.push_back(r.above);
  }
  c.rate = non_increasing(c.gap, c.rate_fitted);
  for (double r : c.rate) c.probability.push_back(probability_or_nan(r, years));
  return c;
}

std::vector<double> non_increasing(std::span<const double> gaps, std::span<const double> rate) {
  if (gaps.size() != rate.size()) throw std::invalid_argument("non_increasing: one rate per gap");
  std::vector<std::size_t> order(gaps.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return gaps[a] < gaps[b]; });
  std::vector<double> out(rate.begin(), rate.end());
  double least = kInf;
  for (std::size_t i : order) {
    if (std::isnan(rate[i])) continue;  // no rate at this gap: neither lowered nor lowering
    least = std::min(least, rate[i]);
    out[i] = least;
  }
  return out;
}

}  // namespace pounding::stripes
