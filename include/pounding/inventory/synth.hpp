#pragma once
// A synthetic city for scale tests (`pounding inventory synth`): blocks of buildings side by side along streets,
// mixed eras and systems, shared walls and small gaps, written as a GeoJSON inventory. Deterministic in the seed
// (splitmix64 draws, no library distribution), the same file on every machine.
#include <cstdint>
#include <string>

namespace pounding::inventory {

struct SynthOptions {
  std::size_t buildings = 100;
  std::uint64_t seed = 1;
  double lon = -122.42, lat = 37.77;  // the city's south-west corner, WGS 84 degrees
};
// The GeoJSON text of the city: FeatureCollection, one Polygon feature per building with id, storeys,
// storey_height, system, year_built, site_class.
std::string synth_city(const SynthOptions& options);

}  // namespace pounding::inventory
