#pragma once
// Velocity-dependent restitution e(v) (issue 26 §3): a polynomial or a table in the approach velocity, with its
// velocity units and its valid (calibrated) range. The restitution an impact uses is e(v0) at the approach velocity
// latched at contact onset, clamped to [restitution_floor, 1] (the (0, 1] the damped laws accept); an impact whose
// v0 lies outside the valid range is an extrapolation, counted and reported by the caller.
// Preset lindsay2011: the bridge paper's eq. 15 (lindsay-2011-bridge-expansion-joints.txt §3.1; its text lost every
// digit "2" and minus sign: ../shared/research/seeds-models.md §1.7), e(x) = a3 x^3 + 0.0011 x^2 - 0.0838 x + 0.9979,
// x in m/s at MODEL scale (the 1/125-scale PVC bridge), calibrated by drop tests from 0.99 to 3.13 m/s. The digit and
// sign of a3 are lost (|a3| = 0.0012 or 0.0021, either sign): the preset takes a3 = -0.0012 and is PROVISIONAL;
// below 0.5 m/s every reading agrees within 4e-4 (e(0.5) = 0.956).
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace pounding::contact {

inline constexpr double restitution_floor = 0.01;  // the smallest e an impact gets (collide_e_min, the damped laws')

struct RestitutionCurve {
  enum class Form : std::uint8_t { polynomial, table };
  Form form = Form::polynomial;
  std::vector<double> coefficients;  // polynomial, constant term first: e(x) = c0 + c1 x + c2 x^2 + ...
  std::vector<double> table_v, table_e;  // table: v strictly ascending, linear between points, end values beyond
  std::string units = "m/s";         // the velocity units of the coefficients/table and of the valid range
  double per_mps = 1.0;              // curve units per m/s (m/s 1, cm/s 100, mm/s 1000)
  double vmin = 0.0, vmax = std::numeric_limits<double>::infinity();  // valid range, curve units
  std::string name;                  // the preset's name, or "polynomial" / "table"
  std::string provisional;           // non-empty: why the preset's numbers are uncertain

  double raw(double v_mps) const;         // e(v0) before clamping
  double operator()(double v_mps) const;  // clamped to [restitution_floor, 1]
  bool in_range(double v_mps) const;      // vmin <= v0 <= vmax (in the curve's units)
  bool clamped(double v_mps) const;       // raw(v0) outside [restitution_floor, 1]
  std::string describe() const;           // one line: form, formula or points, units, valid range, provisional
};

// Units of a curve's velocities: "m/s", "cm/s", "mm/s" -> curve units per m/s; 0 for an unknown name.
double restitution_units_per_mps(std::string_view units);
// The presets by name ("lindsay2011"); an empty name list entry is never returned. Unknown: returns false.
bool restitution_preset(std::string_view name, RestitutionCurve& out);
inline constexpr std::string_view restitution_preset_names = "lindsay2011";
// "" when the curve is usable, else what is wrong (coefficients count 1..8 and finite; table >= 2 points, v
// ascending and >= 0, e in (0, 1]; 0 <= vmin < vmax).
std::string restitution_problem(const RestitutionCurve& c);

}  // namespace pounding::contact
