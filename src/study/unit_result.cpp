// One work unit's results: a typed column per field of the plan's schema.
#include "pounding/study/unit_result.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace pounding {

UnitResult::UnitResult(const WorkPlan& plan, std::size_t lanes) : lanes_(lanes), stripes_(plan.unit_stripes()) {
  columns_.reserve(plan.fields.size());
  for (const results::FieldSpec& f : plan.fields) {
    per_.push_back(plan.per_lane(f));
    columns_.push_back(results::make_column(f, plan.unit_stripes() * lanes * plan.per_lane(f)));
  }
}

template <class T>
std::span<T> UnitResult::values(std::size_t field) {
  auto* v = std::get_if<std::vector<T>>(&columns_.at(field));
  if (!v) throw std::logic_error(fmt::format("UnitResult: field {} has another element type", field));
  return *v;
}
template <class T>
std::span<T> UnitResult::lane_values(std::size_t field, std::size_t lane, std::size_t stripe) {
  if (lane >= lanes_ || stripe >= stripes_)
    throw std::out_of_range(fmt::format("UnitResult: lane {} of {}, stripe {} of {}", lane, lanes_, stripe, stripes_));
  const std::size_t per = per_.at(field);
  return values<T>(field).subspan((stripe * lanes_ + lane) * per, per);
}
template std::span<std::uint8_t> UnitResult::lane_values(std::size_t, std::size_t, std::size_t);
template std::span<std::int32_t> UnitResult::lane_values(std::size_t, std::size_t, std::size_t);
template std::span<std::int64_t> UnitResult::lane_values(std::size_t, std::size_t, std::size_t);
template std::span<double> UnitResult::lane_values(std::size_t, std::size_t, std::size_t);

template std::span<std::uint8_t> UnitResult::values(std::size_t);
template std::span<std::int32_t> UnitResult::values(std::size_t);
template std::span<std::int64_t> UnitResult::values(std::size_t);
template std::span<double> UnitResult::values(std::size_t);

std::size_t serialised_size(const WorkPlan& plan, std::size_t lanes) {
  std::size_t n = 0;
  for (const results::FieldSpec& f : plan.fields)
    n += plan.unit_stripes() * lanes * plan.per_lane(f) * results::dtype_size(f.dtype);
  return n;
}

std::vector<std::byte> UnitResult::serialise() const {
  std::vector<std::byte> out;
  for (const results::Column& c : columns_)
    std::visit(
        [&](const auto& v) {
          const auto* p = reinterpret_cast<const std::byte*>(v.data());
          out.insert(out.end(), p, p + v.size() * sizeof(v[0]));
        },
        c);
  return out;
}

UnitResult UnitResult::deserialise(const WorkPlan& plan, std::size_t lanes, std::span<const std::byte> bytes) {
  if (bytes.size() != serialised_size(plan, lanes))
    throw std::runtime_error(fmt::format("unit result of {} bytes, expected {} for {} lanes", bytes.size(),
                                         serialised_size(plan, lanes), lanes));
  UnitResult r(plan, lanes);
  std::size_t at = 0;
  for (results::Column& c : r.columns_)
    std::visit(
        [&](auto& v) {
          const std::size_t n = v.size() * sizeof(v[0]);
          if (n) std::memcpy(v.data(), bytes.data() + at, n);
          at += n;
        },
        c);
  return r;
}

}  // namespace pounding
