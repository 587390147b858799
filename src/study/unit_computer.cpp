// UnitComputer: one work unit of a study -- the block sampled, the motion built, then the scenes (scenes/scene.hpp).
#include "unit_computer.hpp"

#include <atomic>
#include <memory>
#include <vector>

#include "pounding/sampling/sampler.hpp"
#include "pounding/study/runner.hpp"

#include "run_phases.hpp"
#include "scenes/scene.hpp"

namespace pounding::study_run {

namespace {

// The unit's motion: the record with the study's free vibration, a multi-support bridge's channels (in
// scratch.channels).
UnitMotion unit_motion(const UnitContext& c) {
  const Record& rec = c.record.record;
  const GroundMotion gm{rec.dt, rec.acc, rec.duration() + c.s.free_vibration};
  // a bridge on several supports ([records] supports): channel k is the realisation's support k + 1
  const int channels = c.s.structures.bridge ? c.s.structures.bridge->spec.channels() : 1;
  std::vector<GroundMotion>& out = c.scratch.channels;
  out.clear();
  for (int k = 0; k < channels && channels > 1; ++k)
    out.push_back(k == 0 ? gm
                         : GroundMotion{rec.dt, c.record.more_supports[static_cast<std::size_t>(k - 1)].acc,
                                        rec.duration() + c.s.free_vibration});
  return UnitMotion{gm, out};
}

}  // namespace

// One work unit: sample the block, run its scenes, fill a UnitResult. A rank's threads have one UnitComputer each: it
// holds every buffer it writes (its Runner, the sampled block, the scenes' Scratch); what it shares with the others is
// read only (study, records, stripes, sampler, plan) except `computed`, the rank's count of units started (the compute
// fault fires on the rank's third).
class UnitComputer {
 public:
  UnitComputer(const Study& s, const std::vector<StudyRecord>& records, const StripePlan& stripes,
               const StructureSampler& sampler, const WorkPlan& plan, int rank, std::atomic<int>& computed,
               const std::atomic<bool>* stop)
      : s_(s), records_(records), stripes_(stripes), sampler_(sampler), plan_(plan), rank_(rank), computed_(computed),
        runner_(make_runner(s, plan)), fields_(field_index(s, plan, runner_->layout())) {
    ks_base_.stop = stop;  // a stop reaches the steppers inside a unit (StopRequested: the unit is left to --resume)
    ks_base_.stepper = s.stepper;
    ks_base_.displacement_limit = s.displacement_limit;
    if (s.restitution && plan.impacts)  // e(v0) in the coupled runs (study.cpp: hertzdamp, CD, impacts scene)
      restitution_ = std::make_unique<physics::HertzdampRestitution>(*s.restitution, s.contact);
  }

  // The unit's pipeline: stripes, or probability followed by impacts (gaps coupled) and ida (it bisects); the
  // order is today's, which decides the bits.
  UnitResult operator()(std::size_t unit) {
    if (++computed_ == 3) inject_fault("compute", rank_);  // the rank's third unit, on whichever thread
    const UnitIndex u = plan_.decode(unit);
    const std::size_t n = plan_.lanes(u.block);
    pairs_.resize(n);
    const SampleId pair = s_.structures.pair_id(static_cast<std::int64_t>(u.pair));  // slots i1, i2
    sampler_.sample_block(pair.i1, pair.i2, static_cast<std::int64_t>(u.block * plan_.batch), pairs_);
    KernelSettings ks = ks_base_;
    ks.substeps = study_substeps(s_, records_[u.record].record.dt);
    UnitResult out(plan_, n);
    runner_->load(pairs_);
    UnitContext c{s_, plan_, stripes_, fields_, restitution_.get(), records_[u.record], u.record, ks, *runner_, pairs_,
                  scratch_};
    if (plan_.stripes) {
      stripes(c, out);
      return out;
    }
    const UnitMotion m = unit_motion(c);
    probability(c, m, out);
    if (plan_.impacts)
      for (std::size_t g = 0; g < plan_.gaps; ++g) impacts(c, g, m, out);
    if (plan_.ida) ida(c, out);
    return out;
  }

 private:
  const Study& s_;
  const std::vector<StudyRecord>& records_;
  const StripePlan& stripes_;
  const StructureSampler& sampler_;
  const WorkPlan& plan_;
  int rank_;
  std::atomic<int>& computed_;
  KernelSettings ks_base_;
  std::unique_ptr<Runner> runner_;  // the pair kernel or the system stepper (study/runner.hpp)
  FieldIndex fields_;
  std::unique_ptr<physics::HertzdampRestitution> restitution_;  // [contact] restitution: the kernel's e(v0) hook
  std::vector<SampledPair> pairs_;
  Scratch scratch_;
};

void UnitComputerDelete::operator()(UnitComputer* c) const noexcept { delete c; }

UnitComputerPtr make_unit_computer(const Study& s, const std::vector<StudyRecord>& records, const StripePlan& stripes,
                                   const StructureSampler& sampler, const WorkPlan& plan, int rank,
                                   std::atomic<int>& computed, const std::atomic<bool>* stop) {
  return UnitComputerPtr(new UnitComputer(s, records, stripes, sampler, plan, rank, computed, stop));
}

UnitResult compute_unit(UnitComputer& computer, std::size_t unit) { return computer(unit); }

}  // namespace pounding::study_run
