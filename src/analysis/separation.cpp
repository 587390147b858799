// Separation in metres with two-stage bootstrap intervals, and code separation rules. See separation.hpp.
#include "pounding/analysis/separation.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <thread>

#include <boost/math/special_functions/erf.hpp>
#include <boost/random/binomial_distribution.hpp>

#include "pounding/core/parallel_for.hpp"
#include "pounding/core/progress.hpp"
#include "pounding/core/radix_sort.hpp"
#include "pounding/core/random.hpp"

namespace pounding::separation {

std::vector<double> Demands::record(std::size_t k) const {
  std::vector<double> out;
  out.reserve(models);
  for (std::size_t m = 0; m < models; ++m)
    if (const double v = z[k * models + m]; !std::isnan(v)) out.push_back(v);
  return out;
}

std::vector<double> Demands::pooled() const {
  std::vector<double> out;
  out.reserve(z.size());
  for (double v : z)
    if (!std::isnan(v)) out.push_back(v);
  return out;
}

double LognormalFit::separation(double t) const {
  if (!ok() || !(t > 0 && t < 1)) return NAN;
  const double q = t / (1.0 - p0);  // P(z > g | z > 0)
  if (q >= 1) return 0.0;
  // Phi^-1(1 - q) = sqrt(2) erfc^-1(2 q)
  return std::exp(mu + sigma * std::numbers::sqrt2 * boost::math::erfc_inv(2.0 * q));
}

LognormalFit fit_lognormal(std::span<const double> z) {
  LognormalFit f;
  double s = 0;
  for (double v : z)
    if (!std::isnan(v)) ++f.n, v > 0 ? (s += std::log(v), ++f.n_pos) : 0;
  if (f.n == 0) return f;
  f.p0 = static_cast<double>(f.n - f.n_pos) / static_cast<double>(f.n);
  if (f.n_pos == 0) return f;
  f.mu = s / static_cast<double>(f.n_pos);
  double ss = 0;
  for (double v : z)
    if (!std::isnan(v) && v > 0) ss += (std::log(v) - f.mu) * (std::log(v) - f.mu);
  f.sigma = std::sqrt(ss / static_cast<double>(f.n_pos));
  return f;
}

double exceedance(std::span<const double> z, double g) {
  if (z.empty()) return NAN;
  std::size_t above = 0;
  for (double v : z) above += v > g;
  return static_cast<double>(above) / static_cast<double>(z.size());
}

namespace {

// Index (ascending) of the smallest g with at most floor(t n) values above it: the (floor(t n) + 1)-th largest.
std::size_t separation_index(std::size_t n, double t) {
  const auto j = static_cast<std::size_t>(std::floor(t * static_cast<double>(n)));
  return j >= n ? 0 : n - 1 - j;
}

// SplitMix64 as a counter-based generator; index draws by the multiply-shift map (bias < n / 2^64). Also a
// UniformRandomBitGenerator for the binomial draws.
struct Stream {
  using result_type = std::uint64_t;
  std::uint64_t state;
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }
  result_type operator()() {
    const std::uint64_t r = splitmix64(state);
    state += 0x9e3779b97f4a7c15ULL;
    return r;
  }
  std::size_t below(std::size_t n) { return static_cast<std::size_t>((static_cast<unsigned __int128>((*this)()) * n) >> 64); }
};

// Type-7 quantile of sorted values (NaN-free).
double quantile7(const std::vector<double>& v, double p) {
  if (v.empty()) return NAN;
  const double h = static_cast<double>(v.size() - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  if (lo + 1 >= v.size()) return v.back();
  return v[lo] + (h - static_cast<double>(lo)) * (v[lo + 1] - v[lo]);
}


}  // namespace

std::size_t Prepared::bound(double g) const {
  std::size_t n = 0;
  for (const auto& v : values) n += static_cast<std::size_t>(std::upper_bound(v.begin(), v.end(), g) - v.begin());
  return n;
}

double Prepared::at(std::size_t i) const {
  for (std::size_t k = 0; k < ranks.size(); ++k) {
    const auto it = std::lower_bound(ranks[k].begin(), ranks[k].end(), static_cast<std::uint32_t>(i));
    if (it != ranks[k].end() && *it == i) return values[k][static_cast<std::size_t>(it - ranks[k].begin())];
  }
  return NAN;
}

namespace {

// The pooled ranks of the values at positions [lo[k], hi[k]) of every record k, which are the ranks from
// sum_k lo[k] on: a k-way merge on a tournament (loser) tree over the records, equal values ordered by record (and
// within a record by position). log2(records) comparisons per value; a binary heap of (value, record) pairs, the
// merge before, took 3 s of a 10^8-analysis report.
void merge_ranks(Prepared& p, const std::vector<std::size_t>& lo, const std::vector<std::size_t>& hi) {
  const std::size_t R = lo.size(), L = std::bit_ceil(std::max<std::size_t>(R, 1));
  std::vector<std::size_t> next(lo), end(hi);
  next.resize(L, 0), end.resize(L, 0);  // the leaves past the records: empty
  // a record's next value as its radix key (the doubles' order; -0.0 as +0.0, equal as before), `done` when the
  // record is exhausted (the key of a NaN, which no demand is)
  constexpr std::uint64_t done = ~std::uint64_t{0};
  std::vector<std::uint64_t> head(L, done);
  const auto advance = [&](std::size_t k) {
    const double v = next[k] < end[k] ? p.values[k][next[k]] : 0.0;
    head[k] = next[k] < end[k] ? radix_key(std::bit_cast<std::uint64_t>(v == 0 ? 0.0 : v)) : done;
  };
  for (std::size_t k = 0; k < R; ++k) advance(k);
  const auto before = [&](std::size_t a, std::size_t b) { return head[a] < head[b] || (head[a] == head[b] && a < b); };
  std::vector<std::size_t> loser(L), win(2 * L);
  for (std::size_t i = 0; i < L; ++i) win[L + i] = i;
  for (std::size_t n = L - 1; n >= 1; --n) {
    const std::size_t a = win[2 * n], b = win[2 * n + 1];
    before(a, b) ? (win[n] = a, loser[n] = b) : (win[n] = b, loser[n] = a);
  }
  std::size_t w = L > 1 ? win[1] : 0;
  std::size_t offset = 0;
  for (std::size_t k = 0; k < R; ++k) offset += lo[k];
  for (auto i = static_cast<std::uint32_t>(offset); head[w] != done; ++i) {
    p.ranks[w][next[w]++] = i;
    advance(w);
    for (std::size_t n = (L + w) / 2; n >= 1; n /= 2)  // replay w's path: the winner goes on up
      if (before(loser[n], w)) std::swap(loser[n], w);
  }
}

}  // namespace

std::shared_ptr<const Prepared> prepare(const Demands& d, int threads) {
  return prepare(d.records, [&](std::size_t k, std::vector<double>& v) { v = d.record(k); }, threads);
}

std::shared_ptr<const Prepared> prepare(std::size_t records, const RecordDemands& record, int threads) {
  auto p = std::make_shared<Prepared>();
  const std::size_t R = records;
  p->values.resize(R), p->ranks.resize(R);
  parallel_blocks(R, threads, [&](std::size_t first, std::size_t last) {
    std::vector<std::uint64_t> scratch;
    for (std::size_t k = first; k < last; ++k) {
      record(k, p->values[k]);
      radix_sort(p->values[k], scratch);  // linear: std::sort took 13.6 of 45 s of a report on 10^8 analyses
      p->ranks[k].resize(p->values[k].size());
    }
  });
  for (const auto& v : p->values) p->N += v.size();
  if (p->N > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("separation bootstrap: more than 2^32 - 1 ok analyses");
  // The pooled ranks by a k-way merge (a heap of each record's next value; equal values ordered by record), the
  // value range cut at `threads - 1` pivots (quantiles of a sample of every record) and each part merged on its own
  // thread: a value's rank is its part's offset (the values below the part's lower pivot) plus its rank inside.
  std::vector<double> sample;
  for (const auto& v : p->values)
    for (std::size_t j = 0; j < 64 && !v.empty(); ++j) sample.push_back(v[j * v.size() / 64]);
  std::sort(sample.begin(), sample.end());
  const std::size_t parts = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), sample.size()));
  std::vector<double> pivot(parts + 1);
  pivot[0] = -std::numeric_limits<double>::infinity(), pivot[parts] = std::numeric_limits<double>::infinity();
  for (std::size_t t = 1; t < parts; ++t) pivot[t] = sample[t * sample.size() / parts];
  // first[t][k]: record k's first position at or above pivot t (the last pivot: its end)
  std::vector<std::vector<std::size_t>> first(parts + 1, std::vector<std::size_t>(R));
  for (std::size_t t = 0; t <= parts; ++t)
    for (std::size_t k = 0; k < R; ++k)
      first[t][k] = t == parts ? p->values[k].size()
                               : static_cast<std::size_t>(std::lower_bound(p->values[k].begin(), p->values[k].end(), pivot[t]) -
                                                          p->values[k].begin());
  parallel_blocks(parts, static_cast<int>(parts), [&](std::size_t t0, std::size_t t1) {
    for (std::size_t t = t0; t < t1; ++t) merge_ranks(*p, first[t], first[t + 1]);
  });
  return p;
}

