// A study file parsed once into a validated, immutable Study.
#include "pounding/study/study.hpp"
#include "pounding/study/system_block.hpp"
#include "pounding/study/reductions.hpp"
#include "pounding/study/histories.hpp"

#include "pounding/sampling/bridge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "pounding/config/config.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/core/machine.hpp"

namespace pounding {

namespace fs = std::filesystem;

namespace {

using config::TableReader;

std::string resolve_relative(const std::string& study_path, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute()) return p;
  return (fs::path(study_path).parent_path() / p).lexically_normal().string();
}

}  // namespace

namespace {

// [records].files: strings or {path, scale} tables.
void parse_record_files(Study& s, TableReader& r, const std::string& path) {
  const toml::node* f = r.get("files");
  if (!f) return;
  auto a = f->as_array();
  if (!a) throw InputError("files must be an array", r.where("files"), "write files = [\"a.AT2\", {path = \"b.AT2\", scale = 1.5}]");
  for (auto& e : *a) {
    RecordFile rf;
    if (auto str = e.as_string()) {
      rf.path = str->get();
    } else if (auto tb = e.as_table()) {
      TableReader fr(tb, path, "records.files");
      rf.path = fr.string("path", "");
      rf.scale = fr.number("scale", 1.0);
      fr.finish("path, scale");
    } else {
      throw InputError("files entries must be strings or {path, scale} tables", r.where("files"), "fix the entry");
    }
    if (rf.path.empty()) throw InputError("a files entry has no path", r.where("files"), "give path = \"...\"");
    rf.path = resolve_relative(path, rf.path);
    s.files.push_back(rf);
  }
}

// soil = "D" or soil = ["A", "D"] (one class per support)
std::vector<std::string> read_soil(TableReader& m) {
  const toml::node* n = m.get("soil");
  if (!n) return {};
  if (n->is_string()) return {config::string(*n, "soil", m.where("soil"))};
  std::vector<std::string> out;
  if (const toml::array* a = n->as_array())
    for (const toml::node& e : *a) {
      if (!e.is_string()) break;
      out.push_back(e.value<std::string>().value());
    }
  if (out.empty() || out.size() != (n->is_array() ? n->as_array()->size() : 0))
    throw InputError(fmt::format("soil must be a site class or an array of them, not {}", config::type_name(*n)),
                     m.where("soil"), "write soil = \"D\" or soil = [\"A\", \"D\"] (one per support)");
  return out;
}

// The keys of [records.motions] into the motion layer's request (its checks name the key: OptionNames).
spatial::Request read_motion_request(TableReader& m, const std::string& path, std::uint64_t study_seed) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  constexpr long big = 1000000000;
  spatial::Request q;
  const auto num = [&](const char* key, double& x) { x = m.number(key, x, -inf, inf, "finite numbers"); };
  const auto whole = [&](const char* key, int& x) { x = static_cast<int>(m.integer(key, x, -big, big)); };
  whole("supports", q.supports), whole("match_points", q.match_points), whole("iterations", q.iterations);
  whole("realisations", q.realisations), whole("first", q.first);
  const std::pair<const char*, double*> numbers[] = {
      {"spacing", &q.spacing}, {"velocity", &q.velocity}, {"beta", &q.beta}, {"luco_wong_a", &q.luco_wong_a},
      {"hv_a", &q.hv_a}, {"hv_alpha", &q.hv_alpha}, {"hv_k", &q.hv_k}, {"hv_f0", &q.hv_f0}, {"hv_b", &q.hv_b},
      {"z", &q.z}, {"r", &q.r}, {"damping", &q.damping}, {"dt", &q.dt}, {"duration", &q.duration},
      {"rise", &q.rise}, {"strong", &q.strong}, {"decay", &q.decay}, {"f_min", &q.f_min}, {"f_max", &q.f_max},
      {"tolerance", &q.tolerance}};
  for (const auto& [key, x] : numbers) num(key, *x);
  q.positions = m.numbers("positions", {}, -inf, inf, "finite numbers");
  q.match_range = m.numbers("match_range", q.match_range, -inf, inf, "finite numbers");
  q.site_frequency = m.numbers("site_frequency", {}, -inf, inf, "finite numbers");
  q.site_damping = m.numbers("site_damping", {}, -inf, inf, "finite numbers");
  q.wave_passage = m.boolean("wave_passage", true);
  q.coherency = m.string("coherency", q.coherency);
  q.loss = m.string("loss", "");
  q.spectrum = m.string("spectrum", q.spectrum);
  q.spectrum_file = resolve_relative(path, m.string("spectrum_file", ""));
  q.soil = read_soil(m);
  const toml::node* seed = m.get("seed");
  q.seed = seed ? config::seed(*seed, "seed", m.where("seed")) : study_seed;
  for (const char* key : {"supports", "spacing", "positions", "velocity", "wave_passage", "coherency", "loss", "beta",
                          "luco_wong_a", "hv_a", "hv_alpha", "hv_k", "hv_f0", "hv_b", "site_frequency", "site_damping",
                          "spectrum", "soil", "z", "r", "spectrum_file", "damping", "dt", "duration",
                          "rise", "strong", "decay", "f_min", "f_max", "match_range", "match_points", "iterations",
                          "tolerance", "realisations", "first", "seed"})
    if (m.get(key)) q.given.insert(key);
  return q;
}

// [records.motions]: the study generates its records (StudyMotions); its supports feed a bridge's channels.
void parse_record_motions(Study& s, TableReader& r, const std::string& path) {
  const toml::table* t = r.table("motions");
  if (!t) return;
  TableReader m(t, path, "records.motions");
  const spatial::Request q = read_motion_request(m, path, s.seed);
  auto motions = std::make_shared<StudyMotions>();
  motions->uniform = m.boolean("uniform", false);
  m.finish("supports, spacing, positions, velocity, wave_passage, coherency, loss, beta, luco_wong_a, hv_a, hv_alpha, "
           "hv_k, hv_f0, hv_b, site_frequency, site_damping, spectrum, soil, "
           "z, r, spectrum_file, damping, dt, duration, rise, strong, decay, f_min, f_max, match_range, match_points, "
           "iterations, tolerance, realisations, first, seed, uniform");
  spatial::OptionNames names;
  names.where = [&m](std::string_view key) { return m.where(key); };
  motions->settings = spatial::settings_from(q, names);
  motions->first = static_cast<std::uint64_t>(q.first - 1);
  motions->count = static_cast<std::size_t>(q.realisations);
  motions->seed_given = q.has("seed");
  motions->where = r.where("motions");
  for (const char* key : {"supports", "units", "dt", "real_dir", "synthetic_only", "select"})
    if (r.get(key))
      throw InputError(fmt::format("[records] {} does not apply to generated motions ([records.motions])", key),
                       r.where(key), "delete it (the supports are [records.motions] supports or positions)");
  s.supports = static_cast<int>(motions->settings.positions.size());
  s.supports_where = motions->where;
  s.motions = std::move(motions);
}

