// GeoJSON inventories: features into Buildings, lon/lat projected to a local plane, footprints checked.
#include <cmath>
#include <map>
#include <numbers>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "geometry.hpp"
#include "pounding/core/error.hpp"

namespace pounding::inventory {
namespace detail {
Building building_from_properties(const std::map<std::string, std::string>& f, const std::string& where,
                                  const EraRule& eras, Inventory& inv);
}
namespace {

using json = nlohmann::json;

std::string as_text(const json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number() || v.is_boolean()) return v.dump();
  return v.dump();  // an array or object: refused by the field's parser with its text
}

// The ring of a Polygon's coordinates (the outer ring; holes are ignored and said so by the caller).
std::vector<Point> ring_of(const json& geometry, const std::string& where) {
  if (!geometry.is_object() || !geometry.contains("type"))
    throw InputError("the feature has no geometry", where, "give each building a Polygon footprint");
  const std::string type = as_text(geometry["type"]);
  json rings;
  if (type == "Polygon") rings = geometry.value("coordinates", json::array());
  else if (type == "MultiPolygon" && geometry.value("coordinates", json::array()).size() == 1) rings = geometry["coordinates"][0];
  else throw InputError(fmt::format("geometry type {} is not a footprint", escaped_excerpt(type)), where + " geometry",
                        "give a Polygon (or a MultiPolygon of one polygon) per building");
  if (!rings.is_array() || rings.empty() || !rings[0].is_array())
    throw InputError("the polygon has no outer ring", where + " geometry", "give coordinates [[[x, y], ...]]");
  std::vector<Point> ring;
  for (const json& p : rings[0]) {
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
      throw InputError("a position is not [x, y]", where + " geometry", "write each position as [longitude, latitude]");
    ring.push_back({p[0].get<double>(), p[1].get<double>()});
  }
  if (ring.size() >= 2 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3)
    throw InputError(fmt::format("the footprint has {} distinct corners", ring.size()), where + " geometry",
                     "give at least three corners");
  return ring;
}

bool projected_crs(const json& doc) {
  if (!doc.contains("crs")) return false;
  const std::string name = as_text(doc["crs"].value("properties", json::object()).value("name", json("")));
  return !(name.empty() || name.find("CRS84") != std::string::npos || name.find("4326") != std::string::npos);
}

// WGS 84 to a local plane about (lon0, lat0): x = N cos(lat0) dlon, y = M dlat (the radii of curvature at lat0).
// Distances between neighbours keep a relative error below 1e-3 over 10 km: well under a millimetre on a gap.
void project(Inventory& inv) {
  double lon0 = 0, lat0 = 0, n = 0;
  for (const Building& b : inv.buildings)
    for (const Point& p : b.footprint) lon0 += p[0], lat0 += p[1], n += 1;
  lon0 /= n, lat0 /= n;
  constexpr double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f), rad = std::numbers::pi / 180;
  const double s = std::sin(lat0 * rad), w = std::sqrt(1 - e2 * s * s);
  const double N = a / w, M = a * (1 - e2) / (w * w * w);
  for (Building& b : inv.buildings)
    for (Point& p : b.footprint) {
      if (std::abs(p[0]) > 180 || std::abs(p[1]) > 90)
        throw InputError(fmt::format("position [{}, {}] is not longitude/latitude", p[0], p[1]), b.where + " geometry",
                         "give WGS 84 degrees (RFC 7946), or name the projected system in a \"crs\" member");
      p = {N * std::cos(lat0 * rad) * (p[0] - lon0) * rad, M * (p[1] - lat0) * rad};
    }
  inv.coordinates = fmt::format("WGS 84 longitude/latitude, projected to a local plane about ({:.6f}, {:.6f})", lon0, lat0);
}

// A simple polygon, counter-clockwise after correction; its area becomes plan_area unless given.
void check_footprint(Building& b) {
  geo::Polygon p = geo::polygon_of(b.footprint);
  geo::bg::correct(p);
  std::string reason;
  if (!geo::bg::is_valid(p, reason))
    throw InputError(fmt::format("the footprint is not a simple polygon: {}", reason), b.where + " geometry",
                     "fix the footprint in a GIS (e.g. QGIS's Fix geometries): no self-intersection, no repeated corner");
  b.footprint.clear();
  for (const geo::XY& q : p.outer()) b.footprint.push_back({q.x(), q.y()});
  const double area = geo::bg::area(p);
  if (b.plan_area == 0) b.plan_area = area;
  if (area < 10) throw InputError(fmt::format("the footprint's area is {:.3g} m^2", area), b.where + " geometry",
                                  "a building's footprint is at least 10 m^2: check the coordinates' units");
}

}  // namespace

Inventory read_geojson(const std::string& path, const std::string& body, const EraRule& eras) {
  json doc;
  try {
    doc = json::parse(body);
  } catch (const json::parse_error& e) {
    throw InputError(fmt::format("not valid JSON: {}", e.what()), path, "check the file in a JSON validator");
  }
  if (!doc.is_object() || as_text(doc.value("type", json(""))) != "FeatureCollection" || !doc.contains("features") ||
      !doc["features"].is_array())
    throw InputError("the file is not a GeoJSON FeatureCollection", path, "write {\"type\": \"FeatureCollection\", \"features\": [...]}");
  Inventory inv{path, {}, true, {}, "projected coordinates (m)"};
  std::size_t i = 0;
  for (const json& feature : doc["features"]) {
    const std::string where = fmt::format("{} feature {}", path, i++);
    const json props = feature.is_object() ? feature.value("properties", json::object()) : json::object();
    std::map<std::string, std::string> f;
    if (props.is_object())
      for (auto it = props.begin(); it != props.end(); ++it) f[it.key()] = as_text(it.value());
    if (f["id"].empty() && feature.is_object() && feature.contains("id")) f["id"] = as_text(feature["id"]);
    Building b = detail::building_from_properties(f, where, eras, inv);
    b.footprint = ring_of(feature.is_object() ? feature.value("geometry", json()) : json(), b.where);
    b.footprint_input = b.footprint;
    inv.buildings.push_back(std::move(b));
  }
  if (inv.buildings.empty()) return inv;
  if (!projected_crs(doc)) project(inv);
  for (Building& b : inv.buildings) check_footprint(b);
  return inv;
}

}  // namespace pounding::inventory
