// Per-model results gathered on rank 0 in fixed arrays, the same for any completion order or rank count.
#include "pounding/study/tally.hpp"

#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "pounding/study/unit_result.hpp"

namespace pounding {

Tally::Tally(const WorkPlan& plan) : plan_(plan) {
  const std::size_t rm = plan.analysis_records() * plan.models();
  for (const results::FieldSpec& f : plan.fields) columns_.push_back(results::make_column(f, rm * plan.per_lane(f)));
  done_.assign(plan.units(), 0);
}

Tally::Tally(const WorkPlan& plan, const Study& study) : plan_(plan) {
  if (plan.per_model && !plan.stream) {
    *this = Tally(plan);
    return;
  }
  if (plan.impacts || plan.stripes || plan.ida || !plan.system.empty())
    throw std::logic_error("Tally: reductions are for the probability scene of an SDOF pair");
  reductions_ = std::make_unique<Reductions>(study, plan);
  done_.assign(plan.units(), 0);
}

// A unit's lanes are consecutive models of one record, so each field's block is one contiguous range of its
// column per stripe: [lane] at (r' M + m0 + lane), [lane][gap] at (r' M + m0 + lane) G + gap, where r' = s R + r
// is the (stripe, record) analysis record (r' = r without stripes).
void Tally::store(std::size_t unit, std::span<const std::byte> payload) {
  const UnitIndex i = plan_.decode(unit);
  const std::size_t lanes = plan_.lanes(i.block);
  if (payload.size() != serialised_size(plan_, lanes))
    throw std::runtime_error(fmt::format("unit {}: payload of {} bytes, expected {}", unit, payload.size(),
                                         serialised_size(plan_, lanes)));
  std::size_t at = 0;
  if (reductions_) {  // fold the unit's uncoupled status and peak closing; the payload is dropped
    const std::uint8_t* status = nullptr;
    const double* closing = nullptr;
    for (const results::FieldSpec& f : plan_.fields) {
      const std::size_t n = lanes * plan_.per_lane(f);
      if (f.group == "uncoupled" && f.name == "status") status = reinterpret_cast<const std::uint8_t*>(payload.data() + at);
      std::visit([&](const auto& v) { at += n * sizeof(v[0]); }, results::make_column(f, 0));
      if (f.group == "uncoupled" && f.name == "peak_closing") {
        closing = reinterpret_cast<const double*>(payload.data() + at - n * sizeof(double));
      }
    }
    if (!status || !closing) throw std::logic_error("Tally: the unit schema has no uncoupled status or peak closing");
    std::vector<double> c(closing, closing + lanes);  // aligned copy
    if (!done_[unit]) reductions_->fold(i, {status, lanes}, c);
    if (!done_[unit]) ++n_done_;
    done_[unit] = 1;
    return;
  }
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    const std::size_t per = plan_.per_lane(plan_.fields[k]);
    for (std::size_t s = 0; s < plan_.unit_stripes(); ++s) {
      const std::size_t first = (s * plan_.records + i.record) * plan_.models() + plan_.first_model(i);
      std::visit(
          [&](auto& v) {
            const std::size_t n = lanes * per * sizeof(v[0]);
            std::memcpy(v.data() + first * per, payload.data() + at, n);
            at += n;
          },
          columns_[k]);
    }
  }
  if (!done_[unit]) ++n_done_;
  done_[unit] = 1;
}

ReductionSnapshot Tally::snapshot() const {
  ReductionSnapshot s;
  s.counts = reductions_->counts();
  s.summary = reductions_->summary();
  s.done.assign((done_.size() + 7) / 8, 0);
  for (std::size_t u = 0; u < done_.size(); ++u)
    if (done_[u] == 1) s.done[u / 8] = static_cast<std::uint8_t>(s.done[u / 8] | (1u << (u % 8)));
  return s;
}

void Tally::absorb(const ReductionSnapshot& snap) {
  if (snap.units_done() == 0) return;  // an empty snapshot (a rank that had folded nothing yet)
  if (snap.done.size() != (done_.size() + 7) / 8)
    throw std::invalid_argument(fmt::format("it marks {} units, the study has {}", 8 * snap.done.size(), done_.size()));
  reductions_->add_counts(snap.counts);
  reductions_->merge_summary(snap.summary);
  for (std::size_t u = 0; u < done_.size(); ++u)
    if (snap.has(u)) {
      if (!done_[u]) ++n_done_;
      done_[u] = 1;
    }
}

std::vector<results::Field> Tally::take_fields() {
  std::vector<results::Field> out;
  for (std::size_t k = 0; k < columns_.size(); ++k) out.push_back({plan_.fields[k], std::move(columns_[k])});
  columns_.clear();
  return out;
}

}  // namespace pounding
