// Synthetic cities: blocks of adjacent buildings with mixed eras, systems, heights and gaps, as GeoJSON.
#include "pounding/inventory/synth.hpp"

#include <cmath>
#include <numbers>
#include <string_view>

#include <fmt/format.h>

#include "pounding/core/random.hpp"

namespace pounding::inventory {
namespace {

struct Draws {
  std::uint64_t key, n = 0;
  double u() { return static_cast<double>(splitmix64(key + 0x632be59bd9b4e019ULL * ++n) >> 11) * 0x1.0p-53; }
  double in(double lo, double hi) { return lo + (hi - lo) * u(); }
  int whole(int lo, int hi) { return lo + static_cast<int>(std::floor(u() * (hi - lo + 1))); }
};

// Systems by era: before 1941 masonry and non-ductile frames, 1941-1975 ordinary systems, later ductile ones.
std::string_view system_for(int year, Draws& d) {
  static constexpr std::string_view early[] = {"urm-wall", "urm-wall", "rc-omf"};
  static constexpr std::string_view middle[] = {"rc-omf", "steel-omf", "rm-ordinary-wall", "rc-ordinary-wall"};
  static constexpr std::string_view modern[] = {"rc-smf", "steel-smf", "rc-special-wall", "steel-scbf", "rc-imf"};
  if (year < 1941) return early[d.whole(0, 2)];
  if (year < 1976) return middle[d.whole(0, 3)];
  return modern[d.whole(0, 4)];
}

int storeys_for(std::string_view system, Draws& d) {
  const bool masonry = system == "urm-wall" || system == "rm-ordinary-wall";
  const double u = d.u();  // mostly low and mid rise: 1 + floor(max * u^2)
  return 1 + static_cast<int>(std::floor((masonry ? 5 : 15) * u * u));
}

}  // namespace

std::string synth_city(const SynthOptions& o) {
  Draws d{splitmix64(o.seed)};
  constexpr double a = 6378137.0, rad = std::numbers::pi / 180;  // a sphere is enough for made-up positions
  const double east = a * std::cos(o.lat * rad) * rad, north = a * rad;  // m per degree
  std::string out = "{\"type\": \"FeatureCollection\", \"features\": [\n";
  std::size_t made = 0;
  for (int block = 0; made < o.buildings; ++block) {
    const int in_block = d.whole(8, 20);
    const std::string site = d.u() < 0.5 ? "C" : "D";
    const double y0 = (block / 20) * 80.0, street_x = (block % 20) * 420.0;
    double x = street_x;
    for (int k = 0; k < in_block && made < o.buildings; ++k, ++made) {
      const double w = d.in(8, 25), depth = d.in(12, 30);
      const int year = d.whole(1900, 2020);
      const std::string_view system = system_for(year, d);
      const int storeys = storeys_for(system, d);
      const double hs = std::round(d.in(2.8, 4.0) * 20) / 20;
      const double x0 = o.lon + x / east, x1 = o.lon + (x + w) / east;
      const double ya = o.lat + y0 / north, yb = o.lat + (y0 + depth) / north;
      out += fmt::format("{}{{\"type\": \"Feature\", \"properties\": {{\"id\": \"B{}\", \"storeys\": {}, \"storey_height\": {}, "
                         "\"system\": \"{}\", \"year_built\": {}, \"site_class\": \"{}\"}}, \"geometry\": {{\"type\": \"Polygon\", "
                         "\"coordinates\": [[[{:.9f}, {:.9f}], [{:.9f}, {:.9f}], [{:.9f}, {:.9f}], [{:.9f}, {:.9f}], [{:.9f}, {:.9f}]]]}}}}",
                         made ? ",\n" : "", made + 1, storeys, hs, system, year, site, x0, ya, x1, ya, x1, yb, x0, yb, x0, ya);
      const double r = d.u();  // 35 % shared walls, 35 % gaps of 1-10 cm, 30 % of 10-60 cm
      x += w + (r < 0.35 ? 0.0 : r < 0.7 ? d.in(0.01, 0.10) : d.in(0.10, 0.60));
    }
  }
  return out + "\n]}\n";
}

}  // namespace pounding::inventory
