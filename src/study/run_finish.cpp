// The run's finish phase: the results file written beside the report, /timing, histories, the checkpoint removed.
#include "run_phases.hpp"

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

namespace pounding::study_run {

namespace {

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

}  // namespace

// The run is complete: the workers' slices and the main file go (rank 0; the workers still hold their slices open).
void remove_checkpoint(Checkpoint& main) {
  for (const std::string& path : slice_paths(main.path())) ::unlink(path.c_str());
  main.remove();
}

namespace {

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

}  // namespace

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

}  // namespace pounding::study_run
