// The study report: Tables 2 and 3, the T1 x T2 map, the cubic fit, separation advice and code rules (Markdown, CSV).
#include "pounding/report/report.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/core/parallel_for.hpp"
#include "pounding/core/timing.hpp"
#include "legacy_v1.hpp"
#include "pounding/analysis/stats.hpp"
#include "pounding/core/random.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/report/escape.hpp"
#include "pounding/report/fragility.hpp"

namespace pounding {

using namespace report_detail;

namespace {
// The published study (stochastic-pounding-monte-carlo.txt, Table 3 and eq. 10), printed beside ours only when the
// study asks for it ([report] compare_with = "stochastic-pounding").
constexpr double paper_ratios[] = {0.1, 0.2, 0.3, 0.5, 0.7, 1.0};
constexpr double paper_total[] = {71.09, 45.56, 25.26, 6.12, 1.14, 0.0};
}  // namespace

namespace report_detail {

Data::Data(const results::Results& r, const WorkHook* hook_, double* bootstrap_s_)
    : res(r), h(r.header), rec(r.records), mod(r.models), set(report_settings(r)),
      status(column_or_empty<std::uint8_t>(r, "uncoupled", "status")),
      imp_status(column_or_empty<std::uint8_t>(r, "impacts", "status")),
      peak_u1(column_or_empty<double>(r, "uncoupled", "peak_u1")),
      peak_u2(column_or_empty<double>(r, "uncoupled", "peak_u2")),
      peak_closing(column_or_empty<double>(r, "uncoupled", "peak_closing")),
      peak_force(column_or_empty<double>(r, "impacts", "peak_force")),
      imp_peak_u1(column_or_empty<double>(r, "impacts", "peak_u1")),
      imp_peak_u2(column_or_empty<double>(r, "impacts", "peak_u2")),
      impact_count(column_or_empty<std::int32_t>(r, "impacts", "impact_count")),
      h_omega(column_or_empty<double>(r, "impacts", "h_omega_contact")),
      impacts(r.has_group("impacts")),
      keep_coarse(r.settings.find("analysis", "coarse") && r.settings.text("analysis", "coarse") == "keep"),
      hook(hook_), bootstrap_s(bootstrap_s_), per_record(r.polarities()) {
  // what the analyses depend on (the mass model's aspect, rho, mbar are sampled but unused when masses are
  // given; kh matters only with contact)
  fixed_pair = true;
  using results::ModelTable;
  for (auto column : {&ModelTable::T1, &ModelTable::T2, &ModelTable::h1, &ModelTable::h2, &ModelTable::m1,
                      &ModelTable::m2, &ModelTable::k1, &ModelTable::k2, &ModelTable::fy1, &ModelTable::fy2,
                      &ModelTable::c1, &ModelTable::c2, &ModelTable::code_gap, &ModelTable::zeta1, &ModelTable::zeta2,
                      &ModelTable::alpha1, &ModelTable::alpha2, &ModelTable::kh}) {
    if (column == &ModelTable::kh && !impacts) continue;
    if (!mod.constant(column)) fixed_pair = false;
  }
  if ((red = r.group("reductions"))) {
    red_models = static_cast<std::size_t>(red->number("models"));
    fixed_pair = red->number("fixed_pair") != 0;
  }
}

separation::HistogramDemands Data::histograms() const {
  separation::HistogramDemands h;
  h.edges = red->get<double>("histogram_edges");
  const auto& c = red->get<std::int64_t>("histogram");
  const std::size_t NB = h.bins();
  h.records = independent();
  h.counts.assign(h.records * NB, 0);
  for (std::size_t row = 0; row < records(); ++row)
    for (std::size_t b = 0; b < NB; ++b) h.counts[(row / per_record) * NB + b] += c[row * NB + b];
  return h;
}

namespace {
// The reductions' count of hits at gap ratio x (one of /reductions/gap_ratios: anything else is a logic error,
// never a number read off a neighbour)
Count reduced_count(const Data& r, double ratio, int rec, int pair_i1, int pair_i2) {
  const auto& ratios = r.red->get<double>("gap_ratios");
  const auto at = std::find(ratios.begin(), ratios.end(), ratio);
  if (at == ratios.end()) throw std::logic_error(fmt::format("report: gap ratio {} is not in /reductions", ratio));
  const std::size_t g = static_cast<std::size_t>(at - ratios.begin()), G = ratios.size();
  const auto &i1 = r.red->get<std::int64_t>("pair_i1"), &i2 = r.red->get<std::int64_t>("pair_i2");
  const std::size_t P = i1.size();
  Count c;
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (rec >= 0 && static_cast<int>(k / r.per_record) != rec) continue;
    if (pair_i1 < 0) {
      c.n += r.red->get<std::int64_t>("n")[k], c.hits += r.red->get<std::int64_t>("gap_hits")[k * G + g];
      continue;
    }
    for (std::size_t p = 0; p < P; ++p)
      if (i1[p] == pair_i1 && i2[p] == pair_i2)
        c.n += r.red->get<std::int64_t>("pair_n")[k * P + p],
            c.hits += r.red->get<std::int64_t>("pair_hits")[(k * P + p) * G + g];
  }
  return c;
}
}  // namespace

Interval wilson(const Data& r, std::int64_t hits, std::int64_t n) {
  if (!r.fixed_pair || n <= 0) return wilson_interval(hits, n);
  return wilson_interval_effective(static_cast<double>(hits) / static_cast<double>(n), static_cast<double>(r.independent()));
}

std::string wilson_basis(const Data& r) {
  return r.fixed_pair
             ? fmt::format("Wilson at the observed fraction with n = {} independent records, not the {} analyses: every "
                           "model is the same {}, so a record's analyses{} are not independent draws",
                           r.independent(), r.records() * r.models(), r.set.bridge ? "bridge" : "pair",
                           r.per_record == 2 ? " (and its two signs)" : "")
             : std::string("Wilson on n = the analyses");
}

std::string Data::record_label(std::size_t row) const {
  return rec.id[row] + (row < rec.polarity.size() && rec.polarity[row] < 0 ? " (sign reversed)" : "");
}

double Data::zeta(int b, std::size_t m) const {
  const std::vector<double>& z = b == 1 ? mod.zeta1 : mod.zeta2;
  return z.empty() ? mod.zeta : z[m];  // files from before the per-building models: one damping ratio
}

const std::vector<double>& Data::periods(int b) const {
  const std::vector<double>& p = b == 1 ? mod.periods1 : mod.periods2;
  return p.empty() ? mod.periods : p;
}

separation::Demands Data::demands(bool metres) const {
  separation::Demands d;
  const std::size_t M = models();
  d.records = independent(), d.models = per_record * M;
  d.z.resize(d.records * d.models, NAN);
  for (std::size_t i = 0; i < d.z.size(); ++i)
    if (ok(status[i])) d.z[i] = metres ? peak_closing[i] : peak_closing[i] / unit(i % M);
  return d;
}

separation::BootstrapSettings Data::bootstrap_settings() const {
  separation::BootstrapSettings b;
  b.replicates = set.bootstrap;
  b.confidence = set.confidence;
  b.seed = splitmix64(set.seed ^ 0x7265706f7274ULL);  // the report's own stream ("report")
  b.hook = hook;
  return b;
}

namespace {
// The positions of `wanted` in `have` (each value found exactly), or nullopt when one is missing.
std::optional<std::vector<std::size_t>> positions(std::span<const double> wanted, const std::vector<double>& have) {
  std::vector<std::size_t> at;
  for (double v : wanted) {
    const auto it = std::find(have.begin(), have.end(), v);
    if (it == have.end()) return std::nullopt;
    at.push_back(static_cast<std::size_t>(it - have.begin()));
  }
  return at;
}
}  // namespace

separation::BootstrapResult Data::bootstrap(bool metres, std::span<const double> targets, std::span<const double> gaps,
                                            bool lognormal) const {
  for (const Computed& c : computed_) {
    if (c.metres != metres || (lognormal && !c.lognormal)) continue;
    const auto t = positions(targets, c.targets), g = positions(gaps, c.gaps);
    if (!t || !g) continue;
    separation::BootstrapResult out;
    out.replicates = c.result.replicates;
    for (std::size_t i : *t) out.separation.push_back(c.result.separation[i]);
    for (std::size_t i : *g) out.probability.push_back(c.result.probability[i]);
    if (lognormal) {
      out.fit = c.result.fit;
      for (std::size_t i : *t) out.lognormal.push_back(c.result.lognormal[i]);
    }
    return out;
  }
  separation::BootstrapSettings b = bootstrap_settings();
  b.lognormal = lognormal;
  const separation::Prepared& p = prepared(metres);
  double unused = 0;
  separation::BootstrapResult result;
  {
    timing::Stopwatch w(bootstrap_s ? *bootstrap_s : unused);
    result = separation::bootstrap(p, targets, gaps, b);
  }
  if (bootstrap_runs) ++*bootstrap_runs;
  computed_.push_back({metres, lognormal, {targets.begin(), targets.end()}, {gaps.begin(), gaps.end()}, result});
  return result;
}

const separation::Prepared& Data::prepared(bool metres) const {
  if (!prepared_[metres]) {
    double unused = 0;
    timing::Stopwatch w(bootstrap_s ? *bootstrap_s : unused);
    // demands(metres) record by record, without the array of every demand
    const std::size_t M = models(), per = per_record * M;
    prepared_[metres] = separation::prepare(
        independent(),
        [&](std::size_t k, std::vector<double>& v) {
          v.clear();
          v.reserve(per);
          for (std::size_t i = k * per; i < (k + 1) * per; ++i) {
            if (!ok(status[i])) continue;
            const double z = metres ? peak_closing[i] : peak_closing[i] / unit(i % M);
            if (!std::isnan(z)) v.push_back(z);
          }
        },
        bootstrap_settings().threads);
  }
  return *prepared_[metres];
}

namespace {
// The uncoupled counts at every ratio of xs, from one pass over the analyses on every CPU (blocks of models, their
// integer counts added after: the same for any thread count).
std::vector<UncoupledCounts> count_pass(const Data& r, const std::vector<double>& xs) {
  const std::size_t M = r.models(), X = xs.size();
  const auto& mod = r.mod;
  const bool grid = mod.i1.size() == M && mod.i2.size() == M;  // the grid indices (files may lack them)
  UncoupledCounts shape;
  for (std::size_t m = 0; grid && m < M; ++m) {
    shape.n1 = std::max<std::size_t>(shape.n1, mod.i1[m] >= 0 ? static_cast<std::size_t>(mod.i1[m]) + 1 : 0);
    shape.n2 = std::max<std::size_t>(shape.n2, mod.i2[m] >= 0 ? static_cast<std::size_t>(mod.i2[m]) + 1 : 0);
  }
  shape.per_record.resize((r.records() + r.per_record - 1) / r.per_record);
  shape.per_pair.resize(shape.n1 * shape.n2);
  const int T = thread_count(0, M / 65536 + 1);
  std::vector<std::vector<UncoupledCounts>> part(static_cast<std::size_t>(T), std::vector<UncoupledCounts>(X, shape));
  parallel_blocks(part.size(), T, [&](std::size_t t, std::size_t) {  // one block of models per thread
    std::vector<UncoupledCounts>& u = part[t];
    const std::size_t m0 = M * t / part.size(), m1 = M * (t + 1) / part.size();
    const std::size_t P = shape.per_pair.size();
    // flat, for the inner loop; slot 0 also takes the models outside the grid (added with 0)
    std::vector<std::int64_t> pair_n(std::max<std::size_t>(P, 1), 0), pair_hits(std::max<std::size_t>(P, 1) * X, 0), hits(X);
    for (std::size_t k = 0; k < r.records(); ++k) {
      std::int64_t n = 0;
      std::fill(hits.begin(), hits.end(), 0);
      for (std::size_t m = m0; m < m1; ++m) {
        const std::size_t idx = k * M + m;
        if (!r.ok(r.status[idx])) continue;
        const bool in_grid = grid && mod.i1[m] >= 0 && mod.i2[m] >= 0;
        const std::size_t pair = in_grid ? static_cast<std::size_t>(mod.i1[m]) * shape.n2 + static_cast<std::size_t>(mod.i2[m]) : 0;
        ++n, pair_n[pair] += in_grid;
        const double closing = r.peak_closing[idx], gap = r.unit(m);
        for (std::size_t j = 0; j < X; ++j) {
          const int hit = closing > xs[j] * gap;
          hits[j] += hit, pair_hits[pair * X + j] += in_grid ? hit : 0;
        }
      }
      for (std::size_t j = 0; j < X; ++j) u[j].per_record[k / r.per_record].n += n, u[j].per_record[k / r.per_record].hits += hits[j];
    }
    for (std::size_t j = 0; j < X; ++j)
      for (std::size_t q = 0; q < P; ++q) u[j].per_pair[q].n += pair_n[q], u[j].per_pair[q].hits += pair_hits[q * X + j];
  });
  std::vector<UncoupledCounts> out(X, shape);
  for (std::size_t j = 0; j < X; ++j) {
    for (const auto& u : part)
      for (std::size_t i = 0; i < shape.per_record.size(); ++i)
        out[j].per_record[i].n += u[j].per_record[i].n, out[j].per_record[i].hits += u[j].per_record[i].hits;
    for (const auto& u : part)
      for (std::size_t i = 0; i < shape.per_pair.size(); ++i)
        out[j].per_pair[i].n += u[j].per_pair[i].n, out[j].per_pair[i].hits += u[j].per_pair[i].hits;
    for (const Count& c : out[j].per_record) out[j].total.n += c.n, out[j].total.hits += c.hits;
  }
  return out;
}
}  // namespace

const UncoupledCounts& Data::uncoupled_counts(double x) const {
  const auto cached = [&](double y) -> const UncoupledCounts* {
    for (const auto& [ratio, counts] : uncoupled_)
      if (ratio == y) return counts.get();
    return nullptr;
  };
  if (const UncoupledCounts* u = cached(x)) return *u;
  // x and every gap ratio of the study not counted yet, in one pass (the tables ask for each of them)
  std::vector<double> xs{x};
  for (double y : set.gap_ratios)
    if (!cached(y) && std::find(xs.begin(), xs.end(), y) == xs.end()) xs.push_back(y);
  std::vector<UncoupledCounts> counts = count_pass(*this, xs);
  for (std::size_t j = 0; j < xs.size(); ++j) uncoupled_.emplace_back(xs[j], std::make_shared<UncoupledCounts>(std::move(counts[j])));
  return *cached(x);
}

std::string pct(double p) { return std::isnan(p) ? "n/a" : fmt::format("{:.2f}%", p); }

// uncoupled: hit when peak closing > ratio * code gap (contact is delta = u1 - u2 - gap > 0). Per record, per pair
// and in all from Data::uncoupled_counts (one pass per ratio: the period matrix and the CSV asked a pass per pair and
// ratio, 726 passes over the 10^8 analyses of a large study); a record and a pair together by their own pass.
Count count_uncoupled(const Data& r, double ratio, int rec, int pair_i1, int pair_i2) {
  if (r.red) return reduced_count(r, ratio, rec, pair_i1, pair_i2);
  if (rec < 0 || pair_i1 < 0) {
    const UncoupledCounts& u = r.uncoupled_counts(ratio);
    if (pair_i1 < 0) return rec < 0 ? u.total : static_cast<std::size_t>(rec) < u.per_record.size() ? u.per_record[rec] : Count{};
    const auto a = static_cast<std::size_t>(pair_i1), b = static_cast<std::size_t>(pair_i2);
    return pair_i2 >= 0 && a < u.n1 && b < u.n2 ? u.per_pair[a * u.n2 + b] : Count{};
  }
  Count c;
  const std::size_t M = r.models();
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (rec >= 0 && static_cast<int>(k / r.per_record) != rec) continue;
    for (std::size_t m = 0; m < M; ++m) {
      if (pair_i1 >= 0 && (r.mod.i1[m] != pair_i1 || r.mod.i2[m] != pair_i2)) continue;
      const std::size_t idx = k * M + m;
      if (!r.ok(r.status[idx])) continue;
      ++c.n;
      c.hits += r.peak_closing[idx] > ratio * r.unit(m);
    }
  }
  return c;
}

}  // namespace report_detail

