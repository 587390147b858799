// Studies in-process: run_study on one rank (no mpirun: parallel::Session never initialises MPI then), with the
// CLI's analysis (the fragility fit) and report, progress through a Python callable and Ctrl-C as the CLI's stop
// flag; and the report of a results file, as `pounding report` renders it.
#include <atomic>
#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "common.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/run_context.hpp"
#include "pounding/parallel/executor.hpp"
#include "pounding/report/fragility.hpp"
#include "pounding/report/report.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/study/run.hpp"

namespace pounding::python {
namespace {

// Called from the engine with the GIL released: take it, report, and turn a pending Ctrl-C into the stop flag
// (the run then ends with 130 and keeps its checkpoint, as the CLI's). A KeyboardInterrupt raised inside the user's
// callback is the same stop; any other exception in it stops the run and is raised again after it.
struct Progress {
  py::object callback;
  std::atomic<bool>* stop;
  bool* interrupted;
  std::string* failure;
  void poll() const {
    py::gil_scoped_acquire held;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();
      *interrupted = true;
      stop->store(true);
    }
  }
  template <class... A>
  void call(const py::object& f, A&&... args) const {
    py::gil_scoped_acquire held;
    try {
      f(std::forward<A>(args)...);
    } catch (py::error_already_set& e) {
      if (e.matches(PyExc_KeyboardInterrupt)) *interrupted = true;
      else if (failure->empty()) *failure = e.what();
      stop->store(true);
    }
  }
  void units(const ProgressReport& p) const {
    poll();
    const bool start = p.units_done == p.units_at_start && p.elapsed_s == 0 && !p.final;  // the units start
    if (!callback.is_none() && !start) call(callback, "units", p.units_done, p.units_total, p.elapsed_s, p.final);
  }
  void phase(const PhaseProgress& p) const {
    poll();
    if (!callback.is_none()) call(callback, p.phase, p.done, p.total, p.elapsed_s, p.final);
  }
};

py::dict run_study_py(const std::string& path, const std::optional<std::string>& out, bool resume, bool force,
                      const py::object& progress, const py::object& info, int threads) {
  if (threads < -1 || threads > 1024)
    throw InputError(fmt::format("threads = {} is outside [0, 1024]", threads), "Study.run(threads=)",
                     "give the worker threads, 1 to 1024, 0 for the CPUs this process may use, or None for the "
                     "study's [analysis] threads");
  std::atomic<bool> stop{false};
  bool interrupted = false;
  std::string failure;
  RunOptions ro;
  ro.start = std::chrono::steady_clock::now();  // this call's wall time (the process started long before, or not yet)
  ro.out = out.value_or(""), ro.out_given = out.has_value(), ro.resume = resume, ro.force = force;
  ro.threads = threads;  // -1: the study's [analysis] threads
  ro.analyse = [](results::Results& r, const WorkHook& hook) { analyse_fragility(r, &hook); };
  ro.report = [](const results::Results& r, const WorkHook& hook, double& bootstrap_s) {
    return report_markdown(r, &hook, &bootstrap_s);
  };
  const Progress p{progress, &stop, &interrupted, &failure};
  RunContext ctx;
  ctx.cancel = &stop;
  ctx.progress = [&p](const ProgressReport& r) { p.units(r); };
  ctx.phase_progress = [&p](const PhaseProgress& r) { p.phase(r); };
  ctx.info = [&p, &info](const std::string& line) {
    if (!info.is_none()) p.call(info, line);
  };
  RunOutcome r;
  {
    py::gil_scoped_release unlocked;
    int argc = 0;
    char** argv = nullptr;
    parallel::Session session(argc, argv);
    r = run_study(session, path, ro, ctx);
  }
  if (!failure.empty()) throw std::runtime_error("the progress or info callback failed, the run stopped: " + failure);
  if (interrupted || r.code == 130) {
    PyErr_SetString(PyExc_KeyboardInterrupt,
                     "study interrupted: the checkpoint keeps every finished unit, run again with resume=True");
    throw py::error_already_set();
  }
  py::dict d;
  d["code"] = r.code, d["out"] = r.out, d["report"] = r.report, d["wall_s"] = r.times.wall;
  return d;
}

std::string report_py(const std::string& path, bool csv) {
  py::gil_scoped_release unlocked;
  const results::Results r = results::load(path);
  return csv ? report_csv(r) : report_markdown(r);
}

}  // namespace

void bind_study(py::module_& m) {
  m.def("run_study", &run_study_py, py::arg("path"), py::arg("out"), py::arg("resume"), py::arg("force"),
        py::arg("progress"), py::arg("info"), py::arg("threads") = -1,
        "run a study file on this process (use pounding.Study); threads -1: the study's [analysis] threads");
  m.def("report", &report_py, py::arg("path"), py::arg("csv") = false,
        "the report of a results file, Markdown or CSV, as `pounding report` prints it");
}

}  // namespace pounding::python
