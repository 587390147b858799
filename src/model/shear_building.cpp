// Shear buildings side by side as one System (model/shear_building.hpp; docs/architecture.md §2.2.3, §2.2.4).
#include "pounding/model/shear_building.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <stdexcept>

namespace pounding::model {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("shear_buildings: " + what);
}

// j = the floor of `b` nearest to level z (lowest index on a tie), or -1 when `b` has no floors.
int nearest(const std::vector<double>& b, double z) {
  int best = -1;
  for (std::size_t j = 0; j < b.size(); ++j)
    if (best < 0 || std::abs(b[j] - z) < std::abs(b[static_cast<std::size_t>(best)] - z)) best = static_cast<int>(j);
  return best;
}

// Pairs (floor of a, floor of b), 0-based, of mutually nearest floors within `tol`, bottom up.
std::vector<std::pair<int, int>> facing_floors(const std::vector<double>& a, const std::vector<double>& b, double tol) {
  std::vector<std::pair<int, int>> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const int j = nearest(b, a[i]);
    if (j < 0 || nearest(a, b[static_cast<std::size_t>(j)]) != static_cast<int>(i)) continue;
    if (std::abs(a[i] - b[static_cast<std::size_t>(j)]) <= tol) out.emplace_back(static_cast<int>(i), j);
  }
  return out;
}

// The column of a building with floor levels `z` (bottom first, above its support or base at 0) that a floor at
// level `at` strikes: the floors below (-1: the ground or the base) and above it and xi = (at - z_lo) / (z_hi - z_lo);
// nullopt at or above the roof (no partner, SB §3 pitfall) or within `tol` of one of its ends (a floor meets a floor
// there).
struct ColumnHit {
  int below, above;
  double xi;
};
std::optional<ColumnHit> column_at(const std::vector<double>& z, double at, double tol) {
  for (std::size_t j = 0; j < z.size(); ++j) {
    if (!(z[j] > at)) continue;
    const double lo = j == 0 ? 0.0 : z[j - 1];
    if (at - lo <= tol || z[j] - at <= tol) return std::nullopt;
    return ColumnHit{static_cast<int>(j) - 1, static_cast<int>(j), (at - lo) / (z[j] - lo)};
  }
  return std::nullopt;
}
// A floor-to-floor or floor-to-column element before ordering.
struct Facing {
  int level, interface;  // level: the striking floor's number (from 1)
  double height;         // where it acts (m)
  int striker;           // 0: floor to floor, 1: a left floor on a right column, 2: a right floor on a left column
  Side left, right;
  double xi;
  std::string label;
};

// The column between floors c.below and c.above of `body` (-1: the ground of a fixed building, the base of an isolated
// one; `off` = 1 for an isolated body, whose DOFs start at the base) as a side.
Side column_side(const Body& body, std::size_t off, const ColumnHit& c) {
  const int q = body.dofs[static_cast<std::size_t>(c.above) + off];
  const int p = c.below >= 0 ? body.dofs[static_cast<std::size_t>(c.below) + off] : off == 1 ? body.dofs[0] : ground;
  return Side{SideKind::interpolated, p, q, 0};
}
std::string column_name(const ColumnHit& c) {
  return "column " + std::to_string(c.below + 1) + "-" + std::to_string(c.above + 1);
}