void parse_records(Study& s, const toml::table* t, const std::string& path) {
  TableReader r(t, path, "records");
  s.suite = r.string("suite", "");
  if (s.suite != "builtin") s.suite = resolve_relative(path, s.suite);
  s.real_dir = resolve_relative(path, r.string("real_dir", ""));
  s.directory = resolve_relative(path, r.string("directory", ""));
  s.scale = r.number("scale", 1.0);
  s.units = r.choice("units", "g", parse_units);
  s.dt_one_column = r.number("dt", 0.0);
  s.record_limit = static_cast<int>(r.integer("limit", 0));
  s.synthetic_only = r.boolean("synthetic_only", false);
  if (r.get("select")) {
    s.select = static_cast<int>(r.integer("select", 0));
    s.select_where = r.where("select");
    if (s.record_limit > 0)
      throw InputError("limit and select both shorten the record list", r.where("limit"),
                       "delete limit: select = N already chooses N records (the best matches to [target_spectrum])");
  }
  if (r.get("max_per_event") || r.get("components")) {
    if (s.select == 0)
      throw InputError("max_per_event and components are rules of a selection", r.where(r.get("max_per_event") ? "max_per_event" : "components"),
                       "add select = N and a [target_spectrum], or delete the key");
    s.max_per_event = static_cast<std::size_t>(r.integer("max_per_event", static_cast<long>(default_max_per_event)));
    s.components = r.choice("components", "one", parse_component_rule);
  }
  if (r.get("polarity")) {
    s.polarity = r.choice("polarity", "recorded", parse_polarity);
    s.polarity_given = true;
  }
  parse_record_files(s, r, path);
  parse_record_motions(s, r, path);
  if (!s.motions && r.get("supports")) {
    s.supports = static_cast<int>(r.integer("supports", 0));
    s.supports_where = r.where("supports");
    if (s.directory.empty())
      throw InputError("supports groups a directory's files per realisation, and [records] names no directory",
                       r.where("supports"),
                       "give directory = \"...\" (pounding motions --out DIR writes rRRR_sJJ.AT2 per support), or delete supports");
    if (s.select > 0)
      throw InputError("select chooses single records, and supports groups them per realisation", r.where("select"),
                       "delete select (or supports)");
  }
  r.finish("suite, real_dir, directory, files, scale, units, dt, limit, synthetic_only, select, max_per_event, components, "
           "polarity, supports, motions");
  int sources = !s.suite.empty() + !s.directory.empty() + !s.files.empty() + (s.motions != nullptr);
  if (sources != 1)
    throw InputError(sources == 0 ? "the study names no records" : "the study names records in more than one way",
                     fmt::format("{} [records]", path), "give exactly one of suite, directory, files or [records.motions]");
}

void parse_gaps(Study& s, const toml::table* t, const std::string& path) {
  TableReader g(t, path, "gaps");
  const bool ratios = g.get("ratios") != nullptr, metres = g.get("metres") != nullptr;
  if (ratios && metres)
    throw InputError("[gaps] gives both ratios and metres", g.where("metres"),
                     "give one gap axis: ratios = [...] (ratios x of each model's code gap d) or metres = [...] (every "
                     "model's gap in metres)");
  s.gap_metres = metres;
  const char* key = metres ? "metres" : "ratios";
  s.gap_ratios = g.numbers(key, s.gap_ratios);
  if (s.gap_ratios.empty())
    throw InputError(fmt::format("[gaps] {} is empty", key), g.where(key), "give at least one gap");
  for (std::size_t i = 1; i < s.gap_ratios.size(); ++i)
    if (!(s.gap_ratios[i] > s.gap_ratios[i - 1]))
      throw InputError(fmt::format("gap {} must be strictly increasing ({:g} after {:g})", key, s.gap_ratios[i],
                                   s.gap_ratios[i - 1]),
                       g.where(key), "sort them and remove duplicates");
  // the curve on the axis' unit: ratios up to 1.5 d (or the largest ratio), metres up to 1.5 x the largest gap
  s.curve_max = g.number("curve_max", metres ? std::max(0.01, 1.5 * s.gap_ratios.back()) : std::max(1.5, s.gap_ratios.back()));
  s.curve_step = g.number("curve_step", 0.005);
  s.existing_gap = g.number("existing", NAN);
  g.finish("ratios, metres, curve_max, curve_step, existing");
}

// [contact] restitution: a preset's name, or a table {preset | polynomial | table, units, valid} (the options of
// collide/simulate --restitution-*, contact/restitution.hpp)
std::optional<contact::RestitutionCurve> read_restitution(TableReader& c, const std::string& path) {
  const toml::node* n = c.get("restitution");
  if (!n) return std::nullopt;
  const std::string forms = "give restitution = \"lindsay2011\" (a preset) or a table with one of preset = \"...\", "
                            "polynomial = [c0, c1, ...] (constant term first) or table = [[v1, e1], [v2, e2], ...]";
  contact::RestitutionCurve r;
  if (n->is_string()) {
    if (!contact::restitution_preset(n->value<std::string>().value(), r))
      throw InputError(fmt::format("unknown restitution preset '{}'", n->value<std::string>().value()),
                       c.where("restitution"), fmt::format("give one of: {}", contact::restitution_preset_names));
    return r;
  }
  const toml::table* t = c.table("restitution");
  TableReader q(t, path, "contact.restitution");
  const std::string preset = q.string("preset", "");
  const std::vector<double> poly = q.numbers("polynomial", {});
  const toml::node* tab = q.get("table");
  const toml::node* units = q.get("units");
  const toml::node* valid = q.get("valid");
  const std::vector<double> vv = q.numbers("valid", {});
  q.finish("preset, polynomial, table, units, valid");
  const int given = int(!preset.empty()) + int(!poly.empty()) + int(tab != nullptr);
  if (given != 1)
    throw InputError(given == 0 ? "[contact] restitution gives no curve" : "[contact] restitution gives more than one curve",
                     c.where("restitution"), forms);
  if (!preset.empty()) {
    if (!contact::restitution_preset(preset, r))
      throw InputError(fmt::format("unknown restitution preset '{}'", preset), q.where("preset"),
                       fmt::format("give one of: {}", contact::restitution_preset_names));
    if (units || valid)
      throw InputError("a preset carries its own units and valid range", q.where(units ? "units" : "valid"),
                       "remove the key, or give the preset's numbers as polynomial = [...]");
    return r;
  }
  r.units = q.string("units", "m/s");
  r.per_mps = contact::restitution_units_per_mps(r.units);
  if (!(r.per_mps > 0.0))
    throw InputError(fmt::format("unknown velocity units '{}'", r.units), q.where("units"), "write units = \"m/s\", \"cm/s\" or \"mm/s\"");
  if (!poly.empty()) {
    r.form = contact::RestitutionCurve::Form::polynomial, r.name = "polynomial", r.coefficients = poly;
  } else {
    r.form = contact::RestitutionCurve::Form::table, r.name = "table";
    const toml::array* a = tab->as_array();
    if (a)
      for (const toml::node& p : *a) {
        const toml::array* pe = p.as_array();
        if (!pe || pe->size() != 2 || !pe->get(0)->is_number() || !pe->get(1)->is_number()) {
          a = nullptr;
          break;
        }
        r.table_v.push_back(pe->get(0)->value<double>().value()), r.table_e.push_back(pe->get(1)->value<double>().value());
      }
    if (!a) throw InputError("the restitution table is not a list of points [v, e]", q.where("table"),
                             "write table = [[0.5, 0.9], [3.0, 0.7]] (v ascending, in the units; e in (0, 1])");
    if (!r.table_v.empty()) r.vmin = r.table_v.front(), r.vmax = r.table_v.back();
  }
  if (valid) {
    const std::vector<double>& v = vv;
    if (v.size() != 2 || !(v[0] >= 0.0 && v[0] < v[1]))
      throw InputError("valid is not [vmin, vmax] with 0 <= vmin < vmax", q.where("valid"), "give two velocities, e.g. valid = [0.99, 3.13]");
    r.vmin = v[0], r.vmax = v[1];
  }
  if (const std::string p = contact::restitution_problem(r); !p.empty())
    throw InputError(fmt::format("the restitution curve is not usable: {}", p), q.where(poly.empty() ? "table" : "polynomial"),
                     "correct it");
  return r;
}

