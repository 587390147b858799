// The report's answers about separation (issue 13): a pair study's separation in metres with its bootstrap
// interval, the code rules in metres with the probability of pounding at each, and their CSV rows.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/report/escape.hpp"
#include "pounding/analysis/stats.hpp"
#include "pounding/core/parallel_for.hpp"

namespace pounding::report_detail {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// "0.9 s" when every model has the same value, else "median 0.9 s (5-95 %: 0.71-1.1 s)".
std::string spread(std::vector<double> v, double scale, const char* unit) {
  if (v.empty()) return "-";
  std::sort(v.begin(), v.end());
  const auto at = [&](double p) { return scale * v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))]; };
  if (v.front() == v.back()) return fmt::format("{:.4g} {}", scale * v.front(), unit);
  return fmt::format("median {:.4g} {} (5-95 %: {:.4g}-{:.4g})", scale * median(v), unit, at(0.05), at(0.95));
}

std::string setting_text(const Data& r, const std::string& section, const char* key) {
  const results::SettingValue* v = r.res.settings.find(section, key);
  return v && std::holds_alternative<std::string>(*v) ? std::get<std::string>(*v) : std::string();
}

std::vector<double> zetas(const Data& r, int b) {
  std::vector<double> z(r.models());
  for (std::size_t m = 0; m < z.size(); ++m) z[m] = r.zeta(b, m);
  return z;
}

std::string buildings(const Data& r) {
  std::string s;
  for (int b = 1; b <= 2; ++b) {
    const auto& T = b == 1 ? r.mod.T1 : r.mod.T2;
    const auto& h = b == 1 ? r.mod.h1 : r.mod.h2;
    const auto& m = b == 1 ? r.mod.m1 : r.mod.m2;
    s += fmt::format("- building {}: T {}, height {}, mass {}, damping {}", b, spread(T, 1, "s"), spread(h, 1, "m"),
                     spread(m, 1e-3, "t"), spread(zetas(r, b), 100, "%"));
    const std::string section = fmt::format("structures.building{}", b);
    std::string given;
    for (const char* key : {"period", "height", "mass", "zeta", "yield"})
      if (const std::string t = setting_text(r, section, key); !t.empty()) given += fmt::format("{} {}; ", key, report::md_text(t));
    s += given.empty() ? "\n" : fmt::format(" — as given: {}\n", given.substr(0, given.size() - 2));
  }
  return s;
}

std::vector<double> fractions(const std::vector<double>& percent) {
  std::vector<double> t;
  for (double p : percent) t.push_back(p / 100.0);
  return t;
}

// The cubic of P (%) against the gap in metres over [fit_min, fit_max] x the median code gap.
std::optional<CubicFit> metres_fit(const Data& r, std::vector<double> z, double d) {
  std::sort(z.begin(), z.end());
  std::vector<double> fx, fy;
  const int n = static_cast<int>(std::floor(r.set.curve_max / r.set.curve_step + 1e-9));
  for (int i = 1; i <= n; ++i) {
    const double x = r.set.curve_step * i;
    if (x < r.set.fit_min - 1e-12 || x > r.set.fit_max + 1e-12) continue;
    const double g = x * d;
    fx.push_back(g);
    fy.push_back(100.0 * static_cast<double>(z.end() - std::upper_bound(z.begin(), z.end(), g)) / static_cast<double>(z.size()));
  }
  if (fx.size() < 4 || z.empty()) return std::nullopt;
  return fit_cubic(fx, fy);
}

