// The unit and one-line meaning of every dataset of a results file (its `units` and `description`).
#include "pounding/results/describe.hpp"

#include <optional>
#include <string>
#include <span>
#include <utility>

#include "pounding/io/hdf5.hpp"
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
// /system (format 3): the study's System, one row per building, DOF, spring, contact element and contact group.
constexpr Row system_table[] = {
    {"building_label", {"1", "label of each building (a body of the System), left to right"}},
    {"building_floors", {"1", "floors (DOFs) of each building: the floors axis of its per-floor fields (the study's "
                              "tallest when samples differ)"}},
    {"building_isolated", {"1", "1: the building stands on isolators and its first DOF is the base (floor 0)"}},
    {"dof_building", {"1", "building of each DOF (index into building_label)"}},
    {"dof_floor", {"1", "floor number of each DOF in its building: 0 an isolated base, 1 the first floor"}},
    {"dof_height", {"m", "height of each DOF's floor above its building's support"}},
    {"spring_i", {"1", "lower DOF of each spring (hysteretic element); -1 the ground"}},
    {"spring_j", {"1", "upper DOF of each spring: its deformation is u_j - u_i (the storey drift)"}},
    {"spring_building", {"1", "building of each spring (that of DOF j)"}},
    {"spring_storey", {"1", "storey number of each storey spring (storey s joins floors s-1 and s); 0 an isolator"}},
    {"spring_role", {"1", "role of each spring: storey, isolator or link"}},
    {"spring_law", {"1", "hysteresis model of each spring (model/hysteresis/registry.hpp), e.g. bilinear-kinematic"}},
    {"element_left_kind", {"1", "left side L of each contact element: point (a DOF), interpolated (between dof and "
                                "dof2, floor to column) or wall (the support)"}},
    {"element_left_dof", {"1", "DOF of the left side; -1 for a wall or the ground end of a column"}},
    {"element_left_dof2", {"1", "second DOF of an interpolated left side (the DOF above dof); -1 otherwise"}},
    {"element_left_xi", {"1", "weight of dof2 on the left side: x = (1 - xi) u_dof + xi u_dof2; 0 for a point or wall"}},
    {"element_right_kind", {"1", "right side R of each contact element: point, interpolated or wall"}},
    {"element_right_dof", {"1", "DOF of the right side; -1 for a wall or the ground end of a column"}},
    {"element_right_dof2", {"1", "second DOF of an interpolated right side; -1 otherwise"}},
    {"element_right_xi", {"1", "weight of dof2 on the right side; 0 for a point or wall"}},
    {"element_level", {"1", "number of the floor that strikes at each contact element (1 = the first floor; 0 an isolated base; floor to floor the left one)"}},
    {"element_level_height", {"m", "height above the support where each contact element acts"}},
    {"element_group", {"1", "contact group of each element (index into group_name): the group's law acts there"}},
    {"element_gap_offset", {"m", "gap of each element: for a study-gap group, added to the study's gap x code_gap; "
                                 "for another group (moat walls), the element's whole gap"}},
    {"element_label", {"1", "label of each contact element: the per-element fields' element axis (\"level 3\")"}},
    {"group_name", {"1", "name of each contact group (\"pounding\": the study-gap pounding between buildings)"}},
    {"group_law", {"1", "contact law of each group (contact/registry.hpp names)"}},
    {"group_damping_law", {"1", "damping law of each group's contact law"}},
    {"group_study_gap", {"1", "1: the group's gap is the study gap (switched off in the uncoupled run); 0: its own "
                              "(moat walls)"}},
    {"group_elements", {"1", "number of contact elements in each group"}},
};

