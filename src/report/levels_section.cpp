// The report's per-level answers for a study of Systems (results format 3, impacts scene): per contact element and gap
// ratio, the probability that the element is hit (at least one impact) with the report's interval, the peak impact
// force given a hit (median, 84th percentile) and, where a floor strikes a column, the struck column's extra shears
// (physics::column_shear_per_force, as `pounding simulate` prints them); per floor, the amplification of the peak
// absolute acceleration by pounding (median, 84th percentile). From /system and the per-element and per-floor rows.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/report/escape.hpp"

namespace pounding::report_detail {

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

// The element's struck column: the xi of its interpolated side, or NaN when neither side is (floor to floor, a wall).
double column_xi(const results::SystemTable& sys, std::size_t e) {
  if (sys.element_left_kind[e] == "interpolated") return sys.element_left_xi[e];
  if (sys.element_right_kind[e] == "interpolated") return sys.element_right_xi[e];
  return NAN;
}

// `bridge`: a bridge study's elements are its expansion joints (deck to deck), not floors.
std::string element_kind(const results::SystemTable& sys, std::size_t e, bool bridge) {
  const double xi = column_xi(sys, e);
  if (!std::isnan(xi)) return fmt::format("floor to column (xi {:.3g})", xi);
  if (sys.element_left_kind[e] == "wall" || sys.element_right_kind[e] == "wall") return "wall";
  return bridge ? "deck to deck" : "floor to floor";
}

// One element at one gap ratio: its hits among the ok analyses and the peak forces of those hit.
struct ElementTally {
  std::int64_t hits = 0, n = 0;
  std::vector<double> force;  // N, the analyses with a hit
};

struct ElementArrays {
  std::span<const std::int32_t> count;  // [R, M, G, E]
  std::span<const double> force;        // [R, M, G, E]
  std::size_t E = 0, G = 0;
  explicit ElementArrays(const Data& r)
      : count(column_or_empty<std::int32_t>(r.res, "impacts", "element_impact_count")),
        force(column_or_empty<double>(r.res, "impacts", "element_peak_force")),
        E(r.res.system.element_label.size()), G(r.gaps()) {}
  bool usable(std::size_t lanes) const { return E && !count.empty() && count.size() == force.size() && count.size() == lanes * G * E; }
};

// An analysis not rerun at a gap (it never touched its neighbour there: skip_untouched) holds no impacts at the
// study-gap elements and the uncoupled run's at a moat wall, so the coupled row is the verdict of every ok analysis.
ElementTally element_tally(const Data& r, const ElementArrays& a, std::size_t e, std::size_t g) {
  ElementTally t;
  const std::size_t lanes = r.records() * r.models();
  for (std::size_t i = 0; i < lanes; ++i) {
    const std::size_t k = i * a.G + g;
    if (!r.ok(r.imp_status[k])) continue;
    ++t.n;
    if (a.count[k * a.E + e] > 0) ++t.hits, t.force.push_back(a.force[k * a.E + e]);
  }
  return t;
}

// The per-floor rows of building b (peak absolute acceleration, g) of both runs, or empty when the file lacks one.
struct AccRows {
  std::span<const double> unc, imp;  // [R, M, F], [R, M, G, F]
  std::size_t floors = 0;
};
AccRows acc_rows(const Data& r, std::size_t b) {
  AccRows x;
  const std::string name = fmt::format("peak_acc_floors{}", b + 1);
  x.unc = column_or_empty<double>(r.res, "uncoupled", name.c_str());
  x.imp = column_or_empty<double>(r.res, "impacts", name.c_str());
  const std::size_t lanes = r.records() * r.models();
  x.floors = lanes && !x.unc.empty() && !x.imp.empty() ? x.unc.size() / lanes : 0;
  if (x.floors && x.imp.size() != lanes * r.gaps() * x.floors) x.floors = 0;
  return x;
}

// The acceleration amplification of floor f at gap g over the analyses that pounded there (status ok in both runs,
// at least one impact; the floors_section's basis), the floor below the sample's roof.
std::vector<double> acc_amplification(const Data& r, const AccRows& x, std::size_t f, std::size_t g) {
  std::vector<double> a;
  const std::size_t lanes = r.records() * r.models(), G = r.gaps(), F = x.floors;
  for (std::size_t i = 0; i < lanes; ++i) {
    const std::size_t k = i * G + g;
    if (!r.ok(r.status[i]) || !r.ok(r.imp_status[k]) || !(r.impact_count[k] > 0)) continue;
    const double without = x.unc[i * F + f], with = x.imp[k * F + f];
    if (without > 0 && std::isfinite(with)) a.push_back(with / without);  // NaN without: above this sample's roof
  }
  return a;
}

std::string kn(double x) { return std::isfinite(x) ? fmt::format("{:.4g}", x / 1e3) : "-"; }
std::string ratio(double x) { return std::isfinite(x) ? fmt::format("{:.3g}", x) : "-"; }
std::string floor_name(const results::SystemTable& sys, std::size_t b, std::size_t f) {
  const bool isolated = b < sys.building_isolated.size() && sys.building_isolated[b];
  return fmt::format("{}", isolated ? f : f + 1);
}

bool applies(const Data& r) { return r.impacts && !r.res.system.empty() && r.gaps() > 0 && !r.red; }

}  // namespace

