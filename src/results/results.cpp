// Results in memory: columns, the unit schema and the per-building field names.
#include "pounding/results/results.hpp"

#include <algorithm>
#include <functional>
#include <initializer_list>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace pounding::results {

Column make_column(const FieldSpec& spec, std::size_t n) {
  switch (spec.dtype) {
    case Dtype::u8: return std::vector<std::uint8_t>(n, static_cast<std::uint8_t>(spec.fill));
    case Dtype::i32: return std::vector<std::int32_t>(n, static_cast<std::int32_t>(spec.fill));
    case Dtype::i64: return std::vector<std::int64_t>(n, static_cast<std::int64_t>(spec.fill));
    case Dtype::f64: return std::vector<double>(n, spec.fill);
  }
  throw std::logic_error("make_column: unknown dtype");
}

std::size_t column_size(const Column& c) {
  return std::visit([](const auto& v) { return v.size(); }, c);
}

std::vector<FieldSpec> unit_schema(bool with_gaps, bool ida, bool stripes, const Extents& system) {
  std::vector<FieldSpec> s;
  for (const FieldSpec& f : unit_fields)
    if (with_gaps || f.extent == Extent::lane) s.push_back(f);
  if (stripes) s.insert(s.end(), std::begin(stripe_fields), std::end(stripe_fields));
  if (ida) s.insert(s.end(), std::begin(ida_fields), std::end(ida_fields));
  const std::vector<FieldSpec> sys = system_fields(system, with_gaps);
  s.insert(s.end(), sys.begin(), sys.end());
  return s;
}

namespace {

// Stable storage for expanded row texts: a node-based set never moves its strings.
std::string_view intern(std::string text) {
  static std::mutex mutex;
  static std::set<std::string, std::less<>> texts;
  const std::lock_guard lock(mutex);
  return *texts.insert(std::move(text)).first;
}

std::string replace_b(std::string_view text, std::size_t building) {
  std::string out(text);
  const std::string b = std::to_string(building);
  for (std::size_t at = out.find("{b}"); at != std::string::npos; at = out.find("{b}", at + b.size()))
    out.replace(at, 3, b);
  return out;
}

}  // namespace

std::string building_name(std::string_view row_name, std::size_t building) { return replace_b(row_name, building); }

FieldSpec floor_field(const FieldSpec& row, std::size_t building, std::size_t floors) {
  if (!per_floor(row.extent) || building == 0)
    throw std::logic_error(fmt::format("floor_field: /{}/{} is not a per-floor row, or building 0", row.group, row.name));
  FieldSpec f = row;
  f.name = intern(replace_b(row.name, building));
  f.description = intern(replace_b(row.description, building));
  f.count = static_cast<std::uint32_t>(floors);
  f.building = static_cast<std::uint32_t>(building);
  return f;
}

FieldSpec row_field(const FieldSpec& row, std::size_t building) {
  if ((row.extent != Extent::lane && row.extent != Extent::lane_gap) || building < 3)
    throw std::logic_error(fmt::format("row_field: /{}/{} is not a per-building row, or building < 3", row.group, row.name));
  FieldSpec f = row;
  f.name = intern(replace_b(row.name, building));
  f.description = intern(replace_b(row.description, building));
  f.building = static_cast<std::uint32_t>(building);
  return f;
}

std::vector<FieldSpec> system_fields(const Extents& system, bool with_gaps) {
  std::vector<FieldSpec> s;
  if (system.empty()) return s;
  for (const FieldSpec& row : floor_fields)
    if (with_gaps || !per_gap(row.extent))
      for (std::size_t b = 0; b < system.floors.size(); ++b) s.push_back(floor_field(row, b + 1, system.floors[b]));
  for (const FieldSpec& row : row_fields)  // a row's buildings 3..n
    if (with_gaps || row.extent == Extent::lane)
      for (std::size_t b = 3; b <= system.floors.size(); ++b) s.push_back(row_field(row, b));
  for (FieldSpec f : element_fields)
    if (with_gaps || !per_gap(f.extent)) {
      f.count = static_cast<std::uint32_t>(system.elements);
      s.push_back(f);
    }
  return s;
}

