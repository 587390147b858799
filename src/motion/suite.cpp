// Record suites and their resolution to real or synthetic records (see suite.hpp).
#include "pounding/motion/suite.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "pounding/config/config.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/core/random.hpp"
#include "pounding/motion/library.hpp"
#include "embedded/stochastic_pounding_suite.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {

using config::location;

// Suite values point at "file:line" of the value (tests/motion/test_suite.cpp checks the exact place).
double get_number(const toml::node& n, const std::string& file, const std::string& key) {
  const double v = config::number(n, key, location(file, n.source()));
  if (!std::isfinite(v))
    throw InputError(fmt::format("{} = {} is not finite", key, v), location(file, n.source()),
                     fmt::format("write {} = <number>", key));
  return v;
}

std::string get_string(const toml::node& n, const std::string& file, const std::string& key) {
  return config::string(n, key, location(file, n.source()));
}

void check_keys(const toml::table& t, const std::string& file, const std::set<std::string, std::less<>>& allowed,
                const std::string& what) {
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  config::check_keys(
      t, [&](std::string_view k) { return allowed.count(k) > 0; }, what, list,
      [&](std::string_view, const toml::node& v) { return location(file, v.source()); });
}

std::string normalise(std::string_view s) {
  std::string out;
  for (char c : s)
    if (std::isalnum(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

std::uint64_t derive_seed(std::uint64_t suite_seed, const std::string& id) {
  return splitmix64(suite_seed ^ files::fnv1a(id.data(), id.size(), files::fnv1a_offset_basis));
}

namespace {

// [suite]: name, description, seed, dt.
void parse_suite_table(Suite& s, const toml::table& root, const std::string& path) {
  const toml::node* n = root.get("suite");
  if (!n) return;
  const toml::table* t = n->as_table();
  if (!t) throw InputError("[suite] must be a table", location(path, n->source()), "write [suite] with name, seed, dt");
  check_keys(*t, path, {"name", "description", "seed", "dt"}, "[suite]");
  if (auto v = t->get("name")) s.name = get_string(*v, path, "name");
  if (auto v = t->get("description")) s.description = get_string(*v, path, "description");
  if (auto v = t->get("seed")) s.seed = config::seed(*v, "seed", location(path, v->source()));
  if (auto v = t->get("dt")) {
    s.dt = get_number(*v, path, "dt");
    if (!(s.dt > 0 && s.dt <= 0.05))
      throw InputError(fmt::format("dt = {} is outside (0, 0.05] s", s.dt), location(path, v->source()),
                       "give the synthetic records' time step, e.g. dt = 0.01");
  }
}

// M, R_km, vs30, F of a [[record]]: the site when all four are given (and valid).
void parse_entry_site(SuiteEntry& e, const toml::table& t, const std::string& path, const std::string& at) {
  int site_keys = 0;
  SiteParams sp;
  auto site_num = [&](const char* key, double& out) {
    if (auto v = t.get(key)) {
      out = get_number(*v, path, key);
      ++site_keys;
    }
  };
  double F = -1;
  site_num("M", sp.M);
  site_num("R_km", sp.R_km);
  site_num("vs30", sp.vs30);
  site_num("F", F);
  if (site_keys > 0 && F >= 0) {
    if (F != 0 && F != 1)
      throw InputError(fmt::format("F = {} in record {}", F, e.id), location(path, t.get("F")->source()),
                       "F is 0 (strike-slip) or 1 (reverse or reverse-oblique)");
    sp.F = static_cast<int>(F);
  }
  if (site_keys == 4) {
    validate(sp, at);
    e.site = sp;
  }
}

// pga_g, file (relative to the suite file's directory), scale, units, dt_record of a [[record]].
void parse_entry_record(SuiteEntry& e, const toml::table& t, const std::string& path, const fs::path& base) {
  if (auto v = t.get("pga_g")) {
    e.pga_g = get_number(*v, path, "pga_g");
    if (!(e.pga_g > 0 && e.pga_g <= 5))
      throw InputError(fmt::format("pga_g = {} in record {}", e.pga_g, e.id), location(path, v->source()),
                       "give the PGA in g, in (0, 5]");
  }
  if (auto v = t.get("file")) {
    e.file = get_string(*v, path, "file");
    if (e.file.empty()) throw InputError("empty file name", location(path, v->source()), "give a path or drop the key");
    if (fs::path(e.file).is_relative() && !base.empty()) e.file = (base / e.file).lexically_normal().string();
  }
  if (auto v = t.get("scale")) {
    e.scale = get_number(*v, path, "scale");
    if (!(e.scale > 0))
      throw InputError(fmt::format("scale = {} in record {}", e.scale, e.id), location(path, v->source()), "give a factor > 0");
  }
  if (auto v = t.get("units")) {
    const std::string u = get_string(*v, path, "units");
    try {
      e.units = parse_units(u);
    } catch (const InputError&) {
      throw InputError(fmt::format("units = '{}'", u), location(path, v->source()), "use g, m/s2 or cm/s2");
    }
  }
  if (auto v = t.get("dt_record")) {
    e.dt_record = get_number(*v, path, "dt_record");
    if (!(e.dt_record > 0)) throw InputError("dt_record must be > 0", location(path, v->source()), "give the step in s");
  }
}

// One [[record]]; ids collects the ids seen so far (each must be unique).
SuiteEntry parse_entry(const toml::node& node, const Suite& s, const fs::path& base, std::set<std::string>& ids) {
  const std::string& path = s.path;
  const toml::table* t = node.as_table();
  if (!t) throw InputError("record must be a table", location(path, node.source()), "write [[record]] tables");
  check_keys(*t, path,
             {"id", "event", "year", "station", "component", "M", "R_km", "vs30", "F", "pga_g", "file", "scale",
              "seed", "units", "dt_record"},
             "[[record]]");
  SuiteEntry e;
  e.line = static_cast<int>(node.source().begin.line);
  const std::string at = fmt::format("{}:{}", path, e.line);
  const toml::node* id = t->get("id");
  if (!id) throw InputError("[[record]] without id", at, "give every record an id, e.g. id = \"EQ1\"");
  e.id = get_string(*id, path, "id");
  if (e.id.empty() || !ids.insert(e.id).second)
    throw InputError(fmt::format("id '{}' is empty or repeated", e.id), location(path, id->source()), "give unique ids");
  if (auto v = t->get("event")) e.event = get_string(*v, path, "event");
  if (auto v = t->get("station")) e.station = get_string(*v, path, "station");
  if (auto v = t->get("component")) e.component = get_string(*v, path, "component");
  if (auto v = t->get("year")) e.year = static_cast<int>(get_number(*v, path, "year"));
  parse_entry_site(e, *t, path, at);
  parse_entry_record(e, *t, path, base);
  e.seed = derive_seed(s.seed, e.id);
  if (auto v = t->get("seed")) e.seed = config::seed(*v, "seed", location(path, v->source()));
  if (e.file.empty() && !e.site)
    throw InputError(fmt::format("record {} has neither file nor a complete site (M, R_km, vs30, F)", e.id), at,
                     "add file = \"...\" or all of M, R_km, vs30 and F");
  return e;
}

}  // namespace

Suite parse_suite(const std::string& text, const std::string& path) {
  const toml::table root = config::parse(text, path, "fix the suite file's syntax");
  Suite s;
  s.path = path;
  check_keys(root, path, {"suite", "record"}, "the suite file");
  parse_suite_table(s, root, path);
  if (s.name.empty()) s.name = fs::path(path).stem().string();
  const toml::node* recs = root.get("record");
  const toml::array* arr = recs ? recs->as_array() : nullptr;
  if (!arr || arr->empty())
    throw InputError("no [[record]] entries", path, "list the ground motions as [[record]] tables with id = ...");
  const fs::path base = fs::path(path).parent_path();
  std::set<std::string> ids;
  for (const toml::node& node : *arr) s.entries.push_back(parse_entry(node, s, base, ids));
  return s;
}

Suite load_suite(const std::string& path) { return parse_suite(files::read_text(path, "the suite file"), path); }

// Compiled in from records/stochastic-pounding-suite.toml at build time (cmake/Embed.cmake), the one copy.
std::string_view default_suite_text() { return embedded::stochastic_pounding_suite; }

Suite default_suite() {
  return parse_suite(std::string(default_suite_text()), "<built-in stochastic-pounding-suite>");
}

namespace {

struct Candidate {
  std::string path, descriptor;
};

// What we know of each file in a directory: its name, its AT2 header line 2 (event, date, station,
// component) and its MANIFEST.tsv row when the directory has one.
std::vector<Candidate> scan_directory(const std::string& dir) {
  // the files: record_files_in (library.hpp), the one reader of a records directory
  const std::vector<std::string> paths = record_files_in(dir, "the records directory (--records-dir, [records] real_dir)");
  std::map<std::string, std::string> manifest;
  const fs::path mpath = fs::path(dir) / "MANIFEST.tsv";
  std::error_code ec;
  if (fs::is_regular_file(mpath, ec)) {  // a FIFO or a device is left unread, as library.cpp does (an ifstream blocks)
    std::ifstream m(mpath);
    std::string line;
    while (std::getline(m, line)) {
      std::stringstream ls(line);
      std::string file, rest, f;
      std::getline(ls, file, '\t');
      for (int i = 0; i < 4 && std::getline(ls, f, '\t'); ++i) rest += " " + f;  // event year station component
      manifest[file] = rest;
    }
  }
  std::vector<Candidate> out;
  for (const auto& path : paths) {
    const fs::path p(path);
    const std::string name = p.filename().string();
    const std::string ext = normalise(p.extension().string());
    Candidate c{path, name};
    if (ext == "at2") {
      std::ifstream in(p);
      std::string l1, l2;
      std::getline(in, l1), std::getline(in, l2);
      c.descriptor += " " + l2;
    }
    if (auto it = manifest.find(name); it != manifest.end()) c.descriptor += it->second;
    out.push_back(std::move(c));
  }
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.path < b.path; });
  return out;
}

}  // namespace

ResolvedRecord resolve_entry(const Suite& suite, const SuiteEntry& e, const ResolveOptions& o) {
  ResolvedRecord r;
  r.id = e.id;
  ReadOptions ro;
  ro.units = e.units;
  ro.dt = e.dt_record;
  auto finish_real = [&](Record rec, const std::string& note) {
    if (e.scale != 1.0)
      for (double& a : rec.acc) a *= e.scale;
    r.record = std::move(rec);
    r.scale = e.scale;
    r.synthetic = false;
    r.note = note;
    r.record.meta["suite_id"] = e.id;
    return r;
  };
  if (!o.synthetic_only && !e.file.empty()) return finish_real(read_record(e.file, ro), "file " + e.file);
  if (!o.synthetic_only && !o.records_dir.empty() && !e.station.empty()) {
    const std::string st = normalise(e.station), ev = normalise(e.event), yr = e.year ? std::to_string(e.year) : "";
    const std::string comp = normalise(e.component);
    std::vector<Record> found;
    for (const Candidate& c : scan_directory(o.records_dir)) {
      const std::string d = normalise(c.descriptor);
      if (d.find(st) == std::string::npos || (!ev.empty() && d.find(ev) == std::string::npos) ||
          (!yr.empty() && d.find(yr) == std::string::npos) || (!comp.empty() && d.find(comp) == std::string::npos))
        continue;
      found.push_back(read_record(c.path, ro));
    }
    if (!found.empty()) {
      // the component whose PGA is closest to the listed one (the paper lists one PGA per record)
      std::size_t best = 0;
      if (e.pga_g > 0)
        for (std::size_t i = 1; i < found.size(); ++i)
          if (std::abs(found[i].pga() / g_accel - e.pga_g) < std::abs(found[best].pga() / g_accel - e.pga_g)) best = i;
      const std::string note = fmt::format("directory match {} (PGA {:.3f} g; {} candidate{})", found[best].source,
                                           found[best].pga() / g_accel, found.size(), found.size() == 1 ? "" : "s");
      return finish_real(std::move(found[best]), note);
    }
  }
  if (!e.site) throw InputError(fmt::format("record {} has no file and no site for a synthetic stand-in", e.id),
                                fmt::format("{}:{}", suite.path, e.line), "add file = ... or M, R_km, vs30, F");
  if (!o.allow_synthetic)
    throw InputError(fmt::format("no real record found for {} ({} {}, {})", e.id, e.event, e.year, e.station),
                     fmt::format("{}:{}", suite.path, e.line),
                     o.records_dir.empty() ? "give a records directory or file = ..." : "add the file to " + o.records_dir);
  SynthOptions so;
  so.dt = suite.dt;
  so.pga_g = e.pga_g;
  Record rec = synthesize(*e.site, e.seed, so);
  double scale = 1.0;
  if (auto it = rec.meta.find("scale_to_pga"); it != rec.meta.end()) scale = std::stod(it->second);
  if (e.scale != 1.0)
    for (double& a : rec.acc) a *= e.scale;
  rec.name = e.id + "-synthetic";
  rec.meta["suite_id"] = e.id;
  rec.meta["event"] = e.event;
  rec.meta["station"] = e.station;
  r.record = std::move(rec);
  r.synthetic = true;
  r.scale = scale * e.scale;
  r.note = fmt::format("synthetic R&DK 2010 stand-in, M {} R {} km Vs30 {} F {}, seed {}, scaled to {} g",
                       e.site->M, e.site->R_km, e.site->vs30, e.site->F, e.seed,
                       e.pga_g > 0 ? fmt::format("{}", e.pga_g * e.scale) : std::string("(model amplitude)"));
  return r;
}

std::vector<ResolvedRecord> resolve_suite(const Suite& suite, const ResolveOptions& o) {
  std::vector<ResolvedRecord> out;
  out.reserve(suite.entries.size());
  for (const SuiteEntry& e : suite.entries) out.push_back(resolve_entry(suite, e, o));
  return out;
}

}  // namespace pounding
