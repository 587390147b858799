// The unit's scenes (docs/runner-design.md section 3), each written once against the Runner: what they read and write.
#pragma once
// A unit (study/unit_computer.cpp) samples its block, builds its motion, then runs stripes (stripes.cpp), or
// probability (probability.cpp) followed by impacts (impacts.cpp) when the plan couples gaps and ida (ida.cpp) when it
// bisects: that order decides the bits. The field writers (fields.cpp) put a lane of RunPeaks into the UnitResult by
// the plan's schema: the pair's columns, then a row's buildings 3..n and the per-floor / per-element rows where the
// schema has them. No scene tests the structure kind: the runner answers.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/study/intensity.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/study/runner.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/unit_result.hpp"

namespace pounding::study_run {

// The positions in the plan's schema of the fields the scenes fill beside the fixed ones (fields.cpp's `field`).
struct FieldIndex {
  static constexpr std::size_t npos = std::string::npos;
  std::size_t rest_out = 0;  // [contact] restitution: impacts/restitution_outside
  std::size_t e_outside = 0;  // and impacts/element_restitution_outside (format 3)
  std::size_t substeps = npos;  // [analysis] coarse = "refine": impacts/substeps (npos: another policy)
  std::size_t stripe_scaled = 0;  // uncoupled/scaled (multiple stripes)
  std::size_t ida_analyses = 0, ida_limit = 0, ida_lo = 0, ida_hi = 0;  // the ida rows
  // Format 3: per building the per-floor rows, uncoupled and impacts; a row's buildings 3..n peak_u{b}; the elements'
  std::vector<std::size_t> floor_u, floor_drift, floor_acc, imp_floor_u, imp_floor_drift, imp_floor_acc;
  std::vector<std::size_t> row_unc, row_imp;
  std::size_t e_closing = 0, e_count = 0, e_force = 0, e_pen = 0, e_first = 0, e_hw = 0;
};
// The fields of `plan` for a study whose runner lays its rows out as `layout` (empty: format 2).
FieldIndex field_index(const Study& s, const WorkPlan& plan, const TableLayout& layout);

// Per thread: the buffers the scenes write between a unit's runs.
struct Scratch {
  RunPeaks peaks, coupled;    // the uncoupled run, a gap's coupled run
  RunPeaks anchor, cur, sub;  // fragility studies: the anchor run, the peaks at a factor, a rerun
  std::vector<std::size_t> lanes;  // the lanes a call runs (impacts: coupled; peaks_at: rerun)
  std::vector<std::size_t> todo;   // the IDA's open brackets, (lane, gap) as lane x gaps + gap
  std::vector<LaneFactor> mids;    // and their midpoints
  FactorPeaks factors;
  std::vector<double> scaled;  // the record times a factor
  std::vector<GroundMotion> channels;  // a multi-support bridge's motions of the unit's record
};

// One unit: read only the study, plan, stripes, fields, record and kernel settings; per thread the runner (loaded
// with `block`) and the scratch.
struct UnitContext {
  const Study& s;
  const WorkPlan& plan;
  const StripePlan& stripes;
  const FieldIndex& fields;
  const physics::HertzdampRestitution* restitution;  // [contact] restitution in the impacts scene, else null
  const StudyRecord& record;
  std::size_t r;  // the record's index
  const KernelSettings& ks;
  Runner& runner;
  std::span<const SampledPair> block;
  Scratch& scratch;
};

// fields.cpp: value k of the uncoupled pair columns from lane i of p ([stripe][lane] in a multiple-stripe unit)
void put_uncoupled(UnitResult& out, std::size_t k, const RunPeaks& p, std::size_t i);
// lane i's per-floor / per-element rows and a row's buildings 3..n from lane i of p, at stripe `stripe`
void put_uncoupled_rows(const UnitContext& c, UnitResult& out, std::size_t i, const RunPeaks& p, std::size_t stripe);
// lane i's impacts at gap g: from lane j of scratch.coupled, or (j = npos, untouched) its uncoupled peaks
void put_coupled(const UnitContext& c, UnitResult& out, std::size_t i, std::size_t g, std::size_t j);

// The record times f, in scratch.scaled.
std::span<const double> scaled(Scratch& scratch, const Record& rec, double f);

void probability(UnitContext& c, const UnitMotion& m, UnitResult& out);              // probability.cpp
void impacts(UnitContext& c, std::size_t g, const UnitMotion& m, UnitResult& out);  // impacts.cpp, gap g
void stripes(UnitContext& c, UnitResult& out);                                      // stripes.cpp
// Every lane's peaks under the record scaled by f into scratch.cur (fa == 0: the anchor run; fa becomes f), the lanes
// run in scratch.lanes (stripes.cpp; the IDA's hunt calls it, so the hunt is the stripes' analysis bit for bit).
void peaks_at(UnitContext& c, double f, double& fa);
void ida(UnitContext& c, UnitResult& out);  // ida.cpp

}  // namespace pounding::study_run