void parse_contact(Study& s, const toml::table* t, const std::string& path) {
  TableReader c(t, path, "contact");
  s.contact.law = c.choice("law", "hertzdamp", parse_contact_law);
  s.contact.damping = c.choice("damping_law", "lankarani-nikravesh", parse_damping_law);
  if (!contact::traits(s.contact.law).has_force && !contact::traits(s.contact.law).impulsive)
    throw InputError("contact law 'none' cannot count impacts", c.where("law"), "choose a contact law (hertzdamp, kelvin, ...)");
  s.e = c.number("e", 0.65);
  if (c.get("e") && c.get("restitution"))
    throw InputError("[contact] e and restitution both given", c.where("e"), "remove e: the curve gives e(v0) at each impact");
  s.restitution = read_restitution(c, path);
  s.contact.n = c.number("n", 1.5);
  s.contact.v0_min = c.number("v0_min", 1e-3);
  s.contact_stiffness = c.number("stiffness", 0.0);
  if (contact::traits(s.contact.law).explicit_stiffness && !(s.contact_stiffness > 0))
    throw InputError(fmt::format("contact law '{}' needs a linear stiffness", to_string(s.contact.law)), c.where("stiffness"),
                     "add stiffness = <N/m> to [contact] (the sampled Hertz kh is in N/m^1.5)");
  s.contact_levels = c.choice("levels", "common", [](const std::string& name) {
    if (auto v = parse_enum(model::contact_levels_names, name)) return *v;
    throw InputError(fmt::format("unknown levels '{}'", name), "levels",
                     "write levels = " + enum_name_list(model::contact_levels_names, " or ", "\""));
  });
  s.gap_offsets = c.numbers("gap_offsets", {});
  s.joint_gap_offsets = c.numbers("joint_gap_offsets", {});
  s.level_tolerance = c.number("level_tolerance", 0.05);
  s.shape_functions = c.choice("shape_functions", "linear", [](const std::string& name) {
    if (auto v = parse_enum(model::shape_functions_names, name)) return *v;
    throw InputError(fmt::format("unknown shape_functions '{}'", name), "shape_functions",
                     "write shape_functions = " + enum_name_list(model::shape_functions_names, " or ", "\""));
  });
  c.finish("law, damping_law, e, n, v0_min, stiffness, levels, gap_offsets, joint_gap_offsets, level_tolerance, "
           "shape_functions, restitution");
}

}  // namespace

Polarity parse_polarity(std::string_view name) {
  for (const auto& [v, n] : polarity_names)
    if (n == name) return v;
  throw InputError(fmt::format("unknown polarity '{}'", name), "polarity",
                   "use \"both\" (every record applied with both signs, as two analyses of the same record) or "
                   "\"recorded\" (the sign as recorded only)");
}

CoarsePolicy parse_coarse_policy(std::string_view name) {
  for (const auto& [v, n] : coarse_policy_names)
    if (n == name) return v;
  throw InputError(fmt::format("unknown coarse policy '{}'", name), "coarse",
                   "use \"refine\" (default: coarse analyses run again at a shorter step, excluded if still coarse), "
                   "\"exclude\" (left out of the statistics like diverged ones) or \"keep\" (kept in the statistics, "
                   "still counted and reported)");
}