// The design values of the rules for a pair study: the mean of each building's own uncoupled peak over every ok
// analysis; the periods as the codes take them (code_period: the study's stated period or median, else the sampled
// median, as the rules at each contact level), median damping and code gap over the models.
separation::DesignPair design_pair(const Data& r) {
  separation::DesignPair p;
  double s1 = 0, s2 = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < r.status.size(); ++i)
    if (r.ok(r.status[i])) s1 += r.peak_u1[i], s2 += r.peak_u2[i], ++n;
  p.u1 = n ? s1 / static_cast<double>(n) : NAN, p.u2 = n ? s2 / static_cast<double>(n) : NAN;
  std::string source;
  p.T1 = r.mod.T1.empty() ? NAN : code_period(r, 1, source), p.T2 = r.mod.T2.empty() ? NAN : code_period(r, 2, source);
  p.zeta1 = median(zetas(r, 1)), p.zeta2 = median(zetas(r, 2));
  p.code_gap = median(r.mod.code_gap);
  return p;
}

// Where building b's period of the rules comes from (code_period): "as given", "the study's median (...)", "median
// of N samples".
std::string period_source(const Data& r, int b) {
  std::string source = "no models";
  if (!(b == 1 ? r.mod.T1 : r.mod.T2).empty()) code_period(r, b, source);
  return source;
}

// The rules' gaps of model m for a grid study: each building's mean peak over the ok records of that model.
// Model m's design pair for the code rules: each building's mean uncoupled peak over the records (ok analyses).
separation::DesignPair model_design_pair(const Data& r, std::size_t m) {
  separation::DesignPair p;
  double s1 = 0, s2 = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < r.records(); ++k)
    if (const std::size_t i = k * r.models() + m; r.ok(r.status[i])) s1 += r.peak_u1[i], s2 += r.peak_u2[i], ++n;
  p.u1 = s1 / static_cast<double>(n), p.u2 = s2 / static_cast<double>(n);
  p.T1 = r.mod.T1[m], p.T2 = r.mod.T2[m], p.zeta1 = r.zeta(1, m), p.zeta2 = r.zeta(2, m);
  p.code_gap = r.mod.code_gap[m];
  return p;
}

}  // namespace

bool resolved_by(double t, std::size_t N) { return std::floor(t * static_cast<double>(N)) >= 1; }

std::vector<double> record_peaks(const separation::Demands& d) {
  std::vector<double> peaks;
  for (std::size_t k = 0; k < d.records; ++k) {
    const std::vector<double> z = d.record(k);
    if (!z.empty()) peaks.push_back(*std::max_element(z.begin(), z.end()));
  }
  return peaks;
}

