#pragma once
// One building of a pair: its fully resolved settings (the [structures] defaults overridden by its own
// [structures.building1] or [structures.building2] table) and the distributions a building may be given.
//
// Keys of a building table (every one optional; absent keys take the value of [structures]):
//   periods = [..]  or  period_min, period_max, period_step   the period grid (s), as in [structures]
//   period          a number (fixed, s), {lognormal = {median = 0.9, cov = 0.15}} or {uniform = {min, max}};
//                   not together with a grid. A fixed period is a grid of one point; a distribution is one
//                   "slot" whose T is drawn per sample (with the height rule: truncated to the periods the
//                   rule admits, [ct_lower height_min^x, ct_upper height_max^x], and an error when that keeps
//                   less than 50 % of the distribution)
//   height          m, fixed or a distribution; default the period-height rule (uniform on the rule interval)
//   mass            kg, fixed or a distribution; default the mass-index model m = mbar rho r^2 h
//   zeta            viscous damping ratio, fixed or a distribution
//   yield_coefficient  Cy = Vy / W, fixed or a distribution: fy = Cy m g (g = 9.80665 m/s^2); default the
//                   drift/ductility rule fy = k drift h / ductility (not together with drift or ductility)
//   alpha, hysteresis, aspect_ratios, rho_mean, rho_cov, mbar_mean, mbar_cov, mbar_min, mbar_max, drift,
//   ductility, height_min, height_max, ct_lower, ct_upper, height_exponent   as in [structures]
//   asce7_r, asce7_cd, asce7_ie, ec8_q, s2800_ru, s2800_cd, s2800_importance, storeys, storey_height   the
//                   building's code design factors (code_factors.hpp; storey_height may also be given in
//                   [structures], the default of both buildings)
//   model           "sdof" (today: one DOF at the effective height) or "shear" (a shear building of `storeys`
//                   floors, docs/architecture.md §2.7.1; also a [structures] default). For "shear":
//     storeys       given, or max(1, round(h / storey_height)) PER SAMPLE from its sampled height h
//     storey_height every storey this high (m, (0, 10]; sdof buildings keep [2, 10]); floor k at k storey_height
//     floor_mass    kg per floor (> 0): a number (every floor) or, with storeys given, an array of one per floor
//                   (bottom first); absent: the sampled total mass m split equally over the floors
//     storey_stiffness  N/m per storey (> 0), a number or one per storey as floor_mass; absent: stiffness_profile
//                   scaled to the sampled period T1
//                   (model::stiffness_for_period)
//     stiffness_profile  "uniform" | "shear" (also a [structures] default)
//     strength      the SDOF's rule per storey: drift/ductility -> every storey yields at the drift ratio
//                   theta_y = drift / ductility (Vy_i = k_i theta_y storey_height, the SDOF's u_y = drift h /
//                   ductility spread evenly over the height); yield_coefficient Cy -> Vy_i = Cy M g V_i / V_1 (the
//                   base shear Cy M g, upper storeys by the shear profile); hysteresis "elastic": no yield
//     damping       "rayleigh" (default): the building's zeta, Rayleigh on modes 1 and 2; "modal": classical modal
//                   damping C = M Phi diag(2 zeta_j omega_j / M_j) Phi' M, every mode the building's zeta or
//     modal_zeta    [zeta_1, zeta_2, ...] per mode from mode 1, the last repeating (with damping = "modal" only;
//                   each in [0, 0.5]; not with isolation). Both also [structures] defaults.
//     rayleigh_modes [i, j]: the two modes Rayleigh damping gives exactly zeta (default [1, 2]; two different whole
//                   numbers in [1, 200], either order; not with damping = "modal"). A sample with fewer than j storeys
//                   takes model::rayleigh_modes_for(i, j, n): j' = min(j, n), i' = min(i, j' - 1); one storey: the
//                   SDOF's c = 2 zeta sqrt(k m). Also a [structures] default, which an SDOF building of a mixed
//                   row or pair does not take (it keeps its zeta; refused only where every building is an SDOF).
//     isolation     {bearing = "linear", base_mass, k_eff, zeta_eff} | {bearing = "lead-rubber", base_mass, k1, k2,
//                   qd} | {bearing = "friction-pendulum", base_mass, radius, mu_slow, mu_fast, rate, u_y} |
//                   {bearing = "bouc-wen", base_mass, k1, k2, qd, a, beta, gamma, eta}: a base mass (default one
//                   floor's) on the bearing under the storeys (physics::IsolationSpec)
//     moat          {gap, law, stiffness, e}: rigid walls gap m either side of the isolated base (needs isolation)
//   One storey (storeys = 1, or a sampled height below 1.5 storey_height) with neither floor_mass nor
//   storey_stiffness is the SDOF of the same sample bit for bit.
//
// Distributions: lognormal {median, cov}: ln X ~ N(ln median, sigma^2), sigma^2 = ln(1 + cov^2) (cov is the
// CoV of X; 0 means fixed, at most 2); uniform {min, max} with min <= max. Every value given (a number, a median,
// a uniform's ends) must lie in the key's valid range, a range a real building can have, and every draw is
// truncated to it, exactly by inverse CDF (refused when that keeps less than 50 % of the probability):
//   period   [0.02, 20] s     0.02 s is stiffer than any real building (a one-storey masonry box is ~0.05 s);
//                             20 s is the response spectra's domain and above the tallest building's ~11 s
//                             (also the grid periods, [structures] periods / period_min / period_max)
//   height   [2, 1000] m      one low storey to above the tallest building (828 m); also height_min, height_max
//   mass     [1e3, 1e10] kg   a one-room shed (~10 t) with a decade's margin to 20x the tallest building (~5e8 kg)
//   zeta     [0, 0.5]         0 (undamped, an idealisation) to heavy supplemental damping (real buildings:
//                             0.01-0.1, with dampers up to ~0.3-0.4)
//   yield_coefficient Cy = Vy / W  [0.005, 5]  below the smallest code base shear (~0.01 W) with margin, up to a
//                             structure kept elastic under the strongest short-period spectra (~3-4 g).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "pounding/core/enum_names.hpp"
#include "pounding/model/modes.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/sampling/code_factors.hpp"

