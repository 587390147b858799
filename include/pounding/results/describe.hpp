#pragma once
// What every dataset of a results file means (format 2, docs/results-format.md): its unit and a one-line
// description, written as the dataset's `units` and `description` attributes. Per-model fields carry theirs in
// their schema row (schema.hpp); the other groups (/records, /models, /gaps and the impacts group's gap axis)
// have one table each in describe.cpp. The writer refuses a dataset without a row, and
// tests/results/test_results.cpp checks that every dataset of a written file has both attributes, so a new
// dataset cannot be written without saying what it is.
#include <optional>
#include <string_view>

namespace pounding::results {

struct Description {
  std::string_view units;        // SI: m, N, s, kg, N/m, N/m^1.5, kg/m^3, g; "1" dimensionless, codes, counts
  std::string_view description;  // one line
};

// The row of /<group>/<name>: the group's table, then the schema's unit and derived fields; none when there is none.
std::optional<Description> describe(std::string_view group, std::string_view name);

}  // namespace pounding::results
