#pragma once
// Record suites: a TOML file listing the ground motions of a study (records/*.toml), and the resolver
// that turns each entry into a Record - the user's real file when one is given or found, otherwise a
// Rezaeian & Der Kiureghian (2010) synthetic stand-in for the entry's (M, R, Vs30, F), generated with a
// fixed per-entry seed and scaled to the entry's PGA.
//
// Format (records/stochastic-pounding-suite.toml is the example; unknown keys are errors):
//   [suite]
//   name = "..."            description = "..." (optional)
//   seed = 20240601          master seed of the synthetic stand-ins (default 1)
//   dt = 0.01                time step of the synthetic stand-ins, s (default 0.01)
//   [[record]]               one per ground motion, in study order
//   id = "EQ1"               required, unique
//   event, station = "..."   year = 1984              (used to find the entry's file in a directory)
//   M, R_km, vs30, F         site for the synthetic stand-in (F: 0 strike-slip, 1 reverse/oblique)
//   pga_g = 0.35             the PGA the stand-in is scaled to; picks the closest component in a directory
//   file = "x.AT2"           optional: the user's record (relative to the suite file); then M... are optional
//   component = "270"        optional: only this component when searching a directory
//   scale = 1.0              optional factor on the resolved record (real or synthetic)
//   seed = 123               optional: overrides the derived per-entry seed
//   units = "g", dt_record = 0.01   optional, for `file` in other units / one-column files
// Every entry needs `file` or all of M, R_km, vs30, F.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/motion/records.hpp"
#include "pounding/motion/synthetic.hpp"

namespace pounding {

struct SuiteEntry {
  std::string id, event, station, component;
  int year = 0;
  std::optional<SiteParams> site;  // set when M, R_km, vs30 and F are all given
  double pga_g = 0.0;              // 0: not given
  std::string file;                // resolved against the suite file's directory; empty: none
  double scale = 1.0;
  std::uint64_t seed = 0;          // per-entry seed of the synthetic stand-in (derived unless given)
  AccUnits units = AccUnits::g;
  double dt_record = 0.0;
  int line = 0;                    // line of the [[record]] header in the suite file
};

struct Suite {
  std::string path;  // the suite file ("<built-in>" for the embedded default)
  std::string name, description;
  std::uint64_t seed = 1;
  double dt = 0.01;
  std::vector<SuiteEntry> entries;
};

// Parses and validates; errors name the file, the line and the key.
Suite parse_suite(const std::string& text, const std::string& path);
Suite load_suite(const std::string& path);
// The 25-record suite of stochastic-pounding-monte-carlo.txt: records/stochastic-pounding-suite.toml, compiled
// into the binary at build time (cmake/Embed.cmake), so a fresh install runs without files.
Suite default_suite();
std::string_view default_suite_text();
// seed of an entry without an explicit one: splitmix64(suite seed ^ FNV-1a-64(id)).
std::uint64_t derive_seed(std::uint64_t suite_seed, const std::string& id);

struct ResolveOptions {
  std::string records_dir;       // directory of PEER/real files searched for each entry (empty: none); its .AT2
                                 // and .txt files (record_files_in, library.hpp; none is an InputError)
  bool allow_synthetic = true;   // false: an entry without a real file is an error
  bool synthetic_only = false;   // ignore files and directories: every entry synthetic
};

struct ResolvedRecord {
  std::string id;
  Record record;       // m/s^2, scaled
  bool synthetic = false;
  double scale = 1.0;  // factor applied (for synthetic: to reach pga_g, times the entry's scale)
  std::string note;    // how it was resolved ("file ...", "directory match ...", "synthetic ...")
};

// Resolves every entry in order. Synthetic stand-ins use SynthOptions{dt = suite.dt} and the entry seed.
std::vector<ResolvedRecord> resolve_suite(const Suite& suite, const ResolveOptions& options = {});
ResolvedRecord resolve_entry(const Suite& suite, const SuiteEntry& entry, const ResolveOptions& options = {});

}  // namespace pounding
