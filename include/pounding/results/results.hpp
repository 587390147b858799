#pragma once
// A results file in memory: what `pounding run` writes (results/writer.hpp) and what the report reads
// (results/reader.hpp). Every dataset and attribute of the file has a member here, so write(load(f)) keeps
// everything. The study's settings are a generic table (section, key, value) filled from
// study::visit_settings: this module depends on no study type.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "pounding/results/schema.hpp"

namespace pounding::results {

// Root attributes, in the file's order (provenance, the run's choices, exclusions, wall time).
struct Header {
  // The file's format (reader); in a Results built in memory the writer ignores it and writes
  // pair_format_version (2) without a SystemTable, format_version (3) with one.
  std::int64_t format_version = results::pair_format_version;
  std::string program_version, git_commit, date;
  std::int64_t seed = 0;
  std::string study_text, study_path, title, scene, scene_reason, contact_law, damping_law;
  double restitution = 0;
  std::string stepper;
  std::int64_t substeps = 1;
  double max_dt = 0;
  std::int64_t ranks = 1;
  std::string build;
  // The machine that ran the study (rank 0's, core/machine.hpp): host name, CPU model, CPUs the run could use.
  // Files written before issue 29's provenance item lack them ("" and 0).
  std::string host, cpu_model;
  std::int64_t cpu_cores = 0;
  // analyses excluded from the probabilities (diverged or non-finite)
  std::int64_t excluded_analyses = 0, total_analyses = 0;
  double max_excluded_fraction = 0;
  std::string exclusion_warning;  // non-empty: too many excluded analyses (the run exited with code 3)
  double wall_time_s = 0;
};

// The header's root attributes by name, for the writer and the reader: those written before the data, then
// those known only at the end of the run.
template <class H, class F> void visit_header_start(H& h, F&& f) {
  f("format_version", h.format_version);
  f("program_version", h.program_version);
  f("git_commit", h.git_commit);
  f("date", h.date);
  f("seed", h.seed);
  f("study_text", h.study_text);
  f("study_path", h.study_path);
  f("title", h.title);
  f("scene", h.scene);
  f("scene_reason", h.scene_reason);
  f("contact_law", h.contact_law);
  f("damping_law", h.damping_law);
  f("restitution", h.restitution);
  f("stepper", h.stepper);
  f("substeps", h.substeps);
  f("max_dt", h.max_dt);
  f("ranks", h.ranks);
  f("build", h.build);
  f("host", h.host);
  f("cpu_model", h.cpu_model);
  f("cpu_cores", h.cpu_cores);
}
template <class H, class F> void visit_header_end(H& h, F&& f) {
  f("excluded_analyses", h.excluded_analyses);
  f("total_analyses", h.total_analyses);
  f("max_excluded_fraction", h.max_excluded_fraction);
  f("exclusion_warning", h.exclusion_warning);
  f("wall_time_s", h.wall_time_s);
}

// /records: one entry per ground motion.
struct RecordTable {
  std::vector<std::string> id, name, source, note;
  std::vector<std::uint8_t> synthetic;
  std::vector<double> dt, duration, pga_g;
  std::vector<std::int64_t> npts;
  std::vector<std::int32_t> polarity;  // +1 as recorded, -1 sign reversed ([records] polarity); empty in older files
  std::size_t size() const { return id.size(); }
};

// /models: one entry per sampled pair (record-independent), and the period grid.
struct ModelTable {
  std::vector<double> T1, T2, h1, h2, m1, m2, k1, k2, fy1, fy2, code_gap, kh, aspect1, aspect2, rho1, rho2, mbar1,
      mbar2, c1, c2, zeta1, zeta2, alpha1, alpha2;
  std::vector<std::int32_t> i1, i2;
  std::vector<std::int64_t> sample;
  // A row's buildings 3..n ([structures] buildings = n), each [models]: /models/T3, h3, m3, k3, fy3, zeta3, ...
  struct RowBuilding {
    std::vector<double> T, h, m, k, fy, zeta;
  };
  std::vector<RowBuilding> row;
  std::vector<double> periods;            // building 1's grid (files before periods1/periods2: the one grid)
  std::vector<double> periods1, periods2;  // the buildings' grids (a period distribution: one slot, its median)
  double zeta = 0.05;
  // Columns left empty because their values differ from model to model and the reader was asked only that
  // (results::LoadExtent::report): their names.
  std::vector<std::string> varying;
  std::size_t size() const { return T1.size(); }
  // Whether every model has the same value in `column`: false when it is listed in `varying`, else from its values
  // (an empty column: true).
  bool constant(std::vector<double> ModelTable::*column) const;
};

// The double datasets of /models, in the file's order: the writer and the reader share this list.
// The datasets of a row's building K >= 3: name prefix + K ("T3").
inline constexpr std::pair<std::string_view, std::vector<double> ModelTable::RowBuilding::*> row_model_doubles[] = {
    {"T", &ModelTable::RowBuilding::T},   {"h", &ModelTable::RowBuilding::h},   {"m", &ModelTable::RowBuilding::m},
    {"k", &ModelTable::RowBuilding::k},   {"fy", &ModelTable::RowBuilding::fy}, {"zeta", &ModelTable::RowBuilding::zeta}};
inline constexpr std::pair<std::string_view, std::vector<double> ModelTable::*> model_doubles[] = {
    {"T1", &ModelTable::T1},           {"T2", &ModelTable::T2},           {"h1", &ModelTable::h1},
    {"h2", &ModelTable::h2},           {"m1", &ModelTable::m1},           {"m2", &ModelTable::m2},
    {"k1", &ModelTable::k1},           {"k2", &ModelTable::k2},           {"fy1", &ModelTable::fy1},
    {"fy2", &ModelTable::fy2},         {"code_gap", &ModelTable::code_gap}, {"kh", &ModelTable::kh},
    {"aspect1", &ModelTable::aspect1}, {"aspect2", &ModelTable::aspect2}, {"rho1", &ModelTable::rho1},
    {"rho2", &ModelTable::rho2},       {"mbar1", &ModelTable::mbar1},     {"mbar2", &ModelTable::mbar2},
    {"c1", &ModelTable::c1},           {"c2", &ModelTable::c2},           {"zeta1", &ModelTable::zeta1},
    {"zeta2", &ModelTable::zeta2},     {"alpha1", &ModelTable::alpha1},   {"alpha2", &ModelTable::alpha2}};

// /settings/<section>/<key> (section "" is /settings itself). Booleans are stored as 0/1 integers.
using SettingValue = std::variant<double, std::int64_t, std::string, std::vector<double>, std::vector<std::string>>;
struct Setting {
  std::string section, key;
  SettingValue value;
  bool operator==(const Setting&) const = default;
};

class Settings {
 public:
  std::vector<Setting> entries;  // in writing order (a file read back lists them by name)
  bool empty() const { return entries.empty(); }
  void add(std::string section, std::string key, SettingValue value);
  const SettingValue* find(std::string_view section, std::string_view key) const;
  // Typed look-ups; throw std::runtime_error naming /settings/<section>/<key> when absent or of another type
  // (an integer is accepted where a number is asked for).
  double number(std::string_view section, std::string_view key) const;
  std::vector<double> numbers(std::string_view section, std::string_view key) const;
  std::string text(std::string_view section, std::string_view key) const;
};

// /gaps, in every scene: the study's gap axis and the gap in metres each point gives each model. The axis is ratios x
// of each model's code gap d ([gaps] ratios: /gaps/ratios), or metres ([gaps] metres: /gaps/axis, the group's
// attribute unit = "m"; issue 45 item 4): `ratios` holds the axis either way, in_metres says which.
struct GapTable {
  std::vector<double> ratios;  // [gaps]: the axis (ratios of d, or metres when in_metres)
  std::vector<double> metres;  // [models x gaps], model-major: ratios[g] * code_gap[m] (in_metres: ratios[g])
  bool in_metres = false;
  // model m's gap unit: its code gap d, or 1 (m) on a metres axis
  double unit(std::span<const double> code_gap, std::size_t m) const { return in_metres ? 1.0 : code_gap[m]; }
};
// The gaps of `ratios` for models of code gap `code_gap` (m); in_metres: `ratios` are metres, every model's gap.
GapTable gap_table(std::span<const double> ratios, std::span<const double> code_gap, bool in_metres = false);

// One per-model output: its row of the schema and its values, flat and record-major ([records x models] or
// [records x models x gaps]; the file stores them with that shape).
struct Field {
  FieldSpec spec;
  Column data;
  // Values not held in memory ([outputs] per_model = "stream", study/spill.hpp): `data` is an empty vector of the
  // stored type and source(first, count, out) writes values [first, first + count) of the row-major [records,
  // models(, per lane)] column to out; the writer calls it chunk by chunk, from several threads (h5::Fill).
  std::function<void(std::size_t first, std::size_t count, void* out)> source = {};
};

// A module's group (/intensity, /fragility, /hazard, ...): datasets that carry their own units and description,
// and attributes. Analyses added after the kernel's per-model fields (fragility, hazard, later modules) write
// their results as groups, so a new module needs no new writer or reader code: the writer marks each group
// (attribute `module_group`) and the reader reads every marked group back.
using GroupData = std::variant<std::vector<double>, std::vector<std::int64_t>, std::vector<std::uint8_t>,
                               std::vector<std::string>>;
struct GroupDataset {
  std::string name;
  GroupData data;
  std::vector<std::size_t> shape;  // empty: 1-D
  std::string units, description;  // both required (the writer refuses an empty one)
};
struct Group {
  std::string name;
  std::vector<GroupDataset> datasets;
  std::vector<std::pair<std::string, SettingValue>> attributes;
  // Sub-groups (/histories/1, 2, ...: study/histories.hpp), written and read back like the group itself (the reader
  // reads their datasets with LoadExtent::all only; their attributes always).
  std::vector<Group> children;