bool ModelTable::constant(std::vector<double> ModelTable::*column) const {
  for (const auto& [name, member] : model_doubles)
    if (member == column && std::find(varying.begin(), varying.end(), name) != varying.end()) return false;
  const std::vector<double>& v = this->*column;
  return std::all_of(v.begin(), v.end(), [&](double x) { return x == v.front(); });
}

std::size_t field_index(std::span<const FieldSpec> schema, std::string_view group, std::string_view name) {
  for (std::size_t k = 0; k < schema.size(); ++k)
    if (schema[k].group == group && schema[k].name == name) return k;
  throw std::logic_error(fmt::format("no field {}/{} in this schema", group, name));
}

GapTable gap_table(std::span<const double> ratios, std::span<const double> code_gap, bool in_metres) {
  GapTable t;
  t.ratios.assign(ratios.begin(), ratios.end());
  t.in_metres = in_metres;
  t.metres.reserve(code_gap.size() * ratios.size());
  for (double d : code_gap)  // the report's test: peak closing > x * code_gap (in metres: > x)
    for (double x : ratios) t.metres.push_back(in_metres ? x : x * d);
  return t;
}

void Settings::add(std::string section, std::string key, SettingValue value) {
  entries.push_back({std::move(section), std::move(key), std::move(value)});
}

const SettingValue* Settings::find(std::string_view section, std::string_view key) const {
  for (const Setting& s : entries)
    if (s.section == section && s.key == key) return &s.value;
  return nullptr;
}

namespace {
[[noreturn]] void missing(std::string_view section, std::string_view key, const char* what) {
  throw std::runtime_error(fmt::format("results: /settings/{}{}{} is {}", section, section.empty() ? "" : "/", key,
                                       what));
}
}  // namespace

