// The study's main job: work units through the kernel or the system stepper, checkpoint, results file, report.
#include "pounding/study/run.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <algorithm>
#include <memory>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/core/error.hpp"
#include "pounding/core/parallel_for.hpp"
#include "pounding/core/files.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/model/sdof.hpp"
#include "pounding/motion/library.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/results/writer.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/histories.hpp"
#include "pounding/study/make_results.hpp"
#include "pounding/study/plan.hpp"
#include "pounding/study/refine.hpp"
#include "pounding/study/system_block.hpp"
#include "pounding/study/spill.hpp"
#include "pounding/study/tally.hpp"
#include "pounding/study/unit_result.hpp"

namespace pounding {

namespace fs = std::filesystem;
// The hysteresis model of the springs the kernel runs (model::Registered), asked for its driver traits.
using Spring = model::Registered::Spring;
static_assert(model::Hysteresis<Spring>);

namespace {

// Test-only fault injection: POUNDING_INJECT_FAULT=<phase>[@rank] makes `phase` (load, compute, write)
// throw on that rank (default 0); `compute` throws on the rank's third unit. The fault tests in
// tests/faults/ use it to check that an error anywhere ends the whole job promptly with one message.
void inject_fault(std::string_view phase, int rank) {
  static const char* spec = std::getenv("POUNDING_INJECT_FAULT");
  if (!spec) return;
  std::string_view v(spec);
  int at = 0;
  if (auto k = v.find('@'); k != std::string_view::npos) {
    at = std::atoi(std::string(v.substr(k + 1)).c_str());
    v = v.substr(0, k);
  }
  if (v == phase && at == rank)
    throw std::runtime_error(fmt::format("injected fault in phase '{}' on rank {} (POUNDING_INJECT_FAULT)", phase, rank));
}

// The unit fields this computer fills (results/schema.hpp); indices into the plan's schema.
namespace field {
constexpr std::size_t unc_status = results::unit_field("uncoupled", "status");
constexpr std::size_t unc_peak_u1 = results::unit_field("uncoupled", "peak_u1");
constexpr std::size_t unc_peak_u2 = results::unit_field("uncoupled", "peak_u2");
constexpr std::size_t unc_peak_closing = results::unit_field("uncoupled", "peak_closing");
constexpr std::size_t imp_status = results::unit_field("impacts", "status");
constexpr std::size_t imp_count = results::unit_field("impacts", "impact_count");
constexpr std::size_t imp_peak_force = results::unit_field("impacts", "peak_force");
constexpr std::size_t imp_peak_u1 = results::unit_field("impacts", "peak_u1");
constexpr std::size_t imp_peak_u2 = results::unit_field("impacts", "peak_u2");
constexpr std::size_t imp_t_first = results::unit_field("impacts", "t_first_impact");
constexpr std::size_t imp_h_omega = results::unit_field("impacts", "h_omega_contact");
}  // namespace field

// One work unit: sample the block, run the uncoupled pairs (and, in the impacts scene, the coupled ones per
// gap), fill a UnitResult. A rank's threads have one UnitComputer each: it holds every buffer it writes (batches,
// results, scratch, its SystemBlock); what it shares with the others is read only (study, records, stripes,
// sampler, plan) except `computed`, the rank's count of units started (the compute fault fires on the rank's third).
class UnitComputer {
 public:
  UnitComputer(const Study& s, const std::vector<StudyRecord>& records, const StripePlan& stripes,
               const StructureSampler& sampler, const WorkPlan& plan, int rank, std::atomic<int>& computed,
               const std::atomic<bool>* stop)
      : s_(s), records_(records), stripes_(stripes), sampler_(sampler), plan_(plan), rank_(rank), computed_(computed) {
    ks_base_.stop = stop;  // a stop reaches the steppers inside a unit (StopRequested: the unit is left to --resume)
    ks_base_.stepper = s.stepper;
    ks_base_.displacement_limit = s.displacement_limit;
    uncoupled_ = s.contact;
    uncoupled_.law = ContactLaw::none;
    if (runs_systems(sampler.model()))
      block_.emplace(sampler.model(), s.contact, s.e, s.contact_levels, s.gap_offsets, s.level_tolerance,
                     s.shape_functions);
    if (block_) block_->set_joint_offsets(s.joint_gap_offsets), block_->set_gap_metres(s.gap_metres);
    if (block_ && !plan.system.empty()) table_fields(plan);
    if (block_ && (plan.stripes || plan.ida)) block_->keep_springs(true);  // scales_linearly reads them
    if (s.restitution && plan.impacts) {  // e(v0) in the coupled runs (study.cpp: hertzdamp, CD, impacts scene)
      restitution_ = std::make_unique<physics::HertzdampRestitution>(*s.restitution, s.contact);
      f_rest_out_ = results::field_index(plan.fields, "impacts", "restitution_outside");
      if (block_ && !plan.system.empty())
        f_e_outside_ = results::field_index(plan.fields, "impacts", results::restitution_element_field.name);
    }
    if (plan.stripes) stripe_scaled_ = results::field_index(plan.fields, "uncoupled", "scaled");
    if (s.coarse == CoarsePolicy::refine && plan.impacts) f_substeps_ = results::field_index(plan.fields, "impacts", "substeps");
    if (plan.ida) {
      ida_analyses_ = results::field_index(plan.fields, "ida", "analyses");
      ida_limit_ = results::field_index(plan.fields, "ida", "scale_limit");
      ida_lo_ = results::field_index(plan.fields, "ida", "scale_lo");
      ida_hi_ = results::field_index(plan.fields, "ida", "scale_hi");
    }
  }

  UnitResult operator()(std::size_t unit) {
    if (++computed_ == 3) inject_fault("compute", rank_);  // the rank's third unit, on whichever thread
    const UnitIndex u = plan_.decode(unit);
    const std::size_t n = plan_.lanes(u.block);
    pairs_.resize(n);
    const SampleId pair = s_.structures.pair_id(static_cast<std::int64_t>(u.pair));  // slots i1, i2
    sampler_.sample_block(pair.i1, pair.i2, static_cast<std::int64_t>(u.block * plan_.batch), pairs_);
    const Record& rec = records_[u.record].record;
    KernelSettings ks = ks_base_;
    ks.substeps = substeps_for(rec.dt);
    UnitResult out(plan_, n);
    if (block_) {  // shear buildings, rows, bridges: Systems (study/system_block.hpp)
      if (plan_.stripes) {
        stripes(rec, u.record, ks, out);
        return out;
      }
      systems(records_[u.record], ks, out);
      if (plan_.ida) ida(rec, u.record, ks, out);
      return out;
    }
    batch_.resize(n);
    for (std::size_t i = 0; i < n; ++i) batch_.set(i, pairs_[i].pair_params(0.0, s_.e));
    if (plan_.stripes) {
      stripes(rec, u.record, ks, out);
      return out;
    }
    const GroundMotion gm{rec.dt, rec.acc, rec.duration() + s_.free_vibration};
    run_batch(batch_, uncoupled_, gm, ks, res_);
    for (std::size_t i = 0; i < n; ++i) put_uncoupled(out, i, res_.status[i], res_.peak_u1[i], res_.peak_u2[i], res_.peak_closing[i]);
    if (plan_.impacts)
      for (std::size_t g = 0; g < plan_.gaps; ++g) coupled(g, gm, ks, out);
    if (plan_.ida) ida(rec, u.record, ks, out);
    return out;
  }

 private:
  int substeps_for(double dt) const { return study_substeps(s_, dt); }

  // Value k of the uncoupled per-lane fields ([stripe][lane] in a multiple-stripe unit).
  static void put_uncoupled(UnitResult& out, std::size_t k, std::uint8_t status, double u1, double u2, double closing) {
    out.values<std::uint8_t>(field::unc_status)[k] = status;
    out.values<double>(field::unc_peak_u1)[k] = u1;
    out.values<double>(field::unc_peak_u2)[k] = u2;
    out.values<double>(field::unc_peak_closing)[k] = closing;
  }

  // record * f into scaled_ (the record itself is loaded or synthesised once)
  std::span<const double> scaled(const Record& rec, double f) {
    scaled_.resize(rec.acc.size());
    for (std::size_t t = 0; t < scaled_.size(); ++t) scaled_[t] = f * rec.acc[t];
    return scaled_;
  }

  // A multiple-stripe unit: the block of models under record r scaled to every stripe's level, lowest first. A
  // record dropped from a stripe (factor above max_scale) is not analysed there (status dropped_status). The first
  // stripe analysed runs every model (the anchor, factor fa). At a higher stripe with factor f a model whose
  // buildings stayed elastic in the anchor run and stay so at f -- ratio f / fa times each anchor peak |u| below
  // (1 - 1e-9) fy / k, and ratio times (peak |u1| + peak |u2|) within the displacement limit -- is not rerun: an
  // elastic response scales exactly with the record, so its peaks are the anchor's times the ratio
  // ([analysis] scale_elastic; tests/cli/fragility_scale_elastic.sh compares it with every model run). The others
  // (and all of them with scale_elastic = false) are run on the scaled record.
  void stripes(const Record& rec, std::size_t r, const KernelSettings& ks, UnitResult& out) {
    const std::size_t n = pairs_.size(), R = stripes_.records;
    double fa = 0;
    for (std::size_t s = 0; s < plan_.stripes; ++s) {
      const std::size_t k = s * R + r, at = s * n;
      if (stripes_.dropped[k]) {
        for (std::size_t i = 0; i < n; ++i) out.values<std::uint8_t>(field::unc_status)[at + i] = results::dropped_status;
        continue;
      }
      const bool anchor = fa == 0;
      peaks_at(rec, stripes_.scale[k], fa, ks);
      for (std::size_t i = 0; i < n; ++i) put_uncoupled(out, at + i, st_[i], pu1_[i], pu2_[i], pc_[i]);
      if (block_) put_system_stripe(out, s);
      if (anchor) continue;
      auto scaled_flag = out.values<std::uint8_t>(stripe_scaled_);
      for (std::size_t i = 0; i < n; ++i) scaled_flag[at + i] = 1;
      for (std::size_t i : lanes_) scaled_flag[at + i] = 0;
    }
  }

  // The peaks of every lane under the record scaled by f, into st_, pu1_, pu2_, pc_: with fa == 0 the anchor run
  // (fa becomes f); else the anchor's peaks times f / fa for the lanes elastic at f, a run for the others. The
  // same for the stripes and the IDA's hunt, so the hunt is MSA's own analysis, bit for bit.
  void peaks_at(const Record& rec, double f, double& fa, const KernelSettings& ks) {
    const std::size_t n = pairs_.size();
    st_.resize(n), pu1_.resize(n), pu2_.resize(n), pc_.resize(n);
    const GroundMotion gm{rec.dt, scaled(rec, f), rec.duration() + s_.free_vibration};
    if (block_) {
      system_peaks_at(gm, f, fa, ks);
      return;
    }
    if (fa == 0) {
      fa = f;
      run_batch(batch_, uncoupled_, gm, ks, anchor_);
      for (std::size_t i = 0; i < n; ++i)
        st_[i] = anchor_.status[i], pu1_[i] = anchor_.peak_u1[i], pu2_[i] = anchor_.peak_u2[i], pc_[i] = anchor_.peak_closing[i];
      return;
    }
    const double ratio = f / fa;
    lanes_.clear();
    for (std::size_t i = 0; i < n; ++i)
      if (!(s_.scale_elastic && elastic_at(i, ratio, ks.displacement_limit))) lanes_.push_back(i);
    if (!lanes_.empty()) {
      sub_.resize(lanes_.size());
      for (std::size_t j = 0; j < lanes_.size(); ++j) sub_.set(j, batch_.get(lanes_[j]));
      run_batch(sub_, uncoupled_, gm, ks, res_);
    }
    for (std::size_t i = 0, j = 0; i < n; ++i) {
      if (j < lanes_.size() && lanes_[j] == i) {
        st_[i] = res_.status[j], pu1_[i] = res_.peak_u1[j], pu2_[i] = res_.peak_u2[j], pc_[i] = res_.peak_closing[j];
        ++j;
      } else {
        st_[i] = 0, pu1_[i] = ratio * anchor_.peak_u1[i], pu2_[i] = ratio * anchor_.peak_u2[i];
        pc_[i] = ratio * anchor_.peak_closing[i];
      }
    }
  }

