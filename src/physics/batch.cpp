// The stepper names, from the stepper registry. The steppers are in include/pounding/physics/steppers/, the
// batch driver in src/physics/run_batch.cpp, the value types' methods in src/kernel/batch.cpp.
#include "pounding/physics/batch.hpp"

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/physics/steppers/registry.hpp"

namespace pounding {

Stepper parse_stepper(std::string_view name) {
  for (std::size_t i = 0; i < kernel::stepper_names.size(); ++i)
    if (kernel::stepper_names[i] == name) return static_cast<Stepper>(i);
  throw InputError(fmt::format("unknown stepper '{}'", name), "stepper",
                   fmt::format("use one of: {}", stepper_names));
}
std::string_view to_string(Stepper s) {
  const auto i = static_cast<std::size_t>(s);
  return i < kernel::stepper_names.size() ? kernel::stepper_names[i] : "?";
}
}  // namespace pounding
