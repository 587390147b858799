// Inventory files and adjacency: hand-made footprints (touching, 5 cm apart, corner only, overlapping), street order,
// and the errors that name the row or feature and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "pounding/core/error.hpp"
#include "pounding/inventory/inventory.hpp"

using namespace pounding;
using namespace pounding::inventory;

namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// A feature in projected metres: a w x d rectangle at (x, y).
std::string rect(const std::string& id, double x, double y, double w, double d, int storeys, double hs,
                 const std::string& extra = "") {
  return "{\"type\": \"Feature\", \"properties\": {\"id\": \"" + id + "\", \"storeys\": " + std::to_string(storeys) +
         ", \"storey_height\": " + std::to_string(hs) + ", \"system\": \"rc-smf\", \"year_built\": 1990, \"site_class\": \"D\"" +
         extra + "}, \"geometry\": {\"type\": \"Polygon\", \"coordinates\": [[[" + std::to_string(x) + ", " +
         std::to_string(y) + "], [" + std::to_string(x + w) + ", " + std::to_string(y) + "], [" + std::to_string(x + w) +
         ", " + std::to_string(y + d) + "], [" + std::to_string(x) + ", " + std::to_string(y + d) + "], [" +
         std::to_string(x) + ", " + std::to_string(y) + "]]]}}";
}

std::string collection(const std::vector<std::string>& features) {
  std::string s = "{\"type\": \"FeatureCollection\", \"crs\": {\"type\": \"name\", \"properties\": {\"name\": "
                  "\"urn:ogc:def:crs:EPSG::32610\"}}, \"features\": [";
  for (std::size_t i = 0; i < features.size(); ++i) s += (i ? ", " : "") + features[i];
  return s + "]}";
}

std::string where_of_error(const std::string& path) {
  try {
    const Inventory inv = read_inventory(path);
    adjacent_pairs(inv);
  } catch (const InputError& e) {
    return e.where() + " | " + e.what_part();
  }
  return "accepted";
}

}  // namespace

TEST(Inventory, FootprintsTouchingApartCornerAndFloors) {
  // A and B share a wall (x = 10); C is 5 cm from B; D touches C only at a corner; E is 3 m away from D.
  const std::string path = write_temp("street.geojson", collection({
      rect("A", 0, 0, 10, 20, 5, 3.2), rect("B", 10, 0, 12, 20, 3, 3.0),
      rect("C", 22.05, 0, 8, 15, 5, 3.0), rect("D", 30.05, 15, 8, 8, 2, 3.2), rect("E", 41.05, 15, 8, 8, 2, 3.2)}));
  const Inventory inv = read_inventory(path);
  ASSERT_EQ(inv.buildings.size(), 5u);
  EXPECT_TRUE(inv.footprints);
  EXPECT_NEAR(inv.buildings[0].plan_area, 200, 1e-9);
  const std::vector<Adjacency> pairs = adjacent_pairs(inv);
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0].a, 0u);
  EXPECT_EQ(pairs[0].b, 1u);
  EXPECT_EQ(pairs[0].kind, Adjacency::Kind::wall);
  EXPECT_DOUBLE_EQ(pairs[0].gap, 0.0);
  EXPECT_NEAR(pairs[0].frontage, 20, 1e-9);
  // 5 storeys of 3.2 m against 3 of 3.0: floors 3.2/3.0, 6.4/6.0, 9.6/9.0 -> 0.6 m apart: floor to column
  EXPECT_FALSE(pairs[0].floors_aligned);
  EXPECT_NEAR(pairs[0].worst_offset, 0.6, 1e-9);
  EXPECT_EQ(pairs[1].kind, Adjacency::Kind::gap);
  EXPECT_NEAR(pairs[1].gap, 0.05, 1e-9);
  EXPECT_NEAR(pairs[1].frontage, 15, 1e-9);
  EXPECT_TRUE(pairs[1].floors_aligned);
  EXPECT_EQ(pairs[2].kind, Adjacency::Kind::corner);  // C-D meet at (30.05, 15) only
  EXPECT_EQ(pairs[2].a, 2u);
  EXPECT_EQ(pairs[2].b, 3u);
}

TEST(Inventory, LonLatProjectsToMetres) {
  // Two 10 m x 20 m buildings at 37.77 N, 0.10 m apart, written in WGS 84 degrees (metres per degree on the
  // ellipsoid: pi/180 a cos(lat) / sqrt(1 - e2 sin^2 lat) east, pi/180 a (1 - e2) / (1 - e2 sin^2 lat)^1.5 north).
  const double lat = 37.77, lon = -122.42, r = M_PI / 180, a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double w = 1 - e2 * std::sin(lat * r) * std::sin(lat * r);
  const double east = r * a * std::cos(lat * r) / std::sqrt(w), north = r * a * (1 - e2) / std::pow(w, 1.5);
  auto feature = [&](const std::string& id, double x, double width) {
    char ring[400];
    const double x0 = lon + x / east, x1 = lon + (x + width) / east, y0 = lat, y1 = lat + 20 / north;
    std::snprintf(ring, sizeof ring, "[[[%.10f, %.10f], [%.10f, %.10f], [%.10f, %.10f], [%.10f, %.10f], [%.10f, %.10f]]]",
                  x0, y0, x1, y0, x1, y1, x0, y1, x0, y0);
    return "{\"type\": \"Feature\", \"properties\": {\"id\": \"" + id + "\", \"storeys\": 3, \"height\": 9.6, "
           "\"system\": \"steel-smf\", \"design_level\": \"moderate\", \"vs30\": 300}, \"geometry\": {\"type\": "
           "\"Polygon\", \"coordinates\": " + std::string(ring) + "}}";
  };
  const std::string path = write_temp("lonlat.geojson", "{\"type\": \"FeatureCollection\", \"features\": [" +
                                      feature("P", 0, 10) + ", " + feature("Q", 10.10, 10) + "]}");
  const Inventory inv = read_inventory(path);
  EXPECT_NE(inv.coordinates.find("WGS 84"), std::string::npos);
  EXPECT_NEAR(inv.buildings[0].plan_area, 200, 0.05);
  EXPECT_EQ(inv.buildings[1].site, Asce7SiteClass::D);  // vs30 300 m/s: Table 20.3-1
  EXPECT_EQ(inv.buildings[1].level, DesignLevel::moderate);
  const std::vector<Adjacency> pairs = adjacent_pairs(inv);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_NEAR(pairs[0].gap, 0.10, 1e-3);
  EXPECT_NEAR(pairs[0].frontage, 20, 0.01);
}

