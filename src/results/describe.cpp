#include "pounding/results/describe.hpp"

#include <optional>
#include <span>
#include <utility>

#include "pounding/results/schema.hpp"

namespace pounding::results {

namespace {

using Row = std::pair<std::string_view, Description>;

// /records: one entry per ground motion.
constexpr Row records_table[] = {
    {"id", {"1", "record identifier in the suite (e.g. EQ1)"}},
    {"name", {"1", "record name (event and station)"}},
    {"source", {"1", "where the accelerations came from: the AT2 file, or the synthetic model and its seed"}},
    {"note", {"1", "why a synthetic stand-in replaced the real record, or empty"}},
    {"synthetic", {"1", "1: a synthetic stand-in, 0: the real record"}},
    {"dt", {"s", "time step of the record"}},
    {"duration", {"s", "record length (npts - 1) dt"}},
    {"pga_g", {"g", "peak ground acceleration as used (after scaling), in g = 9.80665 m/s^2"}},
    {"npts", {"1", "number of acceleration samples"}},
    {"polarity", {"1", "+1: the record as recorded, -1: its sign reversed ([records] polarity = \"both\": record r's "
                       "two analyses are rows 2r, 2r + 1 with the same id; the statistics keep them together)"}},
};

// /models: one entry per sampled pair (building 1 on the left, 2 on the right), and the period grid.
// zeta1/2, alpha1/2 and periods1/2 are the per-building structure models' datasets (written once those exist).
constexpr Row models_table[] = {
    {"T1", {"s", "period of building 1"}},
    {"T2", {"s", "period of building 2"}},
    {"h1", {"m", "height of building 1"}},
    {"h2", {"m", "height of building 2"}},
    {"m1", {"kg", "mass of building 1, mbar rho r^2 h (eq. 7)"}},
    {"m2", {"kg", "mass of building 2, mbar rho r^2 h (eq. 7)"}},
    {"k1", {"N/m", "initial stiffness of building 1"}},
    {"k2", {"N/m", "initial stiffness of building 2"}},
    {"fy1", {"N", "yield force of building 1 (infinite: elastic)"}},
    {"fy2", {"N", "yield force of building 2 (infinite: elastic)"}},
    {"code_gap", {"m", "code gap d = code_gap_coefficient (h1 + h2); a gap ratio x means a gap x d"}},
    {"kh", {"N/m^1.5", "Hertz contact stiffness of the pair (equivalent spheres; [contact] stiffness replaces it)"}},
    {"aspect1", {"1", "aspect ratio h / r of building 1"}},
    {"aspect2", {"1", "aspect ratio h / r of building 2"}},
    {"rho1", {"kg/m^3", "density rho of building 1's mass model"}},
    {"rho2", {"kg/m^3", "density rho of building 2's mass model"}},
    {"mbar1", {"1", "mass index mbar of building 1"}},
    {"mbar2", {"1", "mass index mbar of building 2"}},
    {"c1", {"N s/m", "viscous damping coefficient of building 1"}},
    {"c2", {"N s/m", "viscous damping coefficient of building 2"}},
    {"zeta1", {"1", "viscous damping ratio of building 1"}},
    {"zeta2", {"1", "viscous damping ratio of building 2"}},
    {"alpha1", {"1", "post-yield stiffness ratio of building 1"}},
    {"alpha2", {"1", "post-yield stiffness ratio of building 2"}},
    {"i1", {"1", "index of T1 in the period grid (/models/periods or periods1)"}},
    {"i2", {"1", "index of T2 in the period grid (/models/periods or periods2)"}},
    {"sample", {"1", "sample index within the model's period pair"}},
    {"periods", {"s", "the period grid of the study"}},
    {"periods1", {"s", "the period grid of building 1"}},
    {"periods2", {"s", "the period grid of building 2"}},
};

// /gaps (every scene), and the copy of the gap axis in each group of lane x gap fields (/impacts).
constexpr Row gaps_table[] = {
    {"ratios", {"1", "the study's gap ratios x ([gaps] ratios): a gap of x times the code gap d"}},
    {"metres", {"m", "gap in metres of each model at each ratio: ratios x /models/code_gap"}},
};
constexpr Row field_group_table[] = {
    {"gap_ratios", {"1", "the gap axis of this group (= /gaps/ratios; kept for format-1 readers)"}},
};

template <std::size_t N>
std::optional<Description> find(const Row (&table)[N], std::string_view name) {
  for (const Row& row : table)
    if (row.first == name) return row.second;
  return std::nullopt;
}

std::optional<Description> find(std::span<const FieldSpec> fields, std::string_view group, std::string_view name) {
  for (const FieldSpec& f : fields)
    if (f.group == group && f.name == name) return Description{f.units, f.description};
  return std::nullopt;
}

}  // namespace

std::optional<Description> describe(std::string_view group, std::string_view name) {
  if (group == "records") return find(records_table, name);
  if (group == "models") return find(models_table, name);
  if (group == "gaps") return find(gaps_table, name);
  if (auto d = find(field_group_table, name)) return d;
  if (auto d = find(unit_fields, group, name)) return d;
  return find(derived_fields, group, name);
}

}  // namespace pounding::results
