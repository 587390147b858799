#pragma once
// A building's code design factors (issue 23 item 5): what turns a design spectrum into the code's design
// displacement of that building (analysis/code_displacement.hpp) and decides whether Standard 2800's 0.005 h rule
// applies. Keys of [structures.building1] / [structures.building2], each optional (0 / absent: not given):
//   asce7_r, asce7_cd   ASCE 7-16 Table 12.2-1 response modification coefficient R, [1, 8], and deflection
//                       amplification factor Cd, [1, 6.5] (both or neither)
//   asce7_ie            ASCE 7-16 Table 1.5-2 seismic importance factor Ie: 1.0, 1.25 or 1.5 (default 1.0)
//   ec8_q               EN 1998-1 behaviour factor q, [1, 8] (the displacement behaviour factor qd = q, 4.3.4)
//   s2800_ru, s2800_cd  Standard 2800 (4th ed.) table 3-4 behaviour factor Ru, [1, 8], and deflection
//                       amplification factor Cd, [1, 6.5] (both or neither)
//   s2800_importance    Standard 2800 importance factor I: 0.8, 1.0, 1.2 or 1.4 (default: [target_spectrum]
//                       importance for a Standard 2800 target, else not known); 1.2 and 1.4 (high, very high
//                       importance) put the building outside the 0.005 h rule
//   storeys             number of storeys above the base, integer [1, 200] (default: round(height /
//                       storey_height), at least 1, from the building's median height)
//   storey_height       m, [2, 10] (a shear model's (0, 10], building.hpp), default 3.2: the default of storeys
//                       and the storey height of a shear building (building.hpp)
#include <string>

#include <toml++/toml.h>

namespace pounding {

struct CodeFactors {
  double asce7_r = 0, asce7_cd = 0, asce7_ie = 0;
  double ec8_q = 0;
  double s2800_ru = 0, s2800_cd = 0, s2800_importance = 0;
  long storeys = 0;
  double storey_height = 0;  // 0: not given (default_storey_height)
};

inline constexpr double default_storey_height = 3.2;  // m
// The keys above, for a building table's list of known keys.
inline constexpr const char* code_factor_keys =
    "asce7_r, asce7_cd, asce7_ie, ec8_q, s2800_ru, s2800_cd, s2800_importance, storeys, storey_height";

// Reads and checks the keys of one building table (t may be null: none given); InputError naming file:line and
// the key, with the allowed values. Unknown keys are the building table's own finish()'s business.
CodeFactors read_code_factors(const toml::table* t, const std::string& file, const std::string& name);

}  // namespace pounding
