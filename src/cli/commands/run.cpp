// `pounding run STUDY.toml [--out RESULTS.h5] [--resume]` (alone or under mpirun) and
// `pounding report RESULTS.h5 [--md|--csv]`.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <memory>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/errors.hpp"
#include "pounding/core/error.hpp"
#include "pounding/parallel/executor.hpp"
#include "pounding/core/files.hpp"
#include "pounding/report/fragility.hpp"
#include "pounding/report/html.hpp"
#include "pounding/report/report.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/study/run.hpp"

namespace pounding::cli {

namespace {

// The process-wide stop flag: set by SIGINT/SIGTERM (and SIGUSR1/SIGUSR2, which mpirun forwards), read by the run
// between units and by the fit's loops (RunContext::hook).
// The first stop signal is kept: SIGTERM (what Slurm and other batch systems send at a time limit, and `scancel`)
// ends the run with its own exit code, 143, so a job script can tell "requeue and --resume" from a user's Ctrl-C (130).
std::atomic<bool> stop_requested{false};
std::atomic<int> stop_signal{0};
extern "C" void on_stop_signal(int sig) {
  int none = 0;
  stop_signal.compare_exchange_strong(none, sig);
  stop_requested.store(true);
}

// 130 (interrupted) becomes 143 when any rank was stopped by SIGTERM; every rank returns the same code. The ranks
// all reach this with 130 together (run_study agrees on it), so the collectives match.
int stop_code(const parallel::Session& session, int code) {
  if (code != 130) return code;
  std::vector<double> term{stop_signal.load() == SIGTERM ? 1.0 : 0.0};
  session.max_to_root(term);
  int out = term[0] > 0 ? 143 : 130;
  session.broadcast(out);
  return out;
}

std::string hms(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--:--";
  const long t = std::lround(s);
  return fmt::format("{}:{:02}:{:02}", t / 3600, (t / 60) % 60, t % 60);
}

// Progress on stderr: a bar on a terminal (4 updates a second), a line every 10 s otherwise.
class TerminalProgress {
 public:
  TerminalProgress() : tty_(isatty(fileno(stderr)) != 0) {}
  void operator()(const ProgressReport& p) {
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    units_ = p, units_at_ = now, in_units_ = !p.final;
    if (p.units_done == p.units_at_start && p.elapsed_s == 0 && !p.final) {  // the units start: the heartbeat's clock
      last_ = now;
      return;
    }
    if (!p.final && now - last_ < std::chrono::milliseconds(tty_ ? 250 : 10000)) return;
    print(p, now);
  }
  // Called every second by a clock thread: while units run but none finished for an interval (a long unit: a tall
  // building at a fine step), the last report again with the time elapsed, so a long unit is never silent.
  void heartbeat() {
    std::lock_guard lock(mutex_);
    const auto now = std::chrono::steady_clock::now();
    if (!in_units_ || now - last_ < std::chrono::milliseconds(tty_ ? 1000 : 10000)) return;
    ProgressReport p = units_;
    p.elapsed_s += std::chrono::duration<double>(now - units_at_).count();
    print(p, now);
  }

 private:
  void print(const ProgressReport& p, std::chrono::steady_clock::time_point now) {
    last_ = now;
    const double rate = static_cast<double>(p.units_done - p.units_at_start) * p.models_per_unit /
                        std::max(p.elapsed_s, 1e-9);
    const double frac = static_cast<double>(p.units_done) / static_cast<double>(p.units_total);
    const double eta = static_cast<double>(p.units_total - p.units_done) * p.models_per_unit / std::max(rate, 1e-9);
    // no unit finished yet (a long first unit): no rate, no estimate
    const std::string eta_text = p.units_done == p.units_at_start ? std::string("after the first unit") : hms(eta);
    if (tty_) {
      const int w = 30, fill = static_cast<int>(frac * w);
      fmt::print(stderr, "\r[{}{}] {:5.1f}%  units {}/{}  {:.0f} models/s  ETA {}{}", std::string(fill, '#'),
                 std::string(w - fill, '.'), 100 * frac, p.units_done, p.units_total, rate, eta_text,
                 p.final ? "\n" : "");
    } else {
      fmt::print(stderr, "progress: units {}/{} ({:.1f}%), {:.0f} models/s, elapsed {}, ETA {}\n", p.units_done,
                 p.units_total, 100 * frac, rate, hms(p.elapsed_s), eta_text);
    }
  }

