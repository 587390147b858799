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
#include "run_phases.hpp"
#include "unit_computer.hpp"

namespace pounding {

namespace study_run {

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

}  // namespace study_run

using namespace study_run;  // the phases (run_phases.hpp) and the unit computer (unit_computer.hpp)

namespace fs = std::filesystem;

namespace {

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

// Rank 0's measures of the units and the assembly (the master service line; assemble_s adds to T[reduce]): one per run.
struct RunStats {
  double final_sync_s = 0;  // the units phase's closing fsync of the checkpoint (rank 0)
  parallel::MasterStats master_stats;  // rank 0's serving of the workers' units
  double assemble_s = 0;    // rank 0's reading of the workers' slices after the units
};

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
             timing::Times& T, int threads, RunStats& stats) {
  const auto t_setup = std::chrono::steady_clock::now();
  const StructureSampler sampler(in.study.structures, in.study.seed);
  std::atomic<int> computed{0};
  std::vector<UnitComputerPtr> computers;
  for (int t = 0; t < threads; ++t)
    computers.push_back(make_unit_computer(in.study, in.records, in.stripes, sampler, L, session.rank(), computed,
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
        if (!stored) return compute_unit(compute, u).serialise();
        const std::size_t n = L.lanes(L.decode(u).block);
        {
          std::lock_guard lock(kept_mutex);
          if (auto at = kept.find(n); at != kept.end()) return at->second;
        }
        parallel::Payload p = compute_unit(compute, u).serialise();
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
      tick, ctx.cancel ? *ctx.cancel : never, &stats.master_stats);
  for (double s : compute_s) T[Phase::compute] += s;
  double final_sync = 0;
  {
    Stopwatch w(final_sync);
    sync_checkpoint(*ckpt, tally);  // every rank: its units are on disk before rank 0 reads the slices (or the run stops)
  }
  T[Phase::checkpoint] += final_sync;
  stats.final_sync_s = final_sync;
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
              const CheckpointKey& key, timing::Times& T, RunStats& stats) {
  if (session.size() == 1) return;
  session.barrier();
  if (!L.per_model || L.stream) {  // every rank folded its own units into its Reductions
    timing::Stopwatch w(stats.assemble_s);
    merge_reductions(session, tally);
  }
  session.agree([&] {
    if (!session.root()) return;
    timing::Stopwatch w(stats.assemble_s);
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
  T[timing::Phase::reduce] += stats.assemble_s;
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
  RunStats stats;  // the master service line's measures (POUNDING_MASTER_SERVICE)
  try {
    complete = execute(session, in, L, todo, ckpt ? &*ckpt : nullptr, tally, remote, ctx, wall, T, threads, stats);
  } catch (...) {
    save_after_error(ckpt ? &*ckpt : nullptr, tally);
    throw;
  }
  if (complete) assemble(session, in, L, tally, key, T, stats);
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
      const double served = wall - stats.final_sync_s;
      ctx.say(fmt::format("master service (test-only POUNDING_MASTER_SERVICE, stored unit results, no results "
                          "written): {} units in {:.4f} s on {} ranks (+ {:.4f} s closing fsync) = {:.2f} us per unit "
                          "({:.0f} units/s), {} bytes per full unit; of it checkpoint appends {:.2f} us, reduce {:.2f} "
                          "us per unit; {} bytes per unit to the master ({} of {} units stored on rank 0); the master's "
                          "time per worker unit {:.2f} us ({} units: receive the id, send the next unit); assembly "
                          "from the slices after the units {:.4f} s = {:.2f} us per worker unit",
                          todo.size(), served, session.size(), stats.final_sync_s, 1e6 * served / units, units / served,
                          bytes, 1e6 * (T[timing::Phase::checkpoint] - stats.final_sync_s) / units,
                          1e6 * (T[timing::Phase::reduce] - stats.assemble_s) / units, session.size() > 1 ? 8 : 0,
                          todo.size() - remote, todo.size(),
                          stats.master_stats.worker_units
                              ? 1e6 * stats.master_stats.service_s / stats.master_stats.worker_units
                              : 0.0,
                          stats.master_stats.worker_units, stats.assemble_s,
                          remote ? 1e6 * stats.assemble_s / static_cast<double>(remote) : 0.0));
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
