#pragma once
// Reads a results file written by `pounding run`: format 3 (/system into Results::system, and the per-floor and
// per-element fields its extents name), format 2, and any format-1 file (per-model fields stored flat,
// no /gaps: rebuilt from the study's [gaps] ratios and /models/code_gap), including those written before
// /settings and the exclusion attributes existed: what is absent keeps its default. Header::format_version is
// the file's. The per-model fields read are unit_fields, derived_fields, system_fields (schema.hpp) plus `extra` (fields a
// test or a newer writer adds); every field is flat in memory, record-major, whatever the file's shape.
#include <span>
#include <string>
#include <string_view>

#include "pounding/results/results.hpp"

namespace pounding::results {

// What load() reads. `all`: everything. `report`: what `pounding report`'s Markdown and CSV read: /gaps/metres is
// left out (ratios x code gap, which the report computes) and the /models columns it reads only to know whether
// every model is the same (all but report_model_columns) are read only until a value differs from their first:
// such a column is left empty and named in ModelTable::varying (a column that is the same for every model is read
// whole). On a 10^8-analysis file that is 1.8 GB the report never looks at, not inflated.
enum class LoadExtent { all, report };
inline constexpr std::string_view report_model_columns[] = {"T1", "T2", "h1", "h2", "m1", "m2", "code_gap", "zeta1", "zeta2"};

Results load(const std::string& path, std::span<const FieldSpec> extra = {}, LoadExtent extent = LoadExtent::all);
// The root attributes alone (provenance, the study's text): cheap, for the checks made before a run replaces a file.
// Both throw InputError naming `path` when it is not an HDF5 file, not a pounding results file (no integer
// format_version at its root: another program's file) or of a newer format, and when reading it fails (an HDF5 or
// zlib error: a damaged or truncated file).
Header load_header(const std::string& path);

}  // namespace pounding::results