  void add(std::string dataset, GroupData data, std::string units, std::string description,
           std::vector<std::size_t> shape = {});
  void set(std::string key, SettingValue value);
  const GroupDataset* find(std::string_view dataset) const;
  const SettingValue* attribute(std::string_view key) const;
  // Typed look-ups; throw std::runtime_error naming /<group>/<name> when absent or of another type.
  template <class T> const std::vector<T>& get(std::string_view dataset) const;
  double number(std::string_view key) const;
  std::string text(std::string_view key) const;
};

// /system (format 3): the study's System as plain tables, so that results depends on no model type (the study
// converts model::System: study/make_results.hpp system_table). Indices are 0-based; -1 is the ground (a spring's
// i) or "none" (an element side without a second DOF or without a DOF). Per building b the per-floor fields have
// building_floors[b] floors: when samples of a study differ in storeys this is the tallest (max) topology.
struct SystemTable {
  // per building (a body of the System), left to right
  std::vector<std::string> building_label;      // "building1"
  std::vector<std::int32_t> building_floors;    // its DOFs: the floors axis of its per-floor fields
  std::vector<std::uint8_t> building_isolated;  // 1: its first DOF is the base on isolators (floor 0)
  // per DOF
  std::vector<std::int32_t> dof_building, dof_floor;  // floor 0 = an isolated base, 1 = the first floor
  std::vector<double> dof_height;                     // m above the building's support
  // per spring (hysteretic element between DOF i, or the ground, and DOF j)
  std::vector<std::int32_t> spring_i, spring_j, spring_building, spring_storey;
  std::vector<std::string> spring_role, spring_law;  // storey | isolator | link; the hysteresis model's name
  // per contact element: penetration x_L - x_R - gap; a side is a point (dof), an interpolated point
  // (x = (1 - xi) u_dof + xi u_dof2) or a wall (the support)
  std::vector<std::string> element_left_kind, element_right_kind;  // point | interpolated | wall
  std::vector<std::int32_t> element_left_dof, element_left_dof2, element_right_dof, element_right_dof2;
  std::vector<double> element_left_xi, element_right_xi;  // weight of dof2 (0 for a point or a wall)
  std::vector<std::int32_t> element_level, element_group;  // floor number where it acts; index into group_*
  std::vector<double> element_level_height;                // m above the support
  std::vector<double> element_gap_offset;  // m: study-gap groups, added to the study gap; others, the gap itself
  std::vector<std::string> element_label;  // "level 3", "building1 moat left"
  // per contact group (one contact law each)
  std::vector<std::string> group_name, group_law, group_damping_law;
  std::vector<std::uint8_t> group_study_gap;  // 1: the elements' gap is the study gap (plus their offset)
  std::vector<std::int32_t> group_elements;   // elements in the group

