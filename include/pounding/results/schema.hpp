#pragma once
// The results file's shared vocabulary (architecture.md 2.6, 2.7): the format version, and one table of
// FieldSpec rows describing a work unit's per-lane results. The study's UnitResult (its typed-byte
// serialisation for MPI and the checkpoint), the Tally's scatter into [records x models (x gaps)] arrays and
// the HDF5 dataset names all come from this table, so a new per-model output is one row here (and the code
// that computes it).
//
// Format 2 (docs/results-format.md): every per-model field has the shape of its extent, [records, models] or
// [records, models, gaps] (format 1 stored uncoupled/status and impacts/* flat; the reader still reads it), and
// every dataset carries `units` and `description` attributes: a field's come from its row here, the other
// datasets' from results/describe.hpp. In memory every field stays flat, record-major.
//
// Format 3 (architecture.md 2.6.3) adds, for a study whose System is not the SDOF pair, per-floor and
// per-element fields (the extents lane_floor, lane_gap_floor, lane_element, lane_gap_element: floor_fields and element_fields
// below, sized by Extents) and the /system group (results.hpp SystemTable). An SDOF-pair study writes format 2,
// byte for byte as before.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace pounding::results {

// The newest layout: what a study of any System other than the SDOF pair writes (per-floor and per-element fields,
// /system). The reader reads it, 2 and 1.
inline constexpr std::int64_t format_version = 3;
// What an SDOF-pair study writes (no /system, no per-floor or per-element field): format 2, unchanged.
inline constexpr std::int64_t pair_format_version = 2;

// Element types of a field; the order is the alternatives' order in Column.
enum class Dtype : std::uint8_t { u8, i32, i64, f64 };
// Values per lane (inside a unit, lane-major; in the file after [records, models]):
//   lane             one                                    [R, M]
//   lane_gap         one per gap ratio, [lane][gap]          [R, M, G]
//   lane_floor       one per floor of building `building`, [lane][floor] bottom first       [R, M, n_b]
//   lane_element     one per contact element, [lane][element] (System element order)        [R, M, E]
//   lane_gap_element one per gap and element, [lane][gap][element]                          [R, M, G, E]
//   lane_gap_floor   one per gap and floor of building `building`, [lane][gap][floor]       [R, M, G, n_b]
// (a fragility study puts [stripes] in front). `count` of the row holds n_b or E.
enum class Extent : std::uint8_t { lane, lane_gap, lane_floor, lane_element, lane_gap_element, lane_gap_floor };
constexpr bool per_gap(Extent e) {
  return e == Extent::lane_gap || e == Extent::lane_gap_element || e == Extent::lane_gap_floor;
}
constexpr bool per_floor(Extent e) { return e == Extent::lane_floor || e == Extent::lane_gap_floor; }

// A typed column: the values of one field for a unit, or for the whole study.
using Column = std::variant<std::vector<std::uint8_t>, std::vector<std::int32_t>, std::vector<std::int64_t>,
                            std::vector<double>>;

struct FieldSpec {
  std::string_view group, name;  // HDF5 /<group>/<name>
  Dtype dtype;
  Extent extent;
  double fill;                   // value of a model not computed (yet)
  std::string_view units;        // SI unit, the dataset's `units` ("1": dimensionless, codes, counts)
  std::string_view description;  // one line, the dataset's `description` (the writer refuses an empty one)
  // Format 3 only (lane_floor, lane_element, lane_gap_element; 0 for the other extents): the floors of building
  // `building` (1-based, left to right) or the contact elements -- set by unit_schema from the Extents.
  std::uint32_t count = 0;
  std::uint32_t building = 0;
};

constexpr std::size_t dtype_size(Dtype t) {
  switch (t) {
    case Dtype::u8: return 1;
    case Dtype::i32: return 4;
    case Dtype::i64: return 8;
    case Dtype::f64: return 8;
  }
  return 0;
}

// A column of `n` values of `spec`'s type, each `spec.fill`.
Column make_column(const FieldSpec& spec, std::size_t n);
std::size_t column_size(const Column& c);