namespace {

// One replicate's counts, revealed on the tree over the pooled ranks (separation.hpp). A node's entries: record k's
// sorted positions [lo, hi) in the node and its c draws there (only c > 0 is kept).
struct Entry {
  std::uint32_t k, lo, hi;
  std::uint64_t c;
};

class Replicate {
 public:
  Replicate(const Prepared& p, std::uint64_t key, std::span<const std::size_t> gap_bound,
            std::span<const std::size_t> gap_order, double* gap_out, std::span<const std::uint64_t> want, double* target_out)
      : p_(p), key_(key), bound_(gap_bound), order_(gap_order), gap_out_(gap_out), want_(want), target_out_(target_out) {}

  // The replicate's multiplicities per record are in `entries` (c = d M_k): every gap with 0 < bound < N and
  // every target, walked down from the root [0, N); n draws in all.
  void run(std::vector<Entry>& buf, std::size_t gap_first, std::size_t gap_last, std::uint64_t n) {
    n_ = static_cast<double>(n);
    std::uint64_t mask = 0;
    for (std::size_t t = 0; t < want_.size(); ++t) mask |= std::uint64_t{1} << t;
    buf_ = &buf;
    visit(1, 0, p_.N, 0, 0, buf.size(), gap_first, gap_last, mask);
  }

