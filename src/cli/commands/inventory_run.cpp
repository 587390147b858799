// `pounding inventory run STUDY.toml`: every adjacent pair of an inventory as a pair study, run one after another in one
// MPI session, and the answers gathered per pair and per building into CSV, GeoJSON and a Markdown ranking.
//
// The study file is a template: its [inventory] section names the inventory and the site, every other section
// ([records], [contact], [report], [analysis], [gaps] metres, seed) is each pair's; the pair's buildings, spectrum and
// existing gap are written per pair (inventory/pair_study.hpp). Outputs beside the template's output R.h5:
//   R.pairs/<a>--<b>.toml, .h5, .md   each pair's study, results and report (kept: a pair can be rerun alone)
//   R.pairs.csv, R.pairs.geojson      one row / feature per pair (a line between the footprints' centres; GeoJSON
//   R.buildings.geojson               inventories only) and one footprint per building with its worst neighbour
//   R.md, R.html                      the pairs ranked by P(pounding) at their existing gap; the HTML with a map of the
//                                     footprints coloured by their worst neighbour's P
// A pair whose results exist and were made from the same study text is not run again (rerun with --force).
#include <sys/stat.h>

#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "cli/commands.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/inventory/inventory.hpp"
#include "pounding/inventory/pair_study.hpp"
#include "pounding/report/escape.hpp"
#include "pounding/report/report.hpp"
#include "pounding/results/reader.hpp"