// What one work unit returns: status 0 ok, 1 diverged, 2 non-finite, 3 coarse (kernel/batch.hpp); peaks in m, N, s.
// The impacts-scene rows (lane_gap) follow the per-lane rows, so a scene without gaps uses a prefix.
inline constexpr FieldSpec unit_fields[] = {
    {"uncoupled", "status", Dtype::u8, Extent::lane, 255, "1",
     "status of the analysis without contact: 0 ok, 1 diverged, 2 non-finite, 3 coarse (under-resolved contact), "
     "254 not analysed (record dropped from this stripe: scale factor above max_scale), 255 not computed"},
    {"uncoupled", "peak_u1", Dtype::f64, Extent::lane, NAN, "m", "peak |u1| of building 1 without contact"},
    {"uncoupled", "peak_u2", Dtype::f64, Extent::lane, NAN, "m", "peak |u2| of building 2 without contact"},
    {"uncoupled", "peak_closing", Dtype::f64, Extent::lane, NAN, "m",
     "peak closing max(u1 - u2) without contact: the pair touches at a gap g exactly when peak_closing > g"},
    {"impacts", "status", Dtype::u8, Extent::lane_gap, 255, "1",
     "status of the analysis with contact at this gap: 0 ok, 1 diverged, 2 non-finite, 3 coarse (under-resolved "
     "contact), 255 not computed"},
    {"impacts", "impact_count", Dtype::i32, Extent::lane_gap, -1, "1",
     "number of impacts (separated-to-contact transitions); -1 not computed"},
    {"impacts", "peak_force", Dtype::f64, Extent::lane_gap, NAN, "N", "peak contact force"},
    {"impacts", "peak_u1", Dtype::f64, Extent::lane_gap, NAN, "m", "peak |u1| of building 1 with contact"},
    {"impacts", "peak_u2", Dtype::f64, Extent::lane_gap, NAN, "m", "peak |u2| of building 2 with contact"},
    {"impacts", "t_first_impact", Dtype::f64, Extent::lane_gap, NAN, "s",
     "time of the first impact from the start of the record; NaN when the pair never touched"},
    // the resolution guard's h omega_c (physics/resolution.hpp): 0 for a pair that never touched, NaN without a
    // force law or when diverged; beside the limit in /settings it shows each analysis's margin
    {"impacts", "h_omega_contact", Dtype::f64, Extent::lane_gap, NAN, "1",
     "resolution of the contact: step h times the contact frequency omega_c (0 never touched, NaN no force law "
     "or diverged); status 3 above the stepper's limit"},
};

// What a unit of an impacts-scene study with [contact] restitution (e(v0)) returns besides the unit_fields.
inline constexpr FieldSpec restitution_field = {
    "impacts", "restitution_outside", Dtype::i32, Extent::lane_gap, -1, "1",
    "impacts of this analysis whose approach velocity lay outside the valid range of the e(v0) curve ([contact] "
    "restitution: e extrapolated there); 0 for a pair that never touched, -1 not computed"};

// What a unit of an impacts-scene study with [analysis] coarse = "refine" returns besides the unit_fields
// (study/refine.hpp): each coupled analysis's integration steps per record step.
inline constexpr FieldSpec refine_field = {
    "impacts", "substeps", Dtype::i32, Extent::lane_gap, -1, "1",
    "integration steps per record step of this analysis: the study's, or more where the resolution guard found it "
    "coarse and it was run again at a shorter step ([analysis] coarse = \"refine\"); -1 not computed"};

// Format 3: the same per contact element ([R, M, G, E], element order of /system/element_*); written beside
// restitution_field (which sums it over the study-gap elements) by a study of Systems with [contact] restitution.
inline constexpr FieldSpec restitution_element_field = {
    "impacts", "element_restitution_outside", Dtype::i32, Extent::lane_gap_element, -1, "1",
    "impacts at each contact element whose approach velocity lay outside the valid range of the e(v0) curve "
    "([contact] restitution); 0 when it never touched, -1 not computed"};

// What a unit of a multiple-stripe study returns besides the uncoupled rows ([analysis] scale_elastic).
inline constexpr FieldSpec stripe_fields[] = {
    {"uncoupled", "scaled", Dtype::u8, Extent::lane, 0, "1",
     "1: not run -- the buildings stay elastic, so the peaks are the lowest stripe's times the ratio of the scale "
     "factors (exact for an elastic response); 0: analysed"},
};

