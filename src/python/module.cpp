// The compiled core of the Python package `pounding` (pybind11, issue 28): pounding._core. The package's Python
// files (src/python/pounding/) wrap it with numpy/pandas conveniences; users import `pounding`, not `_core`.
// Arrays are SI (m, s, kg, N); ground acceleration in m/s^2 like the kernel, records carry both m/s^2 and g.
#include "common.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>

#include "pounding/core/error.hpp"
#include "pounding/core/progress.hpp"
#include "pounding/core/version.hpp"

namespace pounding::python {

std::string given(const py::handle& value) {
  try {
    const std::string type = py::str(py::type::of(value).attr("__name__")).cast<std::string>();
    if (py::hasattr(value, "shape") && py::hasattr(value, "dtype"))  // an array: its shape and type, never its values
      return fmt::format("a {} of shape {} ({})", type, py::str(value.attr("shape")).cast<std::string>(),
                         py::str(value.attr("dtype")).cast<std::string>());
    std::string repr = py::repr(value).cast<std::string>();
    if (repr.size() > 40) repr = repr.substr(0, 37) + "...";
    return fmt::format("{} {}", type, repr);
  } catch (const py::error_already_set&) {
    return "an object that cannot be shown";
  }
}

Array checked_array(const py::handle& values, const std::string& what) {
  Array a;
  try {
    a = Array::ensure(values);  // a null array (error cleared) where numpy cannot convert it
  } catch (const py::error_already_set&) {
    a = Array();
  }
  if (!a) throw py::value_error(fmt::format("{}: numbers are needed, got {}", what, given(values)));
  return a;
}

std::vector<double> to_vector(const py::handle& values, const std::string& what) {
  const Array a = checked_array(values, what);
  if (a.ndim() != 1) throw py::value_error(fmt::format("{}: a 1-D array of numbers is needed, got {}", what, given(values)));
  return {a.data(), a.data() + a.size()};
}

double to_number(const py::handle& value, const std::string& what) {
  if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value)) {
    try {
      const py::float_ x(py::reinterpret_borrow<py::object>(value));  // int, float, numpy scalars, a 0-D array
      return x.cast<double>();
    } catch (const py::error_already_set&) {
    }
  }
  throw py::value_error(fmt::format("{}: a number is needed, got {}", what, given(value)));
}

void check_threads(int threads) {
  if (threads < 0 || threads > 1024)
    throw InputError(fmt::format("threads = {} is outside [0, 1024]", threads), "threads",
                     "give the worker threads, 1 to 1024, or 0 for every core");
}

void check_duration(double duration) {
  if (!std::isfinite(duration) || duration < 0)
    throw InputError(fmt::format("duration = {} is outside [0, inf) s", duration), "duration",
                     "give the analysis length in s, or 0 for the record's own length");
}

void check_displacement_limit(double displacement_limit) {
  if (!std::isfinite(displacement_limit) || displacement_limit <= 0)
    throw InputError(fmt::format("displacement_limit = {} is outside (0, inf) m", displacement_limit),
                     "displacement_limit", "give |u1| + |u2| in m above which a run counts as diverged (default 10)");
}

namespace {

struct Workers {
  std::size_t batches;
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> stop{false};
  std::mutex mu;
  std::condition_variable cv;
  std::exception_ptr error;
  explicit Workers(std::size_t n) : batches(n) {}
  void loop(const std::function<void(std::size_t)>& work) {
    for (std::size_t b; !stop && (b = next++) < batches;) {
      try {
        work(b);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mu);
        if (!error) error = std::current_exception();
        stop = true;
      }
      ++done;
      cv.notify_all();
    }
  }
};

}  // namespace

void run_parallel(std::size_t batches, int threads, const std::function<void(std::size_t)>& work,
                  std::atomic<bool>* stop) {
  if (batches == 0) return;
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  Workers w(batches);
  bool interrupted = false;
  {
    py::gil_scoped_release unlocked;
    std::vector<std::thread> pool;
    const auto count = std::min<std::size_t>(static_cast<std::size_t>(threads), batches);
    for (std::size_t t = 0; t < count; ++t) pool.emplace_back([&] { w.loop(work); });
    std::unique_lock<std::mutex> lock(w.mu);
    while (w.done < batches && !(w.stop && w.error)) {
      w.cv.wait_for(lock, std::chrono::milliseconds(50));
      lock.unlock();
      {
        py::gil_scoped_acquire held;
        interrupted = PyErr_CheckSignals() != 0;  // the KeyboardInterrupt stays set
      }
      lock.lock();
      if (interrupted) {
        if (stop) stop->store(true);  // the running batches' steppers stop too (StopRequested, dropped below)
        break;
      }
    }
    w.stop = true;
    lock.unlock();
    for (auto& t : pool) t.join();
  }
  if (interrupted) throw py::error_already_set();
  if (w.error) std::rethrow_exception(w.error);
}

void run_interruptible(const std::function<void(const std::atomic<bool>& stop)>& work) {
  std::atomic<bool> stop{false};
  run_parallel(1, 1, [&](std::size_t) { work(stop); }, &stop);
}

}  // namespace pounding::python

PYBIND11_MODULE(_core, m) {
  using namespace pounding;
  namespace py = pybind11;
  m.doc() = "pounding._core: the compiled engine behind the Python package pounding (import pounding instead)";
  m.attr("__version__") = program_version;
  // Bad input is the CLI's InputError: ValueError with the same " <what>, <where>, <how to fix>" text. A stop
  // (Ctrl-C while an engine loop runs) ends as KeyboardInterrupt.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const Cancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    }
  });
  python::bind_kernel(m);
  python::bind_records(m);
  python::bind_analysis(m);
  python::bind_study(m);
  python::bind_systems(m);
}
