// "Records selected to the design spectrum": the /selection group of a study with [records] select = N
// (study/target_spectrum.hpp) as a short Markdown section.
#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/report/escape.hpp"

namespace pounding::report_detail {

std::string selection_section(const results::Results& r) {
  const results::Group* g = r.group("selection");
  if (!g) return "";
  const auto& ids = g->get<std::string>("records");
  const auto& scale = g->get<double>("scale");
  const auto& f = g->get<double>("individual_scale");
  const auto& mse = g->get<double>("mse");
  std::string s = "\n## Records selected to the design spectrum\n\n";
  s += fmt::format("Target: {}. {} of {} candidate records chosen ({} with a least-squares factor within [{:g}, {:g}]) "
                   "by the misfit of ln Sa over {} periods; suite factor F = {:.4f}.\n\n",
                   report::md_text(g->text("target_description")), ids.size(), static_cast<long>(g->number("candidates")),
                   static_cast<long>(g->number("eligible")), g->number("min_scale"), g->number("max_scale"),
                   g->get<double>("periods").size(), g->number("suite_factor"));
  // event/station: results written before issue 23 item 7 have none ("-")
  const bool has_identity = g->find("event") != nullptr;
  auto text_at = [&](const char* name, std::size_t k) {
    if (!has_identity) return std::string("-");
    const auto& v = g->get<std::string>(name);
    return k < v.size() && !v[k].empty() ? report::md_cell(v[k]) : std::string("-");
  };
  s += "| record | event | station | comp. | factor f_i F | f_i | misfit (MSE of ln Sa) |\n"
       "|---|---|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < ids.size(); ++k)
    s += fmt::format("| {} | {} | {} | {} | {:.4f} | {:.4f} | {:.5f} |\n", report::md_cell(ids[k]), text_at("event", k),
                     text_at("station", k), text_at("component", k), scale[k], f[k], mse[k]);
  if (has_identity) {
    const auto mpe = static_cast<long>(g->number("max_per_event"));
    s += fmt::format("\nRules: at most {} per event, components = {}; a second copy of one recording is never "
                     "chosen.\n", mpe == 0 ? std::string("any number") : std::to_string(mpe), g->text("components"));
    if (const auto* w = g->attribute("refused"))
      if (const auto* list = std::get_if<std::vector<std::string>>(w))
        for (const auto& line : *list) s += "- passed over: " + report::md_text(line) + "\n";
  }
  const bool none = g->text("rule") == "none";
  s += fmt::format("\n{}: {} (smallest mean/target {:.4f}{}).\n", g->text("rule_text"),
                   none ? "no condition" : g->number("meets") != 0 ? "**holds**" : "**does NOT hold**",
                   g->number("min_ratio"),
                   g->text("rule") == "EC8" ? fmt::format(", mean PGA / ag S {:.4f}", g->number("pga_ratio")) : "");
  if (const auto* w = g->attribute("warnings"))
    if (const auto* list = std::get_if<std::vector<std::string>>(w))
      for (const auto& line : *list) s += "- warning: " + report::md_text(line) + "\n";
  return s;
}

// /histories: per stored history its analysis, run and peaks (the series are in the file: /histories/<n>/t, u, a_abs,
// force; docs/results-format.md).
std::string histories_section(const results::Results& r) {
  const results::Group* g = r.group("histories");
  if (!g || g->children.empty()) return "";
  std::vector<const results::Group*> h;
  for (const results::Group& c : g->children) h.push_back(&c);
  std::stable_sort(h.begin(), h.end(), [](const results::Group* a, const results::Group* b) {
    return std::stol("0" + a->name) < std::stol("0" + b->name);
  });
  std::string s = fmt::format("\n## Stored time histories\n\n{} analys{} rerun with the recorder ([outputs] histories): "
                              "t, u and a_abs per DOF, force per contact element in /histories/<n>.\n\n",
                              h.size(), h.size() == 1 ? "is" : "es");
  s += "| n | record | model (i1, i2, sample) | run | gap (m) | peak closing (m) | peak force (N) | impacts | chosen |\n"
       "|---|---|---|---|---|---|---|---|---|\n";
  auto number = [](const results::Group* x, const char* key, const char* fmt_) {
    return x->attribute(key) ? fmt::format(fmt::runtime(fmt_), x->number(key)) : std::string("-");
  };
  for (const results::Group* x : h) {
    const bool coupled = x->text("run") == "coupled";
    s += fmt::format("| {} | {} | {} ({}, {}, {}) | {} | {} | {} | {} | {} | {} |\n", x->name,
                     report::md_cell(x->text("record")), static_cast<long>(x->number("model")),
                     static_cast<long>(x->number("i1")), static_cast<long>(x->number("i2")),
                     static_cast<long>(x->number("sample")),
                     !coupled ? std::string("uncoupled")
                     : x->attribute("gap_ratio") ? fmt::format("coupled at {:g} d", x->number("gap_ratio"))
                                                 : fmt::format("coupled at {:g} m", x->number("gap_m")),  // [gaps] metres
                     number(x, "gap_m", "{:.4g}"), number(x, "peak_closing", "{:.4g}"), number(x, "peak_force", "{:.4g}"),
                     number(x, "impact_count", "{:.0f}"), report::md_cell(x->text("chosen")));
  }
  return s;
}

}  // namespace pounding::report_detail