namespace {

Count count_coupled(const Data& r, std::size_t g, int rec) {
  Count c;
  const std::size_t M = r.models(), G = r.gaps();
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (rec >= 0 && static_cast<int>(k) != rec) continue;
    for (std::size_t m = 0; m < M; ++m) {
      const std::size_t idx = (k * M + m) * G + g;
      if (!r.ok(r.imp_status[idx]) || !r.ok(r.status[k * M + m])) continue;
      ++c.n;
      c.hits += r.impact_count[idx] > 0;
    }
  }
  return c;
}

// The curve from /reductions/curve_hits (exact: the same z > x counts), at its own ratios only.
Curve reduced_curve(const Data& r, double step, int n, int record) {
  const auto& xs = r.red->get<double>("curve_x");
  const auto& hits = r.red->get<std::int64_t>("curve_hits");
  const auto& ok = r.red->get<std::int64_t>("n");
  const std::size_t C = xs.size();
  Curve c;
  std::vector<std::int64_t> h(C, 0);
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (record >= 0 && static_cast<int>(k / r.per_record) != record) continue;
    c.n += ok[k];
    for (std::size_t i = 0; i < C; ++i) h[i] += hits[k * C + i];
  }
  for (int i = 1; i <= n; ++i) {
    const double x = step * i;
    const auto at = std::find(xs.begin(), xs.end(), x);
    if (at == xs.end()) throw std::logic_error(fmt::format("report: curve ratio {} is not in /reductions", x));
    c.x.push_back(x);
    c.p.push_back(c.n ? static_cast<double>(h[static_cast<std::size_t>(at - xs.begin())]) / static_cast<double>(c.n) : NAN);
  }
  return c;
}