namespace {

void parse_analysis(Study& s, const toml::table* t, const std::string& path) {
  TableReader a(t, path, "analysis");
  s.stepper = a.choice("stepper", "central-difference", parse_stepper);
  s.step_given = a.get("substeps") != nullptr || a.get("max_dt") != nullptr;
  s.substeps = static_cast<int>(a.integer("substeps", 1));
  s.max_dt = a.number("max_dt", -1.0);
  s.batch = static_cast<int>(a.integer("batch", 0));  // 0: the scene's default, set by choose_scene
  s.threads = static_cast<int>(a.integer("threads", 0));
  s.free_vibration = a.number("free_vibration", 0.0);
  s.displacement_limit = a.number("displacement_limit", 10.0);
  s.skip_untouched = a.boolean("skip_untouched", true);
  s.scale_elastic = a.boolean("scale_elastic", true);
  s.max_excluded_fraction = a.number("max_excluded_fraction", 0.001);
  // a step the user gave is the step of every analysis (as simulate --dt): refine only where the engine chose it
  s.coarse = a.choice("coarse", s.step_given ? "exclude" : "refine", parse_coarse_policy);
  a.finish("stepper, substeps, max_dt, batch, threads, free_vibration, displacement_limit, skip_untouched, scale_elastic, "
           "max_excluded_fraction, coarse");
}

void parse_report(Study& s, const toml::table* t, const std::string& path) {
  TableReader r(t, path, "report");
  s.targets = r.numbers("targets", s.targets);
  for (const char* key : {"h1", "h2"})
    if (r.get(key))
      throw InputError(fmt::format("[report] {} is no longer a setting: separations in metres come from the buildings' "
                                   "own heights, never from assumed ones", key),
                       r.where(key),
                       "delete it; for a pair of given buildings set [structures.building1] height = <m> and "
                       "[structures.building2] height = <m> (a study with heights from the period-height rule "
                       "reports gaps as ratios of the code gap d)");
  s.confidence = r.number("confidence", 0.95);
  s.bootstrap = static_cast<int>(r.integer("bootstrap", 2000));
  s.compare_with = r.string("compare_with", "");
  if (!s.compare_with.empty() && s.compare_with != "stochastic-pounding")
    throw InputError(fmt::format("compare_with = \"{}\" is not a published study the report knows", s.compare_with),
                     r.where("compare_with"), "write compare_with = \"stochastic-pounding\" or leave it out");
  s.html = r.boolean("html", false);
  // on the gap axis' unit: ratios 0.1 to 1.0 d; metres 0.1 x to 1 x the largest gap
  s.fit_min = r.number("fit_min", s.gap_metres ? 0.1 * s.gap_ratios.back() : 0.1);
  s.fit_max = r.number("fit_max", s.gap_metres ? s.gap_ratios.back() : 1.0);
  if (!(s.fit_max > s.fit_min)) throw InputError("fit_max must exceed fit_min", r.where("fit_max"), "give fit_min < fit_max");
  r.finish("targets, fit_min, fit_max, confidence, bootstrap, compare_with, html");
}

// One entry of [outputs] histories (study/histories.hpp): { worst = N (, gap) } or { record, model | pair + sample,
// gap }. The entries are checked against the records and models later (resolve_histories, check_histories).
HistorySpec parse_history(const toml::table& t, const std::string& path, std::size_t k) {
  TableReader r(&t, path, fmt::format("outputs.histories {}", k + 1), "outputs.histories");
  HistorySpec h;
  h.where = config::location(path, t.source()) + fmt::format(" [outputs] histories entry {}", k + 1);
  h.worst = static_cast<int>(r.integer("worst", 0));
  if (const toml::node* n = r.get("record")) {
    if (n->is_string()) h.record_name = n->value_or(std::string());
    else h.record_index = config::integer(*n, "record", r.where("record"));
    if (h.record_name.empty() && h.record_index < 0)
      throw InputError("record must be a record's id (as in /records/id) or its row (0, 1, ...)", r.where("record"),
                       "write record = \"EQ3\" or record = 2");
  }
  h.model = r.integer("model", -1);
  if (const toml::node* n = r.get("pair")) {
    const std::vector<double> v = config::numbers(*n, "pair", r.where("pair"));
    if (v.size() != 2 || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]) || v[0] < 0 || v[1] < 0)
      throw InputError("pair must be two period indices [i1, i2] (/models/i1, i2)", r.where("pair"),
                       "write pair = [0, 3] with sample = k, or model = <row of /models>");
    h.i1 = static_cast<long>(v[0]), h.i2 = static_cast<long>(v[1]);
  }
  h.sample = r.integer("sample", -1);
  if (const toml::node* n = r.get("gap")) {
    h.gap_given = true;
    if (n->is_string()) {
      if (n->value_or(std::string()) != "uncoupled")
        throw InputError(fmt::format("gap = \"{}\" is not a choice", n->value_or(std::string())), r.where("gap"),
                         "write gap = \"uncoupled\" or one of the study's [gaps] ratios");
    } else {
      h.uncoupled = false, h.gap_ratio = config::number(*n, "gap", r.where("gap"));
    }
  }
  r.finish("record, model, pair, sample, gap, worst");
  return h;
}

// An entry as it reads (its /settings text): { record = "EQ2", model = 5, gap = 0.1 }.
std::string history_text(const HistorySpec& h) {
  std::vector<std::string> k;
  if (h.worst > 0) k.push_back(fmt::format("worst = {}", h.worst));
  if (!h.record_name.empty()) k.push_back(fmt::format("record = \"{}\"", h.record_name));
  else if (h.record_index >= 0) k.push_back(fmt::format("record = {}", h.record_index));
  if (h.model >= 0) k.push_back(fmt::format("model = {}", h.model));
  if (h.i1 >= 0) k.push_back(fmt::format("pair = [{}, {}]", h.i1, h.i2));
  if (h.sample >= 0) k.push_back(fmt::format("sample = {}", h.sample));
  if (h.gap_given) k.push_back(h.uncoupled ? std::string("gap = \"uncoupled\"") : fmt::format("gap = {}", h.gap_ratio));
  return fmt::format("{{ {} }}", fmt::join(k, ", "));
}

// [outputs] histories: one entry (an inline table) or an array of them.
void parse_histories(Study& s, TableReader& o, const std::string& path) {
  const toml::node* n = o.get("histories");
  if (n == nullptr) return;
  std::vector<const toml::table*> entries;
  if (const toml::table* t = n->as_table()) entries.push_back(t);
  else if (const toml::array* a = n->as_array(); a && !a->empty() && a->is_array_of_tables())
    for (const toml::node& x : *a) entries.push_back(x.as_table());
  else
    throw InputError("histories must be an entry { ... } or an array of entries", o.where("histories"),
                     "write histories = [{ record = \"EQ1\", model = 0, gap = \"uncoupled\" }, { worst = 3 }]");
  std::vector<std::string> text;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    s.histories.push_back(parse_history(*entries[k], path, k));
    text.push_back(history_text(s.histories.back()));
  }
  s.histories_text = fmt::format("[{}]", fmt::join(text, ", "));
}

void parse_outputs(Study& s, const toml::table* t, const std::string& path) {
  TableReader o(t, path, "outputs");
  s.want_forces = o.boolean("forces", true);
  s.want_amplification = o.boolean("amplification", true);
  // per_model = "stream": every model's peaks, written to the results file from the checkpoint in bounded memory
  if (const toml::node* n = o.get("per_model"); n && n->is_string()) {
    if (n->value_or(std::string()) != "stream")
      throw InputError(fmt::format("per_model = \"{}\" is not a choice", n->value_or(std::string())), o.where("per_model"),
                       "write per_model = true, false or \"stream\"");
    s.per_model = true, s.stream = true;
  } else {
    s.per_model = o.boolean("per_model", true);
  }
  s.per_model_where = o.where("per_model");
  parse_histories(s, o, path);
  o.finish("forces, amplification, per_model, histories");
}