// What a unit of a fragility study with method = "ida" on yielding buildings returns besides the uncoupled rows
// (study/run.cpp, the bisection IDA): per lane the analyses it took, per lane and gap the bracket of the record
// scale factor at first contact. make_results moves them into the module group /ida ([records, models(, gaps)]).
inline constexpr FieldSpec ida_fields[] = {
    {"ida", "analyses", Dtype::i32, Extent::lane, -1, "1",
     "uncoupled analyses this (record, model) took: the record as it is, the hunt and every bisection step"},
    {"ida", "scale_limit", Dtype::f64, Extent::lane, NAN, "1",
     "largest hunt factor up to which this model's analyses stayed within the displacement limit (the hunt's last "
     "factor when none diverged; 0 when the first diverged); the record's capacities are censored at the smallest"},
    {"ida", "scale_lo", Dtype::f64, Extent::lane_gap, NAN, "1",
     "largest record scale factor known to give no contact at this gap (0: the pair touched at the hunt's first "
     "factor and the bracket started at 0); NaN: excluded (diverged at the hunt's first factor or in the bisection)"},
    {"ida", "scale_hi", Dtype::f64, Extent::lane_gap, NAN, "1",
     "smallest record scale factor known to give contact at this gap; +inf: no contact up to the hunt's last "
     "factor, or up to a diverged analysis (right-censored at scale_lo); NaN: excluded"},
};

// Written after the run from the unit fields (results::add_derived_fields).
inline constexpr FieldSpec derived_fields[] = {
    {"impacts", "amplification_u1", Dtype::f64, Extent::lane_gap, NAN, "1",
     "peak_u1 with contact / /uncoupled/peak_u1 of the same record and model"},
    {"impacts", "amplification_u2", Dtype::f64, Extent::lane_gap, NAN, "1",
     "peak_u2 with contact / /uncoupled/peak_u2 of the same record and model"},
};

// Format 3: per floor of each building, one row per building ("{b}" in name and description is the building's
// number, 1 = the left one; floor_field() gives the row of building b). A building's floors are its DOFs bottom
// first -- an isolated building's base (floor 0, on the isolators) first -- as many as the most that building has
// over the study; a sample with fewer floors leaves the values above its roof NaN.
inline constexpr FieldSpec floor_fields[] = {
    {"uncoupled", "peak_u_floors{b}", Dtype::f64, Extent::lane_floor, NAN, "m",
     "peak |u| of each floor of building {b} relative to the ground, without contact; [records, models, floors] "
     "bottom first (an isolated building's base first); NaN above the roof of a building with fewer floors"},
    {"uncoupled", "peak_drift{b}", Dtype::f64, Extent::lane_floor, NAN, "m",
     "peak |drift| of the storey below each floor of building {b} (u of the floor minus u of the floor below; the "
     "isolator's deformation at an isolated base), without contact; bottom first; NaN above the roof"},
    {"uncoupled", "peak_acc_floors{b}", Dtype::f64, Extent::lane_floor, NAN, "g",
     "peak absolute acceleration |a + ag| of each floor of building {b}, without contact, in g = 9.80665 m/s^2; "
     "bottom first; NaN above the roof"},
    // the same with contact at each gap ([records, models, gaps, floors]); an analysis the impacts scene did not run
    // coupled (it never touched) holds its uncoupled values, as impacts/peak_u1 does
    {"impacts", "peak_u_floors{b}", Dtype::f64, Extent::lane_gap_floor, NAN, "m",
     "peak |u| of each floor of building {b} relative to the ground, with contact at each gap; [records, models, gaps, "
     "floors] bottom first (an isolated building's base first); NaN above the roof of a building with fewer floors"},
    {"impacts", "peak_drift{b}", Dtype::f64, Extent::lane_gap_floor, NAN, "m",
     "peak |drift| of the storey below each floor of building {b} (the isolator's deformation at an isolated base), "
     "with contact at each gap; bottom first; NaN above the roof"},
    {"impacts", "peak_acc_floors{b}", Dtype::f64, Extent::lane_gap_floor, NAN, "g",
     "peak absolute acceleration |a + ag| of each floor of building {b}, with contact at each gap, in g = 9.80665 "
     "m/s^2; bottom first; NaN above the roof"},
};

// Format 3, a row of n >= 3 buildings ([structures] buildings = n): the [R, M] and [R, M, G] peaks of buildings 3..n,
// named as building 1's and 2's rows of unit_fields ("{b}" = 3..n; row_field() gives the row of building b).
inline constexpr FieldSpec row_fields[] = {
    {"uncoupled", "peak_u{b}", Dtype::f64, Extent::lane, NAN, "m",
     "peak |u| of building {b} of the row relative to the ground (its largest floor), without contact"},
    {"impacts", "peak_u{b}", Dtype::f64, Extent::lane_gap, NAN, "m",
     "peak |u| of building {b} of the row relative to the ground (its largest floor), with contact at each gap"},
};

