// [analysis] coarse = "refine": the coarse lanes of a coupled run, rerun alone until resolved (study/refine.hpp).
#include "pounding/study/refine.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "pounding/config/study_keys.hpp"
#include "pounding/physics/batch.hpp"

namespace pounding {

int refine_max_substeps(double record_dt, double duration) {
  const double key_hi = config::study_key("analysis", "substeps").hi;
  const double record_steps = std::max(1.0, std::ceil(duration / record_dt - 1e-9));
  return static_cast<int>(std::clamp(std::floor(refine_max_steps / record_steps), 1.0, key_hi));
}

void set_lane(BatchResult& to, std::size_t j, const BatchResult& from, std::size_t k) {
  using D = std::vector<double> BatchResult::*;
  for (D v : {&BatchResult::peak_u1, &BatchResult::peak_u2, &BatchResult::peak_closing, &BatchResult::t_peak_closing,
              &BatchResult::t_first_impact, &BatchResult::peak_force, &BatchResult::peak_penetration,
              &BatchResult::contact_energy, &BatchResult::contact_time, &BatchResult::peak_acc1, &BatchResult::peak_acc2,
              &BatchResult::final_u1, &BatchResult::final_v1, &BatchResult::final_u2, &BatchResult::final_v2,
              &BatchResult::e_input, &BatchResult::e_kinetic, &BatchResult::e_strain, &BatchResult::e_viscous,
              &BatchResult::e_hysteretic, &BatchResult::e_contact_stored, &BatchResult::h_omega_contact})
    (to.*v)[j] = (from.*v)[k];
  using I = std::vector<std::int32_t> BatchResult::*;
  for (I v : {&BatchResult::impact_count, &BatchResult::clamp_count, &BatchResult::restitution_outside})
    (to.*v)[j] = (from.*v)[k];
  to.status[j] = from.status[k];
}

std::size_t refine_coarse(std::span<const std::uint8_t> status, int substeps, double record_dt, int max_substeps,
                          const LaneWorst& worst, const LaneRerun& rerun, std::span<std::int32_t> used) {
  std::size_t rerun_lanes = 0;
  for (std::size_t j = 0; j < status.size(); ++j) {
    used[j] = substeps;
    if (status[j] != static_cast<std::uint8_t>(LaneStatus::coarse) || max_substeps <= substeps) continue;
    const physics::StepChoice c =
        physics::choose_step(false, substeps, record_dt, physics::no_limit, max_substeps, [&](int n) {
          return n == substeps ? worst(j) : rerun(j, n);
        });
    used[j] = c.substeps;
    ++rerun_lanes;
  }
  return rerun_lanes;
}

void refine_pairs(const PairBatch& batch, const ContactModel& cm, const GroundMotion& gm, const KernelSettings& ks,
                  BatchResult& res, RefineScratch& one, std::span<std::int32_t> used) {
  const auto worst = [&](std::size_t j) { return physics::lane_resolution(res, j, ks, cm.law); };
  const auto rerun = [&](std::size_t j, int n) {
    one.pair.resize(1), one.pair.set(0, batch.get(j));
    KernelSettings k1 = ks;
    k1.substeps = n;
    run_batch(one.pair, cm, gm, k1, one.pair_result);
    set_lane(res, j, one.pair_result, 0);
    return physics::lane_resolution(one.pair_result, 0, k1, cm.law);
  };
  refine_coarse(res.status, ks.substeps, gm.dt, refine_max_substeps(gm.dt, gm.total_duration()), worst, rerun, used);
}

void refine_systems(SystemBlock& block, std::span<const SampledPair> pairs, std::span<const std::size_t> lanes,
                    double ratio, const ContactModel& cm, const ContactNumbers& cn, const GroundMotion& gm,
                    const KernelSettings& ks, RunPeaks& out, RefineScratch& one, std::span<std::int32_t> used) {
  const auto worst = [&](std::size_t j) { return out.worst[j]; };
  const auto rerun = [&](std::size_t j, int n) {
    one.lane.assign(1, lanes[j]);
    KernelSettings k1 = ks;
    k1.substeps = n;
    block.coupled(pairs, one.lane, ratio, cm, cn, gm, k1, one.peaks);
    out.set_lane(j, one.peaks, 0);
    return one.peaks.worst[0];
  };
  refine_coarse(out.status, ks.substeps, gm.dt, refine_max_substeps(gm.dt, gm.total_duration()), worst, rerun, used);
}

}  // namespace pounding