// The elements of interface b | b+1: mutually nearest floors within the tolerance meet floor to floor; every other
// floor below the neighbour's roof its column (unless the neighbour has no columns: StickTopology::columns); with
// ContactLevels::top only where the lower building's roof strikes.
void interface_facing(const System::Parts& p, std::span<const StickTopology> sticks,
                      const std::vector<std::vector<double>>& z, std::size_t b, double tol, ContactLevels levels,
                      std::vector<Facing>& facing) {
  // floors above the base: z[b] holds the superstructure's levels; an isolated body's DOFs start at the base
  const std::size_t ol = sticks[b].isolated ? 1 : 0, orr = sticks[b + 1].isolated ? 1 : 0;
  const Body &A = p.bodies[b], &B = p.bodies[b + 1];
  const std::vector<double>&za = z[b], &zb = z[b + 1];
  std::vector<char> a_met(za.size(), 0), b_met(zb.size(), 0);
  const int iface = static_cast<int>(b);
  const bool a_lower = za.back() <= zb.back();  // whose roof is the lower one (levels = "top")
  for (const auto& [i, j] : facing_floors(za, zb, tol)) {
    a_met[static_cast<std::size_t>(i)] = b_met[static_cast<std::size_t>(j)] = 1;
    if (levels == ContactLevels::top &&
        (a_lower ? i != static_cast<int>(za.size()) - 1 : j != static_cast<int>(zb.size()) - 1))
      continue;
    std::string label = "level " + std::to_string(i + 1);
    if (j != i) label += '/' + std::to_string(j + 1);
    facing.push_back({i + 1, iface, za[static_cast<std::size_t>(i)], 0,
                      {SideKind::point, A.dofs[static_cast<std::size_t>(i) + ol], -1, 0},
                      {SideKind::point, B.dofs[static_cast<std::size_t>(j) + orr], -1, 0}, 0.0, label});
  }
  for (std::size_t i = 0; i < za.size() && sticks[b + 1].columns; ++i) {  // a left floor on the right building's column
    if (a_met[i] || (levels == ContactLevels::top && (!a_lower || i + 1 != za.size()))) continue;
    const auto c = column_at(zb, za[i], tol);
    if (!c) continue;
    facing.push_back({static_cast<int>(i) + 1, iface, za[i], 1, {SideKind::point, A.dofs[i + ol], -1, 0},
                      column_side(B, orr, *c), c->xi, "level " + std::to_string(i + 1) + "/" + column_name(*c)});
  }
  for (std::size_t j = 0; j < zb.size() && sticks[b].columns; ++j) {  // a right floor on the left building's column
    if (b_met[j] || (levels == ContactLevels::top && (a_lower || j + 1 != zb.size()))) continue;
    const auto c = column_at(za, zb[j], tol);
    if (!c) continue;
    facing.push_back({static_cast<int>(j) + 1, iface, zb[j], 2, column_side(A, ol, *c),
                      {SideKind::point, B.dofs[j + orr], -1, 0}, c->xi,
                      column_name(*c) + "/level " + std::to_string(j + 1)});
  }
}

// Floor-to-floor and floor-to-column elements (§2.2.4, SB §3) in group 0, ordered by level (the striking floor's
// number: the left floor's for floor to floor), interfaces left to right, then by height; equal storey heights give
// the floor-to-floor elements of before, in the same order.
void add_floor_contacts(System::Parts& p, std::span<const StickTopology> sticks,
                        const std::vector<std::vector<double>>& z, double tol, ContactLevels levels) {
  const std::size_t nb = sticks.size();
  std::vector<Facing> facing;
  for (std::size_t b = 0; b + 1 < nb; ++b) interface_facing(p, sticks, z, b, tol, levels, facing);
  std::stable_sort(facing.begin(), facing.end(), [](const Facing& a, const Facing& b) {
    if (a.level != b.level) return a.level < b.level;
    if (a.interface != b.interface) return a.interface < b.interface;
    return a.height != b.height ? a.height < b.height : a.striker < b.striker;
  });
  for (const Facing& f : facing) {
    ContactElement e;
    e.left = f.left;
    e.right = f.right;
    e.group = 0;
    e.level = f.level;
    e.xi = f.xi;
    if (nb > 2) e.label = std::to_string(f.interface + 1) + '|' + std::to_string(f.interface + 2) + ' ';
    e.label += f.label;
    p.contacts.push_back(std::move(e));
  }
}

