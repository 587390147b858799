#include "pounding/report/report.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "pounding/io/hdf5.hpp"
#include "pounding/analysis/stats.hpp"
#include "pounding/study/study.hpp"

namespace pounding {

namespace {
// The published study (stochastic-pounding-monte-carlo.txt, Table 3 and eq. 10) for comparison.
constexpr double paper_ratios[] = {0.1, 0.2, 0.3, 0.5, 0.7, 1.0};
constexpr double paper_total[] = {71.09, 45.56, 25.26, 6.12, 1.14, 0.0};
constexpr double paper_fit[] = {106.8, -403.4, 510.3, -213.7};  // c0 + c1 x + c2 x^2 + c3 x^3 (%)

bool ok(std::uint8_t s) { return s == 0; }

struct Count {
  std::int64_t hits = 0, n = 0;
  double pct() const { return n ? 100.0 * static_cast<double>(hits) / static_cast<double>(n) : NAN; }
};

// uncoupled: hit when peak closing > ratio * code gap (contact is delta = u1 - u2 - gap > 0)
Count count_uncoupled(const Results& r, double ratio, int rec, int pair_i1 = -1, int pair_i2 = -1) {
  Count c;
  const std::size_t M = r.models();
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (rec >= 0 && static_cast<int>(k) != rec) continue;
    for (std::size_t m = 0; m < M; ++m) {
      if (pair_i1 >= 0 && (r.i1[m] != pair_i1 || r.i2[m] != pair_i2)) continue;
      const std::size_t idx = k * M + m;
      if (!ok(r.status[idx])) continue;
      ++c.n;
      c.hits += r.peak_closing[idx] > ratio * r.code_gap[m];
    }
  }
  return c;
}

Count count_coupled(const Results& r, std::size_t g, int rec) {
  Count c;
  const std::size_t M = r.models(), G = r.gap_ratios.size();
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (rec >= 0 && static_cast<int>(k) != rec) continue;
    for (std::size_t m = 0; m < M; ++m) {
      const std::size_t idx = (k * M + m) * G + g;
      if (!ok(r.imp_status[idx]) || !ok(r.status[k * M + m])) continue;
      ++c.n;
      c.hits += r.impact_count[idx] > 0;
    }
  }
  return c;
}

std::string pct(double p) { return std::isnan(p) ? "n/a" : fmt::format("{:.2f}%", p); }

// Smallest x where the (non-increasing) empirical curve falls to <= target %, interpolated linearly.
double empirical_ratio(const Curve& c, double target) {
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (100.0 * c.p[i] <= target) {
      if (i == 0) return c.x[0];
      double x0 = c.x[i - 1], x1 = c.x[i], p0 = 100.0 * c.p[i - 1], p1 = 100.0 * c.p[i];
      return p0 == p1 ? x1 : x0 + (target - p0) * (x1 - x0) / (p1 - p0);
    }
  }
  return NAN;
}

}  // namespace

