#pragma once
// Intensity measures of one record (issue 14 part 1): the IM a fragility is conditioned on and a record is
// scaled to. Every measure here is linear in the record's amplitude, so scaling a record by f scales its IM
// by f (scale_to_level is then exact).
//   PGA     max |ag|, in g
//   PGV     max |v|, v the exact integral of the piecewise-linear ag (trapezoid; records.hpp measure()), m/s
//   Sa      pseudo-spectral acceleration w^2 SD(T, zeta) / g at one period (spectrum.hpp, exact Nigam-Jennings
//           recurrence, peak sampled within 0.3 %)
//   Sa_avg  the geometric mean of Sa over n >= 2 periods (Eads, Miranda & Lignos 2015, EESD 44(12)):
//           exp(mean_j ln Sa(T_j)); research note fragility-and-codes.md 1.5
#include <cstdint>
#include <string>
#include <vector>

#include "pounding/core/enum_names.hpp"
#include "pounding/motion/records.hpp"

namespace pounding {

enum class ImMeasure : std::uint8_t { pga, pgv, sa, sa_avg };
inline constexpr EnumName<ImMeasure> im_measure_names[] = {
    {ImMeasure::pga, "PGA"}, {ImMeasure::pgv, "PGV"}, {ImMeasure::sa, "Sa"}, {ImMeasure::sa_avg, "Sa_avg"}};
constexpr const auto& enum_names(ImMeasure) { return im_measure_names; }  // to_string(ImMeasure)
// "PGA", "PGV", "Sa", "Sa_avg"; InputError (where "--measure") listing them otherwise.
ImMeasure parse_im_measure(const std::string& name);

struct IntensityMeasure {
  ImMeasure measure = ImMeasure::sa;
  std::vector<double> periods;  // s. Sa: exactly one (> 0); Sa_avg: >= 2 distinct, > 0; PGA, PGV: empty
  double damping = 0.05;        // 0 <= damping < 1 (Sa, Sa_avg)
};

// Throws InputError naming what is wrong (the measure's period count, a period, the damping).
void validate(const IntensityMeasure& im);
// The IM of `rec` in im_units(im.measure): g for PGA, Sa, Sa_avg; m/s for PGV. Validates `im` and the record
// (non-empty, dt > 0).
double intensity(const Record& rec, const IntensityMeasure& im);
const char* im_units(ImMeasure measure);  // "g" or "m/s"
// One line, e.g. "Sa(1.00 s, 5 % damping), g" or
// "Sa_avg over 8 periods 0.20-2.00 s (geometric mean of Sa, 5 % damping), g".
std::string describe(const IntensityMeasure& im);
// Peak |v| in m/s, v(0) = 0 and v exact for the piecewise-linear acceleration (measure(rec).pgv).
double pgv(const Record& rec);
// The amplitude factor that brings a record of intensity `im` to `level` (every measure above is linear in
// amplitude): level / im. InputError unless both are positive and finite.
double scale_to_level(double im, double level);

}  // namespace pounding
