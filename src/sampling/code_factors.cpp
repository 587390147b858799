// A building's code design factors: see code_factors.hpp.
#include "pounding/sampling/code_factors.hpp"

#include <cmath>
#include <initializer_list>

#include <fmt/format.h>

#include "pounding/config/config.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

namespace {

double one_of(config::TableReader& r, const char* key, std::initializer_list<double> values, const char* text) {
  const double v = r.number(key, 0.0, -1e300, 1e300, text);
  if (!r.get(key)) return 0.0;
  for (double x : values)
    if (std::abs(v - x) < 1e-9) return x;
  throw InputError(fmt::format("{} = {:g} is not one of {}", key, v, text), r.where(key), fmt::format("give {}", text));
}

void both_or_neither(config::TableReader& r, const char* a, const char* b, const char* what) {
  if ((r.get(a) != nullptr) != (r.get(b) != nullptr)) {
    const char* missing = r.get(a) ? b : a;
    throw InputError(fmt::format("{} without {}", r.get(a) ? a : b, missing), r.where(r.get(a) ? a : b),
                     fmt::format("give both {} and {} ({})", a, b, what));
  }
}

}  // namespace

CodeFactors read_code_factors(const toml::table* t, const std::string& file, const std::string& name) {
  CodeFactors f;
  if (!t) return f;
  config::TableReader r(t, file, name);
  const auto number = [&](const char* key, double lo, double hi, const char* range) {
    return r.get(key) ? r.number(key, 0.0, lo, hi, range) : 0.0;
  };
  f.asce7_r = number("asce7_r", 1.0, 8.0, "[1, 8] (ASCE 7-16 Table 12.2-1 R)");
  f.asce7_cd = number("asce7_cd", 1.0, 6.5, "[1, 6.5] (ASCE 7-16 Table 12.2-1 Cd)");
  both_or_neither(r, "asce7_r", "asce7_cd", "ASCE 7-16 Table 12.2-1, the building's seismic force-resisting system");
  f.asce7_ie = one_of(r, "asce7_ie", {1.0, 1.25, 1.5}, "1.0, 1.25 or 1.5 (ASCE 7-16 Table 1.5-2 Ie)");
  f.ec8_q = number("ec8_q", 1.0, 8.0, "[1, 8] (EN 1998-1 behaviour factor q)");
  f.s2800_ru = number("s2800_ru", 1.0, 8.0, "[1, 8] (Standard 2800 table 3-4 Ru)");
  f.s2800_cd = number("s2800_cd", 1.0, 6.5, "[1, 6.5] (Standard 2800 table 3-4 Cd)");
  both_or_neither(r, "s2800_ru", "s2800_cd", "Standard 2800 table 3-4, the building's lateral-load system");
  f.s2800_importance = one_of(r, "s2800_importance", {0.8, 1.0, 1.2, 1.4}, "0.8, 1.0, 1.2 or 1.4 (Standard 2800 I)");
  if (r.get("storeys")) f.storeys = r.integer("storeys", 0, 1, 200);
  // the registry's range, [0.01, 10] m; an array (one per storey, a shear building's table): parse_building's
  if (const toml::node* n = r.get("storey_height"); n && !n->is_array()) f.storey_height = r.number("storey_height", 0.0);
  return f;
}

}  // namespace pounding
