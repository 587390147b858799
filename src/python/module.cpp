// The compiled core of the Python package `pounding` (pybind11, issue 28): pounding._core. The package's Python
// files (src/python/pounding/) wrap it with numpy/pandas conveniences; users import `pounding`, not `_core`.
// Arrays are SI (m, s, kg, N); ground acceleration in m/s^2 like the kernel, records carry both m/s^2 and g.
#include "common.hpp"

#include <stdexcept>

#include "pounding/core/error.hpp"
#include "pounding/core/progress.hpp"
#include "pounding/core/version.hpp"

namespace pounding::python {

std::vector<double> to_vector(const py::handle& values, const std::string& what) {
  Array a;
  try {
    a = Array::ensure(values);
  } catch (const py::error_already_set&) {
    a = Array();
  }
  if (!a || a.ndim() != 1) throw py::value_error(what + ": a 1-D array of numbers is needed");
  return {a.data(), a.data() + a.size()};
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
}
