#pragma once
// The registered hysteresis models (architecture.md 2.5.2; docs/runner-design.md section 5), and what each tells the
// driver through traits instead of value tests in the driver (STYLE.md "A model tells the driver what it can do"; D9):
//   name, Spec, params(Spec): the model's key, description and per-lane constants.
//   stays_elastic(spec, peak_abs_deformation, margin): the spring stays on its initial elastic branch when its
//     peak |deformation| is `peak_abs_deformation` (a response scaled from a linear run stays exact only then);
//     a model without an elastic range answers false.
//   unscaled_equivalent(spec, f): the Spec' with R(f w; spec) = f R(w; spec'), so that the response to f ag is f
//     times the response to ag of spec' (the IDA's bisection runs the record unscaled); std::nullopt when no
//     such Spec exists (the record must then be scaled).
//   pack(Spec) -> SpringSpec, unpack(SpringSpec) -> Spec: the batch's description of one spring
//     (model/hysteresis/spring_spec.hpp), its numbers in SpringSpec::p (at most SpringSpec::numbers: more do not compile).
//   roles: where the model may stand (storey, isolator, link); a spring elsewhere is refused before a run.
//   lane_stepper: whether the lane steppers (Newmark, RK4: they need the model's tangent) run it.
//   load(SpringSpec, d0, rows) -> f0: the system stepper's rows of the spring (model/hysteresis/spring_spec.hpp's
//     SpringRows: its numbers and state) and its force at rest in the deformation d0; stored_energy(rows, d, f):
//     its recoverable energy at deformation d and force f.
//   step<WithEnergy, V>(rows, fo, d, dd, rate, x) -> f: the system stepper's update of one spring over a step (rows
//     r.get(slot) / r.set(slot, v) / r.lane(slot, l), the dissipation in x); fast_path: the driver may run the
//     spring in its straight bilinear loop (bilinear only: the stick path and the loop without dispatch).
//   problems(SpringSpec, bad): the model's own input checks; each failure is bad(field, message with {} for the
//     values, fix, values...) (physics/validate.cpp formats it; k, fy, alpha are the driver's checks).
// A spring's `law` (model::Spring) is its model's index in Hystereses (law_of<H>); visit_hysteresis(law, f) calls
// f.template operator()<H>() for it. A new model is its header (model/hysteresis/<model>.hpp, with the functions
// the StructureModel calls and these traits) and one entry in Hystereses: no switch elsewhere names a model.
#include <array>
#include <concepts>
#include <cstddef>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>

#include "pounding/core/type_list.hpp"
#include "pounding/kernel/lane.hpp"
#include "pounding/model/hysteresis/bilinear_kinematic.hpp"
#include "pounding/model/hysteresis/bouc_wen.hpp"
#include "pounding/model/hysteresis/bridge_links.hpp"
#include "pounding/model/hysteresis/friction_pendulum.hpp"
#include "pounding/model/hysteresis/spring_spec.hpp"