TEST(Inventory, StreetOrderFromCsv) {
  const std::string path = write_temp("street.csv",
      "id,block,order,frontage,depth,gap_next,storeys,storey_height,system,year_built,site_class,owner\n"
      "# a comment line\n"
      "S1,north,1,12,18,0,4,3.0,rc-omf,1958,D,\"Smith, J.\"\n"
      "S2,north,2,10,18,0.04,4,3.1,urm-wall,1925,D,x\n"
      "S3,north,3,15,20,,6,3.0,steel-smf,2005,C,y\n"
      "T1,south,1,10,10,,2,3.0,rc-smf,2010,C,z\n");
  const Inventory inv = read_inventory(path);
  ASSERT_EQ(inv.buildings.size(), 4u);
  EXPECT_EQ(inv.ignored, std::vector<std::string>{"owner"});
  EXPECT_EQ(inv.buildings[0].level, DesignLevel::moderate);  // 1958: EraRule's defaults
  EXPECT_EQ(inv.buildings[1].level, DesignLevel::pre_code);
  EXPECT_EQ(inv.buildings[2].level, DesignLevel::high);
  EXPECT_NEAR(inv.buildings[0].plan_area, 216, 1e-12);
  const std::vector<Adjacency> pairs = adjacent_pairs(inv);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].kind, Adjacency::Kind::wall);
  EXPECT_NEAR(pairs[0].worst_offset, 0.4, 1e-9);  // 12.0 against 12.4 m at the 4th floor
  EXPECT_EQ(pairs[1].kind, Adjacency::Kind::gap);
  EXPECT_NEAR(pairs[1].gap, 0.04, 1e-12);
  EXPECT_NEAR(pairs[1].frontage, 18, 1e-12);
}

TEST(Inventory, BadInventoriesNameTheRowAndField) {
  const std::string head = "id,block,order,frontage,depth,gap_next,storeys,storey_height,system,design_level,site_class\n";
  auto csv = [&](const std::string& name, const std::string& rows) { return where_of_error(write_temp(name, head + rows)); };
  std::string w = csv("a.csv", "A,b,1,10,10,0,3,3,rc-smf,high,D\nB,b,2,10,10,,0,3,rc-smf,high,D\n");
  EXPECT_NE(w.find("a.csv:3"), std::string::npos) << w;
  EXPECT_NE(w.find("storeys"), std::string::npos) << w;
  w = csv("b.csv", "A,b,1,10,10,0,3,3,rc-smff,high,D\n");
  EXPECT_NE(w.find("b.csv:2"), std::string::npos) << w;
  EXPECT_NE(w.find("system"), std::string::npos) << w;
  w = csv("c.csv", "A,b,1,10,10,0,3,3,rc-smf,high,\n");
  EXPECT_NE(w.find("site class is missing"), std::string::npos) << w;
  w = csv("d.csv", "A,b,1,10,10,,3,3,rc-smf,high,D\nB,b,2,10,10,,3,3,rc-smf,high,D\n");
  EXPECT_NE(w.find("d.csv:2"), std::string::npos) << w;
  EXPECT_NE(w.find("gap_next"), std::string::npos) << w;
  w = csv("e.csv", "A,b,1,10,10,0,3,3,rc-smf,high,D\nA,b,2,10,10,,3,3,rc-smf,high,D\n");
  EXPECT_NE(w.find("used twice"), std::string::npos) << w;
  // overlapping footprints
  w = where_of_error(write_temp("o.geojson", collection({rect("A", 0, 0, 10, 10, 3, 3), rect("B", 9, 0, 10, 10, 3, 3)})));
  EXPECT_NE(w.find("overlap"), std::string::npos) << w;
  EXPECT_NE(w.find("feature 0"), std::string::npos) << w;
  EXPECT_NE(w.find("feature 1"), std::string::npos) << w;
  // a self-intersecting (bow-tie) polygon
  std::string bow = rect("C", 0, 0, 10, 10, 3, 3);
  bow.replace(bow.find("\"coordinates\": "), std::string::npos,
              "\"coordinates\": [[[0, 0], [10, 10], [10, 0], [0, 10], [0, 0]]]}}");
  w = where_of_error(write_temp("s.geojson", collection({bow})));
  EXPECT_NE(w.find("not a simple polygon"), std::string::npos) << w;
  EXPECT_NE(w.find("id C"), std::string::npos) << w;
  w = where_of_error(write_temp("j.geojson", "{\"type\": \"FeatureCollection\", \"features\": [}"));
  EXPECT_NE(w.find("not valid JSON"), std::string::npos) << w;
}
