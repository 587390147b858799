#pragma once
// [outputs] per_model = false (issue 27, item 5): a study larger than memory keeps only REDUCTIONS, folded in on
// rank 0 as units complete (each unit's payload is dropped once folded), instead of every model's peaks.
// Everything kept is an integer count, so the reductions do not depend on the rank count, the thread count, the
// batch width or the order in which units complete (and a resume that refolds the checkpoint's units gives the
// same counts). Per record row r (the analyses of one record and sign), with z = peak closing / code gap d of an
// ok analysis (status 0, or coarse kept by [analysis] coarse = "keep"):
//   n[r]                 ok analyses;  excluded[r]: the others (diverged, non-finite)
//   gap_hits[r, g]       ok analyses with peak closing > ratio_g * d          (Table 2 and 3: the report's test)
//   pair_n[r, p], pair_hits[r, p, g]: the same per period pair p (the maps)
//   curve_hits[r, c]     ok analyses with z > x_c, x_c = curve_step * c (c = 1..floor(curve_max / curve_step))
//   histogram[r, b]      z in bin b of a log grid: bin 0 is z <= histogram_lo (a pair that never closes included),
//                        bin b in 1..B is (e_{b-1}, e_b], e_b = histogram_lo 10^(b / per_decade), bin B + 1 is
//                        z > histogram_hi
// Memory: 8 bytes x rows x (3 + gaps + pairs (1 + gaps) + curve points + bins + 2), independent of the models per
// pair, plus one byte per unit for the done flags (Tally).
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pounding/results/results.hpp"
#include "pounding/study/plan.hpp"

namespace pounding {

struct Study;
class StructureSampler;

inline constexpr double histogram_lo = 1e-3, histogram_hi = 1e2;  // z = peak closing / d
inline constexpr int histogram_per_decade = 200;                   // bin width: a factor 10^(1/200) = 1.0116
std::vector<double> histogram_edges();                             // e_0 .. e_B (B = 5 x 200 bins)
// Bytes of the reductions for `rows` record rows (the per_model = false result size, result_bytes).
double reduction_bytes(std::size_t rows, std::size_t pairs, std::size_t gaps, std::size_t curve_points);

class Reductions {
 public:
  Reductions(const Study& study, const WorkPlan& plan);
  ~Reductions();
  Reductions(Reductions&&) noexcept;
  Reductions& operator=(Reductions&&) noexcept;

  // One unit's lanes (consecutive samples of one period pair under one record row): status and peak closing.
  void fold(const UnitIndex& unit, std::span<const std::uint8_t> status, std::span<const double> closing);
  bool ok(std::uint8_t status) const;
  // Merging the reductions of other ranks (issue 27.4: every rank folds the units it computes): the integer counts
  // (summed over ranks) and the order-free summary of the models folded (whether all were one pair, the code gaps'
  // range; merged), each as a flat vector of fixed length for the same study and plan.
  std::vector<std::int64_t> counts() const;
  void set_counts(std::span<const std::int64_t> summed);
  // Adds counts of the same length (a checkpoint snapshot's); throws std::invalid_argument on another length.
  void add_counts(std::span<const std::int64_t> more);
  std::vector<double> summary() const;
  void merge_summary(std::span<const double> other);
  std::int64_t excluded(std::size_t row) const { return excluded_[row]; }
  std::int64_t analysed(std::size_t row) const { return n_[row] + excluded_[row]; }
  // The results group "reductions" (docs/results-format.md).
  results::Group group() const;

 private:
  const Study* study_;
  WorkPlan plan_;
  std::unique_ptr<StructureSampler> sampler_;
  std::vector<double> curve_x_, edges_;
  std::vector<std::int64_t> n_, excluded_, gap_hits_, pair_n_, pair_hits_, curve_hits_, histogram_;
  std::vector<std::int32_t> pair_i1_, pair_i2_;
  // [outputs] per_model = "stream" (plan.stream): each model's code gap d kept after its first fold (8 bytes per
  // model; that mode's memory grows with the models anyway), so the other records' units of the same models are
  // folded without drawing the models again (the draw is 0.4 us per model, most of a fold). per_model = false draws
  // them every time and keeps nothing per model.
  std::vector<double> gap_of_;
  void fold_one(std::size_t row, std::size_t pair, std::uint8_t status, double closing, double d);
  std::vector<char> drawn_;  // per (pair, block): gap_of_ holds its models' d
  // every model equal to the first folded (a fixed pair; the report's Wilson basis): order-independent
  std::array<double, 15> first_{};
  bool seen_ = false, varied_ = false;
  double gap_min_ = 0, gap_max_ = 0;  // the code gaps d folded (order-independent)
};

}  // namespace pounding