double Settings::number(std::string_view section, std::string_view key) const {
  const SettingValue* v = find(section, key);
  if (!v) missing(section, key, "missing");
  if (const auto* d = std::get_if<double>(v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(v)) return static_cast<double>(*i);
  missing(section, key, "not a number");
}

std::vector<double> Settings::numbers(std::string_view section, std::string_view key) const {
  const SettingValue* v = find(section, key);
  if (!v) missing(section, key, "missing");
  if (const auto* d = std::get_if<std::vector<double>>(v)) return *d;
  missing(section, key, "not a list of numbers");
}

std::string Settings::text(std::string_view section, std::string_view key) const {
  const SettingValue* v = find(section, key);
  if (!v) missing(section, key, "missing");
  if (const auto* s = std::get_if<std::string>(v)) return *s;
  missing(section, key, "not a string");
}

std::string Results::polarity() const {
  const SettingValue* v = settings.find("records", "polarity");
  const auto* s = v ? std::get_if<std::string>(v) : nullptr;
  return s ? *s : std::string("recorded");
}

std::size_t Results::polarities() const {
  if (polarity() != "both") return 1;
  const std::size_t R = records.size();
  bool paired = R % 2 == 0;
  for (std::size_t k = 0; paired && k < R && k < records.polarity.size(); ++k)
    paired = records.polarity[k] == (k % 2 ? -1 : 1) && (k % 2 == 0 || records.id[k] == records.id[k - 1]);
  if (!paired)
    throw std::runtime_error(path + ": /settings/records polarity is \"both\" but /records does not hold each record "
                                    "twice (+1, -1 in consecutive rows)");
  return 2;
}

bool Results::has_group(std::string_view group) const {
  for (const Field& f : fields)
    if (f.spec.group == group) return true;
  return false;
}

const Field* Results::find(std::string_view group, std::string_view name) const {
  for (const Field& f : fields)
    if (f.spec.group == group && f.spec.name == name) return &f;
  return nullptr;
}

template <class T>
const std::vector<T>& Results::column(std::string_view group, std::string_view name) const {
  const Field* f = find(group, name);
  if (!f) throw std::runtime_error(fmt::format("results: no dataset /{}/{}", group, name));
  const auto* v = std::get_if<std::vector<T>>(&f->data);
  if (!v) throw std::runtime_error(fmt::format("results: /{}/{} has another element type", group, name));
  return *v;
}
template const std::vector<std::uint8_t>& Results::column(std::string_view, std::string_view) const;
template const std::vector<std::int32_t>& Results::column(std::string_view, std::string_view) const;
template const std::vector<std::int64_t>& Results::column(std::string_view, std::string_view) const;
template const std::vector<double>& Results::column(std::string_view, std::string_view) const;

void add_derived_fields(Results& r) {
  if (!r.find("impacts", "peak_u1")) return;
  const auto& pu1 = r.column<double>("uncoupled", "peak_u1");
  const auto& pu2 = r.column<double>("uncoupled", "peak_u2");
  const auto& ipu1 = r.column<double>("impacts", "peak_u1");
  const auto& ipu2 = r.column<double>("impacts", "peak_u2");
  const std::size_t RM = pu1.size(), G = r.gap_ratios.size();
  std::vector<double> amp1(RM * G), amp2(RM * G);
  for (std::size_t q = 0; q < RM; ++q)
    for (std::size_t g = 0; g < G; ++g) {
      amp1[q * G + g] = ipu1[q * G + g] / pu1[q];
      amp2[q * G + g] = ipu2[q * G + g] / pu2[q];
    }
  r.fields.push_back({derived_fields[0], std::move(amp1)});
  r.fields.push_back({derived_fields[1], std::move(amp2)});
}

}  // namespace pounding::results

namespace pounding::results {

void Group::add(std::string dataset, GroupData data, std::string units, std::string description,
                std::vector<std::size_t> shape) {
  datasets.push_back({std::move(dataset), std::move(data), std::move(shape), std::move(units), std::move(description)});
}

void Group::set(std::string key, SettingValue value) {
  for (auto& [k, v] : attributes)
    if (k == key) {
      v = std::move(value);
      return;
    }
  attributes.emplace_back(std::move(key), std::move(value));
}

const GroupDataset* Group::find(std::string_view dataset) const {
  for (const GroupDataset& d : datasets)
    if (d.name == dataset) return &d;
  return nullptr;
}

const SettingValue* Group::attribute(std::string_view key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return &v;
  return nullptr;
}

template <class T>
const std::vector<T>& Group::get(std::string_view dataset) const {
  const GroupDataset* d = find(dataset);
  if (!d) throw std::runtime_error(fmt::format("results: no dataset /{}/{}", name, dataset));
  const auto* v = std::get_if<std::vector<T>>(&d->data);
  if (!v) throw std::runtime_error(fmt::format("results: /{}/{} has another element type", name, dataset));
  return *v;
}
template const std::vector<double>& Group::get(std::string_view) const;
template const std::vector<std::int64_t>& Group::get(std::string_view) const;
template const std::vector<std::uint8_t>& Group::get(std::string_view) const;
template const std::vector<std::string>& Group::get(std::string_view) const;

double Group::number(std::string_view key) const {
  const SettingValue* v = attribute(key);
  if (const auto* d = v ? std::get_if<double>(v) : nullptr) return *d;
  if (const auto* i = v ? std::get_if<std::int64_t>(v) : nullptr) return static_cast<double>(*i);
  throw std::runtime_error(fmt::format("results: /{} has no number attribute {}", name, key));
}

std::string Group::text(std::string_view key) const {
  const SettingValue* v = attribute(key);
  if (const auto* s = v ? std::get_if<std::string>(v) : nullptr) return *s;
  throw std::runtime_error(fmt::format("results: /{} has no text attribute {}", name, key));
}

const Group* Results::group(std::string_view g) const {
  for (const Group& x : groups)
    if (x.name == g) return &x;
  return nullptr;
}

Group& Results::group_for(std::string g) {
  for (Group& x : groups)
    if (x.name == g) return x;
  groups.push_back({std::move(g), {}, {}});
  return groups.back();
}

}  // namespace pounding::results

