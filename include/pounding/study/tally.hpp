#pragma once
// Per-model results gathered on rank 0 in fixed arrays, one column per schema field ([records x models] or
// [records x models x gaps]): any completion order, rank count or resume gives the same arrays.
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "pounding/results/results.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/study/reductions.hpp"

namespace pounding {

class Tally {
 public:
  Tally() = default;
  explicit Tally(const WorkPlan& plan);
  // With plan.per_model = false the units are folded into Reductions (reductions.hpp) and no column is kept; with
  // plan.stream (per_model = "stream") too: the per-model values stay in the checkpoint files, from which the
  // results file is written (study/spill.hpp).
  Tally(const WorkPlan& plan, const Study& study);

  // Scatters one unit's serialised result (UnitResult::serialise) into the columns; throws std::runtime_error
  // on a payload of the wrong size. Storing a unit twice overwrites it.
  void store(std::size_t unit, std::span<const std::byte> payload);

  bool done(std::size_t unit) const { return done_[unit] != 0; }
  std::size_t units_done() const { return n_done_; }
  std::size_t units() const { return done_.size(); }
  const results::Column& column(std::size_t field) const { return columns_[field]; }
  template <class T>
  const std::vector<T>& values(std::size_t field) const {
    return std::get<std::vector<T>>(columns_[field]);
  }
  const Reductions* reductions() const { return reductions_.get(); }
  Reductions* reductions() { return reductions_.get(); }
  // Reductions only: unit `unit` was folded into another rank's Reductions (merged at the end): counted done here,
  // but not in this rank's snapshot.
  void folded_elsewhere(std::size_t unit) {
    if (!done_[unit]) ++n_done_, done_[unit] = elsewhere;
  }
  // Reductions only: the other ranks' counts were merged into this one (after the units): every unit is folded here.
  void merged_elsewhere() {
    for (char& d : done_)
      if (d == elsewhere) d = 1;
  }
  // Reductions only: this rank's checkpoint snapshot (its counts, summary and the units folded HERE), and the
  // loading of one (counts added, summaries merged, its units marked done; the caller has checked that none of them
  // is done already). absorb throws std::invalid_argument when the snapshot's lengths do not fit this study.
  ReductionSnapshot snapshot() const;
  void absorb(const ReductionSnapshot& snap);
  // The columns as results fields (the tally is left empty).
  std::vector<results::Field> take_fields();

 private:
  WorkPlan plan_;
  std::vector<results::Column> columns_;
  static constexpr char elsewhere = 2;  // done_: folded by another rank (1: folded or stored here)
  std::vector<char> done_;
  std::unique_ptr<Reductions> reductions_;
  std::size_t n_done_ = 0;
};

}  // namespace pounding