Curve curve_of(const Data& r, double step, double xmax, int record) {
  Curve c;
  const int n = static_cast<int>(std::floor(xmax / step + 1e-9));
  if (r.red) return reduced_curve(r, step, n, record);
  if (record < 0) {  // every ok analysis: the ranked demands in gap ratios the bootstrap shares (no sort here)
    const separation::Prepared& p = r.prepared(false);
    c.n = static_cast<std::int64_t>(p.N);
    for (int i = 1; i <= n; ++i) {
      const double x = step * i;  // hits: z > x (strict, like delta > 0)
      c.x.push_back(x);
      c.p.push_back(p.N ? static_cast<double>(p.N - p.bound(x)) / static_cast<double>(p.N) : NAN);
    }
    return c;
  }
  std::vector<double> z;  // peak closing / code gap
  const std::size_t M = r.models();
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (static_cast<int>(k / r.per_record) != record) continue;
    for (std::size_t m = 0; m < M; ++m) {
      const std::size_t idx = k * M + m;
      if (r.ok(r.status[idx])) z.push_back(r.peak_closing[idx] / r.unit(m));
    }
  }
  std::sort(z.begin(), z.end());
  c.n = static_cast<std::int64_t>(z.size());
  for (int i = 1; i <= n; ++i) {
    double x = step * i;
    // hits: z > x (strict, like delta > 0)
    auto it = std::upper_bound(z.begin(), z.end(), x);
    c.x.push_back(x);
    c.p.push_back(z.empty() ? NAN : static_cast<double>(z.end() - it) / static_cast<double>(z.size()));
  }
  return c;
}

// The cubic of eq. 10 on the continuous curve over [fit_min, fit_max], or nothing with fewer than 4 points.
std::optional<CubicFit> ratio_fit(const Data& r, std::size_t* points = nullptr) {
  const ReportSettings& set = r.set;
  Curve curve = curve_of(r, set.curve_step, set.curve_max, -1);
  std::vector<double> fx, fy;
  for (std::size_t i = 0; i < curve.x.size(); ++i)
    if (curve.x[i] >= set.fit_min - 1e-12 && curve.x[i] <= set.fit_max + 1e-12)
      fx.push_back(curve.x[i]), fy.push_back(100 * curve.p[i]);
  if (points) *points = fx.size();
  if (fx.size() < 4) return std::nullopt;
  return fit_cubic(fx, fy);
}

// Markdown output, section by section.
class Markdown {
 public:
  explicit Markdown(const Data& r) : r(r) {}
  std::string text() && { return std::move(s); }

  template <typename... A>
  void out(fmt::format_string<A...> f, A&&... a) {
    s += fmt::format(f, std::forward<A>(a)...);
  }
  void raw(const std::string& t) { s += t; }

  void overview();
  void gap_axis();
  void per_record();
  void total();
  void coupled_counts();
  void period_matrix();
  void fit();
  void impacts_table();
  void restitution_note();
  void restitution_per_element();

 private:
  void excluded_uncoupled();
  std::string excluded_coupled();
  const Data& r;
  std::string s;
};