  // Lane i of the anchor run stays elastic when the record is scaled by `ratio` more (see stripes()): each spring's
  // hysteresis model answers (stays_elastic, model/hysteresis/registry.hpp), not a value test here.
  bool elastic_at(std::size_t i, double ratio, double limit) const {
    if (block_) return block_->scales_linearly(anchor_peaks_, i, ratio, limit);
    constexpr double margin = 1.0 - 1e-9;
    const double u1 = ratio * anchor_.peak_u1[i], u2 = ratio * anchor_.peak_u2[i];
    if (anchor_.status[i] != 0) return false;
    const PairParams p = batch_.get(i);
    return Spring::stays_elastic(p.s1, u1, margin) && Spring::stays_elastic(p.s2, u2, margin) && u1 + u2 <= limit;
  }

  // The bisection IDA of yielding pairs (method = "ida"): for every lane and gap ratio x, the record scale factor
  // at which the pair first touches, i.e. the smallest f with peak closing D(f) > x d.
  //  1. Hunt: the record scaled (like a stripe, bit-identical to MSA's analysis at that factor) to each factor of
  //     ida_hunt_factors -- the stripes' levels below max_scale, then max_scale. The first factor whose run
  //     touches brackets f* between it and the factor before (0 before the first); no touch up to the last factor:
  //     censored. A diverged analysis ends the lane's hunt: its open gaps are censored at the factor before (the
  //     record's cap comes down to it in make_results), or excluded when that was the first factor.
  //  2. Bisection on ln f (halving from 0 while the bracket starts there) until hi <= lo (1 + tolerance). Each
  //     step runs every open (lane, gap) as its own kernel lane with its own factor, using the exact identity of
  //     bilinear (kinematic hardening) and elastic restoring forces R(f w; fy) = f R(w; fy / f): the response to
  //     f ag is f times the response to ag of the same structure with yield forces fy / f. So the record stays
  //     unscaled, each lane's fy is divided by its factor, and the peaks are multiplied by it (the displacement
  //     limit is applied to the multiplied peaks). Checked against the scaled record in tests/study.
  //  A lane whose buildings are still elastic at the factor that closed its bracket needs no bisection: its first
  //  contact is the anchor's linear extrapolation, exact (scale_lo = scale_hi).
  // With several crossings of D(f) = x d (a "resurrection"), the hunt's first bracket is kept: f* is the first
  // crossing to the resolution of the hunt.
  void ida(const Record& rec, std::size_t record, const KernelSettings& ks, UnitResult& out) {
    const std::size_t n = pairs_.size(), G = plan_.gaps;
    const std::vector<double> hunt = ida_hunt_factors(s_.intensity, stripes_.im[record]);
    std::vector<std::uint8_t> state(n * G, open);
    std::vector<double> lo(n * G, 0.0), hi(n * G, INFINITY);
    auto analyses = out.values<std::int32_t>(ida_analyses_);
    auto limit = out.values<double>(ida_limit_);
    for (std::size_t i = 0; i < n; ++i) analyses[i] = 1, limit[i] = hunt.back();  // 1: the record as it is
    std::vector<std::uint8_t> diverged(n, 0);
    double fa = 0;
    for (std::size_t h = 0; h < hunt.size(); ++h) {
      const double f = hunt[h];
      peaks_at(rec, f, fa, ks);
      if (h == 0)
        for (std::size_t i = 0; i < n; ++i) ++analyses[i];
      else
        for (std::size_t i : lanes_) ++analyses[i];  // the lanes run, not scaled from the anchor
      for (std::size_t i = 0; i < n; ++i) {
        if (diverged[i]) continue;
        if (st_[i] != 0) {
          // no contact known up to the factor before: censored there (the record's cap goes down to it, make_results);
          // at the first factor nothing is known: excluded
          diverged[i] = 1, limit[i] = h ? hunt[h - 1] : 0.0;
          for (std::size_t g = 0; g < G; ++g)
            if (state[i * G + g] == open && h == 0) state[i * G + g] = excluded;
          continue;
        }
        for (std::size_t g = 0; g < G; ++g) {
          const std::size_t k = i * G + g;
          if (state[k] != open) continue;
          if (pc_[i] > s_.gap_at(g, pairs_[i])) state[k] = found, hi[k] = f;
          else lo[k] = f;
        }
      }
    }
    // A lane still elastic where it first touched is linear on [0, hi]: D(f) = (f / fa) D(fa), so its first contact
    // is exactly at fa x d / D(fa), no bisection needed ([analysis] scale_elastic; the bracket closes on it)
    if (s_.scale_elastic)
      for (std::size_t k = 0; k < n * G; ++k) {
        const std::size_t i = k / G;
        if (state[k] != found || !elastic_at(i, hi[k] / fa, ks.displacement_limit)) continue;
        const double D = block_ ? anchor_peaks_.closing[i] : anchor_.peak_closing[i];
        const double f = fa * s_.gap_ratios[k % G] * s_.gap_unit(pairs_[i]) / D;  // (fa x) d / D in this order: ratio studies' bits
        lo[k] = hi[k] = std::clamp(f, lo[k], hi[k]);
      }
    if (block_) system_bisect(rec, ks, state, lo, hi, analyses);
    else bisect(rec, ks, state, lo, hi, analyses);
    auto slo = out.values<double>(ida_lo_), shi = out.values<double>(ida_hi_);
    for (std::size_t k = 0; k < n * G; ++k) {
      const bool ok = state[k] != excluded;
      slo[k] = ok ? lo[k] : NAN, shi[k] = ok ? hi[k] : NAN;  // open: censored, [last factor analysed, inf)
    }
  }

  // The pair whose response to the unscaled record, times f, is the response of `pp` to the record times f: each
  // spring's unscaled_equivalent (bilinear: fy / f). Every registered model the study runs has one; a model
  // without (answering std::nullopt) would need its lane run on the scaled record, which the bisection does not do.
  static PairParams unscaled_equivalent(PairParams pp, double f) {
    const std::optional<Structure> s1 = Spring::unscaled_equivalent(pp.s1, f), s2 = Spring::unscaled_equivalent(pp.s2, f);
    if (!s1 || !s2) throw std::logic_error("IDA bisection: the structure model does not scale with the record");
    pp.s1 = *s1, pp.s2 = *s2;
    return pp;
  }

  // The IDA's bisection (see ida()): every found (lane, gap) bracket narrowed to the tolerance, one kernel lane
  // per open bracket with each spring replaced by its unscaled equivalent at the lane's factor.
  void bisect(const Record& rec, const KernelSettings& ks, std::vector<std::uint8_t>& state, std::vector<double>& lo,
              std::vector<double>& hi, std::span<std::int32_t> analyses) {
    const std::size_t nG = state.size();
    const std::size_t G = plan_.gaps;
    const GroundMotion gm{rec.dt, rec.acc, rec.duration() + s_.free_vibration};
    for (int step = 0; step < 200; ++step) {
      todo_.clear();
      for (std::size_t k = 0; k < nG; ++k)
        if (state[k] == found && !(hi[k] <= lo[k] * (1.0 + s_.intensity.tolerance))) todo_.push_back(k);
      if (todo_.empty()) break;
      sub_.resize(todo_.size());
      mid_.resize(todo_.size());
      double f_min = INFINITY;
      for (std::size_t j = 0; j < todo_.size(); ++j) {
        const std::size_t k = todo_[j];
        mid_[j] = lo[k] > 0 ? std::sqrt(lo[k] * hi[k]) : 0.5 * hi[k];
        f_min = std::min(f_min, mid_[j]);
        sub_.set(j, unscaled_equivalent(pairs_[k / G].pair_params(0.0, s_.e), mid_[j]));
      }
      KernelSettings kb = ks;
      kb.displacement_limit = ks.displacement_limit / f_min;  // the exact limit is applied per lane below
      run_batch(sub_, uncoupled_, gm, kb, bres_);
      for (std::size_t j = 0; j < todo_.size(); ++j) {
        const std::size_t k = todo_[j], i = k / G, g = k % G;
        const double f = mid_[j];
        ++analyses[i];
        // the kernel's limit is on |u1| + |u2| at one instant; the sum of the peaks bounds it (conservative)
        if (bres_.status[j] != 0 || f * (bres_.peak_u1[j] + bres_.peak_u2[j]) > ks.displacement_limit)
          state[k] = excluded;
        else if (f * bres_.peak_closing[j] > s_.gap_at(g, pairs_[i])) hi[k] = f;
        else lo[k] = f;
      }
    }
  }

  // A pair whose uncoupled peak closing stays <= g never touches at gap g, and its coupled run is
  // bit-identical to the uncoupled one (the first-passage property, tested): only the pairs that touch are
  // run with contact; the others take the uncoupled results (unless [analysis] skip_untouched = false).
  void coupled(std::size_t g, const GroundMotion& gm, const KernelSettings& ks, UnitResult& out) {
    const std::size_t n = pairs_.size();
    lanes_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const bool untouched = res_.status[i] == 0 && !(res_.peak_closing[i] > s_.gap_at(g, pairs_[i]));
      if (!s_.skip_untouched || !untouched) lanes_.push_back(i);
    }
    sub_.resize(lanes_.size());
    for (std::size_t j = 0; j < lanes_.size(); ++j) {
      PairParams pp = pairs_[lanes_[j]].pair_params(s_.gap_ratios[g], s_.e);
      pp.gap = s_.gap_at(g, pairs_[lanes_[j]]);  // ratio x d (the same product), or metres
      if (s_.contact_stiffness > 0) pp.kc = s_.contact_stiffness;
      sub_.set(j, pp);
    }
    KernelSettings kc = ks;
    if (restitution_) kc.restitution = &restitution_->hook;
    if (!lanes_.empty()) run_batch(sub_, s_.contact, gm, kc, cres_);
    used_.assign(lanes_.size(), kc.substeps);  // [analysis] coarse = "refine": the coarse lanes again (study/refine.hpp)
    if (f_substeps_ != npos && !lanes_.empty()) refine_pairs(sub_, s_.contact, gm, kc, cres_, one_, used_);
    std::span<std::int32_t> outside;
    if (restitution_) outside = out.values<std::int32_t>(f_rest_out_);
    auto status = out.values<std::uint8_t>(field::imp_status);
    auto count = out.values<std::int32_t>(field::imp_count);
    auto force = out.values<double>(field::imp_peak_force), first = out.values<double>(field::imp_t_first);
    auto u1 = out.values<double>(field::imp_peak_u1), u2 = out.values<double>(field::imp_peak_u2);
    auto hw = out.values<double>(field::imp_h_omega);
    const std::size_t G = plan_.gaps;
    for (std::size_t i = 0, j = 0; i < n; ++i) {
      const std::size_t k = i * G + g;  // [lane][gap]
      if (j < lanes_.size() && lanes_[j] == i) {
        status[k] = cres_.status[j], count[k] = cres_.impact_count[j], force[k] = cres_.peak_force[j];
        u1[k] = cres_.peak_u1[j], u2[k] = cres_.peak_u2[j], first[k] = cres_.t_first_impact[j];
        hw[k] = cres_.h_omega_contact[j];
        if (restitution_) outside[k] = cres_.restitution_outside[j];
        if (f_substeps_ != npos) out.values<std::int32_t>(f_substeps_)[k] = used_[j];
        ++j;
      } else {
        status[k] = res_.status[i], count[k] = 0, force[k] = 0.0;
        u1[k] = res_.peak_u1[i], u2[k] = res_.peak_u2[i], first[k] = NAN;
        hw[k] = res_.status[i] == 0 && contact::traits(s_.contact.law).has_force ? 0.0 : NAN;  // never touched
        if (restitution_) outside[k] = 0;
        if (f_substeps_ != npos) out.values<std::int32_t>(f_substeps_)[k] = ks.substeps;
      }
    }
  }