// [outputs] per_model = false keeps only the reductions of the probability scene of an SDOF pair (study/reductions.hpp);
// what else would need per-model values it does not keep is refused before any work.
void check_per_model(const Study& s) {
  if (s.per_model && !s.stream) return;
  const char* what = s.stream ? "[outputs] per_model = \"stream\" makes the run's report from the reductions, which "
                                "cover only the probability scene of an SDOF pair,"
                              : "[outputs] per_model = false keeps only the reductions of the probability scene of an "
                                "SDOF pair,";
  const char* why = s.scene == Scene::impacts ? "the impacts scene's forces and amplification are per model and gap"
                    : s.intensity.enabled     ? "a fragility study fits each model's stripes and IDA curves"
                    : runs_systems(s.structures)
                        ? "shear buildings, rows and bridges keep per-floor and per-element peaks (their reductions are "
                          "not written yet)"
                    : s.html ? "the HTML report's figures (tools/pounding_plots.py) read per-model peaks"
                        : nullptr;
  if (why)
    throw InputError(fmt::format("{} and {}", what, why), s.per_model_where,
                     "write scene = \"probability\" for an SDOF pair or grid study without [intensity] or [report] "
                     "html, or delete per_model (per-model outputs in memory)");
}

// The scene actually run (auto resolved from [outputs]), why, and the scene's default step cap (docs/accuracy.md):
// the coupled runs need h <= 2.5 ms for 1 % peak forces; the at-least-one-impact probability of the full paper study
// moves by at most 0.02 percentage points between the record step (10 ms) and 2.5 ms, so the probability scene
// integrates at the record step. The scene's default batch too (default_batch: shorter units for the impacts scene's
// long ones, so 1,000 ranks find work).
void choose_scene(Study& s) {
  const bool max_dt_given = s.max_dt >= 0.0;
  s.scene = s.scene_requested;
  if (s.scene_requested == Scene::automatic) {
    if (s.want_forces || s.want_amplification) {
      s.scene = Scene::impacts;
      s.scene_reason = "auto: [outputs] asks for impact forces/amplification, which need the coupled contact runs";
    } else {
      s.scene = Scene::probability;
      s.scene_reason = "auto: only the at-least-one-impact probability is asked for; it depends only on the "
                       "uncoupled motion before the first contact, so one uncoupled run per model answers every gap";
    }
  } else if (s.scene == Scene::probability) {
    s.scene_reason = "probability scene: whether a pair touches at gap g depends only on the motion before the first "
                     "contact, i.e. the uncoupled motion; one uncoupled run per model and record answers every gap";
  } else {
    s.scene_reason = std::string("impacts scene: one uncoupled run per model, then coupled contact runs at every ") +
                     (s.gap_metres ? "gap" : "gap ratio");
  }
  if (!max_dt_given) s.max_dt = s.scene == Scene::impacts ? 0.0025 : 0.0;
  if (s.batch == 0) s.batch = default_batch(s.scene);
}

// [records] select and [target_spectrum] come together.
void check_selection(const Study& s, const TableReader& top) {
  if (s.select > 0 && !s.target.enabled)
    throw InputError("[records] select = N chooses records to a design spectrum, but the study has no [target_spectrum]",
                     s.select_where,
                     "add [target_spectrum] with code = \"ASCE 7-16\" (sds, sd1, tl), \"EC8\" (type, ground, agr), "
                     "\"Standard 2800\" (a, soil) or \"csv\" (file), or delete select");
  if (s.target.enabled && s.select == 0)
    throw InputError("[target_spectrum] is given but [records] has no select = N", top.where("target_spectrum"),
                     "add select = N to [records] (N records are chosen from the library and scaled to the spectrum; "
                     "ASCE 7-16 asks for at least 11), or delete [target_spectrum]");
}

}  // namespace

static std::string_view bearing_name(physics::Bearing b) {
  for (const auto& n : bearing_names)
    if (n.value == b) return n.name;
  return "smooth";
}

// Studies of systems (shear buildings, rows) run with central difference, Newmark or RK4 (physics::run_system;
// Newmark and RK4: physics/system_lane_stepper.hpp, bilinear springs only); Nigam-Jennings integrates SDOF bodies only
// (docs/architecture.md D7). Refused here, before any work, with the key's line.
static void check_system_stepper(const Study& s, TableReader& top, const std::string& path, const std::string& what,
                                 const std::string& other_fix) {
  if (s.stepper == Stepper::central_difference) return;
  const toml::table* a = top.table("analysis");
  const toml::node* n = a ? a->get("stepper") : nullptr;
  const std::string where =
      n ? fmt::format("{}:{} [analysis].stepper", path, n->source().begin.line) : path + " [analysis].stepper";
  if (s.stepper == Stepper::nigam_jennings)
    throw InputError(fmt::format("nigam-jennings integrates SDOF bodies only (the pair), and the study has {}", what),
                     where, "write stepper = \"central-difference\", \"newmark\" or \"rk4\", " + other_fix);
  for (std::size_t b = 0; b < s.structures.building_count(); ++b)
    if (const BuildingModel m = s.structures.row_building(b);
        m.isolated && !model::runs_on_lane_stepper(physics::isolator_law(m.isolation.bearing)))
      throw InputError(fmt::format("the {} stepper runs systems of bilinear springs (storeys, linear and lead-rubber "
                                   "bearings), and building {} has a {} bearing", to_string(s.stepper), b + 1,
                                   bearing_name(m.isolation.bearing)),
                       where, "write stepper = \"central-difference\", or bearing = \"lead-rubber\"");
}

// A study with a shear building (model = "shear") runs the system steppers: central difference, Newmark or RK4
// (check_system_stepper), force laws only (a contact at every common floor). [intensity] runs (stripes, IDA:
// study/run.cpp, the Systems' scaling by the model trait SystemBlock::scales_linearly).
static void check_row_study(const Study& s, config::TableReader& top, const toml::table* structures, const std::string& path);

// [contact] level_tolerance below half the smallest storey height of the shear buildings (an SDOF of a row of SDOFs:
// its 3.2 m floor), so that a floor meets at most one floor of its neighbour (the floors within the tolerance of it).
static void check_level_tolerance(const Study& s, config::TableReader& top, const std::string& path) {
  if (!s.structures.any_shear() && !s.structures.row()) return;
  double h = INFINITY;
  for (std::size_t b = 0; b < s.structures.building_count(); ++b) {
    const BuildingModel x = s.structures.row_building(b);
    if (x.shear() || s.structures.row()) h = std::min(h, x.shear() ? x.storey_height() : 3.2);
    for (double y : x.storey_heights) h = std::min(h, y);  // storeys of different heights: the lowest
  }
  if (s.level_tolerance < 0.5 * h) return;
  const toml::table* c = top.table("contact");
  const toml::node* n = c ? c->get("level_tolerance") : nullptr;
  throw InputError(fmt::format("[contact] level_tolerance = {:g} m is not below half the smallest storey height ({:g} m): a "
                               "floor could meet two floors of its neighbour",
                               s.level_tolerance, h),
                   n ? fmt::format("{}:{} [contact].level_tolerance", path, n->source().begin.line)
                     : path + " [contact].level_tolerance",
                   fmt::format("give level_tolerance < {:g} m (default 0.05 m)", 0.5 * h));
}