namespace pounding::results {

Extents SystemTable::extents() const {
  Extents e;
  for (std::int32_t n : building_floors) e.floors.push_back(static_cast<std::size_t>(std::max(0, n)));
  e.elements = element_label.size();
  return e;
}

std::string SystemTable::check() const {
  const std::size_t B = building_label.size(), D = dof_building.size(), S = spring_i.size(),
                    E = element_label.size(), G = group_name.size();
  const auto sizes = [](std::string_view what, std::size_t n, std::initializer_list<std::size_t> of) {
    for (std::size_t m : of)
      if (m != n) return fmt::format("the per-{} columns differ in length ({} and {})", what, n, m);
    return std::string();
  };
  for (const std::string& p :
       {sizes("building", B, {building_floors.size(), building_isolated.size()}),
        sizes("DOF", D, {dof_floor.size(), dof_height.size()}),
        sizes("spring", S, {spring_j.size(), spring_building.size(), spring_storey.size(), spring_role.size(),
                            spring_law.size()}),
        sizes("element", E, {element_left_kind.size(), element_left_dof.size(), element_left_dof2.size(),
                             element_left_xi.size(), element_right_kind.size(), element_right_dof.size(),
                             element_right_dof2.size(), element_right_xi.size(), element_level.size(),
                             element_level_height.size(), element_group.size(), element_gap_offset.size()}),
        sizes("group", G, {group_law.size(), group_damping_law.size(), group_study_gap.size(), group_elements.size()})})
    if (!p.empty()) return p;
  const auto in = [](std::int32_t v, std::size_t n, bool none_ok) {
    return (none_ok && v == -1) || (v >= 0 && static_cast<std::size_t>(v) < n);
  };
  std::vector<std::int32_t> per_building(B, 0), per_group(G, 0);
  for (std::size_t d = 0; d < D; ++d) {
    if (!in(dof_building[d], B, false)) return fmt::format("dof_building[{}] = {} is not a building", d, dof_building[d]);
    ++per_building[static_cast<std::size_t>(dof_building[d])];
  }
  for (std::size_t b = 0; b < B; ++b)
    if (per_building[b] != building_floors[b])
      return fmt::format("building_floors[{}] = {} but {} DOFs name building {}", b, building_floors[b],
                         per_building[b], b);
  for (std::size_t s = 0; s < S; ++s)
    if (!in(spring_i[s], D, true) || !in(spring_j[s], D, false) || !in(spring_building[s], B, false))
      return fmt::format("spring {} joins DOFs {} and {} of building {}, outside the {} DOFs", s, spring_i[s],
                         spring_j[s], spring_building[s], D);
  for (std::size_t e = 0; e < E; ++e) {
    for (std::int32_t v : {element_left_dof[e], element_left_dof2[e], element_right_dof[e], element_right_dof2[e]})
      if (!in(v, D, true)) return fmt::format("element {} names DOF {}, outside the {} DOFs", e, v, D);
    if (!in(element_group[e], G, false)) return fmt::format("element_group[{}] = {} is not a group", e, element_group[e]);
    ++per_group[static_cast<std::size_t>(element_group[e])];
  }
  for (std::size_t g = 0; g < G; ++g)
    if (per_group[g] != group_elements[g])
      return fmt::format("group_elements[{}] = {} but {} elements name group {}", g, group_elements[g], per_group[g], g);
  return "";
}

}  // namespace pounding::results