// Two wall elements per moated (isolated) stick on its base, in a group "moat <label>" each (study_gap false).
void add_moats(System::Parts& p, std::span<const StickTopology> sticks) {
  const std::size_t nb = sticks.size();
  for (std::size_t b = 0; b < nb; ++b) {
    if (!sticks[b].moat) continue;
    const Body& body = p.bodies[b];
    const int g = static_cast<int>(p.groups.size());
    p.groups.push_back(ContactGroup{"moat " + body.label, false});
    ContactElement left, right;
    left.left = {SideKind::wall, -1, -1, body.channel};
    left.right = {SideKind::point, body.dofs[0], -1, 0};
    right.left = {SideKind::point, body.dofs[0], -1, 0};
    right.right = {SideKind::wall, -1, -1, body.channel};
    left.group = right.group = g;
    left.level = right.level = 0;
    left.label = body.label + " moat left";
    right.label = body.label + " moat right";
    p.contacts.push_back(std::move(left));
    p.contacts.push_back(std::move(right));
  }
}

}  // namespace

std::vector<double> floor_levels(const StickTopology& stick) {
  require(stick.storeys >= 1, "a building needs at least one storey");
  const auto n = static_cast<std::size_t>(stick.storeys);
  require(stick.storey_heights.size() == 1 || stick.storey_heights.size() == n,
          "give one storey height or one per storey");
  std::vector<double> z(n);
  double level = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = stick.storey_heights[stick.storey_heights.size() == 1 ? 0 : i];
    require(std::isfinite(h) && h > 0.0, "storey heights must be finite and > 0");
    level += h;
    z[i] = level;
  }
  return z;
}

System shear_buildings(std::span<const StickTopology> sticks, double level_tolerance, ContactLevels levels) {
  require(!sticks.empty(), "no buildings");
  require(std::isfinite(level_tolerance) && level_tolerance >= 0.0, "the level tolerance must be finite and >= 0");
  for (const StickTopology& s : sticks) require(s.isolated || !s.moat, "a moat needs an isolated building");
  for (const StickTopology& s : sticks)
    require(s.isolator_law == 0 || (s.isolated && s.isolator_law > 0), "an isolator law needs an isolated building");
  const std::size_t nb = sticks.size();
  std::vector<std::vector<double>> z(nb);
  int top = 0;
  for (std::size_t b = 0; b < nb; ++b) {
    z[b] = floor_levels(sticks[b]);
    top = std::max(top, sticks[b].storeys);
  }
  System::Parts p;
  p.bodies.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    Body& body = p.bodies[b];
    body.heights = z[b];
    const bool dense = sticks[b].damping == DampingForm::dense && sticks[b].storeys > 1;
    body.storey_dashpots = sticks[b].storey_dashpots && sticks[b].storeys > 1 && !dense;
    body.damping = dense ? DampingForm::dense : DampingForm::dashpots;
    body.label = sticks[b].label.empty() ? "building" + std::to_string(b + 1) : sticks[b].label;
    if (sticks[b].isolated) {
      body.isolated = true;
      body.heights.insert(body.heights.begin(), 0.0);
    }
  }
  // level-major: floor k (0: isolated bases) of every building that has it, left to right; spring d under DOF d
  int d = 0;
  for (int k = -1; k < top; ++k)
    for (std::size_t b = 0; b < nb; ++b) {
      if (k >= sticks[b].storeys || (k < 0 && !sticks[b].isolated)) continue;
      Body& body = p.bodies[b];
      Spring s;
      s.i = body.dofs.empty() ? ground : body.dofs.back();
      s.j = d;
      s.body = static_cast<int>(b);
      s.storey = k + 1;
      s.role = k < 0 ? SpringRole::isolator : SpringRole::storey;
      if (k < 0) s.law = sticks[b].isolator_law;
      p.springs.push_back(s);
      body.dofs.push_back(d++);
    }
  for (Body& body : p.bodies)
    if (body.isolated) body.floor_dashpot_ref = body.dofs[0];
  add_floor_contacts(p, sticks, z, level_tolerance, levels);
  p.groups.push_back(ContactGroup{"pounding", true});
  add_moats(p, sticks);
  return System::build(std::move(p));
}

}  // namespace pounding::model
