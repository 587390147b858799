// PairRunner: a unit's SDOF pairs through the pair kernel (pounding::run_batch), study/runner.hpp.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/model/sdof.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/study/refine.hpp"
#include "pounding/study/runner.hpp"

namespace pounding {

namespace {

// The hysteresis model of the springs the kernel runs (model::Registered), asked for its driver traits.
using Spring = model::Registered::Spring;
static_assert(model::Hysteresis<Spring>);

// The pair whose response to the unscaled record, times f, is the response of `pp` to the record times f: each
// spring's unscaled_equivalent (bilinear: fy / f). Every registered model the study runs has one; a model
// without (answering std::nullopt) would need its lane run on the scaled record, which the bisection does not do.
PairParams unscaled_equivalent(PairParams pp, double f) {
  const std::optional<Structure> s1 = Spring::unscaled_equivalent(pp.s1, f), s2 = Spring::unscaled_equivalent(pp.s2, f);
  if (!s1 || !s2) throw std::logic_error("IDA bisection: the structure model does not scale with the record");
  pp.s1 = *s1, pp.s2 = *s2;
  return pp;
}

// The first n lanes of a kernel result as RunPeaks (two bodies, u = {u1, u2}); every value copied.
void put_peaks(const BatchResult& r, std::size_t n, RunPeaks& out) {
  out.resize(n, 2);
  for (std::size_t i = 0; i < n; ++i) {
    out.status[i] = r.status[i];
    out.u1[i] = r.peak_u1[i], out.u2[i] = r.peak_u2[i], out.closing[i] = r.peak_closing[i];
    out.u[2 * i] = r.peak_u1[i], out.u[2 * i + 1] = r.peak_u2[i];
    out.impact_count[i] = r.impact_count[i], out.restitution_outside[i] = r.restitution_outside[i];
    out.peak_force[i] = r.peak_force[i], out.t_first_impact[i] = r.t_first_impact[i];
    out.h_omega_contact[i] = r.h_omega_contact[i];
  }
}

class PairRunner final : public Runner {
 public:
  PairRunner(const Study& s, const WorkPlan& plan)
      : s_(s), refine_(s.coarse == CoarsePolicy::refine && plan.impacts) {
    uncoupled_ = s.contact;
    uncoupled_.law = ContactLaw::none;
  }

  void load(std::span<const SampledPair> block) override {
    pairs_ = block;
    const std::size_t n = block.size();
    batch_.resize(n);
    for (std::size_t i = 0; i < n; ++i) batch_.set(i, pairs_[i].pair_params(0.0, s_.e));
  }

  void uncoupled(const UnitMotion& m, const KernelSettings& ks, RunPeaks& out) override {
    run_batch(batch_, uncoupled_, m.gm, ks, res_);
    put_peaks(res_, pairs_.size(), out);
  }

  void rerun_uncoupled(std::span<const std::size_t> lanes, const UnitMotion& m, const KernelSettings& ks,
                       RunPeaks& out) override {
    sub_.resize(lanes.size());
    for (std::size_t j = 0; j < lanes.size(); ++j) sub_.set(j, batch_.get(lanes[j]));
    run_batch(sub_, uncoupled_, m.gm, ks, res_);
    put_peaks(res_, lanes.size(), out);
  }

  // A pair whose uncoupled peak closing stays <= g never touches at gap g: the scene runs only the others.
  void coupled(std::span<const std::size_t> lanes, double x, const UnitMotion& m, const KernelSettings& kc,
               RunPeaks& out) override {
    sub_.resize(lanes.size());
    for (std::size_t j = 0; j < lanes.size(); ++j) {
      PairParams pp = pairs_[lanes[j]].pair_params(x, s_.e);
      pp.gap = x * s_.gap_unit(pairs_[lanes[j]]);  // ratio x d (the same product), or metres
      if (s_.contact_stiffness > 0) pp.kc = s_.contact_stiffness;
      sub_.set(j, pp);
    }
    if (!lanes.empty()) run_batch(sub_, s_.contact, m.gm, kc, cres_);
    out.substeps.assign(lanes.size(), kc.substeps);  // [analysis] coarse = "refine": the coarse lanes again
    if (refine_ && !lanes.empty()) refine_pairs(sub_, s_.contact, m.gm, kc, cres_, one_, out.substeps);
    put_peaks(cres_, lanes.size(), out);
  }

  // Lane i of the anchor run stays elastic when the record is scaled by `ratio` more: each spring's hysteresis model
  // answers (stays_elastic, model/hysteresis/registry.hpp), not a value test here.
  bool scales_linearly(const RunPeaks& anchor, std::size_t i, double ratio, double limit) const override {
    constexpr double margin = 1.0 - 1e-9;
    const double u1 = ratio * anchor.u1[i], u2 = ratio * anchor.u2[i];
    if (anchor.status[i] != 0) return false;
    const PairParams p = batch_.get(i);
    return Spring::stays_elastic(p.s1, u1, margin) && Spring::stays_elastic(p.s2, u2, margin) && u1 + u2 <= limit;
  }

  // One kernel lane per entry with each spring replaced by its unscaled equivalent at the entry's factor, the record
  // unscaled; the peaks times f (the displacement limit applied to them).
  void at_factors(std::span<const LaneFactor> entries, const Record& rec, double free_vibration,
                  const KernelSettings& ks, FactorPeaks& out) override {
    const GroundMotion gm{rec.dt, rec.acc, rec.duration() + free_vibration};
    sub_.resize(entries.size());
    double f_min = INFINITY;
    for (std::size_t j = 0; j < entries.size(); ++j) {
      f_min = std::min(f_min, entries[j].f);
      sub_.set(j, unscaled_equivalent(pairs_[entries[j].lane].pair_params(0.0, s_.e), entries[j].f));
    }
    KernelSettings kb = ks;
    kb.displacement_limit = ks.displacement_limit / f_min;  // the exact limit is applied per lane below
    run_batch(sub_, uncoupled_, gm, kb, bres_);
    out.excluded.resize(entries.size()), out.ran.assign(entries.size(), 1), out.closing.resize(entries.size());
    for (std::size_t j = 0; j < entries.size(); ++j) {
      const double f = entries[j].f;
      // the kernel's limit is on |u1| + |u2| at one instant; the sum of the peaks bounds it (conservative)
      out.excluded[j] = bres_.status[j] != 0 || f * (bres_.peak_u1[j] + bres_.peak_u2[j]) > ks.displacement_limit;
      out.closing[j] = f * bres_.peak_closing[j];
    }
  }

  const TableLayout& layout() const override { return layout_; }

 private:
  const Study& s_;
  bool refine_;  // [analysis] coarse = "refine" in the impacts scene (study/refine.hpp)
  ContactModel uncoupled_;
  std::span<const SampledPair> pairs_;
  PairBatch batch_, sub_;
  BatchResult res_, cres_, bres_;
  RefineScratch one_;
  TableLayout layout_;  // empty: the pair has no per-floor rows
};

}  // namespace

std::unique_ptr<Runner> make_pair_runner(const Study& s, const WorkPlan& plan) {
  return std::make_unique<PairRunner>(s, plan);
}

std::unique_ptr<Runner> make_runner(const Study& s, const WorkPlan& plan) {
  return runs_systems(s.structures) ? make_system_runner(s, plan) : make_pair_runner(s, plan);
}

}  // namespace pounding