// [contact] joint_gap_offsets: a row's, one value per joint (a pair's one joint takes the gap ratios; a bridge's
// joints their own gaps)
static void check_joint_offsets(const Study& s, config::TableReader& top, const std::string& path) {
  const toml::table* c = top.table("contact");
  const toml::node* n = c ? c->get("joint_gap_offsets") : nullptr;
  if (!n) return;
  const std::string where = fmt::format("{}:{} [contact].joint_gap_offsets", path, n->source().begin.line);
  const std::size_t joints = s.structures.building_count() - 1;
  if (!s.structures.row())
    throw InputError("[contact] joint_gap_offsets is given, and the study is a pair (one joint: its gap is the ratio "
                     "x d)", where, "give buildings = 3 or more for a row, or remove the key (use [gaps] ratios)");
  if (s.joint_gap_offsets.size() != joints)
    throw InputError(fmt::format("[contact] joint_gap_offsets has {} values, and the row of {} buildings has {} joints",
                                 s.joint_gap_offsets.size(), joints + 1, joints),
                     where, fmt::format("give one offset (m) per joint, left to right: {} values", joints));
}

static void check_shear_study(const Study& s, config::TableReader& top, const toml::table* structures, const std::string& path) {
  check_row_study(s, top, structures, path);
  // [contact] levels / gap_offsets act on the floors of shear buildings and the joints of a row
  if (!s.structures.any_shear() && !s.structures.row())
    for (const char* key : {"gap_offsets", "levels", "level_tolerance", "shape_functions"}) {
      const toml::table* c = top.table("contact");
      const toml::node* n = c ? c->get(key) : nullptr;
      if (!n) continue;
      throw InputError(fmt::format("[contact] {} is given, and the study is a pair of SDOF buildings (one contact at "
                                   "one level)",
                                   key),
                       fmt::format("{}:{} [contact].{}", path, n->source().begin.line, key),
                       "give the buildings storeys (model = \"shear\") or a row (buildings = 3 or more), or remove the key");
    }
  check_level_tolerance(s, top, path);
  check_joint_offsets(s, top, path);
  if (!s.structures.any_shear()) return;
  check_system_stepper(s, top, path, "a shear building", "or use model = \"sdof\"");
  if (s.contact.law == ContactLaw::stereomechanical) {
    const toml::table* c = top.table("contact");
    const toml::node* n = c ? c->get("law") : nullptr;
    throw InputError("the stereomechanical law runs one contact element (the SDOF pair), and the study has a shear "
                     "building (a contact at every common floor)",
                     n ? fmt::format("{}:{} [contact].law", path, n->source().begin.line) : path + " [contact].law",
                     "choose a force law (hertzdamp, kelvin, ...), or use model = \"sdof\"");
  }
}

// A row of n >= 3 buildings ([structures] buildings) runs the system stepper too, SDOF or shear: central difference,
// a force law (several contact elements). [intensity] runs (stripes and IDA through SystemBlock, as for shear pairs).
static void check_row_study(const Study& s, config::TableReader& top, const toml::table* structures, const std::string& path) {
  (void)structures;  // (its buildings key located the [intensity] refusal, gone: rows run fragility studies)
  if (!s.structures.row()) return;
  const std::size_t n = s.structures.building_count();
  auto at = [&](const char* table, const char* key) {
    const toml::table* t = top.table(table);
    const toml::node* k = t ? t->get(key) : nullptr;
    return k ? fmt::format("{}:{} [{}].{}", path, k->source().begin.line, table, key)
             : fmt::format("{} [{}].{}", path, table, key);
  };
  check_system_stepper(s, top, path, fmt::format("a row of {} buildings", n), "or buildings = 2");
  if (s.contact.law == ContactLaw::stereomechanical)
    throw InputError(fmt::format("the stereomechanical law runs one contact element (the SDOF pair), and a row of {} "
                                 "buildings has a contact at every joint",
                                 n),
                     at("contact", "law"), "choose a force law (hertzdamp, kelvin, ...), or buildings = 2");
}

// [contact] restitution (e(v0)) runs where central difference reads it at each impact's onset (physics::
// HertzdampRestitution; the pair kernel and the system stepper): the coupled runs of the impacts scene with Hertzdamp,
// for SDOF pairs, shear buildings, rows and bridges (every study-gap element); elsewhere it would do nothing. A moat's
// walls (their own e) would take the curve too: refused.
static void check_restitution(const Study& s, TableReader& top, const std::string& path) {
  if (!s.restitution) return;
  const toml::table* c = top.table("contact");
  const toml::node* n = c ? c->get("restitution") : nullptr;
  const std::string where = n ? fmt::format("{}:{} [contact].restitution", path, n->source().begin.line) : path + " [contact].restitution";
  const char* fix = "remove restitution (and give e), or run with law = \"hertzdamp\", stepper = "
                    "\"central-difference\" in the impacts scene";
  if (s.contact.law != ContactLaw::hertzdamp)
    throw InputError(fmt::format("a velocity-dependent restitution runs with law = \"hertzdamp\", and the law is \"{}\"",
                                 to_string(s.contact.law)), where, fix);
  if (s.stepper != Stepper::central_difference)
    throw InputError(fmt::format("a velocity-dependent restitution runs with the central-difference stepper, and the "
                                 "stepper is \"{}\"", to_string(s.stepper)), where, fix);
  for (std::size_t b = 0; !s.structures.bridge && b < s.structures.building_count(); ++b)
    if (const BuildingModel m = s.structures.row_building(b); m.isolated && m.moat)
      throw InputError(fmt::format("a velocity-dependent restitution acts at every contact of the system, and building "
                                   "{} has a moat (its walls have their own restitution)", b + 1),
                       where, "remove restitution (and give e), or remove the moat");
  if (s.scene != Scene::impacts)
    throw InputError(fmt::format("a velocity-dependent restitution acts in the coupled runs of the impacts scene, and "
                                 "the scene is \"{}\" (no coupled run: whether a pair touches is decided by the "
                                 "uncoupled motion)", to_string(s.scene)), where, fix);
}