namespace {

// [gaps] existing as one more row of the code-rules table (after the rules and the codes' design rows), so that the
// table, its CSV rows and the figure's lines mark it; nothing without an existing gap.
void add_existing(const Data& r, std::vector<separation::Rule>& rules) {
  if (!std::isnan(r.set.existing))
    rules.push_back({fmt::format("existing {:g} m", r.set.existing), "as built", "[gaps] existing", r.set.existing});
}

std::string interval(const separation::Estimate& e, double scale, const char* f) {
  return fmt::format("[{}, {}]", fmt::format(fmt::runtime(f), scale * e.lo), fmt::format(fmt::runtime(f), scale * e.hi));
}

std::string pair_rules(const Data& r) {
  const separation::DesignPair p = design_pair(r);
  std::vector<separation::Rule> rules = separation::code_rules(p, r.set.code_gap_coefficient);
  const std::string scope = coefficient_scope(r, rules);
  const separation::CodeDesign design = code_design(r);  // the codes' own design displacements (code_design.cpp)
  rules.insert(rules.end(), design.rules.begin(), design.rules.end());
  add_existing(r, rules);
  std::vector<double> gaps;
  for (const auto& rule : rules) gaps.push_back(rule.gap);
  const separation::Demands d = r.demands(true);
  const std::vector<double> z = d.pooled();
  const separation::BootstrapResult b = r.bootstrap(true, {}, gaps);
  std::string s = fmt::format(
      "\n## Code separation rules in metres\n\n"
      "Each rule's separation for this pair, and the probability of at least one impact at that separation "
      "according to this study. The rows marked \"mean record peaks\" feed each code's formula the mean over all {} "
      "analyses (records x models) of each building's own uncoupled peak, u1 = {:.4f} m and u2 = {:.4f} m — the "
      "average over the suite as response-history provisions take it (EN 1998-1 sec. 4.3.3.4.3: at least 7 "
      "records; ASCE 7-16 ch. 16: 11) — not the code's design displacement from its design spectrum; the rows "
      "marked \"design\" (when the study gives a design spectrum and the buildings' factors) use those. DDC uses T1 = {:.3f} s, "
      "T2 = {:.3f} s ({}; {}), damping {:.3g} and {:.3g} (medians over the models): rho = {:.3f}. Interval: the two-stage "
      "bootstrap ({} replicates); Wilson: {}.\n\n"
      "| rule | clause | formula | separation m | P(pounding) | {:.0f} % interval | Wilson 95 % |\n"
      "|---|---|---|---|---|---|---|\n",
      z.size(), p.u1, p.u2, p.T1, p.T2, period_source(r, 1), period_source(r, 2), p.zeta1, p.zeta2,
      separation::ddc_rho(p.T1, p.T2, p.zeta1, p.zeta2),
      b.replicates, r.fixed_pair ? wilson_basis(r) : "the sampling error under these records only",
      100 * r.set.confidence);
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const std::int64_t hits = std::count_if(z.begin(), z.end(), [&](double v) { return v > rules[i].gap; });
    const Interval w = wilson(r, hits, static_cast<std::int64_t>(z.size()));
    s += fmt::format("| {} | {} | {} | {:.3f} | {} | {} | [{:.2f}%, {:.2f}%] |\n", rules[i].name, rules[i].clause,
                     rules[i].formula, rules[i].gap, pct(100 * b.probability[i].value),
                     interval(b.probability[i], 100, "{:.2f}%"), 100 * w.lo, 100 * w.hi);
  }
  if (!scope.empty() || !design.notes.empty()) s += "\n" + scope;
  for (const std::string& note : design.notes) s += "- " + note + ".\n";
  return s;
}

std::string grid_rules(const Data& r) {
  std::string s =
      "\n## Code separation rules (probability of pounding at each rule's gap)\n\n"
      "Per model, each rule combines design values of the two buildings: the mean over the records of each "
      "building's own uncoupled peak (not the peaks of the same record, which would make ABS never pound); DDC "
      "uses the model's periods and damping. Wilson 95 % intervals (sampling error under these records).\n\n"
      "| rule | clause | formula | probability of pounding | Wilson 95 % |\n|---|---|---|---|---|\n";
  for (const GridRuleRow& row : grid_rule_rows(r))
    s += fmt::format("| {} | {} | {} | {} | [{:.2f}%, {:.2f}%] |\n", row.rule.name, row.rule.clause, row.rule.formula,
                     pct(row.n ? 100.0 * static_cast<double>(row.hits) / static_cast<double>(row.n) : NAN), 100 * row.wilson.lo, 100 * row.wilson.hi);
  if (!std::isnan(r.set.existing)) {  // the as-built gap, every model's: the marker row
    const Count c = count_existing(r);
    const Interval w = wilson(r, c.hits, c.n);
    s += fmt::format("| **existing {:g} m** | as built | [gaps] existing | {} | [{:.2f}%, {:.2f}%] |\n", r.set.existing,
                     pct(c.pct()), 100 * w.lo, 100 * w.hi);
  }
  return s;
}

}  // namespace

