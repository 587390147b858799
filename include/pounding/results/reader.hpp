#pragma once
// Reads a results file written by `pounding run`: format 3 (/system into Results::system, and the per-floor and
// per-element fields its extents name), format 2, and any format-1 file (per-model fields stored flat,
// no /gaps: rebuilt from the study's [gaps] ratios and /models/code_gap), including those written before
// /settings and the exclusion attributes existed: what is absent keeps its default. Header::format_version is
// the file's. The per-model fields read are unit_fields, derived_fields, system_fields (schema.hpp) plus `extra` (fields a
// test or a newer writer adds); every field is flat in memory, record-major, whatever the file's shape.
#include <span>
#include <string>

#include "pounding/results/results.hpp"

namespace pounding::results {

Results load(const std::string& path, std::span<const FieldSpec> extra = {});
// The root attributes alone (provenance, the study's text): cheap, for the checks made before a run replaces a file.
// Throws InputError when `path` is not an HDF5 file.
Header load_header(const std::string& path);

}  // namespace pounding::results
