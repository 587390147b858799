// "Records selected to the design spectrum": the /selection group of a study with [records] select = N
// (study/target_spectrum.hpp) as a short Markdown section.
#include <fmt/format.h>

#include "data.hpp"

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
                   g->text("target_description"), ids.size(), static_cast<long>(g->number("candidates")),
                   static_cast<long>(g->number("eligible")), g->number("min_scale"), g->number("max_scale"),
                   g->get<double>("periods").size(), g->number("suite_factor"));
  s += "| record | factor f_i F | f_i | misfit (MSE of ln Sa) |\n|---|---|---|---|\n";
  for (std::size_t k = 0; k < ids.size(); ++k)
    s += fmt::format("| {} | {:.4f} | {:.4f} | {:.5f} |\n", ids[k], scale[k], f[k], mse[k]);
  const bool none = g->text("rule") == "none";
  s += fmt::format("\n{}: {} (smallest mean/target {:.4f}{}).\n", g->text("rule_text"),
                   none ? "no condition" : g->number("meets") != 0 ? "**holds**" : "**does NOT hold**",
                   g->number("min_ratio"),
                   g->text("rule") == "EC8" ? fmt::format(", mean PGA / ag S {:.4f}", g->number("pga_ratio")) : "");
  if (const auto* w = g->attribute("warnings"))
    if (const auto* list = std::get_if<std::vector<std::string>>(w))
      for (const auto& line : *list) s += "- warning: " + line + "\n";
  return s;
}

}  // namespace pounding::report_detail
