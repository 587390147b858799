// The moat walls of isolated buildings in the report (issue 45 item 2): the probability that the base hits its moat
// (the share of the analyses with at least one moat-wall impact, with the report's interval), without pounding and
// with it at each gap ratio, and the base's peak displacement; per stripe in a fragility study. From /system (the
// walls: elements of a group that is not study-gap with a wall side; their gap: /system/element_gap_offset) and the
// per-element rows of results format 3.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/report/escape.hpp"

namespace pounding::report_detail {

std::vector<MoatBuilding> moat_buildings(const results::SystemTable& sys) {
  std::vector<MoatBuilding> out;
  for (std::size_t e = 0; e < sys.element_label.size(); ++e) {
    const auto g = static_cast<std::size_t>(sys.element_group[e]);
    if (g >= sys.group_study_gap.size() || sys.group_study_gap[g]) continue;
    const bool wall_left = sys.element_left_kind[e] == "wall", wall_right = sys.element_right_kind[e] == "wall";
    if (wall_left == wall_right) continue;
    const std::int32_t dof = wall_left ? sys.element_right_dof[e] : sys.element_left_dof[e];
    if (dof < 0 || static_cast<std::size_t>(dof) >= sys.dof_building.size()) continue;
    const auto body = static_cast<std::size_t>(sys.dof_building[static_cast<std::size_t>(dof)]);
    auto it = std::find_if(out.begin(), out.end(), [&](const MoatBuilding& m) { return m.body == body; });
    if (it == out.end()) {
      out.push_back({body, body < sys.building_label.size() ? sys.building_label[body] : fmt::format("building{}", body + 1),
                     {}, INFINITY});
      it = out.end() - 1;
    }
    it->walls.push_back(e);
    // files written before the moat gap reached /system/element_gap_offset hold 0 there: unknown (NaN)
    const double gap = e < sys.element_gap_offset.size() && sys.element_gap_offset[e] > 0 ? sys.element_gap_offset[e] : NAN;
    it->gap = std::isinf(it->gap) ? gap : std::min(it->gap, gap);  // NaN stays NaN
  }
  return out;
}

namespace {

// Linear interpolation between order statistics (Hyndman & Fan type 7, numpy's default); NaN for an empty sample.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double h = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

std::string metres(double x) { return std::isfinite(x) ? fmt::format("{:.3f}", x) : "n/a"; }

// One row of the moat table: the analyses' verdicts and the base's peaks, summed per independent record (the
// clusters of the fragility report's interval).
struct MoatTally {
  std::int64_t hits = 0, n = 0;
  std::vector<double> record_hits, record_n, base;
  std::size_t records_hit = 0;
  void add(std::size_t rec, bool hit, double u) {
    if (record_n.size() <= rec) record_hits.resize(rec + 1, 0.0), record_n.resize(rec + 1, 0.0);
    hits += hit, ++n, record_hits[rec] += hit, record_n[rec] += 1;
    if (std::isfinite(u)) base.push_back(u);
  }
  std::size_t records() const {
    return static_cast<std::size_t>(std::count_if(record_n.begin(), record_n.end(), [](double x) { return x > 0; }));
  }
  std::size_t hit_records() const {
    return static_cast<std::size_t>(std::count_if(record_hits.begin(), record_hits.end(), [](double x) { return x > 0; }));
  }
};

// The arrays of one file the walls are read from; empty spans where the file lacks them.
struct MoatArrays {
  std::span<const double> closing, base_u, imp_base_u;  // [lanes, E], [lanes, floors], [lanes, G, floors]
  std::span<const std::int32_t> count;                  // [lanes, G, E]
  std::size_t E = 0, floors = 0, G = 0;
  MoatArrays(const results::Results& r, const MoatBuilding& m, std::size_t lanes)
      : closing(column_or_empty<double>(r, "uncoupled", "peak_closing_elements")),
        count(column_or_empty<std::int32_t>(r, "impacts", "element_impact_count")),
        E(r.system.element_label.size()), G(r.gap_ratios.size()) {
    const std::string name = fmt::format("peak_u_floors{}", m.body + 1);
    base_u = column_or_empty<double>(r, "uncoupled", name.c_str());
    imp_base_u = column_or_empty<double>(r, "impacts", name.c_str());
    floors = lanes ? base_u.size() / lanes : 0;
  }
  // the base touched a wall in the uncoupled run (the walls act there too): its closing passed the moat gap
  bool hit(const MoatBuilding& m, std::size_t i) const {
    return std::any_of(m.walls.begin(), m.walls.end(), [&](std::size_t e) { return closing[i * E + e] > m.gap; });
  }
  bool hit(const MoatBuilding& m, std::size_t i, std::size_t g) const {
    return std::any_of(m.walls.begin(), m.walls.end(), [&](std::size_t e) { return count[(i * G + g) * E + e] > 0; });
  }
  double base(std::size_t i) const { return floors ? base_u[i * floors] : NAN; }  // floor 0: the isolated base
  double base(std::size_t i, std::size_t g) const { return floors && !imp_base_u.empty() ? imp_base_u[(i * G + g) * floors] : NAN; }
};

std::string row(const MoatBuilding& m, const std::string& run, const MoatTally& t, double p, const Interval& w) {
  return fmt::format("| {} | {} | {} | **{}** | [{}, {}] | {} of {} | {} of {} | {} | {} | {} |\n", report::md_cell(m.label),
                     metres(m.gap), run, pct(p), pct(100 * w.lo), pct(100 * w.hi), t.hits, t.n, t.hit_records(),
                     t.records(), metres(quantile(t.base, 0.5)), metres(quantile(t.base, 0.84)),
                     metres(t.base.empty() ? NAN : *std::max_element(t.base.begin(), t.base.end())));
}

constexpr const char* table_head =
    "| building | moat gap m | {} | P(moat impact) | {:.0f} % interval | analyses | records with a moat impact | "
    "base peak median m | base peak 84th percentile m | base peak max m |\n|---|---|---|---|---|---|---|---|---|---|\n";

std::string intro(const std::vector<MoatBuilding>& walls) {
  std::string s = "\n## Moat walls: probability that the isolated base hits its moat\n\n";
  for (const MoatBuilding& m : walls)
    s += fmt::format("{} stands on isolators with moat walls {} either side of its base{}. ", report::md_text(m.label),
                     std::isnan(m.gap) ? "an unknown gap" : fmt::format("{:.3f} m", m.gap),
                     std::isnan(m.gap) ? " (this file predates the moat gap in /system/element_gap_offset: the runs "
                                         "without pounding cannot be judged; run the study again)"
                                       : "");
  return s + "A moat impact is an analysis in which the base touches a wall at least once (the walls act in every "
             "run, with and without pounding between the buildings). The base peak is its largest displacement "
             "relative to the ground with the walls acting (a base held by the walls exceeds the moat gap by the "
             "walls' penetration only).";
}

// The per-analysis verdicts of building m at gap ratio index g (SIZE_MAX: the uncoupled run) over the ok analyses.
MoatTally moat_tally(const Data& r, const MoatBuilding& m, const MoatArrays& a, std::size_t g) {
  MoatTally t;
  const std::size_t R = r.records(), M = r.models();
  for (std::size_t k = 0; k < R; ++k)
    for (std::size_t mm = 0; mm < M; ++mm) {
      const std::size_t i = k * M + mm;
      if (g == SIZE_MAX) {
        if (r.ok(r.status[i]) && !std::isnan(m.gap)) t.add(k / r.per_record, a.hit(m, i), a.base(i));
        continue;
      }
      if (!r.ok(r.imp_status[i * a.G + g])) continue;
      // an analysis that never touched its neighbour at this gap ran as the uncoupled one (skip_untouched: its
      // element rows then hold no impacts, also at the moat): the uncoupled verdict is its verdict
      const bool untouched = r.ok(r.status[i]) && !(r.peak_closing[i] > r.res.gap_ratios[g] * r.unit(mm));
      if (untouched && std::isnan(m.gap)) continue;
      t.add(k / r.per_record, untouched ? a.hit(m, i) : a.hit(m, i, g), a.base(i, g));
    }
  return t;
}

}  // namespace

std::string moat_section(const Data& r) {
  const std::vector<MoatBuilding> walls = moat_buildings(r.res.system);
  if (walls.empty() || r.set.bridge) return {};
  std::string s = intro(walls);
  if (r.red)
    return s + " Not counted here: the file keeps no per-analysis rows ([outputs] per_model = false or \"stream\").\n";
  if (!r.res.find("uncoupled", "peak_closing_elements")) return s + " Not counted: the file has no per-element rows.\n";
  s += fmt::format(" P is the share of the analyses (records x models) with a moat impact; the interval is {}.\n\n",
                   wilson_basis(r));
  s += fmt::format(fmt::runtime(table_head), "run", 100 * r.set.confidence);
  for (const MoatBuilding& m : walls) {
    const MoatArrays a(r.res, m, r.records() * r.models());
    MoatTally t = moat_tally(r, m, a, SIZE_MAX);
    if (t.n) s += row(m, "without pounding", t, 100.0 * t.hits / t.n, wilson(r, t.hits, t.n));
    if (!r.impacts || a.count.empty()) continue;
    for (std::size_t g = 0; g < a.G; ++g) {
      t = moat_tally(r, m, a, g);
      if (t.n) s += row(m, "with pounding at " + gap_title(r, r.res.gap_ratios[g]), t, 100.0 * t.hits / t.n,
                        wilson(r, t.hits, t.n));
    }
  }
  return s;
}

std::string moat_csv(const Data& r) {
  const std::vector<MoatBuilding> walls = moat_buildings(r.res.system);
  if (walls.empty() || r.set.bridge || r.red || !r.res.find("uncoupled", "peak_closing_elements")) return {};
  std::string s;
  for (const MoatBuilding& m : walls) {
    const MoatArrays a(r.res, m, r.records() * r.models());
    const auto put = [&](const MoatTally& t, const std::string& x) {
      if (!t.n) return;
      const Interval w = wilson(r, t.hits, t.n);
      s += fmt::format("moat,,{},,,{},{},{:.6f},{:.6f},{:.6f},{:.6f},{}\n", x, t.hits, t.n,
                       static_cast<double>(t.hits) / static_cast<double>(t.n), m.gap, w.lo, w.hi, report::csv_field(m.label));
    };
    put(moat_tally(r, m, a, SIZE_MAX), "");  // gap_ratio empty: without pounding
    if (r.impacts && !a.count.empty())
      for (std::size_t g = 0; g < a.G; ++g) put(moat_tally(r, m, a, g), fmt::format("{}", r.res.gap_ratios[g]));
  }
  return s;
}

// A fragility study: per stripe, the uncoupled runs' verdicts (the stripes' analyses are [S, R, M]); the interval is
// Wilson's with the records as clusters (Kish's effective n), as a record's analyses are not independent draws.
std::string moat_fragility_section(const results::Results& r, std::span<const double> levels, const std::string& im) {
  const std::vector<MoatBuilding> walls = moat_buildings(r.system);
  if (walls.empty()) return {};
  std::string s = intro(walls);
  if (!r.find("uncoupled", "peak_closing_elements")) return s + " Not counted: the file has no per-element rows.\n\n";
  s += " Per stripe, P is the share of its analyses (records x models) with a moat impact; the interval is Wilson's "
       "with the records as clusters (Kish's effective sample size: a record's analyses are not independent).\n\n";
  const auto& st = r.column<std::uint8_t>("uncoupled", "status");
  const bool keep = r.settings.find("analysis", "coarse") && r.settings.text("analysis", "coarse") == "keep";
  const std::size_t S = levels.size(), R = r.record_count(), M = r.model_count(), P = r.polarities();
  s += fmt::format(fmt::runtime(table_head), "level " + im, 95.0);
  for (const MoatBuilding& m : walls) {
    const MoatArrays a(r, m, S * R * M);
    for (std::size_t j = 0; j < S && !std::isnan(m.gap); ++j) {
      MoatTally t;
      for (std::size_t i = j * R * M; i < (j + 1) * R * M; ++i)
        if (st[i] == 0 || (keep && st[i] == static_cast<std::uint8_t>(LaneStatus::coarse)))
          t.add((i - j * R * M) / M / P, a.hit(m, i), a.base(i));
      if (!t.n) continue;
      const ClusteredInterval w = wilson_clustered(t.record_hits, t.record_n);
      s += row(m, fmt::format("{:.4g}", levels[j]), t, 100.0 * t.hits / t.n, w.w);
    }
  }
  return s + "\n";
}

}  // namespace pounding::report_detail