std::vector<GridRuleRow> grid_rule_rows(const Data& r) {
  std::vector<GridRuleRow> rows;
  const std::size_t M = r.models();
  if (M == 0) return rows;
  for (const separation::Rule& rule : separation::code_rules(model_design_pair(r, 0), r.set.code_gap_coefficient))
    rows.push_back({rule, 0, 0, NAN, {}});  // the rows' texts once; each model's gaps without them
  // blocks of models on every CPU, their integer counts added after (the same for any thread count)
  using Counts = std::array<std::int64_t, 2 * separation::code_rule_count>;  // n, hits per rule
  const int T = thread_count(0, M / 65536 + 1);
  std::vector<Counts> part(static_cast<std::size_t>(T), Counts{});
  parallel_blocks(part.size(), T, [&](std::size_t t, std::size_t) {
    Counts& c = part[t];
    for (std::size_t m = M * t / part.size(); m < M * (t + 1) / part.size(); ++m) {
      const std::array<double, separation::code_rule_count> gaps = separation::code_rule_gaps(model_design_pair(r, m));
      for (std::size_t k = 0; k < r.records(); ++k) {
        const std::size_t i = k * M + m;
        if (!r.ok(r.status[i])) continue;
        for (std::size_t j = 0; j < gaps.size(); ++j) ++c[2 * j], c[2 * j + 1] += r.peak_closing[i] > gaps[j];
      }
    }
  });
  for (const Counts& c : part)
    for (std::size_t j = 0; j < rows.size(); ++j) rows[j].n += c[2 * j], rows[j].hits += c[2 * j + 1];
  for (GridRuleRow& row : rows) {
    row.probability = row.n ? static_cast<double>(row.hits) / static_cast<double>(row.n) : NAN;
    row.wilson = wilson_interval(row.hits, row.n);
  }
  return rows;
}

// A pair study's advice rows (the Markdown's table and the CSV's rows separation_cubic, built once): per target the
// records above the separation (of the independent records) and the cubic fit's root in metres.
struct PairAdviceRows {
  std::size_t records = 0;  // N independent records with an ok analysis
  std::vector<std::size_t> above;
  std::vector<std::optional<double>> cubic;
};

PairAdviceRows pair_advice_rows(const Data& r, const separation::BootstrapResult& b) {
  const separation::Demands d = r.demands(true);
  const std::vector<double> record_peak = record_peaks(d);
  // the curve's and fit's unit: the median code gap on a ratio axis, 1 m on a metres axis ([gaps] metres)
  const double unit = r.set.metres ? 1.0 : median(r.mod.code_gap);
  const std::optional<CubicFit> f = metres_fit(r, d.pooled(), unit);
  PairAdviceRows rows;
  rows.records = record_peak.size();
  for (std::size_t i = 0; i < r.set.targets.size(); ++i) {
    const double v = b.separation[i].value;
    rows.above.push_back(std::count_if(record_peak.begin(), record_peak.end(), [&](double p) { return p > v; }));
    rows.cubic.push_back(f ? solve_fit(*f, r.set.targets[i], r.set.fit_min * unit, r.set.fit_max * unit)
                           : std::nullopt);
  }
  return rows;
}

