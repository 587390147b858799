// The runner of a study's unit (docs/runner-design.md section 2): the pair kernel or the system stepper behind one interface.
#pragma once
// A unit's scenes (src/study/scenes/) run their batches through a Runner: PairRunner (src/study/pair_runner.cpp)
// holds a PairBatch and calls pounding::run_batch, SystemRunner (src/study/system_runner.cpp) wraps SystemBlock. Each
// method is the branch of the scenes it replaced, moved verbatim: the same kernel calls on the same batches in the
// same order, so the bits are the same. A virtual call happens once per batch, never per step.
//
// Both fill RunPeaks (study/system_block.hpp): lane j of a call's output is the call's lanes[j] (all lanes: j = lane).
// The pair's RunPeaks has two bodies (u = {u1, u2}), no table rows, no springs.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "pounding/study/plan.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/system_block.hpp"

namespace pounding {

// A unit's motion: the record (with the study's free vibration); channels: a multi-support bridge's motions (support
// 1 first), empty for uniform input.
struct UnitMotion {
  GroundMotion gm;
  std::span<const GroundMotion> channels;
};
// One open IDA bracket's midpoint: the block's lane and the record's factor.
struct LaneFactor {
  std::size_t lane = 0;
  double f = 0.0;
};
// Per entry of at_factors: the peak closing under f x the record, whether the analysis is excluded (diverged, or the
// pair's displacement limit at f), and whether it cost an analysis (a System's later entries of one lane at one
// factor share the first's run).
struct FactorPeaks {
  std::vector<std::uint8_t> excluded, ran;
  std::vector<double> closing;
};

// One per worker thread; owns every buffer it writes.
class Runner {
 public:
  virtual ~Runner() = default;
  // The unit's sampled models (kept as a view: `block` outlives the unit's calls).
  virtual void load(std::span<const SampledPair> block) = 0;
  // Every lane uncoupled (the study's contact with law none).
  virtual void uncoupled(const UnitMotion& m, const KernelSettings& ks, RunPeaks& out) = 0;
  // The lanes `lanes` uncoupled (out[j]: lanes[j]); a lane's bits do not depend on the lanes run beside it.
  virtual void rerun_uncoupled(std::span<const std::size_t> lanes, const UnitMotion& m, const KernelSettings& ks,
                               RunPeaks& out) = 0;
  // The lanes `lanes` coupled at the study gap gap_ratio x Study::gap_unit with the study's contact, e and [contact]
  // stiffness; out.substeps[j] lane j's substeps (refined: [analysis] coarse = "refine"). No kernel call for no lanes.
  virtual void coupled(std::span<const std::size_t> lanes, double gap_ratio, const UnitMotion& m, const KernelSettings& ks,
                       RunPeaks& out) = 0;
  // Shortcut 1, linear scaling: lane k of `anchor` (an uncoupled run) under the record x ratio (>= 1) more has its
  // peaks times ratio: every spring stays elastic at ratio x its peak, and ratio x the peaks within `limit`.
  virtual bool scales_linearly(const RunPeaks& anchor, std::size_t k, double ratio, double limit) const = 0;
  // Shortcut 2, the IDA's bisection: per entry the peak closing under f x the record (rec, free_vibration after it).
  virtual void at_factors(std::span<const LaneFactor> entries, const Record& rec, double free_vibration,
                          const KernelSettings& ks, FactorPeaks& out) = 0;
  // Where the per-floor / per-element rows go (empty: results format 2).
  virtual const TableLayout& layout() const = 0;
};

// By the structure kind: SystemRunner for Systems (runs_systems: shear buildings, rows, bridges), else PairRunner.
std::unique_ptr<Runner> make_runner(const Study& s, const WorkPlan& plan);
// Each runner on its own (tests/study/test_runner.cpp runs one block of SDOF pairs through both). The study and the
// plan are read at construction and by reference after it: they outlive the runner.
std::unique_ptr<Runner> make_pair_runner(const Study& s, const WorkPlan& plan);
std::unique_ptr<Runner> make_system_runner(const Study& s, const WorkPlan& plan);

}  // namespace pounding