constexpr Row field_group_table[] = {
    {"gap_ratios", {"1", "the gap axis of this group (= /gaps/ratios; kept for format-1 readers)"}},
    {"gap_axis", {"m", "the gap axis of this group in metres (= /gaps/axis; [gaps] metres)"}},
};
// /gaps of a metres axis ([gaps] metres, the group's attribute unit = "m")
constexpr Row metres_gaps_table[] = {
    {"axis", {"m", "the study's gaps in metres ([gaps] metres): every model's gap at axis point g"}},
    {"metres", {"m", "gap in metres of each model at each axis point: /gaps/axis, the same for every model"}},
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

// A floor_fields row's name for some building ("peak_u_floors2" for "peak_u_floors{b}"): its text for that building.
std::optional<Description> find_floor_field(std::string_view group, std::string_view name) {
  for (const FieldSpec& f : floor_fields) {
    const std::string_view prefix = f.name.substr(0, f.name.find("{b}"));
    if (f.group != group || !name.starts_with(prefix) || name.size() == prefix.size()) continue;
    const std::string_view digits = name.substr(prefix.size());
    if (digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string_view::npos || digits[0] == '0')
      continue;  // a building number: 1 to 999999
    const FieldSpec e = floor_field(f, std::stoul(std::string(digits)), 0);
    return Description{e.units, e.description};
  }
  for (const FieldSpec& f : row_fields) {  // a row's buildings 3..n: "peak_u3"
    const std::string_view prefix = f.name.substr(0, f.name.find("{b}"));
    if (f.group != group || !name.starts_with(prefix) || name.size() == prefix.size()) continue;
    const std::string_view digits = name.substr(prefix.size());
    if (digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string_view::npos || digits[0] == '0')
      continue;
    const unsigned long b = std::stoul(std::string(digits));
    if (b < 3) continue;
    const FieldSpec e = row_field(f, b);
    return Description{e.units, e.description};
  }
  return std::nullopt;
}

}  // namespace

// /models/T3, h3, ... of a row's buildings 3..n (the number in the name is the building's).
constexpr Row row_models_table[] = {
    {"T", {"s", "period of this building of the row (the number in the name: its position from the left, 3..n)"}},
    {"h", {"m", "height of this building of the row (the number in the name: its position from the left)"}},
    {"m", {"kg", "mass of this building of the row (the number in the name: its position from the left)"}},
    {"k", {"N/m", "initial stiffness of this building of the row (the number in the name: its position)"}},
    {"fy", {"N", "yield force of this building of the row (infinite: elastic; the number in the name: its position)"}},
    {"zeta", {"1", "damping ratio of this building of the row (the number in the name: its position)"}},
};
std::optional<Description> find_row_model(std::string_view name) {
  for (const auto& [prefix, d] : row_models_table) {
    if (!name.starts_with(prefix) || name.size() == prefix.size()) continue;
    const std::string_view digits = name.substr(prefix.size());
    if (digits.size() > 2 || digits.find_first_not_of("0123456789") != std::string_view::npos) continue;
    if (std::stoul(std::string(digits)) >= 3) return d;
  }
  return std::nullopt;
}

std::optional<Description> describe_metres_axis(std::string_view name) { return find(metres_gaps_table, name); }

std::optional<Description> describe(std::string_view group, std::string_view name) {
  if (group == "records") return find(records_table, name);
  if (group == "models") {
    if (auto d = find(models_table, name)) return d;
    return find_row_model(name);
  }
  if (group == "gaps") return find(gaps_table, name);
  if (group == "system") return find(system_table, name);
  if (auto d = find(field_group_table, name)) return d;
  if (auto d = find(unit_fields, group, name)) return d;
  if (auto d = find(element_fields, group, name)) return d;
  const FieldSpec restitution[] = {restitution_field, restitution_element_field};
  if (auto d = find(restitution, group, name)) return d;
  if (auto d = find_floor_field(group, name)) return d;
  return find(derived_fields, group, name);
}

namespace {

void list_group(h5::hid g, const std::string& at, std::vector<DatasetInfo>& out) {
  for (const std::string& name : h5::member_names(g)) {
    const std::string path = at + "/" + name;
    if (h5::is_group(g, name)) {
      list_group(h5::open_group(g, name).get(), path, out);
      continue;
    }
    DatasetInfo d;
    d.path = path;
    using K = h5::DatasetKind;
    switch (h5::dataset_kind(g, name)) {
      case K::strings: d.type = "string"; break;
      case K::f64: d.type = "f64"; break;
      case K::i64: d.type = "i64"; break;
      case K::i32: d.type = "i32"; break;
      case K::u8: d.type = "u8"; break;
      case K::other: d.type = "other"; break;
    }
    d.shape = h5::dataset_shape(g, name);
    const auto ds = h5::open_dataset(g, name);
    const auto text = [&](const char* a) {
      return h5::attribute_exists(ds.get(), a) && h5::attribute_kind(ds.get(), a) == h5::AttributeKind::string
                 ? h5::read_string_attribute(ds.get(), a)
                 : std::string();
    };
    d.units = text("units"), d.description = text("description"), d.axes = text("axes");
    out.push_back(std::move(d));
  }
}

}  // namespace

std::vector<DatasetInfo> inventory(const std::string& path) {
  const auto f = h5::open_read(path);
  std::vector<DatasetInfo> out;
  list_group(f.get(), "", out);
  return out;
}

}  // namespace pounding::results