namespace pounding::cli {
namespace {

using report::csv_field;
using report::html_text;
using report::md_cell;
using report::md_text;

struct Template {
  std::string path, output_stem, title;
  toml::table study;  // the template less [inventory]
  inventory::PairStudyOptions pair;
  inventory::AdjacencyRules rules;
  inventory::EraRule eras;
  std::string inventory_file;
};

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

double num(const toml::table& t, const char* key, double fallback, const std::string& where) {
  const toml::node* n = t.get(key);
  if (!n) return fallback;
  if (const auto v = n->value<double>()) return *v;
  throw InputError(fmt::format("[inventory] {} is not a number", key), where, "give a number");
}

// [inventory]: file, ss, s1, tl, shaking, samples, records, beta_period, beta_strength, beta_damping, threshold,
// min_frontage, level_tolerance, high_from, moderate_from.
void read_inventory_section(const toml::table& inv, Template& t) {
  static constexpr const char* keys[] = {"file", "ss", "s1", "tl", "shaking", "samples", "records", "beta_period",
                                         "beta_strength", "beta_damping", "threshold", "min_frontage",
                                         "level_tolerance", "high_from", "moderate_from"};
  std::string all;
  for (const char* k : keys) all += (all.empty() ? "" : ", ") + std::string(k);
  for (const auto& [k, v] : inv)
    if (std::find_if(std::begin(keys), std::end(keys), [&](const char* x) { return k.str() == x; }) == std::end(keys))
      throw unknown_key_error(k.str(), "[inventory]", t.path, all);
  const std::string where = t.path + " [inventory]";
  const auto file = inv["file"].value<std::string>();
  if (!file) throw InputError("[inventory] file is missing", where, "name the inventory: file = \"street.geojson\"");
  t.inventory_file = file->front() == '/' ? *file : folder_of(t.path) + *file;
  auto& p = t.pair;
  p.ss = num(inv, "ss", p.ss, where), p.s1 = num(inv, "s1", p.s1, where), p.tl = num(inv, "tl", p.tl, where);
  const std::string shaking = inv["shaking"].value_or(std::string("mce"));
  if (shaking != "mce" && shaking != "design")
    throw InputError(fmt::format("[inventory] shaking = \"{}\"", shaking), where, "give \"mce\" or \"design\"");
  p.mce = shaking == "mce";
  p.samples = static_cast<int>(num(inv, "samples", p.samples, where));
  p.records = static_cast<int>(num(inv, "records", p.records, where));
  p.beta_period = num(inv, "beta_period", p.beta_period, where);
  p.beta_strength = num(inv, "beta_strength", p.beta_strength, where);
  p.beta_damping = num(inv, "beta_damping", p.beta_damping, where);
  require_range(p.samples, 1, 10000, where + " samples", "[1, 10000]");
  require_range(p.records, 1, 1000, where + " records", "[1, 1000]");
  for (double b : {p.beta_period, p.beta_strength, p.beta_damping})
    require_range(b, 0.0, 1.0, where + " beta_*", "[0, 1] (a lognormal dispersion)");
  t.rules.threshold = num(inv, "threshold", t.rules.threshold, where);
  t.rules.min_frontage = num(inv, "min_frontage", t.rules.min_frontage, where);
  t.rules.level_tolerance = num(inv, "level_tolerance", t.rules.level_tolerance, where);
  t.eras.high_from = static_cast<int>(num(inv, "high_from", t.eras.high_from, where));
  t.eras.moderate_from = static_cast<int>(num(inv, "moderate_from", t.eras.moderate_from, where));
}

// A path the template gives relative to itself, made absolute: the pair's study lives in another folder.
std::string rebased(const std::string& value, const std::string& folder) {
  if (value.empty() || value.front() == '/' || value == "builtin") return value;
  return folder + value;
}

// Every key the study-key table describes as "relative to the study file", rebased to the template's folder: strings,
// arrays of strings, and the `path` of tables in arrays ([records] files = [{path = .., scale = ..}]).
void rebase_paths(toml::table& study, const std::string& folder) {
  for (const config::StudyKey& k : config::study_keys()) {
    if (k.meaning.find("relative to the study") == std::string_view::npos) continue;
    toml::node* section = k.section.empty() ? &study : study.at_path(k.section).node();
    toml::table* table = section ? section->as_table() : nullptr;
    if (!table) continue;
    toml::node* v = table->get(k.key);
    if (!v) continue;
    if (auto* str = v->as_string()) *str = rebased(str->get(), folder);
    if (auto* arr = v->as_array())
      for (toml::node& e : *arr) {
        if (auto* str = e.as_string()) *str = rebased(str->get(), folder);
        if (auto* tab = e.as_table())
          if (auto* path = tab->get_as<std::string>("path")) *path = rebased(path->get(), folder);
      }
  }
}

Template read_template(const std::string& path) {
  Template t;
  t.path = path;
  toml::table doc;
  try {
    doc = toml::parse(files::read_text(path, "study"), path);
  } catch (const toml::parse_error& e) {
    throw InputError(std::string(e.description()), fmt::format("{}:{}", path, e.source().begin.line), "fix the TOML syntax");
  }
  const toml::table* inv = doc["inventory"].as_table();
  if (!inv) throw InputError("the study has no [inventory] section", path, "add [inventory] file = \"street.geojson\"");
  read_inventory_section(*inv, t);
  for (const char* own : {"structures", "target_spectrum"})
    if (doc.contains(own))
      throw InputError(fmt::format("[{}] is made per pair from the inventory", own), path,
                       "remove it: the buildings and each site's spectrum come from [inventory] and the inventory file");
  if (const toml::table* g = doc["gaps"].as_table(); g && g->contains("existing"))
    throw InputError("[gaps] existing is each pair's measured gap", path + " [gaps] existing", "remove it");
  const std::string out = doc["output"].value_or(std::string());
  const std::string base = out.empty() ? path.substr(0, path.rfind('.')) : folder_of(path) + out;
  t.output_stem = base.size() > 3 && base.compare(base.size() - 3, 3, ".h5") == 0 ? base.substr(0, base.size() - 3) : base;
  t.title = doc["title"].value_or(std::string("Pounding along ") + path);
  char* real = ::realpath(path.c_str(), nullptr);
  const std::string folder = folder_of(real ? std::string(real) : path);
  std::free(real);
  rebase_paths(doc, folder.empty() ? "./" : folder);
  doc.erase("inventory");
  doc.erase("output");
  doc.erase("title");
  t.study = std::move(doc);
  return t;
}

// The pair's study: the generated text with the template's sections over it ([gaps] merged key by key).
std::string merged_study(const Template& t, const std::string& generated, const std::string& results_name) {
  toml::table pair = toml::parse(generated);
  for (const auto& [k, v] : t.study) {
    if (k.str() == "gaps" && v.is_table()) {
      for (const auto& [gk, gv] : *v.as_table()) pair["gaps"].as_table()->insert_or_assign(gk, gv);
      continue;
    }
    pair.insert_or_assign(k, v);
  }
  // the template's own records without selection: taken as they are (a fragility study scales them to its stripes)
  if (const toml::table* rec = t.study["records"].as_table(); rec && !rec->contains("select")) pair.erase("target_spectrum");
  pair.insert_or_assign("output", results_name);
  std::ostringstream s;
  s << "# Written by `pounding inventory run " << t.path << "` (docs/inventory.md): the template's sections over the "
    << "pair's buildings.\n" << pair << "\n";
  return s.str();
}

std::string file_safe(const std::string& id) {
  std::string s;
  for (char c : id) s += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') ? c : '_';
  return s;
}

struct PairAnswer {
  double p = NAN, p_lo = NAN, p_hi = NAN;  // at the existing gap
  std::vector<std::pair<double, double>> separation;  // (target, m)
  std::string worst_level;
  double worst_level_p = NAN, worst_level_force = NAN;  // at the axis gap nearest the existing one
  // a fragility template (stripes and [hazard]): P(pounding) in the hazard's years at the existing gap, the
  // risk-targeted separation at [hazard] target and the advice (its upper interval bound)
  double p_years = NAN, risk_gap = NAN, risk_target = NAN, advice = NAN;
  // the ranking's key: P at the existing gap, or in the hazard's years
  double rank_key() const { return std::isnan(p) ? p_years : p; }
};

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool q = false;
  for (char c : line) {
    if (c == '"') q = !q;
    else if (c == ',' && !q) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

double to_num(const std::string& s) { return s.empty() ? NAN : std::stod(s); }

// The answers of one pair, read from its report's CSV rows (docs/results-format.md): existing, separation, level,
// level_force.
// The fragility report's rows (docs/results-format.md): the fragility at the existing gap (on the axis: the pair's
// study puts it there), the risk-targeted gap and the separation advice.
void fragility_rows(const std::string& table, const std::vector<std::string>& f, const std::map<std::string, std::size_t>& col,
                    double existing, PairAnswer& a) {
  const auto at = [&](const char* name) { return to_num(f.at(col.at(name))); };
  if (table == "fragility" && existing > 0 && std::abs(at("gap_m") - existing) < 1e-9) a.p_years = at("probability");
  if (table == "risk_targeted_gap") a.risk_gap = at("gap_m"), a.risk_target = at("probability");
  if (table == "separation_advice") a.advice = at("gap_m");
}

PairAnswer answer_of(const results::Results& r, double existing) {
  PairAnswer a;
  std::istringstream in(report_csv(r));
  std::string line;
  std::map<std::string, std::map<double, double>> level_p, level_f;
  std::map<std::string, std::size_t> col;
  for (bool header = true; std::getline(in, line); header = false) {
    const std::vector<std::string> f = csv_fields(line);
    if (header) {
      for (std::size_t i = 0; i < f.size(); ++i) col[f[i]] = i;
      continue;
    }
    if (col.count("annual_rate")) {
      fragility_rows(f[0], f, col, existing, a);
      continue;
    }
    if (f.size() < 12) continue;
    if (f[0] == "existing") a.p = to_num(f[7]), a.p_lo = to_num(f[9]), a.p_hi = to_num(f[10]);
    else if (f[0] == "separation") a.separation.emplace_back(to_num(f[7]), to_num(f[8]));
    else if (f[0] == "level") level_p[f[11]][to_num(f[2])] = to_num(f[7]);
    else if (f[0] == "level_force") level_f[f[11]][to_num(f[2])] = to_num(f[10]);
  }
  for (const auto& [name, byg] : level_p) {
    double best_g = NAN;
    for (const auto& [g, p] : byg)
      if (std::isnan(best_g) || std::abs(g - existing) < std::abs(best_g - existing)) best_g = g;
    const double p = byg.at(best_g);
    if (std::isnan(a.worst_level_p) || p > a.worst_level_p) {
      a.worst_level = name, a.worst_level_p = p;
      const auto fi = level_f[name].find(best_g);
      a.worst_level_force = fi == level_f[name].end() ? 0.0 : fi->second;
    }
  }
  return a;
}

struct RunInventoryOpts {
  std::string study;
  StudyRunFlags flags;
};

void run_inventory(const RunInventoryOpts& o);

}  // namespace

void add_inventory_run(CLI::App* inv) {
  auto o = std::make_shared<RunInventoryOpts>();
  auto* c = inv->add_subcommand("run", "every adjacent pair of an inventory as a pair study, and the answers per pair "
                                       "and per building (CSV, GeoJSON, a ranking)");
  c->add_option("study", o->study, "the study template with its [inventory] section (docs/inventory.md)")->required();
  c->add_flag("--force", o->flags.force, "run every pair again, also those whose results exist");
  c->add_flag("--quiet", o->flags.quiet, "no progress display");
  c->add_option("--threads", o->flags.threads, "worker threads per rank (as pounding run)");
  c->callback([o] { run_inventory(*o); });
}

namespace {

using report::csv_field;
using report::html_text;
using report::md_cell;
using report::md_text;

std::string json_text(const std::string& s) { return nlohmann::json(s).dump(); }

std::string geo_pairs(const inventory::Inventory& inv, const std::vector<inventory::Adjacency>& pairs,
                      const std::vector<PairAnswer>& ans) {
  std::string s = "{\"type\": \"FeatureCollection\", \"features\": [\n";
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& p = pairs[i];
    const auto centre = [](const std::vector<inventory::Point>& r) {
      double x = 0, y = 0;
      for (const auto& q : r) x += q[0], y += q[1];
      return inventory::Point{x / static_cast<double>(r.size()), y / static_cast<double>(r.size())};
    };
    const auto ca = centre(inv.buildings[p.a].footprint_input), cb = centre(inv.buildings[p.b].footprint_input);
    s += fmt::format("{}{{\"type\": \"Feature\", \"properties\": {{\"a\": {}, \"b\": {}, \"kind\": \"{}\", \"gap_m\": {:.3f}, "
                     "\"floors_aligned\": {}, \"p_existing\": {:.6g}, \"p_lo\": {:.6g}, \"p_hi\": {:.6g}{}}}, \"geometry\": "
                     "{{\"type\": \"LineString\", \"coordinates\": [[{:.9f}, {:.9f}], [{:.9f}, {:.9f}]]}}}}",
                     i ? ",\n" : "", json_text(inv.buildings[p.a].id), json_text(inv.buildings[p.b].id), to_string(p.kind), p.gap,
                     p.floors_aligned ? "true" : "false", ans[i].p, ans[i].p_lo, ans[i].p_hi,
                     [&] {
                       std::string x;
                       for (const auto& [t, m] : ans[i].separation) x += fmt::format(", \"separation_{:g}pct_m\": {:.4f}", 100 * t, m);
                       return x;
                     }(),
                     ca[0], ca[1], cb[0], cb[1]);
  }
  return s + "\n]}\n";
}

// Each building's footprint (as the file gives it) with its worst neighbour: the largest P(pounding) at the existing gap.
std::string geo_buildings(const inventory::Inventory& inv, const std::vector<inventory::Adjacency>& pairs,
                          const std::vector<PairAnswer>& ans) {
  std::string s = "{\"type\": \"FeatureCollection\", \"features\": [\n";
  for (std::size_t b = 0; b < inv.buildings.size(); ++b) {
    const inventory::Building& x = inv.buildings[b];
    double worst = -1;
    std::string neighbour;
    for (std::size_t i = 0; i < pairs.size(); ++i)
      if ((pairs[i].a == b || pairs[i].b == b) && ans[i].p > worst)
        worst = ans[i].p, neighbour = inv.buildings[pairs[i].a == b ? pairs[i].b : pairs[i].a].id;
    std::string ring;
    for (const auto& q : x.footprint_input) ring += fmt::format("[{:.9f}, {:.9f}], ", q[0], q[1]);
    if (!x.footprint_input.empty())
      ring += fmt::format("[{:.9f}, {:.9f}]", x.footprint_input.front()[0], x.footprint_input.front()[1]);
    s += fmt::format("{}{{\"type\": \"Feature\", \"properties\": {{\"id\": {}, \"system\": \"{}\", \"storeys\": {}, "
                     "\"design_level\": \"{}\", \"worst_neighbour\": {}, \"p_worst\": {}}}, \"geometry\": {}}}",
                     b ? ",\n" : "", json_text(x.id), x.system, x.storeys, to_string(x.level),
                     neighbour.empty() ? "null" : json_text(neighbour), worst < 0 ? "null" : fmt::format("{:.6g}", worst),
                     ring.empty() ? "null" : "{\"type\": \"Polygon\", \"coordinates\": [[" + ring + "]]}");
  }
  return s + "\n]}\n";
}

// Green (P = 0) through yellow to red (P = 1); grey without an answer.
std::string colour(double p) {
  if (std::isnan(p)) return "#bbbbbb";
  const double t = std::clamp(p, 0.0, 1.0);
  const auto mix = [](double a, double b, double u) { return static_cast<int>(std::lround(a + (b - a) * u)); };
  return t < 0.5 ? fmt::format("#{:02x}{:02x}{:02x}", mix(26, 254, 2 * t), mix(152, 224, 2 * t), mix(80, 139, 2 * t))
                 : fmt::format("#{:02x}{:02x}{:02x}", mix(254, 215, 2 * t - 1), mix(224, 48, 2 * t - 1), mix(139, 39, 2 * t - 1));
}

// The map: footprints in the local plane (metres, north up) filled by their worst neighbour's P(pounding), each pair a
// line between the footprints' centres coloured by its own; every shape carries a tooltip.
std::string svg_map(const inventory::Inventory& inv, const std::vector<inventory::Adjacency>& pairs,
                    const std::vector<PairAnswer>& ans) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const auto& b : inv.buildings)
    for (const auto& q : b.footprint) x0 = std::min(x0, q[0]), x1 = std::max(x1, q[0]), y0 = std::min(y0, q[1]), y1 = std::max(y1, q[1]);
  const double pad = 0.05 * std::max(x1 - x0, y1 - y0) + 1, w = x1 - x0 + 2 * pad, h = y1 - y0 + 2 * pad;
  const auto X = [&](double x) { return x - x0 + pad; };
  const auto Y = [&](double y) { return y1 + pad - y; };
  std::string s = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {:.2f} {:.2f}\" "
                              "style=\"width:100%;max-height:70vh;background:#f7f7f7\">\n", w, h);
  std::vector<inventory::Point> centre(inv.buildings.size());
  for (std::size_t b = 0; b < inv.buildings.size(); ++b) {
    const auto& x = inv.buildings[b];
    double worst = NAN, cx = 0, cy = 0;
    for (std::size_t i = 0; i < pairs.size(); ++i)
      if ((pairs[i].a == b || pairs[i].b == b) && !(ans[i].rank_key() <= worst)) worst = ans[i].rank_key();
    std::string pts;
    for (const auto& q : x.footprint) pts += fmt::format("{:.2f},{:.2f} ", X(q[0]), Y(q[1])), cx += q[0], cy += q[1];
    centre[b] = {cx / static_cast<double>(x.footprint.size()), cy / static_cast<double>(x.footprint.size())};
    s += fmt::format("<polygon points=\"{}\" fill=\"{}\" stroke=\"#333\" stroke-width=\"{:.3g}\"><title>{}: {}, {} storeys, "
                     "{}; worst neighbour P = {}</title></polygon>\n", pts, colour(worst), 0.002 * w, html_text(x.id), x.system,
                     x.storeys, to_string(x.level), std::isnan(worst) ? std::string("-") : fmt::format("{:.1f} %", 100 * worst));
  }
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& a = centre[pairs[i].a];
    const auto& b = centre[pairs[i].b];
    s += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\" stroke-width=\"{:.3g}\" "
                     "stroke-linecap=\"round\"><title>{} - {}: gap {:.3f} m, P(pounding) {:.1f} %</title></line>\n",
                     X(a[0]), Y(a[1]), X(b[0]), Y(b[1]), colour(ans[i].rank_key()), 0.006 * w, html_text(inv.buildings[pairs[i].a].id),
                     html_text(inv.buildings[pairs[i].b].id), pairs[i].gap, 100 * ans[i].rank_key());
  }
  return s + "</svg>\n";
}