 private:
  std::uint64_t binomial(std::uint64_t node, std::uint32_t k, std::uint64_t c, double q) {
    Stream g{splitmix64(key_ ^ splitmix64(node * 0x100000001b3ULL + k))};
    return static_cast<std::uint64_t>(boost::random::binomial_distribution<std::int64_t, double>(static_cast<std::int64_t>(c), q)(g));
  }

  // Node `id` = ranks [a, b), `above` draws at ranks >= b, its entries buf[e0, e1), the gaps order_[g0, g1) (their
  // bounds in (a, b)) and the targets in `mask` (their answer's rank in [a, b)).
  void visit(std::uint64_t id, std::size_t a, std::size_t b, std::uint64_t above, std::size_t e0, std::size_t e1,
             std::size_t g0, std::size_t g1, std::uint64_t mask) {
    std::vector<Entry>& buf = *buf_;
    if (b - a == 1) {  // a leaf: the one record with a value of rank a
      for (; mask; mask &= mask - 1) {
        const int t = std::countr_zero(mask);
        for (std::size_t e = e0; e < e1; ++e) target_out_[t] = p_.values[buf[e].k][buf[e].lo];
      }
      return;
    }
    const std::size_t m = a + (b - a) / 2;
    const std::size_t up0 = buf.size();
    std::uint64_t U = 0;
    for (std::size_t e = e0; e < e1; ++e) {  // the upper child's entries
      const Entry x = buf[e];
      const auto& r = p_.ranks[x.k];
      const auto mk = static_cast<std::uint32_t>(std::lower_bound(r.begin() + x.lo, r.begin() + x.hi, m) - r.begin());
      const std::uint64_t u = mk == x.lo ? x.c : mk == x.hi ? 0 : binomial(id, x.k, x.c, static_cast<double>(x.hi - mk) / static_cast<double>(x.hi - x.lo));
      if (u) buf.push_back({x.k, mk, x.hi, u}), U += u;
    }
    const std::size_t lo0 = buf.size();
    for (std::size_t e = e0, j = up0; e < e1; ++e) {  // the lower child's entries
      const Entry x = buf[e];
      std::uint64_t u = 0;
      std::uint32_t mk = x.hi;
      if (j < lo0 && buf[j].k == x.k) u = buf[j].c, mk = buf[j].lo, ++j;
      else {
        const auto& r = p_.ranks[x.k];
        mk = static_cast<std::uint32_t>(std::lower_bound(r.begin() + x.lo, r.begin() + x.hi, m) - r.begin());
      }
      if (x.c > u) buf.push_back({x.k, x.lo, mk, x.c - u});
    }
    const std::size_t end = buf.size();
    // gaps: bound == m read here; above m to the upper child, below to the lower
    std::size_t gm = g0;
    while (gm < g1 && bound_[order_[gm]] < m) ++gm;
    std::size_t gu = gm;
    while (gu < g1 && bound_[order_[gu]] == m) gap_out_[order_[gu++]] = static_cast<double>(above + U) / n_;
    std::uint64_t up = 0, down = 0;
    for (std::uint64_t t = mask; t; t &= t - 1) {
      const int i = std::countr_zero(t);
      (above + U > want_[i] ? up : down) |= std::uint64_t{1} << i;
    }
    if (gu < g1 || up) visit(2 * id + 1, m, b, above, up0, lo0, gu, g1, up);
    if (g0 < gm || down) visit(2 * id, a, m, above + U, lo0, end, g0, gm, down);
    buf.resize(up0);
  }

