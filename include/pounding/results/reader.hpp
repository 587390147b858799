#pragma once
// Reads a results file written by `pounding run` (any format-1 file, including those written before
// /settings and the exclusion attributes existed: what is absent keeps its default). The per-model fields
// read are unit_fields and derived_fields (schema.hpp) plus `extra` (fields a test or a newer writer adds).
#include <span>
#include <string>

#include "pounding/results/results.hpp"

namespace pounding::results {

Results load(const std::string& path, std::span<const FieldSpec> extra = {});

}  // namespace pounding::results