namespace pounding {

namespace config {
class TableReader;
}

enum class Hysteresis : std::uint8_t {
  bilinear,  // kinematic hardening with fy from drift/ductility (or Cy) and alpha (the paper's model)
  elastic,   // fy = +inf: linear elastic structures
};
inline constexpr EnumName<Hysteresis> hysteresis_names[] = {{Hysteresis::bilinear, "bilinear"},
                                                            {Hysteresis::elastic, "elastic"}};
constexpr const auto& enum_names(Hysteresis) { return hysteresis_names; }  // to_string(Hysteresis), enum_names.hpp

// The bearings a study's isolation table names (physics::IsolationSpec; one entry per bearing law).
inline constexpr EnumName<physics::Bearing> bearing_names[] = {
    {physics::Bearing::linear, "linear"},
    {physics::Bearing::lead_rubber, "lead-rubber"},
    {physics::Bearing::friction_pendulum, "friction-pendulum"},
    {physics::Bearing::bouc_wen, "bouc-wen"}};

// The structural model of a building (docs/architecture.md §2.7.1).
enum class StructureKind : std::uint8_t { sdof, shear };
inline constexpr EnumName<StructureKind> structure_kind_names[] = {{StructureKind::sdof, "sdof"},
                                                                   {StructureKind::shear, "shear"}};
constexpr const auto& enum_names(StructureKind) { return structure_kind_names; }

// A value or the law it is drawn from. Kind::none: the key is not given (its model's default applies).
struct Distribution {
  enum class Kind : std::uint8_t { none, fixed, lognormal, uniform };
  Kind kind = Kind::none;
  double value = 0;       // fixed: the value; lognormal: the median
  double cov = 0;         // lognormal: CoV of X
  double lo = 0, hi = 0;  // uniform: min, max

  static Distribution fixed(double v) { return {Kind::fixed, v, 0, 0, 0}; }
  static Distribution lognormal(double median, double cov) { return {Kind::lognormal, median, cov, 0, 0}; }
  static Distribution uniform(double min, double max) { return {Kind::uniform, 0, 0, min, max}; }

