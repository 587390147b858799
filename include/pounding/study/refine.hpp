#pragma once
// [analysis] coarse = "refine" (issue 45 item 1): a coupled analysis the resolution guard marks coarse
// (physics/resolution.hpp) is run again, alone, at a shorter step -- the rule of `pounding simulate` without --dt
// (physics::choose_step: ceil(n h omega_c / (0.8 limit)) substeps, a diverged run 4 n, at most physics::step_max_runs
// runs in all, the batch's run being the first) -- until it is resolved. The last run is its result: still coarse or
// diverged at the cap, it is excluded as with "exclude". Analyses that were not coarse keep their bits.
//
// One function for every runner that runs coupled analyses (the SDOF pair kernel's and SystemBlock's: coupled() of
// src/study/pair_runner.cpp and src/study/system_runner.cpp): the runner says how to read a lane of its batch run and
// how to run one lane alone. A lane's rerun depends on nothing but that lane (run alone, one lane wide), so the
// results do not depend on the batch width, the threads or the ranks.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "pounding/physics/resolution.hpp"
#include "pounding/study/system_block.hpp"

namespace pounding {

// The most substeps a refined analysis may take: the [analysis] substeps key's range (10,000), and at most
// refine_max_steps integration steps over the analysed duration (the time loop's schedule holds one ground
// acceleration per step: 2^24 steps are 128 MiB).
inline constexpr double refine_max_steps = 16777216.0;
int refine_max_substeps(double record_dt, double duration);

// How one lane of a coupled batch run at `substeps` did; lane j of the batch.
using LaneWorst = std::function<physics::StepResolution(std::size_t j)>;
// Runs lane j alone at `substeps`, puts its peaks in lane j of the batch run's output and returns its worst element.
using LaneRerun = std::function<physics::StepResolution(std::size_t j, int substeps)>;

// Every lane j < status.size() whose status is coarse: physics::choose_step from `substeps` (its first run: the
// batch's, worst(j)) with rerun(j, n) for the later ones, up to `max_substeps`. used[j]: the substeps of lane j's
// final run (`substeps` for a lane not rerun). Returns the lanes rerun.
std::size_t refine_coarse(std::span<const std::uint8_t> status, int substeps, double record_dt, int max_substeps,
                          const LaneWorst& worst, const LaneRerun& rerun, std::span<std::int32_t> used);

// Lane j of `to` = lane k of `from` (the pair kernel's result of a lane's rerun, one lane wide): every value.
void set_lane(BatchResult& to, std::size_t j, const BatchResult& from, std::size_t k);

// The two coupled paths' reruns (the runner's coupled(), docs/runner-design.md section 2): `used` sized as the batch.
struct RefineScratch {  // one lane's rerun
  PairBatch pair;
  BatchResult pair_result;
  RunPeaks peaks;
  std::vector<std::size_t> lane;
};
// The pair kernel's coupled run of `batch` (law cm) into `res`: its coarse lanes, each from its own PairParams.
void refine_pairs(const PairBatch& batch, const ContactModel& cm, const GroundMotion& gm, const KernelSettings& ks,
                  BatchResult& res, RefineScratch& one, std::span<std::int32_t> used);
// SystemBlock::coupled of `lanes` of `pairs` at gap ratio `ratio` into `out`: its coarse lanes, each through
// SystemBlock::coupled on that lane alone.
void refine_systems(SystemBlock& block, std::span<const SampledPair> pairs, std::span<const std::size_t> lanes,
                    double ratio, const ContactModel& cm, const ContactNumbers& cn, const GroundMotion& gm,
                    const KernelSettings& ks, RunPeaks& out, RefineScratch& one, std::span<std::int32_t> used);

}  // namespace pounding
