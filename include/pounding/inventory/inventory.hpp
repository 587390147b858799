#pragma once
// A building inventory (issue 48): what a building department, a retrofit programme or an insurer has -- footprints or
// street positions, storeys, height, structural system, design level or year built, site class -- read from the
// formats GIS users have, and the adjacent pairs found in it.
//
// Formats (docs/inventory.md):
//   GeoJSON  a FeatureCollection of Polygon features (RFC 7946: WGS 84 longitude/latitude, or metres when the
//            legacy member "crs" names a projected system; a MultiPolygon of one polygon is taken). Properties as
//            the CSV columns below; the footprint gives the plan area unless plan_area is given.
//   CSV      one row per building, a header row naming the columns; street positions instead of footprints:
//            block, order (along the street), frontage and depth (m), gap_next (m, to the next building of the
//            block; empty for the last).
// Columns / properties: id (unique), storeys, height or storey_height (m), system (inventory::systems()),
//   design_level (high | moderate | low | pre-code) or year_built (with the era rule), site_class (A-E, D-default) or
//   vs30 (m/s: ASCE 7-16 Table 20.3-1), and optional period (s, measured), plan_area (m^2), unit_weight (kPa),
//   importance (Ie).
// Every error names the file and the row (CSV line) or feature (index and id) and the field.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "pounding/inventory/elf.hpp"
#include "pounding/motion/asce7_site.hpp"

namespace pounding::inventory {

using Point = std::array<double, 2>;  // x east, y north, m (local plane)

// year_built -> design level: built in or after high_from: high; in or after moderate_from: moderate; earlier:
// pre-code (the default years follow HAZUS-MH's guidance for the highest seismic zone; set them for the region).
struct EraRule {
  int high_from = 1976;
  int moderate_from = 1941;
  DesignLevel level(int year) const;
};

struct Building {
  std::string id;
  std::string where;                 // "street.geojson feature 3 (id B12)" / "street.csv:5"
  std::vector<Point> footprint;      // counter-clockwise ring, last point not repeated; empty in street mode
  std::vector<Point> footprint_input;  // the ring as the file gives it (lon/lat or projected), for the GIS outputs
  std::string block;                 // street mode
  int order = 0;
  double frontage = 0, depth = 0;    // m
  std::optional<double> gap_next;    // m, street mode
  int storeys = 0;
  std::vector<double> storey_height;  // m, one per storey
  std::string system;
  DesignLevel level = DesignLevel::high;
  std::string level_source;          // "design_level" or "year_built 1962"
  Asce7SiteClass site = Asce7SiteClass::D;
  std::string site_source;           // "site_class" or "vs30 280 m/s"
  double period = 0, plan_area = 0, unit_weight = 0, importance = 1.0;
  double height() const;             // sum of the storey heights
  std::vector<double> floor_levels() const;  // m above the ground, bottom first
};

struct Inventory {
  std::string file;
  std::vector<Building> buildings;
  bool footprints = false;   // GeoJSON footprints (else street order)
  std::vector<std::string> ignored;  // columns / properties this reader does not use (reported, not an error)
  std::string coordinates;   // "WGS 84 lon/lat, projected to a local plane about (lon0, lat0)" / "projected (m)" / "street order"
};

// Reads a .geojson / .json or .csv file. InputError for bad rows: unknown system, storeys 0, a missing site class,
// a polygon that is not simple, duplicate ids, and the like.
Inventory read_inventory(const std::string& path, const EraRule& eras = {});

struct Adjacency {
  std::size_t a = 0, b = 0;  // indices into Inventory::buildings, a < b
  double gap = 0;            // m, the smallest distance between the footprints (0: a shared wall)
  double frontage = 0;       // m, the length over which they face each other within the threshold
  enum class Kind { wall, gap, corner } kind = Kind::gap;
  // Floors that do not coincide within the tolerance up to the lower roof: the floor-to-column case (FEMA P-154).
  bool floors_aligned = true;
  double worst_offset = 0;   // m, the largest distance of a floor of the lower building to the nearest floor of the other
};
std::string_view to_string(Adjacency::Kind k);

struct AdjacencyRules {
  double threshold = 1.0;        // m: closer footprints are neighbours
  double min_frontage = 1.0;     // m: facing over less than this is corner-only contact
  double level_tolerance = 0.05; // m, as [contact] level_tolerance
};
// The adjacent pairs: from footprints (Boost.Geometry; overlapping footprints are an InputError naming both) or
// from the street order (consecutive buildings of a block, gap_next). Ordered by (a, b).
std::vector<Adjacency> adjacent_pairs(const Inventory& inv, const AdjacencyRules& rules = {});

// The ELF input of an inventory row: its numbers, and the design values of the mapped Ss, S1 (g) and TL (s) on its
// own site class (asce7_site_coefficients).
DesignInput design_input(const Building& b, double ss, double s1, double tl = 8);

}  // namespace pounding::inventory
