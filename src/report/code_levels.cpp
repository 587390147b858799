// The code rules at each contact level of a pair of shear buildings (analysis/code_displacement.hpp, "per contact
// level"): the codes' design displacements are first-mode values, so at a contact level z each building's is
// Gamma1 phi1(z) times its SDOF value, Gamma1 phi1 from the building's own masses and storey stiffnesses (the
// eigen solution `pounding modes` prints), and the levels are the ones the model makes pound
// (model::shear_buildings with the study's tolerance, levels and shape functions). An SDOF pair has one level,
// Gamma1 phi1 = 1: its rows are the code rules section's, and this section is not written (its bits).
#include <algorithm>
#include <cmath>
#include <variant>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "data.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/model/modes.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/report/escape.hpp"
#include "pounding/sampling/code_factors.hpp"

namespace pounding::report_detail {

namespace {

double median_of(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string text_or(const results::Settings& s, std::string_view section, std::string_view key, std::string def) {
  const results::SettingValue* v = s.find(section, key);
  return v && std::holds_alternative<std::string>(*v) ? std::get<std::string>(*v) : def;
}

}  // namespace

// Building b's period as the codes take it: the study's own number where it states one (a fixed period, or a
// distribution's median: /models/periods<b> holds that one slot), else the median of the sampled periods.
double code_period(const Data& r, int b, std::string& source) {
  const std::vector<double>& T = b == 1 ? r.mod.T1 : r.mod.T2;
  const std::string given = text_or(r.res.settings, fmt::format("structures.building{}", b), "period", "");
  if (!T.empty() && std::all_of(T.begin(), T.end(), [&](double t) { return t == T.front(); })) {
    source = "as given";
    return T.front();
  }
  const std::vector<double>& slot = r.periods(b);
  if (slot.size() == 1 && !given.empty() && given.find("grid") == std::string::npos) {
    source = fmt::format("the study's median ({})", given);
    return slot.front();
  }
  source = fmt::format("median of {} samples", T.size());
  return median_of(T);
}

std::vector<double> first_mode_gphi(int storeys, const std::vector<double>& h, model::StiffnessProfile profile) {
  // equal floor masses (the study splits each sample's mass equally, or takes floor_mass): the shape does not
  // depend on their value, nor on the stiffnesses' scale
  const std::vector<double> m(static_cast<std::size_t>(storeys), 1.0);
  const std::vector<double> k = model::stiffness_shape(m, h, profile);
  const model::Modes modes = model::shear_stick_modes(m, k);
  std::vector<double> g;
  for (std::size_t i = 0; i < m.size(); ++i) g.push_back(modes.gamma[0] * modes.phi[0][i]);
  return g;
}

namespace {

LevelBuilding level_building(const Data& r, int b) {
  const results::Settings& s = r.res.settings;
  const std::string sec = fmt::format("structures.building{}", b);
  LevelBuilding x;
  x.code = building_code(r, b);
  x.code.T = code_period(r, b, x.period_source);
  x.storey_heights = storey_height_setting(s, sec);
  if (x.storey_heights.empty()) x.storey_heights = {default_storey_height};
  double sum = 0.0;
  for (double h : x.storey_heights) sum += h;
  x.storey_height = sum / static_cast<double>(x.storey_heights.size());  // the code's storey height: their mean
  x.code.storey_height = x.storey_height;
  x.storeys = text_or(s, sec, "model", "sdof") == "shear" ? static_cast<int>(x.code.resolved_storeys()) : 1;
  if (x.storeys == 1 && x.storey_heights.size() > 1) x.storey_heights = {sum};  // (not a shear building)
  x.profile = text_or(s, sec, "stiffness_profile", "uniform");
  x.gphi = first_mode_gphi(x.storeys, x.storey_heights,
                           parse_enum(model::stiffness_profile_names, x.profile).value_or(model::StiffnessProfile::uniform));
  x.gamma_roof = x.gphi.back();
  return x;
}

std::string metres(double v) { return fmt::format("{:.4f}", v); }

}  // namespace

std::vector<separation::ContactLevel> contact_levels(const LevelBuilding (&b)[2], double tolerance,
                                                    model::ContactLevels levels, model::ShapeFunctions shape) {
  std::vector<separation::ContactLevel> out;
  std::vector<model::StickTopology> sticks(2);
  for (int i = 0; i < 2; ++i) {
    sticks[i].storeys = b[i].storeys, sticks[i].storey_heights = b[i].storey_heights;
    sticks[i].columns = b[i].storeys > 1;  // an SDOF beside a shear building meets its floors only
  }
  const model::System sys = model::shear_buildings(sticks, tolerance, levels);
  // a side's (building, height, Gamma1 phi1); a column side between floors p (may be the ground) and q at weight xi
  const auto side = [&](const model::Side& sd, double xi, int& body, double& z, double& g) {
    const auto at = [&](int dof, int& bb, double& zz, double& gg) {
      if (dof == model::ground) {
        zz = 0, gg = 0;
        return;
      }
      bb = sys.body_of(dof);
      const model::Body& B = sys.bodies()[static_cast<std::size_t>(bb)];
      const std::size_t f = static_cast<std::size_t>(std::find(B.dofs.begin(), B.dofs.end(), dof) - B.dofs.begin());
      zz = B.heights[f], gg = b[bb].gphi[f];
    };
    if (sd.kind == model::SideKind::point) return at(sd.p, body, z, g);
    double z0, g0, z1, g1;
    int b0 = -1;
    at(sd.p, b0, z0, g0), at(sd.q, body, z1, g1);
    const double w = model::column_weight(xi, shape);
    z = z0 + xi * (z1 - z0), g = (1 - w) * g0 + w * g1;
  };
  for (const model::ContactElement& ce : sys.contacts()) {
    separation::ContactLevel L;
    L.label = ce.label;
    int bl = 0, br = 1;
    double zl, gl, zr, gr;
    side(ce.left, ce.xi, bl, zl, gl), side(ce.right, ce.xi, br, zr, gr);
    L.z1 = bl == 0 ? zl : zr, L.gphi1 = bl == 0 ? gl : gr;
    L.z2 = bl == 0 ? zr : zl, L.gphi2 = bl == 0 ? gr : gl;
    L.floors_coincide = ce.left.kind == model::SideKind::point && ce.right.kind == model::SideKind::point;
    out.push_back(L);
  }
  return out;
}

std::optional<CodeLevels> code_levels(const Data& r) {
  const results::Settings& s = r.res.settings;
  if (!r.set.pair || r.set.bridge || s.find("structures", "buildings")) return std::nullopt;
  bool shear = false;
  for (int b = 1; b <= 2; ++b) {
    const std::string sec = fmt::format("structures.building{}", b);
    shear = shear || text_or(s, sec, "model", "sdof") == "shear";
    if (s.find(sec, "isolation")) return std::nullopt;  // an isolated base meets no floor: its moat section
  }
  if (!shear) return std::nullopt;
  CodeLevels c;
  c.b[0] = level_building(r, 1), c.b[1] = level_building(r, 2);
  // stored unless at their defaults (study_keys.hpp's unless_default): absent, the key's default
  const auto key_default = [](const char* key) { return config::typed_default(config::study_key("contact", key)); };
  const double tolerance = s.find("contact", "level_tolerance") ? s.number("contact", "level_tolerance")
                                                                : std::get<double>(key_default("level_tolerance"));
  const auto levels =
      parse_enum(model::contact_levels_names, text_or(s, "contact", "levels", std::get<std::string>(key_default("levels"))))
          .value_or(model::ContactLevels::common);
  const auto shape = parse_enum(model::shape_functions_names,
                                text_or(s, "contact", "shape_functions", std::get<std::string>(key_default("shape_functions"))))
                         .value_or(model::ShapeFunctions::linear);
  c.levels = contact_levels(c.b, tolerance, levels, shape);
  c.levels_rule = fmt::format(
      "the levels where the model makes the buildings pound: {} (level tolerance {:g} m){}",
      levels == model::ContactLevels::top ? "the lower roof only ([contact] levels = \"top\")"
                                          : "every pair of floors within the tolerance, and a floor facing the "
                                            "neighbour's column between two of its floors",
      tolerance,
      shape == model::ShapeFunctions::cubic ? "; a column point's Gamma1 phi1 from its floors' by the cubic shape "
                                              "functions ([contact] shape_functions)"
                                            : "; a column point's Gamma1 phi1 interpolated linearly between its floors");
  return c;
}

std::string code_levels_section(const Data& r) {
  const std::optional<CodeLevels> c = code_levels(r);
  if (!c) return {};
  const std::optional<TargetSpectrumSpec> spec = study_design_spectrum(r.res.settings);
  const TargetSpectrumSpec* sp = spec ? &*spec : nullptr;
  std::string s = fmt::format(
      "\n## Code separation rules at each contact level\n\n"
      "The codes ask for the separation where the buildings can meet, not at the taller roof. The contact levels are "
      "{}. At a level each code's design displacement is its first-mode value there, u(z) = Gamma1 phi1(z) x the "
      "SDOF value of the rows above (ASCE 7-16 12.9.1 modal analysis, delta_M = (Cd / R) Gamma1 phi1(z) Sd(T1); "
      "EN 1998-1 4.3.3.3 and eq. 4.23, d_s = q Gamma1 phi1(z) S_d(T1) g T1^2/4pi^2; Standard 2800, Delta_M = (Cd / "
      "Ru) Gamma1 phi1(z) A B I g T1^2/4pi^2), with Gamma1 phi1 from each building's own first mode (equal floor "
      "masses, the study's stiffness profile: the eigen solution `pounding modes` prints, phi1 = 1 at the roof). "
      "The coefficient rule is linear in height ({} x each building's height at the level). Sd = Sa g T^2/4pi^2, "
      "g = 9.80665 m/s^2.\n\n"
      "| building | storeys x storey height | T1 s (source) | Gamma1 (phi1 roof = 1) | Sa(T1) g | Sd(T1) m | factor |\n"
      "|---|---|---|---|---|---|---|\n",
      c->levels_rule, r.set.code_gap_coefficient);
  for (int b = 0; b < 2; ++b) {
    const LevelBuilding& x = c->b[b];
    const separation::ModalInputs in = sp ? separation::code_modal_inputs(*sp, x.code) : separation::ModalInputs{NAN, NAN, NAN};
    const char* factor = !sp ? "-"
                         : sp->code == TargetCode::asce7_16 ? "Cd / R"
                         : sp->code == TargetCode::ec8      ? "q"
                         : sp->code == TargetCode::iran2800 ? "Cd / Ru"
                                                            : "-";
    s += fmt::format("| {} | {} ({}) | {:.4f} ({}) | {:.4f} | {} | {} | {} |\n", b + 1,
                     x.storey_heights.size() > 1 ? fmt::format("{:g} m", fmt::join(x.storey_heights, " + "))
                                                 : fmt::format("{} x {:g} m", x.storeys, x.storey_height),
                     report::md_cell(x.profile), x.code.T, report::md_cell(x.period_source),
                     x.gamma_roof, std::isfinite(in.sa_g) ? fmt::format("{:.5f}", in.sa_g) : "-",
                     std::isfinite(in.sd) ? fmt::format("{:.5f}", in.sd) : "-",
                     std::isfinite(in.factor) ? fmt::format("{} = {:.5g}", factor, in.factor) : "-");
  }
  // the governing level of each rule: the largest gap over the levels
  std::vector<std::pair<std::string, std::pair<double, std::string>>> governing;
  for (const separation::ContactLevel& L : c->levels) {
    const std::vector<separation::LevelRow> rows =
        separation::code_level_rows(sp, c->b[0].code, c->b[1].code, L, r.set.code_gap_coefficient);
    s += fmt::format(
        "\n### Contact {}: building 1 at z1 = {:.3f} m (Gamma1 phi1 = {:.5f}), building 2 at z2 = {:.3f} m (Gamma1 "
        "phi1 = {:.5f}){}\n\n| rule | clause | u1 m | u2 m | combination | separation m |\n|---|---|---|---|---|---|\n",
        report::md_text(L.label), L.z1, L.gphi1, L.z2, L.gphi2, L.floors_coincide ? "" : " — a floor against a column");
    for (const separation::LevelRow& row : rows) {
      s += fmt::format("| {} | {} | {} | {} | {} | {} |\n", row.rule, row.clause, metres(row.d1), metres(row.d2),
                       row.combination, metres(row.gap));
      auto it = std::find_if(governing.begin(), governing.end(), [&](const auto& g) { return g.first == row.rule; });
      if (it == governing.end()) governing.push_back({row.rule, {row.gap, L.label}});
      else if (row.gap > it->second.first) it->second = {row.gap, L.label};
    }
  }
  if (!governing.empty()) {
    s += "\nThe governing level of each rule (its largest separation over the contact levels):\n\n"
         "| rule | separation m | at |\n|---|---|---|\n";
    for (const auto& [rule, g] : governing)
      s += fmt::format("| {} | {} | {} |\n", rule, metres(g.first), report::md_cell(g.second));
  }
  if (!sp || separation::code_level_rows(sp, c->b[0].code, c->b[1].code, {}, 0).empty())
    s += "\nNo design rows: the code rules section above says what the study needs for them.\n";
  return s;
}

std::string code_levels_csv(const Data& r) {
  const std::optional<CodeLevels> c = code_levels(r);
  if (!c) return {};
  const std::optional<TargetSpectrumSpec> spec = study_design_spectrum(r.res.settings);
  const double unit = median_of(r.mod.code_gap);
  std::string s;
  for (const separation::ContactLevel& L : c->levels)
    for (const separation::LevelRow& row :
         separation::code_level_rows(spec ? &*spec : nullptr, c->b[0].code, c->b[1].code, L, r.set.code_gap_coefficient))
      s += fmt::format("code_level,,{:.6f},,,,,,{:.6f},{:.6f},{:.6f},{}\n", row.gap / unit, row.gap, row.d1, row.d2,
                       report::csv_field(row.rule + " at " + L.label));
  return s;
}

}  // namespace pounding::report_detail
