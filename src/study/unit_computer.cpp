// UnitComputer: one work unit of a study, its scenes written once against the Runner (study/runner.hpp).
#include "unit_computer.hpp"

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
#include "pounding/study/runner.hpp"
#include "pounding/study/system_block.hpp"
#include "pounding/study/spill.hpp"
#include "pounding/study/tally.hpp"
#include "pounding/study/unit_result.hpp"

#include "run_phases.hpp"

namespace pounding::study_run {

namespace {

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

}  // namespace

// One work unit: sample the block, run the uncoupled pairs (and, in the impacts scene, the coupled ones per
// gap), fill a UnitResult. A rank's threads have one UnitComputer each: it holds every buffer it writes (peaks,
// scratch, its Runner); what it shares with the others is read only (study, records, stripes,
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
    runner_ = make_runner(s, plan);
    if (!plan.system.empty()) table_fields(plan);
    if (s.restitution && plan.impacts) {  // e(v0) in the coupled runs (study.cpp: hertzdamp, CD, impacts scene)
      restitution_ = std::make_unique<physics::HertzdampRestitution>(*s.restitution, s.contact);
      f_rest_out_ = results::field_index(plan.fields, "impacts", "restitution_outside");
      if (!plan.system.empty())
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
    runner_->load(pairs_);
    if (plan_.stripes) {
      stripes(rec, u.record, ks, out);
      return out;
    }
    const UnitMotion m = motion(records_[u.record]);
    probability(m, ks, out);
    if (plan_.impacts)
      for (std::size_t g = 0; g < plan_.gaps; ++g) impacts(g, m, ks, out);
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
      for (std::size_t i = 0; i < n; ++i) put_uncoupled(out, at + i, cur_.status[i], cur_.u1[i], cur_.u2[i], cur_.closing[i]);
      put_stripe_rows(out, s);
      if (anchor) continue;
      auto scaled_flag = out.values<std::uint8_t>(stripe_scaled_);
      for (std::size_t i = 0; i < n; ++i) scaled_flag[at + i] = 1;
      for (std::size_t i : lanes_) scaled_flag[at + i] = 0;
    }
  }

  // The peaks of every lane under the record scaled by f, into cur_: with fa == 0 the anchor run of every lane
  // (anchor_; fa becomes f); at a higher factor f the lanes that scale linearly over f / fa (Runner::scales_linearly,
  // the model trait; [analysis] scale_elastic) take the anchor's peaks times f / fa, the others (lanes_) run on the
  // scaled record (a lane's bits do not depend on the lanes run beside it). The same for the stripes and the IDA's
  // hunt, so the hunt is MSA's own analysis, bit for bit.
  void peaks_at(const Record& rec, double f, double& fa, const KernelSettings& ks) {
    const std::size_t n = pairs_.size();
    const UnitMotion m{GroundMotion{rec.dt, scaled(rec, f), rec.duration() + s_.free_vibration}, {}};
    const bool anchor = fa == 0;
    if (anchor) fa = f;
    const double ratio = anchor ? 1.0 : f / fa;
    lanes_.clear();
    if (anchor) {
      runner_->uncoupled(m, ks, anchor_);
    } else {
      for (std::size_t i = 0; i < n; ++i)
        if (!(s_.scale_elastic && runner_->scales_linearly(anchor_, i, ratio, ks.displacement_limit))) lanes_.push_back(i);
      if (!lanes_.empty()) runner_->rerun_uncoupled(lanes_, m, ks, sub_peaks_);
    }
    cur_.resize(n, anchor_.buildings, runner_->layout());
    for (std::size_t i = 0, j = 0; i < n; ++i) {
      if (j < lanes_.size() && lanes_[j] == i) cur_.set_scaled(i, sub_peaks_, j++, 1.0);
      else cur_.set_scaled(i, anchor_, i, ratio);
    }
  }

  // stripe s's per-floor / per-element rows and a row's buildings 3..n from cur_ (the schema's: none for the pair)
  void put_stripe_rows(UnitResult& out, std::size_t s) {
    const std::size_t nb = cur_.buildings;
    const bool table = !runner_->layout().empty();
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
      if (table) put_table_uncoupled(out, i, cur_, s);
      for (std::size_t b = 2; b < nb; ++b) out.lane_values<double>(f_row_unc_[b], i, s)[0] = cur_.u[i * nb + b];
    }
  }

  // The bisection IDA of yielding pairs (method = "ida"): for every lane and gap ratio x, the record scale factor
  // at which the pair first touches, i.e. the smallest f with peak closing D(f) > x d.
  //  1. Hunt: the record scaled (like a stripe, bit-identical to MSA's analysis at that factor) to each factor of
  //     ida_hunt_factors -- the stripes' levels below max_scale, then max_scale. The first factor whose run
  //     touches brackets f* between it and the factor before (0 before the first); no touch up to the last factor:
  //     censored. A diverged analysis ends the lane's hunt: its open gaps are censored at the factor before (the
  //     record's cap comes down to it in make_results), or excluded when that was the first factor.
  //  2. Bisection on ln f (halving from 0 while the bracket starts there) until hi <= lo (1 + tolerance): see
  //     bisect().
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
        if (cur_.status[i] != 0) {
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
          if (cur_.closing[i] > s_.gap_at(g, pairs_[i])) state[k] = found, hi[k] = f;
          else lo[k] = f;
        }
      }
    }
    // A lane still elastic where it first touched is linear on [0, hi]: D(f) = (f / fa) D(fa), so its first contact
    // is exactly at fa x d / D(fa), no bisection needed ([analysis] scale_elastic; the bracket closes on it)
    if (s_.scale_elastic)
      for (std::size_t k = 0; k < n * G; ++k) {
        const std::size_t i = k / G;
        if (state[k] != found || !runner_->scales_linearly(anchor_, i, hi[k] / fa, ks.displacement_limit)) continue;
        const double D = anchor_.closing[i];
        const double f = fa * s_.gap_ratios[k % G] * s_.gap_unit(pairs_[i]) / D;  // (fa x) d / D in this order: ratio studies' bits
        lo[k] = hi[k] = std::clamp(f, lo[k], hi[k]);
      }
    bisect(rec, ks, state, lo, hi, analyses);
    auto slo = out.values<double>(ida_lo_), shi = out.values<double>(ida_hi_);
    for (std::size_t k = 0; k < n * G; ++k) {
      const bool ok = state[k] != excluded;
      slo[k] = ok ? lo[k] : NAN, shi[k] = ok ? hi[k] : NAN;  // open: censored, [last factor analysed, inf)
    }
  }

  // The IDA's bisection (see ida()): every found (lane, gap) bracket narrowed to the tolerance, each step's open
  // brackets at their midpoints through Runner::at_factors (the pair: one kernel lane per bracket, each spring its
  // unscaled equivalent at the factor, the identity R(f w; fy) = f R(w; fy / f) checked in tests/study; a System: the
  // record scaled, one run per (lane, factor)).
  void bisect(const Record& rec, const KernelSettings& ks, std::vector<std::uint8_t>& state, std::vector<double>& lo,
              std::vector<double>& hi, std::span<std::int32_t> analyses) {
    const std::size_t G = plan_.gaps;
    for (int step = 0; step < 200; ++step) {
      todo_.clear();
      for (std::size_t k = 0; k < state.size(); ++k)
        if (state[k] == found && !(hi[k] <= lo[k] * (1.0 + s_.intensity.tolerance))) todo_.push_back(k);
      if (todo_.empty()) break;
      mids_.resize(todo_.size());
      for (std::size_t j = 0; j < todo_.size(); ++j) {
        const std::size_t k = todo_[j];
        mids_[j] = LaneFactor{k / G, lo[k] > 0 ? std::sqrt(lo[k] * hi[k]) : 0.5 * hi[k]};
      }
      runner_->at_factors(mids_, rec, s_.free_vibration, ks, factor_peaks_);
      for (std::size_t j = 0; j < todo_.size(); ++j) {
        const std::size_t k = todo_[j], i = k / G, g = k % G;
        const double f = mids_[j].f;
        if (factor_peaks_.ran[j]) ++analyses[i];
        if (factor_peaks_.excluded[j]) state[k] = excluded;
        else if (factor_peaks_.closing[j] > s_.gap_at(g, pairs_[i])) hi[k] = f;
        else lo[k] = f;
      }
    }
  }

  // The unit's motion: the record with the study's free vibration; a bridge on several supports ([records]
  // supports): channel k is the realisation's support k + 1.
  UnitMotion motion(const StudyRecord& sr) {
    const Record& rec = sr.record;
    const GroundMotion gm{rec.dt, rec.acc, rec.duration() + s_.free_vibration};
    const int channels = s_.structures.bridge ? s_.structures.bridge->spec.channels() : 1;
    channels_.clear();
    for (int c = 0; c < channels && channels > 1; ++c)
      channels_.push_back(c == 0 ? gm
                                 : GroundMotion{rec.dt, sr.more_supports[static_cast<std::size_t>(c - 1)].acc,
                                                rec.duration() + s_.free_vibration});
    return UnitMotion{gm, channels_};
  }

  // The uncoupled runs give status, the buildings' largest floor displacements and D = the largest peak closing over
  // the study-gap contacts (system_block.hpp; the pair's peak closing), so the probability scene answers every gap
  // exactly; the per-floor rows and a row's buildings 3..n where the plan's schema has them.
  void probability(const UnitMotion& m, const KernelSettings& ks, UnitResult& out) {
    runner_->uncoupled(m, ks, peaks_);
    const bool table = !runner_->layout().empty();
    const std::size_t n = pairs_.size(), nb = peaks_.buildings;
    for (std::size_t i = 0; i < n; ++i) {
      put_uncoupled(out, i, peaks_.status[i], peaks_.u1[i], peaks_.u2[i], peaks_.closing[i]);
      if (table) put_table_uncoupled(out, i, peaks_);
      for (std::size_t b = 2; b < nb; ++b) out.values<double>(f_row_unc_[b])[i] = peaks_.u[i * nb + b];
    }
  }

  // A lane whose uncoupled peak closing stays <= g never touches at gap g, and its coupled run is bit-identical to
  // the uncoupled one (the first-passage property, tested): only the lanes that touch (D > gap) or failed are run
  // with contact (all with skip_untouched = false); the others take the uncoupled results.
  void impacts(std::size_t g, const UnitMotion& m, const KernelSettings& ks, UnitResult& out) {
    const std::size_t n = pairs_.size(), G = plan_.gaps, nb = peaks_.buildings;
    const bool table = !runner_->layout().empty();
    KernelSettings kc = ks;  // e(v0) at every study-gap impact ([contact] restitution)
    std::span<std::int32_t> outside;
    if (restitution_) kc.restitution = &restitution_->hook, outside = out.values<std::int32_t>(f_rest_out_);
    auto status = out.values<std::uint8_t>(field::imp_status);
    auto count = out.values<std::int32_t>(field::imp_count);
    auto force = out.values<double>(field::imp_peak_force), first = out.values<double>(field::imp_t_first);
    auto u1 = out.values<double>(field::imp_peak_u1), u2 = out.values<double>(field::imp_peak_u2);
    auto hw = out.values<double>(field::imp_h_omega);
    lanes_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const bool untouched = peaks_.status[i] == 0 && !(peaks_.closing[i] > s_.gap_at(g, pairs_[i]));
      if (!s_.skip_untouched || !untouched) lanes_.push_back(i);
    }
    runner_->coupled(lanes_, s_.gap_ratios[g], m, kc, coupled_);
    for (std::size_t i = 0, j = 0; i < n; ++i) {
      const std::size_t k = i * G + g;  // [lane][gap]
      if (j < lanes_.size() && lanes_[j] == i) {
        status[k] = coupled_.status[j], count[k] = coupled_.impact_count[j], force[k] = coupled_.peak_force[j];
        u1[k] = coupled_.u1[j], u2[k] = coupled_.u2[j], first[k] = coupled_.t_first_impact[j];
        hw[k] = coupled_.h_omega_contact[j];
        if (restitution_) outside[k] = coupled_.restitution_outside[j];
        if (f_substeps_ != npos) out.values<std::int32_t>(f_substeps_)[k] = coupled_.substeps[j];
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
  // Results format 3 (plan.system not empty): the fields of the per-floor and per-element rows, laid out as the
  // study's largest topology (the runner's layout, the plan's /system).
  void table_fields(const WorkPlan& plan) {
    const std::size_t nb = runner_->layout().floors.size();  // the table topology's buildings (its bodies)
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
  void put_table_uncoupled(UnitResult& out, std::size_t i, const RunPeaks& p, std::size_t stripe = 0) {
    const TableLayout& t = runner_->layout();
    for (std::size_t b = 0; b < t.floors.size(); ++b)
      for (auto [field, from] : {std::pair{f_floor_u_[b], &p.floor_u[b]}, {f_floor_drift_[b], &p.floor_drift[b]},
                                 {f_floor_acc_[b], &p.floor_acc[b]}}) {
        auto v = out.lane_values<double>(field, i, stripe);
        std::copy_n(from->begin() + static_cast<std::ptrdiff_t>(i * t.floors[b]), t.floors[b], v.begin());
      }
    auto c = out.lane_values<double>(f_e_closing_, i, stripe);
    std::copy_n(p.e_closing.begin() + static_cast<std::ptrdiff_t>(i * t.elements), t.elements, c.begin());
  }

  // lane i's per-element impacts at gap g: from coupled_ lane j, or (j = npos) untouched: no impacts at the study-gap
  // elements its topology has (those with an uncoupled closing), and a moat wall's of the uncoupled run (the walls act
  // there too, and the coupled run of an untouched lane is the uncoupled run; they held 0, issue 45 item 2)
  void put_table_coupled(UnitResult& out, std::size_t i, std::size_t g, std::size_t j) {
    const std::size_t E = runner_->layout().elements;
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
    const TableLayout& t = runner_->layout();
    const RunPeaks& p = j != std::string::npos ? coupled_ : peaks_;
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
  std::unique_ptr<Runner> runner_;  // the pair kernel or the system stepper (study/runner.hpp)
  std::vector<SampledPair> pairs_;
  std::vector<std::size_t> lanes_;
  std::unique_ptr<physics::HertzdampRestitution> restitution_;  // [contact] restitution: the kernel's e(v0) hook
  std::size_t f_rest_out_ = 0;
  RunPeaks peaks_, coupled_;  // the uncoupled run, a gap's coupled run
  RunPeaks anchor_, cur_, sub_peaks_;  // fragility studies: the anchor run, the peaks at a factor, a rerun
  // [analysis] coarse = "refine": impacts/substeps (npos: another policy; the runner's coupled() refines)
  static constexpr std::size_t npos = std::string::npos;
  std::size_t f_substeps_ = npos;
  std::vector<GroundMotion> channels_;  // a multi-support bridge's motions of the unit's record
  std::vector<std::size_t> f_floor_u_, f_floor_drift_, f_floor_acc_;
  std::vector<std::size_t> f_row_unc_, f_row_imp_;  // a row's buildings 3..n: uncoupled / impacts peak_u{b}
  std::size_t f_e_closing_ = 0, f_e_count_ = 0, f_e_force_ = 0, f_e_pen_ = 0, f_e_first_ = 0, f_e_hw_ = 0;
  std::size_t f_e_outside_ = 0;  // [contact] restitution: impacts/element_restitution_outside
  std::vector<std::size_t> f_imp_floor_u_, f_imp_floor_drift_, f_imp_floor_acc_;  // impacts/peak_u_floors{b}, ...
  std::vector<double> scaled_;
  std::vector<std::size_t> todo_;
  std::vector<LaneFactor> mids_;  // the IDA's bisection: one step's open brackets at their midpoints
  FactorPeaks factor_peaks_;
  enum : std::uint8_t { open, found, excluded };  // the IDA's (lane, gap) states
  std::size_t stripe_scaled_ = 0;
  std::size_t ida_analyses_ = 0, ida_limit_ = 0, ida_lo_ = 0, ida_hi_ = 0;  // the ida rows' positions in the plan's schema
};

void UnitComputerDelete::operator()(UnitComputer* c) const noexcept { delete c; }

UnitComputerPtr make_unit_computer(const Study& s, const std::vector<StudyRecord>& records, const StripePlan& stripes,
                                   const StructureSampler& sampler, const WorkPlan& plan, int rank,
                                   std::atomic<int>& computed, const std::atomic<bool>* stop) {
  return UnitComputerPtr(new UnitComputer(s, records, stripes, sampler, plan, rank, computed, stop));
}

UnitResult compute_unit(UnitComputer& computer, std::size_t unit) { return computer(unit); }

}  // namespace pounding::study_run