// Format 3: per contact element of the System (element order of /system/element_*), without contact (lane_element)
// and with contact at each gap (lane_gap_element).
inline constexpr FieldSpec element_fields[] = {
    {"uncoupled", "peak_closing_elements", Dtype::f64, Extent::lane_element, NAN, "m",
     "peak closing x_L - x_R of each contact element without contact: a study-gap element touches at gap g exactly "
     "when its value minus /system/element_gap_offset exceeds g (peak_closing is the largest of those)"},
    {"impacts", "element_impact_count", Dtype::i32, Extent::lane_gap_element, -1, "1",
     "number of impacts (separated-to-contact transitions) at each contact element; -1 not computed"},
    {"impacts", "element_peak_force", Dtype::f64, Extent::lane_gap_element, NAN, "N",
     "peak contact force of each contact element (0 when it never touched)"},
    {"impacts", "element_peak_penetration", Dtype::f64, Extent::lane_gap_element, NAN, "m",
     "peak penetration x_L - x_R - gap of each contact element (0 when it never touched)"},
    {"impacts", "element_t_first_impact", Dtype::f64, Extent::lane_gap_element, NAN, "s",
     "time of the first impact at each contact element from the start of the record; NaN when it never touched"},
    {"impacts", "element_energy", Dtype::f64, Extent::lane_gap_element, NAN, "J",
     "energy dissipated by each contact element (work of the contact force less what it stores, plus impulsive "
     "losses); NaN when the run did not compute energy"},
    {"impacts", "element_h_omega_contact", Dtype::f64, Extent::lane_gap_element, NAN, "1",
     "resolution of each contact element: step h times its contact frequency omega_c (0 never touched, NaN no "
     "force law or diverged); impacts/h_omega_contact is the largest"},
};

// The per-floor and per-element extents of a study's System (the study computes them from its model::System:
// study/make_results.hpp extents_of). Empty (no buildings): the SDOF pair, whose file is format 2.
struct Extents {
  std::vector<std::size_t> floors;  // per building, left to right: the most floors (DOFs) it has over the study
  std::size_t elements = 0;         // contact elements
  bool empty() const { return floors.empty(); }
  bool operator==(const Extents&) const = default;
};

// uncoupled/status of a (stripe, record) a fragility study does not analyse: the record's factor to the stripe's
// level exceeds [intensity] max_scale. Not an exclusion: the record is simply not in that stripe.
inline constexpr std::uint8_t dropped_status = 254;

// The index of a row of unit_fields, at compile time (an unknown name does not compile).
consteval std::size_t unit_field(std::string_view group, std::string_view name) {
  for (std::size_t k = 0; k < std::size(unit_fields); ++k)
    if (unit_fields[k].group == group && unit_fields[k].name == name) return k;
  throw "no such unit field";
}

// The unit fields of a scene: the per-lane rows, the per-gap rows when it runs coupled analyses, then the
// stripe_fields of a multiple-stripe study and the ida_fields of the bisection IDA, then (format 3, `system` not
// empty) system_fields(system, with_gaps). unit_fields keep their indices (unit_field()) in every schema.
std::vector<FieldSpec> unit_schema(bool with_gaps, bool ida = false, bool stripes = false, const Extents& system = {});
// The format-3 rows of `system`: floor_fields for each building (b = 1, 2, ...; count = its floors), then
// element_fields (count = the elements), the per-gap ones only `with_gaps`. Empty for empty extents.
std::vector<FieldSpec> system_fields(const Extents& system, bool with_gaps);
// A templated row ("{b}" in its name and description) for building b (1-based) with `floors` floors; the expanded
// texts are interned for the program's life (FieldSpec holds views).
FieldSpec floor_field(const FieldSpec& row, std::size_t building, std::size_t floors);
// A row_fields row for building b (1-based, >= 3).
FieldSpec row_field(const FieldSpec& row, std::size_t building);
// "peak_u_floors{b}" with b = building: the name of a floor_fields row for building b.
std::string building_name(std::string_view row_name, std::size_t building);
// The position of a row in a schema; std::logic_error when absent.
std::size_t field_index(std::span<const FieldSpec> schema, std::string_view group, std::string_view name);
// Values per lane of a row: 1, `gaps`, its count, or gaps x count (the Extent table above).
constexpr std::size_t per_lane(const FieldSpec& f, std::size_t gaps) {
  switch (f.extent) {
    case Extent::lane: return 1;
    case Extent::lane_gap: return gaps;
    case Extent::lane_floor:
    case Extent::lane_element: return f.count;
    case Extent::lane_gap_element:
    case Extent::lane_gap_floor: return gaps * f.count;
  }
  return 0;
}

}  // namespace pounding::results