  const Prepared& p_;
  std::uint64_t key_;
  std::span<const std::size_t> bound_, order_;
  double* gap_out_;
  std::span<const std::uint64_t> want_;
  double* target_out_;
  std::vector<Entry>* buf_ = nullptr;
  double n_ = 0;
};

// The lognormal separations at targets of one replicate: its drawn records' models drawn one by one (stream `g`),
// the fit of LognormalFit (ln z shifted by the full-data mu for a stable one-pass sum of squares).
void replicate_lognormal(const Prepared& p, const std::vector<std::uint32_t>& drawn, Stream g, double shift,
                         std::span<const double> targets, double* out) {
  LognormalFit f;
  double s = 0, ss = 0;
  for (std::size_t k = 0; k < drawn.size(); ++k) {
    const std::vector<double>& v = p.values[k];
    const std::size_t M = v.size();
    for (std::size_t j = 0, draws = static_cast<std::size_t>(drawn[k]) * M; j < draws; ++j) {
      const double z = v[g.below(M)];
      ++f.n;
      if (z > 0) {
        const double l = std::log(z) - shift;
        s += l, ss += l * l, ++f.n_pos;
      }
    }
  }
  if (f.n) f.p0 = static_cast<double>(f.n - f.n_pos) / static_cast<double>(f.n);
  if (f.n_pos) {
    const double mean = s / static_cast<double>(f.n_pos);
    f.mu = shift + mean;
    f.sigma = std::sqrt(std::max(0.0, ss / static_cast<double>(f.n_pos) - mean * mean));
  }
  for (std::size_t t = 0; t < targets.size(); ++t) out[t] = f.separation(targets[t]);
}

}  // namespace

double separation_at(std::vector<double> z, double t) {
  if (z.empty()) return NAN;
  auto nth = z.begin() + static_cast<std::ptrdiff_t>(separation_index(z.size(), t));
  std::nth_element(z.begin(), nth, z.end());
  return *nth;
}

BootstrapResult bootstrap(const Demands& d, std::span<const double> targets, std::span<const double> gaps,
                          const BootstrapSettings& s) {
  return bootstrap(*prepare(d, s.threads), targets, gaps, s);
}