std::string pair_separation_section(const Data& r) {
  const std::vector<double> targets = fractions(r.set.targets);
  const separation::Demands d = r.demands(true);
  const separation::BootstrapResult b = r.bootstrap(true, targets, {}, true);
  const PairAdviceRows rows = pair_advice_rows(r, b);
  const std::size_t N = rows.records;
  const double dcode = median(r.mod.code_gap);
  std::string s = fmt::format(
      "\n## Separation for this pair, in metres\n\n{}\n"
      "The separation at a target is the smallest gap that at most floor(t n) of the n = {} analyses "
      "(records x models) exceed with their uncoupled peak closing max(u1 - u2): the exact empirical curve. The "
      "interval is a two-stage bootstrap over records and over models within records ({} replicates, {:.0f} %, "
      "seeded from the study's seed), so it includes record-to-record variability; **the advice is its upper "
      "end**. The code gap is d = {} (h1 + h2) = {:.3f} m{}. The cubic fit (P in % against metres over "
      "[{}, {}] {}) is a secondary summary.\n\n"
      "The records, not the analyses, limit how fine a target can be: with N = {} independent records a target t "
      "with floor(t N) = 0 is **not resolved by N records** -- no record is expected to exceed it, and the empirical "
      "separation is (close to) the largest record's peak, whatever t. \"Records above\" counts the records with "
      "at least one analysis above the separation. Beside it, a **parametric estimate (lognormal, extrapolated)**: "
      "a lognormal fitted to the n demands (maximum likelihood: ln z has mean {:.4f} and standard deviation {:.4f}; "
      "{:.1f} % of the demands <= 0 taken as a point mass at 0), with its interval from the same bootstrap "
      "replicates refitted. Where a target is not resolved, the advice is the lognormal's upper end, so labelled.\n\n"
      "| P(at least one impact) | separation m | {:.0f} % interval m | records above | advice: at least m | in code gaps d | "
      "cubic m | lognormal m (parametric) | lognormal {:.0f} % interval m |\n"
      "|---|---|---|---|---|---|---|---|---|\n",
      buildings(r), d.pooled().size(), b.replicates, 100 * r.set.confidence, r.set.code_gap_coefficient, dcode,
      std::all_of(r.mod.code_gap.begin(), r.mod.code_gap.end(), [&](double v) { return v == dcode; }) ? ""
                                                                                                          : " (median)",
      r.set.fit_min, r.set.fit_max, r.set.metres ? "m" : "d", N, b.fit.mu, b.fit.sigma, 100 * b.fit.p0, 100 * r.set.confidence,
      100 * r.set.confidence);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const separation::Estimate& e = b.separation[i];
    const separation::Estimate& ln = b.lognormal[i];
    const std::optional<double>& xc = rows.cubic[i];
    const bool resolved = resolved_by(targets[i], N);
    const std::size_t above = rows.above[i];
    const std::string advice =
        resolved ? fmt::format("**{:.3f}**", e.hi)
                 : fmt::format("not resolved by {} records; lognormal: **{}**", N,
                               std::isnan(ln.hi) ? "n/a" : fmt::format("{:.3f}", ln.hi));
    s += fmt::format("| {}% | {:.3f} | {} | {} of {} | {} | {:.2f} | {} | {} | {} |\n", r.set.targets[i], e.value,
                     interval(e, 1, "{:.3f}"), above, N, advice, e.value / dcode,
                     xc ? fmt::format("{:.3f}", *xc) : "outside fit range",
                     std::isnan(ln.value) ? "n/a" : fmt::format("{:.3f}", ln.value),
                     std::isnan(ln.lo) ? "n/a" : interval(ln, 1, "{:.3f}"));
  }
  return s;
}

std::string code_rules_section(const Data& r) { return r.set.pair ? pair_rules(r) : grid_rules(r); }

namespace {
// A grid study's code rules (each model has its own gaps) and advice's cubic: rows code_rule, separation_cubic.
std::string grid_csv(const Data& r) {
  std::string s;
  for (const GridRuleRow& row : grid_rule_rows(r))
    s += fmt::format("code_rule,,,,,{},{},{:.6f},,{:.6f},{:.6f},\"{}\"\n", row.hits, row.n, row.probability,
                     row.wilson.lo, row.wilson.hi, row.rule.name);

  for (const AdviceRow& row : grid_advice_rows(r))
    s += fmt::format("separation_cubic,,{},,,,,{},,,,{}\n", row.cubic ? fmt::format("{:.6f}", *row.cubic) : "",
                     row.target / 100, row.cubic ? "" : "\"outside fit range\"");
  return s;
}

// A grid's or bridge's row "existing" ([gaps] existing: every model's gap, in metres; a pair's is a code-rule row).
std::string existing_csv(const Data& r) {
  if (std::isnan(r.set.existing)) return "";
  const Count c = count_existing(r);
  const Interval w = wilson(r, c.hits, c.n);
  return fmt::format("existing,,{},,,{},{},{:.6f},{:.6f},{:.6f},{:.6f},\"existing {:g} m\"\n",
                     r.set.metres ? fmt::format("{:.6f}", r.set.existing) : "", c.hits, c.n, c.pct() / 100,
                     r.set.existing, w.lo, w.hi, r.set.existing);
}
}  // namespace