void Markdown::overview() {
  const std::size_t R = r.records(), M = r.models();
  // every string read from the results file is escaped (report/escape.hpp): a title with a newline and a table row
  // forged the answer (issue 44 item 9)
  out("# Pounding study: {}\n\n", report::md_text(r.h.title));
  if (!r.h.exclusion_warning.empty())
    out("> **WARNING — results not trustworthy as they stand:** {}.\n\n", report::md_text(r.h.exclusion_warning));
  out("- results: {} (written {}, commit {}, {} rank(s), wall time {:.2f} s)\n", report::md_code(r.res.path),
      report::md_text(r.h.date), report::md_text(r.h.git_commit), r.h.ranks, r.h.wall_time_s);
  out("- machine: {}\n", report::md_text(run_machine(r.h)));
  out("- scene: **{}** — {}\n", report::md_text(r.h.scene), report::md_text(r.h.scene_reason));
  out("- contact: {} ({}), e = {}; stepper {}\n", report::md_text(r.h.contact_law), report::md_text(r.h.damping_law),
      r.h.restitution, report::md_text(r.h.stepper));
  std::size_t synth = 0, generated = 0;
  for (std::size_t k = 0; k < R; ++k) synth += r.rec.synthetic[k], generated += record_kind(r.rec, k) == "generated";
  const std::size_t N = r.independent();
  // motions a generator made for the study ([records.motions]) are neither stand-ins nor recorded (issue 45 item 3)
  out("- {} records ({}{} synthetic stand-ins, {} real), {} models per record, seed {}\n", N,
      generated ? fmt::format("{} generated, ", generated / r.per_record) : "", synth / r.per_record,
      (R - synth - generated) / r.per_record, M, r.h.seed);
  const std::string mover = r.set.bridge ? "a joint closes (its left frame moves towards its right one)"
                                         : "building 1 moves towards building 2";
  const std::string closing = r.set.bridge ? "u_left - u_right at a joint" : "u1 - u2";
  out("- record polarity: **{}** — {}\n", r.res.polarity(),
      r.per_record == 2
          ? fmt::format("every record applied with both signs, as two analyses of the same record ({} analyses per "
                        "model); pounding counts when {} (peak of {}), and a ground motion's sign is arbitrary. The "
                        "statistics over records keep a record's two signs together",
                        R, mover, closing)
          : fmt::format("every record applied with its sign as recorded ([records] polarity = \"both\" adds the "
                        "reversed sign: a ground motion's sign is arbitrary, and pounding counts only when {})",
                        mover));
  if (const auto* g = r.res.settings.find("records.motions", "generator"); g && std::holds_alternative<std::string>(*g))
    out("- records generated by the study ([records.motions], the generator of `pounding motions`): {}\n",
        report::md_text(std::get<std::string>(*g)));
  gap_axis();
}

// What the gap axis is (ratios x of d, or metres) and how a gap's verdict is counted; the excluded analyses.
void Markdown::gap_axis() {
  const bool m = r.set.metres;
  if (r.set.bridge) {
    if (m)
      out("- a bridge study with gaps in metres ([gaps] metres): the study gap g is the gap of the joint(s) at d = {:g} "
          "m, the smallest joint gap; joint j's gap is g + (gap_j - d)\n",
          r.set.bridge_d);
    else
      out("- a bridge study: gaps are ratios x of d = {:g} m, the smallest joint gap; joint j's gap is x d + (gap_j - d)\n",
          r.set.bridge_d);
    excluded_uncoupled();
    out("\nAt least one impact at {} is counted from the uncoupled peak closings: before the first contact the "
        "motion is the uncoupled one, so D = max over the joints of (peak closing - (gap_j - d)) > {} is exactly "
        "\"some joint touches at least once\" (restrainers, bearings and abutments act in both runs).\n",
        m ? "gap g" : "ratio x", m ? "g" : "x d");
    return;
  }
  out("- {}\n", m ? "gaps in metres ([gaps] metres): every model's gap at an axis point is that many metres, so the "
                    "tables, the curve and the advice are in metres"
               : r.set.pair ? "a pair study: both buildings' heights are given, so separations are in metres"
                            : "a grid study: heights come from the period-height rule, so gaps are ratios x of the "
                              "code gap d and no separation is given in metres");
  excluded_uncoupled();
  if (m)
    out("\nAt least one impact at gap g (m) is counted from the uncoupled peak closing: the motion before the first "
        "contact is the uncoupled motion, so peak(u1 - u2) > g is exactly \"touches at least once\".\n");
  else
    out("\nAt least one impact at gap g = ratio x d (d = {} (h1 + h2){}) is counted from the "
        "uncoupled peak closing: the motion before the first contact is the uncoupled motion, so "
        "peak(u1 - u2) > g is exactly \"touches at least once\".\n",
        r.set.code_gap_coefficient, r.set.code_gap_coefficient == 0.005 ? ", Standard 2800" : "");
}

physics::CoarseSummary coarse_summary(const Data& r);

void Markdown::excluded_uncoupled() {
  const std::size_t R = r.records(), M = r.models();
  std::size_t bad = 0;
  for (auto v : r.status) bad += !r.ok(v);
  if (r.red) {  // per record only: the models are not kept
    const auto& ex = r.red->get<std::int64_t>("excluded");
    for (auto v : ex) bad += static_cast<std::size_t>(v);
    out("- excluded (diverged or non-finite) analyses: **{}** of {}\n", bad, R * M);
    for (std::size_t k = 0; k < R; ++k)
      if (ex[k]) out("  - record {}: {} excluded\n", report::md_text(r.record_label(k)), ex[k]);
    return;
  }
  // the header's (and the banner's) count: uncoupled and coupled analyses together; the uncoupled part is this one
  const std::int64_t all_bad = r.h.excluded_analyses, all = r.h.total_analyses;
  if (r.impacts && all > static_cast<std::int64_t>(R * M))
    out("- excluded analyses: **{}** of {} ({:.3g} %): uncoupled (diverged or non-finite) {} of {}; coupled ({}) {} "
        "of {}{}\n",
        all_bad, all, all ? 100.0 * static_cast<double>(all_bad) / static_cast<double>(all) : 0.0, bad, R * M,
        r.keep_coarse ? "diverged or non-finite; coarse ones kept" : "coarse, diverged or non-finite",
        all_bad - static_cast<std::int64_t>(bad), all - static_cast<std::int64_t>(R * M),
        r.h_omega.empty() ? std::string() : coarse_summary(r).refined_text());
  else
    out("- excluded (diverged or non-finite) analyses: **{}** of {}\n", bad, R * M);
  if (!bad) return;
  int shown = 0;
  for (std::size_t k = 0; k < R && shown < 10; ++k)
    for (std::size_t m = 0; m < M && shown < 10; ++m)
      if (!r.ok(r.status[k * M + m])) {
        out("  - record {} model (T1 {:.2f}, T2 {:.2f}, sample {}): status {}\n", report::md_text(r.record_label(k)), r.mod.T1[m],
            r.mod.T2[m], r.mod.sample[m], to_string(static_cast<LaneStatus>(r.status[k * M + m])));
        ++shown;
      }
}


// Table 2: per record
void Markdown::per_record() {
  const auto& ratios = r.set.gap_ratios;
  out("\n## Probability of at least one impact per record (Table 2)\n\n{}| record | synthetic | PGA g |",
      r.per_record == 2 ? "Each record with both signs (polarity \"both\"): its two analyses per model counted together.\n\n"
                        : "");
  for (double x : ratios) out(" {} |", gap_title(r, x));
  out("\n|---|---|---|");
  for (std::size_t i = 0; i < ratios.size(); ++i) out("---|");
  out("\n");
  for (std::size_t k = 0; k < r.independent(); ++k) {
    const std::size_t row = k * r.per_record;
    out("| {} | {} | {:.2f} |", report::md_cell(r.rec.id[row]), synthetic_cell(r.rec, row), r.rec.pga_g[row]);
    for (double x : ratios) {
      Count c = count_uncoupled(r, x, static_cast<int>(k));
      out(" {} ({}) |", c.hits, pct(c.pct()));
    }
    out("\n");
  }
}

// Table 3: total with Wilson intervals (beside the paper when the study compares with it)
// Table 3's interval clustered by record (analysis::wilson_clustered): each record's (both signs') ok analyses and
// those whose uncoupled closing exceeds x d.
Interval record_clustered(const Data& r, double x) {
  const std::size_t M = r.models(), C = r.independent();
  std::vector<double> hits(C, 0.0), sizes(C, 0.0);
  for (std::size_t k = 0; k < r.records(); ++k)
    for (std::size_t m = 0; m < M; ++m) {
      const std::size_t idx = k * M + m, c = k / r.per_record;
      if (!r.ok(r.status[idx]) || c >= C) continue;
      sizes[c] += 1.0, hits[c] += r.peak_closing[idx] > x * r.unit(m);
    }
  return wilson_clustered(hits, sizes).w;
}