std::string levels_section(const Data& r) {
  if (!applies(r)) return {};
  const results::SystemTable& sys = r.res.system;
  const ElementArrays a(r);
  const std::size_t lanes = r.records() * r.models();
  std::string s = "\n## Per contact level: impacts, peak forces, column shears\n\n";
  if (!a.usable(lanes)) return s + "Not given: the file has no per-element rows (impacts/element_impact_count).\n";
  s += fmt::format(
      "Per contact element and gap: P(hit) is the share of the ok analyses (records x models) with at least one "
      "impact at that element, the interval {}; the peak impact force is the element's largest contact force, its "
      "median and 84th percentile (numpy's linear interpolation) over the analyses with a hit. Where a floor strikes "
      "the neighbour's column the column's extra shears below and above the contact point are those of a fixed-fixed "
      "column under the peak force at xi (F (1 - xi)^2 (1 + 2 xi) and F xi^2 (3 - 2 xi), Karayannis and Favvata), "
      "not added to the storey shear of the drift. Forces in kN.\n\n",
      wilson_basis(r));
  s += std::string("| element | kind | ") + r.axis_title() + " | P(hit) | 95 % interval | analyses hit | peak force median kN | peak force 84th "
       "percentile kN | column shear below kN: median, 84th | column shear above kN: median, 84th |\n"
       "|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t e = 0; e < a.E; ++e) {
    const double xi = column_xi(sys, e);
    for (std::size_t g = 0; g < a.G; ++g) {
      const ElementTally t = element_tally(r, a, e, g);
      if (!t.n) continue;
      const Interval w = wilson(r, t.hits, t.n);
      const double f50 = quantile(t.force, 0.5), f84 = quantile(t.force, 0.84);
      std::string below = "-", above = "-";
      if (!std::isnan(xi) && t.hits) {
        const physics::ColumnShear v = physics::column_shear_per_force(xi);
        below = kn(v.below * f50) + ", " + kn(v.below * f84), above = kn(v.above * f50) + ", " + kn(v.above * f84);
      }
      s += fmt::format("| {} | {} | {} | {} | [{}, {}] | {} of {} | {} | {} | {} | {} |\n", report::md_cell(sys.element_label[e]),
                       element_kind(sys, e, r.res.settings.find("bridge", "reference_gap") != nullptr),
                       gap_title(r, r.res.gap_ratios[g]),
                       pct(100.0 * static_cast<double>(t.hits) / static_cast<double>(t.n)), pct(100 * w.lo),
                       pct(100 * w.hi), t.hits, t.n, kn(f50), kn(f84), below, above);
    }
  }
  const bool bridge = r.set.bridge;
  s += fmt::format(
      "\nPeak absolute {} acceleration with pounding / without, per {} and gap ratio: its median and 84th percentile "
      "over the analyses that pounded there (status ok, at least one impact; the basis of the per-{} amplification), "
      "N of them{}.\n\n| {} | {} | median | 84th percentile | N |\n|---|{}---|---|---|---|\n",
      bridge ? "deck" : "floor", bridge ? "frame (its deck)" : "building and floor", bridge ? "deck" : "floor",
      bridge ? "" : " (floor 0: an isolated building's base)", bridge ? "frame" : "building | floor", r.axis_title(),
      bridge ? "" : "---|");
  for (std::size_t b = 0; b < sys.building_label.size(); ++b) {
    const AccRows x = acc_rows(r, b);
    for (std::size_t f = bridge && x.floors ? x.floors - 1 : 0; f < x.floors; ++f)
      for (std::size_t g = 0; g < a.G; ++g) {
        const std::vector<double> v = acc_amplification(r, x, f, g);
        if (v.empty()) continue;
        s += bridge ? fmt::format("| {} |", report::md_cell(sys.building_label[b]))
                    : fmt::format("| {} | {} |", report::md_cell(sys.building_label[b]), floor_name(sys, b, f));
        s += fmt::format(" {} | {} | {} | {} |\n", gap_title(r, r.res.gap_ratios[g]), ratio(quantile(v, 0.5)),
                         ratio(quantile(v, 0.84)), v.size());
      }
  }
  return s;
}

