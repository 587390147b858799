// The resolution guard's summary line (physics/resolution.hpp), shared by the study run output and the report.
#include "pounding/physics/resolution.hpp"

#include <fmt/format.h>

namespace pounding::physics {

namespace {
double floor3(double x) {  // rounded down to 3 significant digits (a step cap must not round up)
  const double q = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  return std::floor(x / q) * q;
}
}  // namespace

std::string describe(const CoarseSummary& c) {
  std::string s = fmt::format("coarse: {} analyses (max h·ω_c {}, limit {})", c.coarse,
                              std::isnan(c.hw_max) ? std::string("-") : fmt::format("{:.3g}", c.hw_max),
                              std::isinf(c.limit) ? std::string("none") : fmt::format("{:.3g}", c.limit));
  if (c.coarse == 0) return s;
  s += fmt::format("; {} the statistics ([analysis] coarse = \"{}\")", c.kept ? "kept in" : "excluded from",
                   c.kept ? "keep" : "exclude");
  if (std::isfinite(c.limit) && c.limit > 0 && c.hw_max > 0)
    s += fmt::format(". To bring the largest h·ω_c under the limit: [analysis] substeps = {} (or max_dt = {:.3g} s) "
                     "-- an estimate: the peak penetration, and with it the Hertz tangent, changes with the step",
                     substeps_for_limit(c.substeps_at_max, c.hw_max, c.limit), floor3(c.h_at_max * c.limit / c.hw_max));
  return s;
}

}  // namespace pounding::physics