Count count_existing(const Data& r) {
  Count c;
  if (std::isnan(r.set.existing)) return c;
  for (std::size_t i = 0; i < r.status.size() && i < r.peak_closing.size(); ++i)
    if (r.ok(r.status[i])) ++c.n, c.hits += r.peak_closing[i] > r.set.existing;  // strict, as every gap's verdict
  return c;
}

// [gaps] existing: the answer at the as-built gap, counted from every analysis's peak closing (exact at any gap,
// not read off the axis), with the report's Wilson interval and the two-stage bootstrap's.
std::string existing_section(const Data& r) {
  const double g = r.set.existing;
  if (std::isnan(g)) return "";
  std::string s = fmt::format("\n## At the existing gap\n\nThe as-built gap, [gaps] existing = {:g} m{}: ", g,
                              r.set.bridge ? " (the gap of the joint(s) at d; every other joint's existing + (gap_j - d))"
                                           : "");
  if (r.red) {  // reductions only: no per-model closings; exact when the existing gap is one of the metres axis' gaps
    const auto at = std::find(r.set.gap_ratios.begin(), r.set.gap_ratios.end(), g);
    if (!r.set.metres || at == r.set.gap_ratios.end())
      return s + fmt::format("not given: {}, and it is not one of the study's gaps in metres ([gaps] metres), whose "
                             "counts the reductions keep.\n",
                             reductions_reason(r));
    const Count c = count_uncoupled(r, g, -1);
    const Interval w = wilson(r, c.hits, c.n);
    return s + fmt::format("P(at least one impact) = **{}** ({} of {} analyses), Wilson 95 % [{:.2f}%, {:.2f}%].\n",
                           pct(c.pct()), c.hits, c.n, 100 * w.lo, 100 * w.hi);
  }
  const Count c = count_existing(r);
  const Interval w = wilson(r, c.hits, c.n);
  const double gaps[] = {g};
  const separation::BootstrapResult b = r.bootstrap(true, {}, gaps);
  s += fmt::format("P(at least one impact) = **{}** ({} of {} analyses with an uncoupled peak closing above {:g} m, "
                   "counted from every analysis, not read off the gap axis); {:.0f} % interval {} (two-stage "
                   "bootstrap over records and models within records, {} replicates); Wilson 95 % [{:.2f}%, {:.2f}%] "
                   "({}).{}\n",
                   pct(c.pct()), c.hits, c.n, g, 100 * r.set.confidence, interval(b.probability[0], 100, "{:.2f}%"),
                   b.replicates, 100 * w.lo, 100 * w.hi,
                   r.fixed_pair ? wilson_basis(r) : "the sampling error of the models under these records",
                   r.set.metres || r.set.bridge ? ""
                                                : " Every model has this gap in metres, so its ratio x = existing / d "
                                                  "varies with the model's code gap d.");
  return s;
}