std::string levels_csv(const Data& r) {
  if (!applies(r)) return {};
  const results::SystemTable& sys = r.res.system;
  const ElementArrays a(r);
  if (!a.usable(r.records() * r.models())) return {};
  std::string s;
  auto num = [](double x) { return std::isfinite(x) ? fmt::format("{:.17g}", x) : std::string(); };
  for (std::size_t e = 0; e < a.E; ++e) {
    const double xi = column_xi(sys, e);
    const std::string name = report::csv_field(sys.element_label[e]);
    for (std::size_t g = 0; g < a.G; ++g) {
      const ElementTally t = element_tally(r, a, e, g);
      if (!t.n) continue;
      const Interval w = wilson(r, t.hits, t.n);
      const std::string x = fmt::format("{}", r.res.gap_ratios[g]);
      s += fmt::format("level,,{},,,{},{},{:.6f},,{:.6f},{:.6f},{}\n", x, t.hits, t.n,
                       static_cast<double>(t.hits) / static_cast<double>(t.n), w.lo, w.hi, name);
      if (!t.hits) continue;
      const double f50 = quantile(t.force, 0.5), f84 = quantile(t.force, 0.84);
      s += fmt::format("level_force,,{},,,,{},,,{},{},{}\n", x, t.hits, num(f50), num(f84), name);
      if (std::isnan(xi)) continue;
      const physics::ColumnShear v = physics::column_shear_per_force(xi);
      s += fmt::format("level_shear_below,,{},,,,{},,,{},{},{}\n", x, t.hits, num(v.below * f50), num(v.below * f84), name);
      s += fmt::format("level_shear_above,,{},,,,{},,,{},{},{}\n", x, t.hits, num(v.above * f50), num(v.above * f84), name);
    }
  }
  for (std::size_t b = 0; b < sys.building_label.size(); ++b) {
    const AccRows x = acc_rows(r, b);
    for (std::size_t f = r.set.bridge && x.floors ? x.floors - 1 : 0; f < x.floors; ++f)
      for (std::size_t g = 0; g < a.G; ++g) {
        const std::vector<double> v = acc_amplification(r, x, f, g);
        if (v.empty()) continue;
        const std::string where = r.set.bridge ? sys.building_label[b] : sys.building_label[b] + " floor " + floor_name(sys, b, f);
        s += fmt::format("floor_acc,,{},,,,{},,,{},{},{}\n", r.res.gap_ratios[g], v.size(), num(quantile(v, 0.5)),
                         num(quantile(v, 0.84)), report::csv_field(where));
      }
  }
  return s;
}

}  // namespace pounding::report_detail