  // The coupled Systems of lanes_ at gap ratio `ratio` into coupled_, the coarse ones refined ([analysis] coarse =
  // "refine", study/refine.hpp); used_[j]: lane j's substeps.
  void coupled_systems(double ratio, const GroundMotion& gm, const KernelSettings& kc) {
    used_.assign(lanes_.size(), kc.substeps);
    if (lanes_.empty()) return;
    const ContactNumbers cn{s_.e, s_.contact_stiffness};
    block_->coupled(pairs_, lanes_, ratio, s_.contact, cn, gm, kc, coupled_);
    if (f_substeps_ != npos) refine_systems(*block_, pairs_, lanes_, ratio, s_.contact, cn, gm, kc, coupled_, one_, used_);
  }

  // A block with a shear building (model = "shear"): the uncoupled Systems give status, the buildings' largest
  // floor displacements and D = the largest peak closing over the floor contacts (system_block.hpp), so the
  // probability scene answers every gap exactly as for the pair; the impacts scene runs coupled only the lanes that
  // touch (D > gap) or failed (all with skip_untouched = false), as coupled() does for pairs. [intensity]: stripes()
  // and ida() run the Systems through system_peaks_at / system_bisect.
  // A bridge on several supports ([records] supports): channel k is the realisation's support k + 1.
  void systems(const StudyRecord& sr, const KernelSettings& ks, UnitResult& out) {
    const Record& rec = sr.record;
    const std::size_t n = pairs_.size(), G = plan_.gaps;
    const GroundMotion gm{rec.dt, rec.acc, rec.duration() + s_.free_vibration};
    const int channels = s_.structures.bridge ? s_.structures.bridge->spec.channels() : 1;
    channels_.clear();
    for (int c = 0; c < channels && channels > 1; ++c)
      channels_.push_back(c == 0 ? gm
                                 : GroundMotion{rec.dt, sr.more_supports[static_cast<std::size_t>(c - 1)].acc,
                                                rec.duration() + s_.free_vibration});
    block_->set_channels(channels_);
    block_->uncoupled(pairs_, uncoupled_, gm, ks, peaks_);
    const bool table = !block_->layout().empty();
    const std::size_t nb = peaks_.buildings;
    for (std::size_t i = 0; i < n; ++i) {
      put_uncoupled(out, i, peaks_.status[i], peaks_.u1[i], peaks_.u2[i], peaks_.closing[i]);
      if (table) put_table_uncoupled(out, i, peaks_);
      for (std::size_t b = 2; b < nb; ++b) out.values<double>(f_row_unc_[b])[i] = peaks_.u[i * nb + b];
    }
    if (!plan_.impacts) return;
    auto status = out.values<std::uint8_t>(field::imp_status);
    auto count = out.values<std::int32_t>(field::imp_count);
    auto force = out.values<double>(field::imp_peak_force), first = out.values<double>(field::imp_t_first);
    auto u1 = out.values<double>(field::imp_peak_u1), u2 = out.values<double>(field::imp_peak_u2);
    auto hw = out.values<double>(field::imp_h_omega);
    KernelSettings kc = ks;  // e(v0) at every study-gap element's impact ([contact] restitution)
    std::span<std::int32_t> outside;
    if (restitution_) kc.restitution = &restitution_->hook, outside = out.values<std::int32_t>(f_rest_out_);
    for (std::size_t g = 0; g < G; ++g) {
      lanes_.clear();
      for (std::size_t i = 0; i < n; ++i) {
        const bool untouched = peaks_.status[i] == 0 && !(peaks_.closing[i] > s_.gap_at(g, pairs_[i]));
        if (!s_.skip_untouched || !untouched) lanes_.push_back(i);
      }
      coupled_systems(s_.gap_ratios[g], gm, kc);
      for (std::size_t i = 0, j = 0; i < n; ++i) {
        const std::size_t k = i * G + g;  // [lane][gap]
        if (j < lanes_.size() && lanes_[j] == i) {
          status[k] = coupled_.status[j], count[k] = coupled_.impact_count[j], force[k] = coupled_.peak_force[j];
          u1[k] = coupled_.u1[j], u2[k] = coupled_.u2[j], first[k] = coupled_.t_first_impact[j];
          hw[k] = coupled_.h_omega_contact[j];
          if (restitution_) outside[k] = coupled_.restitution_outside[j];
          if (f_substeps_ != npos) out.values<std::int32_t>(f_substeps_)[k] = used_[j];
          for (std::size_t b = 2; b < nb; ++b) out.values<double>(f_row_imp_[b])[k] = coupled_.u[j * nb + b];
          if (table) put_table_coupled(out, i, g, j);
          ++j;
        } else {
          status[k] = peaks_.status[i], count[k] = 0, force[k] = 0.0;
          u1[k] = peaks_.u1[i], u2[k] = peaks_.u2[i], first[k] = NAN;
          for (std::size_t b = 2; b < nb; ++b) out.values<double>(f_row_imp_[b])[k] = peaks_.u[i * nb + b];
          hw[k] = peaks_.status[i] == 0 && contact::traits(s_.contact.law).has_force ? 0.0 : NAN;  // never touched
          if (restitution_) outside[k] = 0;
          if (f_substeps_ != npos) out.values<std::int32_t>(f_substeps_)[k] = ks.substeps;
          if (table) put_table_coupled(out, i, g, std::string::npos);
        }
      }
    }
  }

