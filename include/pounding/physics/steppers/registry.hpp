#pragma once
// The registered steppers, in the order of the Stepper enum (kernel.hpp); names and dispatch come from here.
#include <array>
#include <string_view>

#include "pounding/contact/registry.hpp"
#include "pounding/physics/steppers/central_difference.hpp"
#include "pounding/physics/steppers/newmark.hpp"
#include "pounding/physics/steppers/nigam_jennings.hpp"
#include "pounding/physics/steppers/rk4.hpp"

namespace pounding::kernel {

using Steppers = TypeList<CentralDifference, Newmark, Rk4, NigamJennings>;

template <class... Ss> constexpr auto stepper_names_of(TypeList<Ss...>) {
  return std::array<std::string_view, sizeof...(Ss)>{Ss::name...};
}
inline constexpr auto stepper_names = stepper_names_of(Steppers{});
static_assert(stepper_names[static_cast<std::size_t>(Stepper::nigam_jennings)] == "nigam-jennings");

// f.template operator()<S>() for the stepper registered as `id`.
template <class F, class... Ss> void visit_stepper(Stepper id, F&& f, TypeList<Ss...>) {
  std::size_t i = 0;
  const auto want = static_cast<std::size_t>(id);
  ((i++ == want ? (f.template operator()<Ss>(), true) : false) || ...);
}
template <class F> void visit_stepper(Stepper id, F&& f) { visit_stepper(id, static_cast<F&&>(f), Steppers{}); }

}  // namespace pounding::kernel
