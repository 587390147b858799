// Intensity measures of a record (see intensity.hpp).
#include "pounding/motion/intensity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pounding/core/error.hpp"
#include "pounding/motion/spectrum.hpp"

namespace pounding {

ImMeasure parse_im_measure(const std::string& name) {
  if (auto m = parse_enum(im_measure_names, name)) return *m;
  throw InputError(fmt::format("unknown intensity measure '{}'", escaped_excerpt(name)), "--measure",
                   "use " + enum_name_list(im_measure_names, " or "));
}

namespace {

void validate_periods(const IntensityMeasure& im) {
  const std::string name(to_string(im.measure));
  for (double t : im.periods)
    if (!(t > 0) || !std::isfinite(t))
      throw InputError(fmt::format("{} period {} is not > 0", name, t), "--period", "give periods in s, > 0");
  if (im.measure == ImMeasure::sa && im.periods.size() != 1)
    throw InputError(fmt::format("Sa takes exactly one period, got {}", im.periods.size()), "--period",
                     "give one period, e.g. --period 1.0 (Sa_avg averages over several)");
  if (im.measure == ImMeasure::sa_avg) {
    std::vector<double> p = im.periods;
    std::sort(p.begin(), p.end());
    if (std::adjacent_find(p.begin(), p.end()) != p.end())
      throw InputError("Sa_avg periods repeat a period", "--periods", "give each period once");
    if (p.size() < 2)
      throw InputError(fmt::format("Sa_avg needs at least 2 periods, got {}", p.size()), "--periods",
                       "give e.g. --periods 0.2,0.5,1,2 (or use Sa for one period)");
  }
  if ((im.measure == ImMeasure::pga || im.measure == ImMeasure::pgv) && !im.periods.empty())
    throw InputError(fmt::format("{} takes no period", name), "--period", "drop --period/--periods for " + name);
}

double sa_g(const Record& rec, double period, double zeta) {
  const double w = 2.0 * std::numbers::pi / period;
  return w * w * peak_displacement(rec, period, zeta) / g_accel;
}

}  // namespace

void validate(const IntensityMeasure& im) {
  if (static_cast<std::size_t>(im.measure) >= std::size(im_measure_names))
    throw InputError("intensity measure out of range", "--measure", "use " + enum_name_list(im_measure_names, " or "));
  validate_periods(im);
  if (!(im.damping >= 0 && im.damping < 1))
    throw InputError(fmt::format("damping ratio {} is outside [0, 1)", im.damping), "--damping", "give e.g. 0.05");
}

double pgv(const Record& rec) { return measure(rec).pgv; }

double intensity(const Record& rec, const IntensityMeasure& im) {
  validate(im);
  if (!(rec.dt > 0) || rec.acc.empty())
    throw InputError("empty record", rec.source.empty() ? rec.name : rec.source, "read a record first");
  switch (im.measure) {
    case ImMeasure::pga: return rec.pga() / g_accel;
    case ImMeasure::pgv: return pgv(rec);
    case ImMeasure::sa: return sa_g(rec, im.periods.front(), im.damping);
    case ImMeasure::sa_avg: break;
  }
  double sum_ln = 0;  // a zero Sa gives ln 0 = -inf and the geometric mean 0, as it should
  for (double t : im.periods) sum_ln += std::log(sa_g(rec, t, im.damping));
  return std::exp(sum_ln / static_cast<double>(im.periods.size()));
}

const char* im_units(ImMeasure measure) { return measure == ImMeasure::pgv ? "m/s" : "g"; }

std::string describe(const IntensityMeasure& im) {
  const char* units = im_units(im.measure);
  switch (im.measure) {
    case ImMeasure::pga: return fmt::format("PGA, {}", units);
    case ImMeasure::pgv: return fmt::format("PGV, {}", units);
    case ImMeasure::sa:
      return fmt::format("Sa({:.2f} s, {:g} % damping), {}", im.periods.empty() ? 0.0 : im.periods.front(),
                         100 * im.damping, units);
    case ImMeasure::sa_avg: break;
  }
  const auto [lo, hi] = std::minmax_element(im.periods.begin(), im.periods.end());
  return fmt::format("Sa_avg over {} periods {:.2f}-{:.2f} s (geometric mean of Sa, {:g} % damping), {}",
                     im.periods.size(), im.periods.empty() ? 0.0 : *lo, im.periods.empty() ? 0.0 : *hi,
                     100 * im.damping, units);
}

double scale_to_level(double im, double level) {
  if (!(im > 0) || !std::isfinite(im))
    throw InputError(fmt::format("intensity {} is not > 0", im), "scale_to_level",
                     "a record with zero intensity cannot be scaled to a level");
  if (!(level > 0) || !std::isfinite(level))
    throw InputError(fmt::format("target level {} is not > 0", level), "scale_to_level", "give a level > 0");
  return level / im;
}

}  // namespace pounding