void Markdown::total() {
  out("\n## Total probability of pounding (Table 3), 95 % Wilson intervals\n\n");
  out("The Wilson interval is the sampling error of the models under this fixed set of records; it leaves out "
      "record-to-record variability{}.{}\n\n",
      r.set.pair ? " (the separation in metres above has the bootstrap interval that includes it)" : "",
      r.fixed_pair ? " Here: " + wilson_basis(r) + "." : "");
  const bool paper = r.paper();
  out("| {} | models with impact | probability | 95 % interval |{}\n|---|---|---|---|{}\n", r.axis_title(),
      paper ? " paper |" : "", paper ? "---|" : "");
  const bool clustered = r.set.bridge && !r.fixed_pair && !r.red;
  if (clustered)
    out("For this bridge study the interval is clustered by record (as the joints figure's): Wilson at the observed "
        "fraction with Kish's effective sample size from the {} records' totals (n_eff between the records and the "
        "analyses), since a record's sampled bridges{} share its ground motion and are not independent draws.\n\n",
        r.independent(), r.per_record == 2 ? " and its two signs" : "");
  for (double x : r.set.gap_ratios) {
    Count c = count_uncoupled(r, x, -1);
    Interval w = clustered ? record_clustered(r, x) : wilson(r, c.hits, c.n);
    std::string paper_cell = "-";
    for (int j = 0; j < 6; ++j)
      if (std::abs(paper_ratios[j] - x) < 1e-12) paper_cell = pct(paper_total[j]);
    out("| {} | {} / {} | {} | [{:.2f}%, {:.2f}%] |{}\n", x, c.hits, c.n, pct(c.pct()), 100 * w.lo, 100 * w.hi,
        paper ? fmt::format(" {} |", paper_cell) : "");
  }
}

void Markdown::coupled_counts() {
  if (!r.impacts) return;
  out("\nCoupled runs ({}): models with at least one counted impact per gap, beside the uncoupled count. Whether a "
      "pair touches depends only on the motion before its first contact, so on the same analyses the two counts "
      "must agree (\"uncoupled, same analyses\"); the coupled count leaves out the analyses excluded at that gap "
      "(coarse, diverged or non-finite coupled runs), which is why its n can be below the uncoupled n:\n\n"
      "| {} | coupled | uncoupled, same analyses | uncoupled, all | excluded coupled runs |\n"
      "|---|---|---|---|---|\n",
      report::md_text(r.h.contact_law), r.axis_title());
  const std::size_t M = r.models(), G = r.gaps();
  for (std::size_t g = 0; g < G; ++g) {
    const double x = r.res.gap_ratios[g];
    Count c = count_coupled(r, g, -1), u = count_uncoupled(r, x, -1), same;
    std::size_t excluded = 0;
    for (std::size_t k = 0; k < r.records(); ++k)
      for (std::size_t m = 0; m < M; ++m) {
        if (!r.ok(r.status[k * M + m])) continue;
        if (!r.ok(r.imp_status[(k * M + m) * G + g])) {
          ++excluded;
          continue;
        }
        ++same.n;
        same.hits += r.peak_closing[k * M + m] > x * r.unit(m);
      }
    out("| {} | {} / {} | {} / {} | {} / {} | {} |\n", x, c.hits, c.n, same.hits, same.n, u.hits, u.n, excluded);
  }
}

// T1 x T2 matrix (rows building 1's grid, columns building 2's); nothing for a single period pair
void Markdown::period_matrix() {
  const auto& ratios = r.set.gap_ratios;
  const auto &p1 = r.periods(1), &p2 = r.periods(2);
  if (p1.size() * p2.size() <= 1) return;
  double xm = ratios[std::min<std::size_t>(ratios.size() - 1, 2)];
  out("\n## Probability by period pair at {} {} (rows T1, columns T2)\n\n| T1 \\ T2 |", r.set.metres ? "gap" : "gap ratio",
      r.set.metres ? gap_title(r, xm) : fmt::format("{}", xm));
  for (double T : p2) out(" {:.2f} |", T);
  out("\n|---|");
  for (std::size_t j = 0; j < p2.size(); ++j) out("---|");
  out("\n");
  for (std::size_t a = 0; a < p1.size(); ++a) {
    out("| {:.2f} |", p1[a]);
    for (std::size_t b = 0; b < p2.size(); ++b) {
      Count c = count_uncoupled(r, xm, -1, static_cast<int>(a), static_cast<int>(b));
      out(" {:.1f} |", c.pct());
    }
    out("\n");
  }
}

// cubic fit on the continuous curve (eq. 10)
void Markdown::fit() {
  const ReportSettings& set = r.set;
  std::size_t points = 0;
  const std::optional<CubicFit> f = ratio_fit(r, &points);
  out("\n## Cubic fit of probability (%) versus {} (eq. 10)\n\n", set.metres ? "gap x in metres" : "gap ratio x");
  if (!f) {
    out("too few curve points in [{}, {}] to fit a cubic\n", set.fit_min, set.fit_max);
    return;
  }
  out("Fitted on the continuous curve, {} points for x in [{}, {}]:\n\n    PP = {:.1f} x^3 {:+.1f} x^2 {:+.1f} x {:+.1f}    "
      "(R^2 = {:.4f})\n",
      points, set.fit_min, set.fit_max, f->c[3], f->c[2], f->c[1], f->c[0], f->r2);
  if (r.paper()) out("\npaper (eq. 10): PP = -213.7 x^3 + 510.3 x^2 - 403.4 x + 106.8\n");
}

// The coupled analyses excluded (diverged or non-finite): a count and the first 10, or "".
std::string Markdown::excluded_coupled() {
  const std::size_t R = r.records(), M = r.models(), G = r.gaps();
  std::string listing;
  std::size_t nbad = 0;
  for (std::size_t k = 0; k < R; ++k)
    for (std::size_t m = 0; m < M; ++m)
      for (std::size_t g = 0; g < G; ++g)
        if (!r.ok(r.imp_status[(k * M + m) * G + g])) {
          if (++nbad <= 10)
            listing += fmt::format("  - record {} model (T1 {:.2f}, T2 {:.2f}, sample {}) at {} {}: {}\n",
                                   report::md_text(r.record_label(k)), r.mod.T1[m], r.mod.T2[m], r.mod.sample[m],
                                   r.set.metres ? "gap" : "gap ratio",
                                   r.set.metres ? gap_title(r, r.res.gap_ratios[g]) : fmt::format("{}", r.res.gap_ratios[g]),
                                   to_string(static_cast<LaneStatus>(r.imp_status[(k * M + m) * G + g])));
        }
  return nbad ? fmt::format("\nExcluded coupled analyses (diverged or non-finite, never counted as results): **{}**{}\n{}",
                            nbad, nbad > 10 ? " (first 10 listed)" : "", listing)
              : std::string();
}