  bool given() const { return kind != Kind::none; }
  // Drawn per sample (a lognormal with cov > 0 or a uniform with min < max); otherwise one value.
  bool random() const;
  double sigma() const;  // lognormal: sqrt(ln(1 + cov^2))
  // The u-quantile (0 < u < 1) of the untruncated law; a fixed value for every u.
  double quantile(double u) const;
  double cdf(double x) const;
  double median() const;
  // "0.9 s", "lognormal(median 0.9 s, cov 0.15)", "uniform(0.8 s, 1 s)"; unit may be empty.
  std::string describe(std::string_view unit) const;
};

// A distribution restricted to [lo, hi] (lo >= 0, hi may be +inf), sampled exactly by inverse CDF:
// x = F^-1(F(lo) + u (F(hi) - F(lo))), through the upper tail when the interval lies in it (as the mass
// index, sampler.cpp). kept() is F(hi) - F(lo).
class Truncated {
 public:
  Truncated() = default;
  Truncated(const Distribution& d, double lo, double hi);
  // Parent lognormal ln X ~ N(mu, sigma^2) restricted to [lo, hi] (the mass index's law).
  static Truncated lognormal_mu_sigma(double mu, double sigma, double lo, double hi);
  double sample(double u) const;
  double kept() const { return kept_; }

 private:
  Distribution d_;
  double lo_ = 0, hi_ = 0, mu_ = 0, sigma_ = 0;
  double pa_ = 0, pb_ = 1, qa_ = 1, qb_ = 0;  // Phi(za), Phi(zb), 1 - Phi(za), 1 - Phi(zb)
  bool upper_tail_ = false, lognormal_ = false;
  double kept_ = 1;
  void set_lognormal(double mu, double sigma, double lo, double hi);
};

// lo + i step for i = 0..n-1 where n = round((hi - lo)/step) + 1; throws InputError (naming `where`) when
// (hi - lo)/step is not an integer to 1e-9 or the grid is empty.
std::vector<double> make_period_grid(double lo, double hi, double step, const std::string& where = "periods");

// Height interval for period T: [max(h_min, (T/ct_upper)^(1/x)), min(h_max, (T/ct_lower)^(1/x))].
struct HeightInterval {
  double lo = 0.0, hi = 0.0;
};

// Valid ranges of the distribution keys (the truncation of their draws): what a real building can have (the
// top of this header says why).
inline constexpr double min_period = 0.02, max_period = 20.0, min_height = 2.0, max_height = 1000.0;
inline constexpr double min_mass = 1e3, max_mass = 1e10, max_zeta = 0.5, min_cy = 0.005, max_cy = 5.0;

// One building's resolved settings. `resolved` false: not yet resolved -- StructureModel::building(b) then
// takes every value from the shared [structures] fields (a model built in code).
struct BuildingModel {
  bool resolved = false;
  std::vector<double> periods;  // the grid (s); a fixed period: {T}; a period distribution: {its median}
  Distribution period;          // none: the grid; fixed: one point; random: one slot drawn per sample
  Distribution height;          // none: the period-height rule
  Distribution mass;            // none: the mass-index model
  Distribution zeta;            // always given (fixed: [structures] zeta)
  Distribution yield_coefficient;  // none: drift/ductility
  std::vector<double> aspect_ratios;
  double rho_mean = 0, rho_cov = 0, mbar_mean = 0, mbar_cov = 0, mbar_min = 0, mbar_max = 0;
  Hysteresis hysteresis = Hysteresis::bilinear;
  double drift = 0, ductility = 0, alpha = 0;
  double height_min = 0, height_max = 0, ct_lower = 0, ct_upper = 0, height_exponent = 0;
  bool rule_explicit = false;  // ct_lower, ct_upper or height_exponent set in this table or [structures]
  CodeFactors code;            // the code design factors of this table (code_factors.hpp)
  // Base isolation of a shear building ([structures.buildingK] isolation = {...}, physics::IsolationSpec): given
  // when `isolated`; base_mass 0: one floor's mass per sample. A moat ({gap, law, stiffness, e}) needs isolation:
  // two walls `moat_gap` m either side of the base; law empty: [contact] law; stiffness 0: equivalent spheres of
  // the base mass with itself; e < 0: [contact] e.
  bool isolated = false;
  physics::IsolationSpec isolation;
  bool moat = false;
  double moat_gap = 0.0, moat_stiffness = 0.0, moat_e = -1.0;
  std::string moat_law;
  // The structural model (the top of this header): sdof, or a shear building with these numbers (0: absent).
  StructureKind kind = StructureKind::sdof;
  // floor_mass (kg), storey_stiffness (N/m): empty when absent; one value (every floor / storey) or, with storeys
  // given, one per floor / storey from the bottom (a building that is not uniform)
  std::vector<double> floor_mass, storey_stiffness;
  std::vector<double> storey_yield;  // N, the same way (empty: drift/ductility or yield_coefficient)
  // storey_height as an array (a shear building with storeys given): one height per storey from the bottom, floor k
  // at the sum of the first k; code.storey_height is then their mean (the code rules' storey count). Empty: every
  // storey storey_height() high.
  std::vector<double> storey_heights;
  model::StiffnessProfile profile = model::StiffnessProfile::uniform;
  // Damping of a shear building: Rayleigh on modes 1, 2 (false) or classical modal damping (modal_zeta per mode
  // from 1, the last repeating; empty: every mode the sampled zeta).
  bool modal_damping = false;
  std::vector<double> modal_zeta;
  int rayleigh_i = 1, rayleigh_j = 2;  // rayleigh_modes (i < j); a sample of n storeys: model::rayleigh_modes_for
  bool rayleigh_default() const { return rayleigh_i == 1 && rayleigh_j == 2; }
  // "Rayleigh damping on modes 1 and 2", "classical modal damping, zeta 0.02, 0.03 (then 0.03)", ...
  std::string damping_text() const;

