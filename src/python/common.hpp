#pragma once
// Shared helpers of the Python module's binding files (src/python/*.cpp): numpy conversions and the bind_*
// functions PYBIND11_MODULE (module.cpp) calls. Exceptions: module.cpp maps InputError to ValueError with the
// CLI's message; pybind11 maps std::invalid_argument to ValueError.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace pounding::python {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

template <class T>
py::array_t<T> to_numpy(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return a;
}

// What a caller gave, short enough for an error message: "str 'abc'", "list [{}]" (the repr cut to 40
// characters), "a ndarray of shape (2, 3) (float64)" (an array's shape, never its values).
std::string given(const py::handle& value);
// Any value numpy converts to float64 numbers, as a C-contiguous array; ValueError "<what>: numbers are needed, got
// <given>" where it cannot (Array::ensure's null array, never dereferenced: issue 44 item 4).
Array checked_array(const py::handle& values, const std::string& what);
// A 1-D float64 array as a vector; `what` names it in the ValueError, with what was given.
std::vector<double> to_vector(const py::handle& values, const std::string& what);
// One number (int, float, numpy scalar; not bool, not a string); ValueError naming `what` and what was given.
double to_number(const py::handle& value, const std::string& what);

// The run settings every engine call checks, as the CLI does (InputError -> ValueError naming the argument, its range
// and the fix): threads in [0, 1024] (0: every core); duration 0 (the record's own length) or positive and finite
// (s); displacement_limit positive and finite (m).
void check_threads(int threads);
void check_duration(double duration);
void check_displacement_limit(double displacement_limit);

// Runs work(b) for every b in [0, batches) on `threads` threads (0: every core) with the GIL released; the calling
// thread takes the GIL every 50 ms to check for Ctrl-C (PyErr_CheckSignals) and then stops the workers after their
// current batch and throws error_already_set (KeyboardInterrupt). The first exception of a worker is rethrown.
// Results must not depend on the order: each b writes only its own lanes. `stop` (optional): raised at Ctrl-C, so a
// batch that passes it to the steppers (KernelSettings::stop) ends within a few thousand steps instead of running on.
void run_parallel(std::size_t batches, int threads, const std::function<void(std::size_t)>& work,
                  std::atomic<bool>* stop = nullptr);
// One long engine call (a spectrum, a fragility fit's bootstrap) on a worker thread with the GIL released, while this
// thread watches for Ctrl-C: the call gets a stop flag (raised at Ctrl-C; it should end within one step of its loop)
// and this throws error_already_set (KeyboardInterrupt) instead of waiting for the call to finish.
void run_interruptible(const std::function<void(const std::atomic<bool>& stop)>& work);

void bind_kernel(py::module_& m);    // kernel.cpp: run_batch, analyze, simulate, status names
void bind_records(py::module_& m);   // records.cpp: Record, read_record, spectrum, design_spectrum
void bind_analysis(py::module_& m);  // analysis.cpp: fragility fits, hazard rates, risk-targeted gap, ddc_rho
void bind_study(py::module_& m);     // study.cpp: run_study in-process, report of a results file
void bind_systems(py::module_& m);   // systems.cpp: analyze_storeys (shear buildings through run_system)

}  // namespace pounding::python