// The resolution guard over the coupled analyses (physics/resolution.hpp), from the results alone.
physics::CoarseSummary coarse_summary(const Data& r) {
  physics::CoarseSummary c;
  c.limit = physics::resolution_limit(parse_stepper(r.h.stepper), false, parse_contact_law(r.h.contact_law));
  c.kept = r.keep_coarse;
  c.refine = r.res.settings.find("analysis", "coarse") && r.res.settings.text("analysis", "coarse") == "refine";
  const results::Field* f = r.res.find("impacts", "substeps");  // coarse = "refine": each analysis's substeps
  const std::vector<std::int32_t>* used = f ? &std::get<std::vector<std::int32_t>>(f->data) : nullptr;
  const std::size_t MG = r.models() * r.gaps();
  for (std::size_t k = 0; k < r.records(); ++k) {
    const double dt = r.rec.dt[k];
    const int q = r.h.max_dt > 0 ? static_cast<int>(std::ceil(dt / r.h.max_dt - 1e-9)) : 1;
    const int n = std::max(static_cast<int>(r.h.substeps), q);
    for (std::size_t i = k * MG; i < (k + 1) * MG; ++i) c.add(r.h_omega[i], r.imp_status[i], used ? (*used)[i] : n, n, dt);
  }
  return c;
}

void Markdown::impacts_table() {
  if (!r.impacts) return;
  out("\n## Impacts scene: counts, forces, amplification (peak with pounding / peak without)\n\n"
      "| {} | mean impacts (pounding models) | max impacts | median peak force MN | max peak force MN | "
      "mean amplification u1 | mean amplification u2 | excluded |\n|---|---|---|---|---|---|---|---|\n",
      r.axis_title());
  const std::size_t R = r.records(), M = r.models(), G = r.gaps();
  const std::string excluded_note = excluded_coupled();
  for (std::size_t g = 0; g < G; ++g) {
    double sum = 0, a1 = 0, a2 = 0;
    std::int64_t n = 0, maxc = 0, na = 0, excl = 0;
    std::vector<double> forces;
    for (std::size_t k = 0; k < R; ++k)
      for (std::size_t m = 0; m < M; ++m) {
        const std::size_t idx = (k * M + m) * G + g, u = k * M + m;
        if (!r.ok(r.imp_status[idx]) || !r.ok(r.status[u])) {
          ++excl;
          continue;
        }
        a1 += r.imp_peak_u1[idx] / r.peak_u1[u], a2 += r.imp_peak_u2[idx] / r.peak_u2[u], ++na;
        if (r.impact_count[idx] > 0) {
          sum += r.impact_count[idx], ++n, maxc = std::max<std::int64_t>(maxc, r.impact_count[idx]);
          forces.push_back(r.peak_force[idx] / 1e6);
        }
      }
    std::sort(forces.begin(), forces.end());
    out("| {} | {:.2f} | {} | {} | {} | {:.3f} | {:.3f} | {} |\n", r.res.gap_ratios[g], n ? sum / n : 0.0, maxc,
        forces.empty() ? "-" : fmt::format("{:.2f}", forces[forces.size() / 2]),
        forces.empty() ? "-" : fmt::format("{:.2f}", forces.back()), na ? a1 / na : NAN, na ? a2 / na : NAN, excl);
  }
  s += excluded_note;
  if (!r.h_omega.empty()) out("\n{}\n", physics::describe(coarse_summary(r)));
  restitution_note();
}

// [contact] restitution: e(v0) at every impact, and how many impacts lay outside the curve's valid range (summed over
// a system's elements: a bridge's joints, a shear pair's floors).
void Markdown::restitution_note() {
  if (const results::Field* f = r.res.find("impacts", "restitution_outside")) {
    const auto& outside = std::get<std::vector<std::int32_t>>(f->data);
    std::int64_t n_out = 0, n_all = 0;
    for (std::size_t i = 0; i < outside.size() && i < r.impact_count.size(); ++i)
      if (r.ok(r.imp_status[i]) && outside[i] >= 0) n_out += outside[i], n_all += std::max(0, r.impact_count[i]);
    out("\nEach impact took e(v0), the restitution at its approach velocity ({}). {} of {} impacts (analyses not "
        "excluded) had an approach velocity outside the curve's valid range, where e is extrapolated{}.\n",
        r.res.settings.find("contact", "restitution") ? report::md_text(r.res.settings.text("contact", "restitution"))
                                                      : "[contact] restitution",
        n_out, n_all, n_out > 0 ? ": their share is the part of the answer the curve's calibration does not cover" : "");
    restitution_per_element();
  }
}

// A System's impacts outside the e(v0) curve's range per contact element (a bridge's joints, a pair's levels), from
// impacts/element_restitution_outside [R, M, G, E]: the sum above, split.
void Markdown::restitution_per_element() {
  const results::Field* f = r.res.find("impacts", "element_restitution_outside");
  const std::size_t E = r.res.system.element_label.size();
  if (!f || E == 0) return;
  const auto& outside = std::get<std::vector<std::int32_t>>(f->data);
  std::vector<std::int64_t> n(E, 0);
  for (std::size_t i = 0; i < r.imp_status.size() && (i + 1) * E <= outside.size(); ++i)
    if (r.ok(r.imp_status[i]))
      for (std::size_t e = 0; e < E; ++e) n[e] += std::max(0, outside[i * E + e]);
  std::string list;
  for (std::size_t e = 0; e < E; ++e)
    if (r.res.system.group_study_gap.empty() || r.res.system.group_study_gap[static_cast<std::size_t>(
                                                     r.res.system.element_group[e])])
      list += fmt::format("{}{} {}", list.empty() ? "" : ", ", report::md_text(r.res.system.element_label[e]), n[e]);
  out("\nImpacts outside the valid range per contact element: {}.\n", list);
}

}  // namespace

