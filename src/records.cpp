// Placeholder until the ground-motion module lands (issue 3): the owner replaces this file.
#include "pounding/records.hpp"

#include <algorithm>
#include <cmath>

#include "pounding/error.hpp"

namespace pounding {

AccUnits parse_units(const std::string& name) {
  if (name == "g") return AccUnits::g;
  if (name == "m/s2") return AccUnits::m_s2;
  if (name == "cm/s2") return AccUnits::cm_s2;
  throw InputError("unknown units '" + name + "'", "--units", "use g, m/s2 or cm/s2");
}

double Record::pga() const {
  double p = 0;
  for (double a : acc) p = std::max(p, std::abs(a));
  return p;
}

Record read_record(const std::string& path, const ReadOptions&) {
  throw InputError("record readers are not built yet", path, "use the built-in example");
}

}  // namespace pounding
