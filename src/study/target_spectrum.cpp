// [target_spectrum] and [records] select (study/target_spectrum.hpp): parsing, the selection of a study's
// records, and the /selection group.
#include "pounding/study/target_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "pounding/config/config.hpp"
#include "pounding/config/fields.hpp"
#include "pounding/core/error.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/intensity.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/study_fields.hpp"

namespace pounding {

namespace fs = std::filesystem;
using config::TableReader;

namespace {

constexpr double any_lo = -1e300, any_hi = 1e300;  // the range is validate()'s (design_spectrum.hpp)

// The study key of a parameter named by a validate() of design_spectrum.hpp or selection.hpp.
std::string key_of(const std::string& param) {
  static const std::pair<const char*, const char*> keys[] = {
      {"SDS", "sds"}, {"SD1", "sd1"}, {"TL", "tl"}, {"agR", "agr"}, {"importance factor gammaI", "importance"},
      {"importance factor I", "importance"}, {"damping ratio xi (%)", "damping"}, {"A", "a"},
      {"ground type", "ground"}, {"soil type", "soil"}, {"--count", "select"}, {"--range", "t_max"},
      {"--points", "points"}, {"--min-scale/--max-scale", "max_scale"}, {"--damping", "damping"},
      {"Ss", "ss"}, {"S1", "s1"}, {"site class", "site_class"}};
  for (const auto& [p, k] : keys)
    if (param == p) return k;
  return "";
}

// Runs f (a validate() or a constructor that validates) and points its InputError at the study key.
template <class F>
auto at_key(TableReader& r, F f) {
  try {
    return f();
  } catch (const InputError& e) {
    const std::string key = key_of(e.where());
    throw InputError(e.what_part(), key.empty() ? r.where("code") : r.where(key), e.fix());
  }
}

double required(TableReader& r, std::string_view key, std::string_view code, const std::string& example) {
  if (!r.get(key))
    throw InputError(fmt::format("code = \"{}\" needs {}", code, key), r.where(key), "write " + example);
  return r.number(key, 0.0, any_lo, any_hi, "the code's own limits are checked next");
}

template <class E, std::size_t N>
E one_of(TableReader& r, std::string_view key, const char* const (&names)[N], std::string_view code,
         const std::string& allowed) {
  if (!r.get(key))
    throw InputError(fmt::format("code = \"{}\" needs {}", code, key), r.where(key), "write " + std::string(key) + " = " + allowed);
  const std::string v = r.string(key, "");
  for (std::size_t i = 0; i < N; ++i)
    if (v == names[i]) return static_cast<E>(i);
  throw InputError(fmt::format("{} = \"{}\" is not one of the {} {}", key, escaped_excerpt(v), code,
                               key == "ground" ? "ground types" : "soil types"),
                   r.where(key), "use " + allowed);
}

// The code's own keys; returns the list of them for finish().
std::string read_code_parameters(TargetSpectrumSpec& spec, TableReader& r, const std::string& path) {
  const std::string code(to_string(spec.code));
  switch (spec.code) {
    case TargetCode::asce7_16: {
      // either the design values (sds, sd1) or the mapped MCER values and the site class (asce7_site.hpp)
      const bool design = r.get("sds") || r.get("sd1"), maps = r.get("ss") || r.get("s1") || r.get("site_class");
      if (design && maps)
        throw InputError("both sds/sd1 and ss/s1/site_class are given", r.where(r.get("ss") ? "ss" : r.get("s1") ? "s1" : "site_class"),
                         "give either sds and sd1 (the design values) or ss, s1 and site_class (the mapped MCER values)");
      const double tl = r.number("tl", 8.0, any_lo, any_hi, "the code's own limits are checked next");
      if (maps) {
        spec.from_maps = true;
        spec.maps.ss = required(r, "ss", code, "ss = 1.5 (g, the mapped MCER Sa at 0.2 s)");
        spec.maps.s1 = required(r, "s1", code, "s1 = 0.6 (g, the mapped MCER Sa at 1 s)");
        if (!r.get("site_class"))
          throw InputError(fmt::format("code = \"{}\" with ss and s1 needs site_class", code), r.where("site_class"),
                           "write site_class = \"C\" (A, B, C, D, D-default, E or F)");
        const std::string site = r.string("site_class", "");
        spec.maps.site = parse_asce7_site_class(site, r.where("site_class"));
        spec.maps.tl = tl;
        spec.asce7 = at_key(r, [&] { return asce7_from_maps(spec.maps); });
      } else {
        spec.asce7.sds = required(r, "sds", code, "sds = 1.0 (g, the design short-period Sa), or ss, s1 and site_class");
        spec.asce7.sd1 = required(r, "sd1", code, "sd1 = 0.6 (g, the design 1-s Sa)");
        spec.asce7.tl = tl;
      }
      spec.mcer = r.boolean("mcer");
      return "sds, sd1, ss, s1, site_class, tl, mcer";
    }
    case TargetCode::ec8: {
      const char* const grounds[] = {"A", "B", "C", "D", "E"};
      spec.ec8.type = r.integer("type") == 1 ? Ec8Type::type1 : Ec8Type::type2;
      spec.ec8.ground = one_of<Ec8Ground>(r, "ground", grounds, code, "\"A\", \"B\", \"C\", \"D\" or \"E\"");
      spec.ec8.agr = required(r, "agr", code, "agr = 0.25 (g, the reference PGA on ground A)");
      spec.ec8.importance = r.number("importance", 1.0, any_lo, any_hi, "the code's own limits are checked next");
      return "type, ground, agr, importance";
    }
    case TargetCode::iran2800: {
      const char* const soils[] = {"I", "II", "III", "IV"};
      spec.iran2800.a = required(r, "a", code, "a = 0.35 (the design base acceleration ratio)");
      spec.iran2800.soil = one_of<Iran2800Soil>(r, "soil", soils, code, "\"I\", \"II\", \"III\" or \"IV\"");
      spec.iran2800.importance = r.number("importance", 1.0, any_lo, any_hi, "the code's own limits are checked next");
      return "a, soil, importance";
    }
    case TargetCode::csv: {
      std::string file = r.string("file", "");
      if (file.empty())
        throw InputError("code = \"csv\" needs the table's file", r.where("file"),
                         "write file = \"target.csv\" (period,sa lines in s, g; relative to the study file)");
      if (!fs::path(file).is_absolute()) file = (fs::path(path).parent_path() / file).lexically_normal().string();
      try {
        spec.table = read_tabulated_spectrum(file);
      } catch (const InputError& e) {
        throw InputError(e.what_part(), e.where(), e.fix() + fmt::format(" ({})", r.where("file")));
      }
      return "file";
    }
  }
  return "";
}

void read_range(TargetSpectrumSection& x, TableReader& r, const StructureModel& structures) {
  const double t1 = median_period(structures, 0), t2 = median_period(structures, 1);
  const auto m = default_range_multiples(x.options.rule);
  x.range_given = r.get("t_min") || r.get("t_max");
  x.options.t_lo = r.number("t_min", m[0] * std::min(t1, t2));
  x.options.t_hi = r.number("t_max", m[1] * std::max(t1, t2));
  if (!(x.options.t_hi > x.options.t_lo))
    throw InputError(fmt::format("the period range {}-{} s is empty", x.options.t_lo, x.options.t_hi), r.where("t_max"),
                     fmt::format("give t_max > t_min (the default is {:g} min(T1, T2) to {:g} max(T1, T2), T1 = {:.3g} "
                                 "s and T2 = {:.3g} s the buildings' median periods)", m[0], m[1], t1, t2));
}

}  // namespace

TargetSpectrumSection parse_target_spectrum(const toml::table* t, const std::string& path,
                                            const StructureModel& structures) {
  TargetSpectrumSection x;
  if (!t) return x;
  x.enabled = true;
  TableReader r(t, path, "target_spectrum");
  x.where = config::location(path, t->source()) + " [target_spectrum]";
  if (!r.get("code"))
    throw InputError("[target_spectrum] names no code", r.where("code"),
                     "write code = " + enum_name_list(target_code_names, " | ", "\""));
  x.spec.code = r.choice("code", "", [](const std::string& name) {
    if (auto c = parse_enum(target_code_names, name)) return *c;
    throw InputError(fmt::format("unknown design code '{}'", escaped_excerpt(name)), "code",
                     "use " + enum_name_list(target_code_names, " or ", "\""));
  });
  const std::string code_keys = read_code_parameters(x.spec, r, path);
  x.options.rule = r.get("rule") ? r.choice("rule", "", parse_scaling_rule) : default_scaling_rule(x.spec.code);
  read_range(x, r, structures);
  // the ranges of src/config/study_keys.cpp are validate()'s (selection.hpp: selection_period_min ...)
  config::read_fields(x.options, r, study_fields::target_spectrum);
  r.finish("code, " + code_keys + ", rule, t_min, t_max, points, damping, min_scale, max_scale");
  if (x.options.min_scale > x.options.max_scale)
    throw InputError(fmt::format("min_scale = {:g} is above max_scale = {:g}", x.options.min_scale, x.options.max_scale),
                     r.where("min_scale"), "give min_scale <= max_scale, e.g. min_scale = 0.25 and max_scale = 4");
  at_key(r, [&] { validate(x.options); return 0; });
  const DesignSpectrum target = at_key(r, [&] { return make_target_spectrum(x.spec, x.options.damping); });
  x.target_text = describe_target(x.spec, target);
  return x;
}

std::vector<std::string> StudySelection::summary() const {
  return selection_summary(selection, ids, sources, target_text, options);
}

namespace {

// select_records' errors speak of command-line flags; here they are study keys.
InputError in_study_terms(const InputError& e, const Study& s) {
  std::string fix = e.fix();
  for (const auto& [flag, key] : {std::pair<std::string, std::string>{"--max-scale", "[target_spectrum] max_scale"},
                                  {"--min-scale", "[target_spectrum] min_scale"},
                                  {"--count", "[records] select"},
                                  {"--max-per-event", "[records] max_per_event"},
                                  {"--components both", "[records] components = \"both\""},
                                  {"--rule", "[target_spectrum] rule"}})
    for (std::size_t p = fix.find(flag); p != std::string::npos; p = fix.find(flag, p + key.size()))
      fix.replace(p, flag.size(), key);
  const bool scale = e.where().find("--count") != std::string::npos;
  const bool rules = e.where().find("--max-per-event") != std::string::npos;
  return InputError(e.what_part(),
                    scale   ? fmt::format("{} and {} min_scale, max_scale", s.select_where, s.target.where)
                    : rules ? s.select_where
                            : s.target.where,
                    fix);
}

}  // namespace

std::vector<StudyRecord> select_study_records(const Study& s, std::vector<StudyRecord> library, StudySelection& out) {
  const auto n = static_cast<std::size_t>(s.select);
  if (library.size() < n)
    throw InputError(fmt::format("select = {} but the library holds {} record{}", n, library.size(),
                                 library.size() == 1 ? "" : "s"),
                     s.select_where, fmt::format("give select <= {}, or name a larger library in [records]", library.size()));
  const TargetSpectrumSection& t = s.target;
  out.options = t.options;
  out.options.count = n;
  out.options.max_per_event = s.max_per_event;
  out.options.components = s.components;
  out.target_text = t.target_text;
  std::vector<SelectionCandidate> candidates;
  for (const auto& r : library) {
    candidates.push_back({r.id, &r.record});
    out.ids.push_back(r.id);
    out.sources.push_back(r.record.source.empty() ? r.note : r.record.source);
  }
  try {
    out.options.mcer_target = t.spec.mcer;
    out.selection = select_records(candidates, make_target_spectrum(t.spec, t.options.damping), out.options);
  } catch (const InputError& e) {
    throw in_study_terms(e, s);
  }
  const Selection& sel = out.selection;
  std::vector<StudyRecord> chosen;
  for (std::size_t k = 0; k < sel.chosen.size(); ++k) {
    StudyRecord r = library[sel.chosen[k]];
    for (double& a : r.record.acc) a *= sel.scale[k];
    r.note += fmt::format("; selected to the design spectrum ({}): x {:.6g} (f_i {:.6g} x F {:.6g})",
                          to_string(out.options.rule), sel.scale[k], sel.individual_scale[k], sel.suite_factor);
    require_analysable(r.record, {sel.scale[k], fmt::format("the selection's factor of record {} ({} and {})", r.id,
                                                            s.select_where, t.where),
                                  "set [records] units = \"cm/s2\" in " + s.path});
    chosen.push_back(std::move(r));
  }
  return chosen;
}

results::Group selection_group(const StudySelection& x) {
  const Selection& s = x.selection;
  const std::size_t n = s.chosen.size(), p = s.periods.size();
  results::Group g{"selection", {}, {}};
  std::vector<std::string> ids;
  std::vector<std::int64_t> index;
  std::vector<double> scaled;  // [records, periods]
  std::vector<std::string> events, stations, components, refused;
  for (std::size_t k = 0; k < n; ++k) {
    events.push_back(s.identity[k].event_text());
    stations.push_back(s.identity[k].station);
    components.push_back(s.identity[k].component);
    ids.push_back(x.ids[s.chosen[k]]);
    index.push_back(static_cast<std::int64_t>(s.chosen[k]));
    for (std::size_t j = 0; j < p; ++j) scaled.push_back(s.scale[k] * s.spectra[k][j]);
  }
  g.set("target_description", x.target_text);
  g.set("rule", std::string(to_string(x.options.rule)));
  g.set("rule_text", s.rule_text);
  g.set("rule_fraction", rule_fraction(x.options.rule));
  g.set("suite_factor", s.suite_factor);
  g.set("meets", static_cast<std::int64_t>(s.meets));
  g.set("min_ratio", s.min_ratio);
  g.set("pga_ratio", s.pga_ratio);
  g.set("candidates", static_cast<std::int64_t>(x.ids.size()));
  g.set("eligible", static_cast<std::int64_t>(s.eligible));
  g.set("t_min", x.options.t_lo);
  g.set("t_max", x.options.t_hi);
  g.set("damping", x.options.damping);
  g.set("min_scale", x.options.min_scale);
  g.set("max_scale", x.options.max_scale);
  if (!s.warnings.empty()) g.set("warnings", s.warnings);
  g.set("max_per_event", static_cast<std::int64_t>(x.options.max_per_event));
  g.set("components", std::string(to_string(x.options.components)));
  g.set("unidentified", static_cast<std::int64_t>(s.unidentified));
  for (const auto& r : s.refused) refused.push_back(x.ids[r.candidate] + ": " + r.reason);
  if (!refused.empty()) g.set("refused", refused);
  g.add("records", ids, "1", "the chosen records' ids, best match (smallest misfit) first: the order of /records");
  g.add("event", events, "1", "each chosen record's earthquake and year (\"\": unknown; MANIFEST.tsv or AT2 header)");
  g.add("station", stations, "1", "each chosen record's station (\"\": unknown)");
  g.add("component", components, "1", "each chosen record's component as its source names it (\"\": unknown)");
  g.add("candidate_index", index, "1", "each chosen record's index among the candidates (the library, in its order)");
  g.add("individual_scale", s.individual_scale, "1",
        "f_i: each chosen record's log-space least-squares factor to the target over the periods");
  g.add("scale", s.scale, "1", "f_i F: the factor each record is analysed with (suite_factor F is an attribute)");
  g.add("mse", s.mse, "1", "misfit: mean squared error of ln Sa (target against f_i x record) over the periods");
  g.add("periods", s.periods, "s", "the log-spaced periods of the match and of the code check");
  g.add("target", s.target, "g", "the target spectrum at the periods (" + x.target_text + ")");
  g.add("mean", s.mean, "g", "arithmetic mean of the scaled spectra (f_i F Sa_i) at the periods");
  g.add("spectra", scaled, "g",
        fmt::format("pseudo-spectral acceleration of each chosen record, scaled by f_i F, damping {:g}; "
                    "[records, periods]", x.options.damping),
        {n, p});
  return g;
}

}  // namespace pounding