namespace report_detail {

// The gap ratio x as a column title; "x d = g m" when the code gap is the same for every model.
std::string gap_title(const Data& r, double x) {
  if (r.set.metres) return fmt::format("{} m", x);
  if (r.red && r.set.pair && r.red->number("code_gap_min") == r.red->number("code_gap_max"))
    return fmt::format("{}d = {:.3f} m", x, x * r.red->number("code_gap_min"));
  if ((!r.set.pair && !r.set.bridge) || r.mod.code_gap.empty()) return fmt::format("{}d", x);
  const auto [lo, hi] = std::minmax_element(r.mod.code_gap.begin(), r.mod.code_gap.end());
  return *lo == *hi ? fmt::format("{}d = {:.3f} m", x, x * *lo) : fmt::format("{}d", x);
}

std::string axis_label(const Data& r, double x) { return r.set.metres ? fmt::format("{:g} m", x) : fmt::format("x = {:g}", x); }

std::string record_kind(const results::RecordTable& t, std::size_t k) {
  if (t.synthetic[k]) return "stand-in";
  // a generated motion's source names its generator ("synthetic:spatial seed 1 realisation 3 support 1",
  // motion/spatial.cpp); a recorded one's is its file or repository
  return k < t.source.size() && t.source[k].rfind("synthetic:", 0) == 0 ? "generated" : "recorded";
}

std::string synthetic_cell(const results::RecordTable& t, std::size_t k) {
  const std::string kind = record_kind(t, k);
  return kind == "stand-in" ? "yes" : kind == "generated" ? "generated" : "no";
}

// Why a report is made from the reductions: the study kept only them, or (per_model = "stream") the run's own
// report is, while every model's peaks went to the results file.
std::string reductions_reason(const Data& r) {
  if (r.res.settings.find("outputs", "stream"))
    return "this run's report is made from the reductions it kept in memory ([outputs] per_model = \"stream\"); "
           "every model's peaks are in the results file, and `pounding report` on it gives this section";
  return "the study kept only its reductions ([outputs] per_model = false)";
}

// What the reductions-only report reads from histograms, and at which resolution.
std::string histogram_note(const Data& r) {
  const double per_decade = r.red->number("histogram_per_decade");
  return fmt::format("**From histograms** ({}): every x in this table is the upper edge of "
                     "its bin on the log grid of {:g} bins per decade (bin width a factor {:.4f}, i.e. {:.2f} %), so "
                     "it is at most one bin width above the exact order statistic a per-model run gives; the "
                     "bootstrap draws the models within a record by counts of its histogram.\n\n",
                     r.res.settings.find("outputs", "stream") ? "the reductions of [outputs] per_model = \"stream\""
                                                              : "[outputs] per_model = false",
                     per_decade, std::pow(10.0, 1.0 / per_decade), 100 * (std::pow(10.0, 1.0 / per_decade) - 1));
}

// The advice's bootstrap from /reductions' histograms, timed as the report's bootstrap.
separation::BootstrapResult histogram_bootstrap(const Data& r, std::span<const double> targets) {
  double unused = 0;
  timing::Stopwatch w(r.bootstrap_s ? *r.bootstrap_s : unused);
  if (r.bootstrap_runs) ++*r.bootstrap_runs;
  return separation::bootstrap(r.histograms(), targets, r.bootstrap_settings());
}

// A grid study's (or a bridge's) advice rows: per target the exact order statistic with its bootstrap interval and,
// for a grid, the cubic's root (eq. 10) -- built once, formatted by grid_advice_section (Markdown) and
// separation_csv (rows separation_cubic). [outputs] per_model = false: the same bootstrap on the per-record
// histograms (each x is its bin's upper edge).
std::vector<AdviceRow> grid_advice_rows(const Data& r, int* replicates) {
  const ReportSettings& set = r.set;
  std::vector<double> targets;
  for (double t : set.targets) targets.push_back(t / 100.0);
  // a bridge: with the lognormal, for the targets its records do not resolve (as the pair's advice; one bootstrap
  // with separation_csv's, which asks the same)
  const separation::BootstrapResult b =
      r.red ? histogram_bootstrap(r, targets) : r.bootstrap(false, targets, {}, set.bridge);
  if (replicates) *replicates = b.replicates;
  // a bridge's d is one number (the smallest joint gap); a grid's heights come from the period-height rule: ratios,
  // and the cubic's root beside them
  const std::optional<CubicFit> f = set.bridge ? std::nullopt : ratio_fit(r);
  const std::size_t N = !set.bridge ? 0 : r.red ? r.independent() : record_peaks(r.demands(false)).size();
  std::vector<AdviceRow> rows;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    rows.push_back({set.targets[i], b.separation[i],
                    f ? solve_fit(*f, set.targets[i], set.fit_min, set.fit_max) : std::nullopt});
    if (!set.bridge) continue;
    rows.back().records = N;
    rows.back().resolved = resolved_by(targets[i], N);
    if (i < b.lognormal.size()) rows.back().lognormal = b.lognormal[i];
  }
  return rows;
}

// A grid study's advice in gap ratios: the exact order statistic, its bootstrap interval, the cubic's root.
std::string grid_advice_section(const Data& r) {
  const ReportSettings& set = r.set;
  int replicates = 0;
  const std::vector<AdviceRow> rows = grid_advice_rows(r, &replicates);
  // the method, in the words of both forms of the table (a bridge's joints, a grid's ratios)
  const std::string exceed = fmt::format(
      "x is the smallest {} that at most floor(t n) of the n analyses exceed (the exact empirical curve",
      set.metres ? "gap (m)" : "gap ratio");
  const std::string interval = fmt::format(
      "The interval is a two-stage bootstrap over records and over models within records ({} replicates, {:.0f} %), "
      "so it includes record-to-record variability; the advice is its upper end.",
      replicates, 100 * set.confidence);
  std::string s =
      set.bridge
          ? fmt::format("\n## Joint gap advice (any joint)\n\n{} of D); the gap of the joint(s) at d is {}, every other "
                        "joint's {} + (gap_j - d). {} The records, not the analyses, limit how fine a target can be: "
                        "with N independent records a target t with floor(t N) = 0 is **not resolved by N records** "
                        "(the empirical gap is (close to) the largest record's D, whatever t); its advice is then the "
                        "upper end of a lognormal fitted to D (parametric, extrapolated; D <= 0 a point mass at 0), so "
                        "labelled.\n\n| target | x{} | gap {} (m) | {:.0f} % interval (m) | advice (m, upper end) |\n"
                        "|---|---|---|---|---|\n",
                        exceed, set.metres ? "x" : "x d", set.metres ? "x" : "x d", interval, set.metres ? " m" : "",
                        set.metres ? "x" : "x d", 100 * set.confidence)
          : set.metres
          ? fmt::format("\n## Separation advice in metres\n\n{}). {} The gaps are metres ([gaps] metres), every "
                        "model's gap the same, so the advice is directly a separation in metres.\n\n| target | x m | "
                        "{:.0f} % interval m | advice m (upper end) | cubic m |\n|---|---|---|---|---|\n",
                        exceed, interval, 100 * set.confidence)
          : fmt::format("\n## Separation advice in gap ratios x of the code gap d\n\n{}). {} Heights here come from the "
                        "period-height rule, so no separation is given in metres.\n\n| target | x | {:.0f} % interval | "
                        "advice x (upper end) | cubic x |\n|---|---|---|---|---|\n",
                        exceed, interval, 100 * set.confidence);
  if (r.red) s.insert(s.find("\n\n| target") + 2, histogram_note(r));
  for (const AdviceRow& row : rows) {
    const separation::Estimate& e = row.estimate;
    const double d = set.metres ? 1.0 : set.bridge_d;  // a bridge's x in metres already on a metres axis
    const std::string lognormal = std::isnan(row.lognormal.hi) ? "n/a" : fmt::format("{:.4f}", row.lognormal.hi * d);
    const std::string advice = row.resolved ? fmt::format("**{:.4f}**", e.hi * d)
                                            : fmt::format("not resolved by {} records; lognormal: **{}**", row.records,
                                                          lognormal);
    s += set.bridge ? fmt::format("| {}% | {:.3f} | {:.4f} | [{:.4f}, {:.4f}] | {} |\n", row.target, e.value,
                                  e.value * d, e.lo * d, e.hi * d, advice)
                    : fmt::format("| {}% | {:.3f} | [{:.3f}, {:.3f}] | **{:.3f}** | {} |\n", row.target, e.value,
                                  e.lo, e.hi, e.hi, row.cubic ? fmt::format("{:.3f}", *row.cubic) : "outside fit range");
  }
  return s;
}

}  // namespace report_detail