  bool empty() const { return building_label.empty(); }
  // The per-floor and per-element extents this table gives the fields (building_floors, elements).
  Extents extents() const;
  // "" or the first inconsistency (sizes of the per-building, per-DOF, per-spring, per-element, per-group
  // columns; building_floors against dof_building; indices in range; group_elements against element_group).
  std::string check() const;
  bool operator==(const SystemTable&) const = default;
};

// The datasets of /system in the file's order, by name: the writer, the reader and describe share this list.
template <class T, class F> void visit_system(T& t, F&& f) {
  f("building_label", t.building_label);
  f("building_floors", t.building_floors);
  f("building_isolated", t.building_isolated);
  f("dof_building", t.dof_building);
  f("dof_floor", t.dof_floor);
  f("dof_height", t.dof_height);
  f("spring_i", t.spring_i);
  f("spring_j", t.spring_j);
  f("spring_building", t.spring_building);
  f("spring_storey", t.spring_storey);
  f("spring_role", t.spring_role);
  f("spring_law", t.spring_law);
  f("element_left_kind", t.element_left_kind);
  f("element_left_dof", t.element_left_dof);
  f("element_left_dof2", t.element_left_dof2);
  f("element_left_xi", t.element_left_xi);
  f("element_right_kind", t.element_right_kind);
  f("element_right_dof", t.element_right_dof);
  f("element_right_dof2", t.element_right_dof2);
  f("element_right_xi", t.element_right_xi);
  f("element_level", t.element_level);
  f("element_level_height", t.element_level_height);
  f("element_group", t.element_group);
  f("element_gap_offset", t.element_gap_offset);
  f("element_label", t.element_label);
  f("group_name", t.group_name);
  f("group_law", t.group_law);
  f("group_damping_law", t.group_damping_law);
  f("group_study_gap", t.group_study_gap);
  f("group_elements", t.group_elements);
}

struct Results {
  std::string path;  // where it was read from (not stored in the file)
  Header header;
  Settings settings;  // empty for files written before /settings existed
  RecordTable records;
  ModelTable models;
  GapTable gaps;                   // empty only for format-1 files without the study's settings or gaps
  std::vector<double> gap_ratios;  // the gap axis of every lane x gap field (impacts scene; else empty)
  std::vector<Field> fields;       // unit fields, then derived ones, in writing order
  // Fragility studies: the stripes (S IM levels) are a leading dimension of every field, [stripes, records,
  // models]; 0 otherwise. The fields stay flat, stripe-major.
  std::size_t stripes = 0;
  std::vector<Group> groups;       // module groups, in writing order
  // Format 3: the study's System (not the SDOF pair); empty for an SDOF-pair study and every format-1/2 file.
  // The writer writes format 3 and /system when it is not empty, and refuses per-floor or per-element fields
  // whose extents differ from it (or that come without it).
  SystemTable system;