BootstrapResult bootstrap(const Prepared& p, std::span<const double> targets, std::span<const double> gaps,
                          const BootstrapSettings& s) {
  if (s.replicates < 0 || !(s.confidence > 0 && s.confidence < 1) || targets.size() > 64)
    throw std::invalid_argument("bootstrap: replicates >= 0, confidence in (0, 1), at most 64 targets");
  const std::size_t T = targets.size(), G = gaps.size(), S0 = T + G, B = static_cast<std::size_t>(s.replicates);
  const std::size_t S = S0 + (s.lognormal ? T : 0), R = p.values.size(), N = p.N;
  // the full data: exact order statistics and exceedances
  std::vector<double> full(S, NAN);
  std::vector<std::size_t> bound(G), order(G);
  for (std::size_t i = 0; i < G; ++i) bound[i] = p.bound(gaps[i]), order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return bound[x] < bound[y]; });
  if (N) {
    for (std::size_t i = 0; i < T; ++i) full[i] = p.at(separation_index(N, targets[i]));
    for (std::size_t i = 0; i < G; ++i) full[T + i] = static_cast<double>(N - bound[i]) / static_cast<double>(N);
  }
  BootstrapResult out;
  if (s.lognormal) {
    std::vector<double> pooled;
    pooled.reserve(N);
    for (const auto& v : p.values) pooled.insert(pooled.end(), v.begin(), v.end());
    out.fit = fit_lognormal(pooled);
    for (std::size_t i = 0; i < T; ++i) full[S0 + i] = out.fit.separation(targets[i]);
  }
  // gaps strictly inside (0, N) are read in the tree; bound 0: every draw is above, bound N: none
  std::size_t gap_first = 0, gap_last = G;
  while (gap_first < G && bound[order[gap_first]] == 0) ++gap_first;
  while (gap_last > gap_first && bound[order[gap_last - 1]] >= N) --gap_last;

  std::vector<double> stats(B * S, NAN);
  Meter meter(s.hook, "report: separation bootstrap", B);
  parallel_blocks(B, s.replicates ? s.threads : 1, [&](std::size_t first, std::size_t last) {
    std::vector<std::uint32_t> drawn(R);
    std::vector<Entry> buf;
    std::vector<std::uint64_t> want(T);
    for (std::size_t b = first; b < last; ++b) {
      if (!meter.step()) return;
      double* o = &stats[b * S];
      const std::uint64_t key = splitmix64(splitmix64(s.seed) ^ static_cast<std::uint64_t>(b));
      Stream g{key};
      std::fill(drawn.begin(), drawn.end(), 0u);
      for (std::size_t i = 0; i < R; ++i) ++drawn[g.below(R)];
      buf.clear();
      std::uint64_t n = 0;
      for (std::size_t k = 0; k < R; ++k)
        if (const std::size_t M = p.values[k].size(); drawn[k] && M)
          buf.push_back({static_cast<std::uint32_t>(k), 0, static_cast<std::uint32_t>(M), std::uint64_t{drawn[k]} * M}),
              n += drawn[k] * M;
      if (n == 0) continue;  // NaN: left out of the interval
      for (std::size_t i = 0; i < T; ++i)
        want[i] = std::min<std::uint64_t>(static_cast<std::uint64_t>(std::floor(targets[i] * static_cast<double>(n))), n - 1);
      for (std::size_t i = 0; i < gap_first; ++i) o[T + order[i]] = 1.0;
      for (std::size_t i = gap_last; i < G; ++i) o[T + order[i]] = 0.0;
      Replicate(p, splitmix64(key ^ 0x74726565ULL), bound, order, o + T, want, o).run(buf, gap_first, gap_last, n);
      if (s.lognormal) replicate_lognormal(p, drawn, Stream{splitmix64(key ^ 0x6c6f676eULL)}, out.fit.mu, targets, o + S0);
    }
  });
  meter.finish();

  out.replicates = s.replicates;
  const double a = 0.5 * (1.0 - s.confidence);
  std::vector<double> v;
  for (std::size_t i = 0; i < S; ++i) {
    v.clear();
    for (std::size_t b = 0; b < B; ++b)
      if (!std::isnan(stats[b * S + i])) v.push_back(stats[b * S + i]);
    std::sort(v.begin(), v.end());
    Estimate e{full[i], B ? quantile7(v, a) : full[i], B ? quantile7(v, 1.0 - a) : full[i]};
    (i < T ? out.separation : i < S0 ? out.probability : out.lognormal).push_back(e);
  }
  return out;
}

// ---------------------------------------------------------------- from histograms

