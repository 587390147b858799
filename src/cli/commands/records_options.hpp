#pragma once
// Options and helpers the `pounding records` subcommands share (records.cpp, records_select.cpp).
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/motion/records.hpp"

namespace pounding::cli {

struct ReadOpts {
  std::string units = "g";
  double dt_record = 0.0;
  ReadOptions get() const {
    ReadOptions r;
    r.units = parse_units(units);
    r.dt = dt_record;
    return r;
  }
};

inline void add_read_options(CLI::App* c, ReadOpts& o) {
  c->add_option("--units", o.units, "units of the values in text files: g, m/s2, cm/s2 (AT2 headers that name "
                                    "their units win)")->capture_default_str();
  c->add_option("--dt-record", o.dt_record, "time step of one-column files (s)");
}

// What a records command reads, for files::check_output_not_input: the files given, and with a folder its record files
// (record_files_in) and MANIFEST.tsv; a folder that cannot be listed adds nothing (reading it then says why).
inline std::vector<std::string> records_read(std::vector<std::string> files, const std::string& dir = "") {
  if (dir.empty()) return files;
  try {
    for (auto& p : record_files_in(dir, "")) files.push_back(std::move(p));
  } catch (const InputError&) {
  }
  files.push_back((std::filesystem::path(dir) / "MANIFEST.tsv").string());
  return files;
}

// Records that an analysis would refuse are still shown (these commands are how one inspects them), with the
// analysis' message as a warning on stderr; exit code 0.
inline void warn_if_not_analysable(const Record& r) {
  if (auto e = analysis_problem(r, {1.0, "", "add --units cm/s2"}))
    fmt::print(stderr, " WARNING: {} (pounding run and simulate refuse this record)\n", e->what());
}

// "0.2,0.5,1" -> {0.2, 0.5, 1}; every value finite and >= `min_value` (> it when `strict`), else InputError
// "'<token>' is not a <what>" naming `option`, with `fix`.
inline std::vector<double> parse_number_list(const std::string& text, const std::string& option, const std::string& what,
                                             const std::string& fix, double min_value = 0.0, bool strict = false) {
  std::vector<double> p;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find(',', pos);
    if (end == std::string::npos) end = text.size();
    const std::string tok = text.substr(pos, end - pos);
    try {
      std::size_t used = 0;
      const double v = std::stod(tok, &used);
      if (used != tok.size() || !std::isfinite(v) || v < min_value || (strict && v == min_value))
        throw std::invalid_argument(tok);
      p.push_back(v);
    } catch (const std::exception&) {
      throw InputError(fmt::format("'{}' is not a {}", escaped_excerpt(tok), what), option, fix);
    }
    pos = end + 1;
  }
  return p;
}

}  // namespace pounding::cli
