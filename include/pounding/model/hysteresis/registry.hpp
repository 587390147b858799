#pragma once
// The registered hysteresis models (architecture.md 2.5.2), and what each tells the driver through traits
// instead of value tests in the driver (STYLE.md "A model tells the driver what it can do"; D9):
//   stays_elastic(spec, peak_abs_deformation, margin): the spring stays on its initial elastic branch when its
//     peak |deformation| is `peak_abs_deformation` (a response scaled from a linear run stays exact only then);
//     a model without an elastic range answers false.
//   unscaled_equivalent(spec, f): the Spec' with R(f w; spec) = f R(w; spec'), so that the response to f ag is f
//     times the response to ag of spec' (the IDA's bisection runs the record unscaled); std::nullopt when no
//     such Spec exists (the record must then be scaled).
// A new model is its header (model/hysteresis/<model>.hpp, with the functions the StructureModel calls and these
// two traits) and one entry in Hystereses.
#include <optional>
#include <string_view>

#include "pounding/core/type_list.hpp"
#include "pounding/model/hysteresis/bilinear_kinematic.hpp"
#include "pounding/model/hysteresis/bouc_wen.hpp"
#include "pounding/model/hysteresis/bridge_links.hpp"
#include "pounding/model/hysteresis/friction_pendulum.hpp"

namespace pounding::model {

template <class H>
concept Hysteresis = requires(const typename H::Spec& s, double x) {
  { H::name } -> std::convertible_to<std::string_view>;
  { H::params(s) } -> std::same_as<typename H::template Params<double>>;
  { H::stays_elastic(s, x, x) } -> std::same_as<bool>;
  { H::unscaled_equivalent(s, x) } -> std::same_as<std::optional<typename H::Spec>>;
};

// A spring's `law` (model::Spring) is its model's index here: 0 bilinear, 1 Bouc-Wen, 2 friction pendulum (these two
// through model/hysteresis/smooth.hpp), 3 restrainer (tension gap), 4 abutment (compression gap, elastic-perfectly
// plastic), 5 hyperbolic abutment, 6 Q-Hyst (model/hysteresis/bridge_links.hpp). Laws 1-6 run in the system stepper
// only. A hinge bearing is law 0 (bilinear kinematic hardening: k0, F_y, alpha) as a link spring.
using Hystereses = TypeList<BilinearKinematic, BoucWen, FrictionPendulum, TensionGap, CompressionGap, HyperbolicGap, QHyst>;
inline constexpr int law_bilinear = 0, law_bouc_wen = 1, law_friction_pendulum = 2, law_restrainer = 3,
                     law_abutment = 4, law_hyperbolic_abutment = 5, law_qhyst = 6;
inline bool is_smooth_law(int law) { return law == law_bouc_wen || law == law_friction_pendulum; }
inline bool is_gap_law(int law) { return law >= law_restrainer && law <= law_hyperbolic_abutment; }

template <class... Hs> constexpr bool all_hystereses(TypeList<Hs...>) { return (Hysteresis<Hs> && ...); }
static_assert(all_hystereses(Hystereses{}),
              "every registered hysteresis model satisfies model::Hysteresis: a name, Spec, params(Spec), "
              "stays_elastic(Spec, peak, margin) and unscaled_equivalent(Spec, f) (model/hysteresis/registry.hpp)");

}  // namespace pounding::model
