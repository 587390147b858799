// The report's per-floor amplification (issue 25 §3 observers): a study of Systems (results format 3, impacts scene)
// stores every floor's peak displacement, storey drift and absolute acceleration without contact (/uncoupled/
// peak_u_floorsK, peak_driftK, peak_acc_floorsK) and with contact at each gap (/impacts/...). This section gives, per
// building and floor (a bridge: per frame, its deck), the median ratio with pounding / without over the analyses that
// pounded at that gap ratio.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/report/escape.hpp"

namespace pounding::report_detail {

namespace {

double median_of(std::vector<double>& v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The three quantities of the table: the per-floor row name (before the building's number).
constexpr const char* quantities[] = {"peak_u_floors", "peak_drift", "peak_acc_floors"};

// Per-floor rows of building b (0-based) of both groups, or nullptr when the file lacks one.
struct Rows {
  const std::vector<double>* unc[3] = {};
  const std::vector<double>* imp[3] = {};
  std::size_t floors = 0;
};
Rows rows_of(const Data& r, std::size_t b) {
  Rows x;
  x.floors = static_cast<std::size_t>(r.res.system.building_floors[b]);
  for (int q = 0; q < 3; ++q) {
    const std::string name = fmt::format("{}{}", quantities[q], b + 1);
    if (!r.res.find("uncoupled", name.c_str()) || !r.res.find("impacts", name.c_str())) return Rows{};
    x.unc[q] = &r.res.column<double>("uncoupled", name);
    x.imp[q] = &r.res.column<double>("impacts", name);
  }
  return x;
}

// "1.12 / 1.30 / 2.45": the median amplification of u, drift and acceleration of floor f of building rows x at gap g
// over the ok analyses with an impact at that gap (n of them); "-" where none pounded.
std::string cell(const Data& r, const Rows& x, std::size_t f, std::size_t g, std::size_t& n) {
  const std::size_t RM = r.records() * r.models(), G = r.gaps(), F = x.floors;
  std::vector<double> a[3];
  n = 0;
  for (std::size_t i = 0; i < RM; ++i) {
    const std::size_t k = i * G + g;
    if (!r.ok(r.status[i]) || !r.ok(r.imp_status[k]) || !(r.impact_count[k] > 0)) continue;
    if (std::isnan((*x.unc[0])[i * F + f])) continue;  // above this sample's roof
    ++n;
    for (int q = 0; q < 3; ++q) {
      const double without = (*x.unc[q])[i * F + f], with = (*x.imp[q])[k * F + f];
      if (without > 0 && std::isfinite(with)) a[q].push_back(with / without);
    }
  }
  if (n == 0) return "-";
  return fmt::format("{:.3g} / {:.3g} / {:.3g}", median_of(a[0]), median_of(a[1]), median_of(a[2]));
}

}  // namespace

std::string floors_section(const Data& r) {
  const results::SystemTable& sys = r.res.system;
  if (!r.impacts || sys.empty() || r.gaps() == 0 || r.red) return {};
  const bool bridge = r.set.bridge;
  std::string s = fmt::format(
      "\n## Per-{} amplification (peak with pounding / peak without)\n\nMedian over the analyses that pounded at "
      "each gap ratio (status ok, at least one impact) of the ratio of the coupled run's peak to the uncoupled run's, "
      "for the peak displacement relative to the ground, the peak drift of the storey below and the peak absolute "
      "acceleration (u / drift / acc); {}. The per-floor peaks of both runs are in the results "
      "(uncoupled/ and impacts/ peak_u_floorsK, peak_driftK, peak_acc_floorsK).\n\n",
      bridge ? "deck" : "floor",
      bridge ? "per frame, its deck (the top level of a stick frame, the mass of an SDOF frame)"
             : "per building and floor, bottom first (floor 0: an isolated building's base on its isolators)");
  s += bridge ? "| frame |" : "| building | floor |";
  std::string rule = bridge ? "|---|" : "|---|---|";
  for (std::size_t g = 0; g < r.gaps(); ++g) s += fmt::format(" {}: u / drift / acc |", axis_label(r, r.res.gap_ratios[g])), rule += "---|";
  s += "\n" + rule + "\n";
  for (std::size_t b = 0; b < sys.building_label.size(); ++b) {
    const Rows x = rows_of(r, b);
    if (x.floors == 0) continue;
    const bool isolated = b < sys.building_isolated.size() && sys.building_isolated[b];
    for (std::size_t f = bridge ? x.floors - 1 : 0; f < x.floors; ++f) {
      const std::string label = report::md_cell(sys.building_label[b]);
      s += bridge ? fmt::format("| {} |", label) : fmt::format("| {} | {} |", label, isolated ? f : f + 1);
      for (std::size_t g = 0; g < r.gaps(); ++g) {
        std::size_t n = 0;
        s += fmt::format(" {} |", cell(r, x, f, g, n));  // not " " + cell(...): GCC 12's -Wrestrict false positive
      }
      s += "\n";
    }
  }
  return s;
}

}  // namespace pounding::report_detail
