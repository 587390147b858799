// storey_height as an array in a building's table (issue 45 item 6): one height per storey of a shear building.
#include "pounding/sampling/building.hpp"

#include <fmt/format.h>

#include "pounding/config/config.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

// storey_height given as an array: a shear building's, with storeys given, one per storey.
void check_storey_heights(const BuildingModel& b, const WhereFn& where) {
  const std::size_t n = b.storey_heights.size();
  if (n == 0) return;
  if (!b.shear())
    throw InputError(fmt::format("storey_height holds {} values (one per storey) for an SDOF building", n),
                     where("storey_height"), "add model = \"shear\" to this table (or [structures]), or give one number");
  if (b.code.storeys <= 0)
    throw InputError(fmt::format("storey_height holds {} values (one per storey) and storeys is not given", n),
                     where("storey_height"),
                     fmt::format("add storeys = {} to this table, or give storey_height one number for every storey", n));
  if (n != static_cast<std::size_t>(b.code.storeys))
    throw InputError(fmt::format("storey_height holds {} values and the building has storeys = {}", n, b.code.storeys),
                     where("storey_height"),
                     fmt::format("give storey_height one number (every storey) or {} numbers, one per storey from the "
                                 "bottom", b.code.storeys));
}

// storey_height = [h1, h2, ...] in a building's table (read_code_factors reads a number): the heights, and their mean
// as the code's storey height; one value is the number.
void read_storey_heights(config::TableReader& r, BuildingModel& b) {
  const toml::node* n = r.get("storey_height");
  if (!n || !n->is_array()) return;
  std::vector<double> h = r.numbers("storey_height", {});
  double sum = 0.0;
  for (double x : h) sum += x;  // bottom first: the roof level
  b.code.storey_height = sum / static_cast<double>(h.size());
  if (h.size() > 1) b.storey_heights = std::move(h);
}
}  // namespace pounding
