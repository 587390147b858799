#pragma once
// One problem found by a validation (a batch, a system's topology, a study's values): the three parts of
// InputError (core/error.hpp). Validations list problems; the caller raises the first as one InputError
// (physics::throw_first), so layers that may not throw for user input (kernel, contact, model) can still
// say what is wrong, where and how to fix it.
#include <string>

namespace pounding {

struct Problem {
  std::string what, where, fix;
  bool operator==(const Problem&) const = default;
};

}  // namespace pounding