ReportSettings report_settings(const results::Results& r) {
  if (r.settings.empty()) return legacy_v1::report_settings_from_text(r);
  const results::Settings& s = r.settings;
  ReportSettings set;
  // the axis' key names its unit ([gaps] metres or ratios; /gaps' attribute unit says the same)
  set.metres = s.find("gaps", "metres") != nullptr;
  set.gap_ratios = s.numbers("gaps", set.metres ? "metres" : "ratios");
  if (s.find("gaps", "existing")) set.existing = s.number("gaps", "existing");
  set.curve_max = s.number("gaps", "curve_max");
  set.curve_step = s.number("gaps", "curve_step");
  set.targets = s.numbers("report", "targets");
  set.fit_min = s.number("report", "fit_min"), set.fit_max = s.number("report", "fit_max");
  // absent from a bridge study (its d is the smallest joint gap, [bridge] reference_gap)
  if (s.find("structures", "code_gap_coefficient")) set.code_gap_coefficient = s.number("structures", "code_gap_coefficient");
  set.seed = static_cast<std::uint64_t>(r.header.seed);
  // added with issue 13; files written before have the defaults (and all studied the paper's model)
  set.compare_with = s.find("report", "compare_with") ? s.text("report", "compare_with") : "stochastic-pounding";
  if (s.find("report", "confidence")) set.confidence = s.number("report", "confidence");
  if (s.find("report", "bootstrap")) set.bootstrap = static_cast<int>(s.number("report", "bootstrap"));
  set.pair = s.find("structures", "heights_specified") && s.number("structures", "heights_specified") != 0;
  if (s.find("bridge", "reference_gap")) {
    set.bridge = true, set.pair = false;
    set.bridge_d = s.number("bridge", "reference_gap");
    set.bridge_text = s.text("bridge", "description");
  }
  return set;
}

std::string run_machine(const results::Header& h) {
  const std::string m = machine_text(Machine{h.host, h.cpu_model, h.cpu_cores});
  return m.empty() ? "not recorded (the file was written before results stored the machine)" : m;
}

Curve probability_curve(const results::Results& r, double step, double xmax, int record) {
  return curve_of(Data(r), step, xmax, record);
}

namespace {

std::string pair_markdown(const Data& r) {
  Markdown md(r);
  md.overview();
  if (r.set.pair && !r.red) {
    const std::string rules = code_rules_section(r);  // first: its bootstrap covers the existing gap's (one run)
    md.raw(pair_separation_section(r));
    md.raw(existing_section(r));  // [gaps] existing ("" without it)
    md.raw(rules);
    md.raw(code_levels_section(r));  // shear buildings: the rules at each contact level ("" for an SDOF pair)
  } else {
    md.raw(existing_section(r));
  }
  if (r.set.pair && r.red)
    md.raw(fmt::format("\n## Separation for this pair\n\nNot given: {}. The reductions count closings in ratios x of "
                       "each model's code gap; a separation in metres and the code rules need each model's peaks and "
                       "code gap. The advice in gap ratios is below.\n",
                       reductions_reason(r)));
  md.per_record();
  md.total();
  md.coupled_counts();
  md.raw(moat_section(r));  // an isolated building in a moat ("" otherwise)
  if (r.set.bridge) {  // the buildings' code rules, period matrix and u1/u2 amplification do not apply
    md.raw(grid_advice_section(r));
    md.raw(bridge_section(r));
    md.raw(floors_section(r));
    md.raw(levels_section(r));
    if (r.impacts) md.restitution_note();
    return std::move(md).text();
  }
  md.period_matrix();
  if (!r.set.pair || r.red) {
    md.fit();
    md.raw(grid_advice_section(r));
    if (!r.red) md.raw(code_rules_section(r));
    else
      md.raw(fmt::format("\n## Code separation rules\n\nNot given: {}. The rules' probabilities need each model's "
                         "own peaks and code-rule gap.\n",
                         reductions_reason(r)));
  }
  md.impacts_table();
  md.raw(floors_section(r));
  md.raw(levels_section(r));
  return std::move(md).text();
}

std::string pair_csv(const Data& r) {
  // gap_ratio is the axis' value: a ratio x of d, or ([gaps] metres) the gap in metres (the name kept for readers)
  std::string s = "table,record,gap_ratio,T1,T2,hits,n,probability,gap_m,lo,hi,name\n";
  const auto& ratios = r.set.gap_ratios;
  const auto &p1 = r.periods(1), &p2 = r.periods(2);
  for (std::size_t k = 0; k < r.independent(); ++k)
    for (double x : ratios) {
      Count c = count_uncoupled(r, x, static_cast<int>(k));
      s += fmt::format("per_record,{},{},,,{},{},{:.6f},,,,\n", report::csv_field(r.rec.id[k * r.per_record]), x, c.hits, c.n,
                       c.pct() / 100);
    }
  for (double x : ratios) {
    Count c = count_uncoupled(r, x, -1);
    s += fmt::format("total,,{},,,{},{},{:.6f},,,,\n", x, c.hits, c.n, c.pct() / 100);
  }
  for (double x : ratios)
    for (std::size_t a = 0; a < p1.size(); ++a)
      for (std::size_t b = 0; b < p2.size(); ++b) {
        Count c = count_uncoupled(r, x, -1, static_cast<int>(a), static_cast<int>(b));
        s += fmt::format("period_pair,,{},{:.2f},{:.2f},{},{},{:.6f},,,,\n", x, p1[a], p2[b], c.hits, c.n,
                         c.pct() / 100);
      }
  Curve c = curve_of(r, r.set.curve_step, r.set.curve_max, -1);
  for (std::size_t i = 0; i < c.x.size(); ++i)
    s += fmt::format("curve,,{:.4f},,,,{},{:.6f},,,,\n", c.x[i], c.n, c.p[i]);
  if (!r.red) return s + separation_csv(r) + code_levels_csv(r) + moat_csv(r) + levels_csv(r);
  // [outputs] per_model = false: the separations in gap ratios from the histograms (bin upper edges)
  std::vector<double> targets;
  for (double t : r.set.targets) targets.push_back(t / 100.0);
  const separation::BootstrapResult b = histogram_bootstrap(r, targets);
  for (std::size_t i = 0; i < targets.size(); ++i)
    s += fmt::format("separation,,{:.6f},,,,{},{},,{:.6f},{:.6f},\"from histograms\"\n", b.separation[i].value, c.n,
                     targets[i], b.separation[i].lo, b.separation[i].hi);
  return s;
}

}  // namespace

namespace {
ReportTexts texts(const results::Results& results, bool with_markdown, bool with_csv, const WorkHook* hook) {
  ReportTexts t;
  if (is_fragility_study(results)) {
    std::optional<results::Results> analysed;  // a file written without the analysis hook: analyse it now, once
    if (!results.group("fragility")) analyse_fragility(analysed.emplace(results), hook);
    const results::Results& r = analysed ? *analysed : results;
    if (with_markdown) t.markdown = fragility_markdown(r) + report_detail::selection_section(results);
    if (with_csv) t.csv = fragility_csv(r);
    return t;
  }
  Data r(results, hook, &t.bootstrap_s);
  r.bootstrap_runs = &t.bootstraps;
  if (with_csv) t.csv = pair_csv(r);  // first: its bootstrap covers every target and gap the Markdown asks for
  if (with_markdown)
    t.markdown = pair_markdown(r) + report_detail::selection_section(results) + report_detail::histories_section(results);
  return t;
}
}  // namespace

ReportTexts report_texts(const results::Results& results, bool with_csv, const WorkHook* hook) {
  return texts(results, true, with_csv, hook);
}

std::string report_markdown(const results::Results& results, const WorkHook* hook, double* bootstrap_s) {
  ReportTexts t = texts(results, true, false, hook);
  if (bootstrap_s) *bootstrap_s += t.bootstrap_s;
  return std::move(t.markdown);
}

std::string report_csv(const results::Results& results, const WorkHook* hook, double* bootstrap_s) {
  ReportTexts t = texts(results, false, true, hook);
  if (bootstrap_s) *bootstrap_s += t.bootstrap_s;
  return std::move(t.csv);
}

}  // namespace pounding