 public:
  // The phases after the units (the fit's bootstrap and jackknife, core/progress.hpp): the same bar or lines, the
  // first report of each phase at once.
  void operator()(const PhaseProgress& p) {
    std::lock_guard lock(mutex_);
    in_units_ = false;
    const auto now = std::chrono::steady_clock::now();
    const bool fresh = p.phase != phase_;
    if (!fresh && !p.final && now - last_ < std::chrono::milliseconds(tty_ ? 250 : 10000)) return;
    if (fresh && tty_ && !phase_.empty() && !phase_done_) fmt::print(stderr, "\n");
    phase_ = p.phase, last_ = now, phase_done_ = p.final;
    const double frac = p.total ? static_cast<double>(p.done) / static_cast<double>(p.total) : 1.0;
    const double eta = p.done ? p.elapsed_s * static_cast<double>(p.total - p.done) / static_cast<double>(p.done) : NAN;
    if (tty_) {
      const int w = 30, fill = static_cast<int>(frac * w);
      fmt::print(stderr, "\r{}: [{}{}] {:5.1f}%  {}/{} {}  ETA {}{}", p.phase, std::string(fill, '#'),
                 std::string(w - fill, '.'), 100 * frac, p.done, p.total, p.unit, hms(eta), p.final ? "\n" : "");
    } else {
      fmt::print(stderr, "progress: {} {}/{} {} ({:.1f}%), elapsed {}, ETA {}\n", p.phase, p.done, p.total, p.unit,
                 100 * frac, hms(p.elapsed_s), hms(eta));
    }
  }

 private:
  bool tty_;
  std::chrono::steady_clock::time_point last_{};
  std::string phase_;
  bool phase_done_ = false;
  std::mutex mutex_;  // the clock thread's heartbeat and the run's own reports
  ProgressReport units_{};
  std::chrono::steady_clock::time_point units_at_{};
  bool in_units_ = false;
};

// The clock of TerminalProgress::heartbeat: a thread that wakes every second until destroyed.
class ProgressClock {
 public:
  explicit ProgressClock(std::shared_ptr<TerminalProgress> bar)
      : thread_([this, bar = std::move(bar)] {
          std::unique_lock lock(mutex_);
          while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; })) bar->heartbeat();
        }) {}
  ~ProgressClock() {
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    cv_.notify_one();
    thread_.join();
  }
  ProgressClock(const ProgressClock&) = delete;
  ProgressClock& operator=(const ProgressClock&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool done_ = false;
  std::thread thread_;  // last: started once the members it uses exist
};

struct RunOpts {
  std::string study, out;
  bool resume = false, force = false, quiet = false, out_given = false, timings = false;
  int threads = -1;  // --threads (-1: the study's [analysis] threads)
};

// The run's phases (core/timing.hpp) in one line, and with --timings as a table (rank 0 and the largest over ranks).
void print_timings(const timing::Times& T, int ranks, bool table) {
  using timing::Phase;
  const auto at = [&](Phase p) { return T[p]; };
  fmt::print(stderr,
             "timing: wall {:.2f} s from program start to results written and report printed = MPI start {:.2f} + inputs "
             "{:.2f} + structures {:.2f} + units {:.2f} (compute {:.2f}, largest rank {:.2f}; reduce {:.2f}; checkpoint "
             "{:.2f}) + analysis {:.2f} + report {:.2f} (bootstrap {:.2f}) + results write {:.2f} s; rank 0 of {}\n",
             T.wall, at(Phase::mpi_start), at(Phase::inputs), at(Phase::structures), at(Phase::units), at(Phase::compute),
             T.max[static_cast<std::size_t>(Phase::compute)], at(Phase::reduce), at(Phase::checkpoint),
             at(Phase::analysis), at(Phase::report), at(Phase::bootstrap), at(Phase::results_write), ranks);
  if (!table) return;
  fmt::print(stderr, "\n| phase | rank 0 s | max over ranks s | what it covers |\n|---|---|---|---|\n");
  for (std::size_t i = 0; i < timing::phase_count; ++i)
    fmt::print(stderr, "| {} | {:.3f} | {:.3f} | {} |\n", timing::phase_names[i], T.rank0[i], T.max[i],
               timing::phase_meanings[i]);
  fmt::print(stderr, "| wall | {:.3f} | | program start to results written and report printed |\n", T.wall);
}

// The HTML report of a results file (report/html.hpp), written atomically; one line on stderr says where and what
// was left out.
void write_html_report(const std::string& results_path, const std::string& html_path) {
  const results::Results r = results::load(results_path);
  const FigureOptions fo = default_figure_options();
  const std::string html = report_html(r, fo);
  files::write_text_atomically(html_path, html);
  fmt::print(stderr, "HTML report: {}\n", html_path);
}

