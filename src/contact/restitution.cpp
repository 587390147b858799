// Velocity-dependent restitution e(v0): presets, polynomials and tables, their units and valid range.
#include "pounding/contact/restitution.hpp"

#include <algorithm>
#include <cmath>

#include <charconv>
#include <string>

namespace pounding::contact {

namespace {
// %g-like text of a number, without fmt (the contact layer formats nothing else: tests/arch/check_layers.py)
std::string g(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 6);
  return std::string(buf, r.ptr);
}
}  // namespace

double RestitutionCurve::raw(double v_mps) const {
  const double x = v_mps * per_mps;
  if (form == Form::polynomial) {
    double e = 0.0;  // Horner, highest power first
    for (auto it = coefficients.rbegin(); it != coefficients.rend(); ++it) e = e * x + *it;
    return e;
  }
  if (x <= table_v.front()) return table_e.front();
  if (x >= table_v.back()) return table_e.back();
  const auto hi = std::upper_bound(table_v.begin(), table_v.end(), x);
  const std::size_t j = static_cast<std::size_t>(hi - table_v.begin()), i = j - 1;
  const double t = (x - table_v[i]) / (table_v[j] - table_v[i]);
  return table_e[i] + t * (table_e[j] - table_e[i]);
}

double RestitutionCurve::operator()(double v_mps) const {
  const double e = raw(v_mps);
  if (!(e >= restitution_floor)) return restitution_floor;  // NaN too
  return std::min(e, 1.0);
}

bool RestitutionCurve::in_range(double v_mps) const {
  const double x = v_mps * per_mps;
  return x >= vmin && x <= vmax;
}

bool RestitutionCurve::clamped(double v_mps) const {
  const double e = raw(v_mps);
  return !(e >= restitution_floor && e <= 1.0);
}

std::string RestitutionCurve::describe() const {
  std::string what;
  if (form == Form::polynomial) {
    what = "e(v) =";
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
      const double c = coefficients[i];
      what += i == 0 ? " " + g(c) : std::string(c < 0 ? " - " : " + ") + g(std::abs(c));
      if (i == 1) what += " v";
      if (i > 1) what += " v^" + std::to_string(i);
    }
  } else {
    what = "e(v) table";
    for (std::size_t i = 0; i < table_v.size(); ++i) what += " " + g(table_v[i]) + ":" + g(table_e[i]);
  }
  std::string s = name + " (" + what + "), v in " + units + ", valid [" + g(vmin) + ", " + g(vmax) + "] " + units +
                  ", clamped to [" + g(restitution_floor) + ", 1]";
  if (!provisional.empty()) s += "; PROVISIONAL: " + provisional;
  return s;
}

double restitution_units_per_mps(std::string_view units) {
  if (units == "m/s") return 1.0;
  if (units == "cm/s") return 100.0;
  if (units == "mm/s") return 1000.0;
  return 0.0;
}

bool restitution_preset(std::string_view name, RestitutionCurve& out) {
  if (name == "lindsay2011") {
    out = RestitutionCurve{};
    out.form = RestitutionCurve::Form::polynomial;
    out.coefficients = {0.9979, -0.0838, 0.0011, -0.0012};
    out.units = "m/s";
    out.per_mps = 1.0;
    out.vmin = 0.99, out.vmax = 3.13;  // the drop tests: sqrt(2 g H), H = 50 to 500 mm
    out.name = "lindsay2011";
    out.provisional = "the bridge paper's eq. 15 lost a3's second digit and its sign (|a3| = 0.0012 or 0.0021, "
                      "either sign; seeds-models.md §1.7): a3 = -0.0012 taken, the readings agree within 4e-4 below "
                      "0.5 m/s and differ by up to 0.13 at 3.13 m/s; fitted at model scale (1/125 PVC bridge; "
                      "prototype velocities / 62.5)";
    return true;
  }
  return false;
}

namespace {
std::string range_problem(const RestitutionCurve& c) {
  if (!(c.vmin >= 0.0 && c.vmin < c.vmax)) return "valid range [" + g(c.vmin) + ", " + g(c.vmax) + "] is not 0 <= vmin < vmax";
  return "";
}
}  // namespace

std::string restitution_problem(const RestitutionCurve& c) {
  if (!(c.per_mps > 0.0)) return "unknown velocity units";
  if (c.form == RestitutionCurve::Form::polynomial) {
    if (c.coefficients.empty() || c.coefficients.size() > 8)
      return std::to_string(c.coefficients.size()) + " coefficients (give 1 to 8, the constant term first)";
    for (double v : c.coefficients)
      if (!std::isfinite(v)) return "a coefficient is not finite";
    return range_problem(c);
  }
  if (c.table_v.size() < 2 || c.table_v.size() != c.table_e.size())
    return std::to_string(c.table_v.size()) + " table points (give at least 2 pairs v:e)";
  for (std::size_t i = 0; i < c.table_v.size(); ++i) {
    if (!(std::isfinite(c.table_v[i]) && c.table_v[i] >= 0.0)) return "table velocity " + g(c.table_v[i]) + " is not >= 0";
    if (i > 0 && !(c.table_v[i] > c.table_v[i - 1])) return "table velocities are not strictly ascending";
    if (!(c.table_e[i] > 0.0 && c.table_e[i] <= 1.0)) return "table restitution " + g(c.table_e[i]) + " is not in (0, 1]";
  }
  return range_problem(c);
}

}  // namespace pounding::contact