  // Results format 3 (plan.system not empty): the per-floor and per-element rows, laid out as the study's largest
  // topology (table_topology, the plan's /system).
  void table_fields(const WorkPlan& plan) {
    const std::optional<LaneTopology> t = table_topology(sampler_.model(), sampler_.seed());
    block_->set_table(block_->table_system(*t));
    const std::size_t nb = t->buildings();
    f_floor_u_.resize(nb), f_floor_drift_.resize(nb), f_floor_acc_.resize(nb);
    f_row_unc_.assign(nb, 0), f_row_imp_.assign(nb, 0);
    for (std::size_t b = 2; b < nb; ++b) {  // a row's buildings 3..n
      f_row_unc_[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_u{b}", b + 1));
      if (plan.impacts)
        f_row_imp_[b] = results::field_index(plan.fields, "impacts", results::building_name("peak_u{b}", b + 1));
    }
    for (std::size_t b = 0; b < nb; ++b) {
      f_floor_u_[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_u_floors{b}", b + 1));
      f_floor_drift_[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_drift{b}", b + 1));
      f_floor_acc_[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_acc_floors{b}", b + 1));
    }
    f_e_closing_ = results::field_index(plan.fields, "uncoupled", "peak_closing_elements");
    if (!plan.impacts) return;
    f_imp_floor_u_.resize(nb), f_imp_floor_drift_.resize(nb), f_imp_floor_acc_.resize(nb);
    for (std::size_t b = 0; b < nb; ++b) {
      f_imp_floor_u_[b] = results::field_index(plan.fields, "impacts", results::building_name("peak_u_floors{b}", b + 1));
      f_imp_floor_drift_[b] = results::field_index(plan.fields, "impacts", results::building_name("peak_drift{b}", b + 1));
      f_imp_floor_acc_[b] =
          results::field_index(plan.fields, "impacts", results::building_name("peak_acc_floors{b}", b + 1));
    }
    f_e_count_ = results::field_index(plan.fields, "impacts", "element_impact_count");
    f_e_force_ = results::field_index(plan.fields, "impacts", "element_peak_force");
    f_e_pen_ = results::field_index(plan.fields, "impacts", "element_peak_penetration");
    f_e_first_ = results::field_index(plan.fields, "impacts", "element_t_first_impact");
    f_e_hw_ = results::field_index(plan.fields, "impacts", "element_h_omega_contact");
  }

  // lane i's per-floor rows and per-element closings from the uncoupled run p (at stripe `stripe`)
  void put_table_uncoupled(UnitResult& out, std::size_t i, const BlockPeaks& p, std::size_t stripe = 0) {
    const TableLayout& t = block_->layout();
    for (std::size_t b = 0; b < t.floors.size(); ++b)
      for (auto [field, from] : {std::pair{f_floor_u_[b], &p.floor_u[b]}, {f_floor_drift_[b], &p.floor_drift[b]},
                                 {f_floor_acc_[b], &p.floor_acc[b]}}) {
        auto v = out.lane_values<double>(field, i, stripe);
        std::copy_n(from->begin() + static_cast<std::ptrdiff_t>(i * t.floors[b]), t.floors[b], v.begin());
      }
    auto c = out.lane_values<double>(f_e_closing_, i, stripe);
    std::copy_n(p.e_closing.begin() + static_cast<std::ptrdiff_t>(i * t.elements), t.elements, c.begin());
  }

  // peaks_at() for Systems (shear buildings, rows): with fa == 0 the anchor run of every lane (anchor_peaks_, each
  // lane's springs kept); at a higher factor f the lanes that scale linearly over f / fa (SystemBlock::scales_linearly,
  // the model trait; [analysis] scale_elastic) take the anchor's peaks times f / fa, the others run on the scaled
  // record (SystemBlock::coupled at ratio 0 with the law none is the uncoupled run of those lanes: a lane's bits do
  // not depend on the lanes run beside it). cur_ holds every lane's peaks at f; st_, pu1_, pu2_, pc_ its pair columns.
  void system_peaks_at(const GroundMotion& gm, double f, double& fa, const KernelSettings& ks) {
    const std::size_t n = pairs_.size();
    const bool anchor = fa == 0;
    if (anchor) fa = f;
    const double ratio = anchor ? 1.0 : f / fa;
    lanes_.clear();
    if (anchor) {
      block_->uncoupled(pairs_, uncoupled_, gm, ks, anchor_peaks_);
    } else {
      for (std::size_t i = 0; i < n; ++i)
        if (!(s_.scale_elastic && elastic_at(i, ratio, ks.displacement_limit))) lanes_.push_back(i);
      if (!lanes_.empty()) block_->coupled(pairs_, lanes_, 0.0, uncoupled_, ContactNumbers{}, gm, ks, sub_peaks_);
    }
    cur_.resize(n, anchor_peaks_.buildings, block_->layout());
    for (std::size_t i = 0, j = 0; i < n; ++i) {
      if (j < lanes_.size() && lanes_[j] == i) cur_.set_scaled(i, sub_peaks_, j++, 1.0);
      else cur_.set_scaled(i, anchor_peaks_, i, ratio);
      st_[i] = cur_.status[i], pu1_[i] = cur_.u1[i], pu2_[i] = cur_.u2[i], pc_[i] = cur_.closing[i];
    }
  }

  // stripe s's per-floor / per-element rows and a row's buildings 3..n from cur_
  void put_system_stripe(UnitResult& out, std::size_t s) {
    const std::size_t nb = cur_.buildings;
    const bool table = !block_->layout().empty();
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
      if (table) put_table_uncoupled(out, i, cur_, s);
      for (std::size_t b = 2; b < nb; ++b) out.lane_values<double>(f_row_unc_[b], i, s)[0] = cur_.u[i * nb + b];
    }
  }

  // The IDA's bisection for Systems (see ida()): every found (lane, gap) bracket narrowed to the tolerance as for
  // pairs, each lane run on the record scaled by its factor -- a System has no unscaled equivalent in general (a
  // smooth bearing, a moat wall, the guard's sum over floors), so the record is scaled, one run per (lane, factor);
  // the gaps of a lane that meet at the same factor share its run.
  void system_bisect(const Record& rec, const KernelSettings& ks, std::vector<std::uint8_t>& state,
                     std::vector<double>& lo, std::vector<double>& hi, std::span<std::int32_t> analyses) {
    const std::size_t G = plan_.gaps;
    for (int step = 0; step < 200; ++step) {
      todo_.clear();
      for (std::size_t k = 0; k < state.size(); ++k)
        if (state[k] == found && !(hi[k] <= lo[k] * (1.0 + s_.intensity.tolerance))) todo_.push_back(k);
      if (todo_.empty()) break;
      std::size_t ran = std::string::npos;
      double ran_f = 0.0;
      for (std::size_t k : todo_) {
        const std::size_t i = k / G, g = k % G;
        const double f = lo[k] > 0 ? std::sqrt(lo[k] * hi[k]) : 0.5 * hi[k];
        if (i != ran || f != ran_f) {
          const std::size_t one[] = {i};
          const GroundMotion gm{rec.dt, scaled(rec, f), rec.duration() + s_.free_vibration};
          block_->coupled(pairs_, one, 0.0, uncoupled_, ContactNumbers{}, gm, ks, sub_peaks_);
          ++analyses[i], ran = i, ran_f = f;
        }
        if (sub_peaks_.status[0] != 0) state[k] = excluded;
        else if (sub_peaks_.closing[0] > s_.gap_at(g, pairs_[i])) hi[k] = f;
        else lo[k] = f;
      }
    }
  }

  // lane i's per-element impacts at gap g: from coupled_ lane j, or (j = npos) untouched: no impacts at the study-gap
  // elements its topology has (those with an uncoupled closing), and a moat wall's of the uncoupled run (the walls act
  // there too, and the coupled run of an untouched lane is the uncoupled run; they held 0, issue 45 item 2)
  void put_table_coupled(UnitResult& out, std::size_t i, std::size_t g, std::size_t j) {
    const std::size_t E = block_->layout().elements;
    auto count = out.lane_values<std::int32_t>(f_e_count_, i);
    auto force = out.lane_values<double>(f_e_force_, i), pen = out.lane_values<double>(f_e_pen_, i);
    auto first = out.lane_values<double>(f_e_first_, i), hw = out.lane_values<double>(f_e_hw_, i);
    const bool has_force = contact::traits(s_.contact.law).has_force;
    for (std::size_t e = 0; e < E; ++e) {
      const std::size_t o = g * E + e;
      if (j != std::string::npos) {
        const std::size_t x = j * E + e;
        count[o] = coupled_.e_count[x], force[o] = coupled_.e_force[x], pen[o] = coupled_.e_penetration[x];
        first[o] = coupled_.e_first[x], hw[o] = coupled_.e_hw[x];
      } else if (!std::isnan(peaks_.e_closing[i * E + e]) && !study_gap(e)) {
        const std::size_t x = i * E + e;
        count[o] = peaks_.e_count[x], force[o] = peaks_.e_force[x], pen[o] = peaks_.e_penetration[x];
        first[o] = peaks_.e_first[x], hw[o] = peaks_.e_hw[x];
      } else if (!std::isnan(peaks_.e_closing[i * E + e])) {
        count[o] = 0, force[o] = 0.0, pen[o] = 0.0, first[o] = NAN;
        hw[o] = peaks_.status[i] == 0 && has_force ? 0.0 : NAN;
      }
    }
    if (restitution_) {  // per element: impacts outside the e(v0) curve's range (0 where it never touched)
      auto outside = out.lane_values<std::int32_t>(f_e_outside_, i);
      for (std::size_t e = 0; e < E; ++e)
        if (j != std::string::npos) outside[g * E + e] = coupled_.e_outside[j * E + e];
        else if (!std::isnan(peaks_.e_closing[i * E + e])) outside[g * E + e] = 0;
    }
    put_floors_coupled(out, i, g, j);
  }

  // element e of the plan's /system belongs to a study-gap group (a moat wall does not)
  bool study_gap(std::size_t e) const {
    const results::SystemTable& t = plan_.system;
    return e >= t.element_group.size() || t.group_study_gap[static_cast<std::size_t>(t.element_group[e])] != 0;
  }

  // lane i's per-floor peaks at gap g: from coupled_ lane j, or (j = npos, a lane that never touched) its uncoupled
  // peaks, as impacts/peak_u1 takes them
  void put_floors_coupled(UnitResult& out, std::size_t i, std::size_t g, std::size_t j) {
    const TableLayout& t = block_->layout();
    const BlockPeaks& p = j != std::string::npos ? coupled_ : peaks_;
    const std::size_t lane = j != std::string::npos ? j : i;
    for (std::size_t b = 0; b < t.floors.size(); ++b) {
      const std::size_t F = t.floors[b];
      for (auto [field, from] : {std::pair{f_imp_floor_u_[b], &p.floor_u[b]}, {f_imp_floor_drift_[b], &p.floor_drift[b]},
                                 {f_imp_floor_acc_[b], &p.floor_acc[b]}}) {
        auto v = out.lane_values<double>(field, i);
        std::copy_n(from->begin() + static_cast<std::ptrdiff_t>(lane * F), F, v.begin() + static_cast<std::ptrdiff_t>(g * F));
      }
    }
  }

  const Study& s_;
  const std::vector<StudyRecord>& records_;
  const StripePlan& stripes_;
  const StructureSampler& sampler_;
  const WorkPlan& plan_;
  int rank_;
  std::atomic<int>& computed_;
  KernelSettings ks_base_;
  ContactModel uncoupled_;
  std::vector<SampledPair> pairs_;
  std::vector<std::size_t> lanes_;
  PairBatch sub_;
  PairBatch batch_;
  BatchResult res_, cres_, bres_, anchor_;
  std::optional<SystemBlock> block_;
  std::unique_ptr<physics::HertzdampRestitution> restitution_;  // [contact] restitution: the kernel's e(v0) hook
  std::size_t f_rest_out_ = 0;
  BlockPeaks peaks_, coupled_;
  BlockPeaks anchor_peaks_, cur_, sub_peaks_;  // fragility studies of Systems: the anchor run, the peaks at a factor, a run
  // [analysis] coarse = "refine": impacts/substeps (npos: another policy), each coupled lane's substeps, one lane's
  // rerun (study/refine.hpp)
  static constexpr std::size_t npos = std::string::npos;
  std::size_t f_substeps_ = npos;
  std::vector<std::int32_t> used_;
  RefineScratch one_;
  std::vector<GroundMotion> channels_;  // a multi-support bridge's motions of the unit's record
  std::vector<std::size_t> f_floor_u_, f_floor_drift_, f_floor_acc_;
  std::vector<std::size_t> f_row_unc_, f_row_imp_;  // a row's buildings 3..n: uncoupled / impacts peak_u{b}
  std::size_t f_e_closing_ = 0, f_e_count_ = 0, f_e_force_ = 0, f_e_pen_ = 0, f_e_first_ = 0, f_e_hw_ = 0;
  std::size_t f_e_outside_ = 0;  // [contact] restitution: impacts/element_restitution_outside
  std::vector<std::size_t> f_imp_floor_u_, f_imp_floor_drift_, f_imp_floor_acc_;  // impacts/peak_u_floors{b}, ...
  std::vector<std::uint8_t> st_;
  std::vector<double> scaled_, mid_, pu1_, pu2_, pc_;
  std::vector<std::size_t> todo_;
  enum : std::uint8_t { open, found, excluded };  // the IDA's (lane, gap) states
  std::size_t stripe_scaled_ = 0;
  std::size_t ida_analyses_ = 0, ida_limit_ = 0, ida_lo_ = 0, ida_hi_ = 0;  // the ida rows' positions in the plan's schema
};

}  // namespace

namespace {

// ---- phase 1: the inputs, identical on every rank -------------------------------------------------
struct Inputs {
  Study study;
  std::string out, out_where;
  std::vector<StudyRecord> records;
  StripePlan stripes;  // a fragility study's stripes (none otherwise)
  std::optional<StudySelection> selection;  // [records] select: the records chosen to [target_spectrum]
  std::vector<HistoryChoice> histories;     // [outputs] histories: the named analyses (worst N: after the units)
  bool stopped = false;  // a stop while the records were made (every rank agrees: it is in the exchanged shares)
};

// A finished results file is replaced by a rerun of its own study (the same study text) only: another study's
// results, or a file that is not a results file, need --force (as a checkpoint with progress does).
void check_replaceable_results(const std::string& out, const std::string& where, const Study& study) {
  struct stat st {};
  if (::stat(out.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0) return;
  results::Header h;
  try {
    h = results::load_header(out);
  } catch (const std::exception&) {
    throw InputError(fmt::format("{} exists and is not a pounding results file", out), where,
                     "give another output path, or rerun with --force to replace it");
  }
  if (h.study_text == study.text) return;
  throw InputError(fmt::format("{} holds the results of another study (\"{}\", {}, written {})", out, h.title,
                               h.study_path, h.date),
                   where, "give another output path, or rerun with --force to replace them");
}

// The run's outputs -- the results file, its checkpoint <out>.ckpt and with [report] html = true the HTML report
// (the results' name with .html) -- before any work: none of them may be a file the study reads, nor one of the
// others (--out r.html would leave only the report), nor a folder, FIFO or device (the checkpoint is read back: a
// FIFO there would block the run forever).
void check_outputs(const Inputs& in) {
  const std::vector<std::string> inputs = study_input_files(in.study);
  const std::string ckpt = in.out + ".ckpt", ckpt_where = in.out_where + " (its checkpoint " + ckpt + ")";
  files::check_output_not_input(in.out, inputs, in.out_where);
  files::check_output_not_input(ckpt, inputs, ckpt_where);
  files::check_output_not_input(ckpt, {in.out}, ckpt_where, "the results file");
  files::check_output_path(in.out, in.out_where);
  files::check_replaceable(ckpt, ckpt_where, fmt::format("remove {} (the checkpoint is a regular file that pounding "
                                                          "writes and reads back), or give another --out", ckpt));
  if (!in.study.html) return;
  const std::string html = files::with_extension(in.out, ".html");
  const std::string html_where = in.out_where + " ([report] html = true: its .html, " + html + ")";
  files::check_output_not_input(html, {in.out}, html_where, "the results file",
                                fmt::format("give the results a name with another extension, e.g. --out {}: the report "
                                            "goes beside it as {}", files::with_extension(in.out, ".h5"), html));
  files::check_output_not_input(html, {ckpt}, html_where, "the checkpoint");
  files::check_output_not_input(html, inputs, html_where);
  files::check_output_path(html, html_where);
}

// Every rank parses the same text (rank 0 reads the file) and holds the same records (each rank makes a share,
// the shares are exchanged). The output is checked and the checkpoint locked (rank 0) before any work: a bad path
// or a second run on one output stops here.
Inputs load_inputs(const parallel::Session& session, const std::string& study_path, const RunOptions& opt,
                   std::optional<Checkpoint>& ckpt, const RunContext& ctx) {
  std::string text;
  session.agree([&] {
    if (session.root()) text = files::read_text(study_path, "the study file");
  });
  session.broadcast(text);
  std::optional<Inputs> in;
  session.agree([&] { in.emplace(Inputs{parse_study(text, study_path), {}, {}, {}, {}, {}, {}}); });
  in->out = opt.out_given ? opt.out : in->study.output;
  in->out_where = opt.out_given ? "--out" : study_path + ": output";
  session.agree([&] {
    if (!session.root()) return;
    check_outputs(*in);
    if (!opt.force) check_replaceable_results(in->out, in->out_where, in->study);
    ckpt.emplace(in->out + ".ckpt", !in->study.per_model);  // per_model = false: snapshots (study/checkpoint.hpp)
    files::remove_stale_temporaries(in->out);
    files::remove_stale_temporaries(ckpt->path());  // a snapshot's temporary left by a SIGKILL
  });
  // the records: each rank reads or synthesises its share (records rank, rank + ranks, ...) on its threads, the
  // shares are exchanged, and every rank joins them into the same records bit for bit (a record that failed is
  // the first error in record order on every rank)
  // (generated motions: with progress lines and the stop flag; a stop leaves records unmade on every rank's share,
  // so every rank sees it in the joined shares and returns stopped together)
  RecordPlan plan;
  std::string share;
  const WorkHook hook = ctx.hook();
  session.agree([&] {
    inject_fault("load", session.rank());
    plan = plan_study_records(in->study);
    share = make_record_share(plan, session.rank(), session.size(), 0, &hook);
  });
  const std::vector<std::string> shares = session.allgather(share);
  share.clear();
  session.agree([&] {
    if (in->study.select > 0) in->selection.emplace();
    std::vector<StudyRecord> made;
    try {
      made = join_record_shares(shares, plan.count);
    } catch (const Cancelled&) {
      in->stopped = true;
      return;
    }
    in->records = finish_study_records(in->study, std::move(made), in->selection ? &*in->selection : nullptr);
    if (in->records.empty()) throw InputError("the study resolves to no records", study_path, "check [records]");
    // shear buildings: every sample's highest frequency against the integration step, before any work; without
    // [analysis] substeps / max_dt it chooses a stable max_dt, so every rank runs it (the same choice everywhere)
    check_shear_steps(in->study, in->records);
    in->histories = resolve_histories(in->study, in->records);  // a record or model that is not there: before any work
    check_history_memory(in->study, in->records, in->histories.size());
    if (in->study.intensity.enabled) {
      std::vector<double> im;
      for (const auto& rr : in->records) im.push_back(intensity(rr.record, in->study.intensity.im));
      in->stripes = plan_stripes(in->study.intensity, im);
      check_stripes_reachable(in->study.intensity, in->stripes);  // before any work, not a failed fit after it
    }
  });
  return std::move(*in);
}

// ---- phase 2: the work plan ---------------------------------------------------------------------
WorkPlan plan_work(const Inputs& in) {
  const Study& s = in.study;
  WorkPlan L;
  L.records = in.records.size();
  L.stripes = in.stripes.stripes;  // a multiple-stripe unit analyses its block at every stripe
  L.pairs = static_cast<std::size_t>(s.structures.period_pair_count());
  L.samples = static_cast<std::size_t>(s.structures.samples_per_pair);
  L.batch = static_cast<std::size_t>(s.batch);
  L.blocks = (L.samples + L.batch - 1) / L.batch;
  L.gaps = s.gap_ratios.size();
  L.impacts = s.scene == Scene::impacts;
  L.ida = s.intensity.bisection;
  L.per_model = s.per_model;
  L.stream = s.stream;
  // shear buildings: results format 3 with the study's largest topology as /system (format 2 for an SDOF facing a
  // shear building, and for one storey each: system_table gives the SDOF pair nothing)
  if (runs_systems(s.structures))
    if (const std::optional<LaneTopology> t = table_topology(s.structures, s.seed)) {
      SystemBlock block(s);
      const model::System& sys = block.table_system(*t);
      L.system = system_table(sys, block.groups(*t, s.contact), block.element_offsets(sys));
    }
  L.fields = results::unit_schema(L.impacts, L.ida, L.stripes > 0, L.system.extents());
  if (s.restitution && L.impacts) L.fields.push_back(results::restitution_field);  // e(v0): impacts outside its range
  if (s.coarse == CoarsePolicy::refine && L.impacts) L.fields.push_back(results::refine_field);  // each one's substeps
  if (s.restitution && L.impacts && !L.system.empty()) {  // ... and per contact element
    results::FieldSpec f = results::restitution_element_field;
    f.count = static_cast<std::uint32_t>(L.system.extents().elements);
    L.fields.push_back(f);
  }
  return L;
}

// The study, its records and the build: a checkpoint of anything else is not resumed.
CheckpointKey checkpoint_key(const Inputs& in, const WorkPlan& L) {
  CheckpointKey key = this_build();
  std::uint64_t hash = files::fnv1a(in.study.text.data(), in.study.text.size());
  const std::int64_t version = L.format_version();  // 2 for the SDOF pair: its checkpoints' keys as before
  hash = files::fnv1a(&version, sizeof version, hash);
  for (const auto& rr : in.records) {
    hash = files::fnv1a(rr.record.acc.data(), rr.record.acc.size() * sizeof(double), hash);
    hash = files::fnv1a(&rr.record.dt, sizeof(double), hash);
    for (const Record& m : rr.more_supports)  // a multi-support realisation's other supports (none elsewhere)
      hash = files::fnv1a(m.acc.data(), m.acc.size() * sizeof(double), hash);
  }
  key.study_hash = hash;
  key.units = L.units();
  return key;
}

// ---- phase 3: checkpoint and resume (rank 0); every rank learns which units remain ---------------
// [outputs] per_model = false (snapshots): rank 0 adds a rank's snapshot to its tally. The main file is read first;
// a snapshot whose units are all done already was absorbed into rank 0's by a resume that stopped before removing
// it (skipped: its counts are in rank 0's), one sharing only some of them is two runs' files mixed (refused: a unit
// must never count twice).
void absorb_snapshot(Tally& tally, const std::string& path, const ReductionSnapshot& snap) {
  std::size_t n = 0, seen = 0;
  for (std::size_t u = 0; u < tally.units(); ++u)
    if (snap.has(u)) ++n, seen += tally.done(u) ? 1 : 0;
  if (n == 0 || seen == n) return;
  if (seen > 0)
    throw InputError(fmt::format("checkpoint {} shares {} of its {} units with the checkpoint files read before it "
                                 "(files of two runs mixed)",
                                 path, seen, n),
                     path, "move the files of the other run away, or rerun with --force to start afresh");
  try {
    tally.absorb(snap);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("checkpoint {} does not fit this study: {}", path, e.what()), path,
                     "rerun with --force to start afresh");
  }
}

// Rank 0: the slices beside the main file (workers' units, any earlier rank count; study/checkpoint.hpp). A fresh run
// refuses one holding progress (unless --force) as it refuses the main file, then removes it; --resume loads each
// one's units by id and cuts off a torn tail (said, as for the main file). Returns the slices read on --resume.
std::vector<std::string> open_slices(const RunOptions& opt, const Checkpoint& main, const CheckpointKey& key,
                                     Tally& tally, const RunContext& ctx) {
  std::vector<std::string> read;
  for (const std::string& path : slice_paths(main.path())) {
    Checkpoint c(path, main.snapshots());
    files::remove_stale_temporaries(path);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && st.st_size == 0) {  // a rank killed before its header: nothing in it
      c.remove();
      continue;
    }
    if (!opt.resume) {
      open_for_run(c, key, false, opt.force, {});
      c.remove();
      continue;
    }
    std::string dropped;
    open_for_run(
        c, key, true, false,
        [&](std::size_t u, std::vector<std::byte>&& d) {
          if (!tally.done(u)) tally.store(u, d);
        },
        &dropped, [&](ReductionSnapshot&& snap) { absorb_snapshot(tally, path, snap); });
    if (!dropped.empty()) ctx.say(fmt::format("checkpoint {}: {}", path, dropped));
    read.push_back(path);
  }
  return read;
}

// Every worker opens its own slice (continued on --resume, else started; a snapshot slice always starts empty: rank 0
// has absorbed and removed the old one); rank 0 then checks that it sees every worker's slice: the results are
// assembled from them, so the output folder must be shared by every node.
void open_worker_slice(const parallel::Session& session, const RunOptions& opt, const Inputs& in,
                       std::optional<Checkpoint>& ckpt, const CheckpointKey& key) {
  session.agree([&] {
    if (session.root()) return;
    ckpt.emplace(slice_path(in.out + ".ckpt", session.rank()), !in.study.per_model);
    files::remove_stale_temporaries(ckpt->path());
    struct stat st {};
    if (!ckpt->snapshots() && opt.resume && ::stat(ckpt->path().c_str(), &st) == 0 && st.st_size > 0)
      ckpt->resume(ckpt->scan(key), key);
    else
      ckpt->start(key);
  });
  session.agree([&] {
    if (!session.root()) return;
    for (int r = 1; r < session.size(); ++r) {
      const std::string path = slice_path(in.out + ".ckpt", r);
      if (::access(path.c_str(), F_OK) != 0)
        throw InputError(fmt::format("rank {}'s checkpoint slice {} is not visible from rank 0 (the results are "
                                     "assembled from the slices)", r, path),
                         in.out_where,
                         "give an output folder on a filesystem shared by every node (docs/cluster.md), e.g. the "
                         "job's working directory on the cluster's shared filesystem");
    }
  });
}

// Rank 0 loads the main file and the slices. With snapshots (per_model = false) everything loaded is then saved as
// rank 0's one snapshot BEFORE the slices are removed (and before the workers start theirs afresh): a stop between
// the two leaves slices whose units rank 0's snapshot holds, skipped by absorb_snapshot at the next resume.
std::vector<std::size_t> open_checkpoint(const parallel::Session& session, const RunOptions& opt, const Inputs& in,
                                         const WorkPlan& L, std::optional<Checkpoint>& ckpt, const CheckpointKey& key,
                                         Tally& tally, const RunContext& ctx) {
  std::string todo_bytes;  // the remaining unit ids as u64, native order
  session.agree([&] {
    if (!session.root()) return;
    std::string dropped;
    open_for_run(
        *ckpt, key, opt.resume, opt.force, [&](std::size_t u, std::vector<std::byte>&& d) { tally.store(u, d); },
        &dropped, [&](ReductionSnapshot&& snap) { absorb_snapshot(tally, ckpt->path(), snap); });
    if (!dropped.empty()) ctx.say(fmt::format("checkpoint {}: {}", ckpt->path(), dropped));
    const std::vector<std::string> read = open_slices(opt, *ckpt, key, tally, ctx);
    if (ckpt->snapshots() && opt.resume) {
      ckpt->save(tally.snapshot());
      for (const std::string& path : read) ::unlink(path.c_str());
    }
    for (std::uint64_t u = 0; u < L.units(); ++u)
      if (!tally.done(u)) todo_bytes.append(reinterpret_cast<const char*>(&u), sizeof u);
    if (opt.resume) ctx.say(fmt::format("resuming: {} of {} units already done", tally.units_done(), L.units()));
  });
  session.broadcast(todo_bytes);
  std::vector<std::size_t> todo(todo_bytes.size() / sizeof(std::uint64_t));
  for (std::size_t k = 0; k < todo.size(); ++k) {
    std::uint64_t u = 0;
    std::memcpy(&u, todo_bytes.data() + k * sizeof u, sizeof u);
    todo[k] = static_cast<std::size_t>(u);
  }
  if (session.size() > 1) open_worker_slice(session, opt, in, ckpt, key);
  return todo;
}

// A flush of a rank's checkpoint: fsync of its appended units, or (snapshots) its reductions saved whole.
void sync_checkpoint(Checkpoint& c, const Tally& tally) {
  if (c.snapshots()) c.save(tally.snapshot());
  else c.sync();
}

// An error during the units (a failed unit or write, on any rank): a snapshot rank saves what it folded so far, so its
// checkpoint keeps every finished unit as unit records do; if that save fails too, the previous snapshot stays.
void save_after_error(Checkpoint* ckpt, const Tally& tally) noexcept {
  if (!ckpt || !ckpt->snapshots()) return;
  try {
    ckpt->save(tally.snapshot());
  } catch (...) {  // the error being thrown is the one to report
  }
}

// Seconds between the periodic flushes: 5 (POUNDING_TEST_CHECKPOINT_S sets another, for tests only).
double checkpoint_interval_s() {
  static const double s = [] {
    const char* v = std::getenv("POUNDING_TEST_CHECKPOINT_S");
    return v ? std::atof(v) : 5.0;
  }();
  return s;
}

// "building1: shear building, storeys from each sample's height at 3.2 m, ..." (a study with a shear building)
std::string describe_structure(const StructureModel& m, int i) {
  const BuildingModel b = m.row_building(static_cast<std::size_t>(i));
  if (!b.shear()) return fmt::format("building{}: SDOF (one storey facing the other building's floor nearest its height)", i + 1);
  const std::string yield = b.hysteresis == Hysteresis::elastic ? "elastic storeys"
                            : !b.storey_yield.empty()
                                ? fmt::format("storeys yielding at {:g} N", fmt::join(b.storey_yield, ", "))
                            : b.yield_coefficient.given()       ? "storey yield from the base shear Cy M g"
                                                                 : fmt::format("storeys yielding at drift ratio {:.4g}",
                                                                               b.drift / b.ductility);
  return fmt::format("building{}: shear building, {}, {}, {}, {}, {}", i + 1,
                     !b.storey_heights.empty()
                         ? fmt::format("{} storeys of {:g} m", b.code.storeys, fmt::join(b.storey_heights, ", "))
                     : b.code.storeys > 0 ? fmt::format("{} storeys of {:g} m", b.code.storeys, b.storey_height())
                                        : fmt::format("storeys of {0:g} m, max(1, round(h / {0:g} m)) per sample",
                                                      b.storey_height()),
                     !b.floor_mass.empty() ? fmt::format("floors of {:g} kg", fmt::join(b.floor_mass, ", "))
                                           : "the mass split equally over the floors",
                     !b.storey_stiffness.empty() ? fmt::format("storeys of {:g} N/m", fmt::join(b.storey_stiffness, ", "))
                                            : fmt::format("{} storey stiffnesses scaled to T1", to_string(b.profile)),
                     yield, b.damping_text()) +
         (b.isolated ? "; isolated: " + b.isolation_text() : std::string()) +
         (b.moat ? "; moat: " + b.moat_text() : std::string());
}

// Heavy amplitude scaling distorts a record's magnitude-duration-shape consistency (the research note, 2.3; practice
// keeps factors within about [0.25, 4]): name each record scaled outside that range at a stripe, and where.
void warn_scale_factors(const Inputs& in, const RunContext& ctx) {
  const StripePlan& p = in.stripes;
  if (!p.stripes) return;
  // A selected record ([records] select) is already scaled by its selection factor f_i F: the record's factor
  // against its recording is that times the stripe's.
  const IntensitySpec& x = in.study.intensity;
  const std::size_t P = static_cast<std::size_t>(polarity_count(in.study.polarity));
  std::size_t outside = 0;
  for (std::size_t r = 0; r < p.records; r += P) {
    const double sel = in.selection && r / P < in.selection->selection.scale.size() ? in.selection->selection.scale[r / P] : 1.0;
    std::string at;
    for (std::size_t s = 0; s < p.stripes; ++s) {
      const double f = p.scale[s * p.records + r] * sel;
      if (!p.dropped[s * p.records + r] && (f < 0.25 || f > 4.0))
        at += fmt::format("{}x{:.3g}{} at {:g}", at.empty() ? "" : ", ", f,
                          in.selection ? fmt::format(" (selection {:.3g} x stripe {:.3g})", sel, p.scale[s * p.records + r])
                                       : std::string(),
                          x.levels[s]);
    }
    if (at.empty()) continue;
    ++outside;
    ctx.say(fmt::format("record {}: scale factor outside [0.25, 4] (IM {:.3g} {}): {}", in.records[r].id, p.im[r],
                        im_units(x.im.measure), at));
  }
  if (outside)
    ctx.say(fmt::format("{} of {} records are scaled outside [0.25, 4] at some stripe: large factors can bias "
                        "the response (Baker 2015 prefers records selected near each level); the report counts them",
                        outside, p.records / static_cast<std::size_t>(polarity_count(in.study.polarity))));
}

void announce(const parallel::Session& session, const Inputs& in, const WorkPlan& L, const RunContext& ctx) {
  if (!session.root()) return;
  ctx.say(fmt::format("pounding run: {} ({} records{}, {} models, scene {}, {} units on {} rank{})", in.study.title,
                      in.records.size() / polarity_count(in.study.polarity),
                      in.study.polarity == Polarity::both ? " x 2 signs" : "", L.models(), to_string(in.study.scene), L.units(), session.size(),
                      session.size() > 1 ? "s" : ""));
  ctx.say(in.study.scene_reason);
  const StructureModel& sm = in.study.structures;
  const bool m = in.study.gap_metres;
  if (sm.bridge)
    ctx.say(fmt::format("a bridge: {}. The study gap {} sets every joint's gap to {} + (its gap - d), d = {:g} m "
                        "(the smallest joint gap); an analysis pounds when ANY joint closes",
                        sm.bridge->describe(), m ? "g (m)" : "ratio x", m ? "g" : "x d", sm.bridge->reference_gap));
  if (sm.row())
    ctx.say(fmt::format("a row of {} buildings, left to right: every joint with the study gap {}; an analysis pounds "
                        "when ANY joint touches",
                        sm.building_count(),
                        m ? "g ([gaps] metres)" : "ratio x d (d = the row's largest joint code separation)"));
  for (int b = 0; b < static_cast<int>(sm.building_count()) && sm.any_shear(); ++b) ctx.say(describe_structure(sm, b));
  if (in.study.polarity == Polarity::both)
    ctx.say(fmt::format("record polarity \"both\": each of the {} records applied with both signs, as two analyses of "
                        "the same record", in.records.size() / 2));
  if (in.selection) {
    ctx.say(fmt::format("records selected to the design spectrum ([records] select = {}, [target_spectrum]):",
                        in.study.select));
    for (const auto& line : in.selection->summary()) ctx.say(line);
  } else if (in.records.size() <= 500 * static_cast<std::size_t>(polarity_count(in.study.polarity))) {
    // A library used whole counts one recording twice when it holds two files of it (the El Centro 1940 N-S
    // motion is in ../shared/records/real as NGA's Array #9 180 and as Peknold's digitisation): say so
    // (motion/library.hpp; the pairwise check is skipped for libraries above 500 records).
    // (a record's reversed copy, [records] polarity = "both", is the same recording by design: left out)
    std::vector<RecordIdentity> ids;
    std::vector<std::size_t> row;
    for (std::size_t k = 0; k < in.records.size(); ++k)
      if (in.records[k].polarity > 0) ids.push_back(identity_of(in.records[k].record)), row.push_back(k);
    for (std::size_t i = 0; i < ids.size(); ++i)
      for (std::size_t j = i + 1; j < ids.size(); ++j)
        if (same_recording(ids[i], ids[j]))
          ctx.say(fmt::format(" WARNING: records {} and {} are one recording ({}, {}, components {} and {}): the "
                              "statistics count that motion twice; drop one file, or choose records with [records] "
                              "select", in.records[row[i]].id, in.records[row[j]].id, ids[i].event_text(), ids[i].station,
                              ids[i].component, ids[j].component));
  }
  if (const StripePlan& p = in.stripes; p.stripes) {
    const IntensitySpec& x = in.study.intensity;
    std::string dropped;
    for (std::size_t s = 0; s < p.stripes; ++s)
      if (const std::size_t d = p.dropped_count(s))
        dropped += fmt::format("{}{} at {:g}", dropped.empty() ? "" : ", ", d, x.levels[s]);
    ctx.say(fmt::format("multiple-stripe analysis: {} stripes of {}{}; every record scaled to each level, the same "
                        "models at every stripe{}",
                        p.stripes, describe(x.im), x.period_pair ? " (period \"pair\": the geometric mean of the "
                                                                  "buildings' median periods)" : "",
                        dropped.empty() ? "" : fmt::format("; records dropped (factor above max_scale = {:g}): {}",
                                                           x.max_scale, dropped)));
  }
  warn_scale_factors(in, ctx);
  for (const auto& rr : in.records)
    if (rr.synthetic && rr.polarity > 0) ctx.say(fmt::format("record {}: synthetic stand-in ({})", rr.id, rr.note));
}

// Test-only: POUNDING_MASTER_SERVICE=1 measures the master's service time per unit (issue 27.4;
// docs/performance.md "Scaling across ranks", tools/predict_scaling.py): units return stored results at once,
// rank 0 prints the master's time per unit and bytes per unit after the units, and the run ends without results
// (the checkpoint is removed).
bool master_service_mode() {
  static const bool on = [] {
    const char* v = std::getenv("POUNDING_MASTER_SERVICE");
    return v != nullptr && std::string_view(v) == "1";
  }();
  return on;
}

double final_sync_s = 0;  // the units phase's closing fsync of the checkpoint (rank 0), for the line above
parallel::MasterStats master_stats;  // rank 0's serving of the workers' units, for the line above
double assemble_s = 0;    // rank 0's reading of the workers' slices after the units, for the line above

ProgressReport progress_report(const WorkPlan& L, std::size_t done, std::size_t at_start, double elapsed_s) {
  ProgressReport p;
  p.units_done = done, p.units_total = L.units(), p.units_at_start = at_start;
  p.models_per_unit = static_cast<double>(L.samples * L.unit_stripes()) / static_cast<double>(L.blocks);
  p.elapsed_s = elapsed_s;
  p.final = done == L.units();
  return p;
}

// ---- phase 4: the work (every rank computes and checkpoints its own units; rank 0 schedules) -----
// `threads` worker threads per rank, each with its own UnitComputer (parallel::run_units with a ThreadComputeFn).
// Each rank appends the units it computed to its own checkpoint file (rank 0: <out>.ckpt, rank r: its slice) on the
// calling thread; a worker tells rank 0 only the unit's id (issue 27.4), and rank 0 stores its own units in the tally
// by unit id. `remote` counts the units the workers stored. T[compute] is the sum of the threads' compute seconds
// (CPU-like: with 2 busy threads it is about twice the units' wall time).
bool execute(const parallel::Session& session, const Inputs& in, const WorkPlan& L, const std::vector<std::size_t>& todo,
             Checkpoint* ckpt, Tally& tally, std::size_t& remote, const RunContext& ctx, double& wall,
             timing::Times& T, int threads) {
  const auto t_setup = std::chrono::steady_clock::now();
  const StructureSampler sampler(in.study.structures, in.study.seed);
  std::atomic<int> computed{0};
  std::vector<std::unique_ptr<UnitComputer>> computers;
  for (int t = 0; t < threads; ++t)
    computers.push_back(std::make_unique<UnitComputer>(in.study, in.records, in.stripes, sampler, L, session.rank(), computed,
                                                       ctx.cancel));
  std::vector<double> compute_s(static_cast<std::size_t>(threads), 0.0);  // each thread's compute seconds
  T[timing::Phase::structures] = timing::seconds_since(t_setup);
  using timing::Phase, timing::Stopwatch;
  const auto t0 = std::chrono::steady_clock::now();
  auto last_sync = t0;
  const std::size_t at_start = tally.units_done();
  auto tick = [&] {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_sync > std::chrono::duration<double>(checkpoint_interval_s())) {
      Stopwatch w(T[Phase::checkpoint]);
      sync_checkpoint(*ckpt, tally), last_sync = now;
    }
    if (!ctx.progress || !session.root()) return;
    ctx.progress(progress_report(L, tally.units_done() + remote, at_start, std::chrono::duration<double>(now - t0).count()));
  };
  // the units start (no line: the display's clock for a long first unit)
  if (ctx.progress && session.root() && !todo.empty()) ctx.progress(progress_report(L, at_start, at_start, 0.0));
  static const std::atomic<bool> never{false};
  // Test-only (issue 27.4, POUNDING_MASTER_SERVICE): every rank computes one unit of each size once and returns a
  // copy of it for every later unit, so the workers answer at once and the run measures the master alone.
  const bool stored = master_service_mode();
  std::map<std::size_t, parallel::Payload> kept;
  std::mutex kept_mutex;  // the threads share `kept`
  const bool complete = parallel::run_units(
      session, todo,
      [&](std::size_t u, int t) {
        Stopwatch w(compute_s[static_cast<std::size_t>(t)]);
        UnitComputer& compute = *computers[static_cast<std::size_t>(t)];
        if (!stored) return compute(u).serialise();
        const std::size_t n = L.lanes(L.decode(u).block);
        {
          std::lock_guard lock(kept_mutex);
          if (auto at = kept.find(n); at != kept.end()) return at->second;
        }
        parallel::Payload p = compute(u).serialise();
        std::lock_guard lock(kept_mutex);
        return kept.emplace(n, std::move(p)).first->second;  // a unit of this size kept meanwhile: that one
      },
      threads,
      [&](std::size_t u, parallel::Payload&& d) {
        if (session.root() || tally.reductions()) {  // a worker folds its own units into its Reductions
          Stopwatch w(T[Phase::reduce]);
          tally.store(u, d);
        }
        Stopwatch w(T[Phase::checkpoint]);
        if (!ckpt->snapshots()) ckpt->append(u, d);  // a snapshot holds the folded counts instead (saved in tick)
      },
      [&](std::size_t u, int) {
        ckpt->keep();  // the main file stays with the slices even if rank 0 stored no unit
        if (tally.reductions()) tally.folded_elsewhere(u);  // merged from the worker's Reductions at the end
        else ++remote;
      },
      tick, ctx.cancel ? *ctx.cancel : never, &master_stats);
  for (double s : compute_s) T[Phase::compute] += s;
  double final_sync = 0;
  {
    Stopwatch w(final_sync);
    sync_checkpoint(*ckpt, tally);  // every rank: its units are on disk before rank 0 reads the slices (or the run stops)
  }
  T[Phase::checkpoint] += final_sync;
  final_sync_s = final_sync;
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  T[Phase::units] = wall;
  return complete;  // the same on every rank; assemble() checks that every unit is there
}

// ---- phase 4b: rank 0 reads the workers' slices into the tally, by unit id ------------------------
// After every rank has flushed its slice (the barrier). Only the main file and the slices hold the units, so one
// missing here (a slice on a folder rank 0 does not see, damaged since) is an error before any result is written.
// With [outputs] per_model = false or "stream" every rank folded its own units: their integer counts are summed on
// rank 0 and the models' summaries merged (order-free), and the slices are not read here ("stream": they are read
// when the results file is written, study/spill.hpp, which refuses a missing unit before anything is written).
void merge_reductions(const parallel::Session& session, Tally& tally) {
  Reductions& red = *tally.reductions();
  std::vector<std::int64_t> counts = red.counts();
  session.sum_to_root(counts);
  const std::vector<double> mine = red.summary(), all = session.gather_to_root(mine);
  if (!session.root()) return;
  red.set_counts(counts);  // every rank's, rank 0's included
  tally.merged_elsewhere();  // a later snapshot of rank 0 (a stop in the analysis) holds every unit
  for (int r = 1; r < session.size(); ++r)
    red.merge_summary(std::span<const double>(all).subspan(static_cast<std::size_t>(r) * mine.size(), mine.size()));
}

void assemble(const parallel::Session& session, const Inputs& in, const WorkPlan& L, Tally& tally,
              const CheckpointKey& key, timing::Times& T) {
  if (session.size() == 1) return;
  session.barrier();
  if (!L.per_model || L.stream) {  // every rank folded its own units into its Reductions
    timing::Stopwatch w(assemble_s);
    merge_reductions(session, tally);
  }
  session.agree([&] {
    if (!session.root()) return;
    timing::Stopwatch w(assemble_s);
    const std::string main = in.out + ".ckpt";
    if (L.per_model && !L.stream)  // "stream": the slices are read when the results are written (study/spill.hpp)
      for (const std::string& path : slice_paths(main))
        scan_checkpoint(path, key, [&](std::size_t u, std::vector<std::byte>&& d) {
          if (!tally.done(u)) tally.store(u, d);
        });
    if (tally.units_done() != L.units())
      throw InputError(fmt::format("{} of {} units are missing from the checkpoint slices after the run",
                                   L.units() - tally.units_done(), L.units()),
                       main, "check that every rank writes to the same shared output folder, then rerun with --resume "
                             "(the missing units are computed again)");
  });
  T[timing::Phase::reduce] += assemble_s;
}

// ---- phase 5: the results file (rank 0; the others wait for its outcome), then the checkpoint goes --
// The wall time written and logged runs from the process's start (timing::program_start) to the results write: MPI
// start-up, reading, the units, the fit and the report of this invocation; `wall` is the units' share. A stop during the analysis (Cancelled, from the
// hook's flag) ends with 130 and keeps the checkpoint, which holds every unit: --resume redoes only the analysis.
// /timing: each phase's seconds on rank 0 and the largest over the ranks (core/timing.hpp; docs/results-format.md).
results::Group timing_group(const timing::Times& T, std::size_t units, std::size_t units_resumed, int threads) {
  results::Group g{"timing", {}, {}};
  std::vector<std::string> names, meanings;
  for (std::size_t i = 0; i < timing::phase_count; ++i)
    names.emplace_back(timing::phase_names[i]), meanings.emplace_back(timing::phase_meanings[i]);
  g.add("phase", names, "1", "the phases of this invocation (core/timing.hpp); they overlap: compute, reduce and "
                             "checkpoint are inside units, bootstrap inside report");
  g.add("meaning", meanings, "1", "what each phase covers");
  g.add("rank0_s", std::vector<double>(T.rank0.begin(), T.rank0.end()), "s", "rank 0's seconds in each phase");
  g.add("max_s", std::vector<double>(T.max.begin(), T.max.end()), "s",
        "the largest seconds over the ranks (phases after the units run on rank 0 only: its seconds)");
  g.set("wall_s", T.wall);
  g.set("units", static_cast<std::int64_t>(units));
  g.set("units_resumed", static_cast<std::int64_t>(units_resumed));
  g.set("threads", static_cast<std::int64_t>(threads));
  g.set("description", std::string("wall_s: from this process's start (before MPI start-up) to the end of the "
                                   "report (the results write's bulk runs beside the report), so it holds every "
                                   "phase but results_write, the write's part after the report; after --resume only "
                                   "this invocation (units_resumed units came from the checkpoint); threads: the "
                                   "worker threads per rank (results do not depend on it); the compute phase sums a "
                                   "rank's threads"));
  return g;
}

// The run is complete: the workers' slices and the main file go (rank 0; the workers still hold their slices open).
void remove_checkpoint(Checkpoint& main) {
  for (const std::string& path : slice_paths(main.path())) ::unlink(path.c_str());
  main.remove();
}

// The report (RunOptions::report) rendered on a thread of its own while this thread writes the bulk of the results
// file (results::Writer: everything the report's end does not change), so the two serial phases after the units
// overlap: on the paper study the report takes 0.2 s and the bulk 0.2-0.4 s on 2 cores. HDF5 is called from this
// thread only; the report reads `res`, which neither side changes. Sets the report, its time and its bootstrap's, and
// in `write_s` the wall time the bulk added after the report ended (0 when the report took longer). An error or a
// stop on either side is thrown here after both have ended, the report's first; the unfinished Writer then leaves
// nothing on disk. Without a report the bulk alone, all of it in `write_s`.
// `view` (may be null: res): the results the report is made from ([outputs] per_model = "stream": the reductions'),
// and `on_disk`: the file is built in an on-disk temporary (results::Writer).
results::Writer report_beside_write(const RunOptions& opt, const RunContext& ctx, const std::string& out,
                                    results::Results& res, results::Results* view, bool on_disk, std::string& report,
                                    timing::Times& T, double& write_s) {
  using timing::Phase;
  const auto t0 = std::chrono::steady_clock::now();
  if (!opt.report) {
    results::Writer file(out, res, on_disk);
    write_s = timing::seconds_since(t0);
    return file;
  }
  if (!view) view = &res;
  res.path = view->path = out;
  res.header.wall_time_s = view->header.wall_time_s = NAN;
  std::exception_ptr report_error;
  double bootstrap_s = 0;
  std::chrono::steady_clock::time_point report_end;
  std::thread renderer([&] {
    try {
      report = opt.report(*view, ctx.hook(), bootstrap_s);
    } catch (...) {
      report_error = std::current_exception();
    }
    report_end = std::chrono::steady_clock::now();
  });
  std::optional<results::Writer> file;
  std::exception_ptr write_error;
  try {
    file.emplace(out, res, on_disk);
  } catch (...) {
    write_error = std::current_exception();
  }
  const auto bulk_end = std::chrono::steady_clock::now();
  renderer.join();
  if (report_error) std::rethrow_exception(report_error);
  if (write_error) std::rethrow_exception(write_error);
  T[Phase::bootstrap] += bootstrap_s;
  T[Phase::report] = std::chrono::duration<double>(report_end - t0).count();
  write_s = std::max(0.0, std::chrono::duration<double>(bulk_end - report_end).count());
  return std::move(*file);
}

// The run's results (the selection's group added). [outputs] per_model = "stream": the per-model fields are read from
// the checkpoint files as the file is written (study/spill.hpp), and `view` gets the results the report is made
// from, the reductions'.
// `meter` ("stream"): the write's progress and stop, counted in values (each per-model field's, and a model row each).
results::Results run_results(const Inputs& in, const WorkPlan& L, Tally& tally, const Exclusions& ex,
                             const RunFacts& facts, const CheckpointKey& key, std::optional<results::Results>& view,
                             const WorkHook* hook, std::shared_ptr<Meter>& meter) {
  std::shared_ptr<const SpilledColumns> spilled;
  if (L.stream) spilled = std::make_shared<const SpilledColumns>(L, in.out + ".ckpt", key);
  results::Results res = make_results(in.study, in.records, L, tally, ex, facts, in.stripes, spilled);
  if (spilled) {
    std::size_t total = res.streamed_models;
    for (const results::Field& f : res.fields) total += L.analysis_records() * L.models() * L.per_lane(f.spec);
    static const std::string phase = "results write: per-model datasets from the checkpoint";
    meter = std::make_shared<Meter>(hook, phase, total, "values");
    for (results::Field& f : res.fields)
      f.source = [fill = f.source, m = meter, last = &f == &res.fields.back()](std::size_t first, std::size_t n, void* to) {
        if (last) inject_fault("stream", 0);  // tests: POUNDING_INJECT_FAULT=stream@0 fails the write half-way
        if (!m->step(n)) throw Cancelled(phase);
        fill(first, n, to);
      };
    res.model_rows = [rows = res.model_rows, m = meter](std::size_t first, std::size_t n, results::ModelTable& t) {
      if (!m->step(n)) throw Cancelled(phase);
      rows(first, n, t);
    };
  }
  if (L.stream) view.emplace(make_results(in.study, in.records, L, tally, ex, facts, in.stripes));
  if (in.selection) res.groups.push_back(selection_group(*in.selection));
  return res;
}

// [outputs] histories (study/histories.hpp): the named analyses and the worst N (ranked from `res`) rerun with the
// recorder into /histories; `view` (the report's results, "stream") gets their attributes. Progress and a stop
// through the context; a history whose peaks differ from the study's is said (it cannot be: the same code runs it).
void add_histories(const Inputs& in, results::Results& res, results::Results* view, const RunContext& ctx) {
  const std::vector<HistoryChoice> choices = choose_worst(in.study, res, in.histories);
  ctx.say(fmt::format("histories: {} analys{} rerun with the recorder ([outputs] histories)", choices.size(),
                      choices.size() == 1 ? "is" : "es"));
  const WorkHook hook = ctx.hook();
  std::string mismatch;
  results::Group g = run_histories(in.study, in.records, choices, res, &hook, mismatch);
  if (!mismatch.empty())
    ctx.say(" WARNING: a stored history's peaks differ from the study's per-model values: " + mismatch);
  if (view) {
    results::Group light = g;
    for (results::Group& c : light.children) c.datasets.clear();
    view->groups.push_back(std::move(light));
  }
  res.groups.push_back(std::move(g));
}

// After the caller's analyses: the report's results ("stream": `view`) get the groups they added (and the selection's),
// then [outputs] histories are run.
void after_analysis(const Inputs& in, results::Results& res, results::Results* view, std::size_t groups_before,
                    const RunContext& ctx) {
  if (view) view->groups.insert(view->groups.end(), res.groups.begin() + (in.selection ? groups_before - 1 : groups_before),
                                res.groups.end());
  if (!in.study.histories.empty()) add_histories(in, res, view, ctx);
}

int finish(const parallel::Session& session, const Inputs& in, const WorkPlan& L, Checkpoint* ckpt, Tally& tally,
           const CheckpointKey& key, double wall, const RunContext& ctx, const RunOptions& opt, timing::Times& T,
           std::size_t units_resumed, int threads, std::string& report) {
  using timing::Phase;
  int rc = 0;
  std::string summary_line, stopped_in;
  double total = 0, analysis = 0;
  session.lend_cpus_to_root();  // the other ranks wait in agree() below: rank 0's report and write use their CPUs
  session.agree([&] {
    if (!session.root()) return;
    inject_fault("write", 0);
    const Exclusions ex = count_exclusions(in.study, L, tally, in.records);
    if (L.impacts) summary_line = physics::describe(ex.coarse);
    if (L.stripes) {
      const auto& sc = tally.values<std::uint8_t>(results::field_index(L.fields, "uncoupled", "scaled"));
      const auto& st = tally.values<std::uint8_t>(results::unit_field("uncoupled", "status"));
      std::size_t scaled = 0, analysed = 0;
      for (std::size_t k = 0; k < sc.size(); ++k) scaled += sc[k], analysed += st[k] != results::dropped_status;
      summary_line = fmt::format("multiple stripes: {} of {} analyses ({:.1f} %) scaled from the lowest stripe (elastic "
                                "buildings, [analysis] scale_elastic), {} run",
                                scaled, analysed, analysed ? 100.0 * static_cast<double>(scaled) / static_cast<double>(analysed) : 0.0,
                                analysed - scaled);
    }
    try {
      std::optional<results::Results> view;
      std::shared_ptr<Meter> meter;  // "stream": the write's progress
      const WorkHook hook = ctx.hook();
      results::Results res = run_results(in, L, tally, ex, {key.build, session.size(), wall}, key, view, &hook, meter);
      const auto t_analysis = std::chrono::steady_clock::now();
      // the analyses the caller adds (fragility, hazard: report/fragility.hpp), with progress and the stop flag
      const std::size_t groups_before = res.groups.size();
      if (opt.analyse) opt.analyse(res, ctx.hook());
      after_analysis(in, res, view ? &*view : nullptr, groups_before, ctx);
      analysis = T[Phase::analysis] = timing::seconds_since(t_analysis);
      // the report pounding run prints, from these results (its wall time filled in below), rendered while this
      // thread writes the file's bulk; results_write counts what the write adds after the report
      double write_s = 0;
      results::Writer file =
          report_beside_write(opt, ctx, in.out, res, view ? &*view : nullptr, L.stream, report, T, write_s);
      if (meter) meter->finish();
      total = T.wall = timing::seconds_since(opt.start);
      res.header.wall_time_s = total;
      if (const auto at = report.find("wall time nan s"); at != std::string::npos)
        report.replace(at, 15, fmt::format("wall time {:.2f} s", total));
      for (std::size_t i = static_cast<std::size_t>(Phase::analysis); i < timing::phase_count; ++i) T.max[i] = T.rank0[i];
      res.groups.push_back(timing_group(T, L.units(), units_resumed, threads));
      const auto t_write = std::chrono::steady_clock::now();
      file.finish(res);
      T.max[static_cast<std::size_t>(Phase::results_write)] = T[Phase::results_write] =
          write_s + timing::seconds_since(t_write);
      T.wall = timing::seconds_since(opt.start);
    } catch (const Cancelled& c) {
      sync_checkpoint(*ckpt, tally);
      stopped_in = c.phase();
      rc = 130;
      return;
    } catch (const InputError& e) {
      throw InputError(e.what_part(), e.where(),
                       e.fix() + "; the checkpoint keeps every unit: --resume writes the results without recomputing");
    }
    remove_checkpoint(*ckpt);
    rc = ex.verdict.empty() ? 0 : 3;
  });
  session.broadcast(rc);
  if (session.root() && rc == 130) {
    ctx.say(fmt::format("\ninterrupted during the analysis ({}): all {} units are checkpointed in {}; --resume "
                        "redoes only the analysis",
                        stopped_in, L.units(), ckpt->path()));
    return rc;
  }
  if (session.root()) {
    if (!summary_line.empty()) ctx.say(summary_line);
    ctx.say(fmt::format("results: {} (wall time {:.2f} s: units {:.2f} s, analysis {:.2f} s; {} rank{} x {} thread{})",
                        in.out, total, wall, analysis, session.size(), session.size() == 1 ? "" : "s", threads,
                        threads == 1 ? "" : "s"));
    if (rc == 3) ctx.say(" WARNING: too many excluded analyses; the results file says so (exit code 3)");
  }
  return rc;
}

}  // namespace

int study_threads(int requested, int ranks, std::size_t units) {
  if (requested <= 0 && ranks > 1) return 1;
  return thread_count(requested, units);
}

RunOutcome run_study(const parallel::Session& session, const std::string& study_path, const RunOptions& opt,
                     const RunContext& ctx) {
  // Every phase runs inside session.agree() or run_units: an error on any rank stops every rank together,
  // and rank 0 prints one message.
  timing::Times T;
  T[timing::Phase::mpi_start] = opt.mpi_start_s;
  const auto t_inputs = std::chrono::steady_clock::now();
  std::optional<Checkpoint> ckpt;  // rank 0: the main file; a worker: its slice (opened in open_checkpoint)
  const Inputs in = load_inputs(session, study_path, opt, ckpt, ctx);
  if (in.stopped) {  // nothing done: the checkpoint this run created goes with ckpt
    if (session.root()) ctx.say("\ninterrupted while the records were made: nothing done, no checkpoint left");
    return {130, in.out, {}, T, {}};
  }
  const WorkPlan L = plan_work(in);
  Tally tally;
  // rank 0; with [outputs] per_model = false or "stream" every rank (each folds its own units into its Reductions)
  if (session.root() || !L.per_model || L.stream) tally = Tally(L, in.study);
  const CheckpointKey key = checkpoint_key(in, L);  // every rank: the workers' slices carry it too
  const std::vector<std::size_t> todo = open_checkpoint(session, opt, in, L, ckpt, key, tally, ctx);
  const std::size_t units_resumed = tally.units_done();
  T[timing::Phase::inputs] = timing::seconds_since(t_inputs);
  announce(session, in, L, ctx);
  double wall = 0.0;
  const int threads = study_threads(opt.threads >= 0 ? opt.threads : in.study.threads, session.size(), todo.size());
  std::size_t remote = 0;  // rank 0: units the workers stored in their slices
  bool complete = false;
  try {
    complete = execute(session, in, L, todo, ckpt ? &*ckpt : nullptr, tally, remote, ctx, wall, T, threads);
  } catch (...) {
    save_after_error(ckpt ? &*ckpt : nullptr, tally);
    throw;
  }
  if (complete) assemble(session, in, L, tally, key, T);
  std::vector<double> phases(T.rank0.begin(), T.rank0.end());  // every rank: the maxima of the phases so far
  session.max_to_root(phases);
  std::copy(phases.begin(), phases.end(), T.max.begin());
  if (!complete) {
    if (session.root())
      ctx.say(tally.units_done() + remote > 0
                  ? fmt::format("\ninterrupted: {} of {} units done and checkpointed in {}{}; continue with --resume",
                                tally.units_done() + remote, L.units(), ckpt->path(),
                                session.size() > 1 ? " and its rank slices" : "")
                  : fmt::format("\ninterrupted before any unit finished: nothing to keep, no checkpoint left"));
    return {130, in.out, {}, T, {}};
  }
  if (master_service_mode()) {
    if (session.root()) {
      const double units = static_cast<double>(todo.size());
      const std::size_t bytes = serialised_size(L, L.lanes(0));
      const double served = wall - final_sync_s;
      ctx.say(fmt::format("master service (test-only POUNDING_MASTER_SERVICE, stored unit results, no results "
                          "written): {} units in {:.4f} s on {} ranks (+ {:.4f} s closing fsync) = {:.2f} us per unit "
                          "({:.0f} units/s), {} bytes per full unit; of it checkpoint appends {:.2f} us, reduce {:.2f} "
                          "us per unit; {} bytes per unit to the master ({} of {} units stored on rank 0); the master's "
                          "time per worker unit {:.2f} us ({} units: receive the id, send the next unit); assembly "
                          "from the slices after the units {:.4f} s = {:.2f} us per worker unit",
                          todo.size(), served, session.size(), final_sync_s, 1e6 * served / units, units / served,
                          bytes, 1e6 * (T[timing::Phase::checkpoint] - final_sync_s) / units,
                          1e6 * (T[timing::Phase::reduce] - assemble_s) / units, session.size() > 1 ? 8 : 0,
                          todo.size() - remote, todo.size(),
                          master_stats.worker_units ? 1e6 * master_stats.service_s / master_stats.worker_units : 0.0,
                          master_stats.worker_units, assemble_s, remote ? 1e6 * assemble_s / static_cast<double>(remote) : 0.0));
      remove_checkpoint(*ckpt);
    }
    return {0, in.out, {}, T, {}};
  }
  RunOutcome r{0, in.out, {}, {}, {}};
  r.code = finish(session, in, L, ckpt ? &*ckpt : nullptr, tally, key, wall, ctx, opt, T, units_resumed, threads,
                  r.report);
  r.times = T;
  if (in.study.html) r.html = files::with_extension(in.out, ".html");
  return r;
}

}  // namespace pounding
