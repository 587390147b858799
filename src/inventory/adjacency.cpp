// Adjacent pairs of an inventory: from footprints (an R-tree of their boxes, Boost.Geometry distances) or street order.
#include <algorithm>
#include <cmath>
#include <map>

#include <boost/geometry/index/rtree.hpp>
#include <fmt/format.h>

#include "geometry.hpp"
#include "pounding/core/error.hpp"

namespace pounding::inventory {
namespace {

namespace bgi = boost::geometry::index;

// The largest distance of a floor (up to the lower roof) of either building to the other's nearest floor.
void compare_floors(const Building& a, const Building& b, double tol, Adjacency& out) {
  const std::vector<double> za = a.floor_levels(), zb = b.floor_levels();
  const double roof = std::min(za.back(), zb.back());
  const auto nearest = [](double z, const std::vector<double>& other) {
    double d = INFINITY;
    for (double v : other) d = std::min(d, std::abs(v - z));
    return d;
  };
  double worst = 0;
  for (double z : za)
    if (z <= roof + tol) worst = std::max(worst, nearest(z, zb));
  for (double z : zb)
    if (z <= roof + tol) worst = std::max(worst, nearest(z, za));
  out.worst_offset = worst;
  out.floors_aligned = worst <= tol;
}

// Length over which two footprints face each other within `reach`: the overlap of the projections of nearly
// parallel edges (within 15 degrees) that come within reach of each other, the largest over the edge pairs.
double facing_length(const geo::Polygon& p, const geo::Polygon& q, double reach) {
  const auto& r1 = p.outer();
  const auto& r2 = q.outer();
  double best = 0;
  for (std::size_t i = 0; i < r1.size(); ++i) {
    const geo::XY& a0 = r1[i];
    const geo::XY& a1 = r1[(i + 1) % r1.size()];
    const double ux = a1.x() - a0.x(), uy = a1.y() - a0.y(), len = std::hypot(ux, uy);
    if (len == 0) continue;
    for (std::size_t j = 0; j < r2.size(); ++j) {
      const geo::XY& b0 = r2[j];
      const geo::XY& b1 = r2[(j + 1) % r2.size()];
      const double vx = b1.x() - b0.x(), vy = b1.y() - b0.y(), lv = std::hypot(vx, vy);
      if (lv == 0 || std::abs(ux * vy - uy * vx) > std::sin(15 * M_PI / 180) * len * lv) continue;
      if (geo::bg::distance(geo::Segment(a0, a1), geo::Segment(b0, b1)) > reach) continue;
      const double t0 = ((b0.x() - a0.x()) * ux + (b0.y() - a0.y()) * uy) / len;
      const double t1 = ((b1.x() - a0.x()) * ux + (b1.y() - a0.y()) * uy) / len;
      best = std::max(best, std::min(len, std::max(t0, t1)) - std::max(0.0, std::min(t0, t1)));
    }
  }
  return best;
}

std::vector<Adjacency> from_footprints(const Inventory& inv, const AdjacencyRules& rules) {
  const std::size_t n = inv.buildings.size();
  std::vector<geo::Polygon> poly(n);
  std::vector<std::pair<geo::Box, std::size_t>> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    poly[i] = geo::polygon_of(inv.buildings[i].footprint);
    geo::Box box;
    geo::bg::envelope(poly[i], box);
    boxes[i] = {box, i};
  }
  const bgi::rtree<std::pair<geo::Box, std::size_t>, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
  std::vector<Adjacency> out;
  for (std::size_t i = 0; i < n; ++i) {
    geo::Box wide = boxes[i].first;
    wide.min_corner() = geo::XY(wide.min_corner().x() - rules.threshold, wide.min_corner().y() - rules.threshold);
    wide.max_corner() = geo::XY(wide.max_corner().x() + rules.threshold, wide.max_corner().y() + rules.threshold);
    std::vector<std::pair<geo::Box, std::size_t>> near;
    tree.query(bgi::intersects(wide), std::back_inserter(near));
    std::sort(near.begin(), near.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
    for (const auto& [box, j] : near) {
      if (j <= i) continue;
      const Building& a = inv.buildings[i];
      const Building& b = inv.buildings[j];
      std::vector<geo::Polygon> common;
      geo::bg::intersection(poly[i], poly[j], common);
      double overlap = 0;
      for (const geo::Polygon& c : common) overlap += geo::bg::area(c);
      if (overlap > 0.01)
        throw InputError(fmt::format("the footprints of {} and {} overlap by {:.3g} m^2", a.id, b.id, overlap),
                         a.where + " and " + b.where, "buildings cannot share ground: fix the footprints (a shared wall touches, it does not overlap)");
      const double gap = geo::bg::distance(poly[i], poly[j]);
      if (gap > rules.threshold) continue;
      Adjacency adj;
      // to the millimetre: positions written to 1e-9 degrees are good to 0.1 mm each, a gap to about 0.2 mm
      adj.a = i, adj.b = j, adj.gap = std::round(gap * 1e3) / 1e3;
      adj.frontage = facing_length(poly[i], poly[j], gap + 1e-3);
      adj.kind = adj.frontage < rules.min_frontage ? Adjacency::Kind::corner
                 : adj.gap == 0                    ? Adjacency::Kind::wall
                                                   : Adjacency::Kind::gap;
      compare_floors(a, b, rules.level_tolerance, adj);
      out.push_back(adj);
    }
  }
  return out;
}

std::vector<Adjacency> from_street(const Inventory& inv, const AdjacencyRules& rules) {
  std::map<std::string, std::map<int, std::size_t>> blocks;
  for (std::size_t i = 0; i < inv.buildings.size(); ++i) {
    const Building& b = inv.buildings[i];
    const auto [it, fresh] = blocks[b.block].emplace(b.order, i);
    if (!fresh)
      throw InputError(fmt::format("order {} of block {} is also {}'s", b.order, b.block, inv.buildings[it->second].id),
                       b.where + " order", "give each building of a block its own place along the street");
  }
  std::vector<Adjacency> out;
  for (const auto& [block, row] : blocks) {
    for (auto it = row.begin(); std::next(it) != row.end(); ++it) {
      const Building& a = inv.buildings[it->second];
      const Building& b = inv.buildings[std::next(it)->second];
      if (!a.gap_next)
        throw InputError(fmt::format("gap_next is missing, and {} follows in block {}", b.id, block), a.where + " gap_next",
                         "give the gap to the next building (0 for a shared wall); leave it empty only for a block's last");
      if (*a.gap_next > rules.threshold) continue;
      Adjacency adj;
      adj.a = std::min(it->second, std::next(it)->second), adj.b = std::max(it->second, std::next(it)->second);
      adj.gap = *a.gap_next;
      adj.frontage = std::min(a.depth, b.depth);
      adj.kind = adj.gap == 0 ? Adjacency::Kind::wall : Adjacency::Kind::gap;
      compare_floors(a, b, rules.level_tolerance, adj);
      out.push_back(adj);
    }
  }
  std::sort(out.begin(), out.end(), [](const Adjacency& x, const Adjacency& y) { return std::pair(x.a, x.b) < std::pair(y.a, y.b); });
  return out;
}

}  // namespace

std::vector<Adjacency> adjacent_pairs(const Inventory& inv, const AdjacencyRules& rules) {
  require_range(rules.threshold, 0.0, 50.0, "adjacency threshold", "[0, 50] m");
  return inv.footprints ? from_footprints(inv, rules) : from_street(inv, rules);
}

}  // namespace pounding::inventory