namespace pounding::model {

namespace detail {
// A stand-in for the problems trait's callback in the concept below.
struct AnyBad {
  template <class... A> void operator()(A&&...) const {}
};
}  // namespace detail

template <class H>
concept Hysteresis = requires(const typename H::Spec& s, const SpringSpec& ss, double x) {
  { H::name } -> std::convertible_to<std::string_view>;
  { H::params(s) } -> std::same_as<typename H::template Params<double>>;
  { H::stays_elastic(s, x, x) } -> std::same_as<bool>;
  { H::unscaled_equivalent(s, x) } -> std::same_as<std::optional<typename H::Spec>>;
  { H::pack(s) } -> std::same_as<SpringSpec>;
  { H::unpack(ss) } -> std::same_as<typename H::Spec>;
  { H::roles } -> std::convertible_to<Roles>;
  { H::lane_stepper } -> std::convertible_to<bool>;
  H::problems(ss, detail::AnyBad{});
  { H::load(ss, x, std::declval<SpringRows&>()) } -> std::same_as<double>;
  { H::stored_energy(std::declval<const SpringRows&>(), x, x) } -> std::same_as<double>;
  { H::fast_path } -> std::convertible_to<bool>;
};

// THE list of hysteresis models: a spring's `law` is its model's index here. Laws other than bilinear run in the
// system stepper only (lane_stepper); a hinge bearing is bilinear (k0, F_y, alpha) as a link spring.
using Hystereses = TypeList<BilinearKinematic, BoucWen, FrictionPendulum, TensionGap, CompressionGap, HyperbolicGap, QHyst>;

template <class... Hs> constexpr bool all_hystereses(TypeList<Hs...>) { return (Hysteresis<Hs> && ...); }
static_assert(all_hystereses(Hystereses{}),
              "every registered hysteresis model satisfies model::Hysteresis: a name, Spec, params(Spec), "
              "stays_elastic(Spec, peak, margin), unscaled_equivalent(Spec, f), pack, unpack, roles, lane_stepper, "
              "problems, load and stored_energy (model/hysteresis/registry.hpp)");

namespace detail {
template <class H, class... Hs> consteval int index_in(TypeList<Hs...>) {
  int i = 0, at = -1;
  ((std::is_same_v<H, Hs> ? (at = i, ++i) : ++i), ...);
  return at;
}
}  // namespace detail
// The law of model H (its index in Hystereses); a model outside the list does not compile.
template <class H> inline constexpr int law_of = detail::index_in<H>(Hystereses{});

// f.template operator()<H>() for the model of `law`, the list's order (bilinear first); a law outside the list
// calls nothing and returns R{}. Always inlined: the system stepper dispatches through it per spring and step.
template <class F, class... Hs> POUNDING_INLINE decltype(auto) visit_hysteresis(int law, F&& f, TypeList<Hs...>) {
  using R = decltype(f.template operator()<BilinearKinematic>());
  int i = 0;
  if constexpr (std::is_void_v<R>) {
    ((i++ == law ? (f.template operator()<Hs>(), true) : false) || ...);
  } else {
    R r{};
    ((i++ == law ? (r = f.template operator()<Hs>(), true) : false) || ...);
    return r;
  }
}
template <class F> POUNDING_INLINE decltype(auto) visit_hysteresis(int law, F&& f) {
  return visit_hysteresis(law, std::forward<F>(f), Hystereses{});
}
inline constexpr bool is_law(int law) { return law >= 0 && law < static_cast<int>(Hystereses::size); }

template <class... Hs> constexpr auto hysteresis_names_of(TypeList<Hs...>) {
  return std::array<std::string_view, sizeof...(Hs)>{Hs::name...};
}
// The models' names in the list's order; hysteresis_name(law): "" for a law outside the list.
inline constexpr auto hysteresis_names = hysteresis_names_of(Hystereses{});
inline constexpr std::string_view hysteresis_name(int law) {
  return is_law(law) ? hysteresis_names[static_cast<std::size_t>(law)] : std::string_view{};
}
// The law of the model called `name`, -1 when none is.
inline constexpr int law_named(std::string_view name) {
  for (std::size_t i = 0; i < hysteresis_names.size(); ++i)
    if (hysteresis_names[i] == name) return static_cast<int>(i);
  return -1;
}
template <class... Hs> constexpr auto roles_of(TypeList<Hs...>) { return std::array<Roles, sizeof...(Hs)>{Hs::roles...}; }
inline constexpr auto hysteresis_roles = roles_of(Hystereses{});
template <class... Hs> constexpr auto lane_steppers_of(TypeList<Hs...>) {
  return std::array<bool, sizeof...(Hs)>{Hs::lane_stepper...};
}
inline constexpr auto hysteresis_lane_steppers = lane_steppers_of(Hystereses{});
template <class... Hs> constexpr auto fast_paths_of(TypeList<Hs...>) { return std::array<bool, sizeof...(Hs)>{Hs::fast_path...}; }
inline constexpr auto hysteresis_fast_paths = fast_paths_of(Hystereses{});
inline constexpr bool fast_path(int law) { return is_law(law) && hysteresis_fast_paths[static_cast<std::size_t>(law)]; }
// Traits by law (false outside the list).
inline constexpr bool runs_on_lane_stepper(int law) {
  return is_law(law) && hysteresis_lane_steppers[static_cast<std::size_t>(law)];
}

// stays_elastic asked of a spring of the batch by its law (its Spec unpacked): false outside the list.
inline bool stays_elastic(int law, const SpringSpec& s, double peak, double margin) {
  return visit_hysteresis(law, [&]<class H>() { return H::stays_elastic(H::unpack(s), peak, margin); });
}

}  // namespace pounding::model