std::string html_page(const std::string& title, const inventory::Inventory& inv, const std::vector<inventory::Adjacency>& pairs,
                      const std::vector<PairAnswer>& ans, const std::vector<std::size_t>& order) {
  std::string s = fmt::format("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title><style>"
                              "body{{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em}}"
                              "table{{border-collapse:collapse}}td,th{{border:1px solid #ccc;padding:3px 8px;text-align:right}}"
                              "td:nth-child(2),th:nth-child(2){{text-align:left}}</style></head><body>\n<h1>{}</h1>\n"
                              "<p>{} buildings, {} adjacent pairs from <code>{}</code>. Footprints are filled by the "
                              "largest P(pounding) at the existing gap of any of their pairs, lines join the pairs: green "
                              "0 %, yellow 50 %, red 100 % (hover for the numbers).</p>\n",
                              html_text(title), html_text(title), inv.buildings.size(), pairs.size(), html_text(inv.file));
  s += inv.footprints ? svg_map(inv, pairs, ans) : "<p>(a street-order inventory has no footprints to map)</p>\n";
  s += "<h2>Pairs ranked by P(pounding) at the existing gap</h2>\n<table><tr><th>rank</th><th>pair</th><th>kind</th>"
       "<th>gap m</th><th>floors</th><th>P(pounding)</th><th>95 % interval</th><th>separation for 10 % m</th></tr>\n";
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto& p = pairs[order[k]];
    const auto& a = ans[order[k]];
    s += fmt::format("<tr><td>{}</td><td>{} &ndash; {}</td><td>{}</td><td>{:.3f}</td><td>{}</td><td style=\"background:{}\">"
                     "{:.1f} %</td><td>[{:.1f}, {:.1f}] %</td><td>{:.3f}</td></tr>\n",
                     k + 1, html_text(inv.buildings[p.a].id), html_text(inv.buildings[p.b].id), to_string(p.kind), p.gap,
                     p.floors_aligned ? "aligned" : "floor to column", colour(a.p), 100 * a.p, 100 * a.p_lo, 100 * a.p_hi,
                     a.separation.empty() ? NAN : a.separation.front().second);
  }
  return s + "</table>\n</body></html>\n";
}

