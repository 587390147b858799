// Boost.Geometry types of the inventory's footprints (private to src/inventory).
#pragma once
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/geometries/segment.hpp>

#include "pounding/inventory/inventory.hpp"

namespace pounding::inventory::geo {

namespace bg = boost::geometry;
using XY = bg::model::d2::point_xy<double>;
using Polygon = bg::model::polygon<XY, false, false>;  // counter-clockwise, open
using Box = bg::model::box<XY>;
using Segment = bg::model::segment<XY>;

inline Polygon polygon_of(const std::vector<Point>& ring) {
  Polygon p;
  for (const Point& q : ring) p.outer().push_back(XY(q[0], q[1]));
  return p;
}

}  // namespace pounding::inventory::geo