Results load_results(const std::string& path) {
  Results r;
  r.path = path;
  auto f = h5::open_read(path);
  const auto root = f.get();
  r.title = h5::read_string_attribute(root, "title");
  r.scene = h5::read_string_attribute(root, "scene");
  r.scene_reason = h5::read_string_attribute(root, "scene_reason");
  r.contact_law = h5::read_string_attribute(root, "contact_law");
  r.damping_law = h5::read_string_attribute(root, "damping_law");
  r.stepper = h5::read_string_attribute(root, "stepper");
  if (h5::attribute_exists(root, "study_text")) r.study_text = h5::read_string_attribute(root, "study_text");
  r.date = h5::read_string_attribute(root, "date");
  r.commit = h5::read_string_attribute(root, "git_commit");
  r.restitution = h5::read_double_attribute(root, "restitution");
  r.wall_time = h5::read_double_attribute(root, "wall_time_s");
  r.ranks = h5::read_int64_attribute(root, "ranks");
  r.seed = h5::read_int64_attribute(root, "seed");
  if (h5::attribute_exists(root, "exclusion_warning"))
    r.exclusion_warning = h5::read_string_attribute(root, "exclusion_warning");
  {
    auto g = h5::open_group(root, "records");
    r.record_id = h5::read_strings(g.get(), "id");
    r.record_name = h5::read_strings(g.get(), "name");
    r.record_note = h5::read_strings(g.get(), "note");
    r.record_synthetic = h5::read_uint8(g.get(), "synthetic");
    r.record_pga_g = h5::read_doubles(g.get(), "pga_g");
    r.record_duration = h5::read_doubles(g.get(), "duration");
  }
  {
    auto g = h5::open_group(root, "models");
    r.T1 = h5::read_doubles(g.get(), "T1"), r.T2 = h5::read_doubles(g.get(), "T2");
    r.h1 = h5::read_doubles(g.get(), "h1"), r.h2 = h5::read_doubles(g.get(), "h2");
    r.code_gap = h5::read_doubles(g.get(), "code_gap");
    r.periods = h5::read_doubles(g.get(), "periods");
    r.i1 = h5::read_int32(g.get(), "i1"), r.i2 = h5::read_int32(g.get(), "i2");
    r.sample = h5::read_int64(g.get(), "sample");
    r.zeta = h5::read_double_attribute(g.get(), "zeta");
  }
  {
    auto g = h5::open_group(root, "uncoupled");
    r.status = h5::read_uint8(g.get(), "status");
    r.peak_u1 = h5::read_doubles(g.get(), "peak_u1");
    r.peak_u2 = h5::read_doubles(g.get(), "peak_u2");
    r.peak_closing = h5::read_doubles(g.get(), "peak_closing");
  }
  if (h5::exists(root, "impacts")) {
    r.impacts = true;
    auto g = h5::open_group(root, "impacts");
    r.gap_ratios = h5::read_doubles(g.get(), "gap_ratios");
    r.imp_status = h5::read_uint8(g.get(), "status");
    r.impact_count = h5::read_int32(g.get(), "impact_count");
    r.peak_force = h5::read_doubles(g.get(), "peak_force");
    r.imp_peak_u1 = h5::read_doubles(g.get(), "peak_u1");
    r.imp_peak_u2 = h5::read_doubles(g.get(), "peak_u2");
  }
  // report settings: /settings (format with settings) or, for older files, the echoed study text
  if (h5::exists(root, "settings")) {
    auto g = h5::open_group(root, "settings");
    auto section = [&](const char* name) { return h5::open_group(g.get(), name); };
    {
      auto s = section("gaps");
      r.study_gap_ratios = h5::read_doubles_attribute(s.get(), "ratios");
      r.curve_max = h5::read_double_attribute(s.get(), "curve_max");
      r.curve_step = h5::read_double_attribute(s.get(), "curve_step");
    }
    {
      auto s = section("report");
      r.targets = h5::read_doubles_attribute(s.get(), "targets");
      r.h1_report = h5::read_double_attribute(s.get(), "h1"), r.h2_report = h5::read_double_attribute(s.get(), "h2");
      r.fit_min = h5::read_double_attribute(s.get(), "fit_min"), r.fit_max = h5::read_double_attribute(s.get(), "fit_max");
    }
    r.code_gap_coefficient = h5::read_double_attribute(section("structures").get(), "code_gap_coefficient");
  } else {
    const std::string spath = h5::read_string_attribute(root, "study_path");
    const Study s = parse_study(r.study_text, spath);
    r.study_gap_ratios = s.gap_ratios;
    r.targets = s.targets;
    r.code_gap_coefficient = s.structures.code_gap_coefficient;
    r.h1_report = s.h1, r.h2_report = s.h2, r.fit_min = s.fit_min, r.fit_max = s.fit_max;
    r.curve_max = s.curve_max, r.curve_step = s.curve_step;
  }
  return r;
}

Curve probability_curve(const Results& r, double step, double xmax, int record) {
  std::vector<double> z;  // peak closing / code gap
  const std::size_t M = r.models();
  for (std::size_t k = 0; k < r.records(); ++k) {
    if (record >= 0 && static_cast<int>(k) != record) continue;
    for (std::size_t m = 0; m < M; ++m) {
      const std::size_t idx = k * M + m;
      if (ok(r.status[idx])) z.push_back(r.peak_closing[idx] / r.code_gap[m]);
    }
  }
  std::sort(z.begin(), z.end());
  Curve c;
  c.n = static_cast<std::int64_t>(z.size());
  const int n = static_cast<int>(std::floor(xmax / step + 1e-9));
  for (int i = 1; i <= n; ++i) {
    double x = step * i;
    // hits: z > x (strict, like delta > 0)
    auto it = std::upper_bound(z.begin(), z.end(), x);
    c.x.push_back(x);
    c.p.push_back(z.empty() ? NAN : static_cast<double>(z.end() - it) / static_cast<double>(z.size()));
  }
  return c;
}

