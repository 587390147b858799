// The Python module `pounding` (pybind11): the batch kernel on numpy arrays, for notebooks and scripts.
// A smoke module for now (issue 11, C23): run_batch and the deterministic test workloads; the study
// driver, sampler and results follow with the Python issue. Arrays are SI (m, s, kg, N); ground
// acceleration in m/s^2 like the kernel (the study file's g convention lives at the study's edge).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "pounding/analysis/separation.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/version.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/testing/workloads.hpp"

namespace py = pybind11;
using namespace pounding;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

template <class T>
py::array_t<T> to_numpy(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return a;
}

// The PairBatch fields by name, in one list for both directions.
template <class F>
void visit_batch(PairBatch& b, F&& f) {
  f("m1", b.m1), f("k1", b.k1), f("c1", b.c1), f("fy1", b.fy1), f("alpha1", b.alpha1);
  f("m2", b.m2), f("k2", b.k2), f("c2", b.c2), f("fy2", b.fy2), f("alpha2", b.alpha2);
  f("gap", b.gap), f("kc", b.kc), f("e", b.e);
  f("u1_0", b.u1_0), f("v1_0", b.v1_0), f("u2_0", b.u2_0), f("v2_0", b.v2_0);
}

template <class F>
void visit_result(const BatchResult& r, F&& f) {
  f("peak_u1", r.peak_u1), f("peak_u2", r.peak_u2), f("peak_closing", r.peak_closing);
  f("t_peak_closing", r.t_peak_closing), f("t_first_impact", r.t_first_impact), f("impact_count", r.impact_count);
  f("peak_force", r.peak_force), f("peak_penetration", r.peak_penetration), f("contact_energy", r.contact_energy);
  f("contact_time", r.contact_time), f("peak_acc1", r.peak_acc1), f("peak_acc2", r.peak_acc2);
  f("clamp_count", r.clamp_count), f("status", r.status), f("final_u1", r.final_u1), f("final_v1", r.final_v1);
  f("final_u2", r.final_u2), f("final_v2", r.final_v2), f("e_input", r.e_input), f("e_kinetic", r.e_kinetic);
  f("e_strain", r.e_strain), f("e_viscous", r.e_viscous), f("e_hysteretic", r.e_hysteretic);
  f("e_contact_stored", r.e_contact_stored);
}

// dict of 1-D arrays (missing initial conditions default to rest, missing fy to elastic) -> PairBatch.
PairBatch batch_from_dict(const py::dict& d) {
  if (!d.contains("m1")) throw py::value_error("pairs: the key 'm1' is missing (give every pair parameter)");
  const auto width = static_cast<std::size_t>(Array::ensure(d["m1"]).size());
  PairBatch b;
  b.resize(width);
  visit_batch(b, [&](const char* key, std::vector<double>& v) {
    if (!d.contains(key)) {
      const bool optional = std::string(key).find("_0") != std::string::npos || key[0] == 'f' || key[0] == 'a';
      if (!optional) throw py::value_error(std::string("pairs: the key '") + key + "' is missing");
      if (key[0] == 'f') std::fill(v.begin(), v.end(), std::numeric_limits<double>::infinity());  // elastic
      return;  // resize() filled the other defaults with 0: at rest, no hardening
    }
    Array a = Array::ensure(d[key]);
    if (!a || a.ndim() != 1 || static_cast<std::size_t>(a.size()) != width)
      throw py::value_error(std::string("pairs['") + key + "']: a 1-D array of " + std::to_string(width) +
                            " values (one per pair) is needed");
    std::memcpy(v.data(), a.data(), width * sizeof(double));
  });
  for (const auto& kv : d) {
    bool known = false;
    visit_batch(b, [&](const char* key, std::vector<double>&) { known = known || py::str(kv.first).cast<std::string>() == key; });
    if (!known) throw py::value_error("pairs: unknown key '" + py::str(kv.first).cast<std::string>() + "'");
  }
  return b;
}

py::dict batch_to_dict(PairBatch b) {
  py::dict d;
  visit_batch(b, [&](const char* key, std::vector<double>& v) { d[key] = to_numpy(v); });
  return d;
}

py::dict run_batch_py(const py::dict& pairs, const Array& ag, double dt, const std::string& stepper,
                      const std::string& contact, const std::string& damping, double n, int substeps, bool energy,
                      double duration, double displacement_limit) {
  PairBatch batch = batch_from_dict(pairs);
  if (ag.ndim() != 1 || ag.size() < 2) throw py::value_error("ag: a 1-D array of at least 2 samples (m/s^2) is needed");
  ContactModel cm;
  KernelSettings ks;
  try {
    ks.stepper = parse_stepper(stepper);
    cm.law = parse_contact_law(contact);
    cm.damping = parse_damping_law(damping);
  } catch (const InputError& e) {
    throw py::value_error(e.what());
  }
  cm.n = n;
  ks.substeps = substeps, ks.energy = energy, ks.displacement_limit = displacement_limit;
  const std::vector<double> acc(ag.data(), ag.data() + ag.size());
  GroundMotion gm{dt, acc, duration};
  BatchResult r;
  try {
    py::gil_scoped_release unlocked;  // the kernel touches no Python object
    run_batch(batch, cm, gm, ks, r);
  } catch (const InputError& e) {
    throw py::value_error(e.what());
  }
  py::dict out;
  visit_result(r, [&](const char* key, const auto& v) { out[key] = to_numpy(v); });
  return out;
}

}  // namespace

PYBIND11_MODULE(pounding, m) {
  m.doc() = "pounding: Monte Carlo seismic pounding of adjacent structures (batch kernel on numpy arrays)";
  m.attr("__version__") = program_version;
  m.def("run_batch", &run_batch_py, py::arg("pairs"), py::arg("ag"), py::arg("dt"),
        py::arg("stepper") = "central-difference", py::arg("contact") = "hertzdamp",
        py::arg("damping") = "lankarani-nikravesh", py::arg("n") = 1.5, py::arg("substeps") = 1,
        py::arg("energy") = false, py::arg("duration") = 0.0, py::arg("displacement_limit") = 10.0,
        "Runs every pair (dict of 1-D arrays: m1 k1 c1 fy1 alpha1 m2 k2 c2 fy2 alpha2 gap kc e [u1_0 v1_0 u2_0 "
        "v2_0]; SI units) through the ground acceleration ag (m/s^2, spacing dt s) in lockstep; returns a dict "
        "of per-pair arrays (peaks, impact counts, status 0 ok / 1 diverged / 2 non-finite, energies).");
  py::module_ a = m.def_submodule("analysis", "the statistics and code rules of the analysis layer");
  a.def("ddc_rho", &separation::ddc_rho, py::arg("T1"), py::arg("T2"), py::arg("zeta1"), py::arg("zeta2"),
        "CQC correlation of two oscillators (Der Kiureghian 1981) that the DDC code rule uses; periods in s, damping "
        "ratios as fractions.");
  py::module_ t = m.def_submodule("testing", "deterministic workloads (the kernel digests' inputs)");
  t.def("benchmark_batch", [](std::size_t width) { return batch_to_dict(benchmark_batch(width)); }, py::arg("width"));
  t.def("builtin_motion", [](double dt, double duration) { return to_numpy(builtin_motion(dt, duration)); },
        py::arg("dt"), py::arg("duration"));
}