// One study of a run on this rank, in the open session; returns its exit code.
int run_one(const parallel::Session& session, const RunOpts& o, double mpi_start_s, const StudyDone& done,
            std::size_t index) {
  RunOptions ro;
  ro.out = o.out;
  ro.out_given = o.out_given;
  ro.resume = o.resume;
  ro.force = o.force;
  ro.threads = o.threads;
  // a fragility study's /fragility and /hazard (nothing for other studies)
  ro.analyse = [](results::Results& r, const WorkHook& hook) { analyse_fragility(r, &hook); };
  // the report, rendered before the results are written so that its time is in them (a stop there: exit 130)
  ro.report = [](const results::Results& r, const WorkHook& hook, double& bootstrap_s) {
    return report_markdown(r, &hook, &bootstrap_s);
  };
  ro.mpi_start_s = mpi_start_s;
  ro.start = std::chrono::steady_clock::now();
  if (index == 0) ro.start = timing::program_start();
  RunContext ctx;
  ctx.cancel = &stop_requested;
  std::unique_ptr<ProgressClock> clock;
  if (session.root()) {
    ctx.info = [](const std::string& line) { fmt::print(stderr, "{}\n", line); };
    if (!o.quiet) {
      auto bar = std::make_shared<TerminalProgress>();
      ctx.progress = [bar](const ProgressReport& p) { (*bar)(p); };
      ctx.phase_progress = [bar](const PhaseProgress& p) { (*bar)(p); };
      clock = std::make_unique<ProgressClock>(bar);
    }
  }
  RunOutcome r = run_study(session, o.study, ro, ctx);
  clock.reset();
  r.code = stop_code(session, r.code);
  if (session.root() && r.code == 143)
    fmt::print(stderr, "stopped by SIGTERM (a batch system's time limit or scancel): exit 143; the checkpoint keeps "
                       "every finished unit, rerun the same command with --resume (docs/cluster.md)\n");
  if (session.root() && (r.code == 0 || r.code == 3)) {
    if (done) {
      done(index, r);
    } else {
      fmt::print("{}", r.report);
      std::fflush(stdout);
    }
    if (!r.html.empty()) write_html_report(r.out, r.html);
    r.times.wall = timing::seconds_since(ro.start);
    print_timings(r.times, session.size(), o.timings);
  }
  return r.code;
}

// The studies of `jobs` one after another in one MPI session on this rank; returns the first non-zero exit code
// (a stop ends the list), 0 when every study is done (the session has ended when it returns).
int run_jobs(const std::vector<RunOpts>& jobs, const StudyDone& done) {
  // POUNDING_MPI_TRANSPORTS (parallel/mpi_executor.cpp, docs/cluster.md): "all" or unset; anything else is a typo that
  // would silently be the default. Refused on every rank before MPI starts, said once (rank 0, or no launcher).
  if (const char* t = std::getenv("POUNDING_MPI_TRANSPORTS"); t && *t && std::string_view(t) != "all") {
    const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!rank) rank = std::getenv("PMI_RANK");
    if (!rank || std::string_view(rank) == "0")
      fmt::print(stderr, " ERROR: POUNDING_MPI_TRANSPORTS={} is not a choice, the environment, unset it (on one node "
                         "pounding leaves out Open MPI's network layers) or set it to all (Open MPI's own choice; "
                         "docs/cluster.md)\n", t);
    return 2;
  }
  int argc = 0;
  char** argv = nullptr;
  const auto t_mpi = std::chrono::steady_clock::now();
  parallel::Session session(argc, argv);
  const double mpi_start_s = timing::seconds_since(t_mpi);
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  // Open MPI's mpirun forwards SIGUSR1/SIGUSR2 to every rank; signalled with SIGINT/SIGTERM itself it stops the ranks
  // but exits 1 whatever they return (orterun's abort path). `kill -USR1 <mpirun>` is the stop that keeps 130.
  std::signal(SIGUSR1, on_stop_signal);
  std::signal(SIGUSR2, on_stop_signal);
  try {
    int code = 0;
    for (std::size_t i = 0; i < jobs.size() && (code == 0 || code == 3); ++i) {
      const int c = run_one(session, jobs[i], mpi_start_s, done, i);
      if (c != 0 && (code == 0 || c != 3)) code = c;
    }
    return code;
  } catch (const InputError& e) {
    // thrown on every rank after the job stopped together (Session::agree, run_units): one message
    if (session.root()) fmt::print(stderr, " ERROR: {}\n", e.what());
    return 2;
  } catch (...) {
    // outside the agreed phases: this rank alone knows; end the job rather than let the others wait. Out of memory
    // and other unexpected errors in the wording of every error (cli/errors.hpp).
    const InputError e = describe_failure(std::current_exception(), jobs.size() == 1 ? "pounding run" : "pounding inventory run");
    fmt::print(stderr, " ERROR: {}, {} (rank {}), {}\n", e.what_part(), e.where(), session.rank(), e.fix());
    if (session.size() > 1) session.abort(2);
    return 2;
  }
}

}  // namespace

