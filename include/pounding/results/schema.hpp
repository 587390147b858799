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
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

namespace pounding::results {

inline constexpr std::int64_t format_version = 2;

// Element types of a field; the order is the alternatives' order in Column.
enum class Dtype : std::uint8_t { u8, i32, i64, f64 };
// Per lane (one value per model) or per lane and gap ratio ([lane][gap] inside a unit).
enum class Extent : std::uint8_t { lane, lane_gap };

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
// stripe_fields of a multiple-stripe study and the ida_fields of the bisection IDA.
std::vector<FieldSpec> unit_schema(bool with_gaps, bool ida = false, bool stripes = false);
// The position of a row in a schema; std::logic_error when absent.
std::size_t field_index(std::span<const FieldSpec> schema, std::string_view group, std::string_view name);

}  // namespace pounding::results