  const Group* group(std::string_view name) const;
  Group& group_for(std::string name);  // the group, created (at the end) when absent

  std::size_t record_count() const { return records.size(); }
  // [outputs] per_model = "stream" (study/spill.hpp): the models' table is not held (ModelTable's per-model columns
  // and GapTable::metres stay empty) but drawn a window at a time as the file is written: model_rows(first, n, out)
  // fills every per-model column of `out` with models [first, first + n); streamed_models is their count.
  std::function<void(std::size_t first, std::size_t n, ModelTable& out)> model_rows = {};
  std::size_t streamed_models = 0;
  std::size_t model_count() const { return model_rows ? streamed_models : models.size(); }
  // [records] polarity: "both" (rows 2r, 2r + 1 are record r's two signs) or "recorded" (also every file written
  // before the key). polarities() is the number of analyses (rows) per independent record, 1 or 2, and
  // independent_records() the records the statistics resample. Throws std::runtime_error for a "both" file whose
  // rows do not pair up (odd count, or /records/polarity not +1, -1 alternating with equal ids).
  std::string polarity() const;
  std::size_t polarities() const;
  std::size_t independent_records() const { return record_count() / polarities(); }
  bool has_group(std::string_view group) const;
  const Field* find(std::string_view group, std::string_view name) const;
  // The values of /<group>/<name>; throws std::runtime_error when absent or of another type.
  template <class T>
  const std::vector<T>& column(std::string_view group, std::string_view name) const;
};

// Appends derived_fields (schema.hpp) computed from the unit fields: amplification = impacts peak / uncoupled
// peak of the same model, per gap. Does nothing without impacts fields.
void add_derived_fields(Results& r);

}  // namespace pounding::results