  bool shear() const { return kind == StructureKind::shear; }
  // The storey height (m): storey_height given here or in [structures], else 3.2.
  double storey_height() const { return code.storey_height > 0 ? code.storey_height : default_storey_height; }
  // Storeys of a sample of height h: `storeys` given, else max(1, round(h / storey_height())).
  int storeys_at(double h) const;
  // "linear bearing k_eff 1e+06 N/m, zeta_eff 0; base 300000 kg", "walls 0.1 m either side ..." ("" when absent)
  std::string isolation_text() const;
  std::string moat_text() const;

  std::size_t slots() const { return periods.size(); }
  bool height_from_rule() const { return !height.given(); }
  bool mass_index_model() const { return !mass.given(); }
  // The period range where the rule interval is non-empty: [ct_lower height_min^x, ct_upper height_max^x].
  HeightInterval rule_periods() const;
  // The rule interval at T; lo > hi when empty.
  HeightInterval rule_heights(double T) const;
  // Descriptions for the settings: "lognormal(median 0.9 s, cov 0.15)", "grid of 11 periods (1 s to 1.5 s)",
  // "period-height rule", "mass-index model", "drift 0.02 / ductility 6", "Cy 0.1" ...
  std::string period_text() const;
  std::string height_text() const;
  std::string mass_text() const;
  std::string zeta_text() const;
  std::string yield_text() const;
};

// A distribution key: a number, {lognormal = {median, cov}} or {uniform = {min, max}}. `name` is the table
// holding the key ("structures.building1"), for errors inside it ("[structures.building1.period.lognormal].cov");
// `where` is the key's location. Only the shape and types are checked here (ranges: validate_building).
Distribution parse_distribution(const toml::node& n, std::string_view key, const std::string& file,
                                const std::string& name, const std::string& where);

using WhereFn = std::function<std::string(std::string_view key)>;

// Reads one building table over `defaults` (the building [structures] makes); t may be null (the table is
// absent: the defaults). name: "structures.building1". Keys absent from the table point at `fallback`
// (their [structures] key) in errors. Validates the result (validate_building).
// The value of key `hysteresis` of a table (InputError naming file:line and the known models), or nothing.
std::optional<Hysteresis> read_hysteresis(const toml::node* n, const std::string& where);

BuildingModel parse_building(const toml::table* t, const std::string& file, const std::string& name,
                             BuildingModel defaults, const WhereFn& fallback);

// Checks every value and cross-condition of one resolved building (ranges, the period grid, the rule interval
// of every grid period, the truncations, a given height against an explicit rule); where(key) locates a key.
void validate_building(const BuildingModel& b, const WhereFn& where);

// model and stiffness_profile of a table ([structures] or a building's) over b's values: InputError for unknown names.
void read_shear_defaults(config::TableReader& r, BuildingModel& b);

// floor_mass / storey_stiffness / a storey_height below 2 m given to an SDOF building: InputError at where(key).
void check_shear_keys(const BuildingModel& b, const WhereFn& where);

// storey_height = [h1, h2, ...] in a building's table (src/sampling/storey_heights.cpp): read_storey_heights sets
// storey_heights (more than one value) and code.storey_height = their mean; check_storey_heights refuses them for an
// SDOF building, without storeys or with another count (InputError at where("storey_height")).
void read_storey_heights(config::TableReader& r, BuildingModel& b);
void check_storey_heights(const BuildingModel& b, const WhereFn& where);

// The rule interval at T, or InputError naming T and both bounds (where) when it is empty.
HeightInterval checked_rule_heights(const BuildingModel& b, double T, const std::string& where);

}  // namespace pounding