namespace {

// The upper edge of bin b (the histogram's value of a separation in it).
double bin_value(const HistogramDemands& h, std::size_t b) {
  return b < h.edges.size() ? h.edges[b] : std::numeric_limits<double>::infinity();
}

// The bin holding the (want + 1)-th largest of one replicate's draws: c[k] draws of record k in [0, bins), split
// down a binary tree by binomials of the record's counts (prefix sums `cum`, [k][bins + 1]).
std::size_t histogram_walk(const HistogramDemands& h, const std::vector<std::int64_t>& cum, std::vector<std::uint64_t> c,
                           std::uint64_t want, std::uint64_t key) {
  const std::size_t NB = h.bins(), W = NB + 1;
  std::size_t a = 0, e = NB;
  while (e - a > 1) {
    const std::size_t m = a + (e - a) / 2;
    std::uint64_t above = 0;
    std::vector<std::uint64_t> up(c.size(), 0);
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (!c[k]) continue;
      const auto all = cum[k * W + e] - cum[k * W + a], hi = cum[k * W + e] - cum[k * W + m];
      if (hi == all) up[k] = c[k];
      else if (hi > 0) {
        Stream g{splitmix64(key ^ splitmix64((static_cast<std::uint64_t>(a) << 32 | e) ^ splitmix64(k + 1)))};
        boost::random::binomial_distribution<std::int64_t, double> bin(static_cast<std::int64_t>(c[k]),
                                                                       static_cast<double>(hi) / static_cast<double>(all));
        up[k] = static_cast<std::uint64_t>(bin(g));
      }
      above += up[k];
    }
    if (above > want) {
      c = up, a = m;
    } else {
      want -= above;
      for (std::size_t k = 0; k < c.size(); ++k) c[k] -= up[k];
      e = m;
    }
  }
  return a;
}

}  // namespace

BootstrapResult bootstrap(const HistogramDemands& h, std::span<const double> targets, const BootstrapSettings& s) {
  if (s.replicates < 0 || !(s.confidence > 0 && s.confidence < 1))
    throw std::invalid_argument("bootstrap: replicates >= 0, confidence in (0, 1)");
  const std::size_t R = h.records, NB = h.bins(), W = NB + 1, T = targets.size(), B = static_cast<std::size_t>(s.replicates);
  if (h.counts.size() != R * NB) throw std::invalid_argument("bootstrap: histogram counts are not records x bins");
  std::vector<std::int64_t> cum(R * W, 0), n_k(R, 0);
  for (std::size_t k = 0; k < R; ++k) {
    for (std::size_t b = 0; b < NB; ++b) cum[k * W + b + 1] = cum[k * W + b] + h.counts[k * NB + b];
    n_k[k] = cum[k * W + NB];
  }
  // the full data: the bin of the (floor(t N) + 1)-th largest, counted from the top
  std::uint64_t N = 0;
  for (auto v : n_k) N += static_cast<std::uint64_t>(v);
  std::vector<double> full(T, NAN);
  for (std::size_t i = 0; i < T && N; ++i) {
    const auto want = std::min<std::uint64_t>(static_cast<std::uint64_t>(std::floor(targets[i] * static_cast<double>(N))), N - 1);
    std::uint64_t above = 0;
    std::size_t b = NB;
    while (b > 0) {
      std::uint64_t in = 0;
      for (std::size_t k = 0; k < R; ++k) in += static_cast<std::uint64_t>(h.counts[k * NB + b - 1]);
      if (above + in > want) break;
      above += in, --b;
    }
    full[i] = bin_value(h, b - 1);
  }
  std::vector<double> stats(B * T, NAN);
  Meter meter(s.hook, "report: separation bootstrap (histograms)", B);
  parallel_blocks(B, s.replicates ? s.threads : 1, [&](std::size_t first, std::size_t last) {
    std::vector<std::uint32_t> drawn(R);
    std::vector<std::uint64_t> c(R);
    for (std::size_t b = first; b < last; ++b) {
      if (!meter.step()) return;
      const std::uint64_t key = splitmix64(splitmix64(s.seed) ^ static_cast<std::uint64_t>(b));
      Stream g{key};  // the record draws of bootstrap(Prepared) for replicate b
      std::fill(drawn.begin(), drawn.end(), 0u);
      for (std::size_t i = 0; i < R; ++i) ++drawn[g.below(R)];
      std::uint64_t n = 0;
      for (std::size_t k = 0; k < R; ++k) c[k] = std::uint64_t{drawn[k]} * static_cast<std::uint64_t>(n_k[k]), n += c[k];
      if (n == 0) continue;
      for (std::size_t i = 0; i < T; ++i) {
        const auto want = std::min<std::uint64_t>(static_cast<std::uint64_t>(std::floor(targets[i] * static_cast<double>(n))), n - 1);
        stats[b * T + i] = bin_value(h, histogram_walk(h, cum, c, want, splitmix64(key ^ 0x68697374ULL)));
      }
    }
  });
  meter.finish();
  BootstrapResult out;
  out.replicates = s.replicates;
  const double a = 0.5 * (1.0 - s.confidence);
  std::vector<double> v;
  for (std::size_t i = 0; i < T; ++i) {
    v.clear();
    for (std::size_t b = 0; b < B; ++b)
      if (!std::isnan(stats[b * T + i])) v.push_back(stats[b * T + i]);
    std::sort(v.begin(), v.end());
    out.separation.push_back({full[i], B ? quantile7(v, a) : full[i], B ? quantile7(v, 1.0 - a) : full[i]});
  }
  return out;
}