// A bridge study ([bridge], sampling/bridge.hpp): the frames come from [bridge], not [structures]; the structure
// model only numbers the samples (one period slot each, [bridge] samples per record). The system stepper runs it:
// central difference and a force law at the joints, no [intensity], no [contact] levels / gap_offsets (the joints
// are the contact elements; their own gaps give the offsets).
static void parse_bridge(Study& s, TableReader& top, const toml::table* bridge, const toml::table* structures,
                         const std::string& path) {
  if (structures)
    throw InputError("a bridge study takes its frames from [bridge], and the study also has [structures]",
                     top.where("structures"), "remove [structures] (frames, periods and masses are [[bridge.frame]] keys)");
  std::int64_t samples = 1;
  auto model = std::make_shared<BridgeModel>(
      parse_bridge_model(bridge, path, s.contact_stiffness > 0 ? s.contact_stiffness : NAN, s.e, &samples,
                         s.restitution ? "[contact] restitution" : ""));
  toml::table t;
  t.insert("periods", toml::array{1.0});
  t.insert("samples_per_pair", samples);
  s.structures = parse_structure_model(t, path);
  s.structures.bridge = std::move(model);
  auto at = [&](const char* table, const char* key) {
    const toml::table* x = top.table(table);
    const toml::node* k = x ? x->get(key) : nullptr;
    return k ? fmt::format("{}:{} [{}].{}", path, k->source().begin.line, table, key) : fmt::format("{} [{}].{}", path, table, key);
  };
  if (s.stepper != Stepper::central_difference)
    throw InputError(fmt::format("the {} stepper runs SDOF pairs, shear buildings and rows, and the study is a bridge "
                                 "(its links' gap laws and support channels run with central difference only)",
                                 to_string(s.stepper)),
                     at("analysis", "stepper"), "write stepper = \"central-difference\" (the system stepper)");
  if (s.contact.law == ContactLaw::stereomechanical)
    throw InputError("the stereomechanical law runs one contact element (the SDOF pair), and a bridge has a contact at "
                     "every joint",
                     at("contact", "law"), "choose a force law (hertzdamp, kelvin, ...)");
  if (s.intensity.enabled)
    throw InputError("a fragility study ([intensity]: stripes, IDA) runs a pair of buildings, and the study is a bridge",
                     top.where("intensity"), "remove [intensity] to run the bridge in the probability or impacts scene");
  for (const char* key : {"gap_offsets", "levels", "joint_gap_offsets"}) {
    const toml::table* c = top.table("contact");
    if (c && c->get(key))
      throw InputError(fmt::format("[contact] {} is given, and the study is a bridge (its joints are the contacts)", key),
                       at("contact", key), "give each [[bridge.joint]] its own gap instead, or remove the key");
  }
  const int channels = s.structures.bridge->spec.channels();
  if (channels > std::max(1, s.supports))
    throw InputError(fmt::format("the bridge stands on {} supports (its largest support = {}), and the records give {}",
                                 channels, channels, std::max(1, s.supports)),
                     s.supports > 0 ? s.supports_where : fmt::format("{} [records].supports", path),
                     s.motions ? fmt::format("give [records.motions] supports = {} (or {} positions), or put every "
                                             "frame on support 1", channels, channels)
                               : fmt::format("give [records] supports = {} and a directory of support motions (pounding "
                                             "motions --supports {} --out DIR), or put every frame on support 1",
                                             channels, channels));
}

Study parse_study(const std::string& text, const std::string& path) {
  Study s;
  s.path = path;
  s.text = text;
  const toml::table root = config::parse(text, path, "fix the study file's syntax");
  TableReader top(&root, path, "");
  s.title = top.string("title", fs::path(path).stem().string());
  top.get("seed");
  s.seed = parse_study_seed(root, path);
  s.scene_requested = top.choice("scene", "probability", [](const std::string& name) {
    if (auto scene = parse_enum(scene_names, name)) return *scene;
    throw InputError(fmt::format("unknown scene '{}'", name), "scene", "use " + enum_name_list(scene_names, " or ", "\""));
  });
  s.output = top.string("output", fs::path(path).stem().string() + ".h5");
  if (s.output.empty()) throw InputError("output is empty", top.where("output"), "give a results file name");

  parse_records(s, top.table("records"), path);
  const toml::table* structures = top.table("structures");
  const toml::table empty;  // a named table, not `t ? *t : toml::table{}`: that copies *t and loses its lines
  s.structures = parse_structure_model(structures ? *structures : empty, path);
  parse_gaps(s, top.table("gaps"), path);
  parse_contact(s, top.table("contact"), path);
  parse_analysis(s, top.table("analysis"), path);
  parse_report(s, top.table("report"), path);
  parse_outputs(s, top.table("outputs"), path);
  s.intensity = parse_intensity(top.table("intensity"), path, s.structures);
  s.hazard = parse_hazard(top.table("hazard"), path, s.intensity);
  s.target = parse_target_spectrum(top.table("target_spectrum"), path, s.structures);
  if (const toml::table* bridge = top.table("bridge")) parse_bridge(s, top, bridge, structures, path);
  top.finish("title, seed, scene, output, records, structures, gaps, contact, analysis, report, outputs, intensity, "
             "hazard, target_spectrum, bridge");
  check_selection(s, top);
  // a ground motion's sign is arbitrary: a pair study (one pair, answers in metres) takes both by default
  if (!s.polarity_given) s.polarity = s.structures.heights_specified() ? Polarity::both : Polarity::recorded;
  // ida: linear pairs take every capacity exactly from one run; yielding ones need the bisection (study/run.cpp)
  s.intensity.bisection =
      s.intensity.method == FragilityMethod::ida &&
      !(s.structures.building(0).hysteresis == Hysteresis::elastic && s.structures.building(1).hysteresis == Hysteresis::elastic);
  if (!s.structures.bridge) check_shear_study(s, top, structures, path);
  if (s.motions && !s.structures.bridge)
    throw InputError("[records.motions] generates a bridge's support motions, and the study has no [bridge]",
                     s.motions->where, "add a [bridge] whose frames name their support, or name records another way");
  if (s.supports > 0 && !s.structures.bridge)
    throw InputError("[records] supports feeds a bridge's supports, and the study has no [bridge]", s.supports_where,
                     "add a [bridge] whose frames name their support, or delete supports");
  if (s.intensity.enabled && s.scene_requested != Scene::probability)
    throw InputError("a fragility study ([intensity]) runs in the probability scene", top.where("scene"),
                     "write scene = \"probability\": whether a pair touches at a gap is decided by the uncoupled motion");

  choose_scene(s);
  check_per_model(s);
  check_histories(s);
  check_restitution(s, top, path);
  // the results must fit in memory; the suite's record count is not known yet, so count at least one record
  check_result_memory(s, s.select > 0 ? static_cast<std::size_t>(s.select)
                                      : std::max<std::size_t>({std::size_t{1}, s.files.size(),
                                                               static_cast<std::size_t>(std::max(0, s.record_limit))}));
  if (s.intensity.stripes())
    s.scene_reason += s.scale_elastic
                          ? "; at each stripe above the lowest, a model whose buildings stayed elastic at the lowest "
                            "stripe and stay within yield at this one takes the lowest stripe's peaks times the ratio of "
                            "the scale factors (an elastic response scales exactly with the record) instead of a run"
                          : "; every model is analysed at every stripe (scale_elastic = false)";
  if (s.scene == Scene::impacts)
    s.scene_reason += s.skip_untouched
                          ? "; pairs whose uncoupled peak closing stays below a gap never touch there and are not rerun "
                            "with contact (their coupled run would be bit-identical to the uncoupled one)"
                          : "; every pair is rerun with contact at every gap (skip_untouched = false)";
  return s;
}

