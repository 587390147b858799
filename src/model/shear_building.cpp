// Shear buildings side by side as one System (model/shear_building.hpp; docs/architecture.md §2.2.3, §2.2.4).
#include "pounding/model/shear_building.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
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
std::vector<std::pair<int, int>> facing_floors(const std::vector<double>& a, const std::vector<double>& b, double tol,
                                               ContactLevels levels) {
  std::vector<std::pair<int, int>> out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const int j = nearest(b, a[i]);
    if (j < 0 || nearest(a, b[static_cast<std::size_t>(j)]) != static_cast<int>(i)) continue;
    if (std::abs(a[i] - b[static_cast<std::size_t>(j)]) <= tol) out.emplace_back(static_cast<int>(i), j);
  }
  if (levels == ContactLevels::top) {
    // the lower roof: the shorter building's top floor, if it faces a floor
    const bool a_lower = a.back() <= b.back();
    std::erase_if(out, [&](const std::pair<int, int>& f) {
      return a_lower ? f.first != static_cast<int>(a.size()) - 1 : f.second != static_cast<int>(b.size()) - 1;
    });
  }
  return out;
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
    body.storey_dashpots = sticks[b].storey_dashpots && sticks[b].storeys > 1;
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
  // floor-to-floor elements, ordered by the left floor's level, interfaces left to right
  struct Facing {
    int level, interface, left, right;  // level: the left floor's number (from 1); left/right: DOFs
    int right_floor;
  };
  std::vector<Facing> facing;
  for (std::size_t b = 0; b + 1 < nb; ++b) {
    // floors above the base: z[b] holds the superstructure's levels; an isolated body's DOFs start at the base
    const std::size_t ol = sticks[b].isolated ? 1 : 0, orr = sticks[b + 1].isolated ? 1 : 0;
    for (const auto& [i, j] : facing_floors(z[b], z[b + 1], level_tolerance, levels))
      facing.push_back({i + 1, static_cast<int>(b), p.bodies[b].dofs[static_cast<std::size_t>(i) + ol],
                        p.bodies[b + 1].dofs[static_cast<std::size_t>(j) + orr], j + 1});
  }
  std::stable_sort(facing.begin(), facing.end(), [](const Facing& a, const Facing& b) {
    return a.level != b.level ? a.level < b.level : a.interface < b.interface;
  });
  for (const Facing& f : facing) {
    ContactElement e;
    e.left = {SideKind::point, f.left, -1, 0};
    e.right = {SideKind::point, f.right, -1, 0};
    e.group = 0;
    e.level = f.level;
    if (nb > 2) e.label = std::to_string(f.interface + 1) + '|' + std::to_string(f.interface + 2) + ' ';
    e.label += "level ";
    e.label += std::to_string(f.level);
    if (f.right_floor != f.level) e.label += '/' + std::to_string(f.right_floor);
    p.contacts.push_back(std::move(e));
  }
  p.groups.push_back(ContactGroup{"pounding", true});
  add_moats(p, sticks);
  return System::build(std::move(p));
}

}  // namespace pounding::model
