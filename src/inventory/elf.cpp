// ASCE 7-16 equivalent lateral force design of a building from a few numbers, and the shear stick built on it.
#include "pounding/inventory/elf.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/model/modes.hpp"

namespace pounding::inventory {
namespace {

constexpr double g = 9.80665;  // m/s^2
// Table 12.8-2 (SI): steel moment frames, concrete moment frames, all other structural systems.
constexpr double ct_steel_mf = 0.0724, x_steel_mf = 0.8, ct_rc_mf = 0.0466, x_rc_mf = 0.9, ct_other = 0.0488,
                 x_other = 0.75;
// Unit weights (kPa) within the ranges of research/inventory-and-design.md section 2: RC 7-10, steel 5-7, masonry 8-12.
constexpr double w_rc = 8.5, w_steel = 6.0, w_masonry = 10.0;

// R, Omega0, Cd from Table 12.2-1; drift limits from Table 12.12-1 (risk category I/II): 0.020 hsx for "all other
// structures", 0.007 hsx for masonry shear walls other than cantilevers.
constexpr std::array<SystemRow, 12> system_table{{
    {"rc-smf", "special reinforced concrete moment frame", 8, 3, 5.5, ct_rc_mf, x_rc_mf, 0.020, w_rc, Material::concrete, 0.05, "rc-smf"},
    {"rc-imf", "intermediate reinforced concrete moment frame", 5, 3, 4.5, ct_rc_mf, x_rc_mf, 0.020, w_rc, Material::concrete, 0.05, "rc-smf"},
    {"rc-omf", "ordinary reinforced concrete moment frame", 3, 3, 2.5, ct_rc_mf, x_rc_mf, 0.020, w_rc, Material::concrete, 0.05, "rc-smf"},
    {"rc-special-wall", "special reinforced concrete shear walls (building frame)", 6, 2.5, 5, ct_other, x_other, 0.020, w_rc + 0.5, Material::concrete, 0.05, "rc-special-wall"},
    {"rc-ordinary-wall", "ordinary reinforced concrete shear walls (building frame)", 5, 2.5, 4.5, ct_other, x_other, 0.020, w_rc + 0.5, Material::concrete, 0.05, "rc-special-wall"},
    {"steel-smf", "special steel moment frame", 8, 3, 5.5, ct_steel_mf, x_steel_mf, 0.020, w_steel, Material::steel, 0.03, "steel-smf"},
    {"steel-imf", "intermediate steel moment frame", 4.5, 3, 4, ct_steel_mf, x_steel_mf, 0.020, w_steel, Material::steel, 0.03, "steel-smf"},
    {"steel-omf", "ordinary steel moment frame", 3.5, 3, 3, ct_steel_mf, x_steel_mf, 0.020, w_steel, Material::steel, 0.03, "steel-smf"},
    {"steel-scbf", "special steel concentrically braced frame (building frame)", 6, 2, 5, ct_other, x_other, 0.020, w_steel, Material::steel, 0.03, "steel-scbf"},
    {"rm-special-wall", "special reinforced masonry shear walls (bearing wall)", 5, 2.5, 3.5, ct_other, x_other, 0.007, w_masonry, Material::masonry, 0.02, "rm-special-wall"},
    {"rm-ordinary-wall", "ordinary reinforced masonry shear walls (bearing wall)", 2, 2.5, 1.75, ct_other, x_other, 0.007, w_masonry, Material::masonry, 0.02, "rm-special-wall"},
    {"urm-wall", "ordinary plain (unreinforced) masonry shear walls (bearing wall)", 1.5, 2.5, 1.25, ct_other, x_other, 0.007, w_masonry, Material::masonry, 0.02, "rm-special-wall"},
}};

std::string system_keys() {
  std::string s;
  for (const SystemRow& r : system_table) s += (s.empty() ? "" : ", ") + std::string(r.key);
  return s;
}

std::vector<double> heights_of(const DesignInput& in) {
  if (in.storeys < 1 || in.storeys > 200)
    throw InputError(fmt::format("storeys {} is outside [1, 200]", in.storeys), in.where + " storeys",
                     "give the number of storeys above the ground (1 to 200)");
  const std::size_t n = static_cast<std::size_t>(in.storeys);
  if (in.storey_height.size() != 1 && in.storey_height.size() != n)
    throw InputError(fmt::format("{} storey heights for {} storeys", in.storey_height.size(), n),
                     in.where + " storey_height", "give one height for every storey or one per storey");
  std::vector<double> h(n, in.storey_height.front());
  if (in.storey_height.size() == n) h = in.storey_height;
  for (double v : h) require_range(v, 2.0, 10.0, in.where + " storey_height", "[2, 10] m");
  return h;
}

void check_input(const DesignInput& in) {
  require_range(in.plan_area, 10.0, 1e6, in.where + " plan_area", "[10, 1e6] m^2");
  if (in.unit_weight != 0) require_range(in.unit_weight, 1.0, 30.0, in.where + " unit_weight", "[1, 30] kPa");
  if (in.period != 0) require_range(in.period, 0.02, 20.0, in.where + " period", "[0.02, 20] s");
  require_range(in.sds, 0.01, 5.0, in.where + " SDS", "(0, 5] g");
  require_range(in.sd1, 0.01, 5.0, in.where + " SD1", "(0, 5] g");
  require_range(in.s1, 0.0, 3.0, in.where + " S1", "[0, 3] g");
  require_range(in.tl, 1.0, 20.0, in.where + " TL", "[1, 20] s");
  require_range(in.ie, 1.0, 1.5, in.where + " importance", "[1, 1.5] (Table 1.5-2)");
  if (in.overstrength != 0) require_range(in.overstrength, 1.0, 5.0, in.where + " overstrength", "[1, 5]");
}

// Storey stiffnesses proportional to `shape`, scaled so that the first period of the stick is T.
std::vector<double> scaled_to_period(std::span<const double> m, std::vector<double> k, double T) {
  const model::Modes modes = model::shear_stick_modes(m, k);
  const double w = 2 * std::numbers::pi / T;
  const double s = (w / modes.omega.front()) * (w / modes.omega.front());
  for (double& v : k) v *= s;
  return k;
}

void add_p_delta(DesignedBuilding& b) {
  const std::size_t n = b.floor_mass.size();
  b.gravity_load.assign(n, 0.0);
  double above = 0;
  for (std::size_t i = n; i-- > 0;) b.gravity_load[i] = above += g * b.floor_mass[i];
  b.model_stiffness = b.stiffness;
  b.model_strength = b.strength;
  b.model_alpha.assign(n, b.alpha);
  if (!b.p_delta) return;
  for (std::size_t i = 0; i < n; ++i) {
    const double kg = b.gravity_load[i] / b.storey_height[i];
    const double k = b.stiffness[i];
    if (kg >= 0.5 * k)
      throw InputError(fmt::format("storey {}'s geometric stiffness P/h = {:.3g} N/m is {:.0f} % of its stiffness", i + 1,
                                   kg, 100 * kg / k),
                       "P-Delta", "the storey is near elastic buckling: check the storey heights and unit weight");
    b.model_stiffness[i] = k - kg;
    b.model_alpha[i] = (b.alpha * k - kg) / (k - kg);
    b.model_strength[i] = b.strength[i] * (k - kg) / k;
  }
}

}  // namespace

std::string_view to_string(Material m) {
  switch (m) {
    case Material::concrete: return "concrete";
    case Material::steel: return "steel";
    case Material::masonry: return "masonry";
    case Material::wood: return "wood";
  }
  return "?";
}

std::span<const SystemRow> systems() { return system_table; }

const SystemRow& system_row(std::string_view key, const std::string& where) {
  for (const SystemRow& r : system_table)
    if (r.key == key) return r;
  throw unknown_key_error(key, "structural systems", where, system_keys(), "system");
}

DesignLevel parse_design_level(std::string_view name, const std::string& where) {
  if (name == "high") return DesignLevel::high;
  if (name == "moderate") return DesignLevel::moderate;
  if (name == "low") return DesignLevel::low;
  if (name == "pre-code") return DesignLevel::pre_code;
  throw unknown_key_error(name, "design levels", where, "high, moderate, low, pre-code", "design level");
}

std::string_view to_string(DesignLevel d) {
  switch (d) {
    case DesignLevel::high: return "high";
    case DesignLevel::moderate: return "moderate";
    case DesignLevel::low: return "low";
    case DesignLevel::pre_code: return "pre-code";
  }
  return "?";
}

double strength_factor(DesignLevel d) {
  switch (d) {
    case DesignLevel::high: return 1.0;
    case DesignLevel::moderate: return 0.5;
    case DesignLevel::low:
    case DesignLevel::pre_code: return 0.25;
  }
  return 1.0;
}

double asce7_cu(double sd1) {
  // Table 12.8-1: SD1 >= 0.4: 1.4; 0.3: 1.4; 0.2: 1.5; 0.15: 1.6; <= 0.1: 1.7.
  constexpr std::array<std::pair<double, double>, 5> t{{{0.1, 1.7}, {0.15, 1.6}, {0.2, 1.5}, {0.3, 1.4}, {0.4, 1.4}}};
  if (sd1 <= t.front().first) return t.front().second;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (sd1 <= t[i].first)
      return t[i - 1].second + (t[i].second - t[i - 1].second) * (sd1 - t[i - 1].first) / (t[i].first - t[i - 1].first);
  return t.back().second;
}

SeismicCoefficient asce7_cs(double sds, double sd1, double s1, double tl, double T, double r, double ie, bool exception_2) {
  const double ri = r / ie;
  SeismicCoefficient c{sds / ri, "SDS/(R/Ie)"};
  const double factor = exception_2 ? 1.5 : 1.0;
  const double cap = factor * (T <= tl ? sd1 / (T * ri) : sd1 * tl / (T * T * ri));
  const bool capped = !exception_2 || T > 1.5 * sd1 / sds;
  if (capped && cap < c.cs)
    c = {cap, std::string(exception_2 ? "1.5 " : "") + (T <= tl ? "SD1/(T R/Ie)" : "SD1 TL/(T^2 R/Ie)")};
  else if (exception_2 && !capped)
    c.governs += " (11.4.8 exception 2, T <= 1.5 TS)";
  const double floor1 = 0.044 * sds * ie;
  if (std::max(floor1, 0.01) > c.cs) c = floor1 >= 0.01 ? SeismicCoefficient{floor1, "0.044 SDS Ie"} : SeismicCoefficient{0.01, "0.01"};
  if (s1 >= 0.6 && 0.5 * s1 / ri > c.cs) c = {0.5 * s1 / ri, "0.5 S1/(R/Ie)"};
  return c;
}

double asce7_k(double T) { return T <= 0.5 ? 1.0 : T >= 2.5 ? 2.0 : 1.0 + (T - 0.5) / 2.0; }

void set_design_values(DesignInput& in, const Asce7MapValues& maps) {
  const Asce7SiteCoefficients c = asce7_site_coefficients(maps, true);
  in.exception_2 = c.exception_2;
  in.sds = c.sds;
  in.sd1 = c.sd1;
  in.s1 = maps.s1;
  in.tl = maps.tl;
}

DesignedBuilding design_elf(const DesignInput& in) {
  DesignedBuilding b;
  b.system = &system_row(in.system, in.where + " system");
  b.storey_height = heights_of(in);
  check_input(in);
  b.sds = in.sds;
  b.sd1 = in.sd1;
  const std::size_t n = b.storey_height.size();
  double z = 0;
  for (double h : b.storey_height) b.floor_level.push_back(z += h);
  b.hn = z;
  b.ta = b.system->ct * std::pow(b.hn, b.system->x);
  b.cu = asce7_cu(in.sd1);
  b.period = in.period > 0 ? in.period : b.cu * b.ta;
  b.period_rule = in.period > 0 ? "measured" : "Cu Ta";
  b.design_period = std::min(b.period, b.cu * b.ta);
  b.cs = asce7_cs(in.sds, in.sd1, in.s1, in.tl, b.design_period, b.system->r, in.ie, in.exception_2);
  const double unit = (in.unit_weight > 0 ? in.unit_weight : b.system->unit_weight) * 1e3;  // Pa
  b.floor_mass.assign(n, in.plan_area * unit / g);
  b.weight = g * b.floor_mass.front() * static_cast<double>(n);
  b.base_shear = b.cs.cs * b.weight;
  b.k = asce7_k(b.design_period);
  std::vector<double> whk(n);
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += whk[i] = g * b.floor_mass[i] * std::pow(b.floor_level[i], b.k);
  b.fx.resize(n);
  b.vx.resize(n);
  double above = 0;
  for (std::size_t i = 0; i < n; ++i) b.fx[i] = b.base_shear * whk[i] / sum;
  for (std::size_t i = n; i-- > 0;) b.vx[i] = above += b.fx[i];
  b.stiffness = scaled_to_period(b.floor_mass, b.vx, b.period);
  b.reference = &system_row(b.system->reference, in.where + " system");
  b.cs_reference = asce7_cs(in.sds, in.sd1, in.s1, in.tl, b.design_period, b.reference->r, in.ie, in.exception_2);
  b.strength_factor = strength_factor(in.level);
  b.overstrength = in.overstrength > 0 ? in.overstrength : b.reference->omega0;
  b.strength.resize(n);
  const double capacity = b.overstrength * b.strength_factor * b.cs_reference.cs * b.weight;
  for (std::size_t i = 0; i < n; ++i) b.strength[i] = capacity * b.vx[i] / b.base_shear;
  b.alpha = b.system->alpha;
  b.p_delta = in.p_delta;
  add_p_delta(b);
  return b;
}

std::vector<std::string> describe(const DesignedBuilding& b) {
  std::vector<std::string> out;
  out.push_back(fmt::format("{} ({}), {} storeys, hn {:.4g} m: Ta = {:.4g} s, Cu = {:.3g}, T = {:.4g} s ({}); Cs = {:.4g} "
                            "({}) at {:.4g} s, W = {:.4g} MN, V = {:.4g} MN, k = {:.4g}",
                            b.system->key, b.system->description, b.floor_mass.size(), b.hn, b.ta, b.cu, b.period,
                            b.period_rule, b.cs.cs, b.cs.governs, b.design_period, b.weight / 1e6, b.base_shear / 1e6, b.k));
  out.push_back(fmt::format("capacity = {:.3g} (overstrength) x {:.3g} (design level) x Cs {:.4g} of {} ({}) x W = {:.4g} MN, "
                            "over the storeys as Vx; alpha {:.3g}{}",
                            b.overstrength, b.strength_factor, b.cs_reference.cs, b.reference->key, b.cs_reference.governs,
                            b.strength.front() / 1e6, b.alpha, b.p_delta ? "; P-Delta in the storey springs" : ""));
  for (std::size_t i = 0; i < b.floor_mass.size(); ++i)
    out.push_back(fmt::format("storey {:>3}  level {:>7.3f} m  mass {:>10.4g} kg  Fx {:>10.4g} N  Vx {:>10.4g} N  "
                              "k {:>10.4g} N/m  Vy {:>10.4g} N",
                              i + 1, b.floor_level[i], b.floor_mass[i], b.fx[i], b.vx[i], b.model_stiffness[i],
                              b.model_strength[i]));
  return out;
}

}  // namespace pounding::inventory