// ---------------------------------------------------------------- code rules

double ddc_rho(double T1, double T2, double z1, double z2) {
  const double r = T1 / T2;  // = omega2 / omega1: (z1 + r z2) pairs z2 with the frequency in r's numerator
  const double num = 8.0 * std::sqrt(z1 * z2) * (z1 + r * z2) * std::pow(r, 1.5);
  const double den = (1.0 - r * r) * (1.0 - r * r) + 4.0 * z1 * z2 * r * (1.0 + r * r) + 4.0 * (z1 * z1 + z2 * z2) * r * r;
  return num / den;
}

std::array<double, code_rule_count> code_rule_gaps(const DesignPair& p) {
  const double abs = p.u1 + p.u2, srss = std::hypot(p.u1, p.u2);
  const double rho = ddc_rho(p.T1, p.T2, p.zeta1, p.zeta2);
  const double ddc = std::sqrt(std::max(0.0, p.u1 * p.u1 + p.u2 * p.u2 - 2.0 * rho * p.u1 * p.u2));
  return {p.code_gap, abs, srss, ddc, srss, abs, abs, srss, 0.7 * srss};
}

std::vector<Rule> code_rules(const DesignPair& p, double coefficient) {
  const std::array<double, code_rule_count> g = code_rule_gaps(p);
  const double abs = g[1], srss = g[2], ddc = g[3];
  const bool s2800 = coefficient == 0.005;
  std::string coef = std::to_string(coefficient);
  coef.erase(coef.find_last_not_of('0') + 1);
  return {
      {s2800 ? "Standard 2800" : "coefficient rule",
       s2800 ? "Standard 2800 (4th ed.): each building up to 8 storeys 0.005 h from the boundary" : "[structures] code_gap_coefficient",
       coef + " (h1 + h2)", p.code_gap},
      {"ABS", "sum of the peaks; what any set-back-from-the-boundary rule implies", "u1 + u2", abs},
      {"SRSS", "square root of the sum of squares", "sqrt(u1^2 + u2^2)", srss},
      {"DDC", "double difference combination (Jeng, Kasai & Maison 1992; Penzien 1997), rho of Der Kiureghian 1981",
       "sqrt(u1^2 + u2^2 - 2 rho u1 u2)", ddc},
      // The codes' formulas fed the mean record peaks u1, u2 -- not the codes' design displacements, which
      // code_displacement.hpp computes from a design spectrum; the names and clauses say so.
      {"ASCE 7-16 formula, same property (mean record peaks)",
       "ASCE 7-16 sec. 12.12.3 delta_MT = sqrt(delta_M1^2 + delta_M2^2) fed the mean of the records' uncoupled peaks, "
       "not delta_M", "sqrt(u1^2 + u2^2)", srss},
      {"ASCE 7-16 formula, separate lots (mean record peaks)",
       "ASCE 7-16 sec. 12.12.3 each set back from the property line by its own delta_M, fed the mean of the records' "
       "uncoupled peaks, not delta_M", "u1 + u2", abs},
      {"EC8 formula, separate properties (mean record peaks)",
       "EN 1998-1 sec. 4.4.2.7(2)a each building its own d_s from the property line, fed the mean of the records' "
       "uncoupled peaks, not d_s", "u1 + u2", abs},
      {"EC8 formula, same property (mean record peaks)",
       "EN 1998-1 sec. 4.4.2.7(2)b SRSS at the level, fed the mean of the records' uncoupled peaks, not d_s",
       "sqrt(u1^2 + u2^2)", srss},
      {"EC8 formula, same property, floor levels coincide (mean record peaks)",
       "EN 1998-1 sec. 4.4.2.7(3) 0.7 x the SRSS distance, fed the mean of the records' uncoupled peaks, not d_s",
       "0.7 sqrt(u1^2 + u2^2)", g[8]},
  };
}

}  // namespace pounding::separation
