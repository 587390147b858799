#pragma once
// The results file's shared vocabulary (architecture.md 2.6, 2.7): the format version, and one table of
// FieldSpec rows describing a work unit's per-lane results. The study's UnitResult (its typed-byte
// serialisation for MPI and the checkpoint), the Tally's scatter into [records x models (x gaps)] arrays and
// the HDF5 dataset names all come from this table, so a new per-model output is one row here (and the code
// that computes it).
//
// Format 1 keeps its quirks for bit-identical files: uncoupled/peak_* are 2-D [records, models] while
// uncoupled/status and impacts/* are flat, and no dataset carries its unit yet (`unit` is written from
// format 2 on; adding an attribute now would change every file).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

namespace pounding::results {

inline constexpr std::int64_t format_version = 1;

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
  bool matrix;                   // stored 2-D [records, models] (format 1: uncoupled f64 fields), else flat
  std::string_view unit;         // SI unit ("" dimensionless, "code" for status codes)
  double fill;                   // value of a model not computed (yet)
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
    {"uncoupled", "status", Dtype::u8, Extent::lane, false, "code", 255},
    {"uncoupled", "peak_u1", Dtype::f64, Extent::lane, true, "m", NAN},
    {"uncoupled", "peak_u2", Dtype::f64, Extent::lane, true, "m", NAN},
    {"uncoupled", "peak_closing", Dtype::f64, Extent::lane, true, "m", NAN},
    {"impacts", "status", Dtype::u8, Extent::lane_gap, false, "code", 255},
    {"impacts", "impact_count", Dtype::i32, Extent::lane_gap, false, "", -1},
    {"impacts", "peak_force", Dtype::f64, Extent::lane_gap, false, "N", NAN},
    {"impacts", "peak_u1", Dtype::f64, Extent::lane_gap, false, "m", NAN},
    {"impacts", "peak_u2", Dtype::f64, Extent::lane_gap, false, "m", NAN},
    {"impacts", "t_first_impact", Dtype::f64, Extent::lane_gap, false, "s", NAN},
    // the resolution guard's h omega_c (physics/resolution.hpp): 0 for a pair that never touched, NaN without a
    // force law or when diverged; beside the limit in /settings it shows each analysis's margin
    {"impacts", "h_omega_contact", Dtype::f64, Extent::lane_gap, false, "", NAN},
};

// Written after the run from the unit fields (results::add_derived_fields).
inline constexpr FieldSpec derived_fields[] = {
    {"impacts", "amplification_u1", Dtype::f64, Extent::lane_gap, false, "", NAN},  // peak with / without pounding
    {"impacts", "amplification_u2", Dtype::f64, Extent::lane_gap, false, "", NAN},
};

// The index of a row of unit_fields, at compile time (an unknown name does not compile).
consteval std::size_t unit_field(std::string_view group, std::string_view name) {
  for (std::size_t k = 0; k < std::size(unit_fields); ++k)
    if (unit_fields[k].group == group && unit_fields[k].name == name) return k;
  throw "no such unit field";
}

// The unit fields of a scene: the per-lane rows, and the per-gap rows when it runs coupled analyses.
std::vector<FieldSpec> unit_schema(bool with_gaps);

}  // namespace pounding::results
