// The codes' own design displacements in the report (issue 23 item 5): the study's design spectrum and each
// building's factors, read back from /settings, turned into separations by analysis/code_displacement.hpp; and
// the scope of Standard 2800's 0.005 h rule.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "data.hpp"
#include "pounding/analysis/code_displacement.hpp"

namespace pounding::report_detail {

namespace {

double median_of(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double number_or(const results::Settings& s, std::string_view section, std::string_view key, double def) {
  return s.find(section, key) ? s.number(section, key) : def;
}

}  // namespace

std::vector<double> storey_height_setting(const results::Settings& s, std::string_view section) {
  const results::SettingValue* v = s.find(section, "storey_height");
  if (!v) return {};
  if (std::holds_alternative<std::vector<double>>(*v)) return s.numbers(section, "storey_height");
  return {s.number(section, "storey_height")};
}

std::optional<TargetSpectrumSpec> study_design_spectrum(const results::Settings& s) {
  const results::SettingValue* code = s.find("target_spectrum", "code");
  if (!code || !std::holds_alternative<std::string>(*code)) return std::nullopt;
  const auto c = parse_enum(target_code_names, std::get<std::string>(*code));
  if (!c) return std::nullopt;
  TargetSpectrumSpec spec;
  spec.code = *c;
  const char* t = "target_spectrum";
  switch (spec.code) {
    case TargetCode::asce7_16:
      if (!s.find(t, "sds")) return std::nullopt;  // a file written before the parameters were stored
      spec.asce7 = {s.number(t, "sds"), s.number(t, "sd1"), s.number(t, "tl")};
      break;
    case TargetCode::ec8: {
      if (!s.find(t, "agr")) return std::nullopt;
      spec.ec8.type = s.number(t, "type") == 1 ? Ec8Type::type1 : Ec8Type::type2;
      spec.ec8.ground = static_cast<Ec8Ground>(std::string("ABCDE").find(s.text(t, "ground")));
      spec.ec8.agr = s.number(t, "agr");
      spec.ec8.importance = s.number(t, "importance");
      break;
    }
    case TargetCode::iran2800: {
      if (!s.find(t, "a")) return std::nullopt;
      const std::string soil = s.text(t, "soil");
      spec.iran2800.a = s.number(t, "a");
      spec.iran2800.soil = soil == "I" ? Iran2800Soil::I : soil == "II" ? Iran2800Soil::II
                           : soil == "III" ? Iran2800Soil::III : Iran2800Soil::IV;
      spec.iran2800.importance = s.number(t, "importance");
      break;
    }
    case TargetCode::csv: break;
  }
  return spec;
}

separation::BuildingCode building_code(const Data& r, int b, std::size_t model) {
  const results::Settings& s = r.res.settings;
  const std::string sec = fmt::format("structures.building{}", b);
  separation::BuildingCode c;
  if (model == static_cast<std::size_t>(-1)) {  // the pair's: its period as the codes take it (code_period)
    std::string source;
    c.T = (b == 1 ? r.mod.T1 : r.mod.T2).empty() ? NAN : code_period(r, b, source);
    c.height = median_of(b == 1 ? r.mod.h1 : r.mod.h2);
  } else {
    c.T = (b == 1 ? r.mod.T1 : r.mod.T2)[model];
    c.height = (b == 1 ? r.mod.h1 : r.mod.h2)[model];
  }
  c.asce7_r = number_or(s, sec, "asce7_r", 0), c.asce7_cd = number_or(s, sec, "asce7_cd", 0);
  c.asce7_ie = number_or(s, sec, "asce7_ie", 0), c.ec8_q = number_or(s, sec, "ec8_q", 0);
  c.s2800_ru = number_or(s, sec, "s2800_ru", 0), c.s2800_cd = number_or(s, sec, "s2800_cd", 0);
  c.s2800_importance = number_or(s, sec, "s2800_importance", 0);
  c.storeys = std::lround(number_or(s, sec, "storeys", 0));
  const std::vector<double> h = storey_height_setting(s, sec);  // one per storey: their mean, the code's storey
  double sum = 0.0;
  for (double x : h) sum += x;
  c.storey_height = h.empty() ? 0.0 : sum / static_cast<double>(h.size());
  return c;
}

std::string coefficient_scope(const Data& r, std::vector<separation::Rule>& rules) {
  if (rules.empty() || r.set.code_gap_coefficient != 0.005) return "";
  const std::optional<TargetSpectrumSpec> spec = study_design_spectrum(r.res.settings);
  const double importance = spec && spec->code == TargetCode::iran2800 ? spec->iran2800.importance : 0.0;
  const separation::Scope scope =
      separation::s2800_coefficient_scope(building_code(r, 1), building_code(r, 2), importance);
  if (scope.inside)
    return scope.reason.empty() ? "" : fmt::format("Standard 2800's 0.005 h rule applies here (up to 8 storeys; {}).\n", scope.reason);
  rules[0].name = "Standard 2800 (outside its scope)";
  rules[0].clause = fmt::format("Standard 2800 (4th ed.) 0.005 h applies only up to 8 storeys of ordinary importance: "
                                "{}; shown for comparison only", scope.reason);
  const bool drift_row = spec && spec->code == TargetCode::iran2800 &&
                         building_code(r, 1).s2800_ru > 0 && building_code(r, 2).s2800_ru > 0;
  return fmt::format(
      "**Standard 2800's 0.005 h rule is outside its scope for this pair** ({}): the standard requires a joint from the "
      "design inelastic drift, Delta_M = Cd Delta_eu with P-Delta, {}.\n",
      scope.reason,
      drift_row ? "the row \"Standard 2800 design drift joint\" below (without P-Delta)"
                : "which needs a Standard 2800 design spectrum ([target_spectrum] code = \"Standard 2800\", with "
                  "[records] select) and s2800_ru, s2800_cd in both building tables");
}

separation::CodeDesign code_design(const Data& r) {
  const std::optional<TargetSpectrumSpec> spec = study_design_spectrum(r.res.settings);
  const bool stored = !(r.res.settings.find("target_spectrum", "code") && !spec);
  separation::CodeDesign d =
      separation::code_design_rules(spec ? &*spec : nullptr, building_code(r, 1), building_code(r, 2));
  if (!stored) {
    d.notes.clear();
    d.notes.push_back("This results file does not store the design spectrum's parameters (written before they were); "
                      "rerun the study for the code design displacements");
  }
  return d;
}

}  // namespace pounding::report_detail
