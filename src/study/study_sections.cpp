// The sections of a study file that belong to the Study itself -- [records], [gaps], [contact], [analysis], [report],
// [outputs] -- read into it (split from src/study/study.cpp; parse_study calls them in this order).
#include "study_sections.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "pounding/config/config.hpp"
#include "pounding/config/fields.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/study/histories.hpp"
#include "pounding/study/study_fields.hpp"

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
      rf.scale = fr.number("scale");
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
  q.wave_passage = m.boolean("wave_passage");
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
  motions->uniform = m.boolean("uniform");
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

}  // namespace

void parse_records(Study& s, const toml::table* t, const std::string& path) {
  TableReader r(t, path, "records");
  s.suite = r.string("suite", "");
  if (s.suite != "builtin") s.suite = resolve_relative(path, s.suite);
  s.real_dir = resolve_relative(path, r.string("real_dir", ""));
  s.directory = resolve_relative(path, r.string("directory", ""));
  config::read_fields(s, r, study_fields::records);
  s.units = r.choice("units", "g", parse_units);
  s.dt_one_column = r.number("dt", 0.0);
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
  config::read_fields(s, g, study_fields::gaps);
  s.existing_gap = g.number("existing", NAN);
  g.finish("ratios, metres, curve_max, curve_step, existing");
}

namespace {

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
  r.units = q.string("units");
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

}  // namespace

void parse_contact(Study& s, const toml::table* t, const std::string& path) {
  TableReader c(t, path, "contact");
  s.contact.law = c.choice("law", "hertzdamp", parse_contact_law);
  s.contact.damping = c.choice("damping_law", "lankarani-nikravesh", parse_damping_law);
  if (!contact::traits(s.contact.law).has_force && !contact::traits(s.contact.law).impulsive)
    throw InputError("contact law 'none' cannot count impacts", c.where("law"), "choose a contact law (hertzdamp, kelvin, ...)");
  config::read_fields(s, c, study_fields::contact);
  if (c.get("e") && c.get("restitution"))
    throw InputError("[contact] e and restitution both given", c.where("e"), "remove e: the curve gives e(v0) at each impact");
  s.restitution = read_restitution(c, path);
  s.contact.n = c.number("n");
  s.contact.v0_min = c.number("v0_min");
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
  s.shape_functions = c.choice("shape_functions", "linear", [](const std::string& name) {
    if (auto v = parse_enum(model::shape_functions_names, name)) return *v;
    throw InputError(fmt::format("unknown shape_functions '{}'", name), "shape_functions",
                     "write shape_functions = " + enum_name_list(model::shape_functions_names, " or ", "\""));
  });
  c.finish("law, damping_law, e, n, v0_min, stiffness, levels, gap_offsets, joint_gap_offsets, level_tolerance, "
           "shape_functions, restitution");
}


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


void parse_analysis(Study& s, const toml::table* t, const std::string& path) {
  TableReader a(t, path, "analysis");
  s.stepper = a.choice("stepper", "central-difference", parse_stepper);
  s.step_given = a.get("substeps") != nullptr || a.get("max_dt") != nullptr;
  config::read_fields(s, a, study_fields::analysis);
  s.max_dt = a.number("max_dt", -1.0);
  s.batch = static_cast<int>(a.integer("batch", 0));  // 0: the scene's default, set by choose_scene
  // a step the user gave is the step of every analysis (as simulate --dt): refine only where the engine chose it
  s.coarse = a.choice("coarse", s.step_given ? "exclude" : "refine", parse_coarse_policy);
  a.finish("stepper, substeps, max_dt, batch, threads, free_vibration, displacement_limit, skip_untouched, scale_elastic, "
           "max_excluded_fraction, coarse");
}


void parse_report(Study& s, const toml::table* t, const std::string& path) {
  TableReader r(t, path, "report");
  config::read_fields(s, r, study_fields::report);
  for (const char* key : {"h1", "h2"})
    if (r.get(key))
      throw InputError(fmt::format("[report] {} is no longer a setting: separations in metres come from the buildings' "
                                   "own heights, never from assumed ones", key),
                       r.where(key),
                       "delete it; for a pair of given buildings set [structures.building1] height = <m> and "
                       "[structures.building2] height = <m> (a study with heights from the period-height rule "
                       "reports gaps as ratios of the code gap d)");
  if (!s.compare_with.empty() && s.compare_with != "stochastic-pounding")
    throw InputError(fmt::format("compare_with = \"{}\" is not a published study the report knows", s.compare_with),
                     r.where("compare_with"), "write compare_with = \"stochastic-pounding\" or leave it out");
  // on the gap axis' unit: ratios 0.1 to 1.0 d; metres 0.1 x to 1 x the largest gap
  s.fit_min = r.number("fit_min", s.gap_metres ? 0.1 * s.gap_ratios.back() : 0.1);
  s.fit_max = r.number("fit_max", s.gap_metres ? s.gap_ratios.back() : 1.0);
  if (!(s.fit_max > s.fit_min)) throw InputError("fit_max must exceed fit_min", r.where("fit_max"), "give fit_min < fit_max");
  r.finish("targets, fit_min, fit_max, confidence, bootstrap, compare_with, html");
}

namespace {

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

}  // namespace

void parse_outputs(Study& s, const toml::table* t, const std::string& path) {
  TableReader o(t, path, "outputs");
  config::read_fields(s, o, study_fields::outputs);
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

namespace {

}  // namespace

}  // namespace pounding
