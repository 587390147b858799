#pragma once
// What every dataset of a results file means (formats 2 and 3, docs/results-format.md): its unit and a one-line
// description, written as the dataset's `units` and `description` attributes. Per-model fields carry theirs in
// their schema row (schema.hpp); the other groups (/records, /models, /gaps and the impacts group's gap axis)
// have one table each in describe.cpp. The writer refuses a dataset without a row, and
// tests/results/test_results.cpp checks that every dataset of a written file has both attributes, so a new
// dataset cannot be written without saying what it is.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pounding::results {

struct Description {
  std::string_view units;        // SI: m, N, s, kg, N/m, N/m^1.5, kg/m^3, g; "1" dimensionless, codes, counts
  std::string_view description;  // one line
};

// The row of /<group>/<name>: the group's table (/system's included), then the schema's unit, per-element,
// per-floor (any building: "peak_drift3") and derived fields; none when there is none.
std::optional<Description> describe(std::string_view group, std::string_view name);
// The rows of /gaps on a metres axis ([gaps] metres: /gaps/axis, and /gaps/metres described as such).
std::optional<Description> describe_metres_axis(std::string_view name);

// One dataset of a results file as `pounding results FILE` lists it.
struct DatasetInfo {
  std::string path;                // "/uncoupled/peak_u_floors2"
  std::string type;                // "f64", "i64", "i32", "u8", "string", "other"
  std::vector<std::size_t> shape;  // [] for a scalar
  std::string units, description, axes;  // its attributes ("" when absent: files of format 1)
};
// Every dataset of the HDF5 file at `path` (any format), groups and members in name order. InputError when `path`
// is not an HDF5 file.
std::vector<DatasetInfo> inventory(const std::string& path);

}  // namespace pounding::results
