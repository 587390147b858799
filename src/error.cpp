#include "pounding/error.hpp"

#include <cmath>
#include <fmt/format.h>

namespace pounding {

InputError::InputError(std::string what, std::string where, std::string fix)
    : std::runtime_error(fmt::format("{}, {}, {}", what, where, fix)),
      what_(std::move(what)), where_(std::move(where)), fix_(std::move(fix)) {}

void require_range(double value, double lo, double hi, const std::string& name, const std::string& range_text) {
  if (!std::isfinite(value) || value < lo || value > hi)
    throw InputError(fmt::format("{} = {} is out of range", name, value), name,
                     fmt::format("give a value in {}", range_text));
}

void require_positive(double value, const std::string& name) {
  if (!std::isfinite(value) || value <= 0.0)
    throw InputError(fmt::format("{} = {} must be positive and finite", name, value), name,
                     "give a value > 0");
}

}  // namespace pounding
