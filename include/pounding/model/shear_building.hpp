#pragma once
// Shear buildings side by side as one System (docs/architecture.md §2.2.3, §2.2.4 "Floor to floor", §2.1;
// ../shared/research/systems-and-bridges.md §1, §4): n >= 1 sticks left to right, each a chain of floors on storey
// springs (bilinear, law 0) to the ground, floor dashpots to ground and -- for Rayleigh damping -- a dashpot on
// every storey spring; contacts between NEIGHBOURING buildings, all in one study-gap group "pounding": floor to
// floor (a point on each side) where floor levels agree within a tolerance (only floors that exist on both sides, SB
// §1 pitfall 4), and floor to column (§2.2.4, SB §3) where a floor below the neighbour's roof faces no floor within
// the tolerance: the floor (a point) against the neighbour's column between the floors below and above it (an
// interpolated side, linear shape functions N1 = 1 - xi, N2 = xi, xi = (z - z_below) / (z_above - z_below); the
// column below a fixed building's first floor has the ground as its lower end). A floor above the neighbour's roof
// meets nothing. The per-lane numbers are physics::set_shear_building's.
//
// Numbering (level-major, §2.1): the bases of isolated buildings (floor 0) left to right, then floor 1 of every building left to right, then floor 2 of every building that has
// one, and so on; spring d is the storey spring under DOF d (springs in DOF order). Two one-storey buildings give
// DOF 0 = building 1, DOF 1 = building 2: exactly System::sdof_pair() when both storeys are 3.2 m high.
// Elements in level order, interfaces left to right within a level, then by height; element `level` is the
// striking floor's number: floor to floor the left floor's, labelled "level k" ("level k/k'" when the right floor
// is k'); a left floor k on the right building's column between its floors j and j+1 "level k/column j-(j+1)"
// (floor 0: the ground or an isolated base), a right floor k on the left building's column "column j-(j+1)/level k";
// in a row of three or more buildings prefixed with the interface, "1|2 level k". ContactElement::xi holds xi.
#include <span>
#include <string>
#include <vector>

#include "pounding/core/enum_names.hpp"
#include "pounding/model/system.hpp"

namespace pounding::model {

// The most storeys a building may have: simulate's --storeysK, the study key storeys and Python's analyze_storeys.
inline constexpr int max_storeys = 200;

struct StickTopology {
  int storeys = 1;
  // m: one value for every storey, or one per storey (bottom first); floor levels are their running sums
  std::vector<double> storey_heights{3.2};
  // Rayleigh's stiffness-proportional part as a dashpot on each storey spring. Ignored for one storey: an SDOF's
  // damping is its floor dashpot (Structure::from_period), so a one-storey building is today's SDOF.
  bool storey_dashpots = true;
  // Classical modal damping (DampingForm::dense: a per-lane n x n C, physics::ShearSpec::modal_zeta) instead of
  // Rayleigh's dashpots; then no storey dashpots. Ignored for one storey (the SDOF's floor dashpot is exact).
  DampingForm damping = DampingForm::dashpots;
  std::string label;  // empty: "building<b>" (b from 1, left to right)
  // Base isolation (docs/architecture.md §2.2.3 "Isolated stick", §2.2.4 "Walls"): a base mass (floor 0, level 0 m)
  // on an isolator spring (role isolator, storey 0) under the `storeys` floors; the superstructure's floor dashpots
  // reference the base (Body::floor_dashpot_ref = dofs[0]). The base meets no neighbour's floor.
  bool isolated = false;
  // Moat walls (isolated only): two wall elements on the base, "<label> moat left" (L = wall, R = base: delta =
  // -u_b - gap) and "<label> moat right" (L = base, R = wall: delta = u_b - gap), in their own group "moat <label>"
  // (study_gap = false: their gaps are the moat's, physics::set_moat), after the floor-to-floor elements.
  bool moat = false;
  // The isolator spring's hysteresis law (isolated only; model/hysteresis/registry.hpp: 0 bilinear -- linear and
  // lead-rubber bearings --, 1 Bouc-Wen, 2 friction pendulum; physics::isolator_law(Bearing) gives it).
  int isolator_law = 0;
  // Whether a neighbour's floor may strike this building's columns between its floors (floor to column). false for
  // an SDOF idealisation standing for a whole building beside a shear one (study/system_block.hpp): its one storey is
  // not a column, so it meets the neighbour's floors only (floor to floor, as before floors met columns).
  bool columns = true;
};

enum class ContactLevels {
  common,  // every pair of facing floors whose levels agree within the tolerance
  top,     // only the lower roof of each neighbouring pair (against the other building's floor or column there)
};
inline constexpr EnumName<ContactLevels> contact_levels_names[] = {{ContactLevels::common, "common"},
                                                                   {ContactLevels::top, "top"}};
constexpr const auto& enum_names(ContactLevels) { return contact_levels_names; }

// The shape functions of a column side (a floor striking the column between two floors, §2.2.4, SB §3): the weight
// N2 of the floor above at xi along the column (N1 = 1 - N2). linear: N2 = xi; cubic: the deflected shape of a
// fixed-fixed column under relative floor translation (no floor rotation, the shear-building assumption),
// N2 = 3 xi^2 - 2 xi^3, whose nodal forces are the column's fixed-end reactions. Both give 0 and 1 at the ends exactly.
enum class ShapeFunctions {
  linear,
  cubic,
};
inline constexpr EnumName<ShapeFunctions> shape_functions_names[] = {{ShapeFunctions::linear, "linear"},
                                                                     {ShapeFunctions::cubic, "cubic"}};
constexpr const auto& enum_names(ShapeFunctions) { return shape_functions_names; }
inline double column_weight(double xi, ShapeFunctions s) {
  return s == ShapeFunctions::linear ? xi : xi * xi * (3.0 - 2.0 * xi);
}

// Floor levels above the ground (m), bottom first, of a stick: the running sums of its storey heights.
std::vector<double> floor_levels(const StickTopology& stick);

// The system of `sticks`, left to right. A floor of building b meets the floor of building b+1 nearest to its level
// when they are within `level_tolerance` (m) of each other and each is the other's nearest, else (below the
// neighbour's roof, farther than the tolerance from both ends of the column it faces) the neighbour's column. With
// ContactLevels::top only the elements where the lower building's roof strikes (a floor or a column). Throws
// std::invalid_argument (a programming error: the command line and study validate first) for no sticks, storeys
// < 1, heights not finite and > 0, a height list of neither 1 nor `storeys` values, or a tolerance not finite and
// >= 0.
System shear_buildings(std::span<const StickTopology> sticks, double level_tolerance = 0.05,
                       ContactLevels levels = ContactLevels::common);

}  // namespace pounding::model
