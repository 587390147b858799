#pragma once
// One work unit's results: a typed column per row of the plan's schema (results/schema.hpp), `lanes` values
// per lane field, lanes x gaps ([lane][gap]) per lane x gap field, lanes x floors / elements / gaps x elements per
// format-3 field (plan.per_lane), times the plan's stripes ([stripe][...]). Serialised as typed bytes -- each
// column's values in schema order, native byte order, no padding -- for MPI and the checkpoint; the size is
// implied by the schema and the lane count, and checked when read back.
#include <cstddef>
#include <span>
#include <vector>

#include "pounding/results/schema.hpp"
#include "pounding/study/plan.hpp"

namespace pounding {

class UnitResult {
 public:
  UnitResult() = default;
  // Columns for `lanes` lanes, each value the field's fill.
  UnitResult(const WorkPlan& plan, std::size_t lanes);

  std::size_t lanes() const { return lanes_; }
  std::size_t size() const { return columns_.size(); }
  const results::Column& column(std::size_t field) const { return columns_[field]; }
  // Field `field`'s values (T must be its dtype's type; a mismatch throws std::logic_error).
  template <class T>
  std::span<T> values(std::size_t field);
  // The values of lane `lane` at stripe `stripe` (0 without stripes): plan.per_lane(field) values -- one (lane),
  // [gap] (lane_gap), [floor] bottom first (lane_floor), [element] (lane_element), [gap][element]
  // (lane_gap_element). Out-of-range lane or stripe: std::out_of_range.
  template <class T>
  std::span<T> lane_values(std::size_t field, std::size_t lane, std::size_t stripe = 0);

  std::vector<std::byte> serialise() const;
  // Throws std::runtime_error when `bytes` is not the size this plan gives `lanes` lanes.
  static UnitResult deserialise(const WorkPlan& plan, std::size_t lanes, std::span<const std::byte> bytes);

 private:
  std::size_t lanes_ = 0, stripes_ = 1;
  std::vector<std::size_t> per_;  // values per lane of each column
  std::vector<results::Column> columns_;
};

// The serialised size of a unit of `lanes` lanes.
std::size_t serialised_size(const WorkPlan& plan, std::size_t lanes);

}  // namespace pounding