// One row per pair: the adjacency, the answer at the existing gap, the separations, the worst level.
std::string pairs_csv(const inventory::Inventory& inv, const std::vector<inventory::Adjacency>& pairs,
                      const std::vector<PairAnswer>& answers, const std::vector<std::string>& stems) {
  std::string csv = "building_a,building_b,kind,gap_m,frontage_m,floors_aligned,worst_floor_offset_m,p_existing,p_lo,p_hi";
  for (const auto& [tgt, m] : answers.front().separation) csv += fmt::format(",separation_{:g}pct_m", 100 * tgt);
  csv += ",worst_level,worst_level_p,worst_level_force_p84_N,p_hazard_years,risk_targeted_gap_m,risk_target,"
         "separation_advice_m,results\n";
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& p = pairs[i];
    const auto& a = answers[i];
    csv += fmt::format("{},{},{},{:.3f},{:.2f},{},{:.3f},{:.6g},{:.6g},{:.6g}", csv_field(inv.buildings[p.a].id),
                       csv_field(inv.buildings[p.b].id),
                       to_string(p.kind), p.gap, p.frontage, p.floors_aligned ? "yes" : "no", p.worst_offset, a.p, a.p_lo, a.p_hi);
    for (const auto& [tgt, m] : a.separation) csv += fmt::format(",{:.4f}", m);
    csv += fmt::format(",{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{}\n", csv_field(a.worst_level), a.worst_level_p,
                       a.worst_level_force, a.p_years, a.risk_gap, a.risk_target, a.advice,
                       csv_field(stems[i] + ".h5"));
  }
  return csv;
}