std::string report_markdown(const Results& r) {
  std::string s;
  auto out = [&]<typename... A>(fmt::format_string<A...> f, A&&... a) { s += fmt::format(f, std::forward<A>(a)...); };
  const std::size_t R = r.records(), M = r.models();
  const auto& ratios = r.study_gap_ratios;
  out("# Pounding study: {}\n\n", r.title);
  if (!r.exclusion_warning.empty())
    out("> **WARNING — results not trustworthy as they stand:** {}.\n\n", r.exclusion_warning);
  out("- results: `{}` (written {}, commit {}, {} rank(s), wall time {:.2f} s)\n", r.path, r.date, r.commit, r.ranks,
      r.wall_time);
  out("- scene: **{}** — {}\n", r.scene, r.scene_reason);
  out("- contact: {} ({}), e = {}; stepper {}\n", r.contact_law, r.damping_law, r.restitution, r.stepper);
  std::size_t synth = 0;
  for (auto v : r.record_synthetic) synth += v;
  out("- {} records ({} synthetic stand-ins, {} real), {} models per record, seed {}\n", R, synth, R - synth, M, r.seed);
  std::size_t bad = 0;
  for (auto v : r.status) bad += !ok(v);
  out("- excluded (diverged or non-finite) analyses: **{}** of {}\n", bad, R * M);
  if (bad) {
    int shown = 0;
    for (std::size_t k = 0; k < R && shown < 10; ++k)
      for (std::size_t m = 0; m < M && shown < 10; ++m)
        if (!ok(r.status[k * M + m])) {
          out("  - record {} model (T1 {:.2f}, T2 {:.2f}, sample {}): status {}\n", r.record_id[k], r.T1[m], r.T2[m],
              r.sample[m], r.status[k * M + m] == 1 ? "diverged" : "non-finite");
          ++shown;
        }
  }
  out("\nAt least one impact at gap g = ratio x d (d = {} (h1 + h2){}) is counted from the "
      "uncoupled peak closing: the motion before the first contact is the uncoupled motion, so "
      "peak(u1 - u2) > g is exactly \"touches at least once\".\n",
      r.code_gap_coefficient, r.code_gap_coefficient == 0.005 ? ", Standard 2800" : "");

  // Table 2: per record
  out("\n## Probability of at least one impact per record (Table 2)\n\n| record | synthetic | PGA g |");
  for (double x : ratios) out(" {}d |", x);
  out("\n|---|---|---|");
  for (std::size_t i = 0; i < ratios.size(); ++i) out("---|");
  out("\n");
  for (std::size_t k = 0; k < R; ++k) {
    out("| {} | {} | {:.2f} |", r.record_id[k], r.record_synthetic[k] ? "yes" : "no", r.record_pga_g[k]);
    for (double x : ratios) {
      Count c = count_uncoupled(r, x, static_cast<int>(k));
      out(" {} ({}) |", c.hits, pct(c.pct()));
    }
    out("\n");
  }

  // Table 3: total with Wilson intervals, beside the paper
  out("\n## Total probability of pounding (Table 3), 95 % Wilson intervals\n\n");
  out("| gap ratio | models with impact | probability | 95 % interval | paper |\n|---|---|---|---|---|\n");
  for (double x : ratios) {
    Count c = count_uncoupled(r, x, -1);
    Interval w = wilson_interval(c.hits, c.n);
    std::string paper = "-";
    for (int j = 0; j < 6; ++j)
      if (std::abs(paper_ratios[j] - x) < 1e-12) paper = pct(paper_total[j]);
    out("| {} | {} / {} | {} | [{:.2f}%, {:.2f}%] | {} |\n", x, c.hits, c.n, pct(c.pct()), 100 * w.lo, 100 * w.hi, paper);
  }
  if (r.impacts) {
    out("\nCoupled runs ({}): models with at least one counted impact per gap, beside the uncoupled count "
        "(they must agree):\n\n| gap ratio | coupled | uncoupled |\n|---|---|---|\n", r.contact_law);
    for (std::size_t g = 0; g < r.gap_ratios.size(); ++g) {
      Count c = count_coupled(r, g, -1), u = count_uncoupled(r, r.gap_ratios[g], -1);
      out("| {} | {} / {} | {} / {} |\n", r.gap_ratios[g], c.hits, c.n, u.hits, u.n);
    }
  }

  // T1 x T2 matrix
  double xm = ratios[std::min<std::size_t>(ratios.size() - 1, 2)];
  out("\n## Probability by period pair at gap ratio {} (rows T1, columns T2)\n\n| T1 \\ T2 |", xm);
  for (double T : r.periods) out(" {:.2f} |", T);
  out("\n|---|");
  for (std::size_t j = 0; j < r.periods.size(); ++j) out("---|");
  out("\n");
  for (std::size_t a = 0; a < r.periods.size(); ++a) {
    out("| {:.2f} |", r.periods[a]);
    for (std::size_t b = 0; b < r.periods.size(); ++b) {
      Count c = count_uncoupled(r, xm, -1, static_cast<int>(a), static_cast<int>(b));
      out(" {:.1f} |", c.pct());
    }
    out("\n");
  }

  // cubic fit on the continuous curve
  Curve curve = probability_curve(r, r.curve_step, r.curve_max);
  std::vector<double> fx, fy;
  for (std::size_t i = 0; i < curve.x.size(); ++i)
    if (curve.x[i] >= r.fit_min - 1e-12 && curve.x[i] <= r.fit_max + 1e-12) fx.push_back(curve.x[i]), fy.push_back(100 * curve.p[i]);
  out("\n## Cubic fit of probability (%) versus gap ratio x (eq. 10)\n\n");
  if (fx.size() >= 4) {
    CubicFit f = fit_cubic(fx, fy);
    out("Fitted on the continuous curve, {} points for x in [{}, {}]:\n\n    PP = {:.1f} x^3 {:+.1f} x^2 {:+.1f} x {:+.1f}    "
        "(R^2 = {:.4f})\n\npaper (eq. 10): PP = -213.7 x^3 + 510.3 x^2 - 403.4 x + 106.8\n",
        fx.size(), r.fit_min, r.fit_max, f.c[3], f.c[2], f.c[1], f.c[0], f.r2);
    out("\n## Separation recommendation\n\nGap ratio x (and metres for h1 = {} m, h2 = {} m: g = x {} (h1 + h2)) at "
        "which the probability of at least one impact falls to the target:\n\n"
        "| target | empirical x | empirical m | cubic x | cubic m | difference x |\n|---|---|---|---|---|---|\n",
        r.h1_report, r.h2_report, r.code_gap_coefficient);
    const double dcode = r.code_gap_coefficient * (r.h1_report + r.h2_report);
    for (double t : r.targets) {
      double xe = empirical_ratio(curve, t);
      auto xc = solve_fit(f, t, r.fit_min, r.fit_max);
      out("| {}% | {} | {} | {} | {} | {} |\n", t, std::isnan(xe) ? "> curve_max" : fmt::format("{:.3f}", xe),
          std::isnan(xe) ? "-" : fmt::format("{:.3f}", xe * dcode), xc ? fmt::format("{:.3f}", *xc) : "outside fit range",
          xc ? fmt::format("{:.3f}", *xc * dcode) : "-",
          (xc && !std::isnan(xe)) ? fmt::format("{:+.3f}", *xc - xe) : "-");
    }
  } else {
    out("too few curve points in [{}, {}] to fit a cubic\n", r.fit_min, r.fit_max);
  }

  // code rules side by side, each from the models' own uncoupled peaks
  out("\n## Code separation rules (each from the models' own uncoupled peaks)\n\n| rule | gap | probability of pounding |\n|---|---|---|\n");
  struct Rule { const char* name; const char* gap; int kind; };
  const std::string code_rule = fmt::format("{} (h1 + h2)", r.code_gap_coefficient);
  const Rule rules[] = {{r.code_gap_coefficient == 0.005 ? "Standard 2800" : "code gap", code_rule.c_str(), 0}, {"ABS", "u1 + u2", 1}, {"SRSS", "sqrt(u1^2 + u2^2)", 2},
                        {"double difference (CQC)", "sqrt(u1^2 + u2^2 - 2 rho u1 u2)", 3}};
  for (const Rule& rule : rules) {
    std::int64_t hits = 0, n = 0;
    for (std::size_t k = 0; k < R; ++k)
      for (std::size_t m = 0; m < M; ++m) {
        const std::size_t idx = k * M + m;
        if (!ok(r.status[idx])) continue;
        double u1 = r.peak_u1[idx], u2 = r.peak_u2[idx], g = 0;
        switch (rule.kind) {
          case 0: g = r.code_gap[m]; break;
          case 1: g = u1 + u2; break;
          case 2: g = std::sqrt(u1 * u1 + u2 * u2); break;
          default: {
            double rho = cqc_rho(r.T2[m] / r.T1[m], r.zeta);  // r = omega1/omega2 = T2/T1
            g = std::sqrt(std::max(0.0, u1 * u1 + u2 * u2 - 2.0 * rho * u1 * u2));
          }
        }
        ++n;
        hits += r.peak_closing[idx] > g;
      }
    out("| {} | {} | {} |\n", rule.name, rule.gap, pct(n ? 100.0 * static_cast<double>(hits) / static_cast<double>(n) : NAN));
  }

  if (r.impacts) {
    out("\n## Impacts scene: counts, forces, amplification (peak with pounding / peak without)\n\n"
        "| gap ratio | mean impacts (pounding models) | max impacts | median peak force MN | max peak force MN | "
        "mean amplification u1 | mean amplification u2 | excluded |\n|---|---|---|---|---|---|---|---|\n");
    const std::size_t G = r.gap_ratios.size();
    std::string listing;
    std::size_t nbad = 0;
    for (std::size_t k = 0; k < R; ++k)
      for (std::size_t m = 0; m < M; ++m)
        for (std::size_t g = 0; g < G; ++g)
          if (!ok(r.imp_status[(k * M + m) * G + g])) {
            if (++nbad <= 10)
              listing += fmt::format("  - record {} model (T1 {:.2f}, T2 {:.2f}, sample {}) at gap ratio {}: {}\n",
                                     r.record_id[k], r.T1[m], r.T2[m], r.sample[m], r.gap_ratios[g],
                                     r.imp_status[(k * M + m) * G + g] == 1 ? "diverged" : "non-finite");
          }
    std::string excluded_note =
        nbad ? fmt::format("\nExcluded coupled analyses (diverged or non-finite, never counted as results): **{}**{}\n{}",
                           nbad, nbad > 10 ? " (first 10 listed)" : "", listing)
             : std::string();
    for (std::size_t g = 0; g < G; ++g) {
      double sum = 0, a1 = 0, a2 = 0;
      std::int64_t n = 0, maxc = 0, na = 0, excl = 0;
      std::vector<double> forces;
      for (std::size_t k = 0; k < R; ++k)
        for (std::size_t m = 0; m < M; ++m) {
          const std::size_t idx = (k * M + m) * G + g, u = k * M + m;
          if (!ok(r.imp_status[idx]) || !ok(r.status[u])) {
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
      out("| {} | {:.2f} | {} | {} | {} | {:.3f} | {:.3f} | {} |\n", r.gap_ratios[g], n ? sum / n : 0.0, maxc,
          forces.empty() ? "-" : fmt::format("{:.2f}", forces[forces.size() / 2]),
          forces.empty() ? "-" : fmt::format("{:.2f}", forces.back()), na ? a1 / na : NAN, na ? a2 / na : NAN, excl);
    }
    s += excluded_note;
  }
  return s;
}

std::string report_csv(const Results& r) {
  std::string s = "table,record,gap_ratio,T1,T2,hits,n,probability\n";
  const auto& ratios = r.study_gap_ratios;
  for (std::size_t k = 0; k < r.records(); ++k)
    for (double x : ratios) {
      Count c = count_uncoupled(r, x, static_cast<int>(k));
      s += fmt::format("per_record,{},{},,,{},{},{:.6f}\n", r.record_id[k], x, c.hits, c.n, c.pct() / 100);
    }
  for (double x : ratios) {
    Count c = count_uncoupled(r, x, -1);
    s += fmt::format("total,,{},,,{},{},{:.6f}\n", x, c.hits, c.n, c.pct() / 100);
  }
  for (double x : ratios)
    for (std::size_t a = 0; a < r.periods.size(); ++a)
      for (std::size_t b = 0; b < r.periods.size(); ++b) {
        Count c = count_uncoupled(r, x, -1, static_cast<int>(a), static_cast<int>(b));
        s += fmt::format("period_pair,,{},{:.2f},{:.2f},{},{},{:.6f}\n", x, r.periods[a], r.periods[b], c.hits, c.n,
                         c.pct() / 100);
      }
  Curve c = probability_curve(r, r.curve_step, r.curve_max);
  for (std::size_t i = 0; i < c.x.size(); ++i)
    s += fmt::format("curve,,{:.4f},,,,{},{:.6f}\n", c.x[i], c.n, c.p[i]);
  return s;
}

}  // namespace pounding
