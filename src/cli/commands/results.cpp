// `pounding results FILE`: every dataset of a results file (formats 1, 2 and 3) with its type, shape, units and
// description -- what a script needs to read it (docs/results-format.md), without h5dump.
#include <memory>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>

#include "cli/commands.hpp"
#include "pounding/results/describe.hpp"
#include "pounding/results/reader.hpp"

namespace pounding::cli {

void add_results(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto* c = app.add_subcommand("results", "list every dataset of a results file: type, shape, units, description "
                                          "(formats 1, 2 and 3; docs/results-format.md)");
  c->add_option("results", *path, "results file written by `pounding run`")->required();
  c->callback([path] {
    const results::Header h = results::load_header(*path);
    const auto all = results::inventory(*path);
    fmt::print("{}: format {}, {} datasets{}\n", *path, h.format_version, all.size(),
               h.title.empty() ? "" : ", \"" + h.title + "\"");
    fmt::print("{:<44} {:<6} {:<16} {:<8} {}\n", "dataset", "type", "shape", "units", "description");
    for (const results::DatasetInfo& d : all) {
      std::string desc = d.description;
      if (!d.axes.empty()) desc += " " + d.axes;
      fmt::print("{:<44} {:<6} {:<16} {:<8} {}\n", d.path, d.type, fmt::format("[{}]", fmt::join(d.shape, ",")),
                 d.units.empty() ? "-" : d.units, desc.empty() ? "-" : desc);
    }
  });
}

}  // namespace pounding::cli