void run_inventory(const RunInventoryOpts& o) {
  const Template t = read_template(o.study);
  const inventory::Inventory inv = inventory::read_inventory(t.inventory_file, t.eras);
  const std::vector<inventory::Adjacency> pairs = inventory::adjacent_pairs(inv, t.rules);
  if (pairs.empty()) throw InputError("the inventory has no adjacent pair", t.inventory_file, "check --threshold and the footprints");
  const std::string dir = t.output_stem + ".pairs";
  for (const std::string& out : {t.output_stem + ".pairs.csv", t.output_stem + ".pairs.geojson",
                                 t.output_stem + ".buildings.geojson", t.output_stem + ".md", t.output_stem + ".html"}) {
    files::check_output_path(out, o.study);
    files::check_output_not_input(out, {o.study, t.inventory_file}, o.study);
  }
  ::mkdir(dir.c_str(), 0777);
  std::vector<StudyJob> jobs;
  std::vector<std::size_t> job_pair;
  std::vector<std::string> stems(pairs.size());
  std::vector<PairAnswer> answers(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto& a = inv.buildings[pairs[i].a];
    const auto& b = inv.buildings[pairs[i].b];
    stems[i] = dir + "/" + file_safe(a.id) + "--" + file_safe(b.id);
    const std::string text = merged_study(t, inventory::pair_study_text(inv, pairs[i], t.pair), stems[i] + ".h5");
    bool current = false;
    if (!o.flags.force && ::access((stems[i] + ".h5").c_str(), R_OK) == 0) {
      try {
        current = results::load(stems[i] + ".h5", {}, results::LoadExtent::report).header.study_text == text;
      } catch (const std::exception&) {
      }
    }
    if (current) continue;
    files::write_text_atomically(stems[i] + ".toml", text);
    jobs.push_back({stems[i] + ".toml", stems[i] + ".h5"});
    job_pair.push_back(i);
  }
  fmt::print(stderr, "inventory {}: {} buildings, {} adjacent pairs; {} to run, {} current\n", t.inventory_file,
             inv.buildings.size(), pairs.size(), jobs.size(), pairs.size() - jobs.size());
  StudyRunFlags flags = o.flags;
  flags.force = true;  // a pair rerun starts afresh: its text changed or it never finished
  const int code = jobs.empty() ? 0 : run_study_files(jobs, flags, [&](std::size_t k, const RunOutcome& r) {
    files::write_text_atomically(stems[job_pair[k]] + ".md", r.report);
    fmt::print(stderr, "pair {}/{} done: {}\n", k + 1, jobs.size(), stems[job_pair[k]]);
  });
  if (code != 0 && code != 3) throw ExitRequest{code};
  for (std::size_t i = 0; i < pairs.size(); ++i)
    answers[i] = answer_of(results::load(stems[i] + ".h5", {}, results::LoadExtent::report), pairs[i].gap);
  files::write_text_atomically(t.output_stem + ".pairs.csv", pairs_csv(inv, pairs, answers, stems));
  if (inv.footprints) {
    files::write_text_atomically(t.output_stem + ".pairs.geojson", geo_pairs(inv, pairs, answers));
    files::write_text_atomically(t.output_stem + ".buildings.geojson", geo_buildings(inv, pairs, answers));
  }
  std::vector<std::size_t> order(pairs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) {  // unanswered (a shared wall in a fragility study) first: in contact
                     const double kx = answers[x].rank_key(), ky = answers[y].rank_key();
                     return std::isnan(kx) ? !std::isnan(ky) : kx > ky;
                   });
  std::string md = fmt::format("# {}\n\n{} buildings, {} adjacent pairs; each pair's study, results and "
                               "report in `{}/`.\n\n| rank | pair | kind | gap m | floors | P(pounding) at the gap | 95 % "
                               "interval | separation for 10 % m | worst level | its peak force kN (84th pct) | P over the hazard's years | "
                               "risk-targeted gap m |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                               md_text(t.title), inv.buildings.size(), pairs.size(), dir);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto& p = pairs[order[k]];
    const auto& a = answers[order[k]];
    const double sep10 = a.separation.empty() ? NAN : a.separation.front().second;
    const auto pct = [](double x) { return std::isnan(x) ? std::string("-") : fmt::format("{:.1f} %", 100 * x); };
    const auto m = [](double x) { return std::isnan(x) ? std::string("-") : fmt::format("{:.3f}", x); };
    md += fmt::format("| {} | {} – {} | {} | {:.3f} | {} | {} | [{}, {}] | {} | {} | {} | {} | {} |\n", k + 1,
                      md_cell(inv.buildings[p.a].id), md_cell(inv.buildings[p.b].id), to_string(p.kind), p.gap,
                      p.floors_aligned ? "aligned" : "floor to column", pct(a.p), pct(a.p_lo), pct(a.p_hi), m(sep10),
                      a.worst_level.empty() ? "-" : a.worst_level,
                      std::isnan(a.worst_level_force) ? std::string("-") : fmt::format("{:.0f}", a.worst_level_force / 1e3),
                      pct(a.p_years), m(a.risk_gap));
  }
  files::write_text_atomically(t.output_stem + ".md", md);
  files::write_text_atomically(t.output_stem + ".html", html_page(t.title, inv, pairs, answers, order));
  fmt::print("{}", md);
}

}  // namespace
}  // namespace pounding::cli