double result_bytes(const Study& s, std::size_t records) {
  if (!s.per_model || s.stream) {  // the reductions; "stream": and where each unit lies in the checkpoint (16 bytes)
    const std::size_t rows = records * static_cast<std::size_t>(polarity_count(s.polarity));
    const double units = s.stream ? static_cast<double>(rows) * static_cast<double>(s.structures.period_pair_count()) *
                                        std::ceil(static_cast<double>(s.structures.samples_per_pair) / std::max(1, s.batch))
                                  : 0.0;
    return reduction_bytes(rows, static_cast<std::size_t>(s.structures.period_pair_count()), s.gap_ratios.size(),
                           static_cast<std::size_t>(std::floor(s.curve_max / s.curve_step + 1e-9))) +
           16.0 * units;
  }
  const double per_gap = 45.0 + (s.coarse == CoarsePolicy::refine ? 4.0 : 0.0);  // refine: impacts/substeps
  const double per_model = 25.0 + (s.scene == Scene::impacts ? per_gap * static_cast<double>(s.gap_ratios.size()) : 0.0);
  return static_cast<double>(records) * polarity_count(s.polarity) *
         static_cast<double>(std::max<std::size_t>(1, s.intensity.stripes())) * static_cast<double>(s.structures.period_pair_count()) *
         static_cast<double>(s.structures.samples_per_pair) * per_model;
}

int ranks_on_this_node() {
  for (const char* v : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "MPI_LOCAL_NRANKS", "PMI_LOCAL_SIZE"})
    if (const char* s = std::getenv(v); s && std::atoi(s) > 0) return std::atoi(s);
  return 1;
}

// [outputs] per_model = "stream": rank 0's peak (docs/studies.md, "Studies larger than memory"): the reductions and
// the unit index (`need`), each model's code gap (8 bytes), the write's chunks with their shuffled and deflated copies
// (at most 512 MiB of them and the window's deflated chunks, or 4 copies of one record row of 8 M bytes when that is
// more: h5::write_dataset with a Fill), the models' window (64 MiB) and the base.
double stream_peak_bytes(const Study& s, double need) {
  const double M = static_cast<double>(s.structures.period_pair_count()) * static_cast<double>(s.structures.samples_per_pair);
  constexpr double MiB = 1024.0 * 1024;
  return need + 8.0 * M + std::max(640.0 * MiB, 4.0 * 8.0 * M) + 64.0 * MiB + rank_base_bytes;
}

void check_result_memory(const Study& s, std::size_t records) {
  const double need = result_bytes(s, records);
  const double avail = available_memory_bytes();
  const int local = ranks_on_this_node();
  // rank 0's peak: the gathered arrays, the results built from them, the HDF5 image and its copy written out
  // per_model = false builds no models' table (its reductions hold the period grids only)
  const double models = s.per_model && !s.stream ? static_cast<double>(s.structures.period_pair_count()) *
                                                       static_cast<double>(s.structures.samples_per_pair)
                                                 : 0.0;
  const double peak = s.stream ? stream_peak_bytes(s, need) : need * result_peak_factor + models * model_peak_bytes + rank_base_bytes;
  const double share = avail - static_cast<double>(local - 1) * rank_base_bytes;  // the other ranks' part
  const bool over_machine = std::isfinite(avail) && peak > share;
  if (need <= max_result_bytes && !over_machine) return;
  // where samples_per_pair is (or would be) written
  std::string where = fmt::format("{} [structures].samples_per_pair", s.path);
  try {
    const toml::table root = toml::parse(s.text, s.path);
    if (const toml::node* n = root.at_path("structures.samples_per_pair").node())
      where = fmt::format("{}:{} [structures].samples_per_pair", s.path, n->source().begin.line);
    else
      where += fmt::format(" (default {})", s.structures.samples_per_pair);
  } catch (const toml::parse_error&) {
  }
  const double stripes = static_cast<double>(std::max<std::size_t>(1, s.intensity.stripes()));
  const double per_model = need / (static_cast<double>(records) * stripes *
                                   static_cast<double>(s.structures.period_pair_count()) *
                                   static_cast<double>(s.structures.samples_per_pair));
  const double per_sample = need / static_cast<double>(s.structures.samples_per_pair);
  const std::string sizes = fmt::format("{} record{} x {}{} period pairs x {} samples x {} bytes per model", records,
                                        records == 1 ? "" : "s",
                                        stripes > 1 ? fmt::format("{:.0f} stripes x ", stripes) : std::string(),
                                        s.structures.period_pair_count(), s.structures.samples_per_pair, per_model);
  if (need > max_result_bytes) {
    const double fits = std::floor(max_result_bytes / per_sample);
    throw InputError(fmt::format("samples_per_pair = {} needs {} of result arrays ({}), more than the {} limit",
                                 s.structures.samples_per_pair, human_bytes(need), sizes, human_bytes(max_result_bytes)),
                     where,
                     fits >= 1 ? fmt::format("give samples_per_pair <= {:.0f} (the paper uses 256), or split the study, or "
                                             "keep only the reductions ([outputs] per_model = false), or write every "
                                             "model's peaks in bounded memory ([outputs] per_model = \"stream\")", fits)
                               : std::string("split the study into fewer records, period pairs or gaps"));
  }
  const double per_sample_peak = per_sample * result_peak_factor +
                                 static_cast<double>(s.structures.period_pair_count()) * model_peak_bytes;
  const double fits = std::floor((share - rank_base_bytes) / per_sample_peak);
  throw InputError(
      fmt::format("samples_per_pair = {} needs {} of result arrays ({}); with the models' table and the copies made while "
                  "the results are written rank 0 needs about {}, more than the {} of memory available on this machine{}",
                  s.structures.samples_per_pair, human_bytes(need), sizes, human_bytes(peak),
                  human_bytes(share),
                  local > 1 ? fmt::format(" for rank 0 (MemAvailable less the other {} ranks on this node)", local - 1)
                            : std::string(" (MemAvailable)")),
      where,
      fits >= 1 ? fmt::format("give samples_per_pair <= {:.0f}, or split the study (fewer records, period pairs, "
                              "stripes or gaps), or run on a machine with more memory, or keep only the reductions "
                              "([outputs] per_model = false), or write every model's peaks from the checkpoint in "
                              "bounded memory ([outputs] per_model = \"stream\", probability scene of an SDOF pair)",
                              fits)
                : std::string("split the study (fewer records, period pairs, stripes or gaps), or run on a machine with "
                              "more memory"));
}

Study load_study(const std::string& path) { return parse_study(files::read_text(path, "the study file"), path); }

}  // namespace pounding