int run_study_files(const std::vector<StudyJob>& jobs, const StudyRunFlags& flags, const StudyDone& done) {
  std::vector<RunOpts> list;
  for (const StudyJob& j : jobs) {
    RunOpts o;
    o.study = j.study, o.out = j.out, o.out_given = !j.out.empty();
    o.resume = flags.resume, o.force = flags.force, o.quiet = flags.quiet, o.timings = flags.timings;
    o.threads = flags.threads;
    list.push_back(o);
  }
  return run_jobs(list, done);
}

void add_run(CLI::App& app) {
  auto o = std::make_shared<RunOpts>();
  auto* c = app.add_subcommand("run", "run a study (Monte Carlo over records x period pairs x samples); "
                                      "under mpirun the ranks share the work");
  c->add_option("study", o->study, "study file (studies/*.toml; every key: docs/study-reference.md or "
                                   "`pounding study-reference`)")->required();
  auto* out = c->add_option("--out", o->out, "results file (default: the study's output)");
  c->add_flag("--resume", o->resume, "continue a killed, interrupted or failed run from its checkpoint (<out>.ckpt)");
  c->add_flag("--force", o->force, "discard the progress in <out>.ckpt and start afresh");
  c->add_flag("--quiet", o->quiet, "no progress display");
  c->add_flag("--timings", o->timings, "print the table of phases (rank 0 and the largest over the ranks) after the run");
  auto* threads = c->add_option("--threads", o->threads,
                                 "worker threads per rank (default: the study's [analysis] threads; 0: the CPUs of the "
                                 "affinity mask on one rank, 1 per rank under mpirun with several ranks); results do "
                                 "not depend on it");
  c->callback([o, out, threads] {
    if (threads->count() > 0 && (o->threads < 0 || o->threads > 1024))
      throw InputError(fmt::format("--threads {} is outside [0, 1024]", o->threads), "--threads",
                       "give the worker threads per rank, 1 to 1024, or 0 for the CPUs this process may use");
    // A write beyond the file-size limit (ulimit -f) must be an EFBIG error we report, not SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    o->out_given = out->count() > 0;
    if (const int code = run_jobs({*o}, nullptr)) throw ExitRequest{code};
  });
}

void add_report(CLI::App& app) {
  struct Opts {
    std::vector<std::string> paths;
    std::string html;
    bool md = false, csv = false, no_figures = false;
  };
  auto o = std::make_shared<Opts>();
  auto* c = app.add_subcommand("report", "tables, cubic fit, separation advice and code rules from a results file; "
                                         "--html: one self-contained HTML report (two files: side by side)");
  c->add_option("results", o->paths, "results file written by `pounding run` (with --html: one, or two or more to "
                                     "compare side by side)")->required();
  auto* md = c->add_flag("--md", o->md, "Markdown (default)");
  auto* csv = c->add_flag("--csv", o->csv, "CSV: per-record, total, per-period-pair tables and the continuous curve")->excludes(md);
  auto* html = c->add_option("--html", o->html, "write the HTML report to this file (answer, figures, every table, "
                                                "provenance; inline CSS and SVG, nothing loaded from elsewhere)");
  html->excludes(md)->excludes(csv);
  c->add_flag("--no-figures", o->no_figures, "with --html: leave the figures out (no Python run)")->needs(html);
  c->callback([o] {
    if (o->html.empty() && o->paths.size() > 1)
      throw InputError(fmt::format("{} results files given", o->paths.size()), "pounding report",
                       "give one results file, or add --html OUT.html to compare two side by side");
    if (!o->html.empty()) {
      files::check_output_not_input(o->html, o->paths, "--html");  // before any work: never over a results file
      files::check_output_path(o->html, "--html");
      std::vector<results::Results> all;
      for (const auto& p : o->paths) all.push_back(results::load(p));
      FigureOptions fo = default_figure_options();
      fo.enabled = !o->no_figures;
      std::vector<const results::Results*> ptrs;
      for (const auto& r : all) ptrs.push_back(&r);
      const std::string text = ptrs.size() == 1 ? report_html(*ptrs[0], fo) : compare_html(ptrs, fo);
      files::write_text_atomically(o->html, text);
      return;
    }
    const results::Results r = results::load(o->paths.front(), {}, results::LoadExtent::report);
    fmt::print("{}", o->csv ? report_csv(r) : report_markdown(r));
  });
}

}  // namespace pounding::cli
