// The report's bridge section ([bridge] studies, sampling/bridge.hpp): joints and frames by name, from the per-element
// and per-frame rows of results format 3.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/report/escape.hpp"

namespace pounding::report_detail {

namespace {

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// "joint 1 (F1\|F2)": the element's label and the frames on its two sides, as a Markdown table cell (the '|' escaped:
// unescaped it split the row, issue 45 item 3)
std::string joint_name(const results::SystemTable& sys, std::size_t e) {
  auto frame = [&](std::int32_t dof) {
    return dof >= 0 && static_cast<std::size_t>(dof) < sys.dof_building.size()
               ? report::md_cell(sys.building_label[static_cast<std::size_t>(sys.dof_building[static_cast<std::size_t>(dof)])])
               : std::string("?");
  };
  return fmt::format("{} ({}\\|{})", report::md_cell(sys.element_label[e]), frame(sys.element_left_dof[e]),
                     frame(sys.element_right_dof[e]));
}

// Per frame: the median peak displacement without pounding and with it at each gap ratio.
std::string frames_table(const Data& r) {
  const results::SystemTable& sys = r.res.system;
  const std::size_t R = r.records(), M = r.models(), B = sys.building_label.size();
  std::string s, rule;
  s += "\nFrames: median peak displacement relative to the ground (m) without pounding (uncoupled)";
  s += r.impacts ? " and with pounding at each gap ratio." : ".";
  if (std::any_of(sys.building_floors.begin(), sys.building_floors.end(), [](std::int32_t n) { return n > 1; }))
    s += " A stick frame's is its largest level's (each level's: peak_u_floorsK in the results).";
  s += "\n\n| frame | uncoupled |";
  rule = "|---|---|";
  if (r.impacts)
    for (std::size_t g = 0; g < r.gaps(); ++g) s += fmt::format(" {} |", axis_label(r, r.res.gap_ratios[g])), rule += "---|";
  s += "\n" + rule + "\n";
  for (std::size_t b = 0; b < B; ++b) {
    const std::string name = fmt::format("peak_u{}", b + 1);
    if (!r.res.find("uncoupled", name.c_str())) continue;
    const std::vector<double>& u = r.res.column<double>("uncoupled", name);
    std::vector<double> v;
    for (std::size_t i = 0; i < R * M; ++i)
      if (r.ok(r.status[i])) v.push_back(u[i]);
    s += fmt::format("| {} | {:.4g} |", report::md_cell(sys.building_label[b]), median(v));
    if (r.impacts && r.res.find("impacts", name.c_str())) {
      const std::vector<double>& c = r.res.column<double>("impacts", name);
      const std::size_t G = r.gaps();
      for (std::size_t g = 0; g < G; ++g) {
        std::vector<double> w;
        for (std::size_t i = 0; i < R * M; ++i)
          if (r.ok(r.imp_status[i * G + g])) w.push_back(c[i * G + g]);
        s += fmt::format(" {:.4g} |", median(w));
      }
    }
    s += "\n";
  }
  return s;
}

}  // namespace

std::string bridge_section(const Data& r) {
  const results::SystemTable& sys = r.res.system;
  const std::size_t E = sys.element_label.size();
  if (!r.set.bridge || E == 0) return {};
  const std::size_t R = r.records(), M = r.models();
  const double d = r.set.bridge_d, unit = r.set.metres ? 1.0 : d;  // the axis' metres per unit ([gaps] metres: 1)
  const std::vector<double>& closing = r.res.column<double>("uncoupled", "peak_closing_elements");  // [R, M, E]
  std::string s = fmt::format("\n## Bridge: joints and frames\n\n{}.\n\n", report::md_text(r.set.bridge_text));
  s += fmt::format(
      "Each joint's gap at {} + (its gap - d), d = {:g} m. P(joint touches) is the share of the ok analyses "
      "whose uncoupled peak closing exceeds that gap (first passage at that joint; the bridge pounds when any joint "
      "does). Closings are the peak of u_left - u_right (m).\n\n| joint | {} | median peak closing (m) |",
      r.set.metres ? "the study gap g (m) is g" : "ratio x is x d", d, r.set.metres ? "gap at g = d (m)" : "gap at x = 1 (m)");
  const auto& ratios = r.set.gap_ratios;
  std::string rule = "|---|---|---|";
  for (double x : ratios) s += fmt::format(" P at {} |", axis_label(r, x)), rule += "---|";
  s += "\n" + rule + "\n";
  for (std::size_t e = 0; e < E; ++e) {
    const double offset = e < sys.element_gap_offset.size() ? sys.element_gap_offset[e] : 0.0;
    std::vector<double> c;
    for (std::size_t k = 0; k < R; ++k)
      for (std::size_t m = 0; m < M; ++m)
        if (r.ok(r.status[k * M + m])) c.push_back(closing[(k * M + m) * E + e]);
    s += fmt::format("| {} | {:.4g} | {:.4g} |", joint_name(sys, e), d + offset, median(c));
    for (double x : ratios) {
      std::size_t hits = 0;
      for (double v : c) hits += v > x * unit + offset;
      s += c.empty() ? " - |" : fmt::format(" {:.1f}% |", 100.0 * static_cast<double>(hits) / static_cast<double>(c.size()));
    }
    s += "\n";
  }
  if (r.impacts) {
    const std::size_t G = r.gaps();
    const std::vector<std::int32_t>& count = r.res.column<std::int32_t>("impacts", "element_impact_count");  // [R,M,G,E]
    const std::vector<double>& force = r.res.column<double>("impacts", "element_peak_force");
    s += fmt::format("\nCoupled runs ({}): per joint and gap ratio, the mean impact count over the analyses in which the "
                     "joint is hit and the largest peak force (MN).\n\n| joint |",
                     report::md_text(r.h.contact_law));
    rule = "|---|";
    for (std::size_t g = 0; g < G; ++g) s += fmt::format(" {}: impacts, max force |", axis_label(r, r.res.gap_ratios[g])), rule += "---|";
    s += "\n" + rule + "\n";
    for (std::size_t e = 0; e < E; ++e) {
      s += fmt::format("| {} |", joint_name(sys, e));
      for (std::size_t g = 0; g < G; ++g) {
        double sum = 0, fmax = 0;
        std::size_t n = 0;
        for (std::size_t k = 0; k < R; ++k)
          for (std::size_t m = 0; m < M; ++m) {
            const std::size_t i = (k * M + m) * G + g;
            if (!r.ok(r.imp_status[i]) || count[i * E + e] <= 0) continue;
            sum += count[i * E + e], ++n, fmax = std::max(fmax, force[i * E + e]);
          }
        s += n ? fmt::format(" {:.1f}, {:.3g} |", sum / static_cast<double>(n), fmax / 1e6) : " 0, - |";
      }
      s += "\n";
    }
  }
  return s + frames_table(r);
}

}  // namespace pounding::report_detail
