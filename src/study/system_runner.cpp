// SystemRunner: a unit's Systems (shear buildings, rows, bridges) through SystemBlock, study/runner.hpp.
#include <string>

#include "pounding/study/refine.hpp"
#include "pounding/study/runner.hpp"

namespace pounding {

namespace {

class SystemRunner final : public Runner {
 public:
  SystemRunner(const Study& s, const WorkPlan& plan)
      : s_(s), block_(s.structures, s.contact, s.e, s.contact_levels, s.gap_offsets, s.level_tolerance,
                      s.shape_functions),
        refine_(s.coarse == CoarsePolicy::refine && plan.impacts) {
    uncoupled_ = s.contact;
    uncoupled_.law = ContactLaw::none;
    block_.set_joint_offsets(s.joint_gap_offsets), block_.set_gap_metres(s.gap_metres);
    // results format 3: the per-floor and per-element rows laid out as the study's largest topology (the plan's /system)
    if (!plan.system.empty()) block_.set_table(block_.table_system(*table_topology(s.structures, s.seed)));
    if (plan.stripes || plan.ida) block_.keep_springs(true);  // scales_linearly reads them
  }

  void load(std::span<const SampledPair> block) override { pairs_ = block; }

  void uncoupled(const UnitMotion& m, const KernelSettings& ks, RunPeaks& out) override {
    block_.set_channels(m.channels);
    block_.uncoupled(pairs_, uncoupled_, m.gm, ks, out);
  }

  // SystemBlock::coupled at ratio 0 with the law none is the uncoupled run of those lanes
  void rerun_uncoupled(std::span<const std::size_t> lanes, const UnitMotion& m, const KernelSettings& ks,
                       RunPeaks& out) override {
    block_.set_channels(m.channels);
    block_.coupled(pairs_, lanes, 0.0, uncoupled_, ContactNumbers{}, m.gm, ks, out);
  }

  // The coupled Systems of `lanes` at gap ratio x, the coarse ones refined ([analysis] coarse = "refine",
  // study/refine.hpp)
  void coupled(std::span<const std::size_t> lanes, double x, const UnitMotion& m, const KernelSettings& kc,
               RunPeaks& out) override {
    block_.set_channels(m.channels);
    out.substeps.assign(lanes.size(), kc.substeps);
    if (lanes.empty()) return;
    const ContactNumbers cn{s_.e, s_.contact_stiffness};
    block_.coupled(pairs_, lanes, x, s_.contact, cn, m.gm, kc, out);
    if (refine_) refine_systems(block_, pairs_, lanes, x, s_.contact, cn, m.gm, kc, out, one_, out.substeps);
  }

  bool scales_linearly(const RunPeaks& anchor, std::size_t k, double ratio, double limit) const override {
    return block_.scales_linearly(anchor, k, ratio, limit);
  }

  // A System has no unscaled equivalent in general (a smooth bearing, a moat wall, the guard's sum over floors), so
  // the record is scaled, one run per (lane, factor); consecutive entries of one lane at one factor share its run.
  void at_factors(std::span<const LaneFactor> entries, const Record& rec, double free_vibration,
                  const KernelSettings& ks, FactorPeaks& out) override {
    out.excluded.resize(entries.size()), out.ran.resize(entries.size()), out.closing.resize(entries.size());
    block_.set_channels({});
    std::size_t ran = std::string::npos;
    double ran_f = 0.0;
    for (std::size_t j = 0; j < entries.size(); ++j) {
      const std::size_t i = entries[j].lane;
      const double f = entries[j].f;
      out.ran[j] = i != ran || f != ran_f;
      if (out.ran[j]) {
        const std::size_t one[] = {i};
        scaled_.resize(rec.acc.size());
        for (std::size_t t = 0; t < scaled_.size(); ++t) scaled_[t] = f * rec.acc[t];
        const GroundMotion gm{rec.dt, scaled_, rec.duration() + free_vibration};
        block_.coupled(pairs_, one, 0.0, uncoupled_, ContactNumbers{}, gm, ks, sub_);
        ran = i, ran_f = f;
      }
      out.excluded[j] = sub_.status[0] != 0;
      out.closing[j] = sub_.closing[0];
    }
  }

  const TableLayout& layout() const override { return block_.layout(); }

 private:
  const Study& s_;
  SystemBlock block_;
  bool refine_;  // [analysis] coarse = "refine" in the impacts scene (study/refine.hpp)
  ContactModel uncoupled_;
  std::span<const SampledPair> pairs_;
  std::vector<double> scaled_;
  RunPeaks sub_;
  RefineScratch one_;
};

}  // namespace

std::unique_ptr<Runner> make_system_runner(const Study& s, const WorkPlan& plan) {
  return std::make_unique<SystemRunner>(s, plan);
}

}  // namespace pounding