std::string separation_csv(const Data& r) {
  const std::vector<double> targets = fractions(r.set.targets);
  const separation::Demands d = r.demands(r.set.pair);
  std::vector<double> gaps;
  std::vector<separation::Rule> rules;
  // code_rule rows; after them code_design rows (the codes' design displacements), then [gaps] existing's
  std::size_t formula_rules = 0, design_rules = 0;
  if (r.set.pair) {
    rules = separation::code_rules(design_pair(r), r.set.code_gap_coefficient);
    coefficient_scope(r, rules);
    formula_rules = rules.size();
    const separation::CodeDesign design = code_design(r);
    rules.insert(rules.end(), design.rules.begin(), design.rules.end());
    design_rules = rules.size();
    add_existing(r, rules);  // its row: table "existing"
    for (const auto& rule : rules) gaps.push_back(rule.gap);
  }
  // A pair study's curve with its band, in metres (a grid study's 10^5 analyses make 300 gaps x 2000 replicates
  // too slow for a report; its curve rows above have no band)
  // (the column gap_ratio: the gap over the median code gap; on a metres axis the gap in metres, as the header says)
  const double unit = r.set.pair && !r.set.metres ? median(r.mod.code_gap) : 1.0;
  const int n = r.set.pair ? static_cast<int>(std::floor(r.set.curve_max / r.set.curve_step + 1e-9)) : 0;
  for (int i = 1; i <= n; ++i) gaps.push_back(r.set.curve_step * i * unit);
  // pairs and bridges: with the lognormal, the advice of a target the records do not resolve
  const bool lognormal = r.set.pair || r.set.bridge;
  const separation::BootstrapResult b = r.bootstrap(r.set.pair, targets, gaps, lognormal);
  const std::size_t N = d.pooled().size(), records = record_peaks(d).size();
  std::string s;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const separation::Estimate& e = b.separation[i];
    // name: "not resolved by R records" where floor(t R) = 0 (R independent records with an ok analysis)
    const std::string note =
        !lognormal || resolved_by(targets[i], records) ? "" : fmt::format("\"not resolved by {} records\"", records);
    s += r.set.pair ? fmt::format("separation,,{:.6f},,,,{},{},{:.6f},{:.6f},{:.6f},{}\n", e.value / unit, N, targets[i],
                                  e.value, e.lo, e.hi, note)
                    : fmt::format("separation,,{:.6f},,,,{},{},,{:.6f},{:.6f},{}\n", e.value, N, targets[i], e.lo, e.hi,
                                  note);
  }
  for (std::size_t i = 0; i < b.lognormal.size(); ++i) {  // pairs and bridges: the parametric (lognormal) estimate
    const separation::Estimate& e = b.lognormal[i];       // (a bridge's in units of d, as its separation rows)
    s += fmt::format("separation_lognormal,,{:.6f},,,,{},{},{},{:.6f},{:.6f},\"lognormal fit: mu {:.9g} sigma {:.9g} "
                     "p0 {:.9g}\"\n",
                     e.value / unit, N, targets[i], r.set.pair ? fmt::format("{:.6f}", e.value) : "", e.lo, e.hi,
                     b.fit.mu, b.fit.sigma, b.fit.p0);
  }
  const std::vector<double> z = d.pooled();
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    const separation::Estimate& e = b.probability[i];
    const bool rule = i < rules.size();
    // a rule's hits: the analyses above its gap, as the Markdown table counts them (its Wilson row below)
    const std::int64_t hits = rule ? std::count_if(z.begin(), z.end(), [&](double v) { return v > gaps[i]; }) : -1;
    s += fmt::format("{},,{:.6f},,,{},{},{:.6f},{},{:.6f},{:.6f},{}\n",
                     rule ? (i < formula_rules ? "code_rule" : i < design_rules ? "code_design" : "existing") : "curve_band",
                     gaps[i] / unit,
                     rule ? std::to_string(hits) : "", N, e.value, r.set.pair ? fmt::format("{:.6f}", gaps[i]) : "",
                     e.lo, e.hi, rule ? "\"" + rules[i].name + "\"" : "");
    if (rule) {
      const Interval w = wilson(r, hits, static_cast<std::int64_t>(N));
      s += fmt::format("rule_wilson,,{:.6f},,,{},{},{:.6f},{:.6f},{:.6f},{:.6f},\"{}\"\n", gaps[i] / unit, hits, N,
                       N ? static_cast<double>(hits) / static_cast<double>(N) : NAN, gaps[i], w.lo, w.hi, rules[i].name);
    }
  }
  if (r.set.pair) {  // the advice table's other columns: the cubic's root, the records above the separation
    const PairAdviceRows rows = pair_advice_rows(r, b);
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const std::optional<double>& c = rows.cubic[i];
      s += fmt::format("separation_cubic,,{},,,{},{},{},{},,,{}\n", c ? fmt::format("{:.6f}", *c / unit) : "",
                       rows.above[i], rows.records, targets[i], c ? fmt::format("{:.6f}", *c) : "",
                       c ? "" : "\"outside fit range\"");
    }
  }
  if (!r.set.pair && !r.set.bridge) s += grid_csv(r);
  if (!r.set.pair) s += existing_csv(r);
  return s;
}

}  // namespace pounding::report_detail
