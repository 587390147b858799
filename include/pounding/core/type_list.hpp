#pragma once
// A list of types: the registries (contact::Laws, model::Hystereses) are one TypeList each, and everything kept
// per entry (names, traits, dispatch) is derived from it.
#include <cstddef>

namespace pounding {

template <class... Ts> struct TypeList {
  static constexpr std::size_t size = sizeof...(Ts);
};

}  // namespace pounding
