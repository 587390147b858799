// `pounding run STUDY.toml [--out RESULTS.h5] [--resume]` (alone or under mpirun) and
// `pounding report RESULTS.h5 [--md|--csv]`.
#include <csignal>
#include <memory>

#include <fmt/format.h>

#include "pounding/cli.hpp"
#include "pounding/error.hpp"
#include "pounding/parallel.hpp"
#include "pounding/report.hpp"
#include "pounding/study_run.hpp"

namespace pounding::cli {

void add_run(CLI::App& app) {
  struct Opts {
    std::string study, out;
    bool resume = false, force = false, quiet = false;
  };
  auto o = std::make_shared<Opts>();
  auto* c = app.add_subcommand("run", "run a study (Monte Carlo over records x period pairs x samples); "
                                      "under mpirun the ranks share the work");
  c->add_option("study", o->study, "study file (studies/*.toml)")->required();
  auto* out = c->add_option("--out", o->out, "results file (default: the study's output)");
  c->add_flag("--resume", o->resume, "continue a killed, interrupted or failed run from its checkpoint (<out>.ckpt)");
  c->add_flag("--force", o->force, "discard the progress in <out>.ckpt and start afresh");
  c->add_flag("--quiet", o->quiet, "no progress display");
  c->callback([o, out] {
    // A write beyond the file-size limit (ulimit -f) must be an EFBIG error we report, not SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    int argc = 0;
    char** argv = nullptr;
    parallel::Session session(argc, argv);
    try {
      RunOptions ro;
      ro.out = o->out;
      ro.out_given = out->count() > 0;
      ro.resume = o->resume;
      ro.force = o->force;
      ro.progress = !o->quiet;
      exit_code() = run_study(session, o->study, ro);
    } catch (const InputError& e) {
      // thrown on every rank after the job stopped together (Session::agree, run_units): one message
      if (session.root()) fmt::print(stderr, " ERROR: {}\n", e.what());
      exit_code() = 2;
    } catch (const std::exception& e) {
      // outside the agreed phases: this rank alone knows; end the job rather than let the others wait
      fmt::print(stderr, " ERROR: {} (rank {})\n", e.what(), session.rank());
      if (session.size() > 1) session.abort(2);
      exit_code() = 2;
    }
  });
}

void add_report(CLI::App& app) {
  struct Opts {
    std::string path;
    bool md = false, csv = false;
  };
  auto o = std::make_shared<Opts>();
  auto* c = app.add_subcommand("report", "tables, cubic fit, separation advice and code rules from a results file");
  c->add_option("results", o->path, "results file written by `pounding run`")->required();
  auto* md = c->add_flag("--md", o->md, "Markdown (default)");
  c->add_flag("--csv", o->csv, "CSV: per-record, total, per-period-pair tables and the continuous curve")->excludes(md);
  c->callback([o] {
    Results r = load_results(o->path);
    fmt::print("{}", o->csv ? report_csv(r) : report_markdown(r));
  });
}

}  // namespace pounding::cli
