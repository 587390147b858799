// The pair kernel on numpy arrays: run_batch (one call, the kernel's own fields), analyze (many pairs, threads over
// batches with the GIL released, Ctrl-C between batches) and simulate (one pair, full time series).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/single_impact.hpp"
#include "pounding/physics/validate.hpp"
#include "pounding/workloads/workloads.hpp"

namespace pounding::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The PairBatch fields by name, in one list for both directions.
template <class B, class F>
void visit_batch(B& b, F&& f) {
  f("m1", b.m1), f("k1", b.k1), f("c1", b.c1), f("fy1", b.fy1), f("alpha1", b.alpha1);
  f("m2", b.m2), f("k2", b.k2), f("c2", b.c2), f("fy2", b.fy2), f("alpha2", b.alpha2);
  f("gap", b.gap), f("kc", b.kc), f("e", b.e);
  f("u1_0", b.u1_0), f("v1_0", b.v1_0), f("u2_0", b.u2_0), f("v2_0", b.v2_0);
}

// Every BatchResult field, under the results files' names where the files have one (impacts/peak_force, ...).
template <class R, class F>
void visit_result(R& r, F&& f) {
  f("peak_u1", r.peak_u1), f("peak_u2", r.peak_u2), f("peak_closing", r.peak_closing);
  f("t_peak_closing", r.t_peak_closing), f("t_first_impact", r.t_first_impact), f("impact_count", r.impact_count);
  f("peak_force", r.peak_force), f("peak_penetration", r.peak_penetration), f("contact_energy", r.contact_energy);
  f("contact_time", r.contact_time), f("peak_acc1", r.peak_acc1), f("peak_acc2", r.peak_acc2);
  f("clamp_count", r.clamp_count), f("status", r.status), f("final_u1", r.final_u1), f("final_v1", r.final_v1);
  f("final_u2", r.final_u2), f("final_v2", r.final_v2), f("e_input", r.e_input), f("e_kinetic", r.e_kinetic);
  f("e_strain", r.e_strain), f("e_viscous", r.e_viscous), f("e_hysteretic", r.e_hysteretic);
  f("e_contact_stored", r.e_contact_stored), f("h_omega_contact", r.h_omega_contact);
  f("restitution_outside", r.restitution_outside);
}

bool optional_key(const std::string& key) {
  return key.find("_0") != std::string::npos || key == "fy1" || key == "fy2" || key == "alpha1" || key == "alpha2" ||
         key == "kc" || key == "e";
}

// dict of 1-D arrays -> PairBatch. Missing initial conditions: at rest; fy: elastic (inf); alpha 0; kc 0 and e 1
// (the laws that need them refuse those values in validate, naming the pair). Every column is converted with a check
// (checked_array): m1's unchecked conversion, which sizes the batch, crashed on pairs['m1'] = 'abc' (issue 44 item 4).
// The memory a batch of `width` pairs takes here, checked before any column is copied: the pairs' columns, the
// result (twice while the threads place their parts) and the arrays returned, 8 bytes a value. 10^9 pairs were
// copied (24 GB) until the process was killed.
void check_batch_memory(std::size_t width) {
  PairBatch probe;
  std::size_t columns = 0;
  visit_batch(probe, [&](const char*, std::vector<double>&) { ++columns; });
  const double per_pair = 8.0 * static_cast<double>(columns + 3 * 26);
  const double need = per_pair * static_cast<double>(width), have = available_memory_bytes();
  if (need > have)
    throw py::value_error(fmt::format(
        "pairs: {} pairs need about {} of memory ({:.0f} bytes a pair: the columns copied, the results and the arrays "
        "returned), {} is available; give the pairs in parts of at most {} and join the results",
        width, human_bytes(need), per_pair, human_bytes(have), static_cast<std::size_t>(have / per_pair)));
}

PairBatch batch_from_dict(const py::dict& d) {
  if (!d.contains("m1")) throw py::value_error("pairs: the key 'm1' is missing (give every pair parameter)");
  try {  // the size first, before any column is converted (a view of 10^9 values costs nothing until copied)
    check_batch_memory(py::len(d["m1"]));
  } catch (const py::error_already_set&) {  // no length: column("m1") below names what was given
  } catch (const py::type_error&) {
  }
  auto column = [&](const char* key) {
    const std::string what = std::string("pairs['") + key + "']";
    Array a = checked_array(d[key], what);
    if (a.ndim() != 1)
      throw py::value_error(what + ": a 1-D array (one value per pair) is needed, got " + given(d[key]));
    return a;
  };
  const auto width = static_cast<std::size_t>(column("m1").size());
  PairBatch b;
  b.resize(width);
  visit_batch(b, [&](const char* key, std::vector<double>& v) {
    if (!d.contains(key)) {
      if (!optional_key(key)) throw py::value_error(std::string("pairs: the key '") + key + "' is missing");
      if (key[0] == 'f') std::fill(v.begin(), v.end(), std::numeric_limits<double>::infinity());  // elastic
      if (std::string(key) == "e") std::fill(v.begin(), v.end(), 1.0);
      return;
    }
    const Array a = column(key);
    if (static_cast<std::size_t>(a.size()) != width)
      throw py::value_error(std::string("pairs['") + key + "']: " + std::to_string(width) + " values (one per pair, as " +
                            "pairs['m1']) are needed, got " + std::to_string(a.size()));
    std::copy_n(a.data(), width, v.data());
  });
  for (const auto& kv : d) {
    bool known = false;
    const auto name = py::str(kv.first).cast<std::string>();
    visit_batch(b, [&](const char* key, std::vector<double>&) { known = known || name == key; });
    if (!known) throw py::value_error("pairs: unknown key '" + name + "'");
  }
  return b;
}

py::dict batch_to_dict(PairBatch b) {
  py::dict d;
  visit_batch(b, [&](const char* key, std::vector<double>& v) { d[key] = to_numpy(v); });
  return d;
}

struct Setup {
  ContactModel cm;
  KernelSettings ks;
  std::vector<double> ag;
  GroundMotion motion() const { return GroundMotion{dt, ag, duration}; }
  double dt = 0, duration = 0;
};

Setup make_setup(const py::handle& ag_values, double dt, const std::string& stepper, const std::string& contact,
                 const std::string& damping, double n, int substeps, bool energy, double duration, double u_limit) {
  const Array ag = checked_array(ag_values, "ag");
  if (ag.ndim() != 1 || ag.size() < 2)
    throw py::value_error("ag: a 1-D array of at least 2 samples (m/s^2) is needed, got " + given(ag_values));
  Setup s;
  check_duration(duration), check_displacement_limit(u_limit);
  s.ks.stepper = parse_stepper(stepper);  // InputError -> ValueError naming the allowed values
  s.cm.law = parse_contact_law(contact);
  s.cm.damping = parse_damping_law(damping);
  s.cm.n = n;
  s.ks.substeps = substeps, s.ks.energy = energy, s.ks.displacement_limit = u_limit;
  s.ag.assign(ag.data(), ag.data() + ag.size());
  s.dt = dt, s.duration = duration;
  return s;
}

// What the run did not compute is NaN, never 0: the energy integrals (input, viscous, hysteretic) are tracked only
// with energy=True (kernel/observers.hpp); kinetic, strain and contact-stored energy are of the final state and
// always computed.
void mark_not_computed(py::dict& out, bool energy) {
  if (energy) return;
  for (const char* key : {"e_input", "e_viscous", "e_hysteretic"}) {
    auto a = out[key].cast<py::array_t<double>>();
    std::fill(a.mutable_data(), a.mutable_data() + a.size(), kNaN);
  }
}

py::dict result_dict(const BatchResult& r, bool energy) {
  py::dict out;
  visit_result(r, [&](const char* key, const auto& v) { out[key] = to_numpy(v); });
  mark_not_computed(out, energy);
  return out;
}

py::dict run_batch_py(const py::dict& pairs, const py::handle& ag, double dt, const std::string& stepper,
                      const std::string& contact, const std::string& damping, double n, int substeps, bool energy,
                      double duration, double displacement_limit) {
  PairBatch batch = batch_from_dict(pairs);
  const Setup s = make_setup(ag, dt, stepper, contact, damping, n, substeps, energy, duration, displacement_limit);
  BatchResult r;
  {
    py::gil_scoped_release unlocked;  // the kernel touches no Python object
    run_batch(batch, s.cm, s.motion(), s.ks, r);
  }
  return result_dict(r, energy);
}

// Lanes [first, first + n) of a batch (or result) as their own.
PairBatch slice(const PairBatch& all, std::size_t first, std::size_t n) {
  PairBatch b;
  b.resize(n);
  visit_batch(b, [&](const char* key, std::vector<double>& v) {
    visit_batch(all, [&](const char* k2, const std::vector<double>& src) {
      if (std::string(key) == k2) std::copy_n(src.begin() + static_cast<std::ptrdiff_t>(first), n, v.begin());
    });
  });
  return b;
}

void place(const BatchResult& part, std::size_t first, BatchResult& out) {
  visit_result(out, [&](const char* key, auto& dst) {
    visit_result(part, [&](const char* k2, const auto& src) {
      if constexpr (std::is_same_v<std::decay_t<decltype(src)>, std::decay_t<decltype(dst)>>)
        if (std::string(key) == k2) std::copy(src.begin(), src.end(), dst.begin() + static_cast<std::ptrdiff_t>(first));
    });
  });
}

py::dict analyze_py(const py::dict& pairs, const py::handle& ag, double dt, const std::string& stepper,
                    const std::string& contact, const std::string& damping, double n, int substeps, bool energy,
                    double duration, double displacement_limit, std::size_t width, int threads) {
  check_threads(threads);
  const PairBatch all = batch_from_dict(pairs);
  const Setup s = make_setup(ag, dt, stepper, contact, damping, n, substeps, energy, duration, displacement_limit);
  // Every pair checked before any work, numbered as the caller numbers them (a batch would count from 0).
  physics::throw_first(physics::validate(all, s.cm, s.motion(), s.ks));
  if (width < 1) throw py::value_error("batch: at least 1 pair per batch is needed");
  BatchResult out;
  out.resize(all.width());
  const std::size_t batches = (all.width() + width - 1) / width;
  run_parallel(batches, threads, [&](std::size_t b) {
    const std::size_t first = b * width, n = std::min(width, all.width() - first);
    BatchResult r;
    run_batch(slice(all, first, n), s.cm, s.motion(), s.ks, r);
    place(r, first, out);  // disjoint lanes: no lock needed
  });
  return result_dict(out, energy);
}

// One pair with the full time series (the kernel's SeriesRecorder, as `pounding simulate --series`).
py::tuple simulate_py(const py::dict& pair, const py::handle& ag, double dt, const std::string& stepper,
                      const std::string& contact, const std::string& damping, double n, int substeps, bool energy,
                      double duration, double displacement_limit) {
  PairBatch batch = batch_from_dict(pair);
  if (batch.width() != 1) throw py::value_error("simulate: one pair (arrays of length 1) is needed");
  Setup s = make_setup(ag, dt, stepper, contact, damping, n, substeps, energy, duration, displacement_limit);
  SeriesRecorder series;
  const double total = s.motion().total_duration();
  series.reserve_for(static_cast<std::size_t>(std::llround(total / dt)) * static_cast<std::size_t>(substeps) + 2);
  s.ks.series = &series;
  BatchResult r;
  {
    py::gil_scoped_release unlocked;
    run_batch(batch, s.cm, s.motion(), s.ks, r);
  }
  py::dict ts;
  for (auto [key, v] : {std::pair{"t", &series.t}, {"u1", &series.u1}, {"u2", &series.u2}, {"v1", &series.v1},
                        {"v2", &series.v2}, {"a1_abs", &series.a1_abs}, {"a2_abs", &series.a2_abs},
                        {"fs1", &series.fs1}, {"fs2", &series.fs2}, {"force", &series.force}, {"ag", &series.ag}})
    ts[key] = to_numpy(*v);
  return py::make_tuple(result_dict(r, energy), ts);
}

// `pounding collide`: one free impact of m1 at v0 on m2 at rest (physics/single_impact.hpp), its inputs checked as
// the CLI checks them (the same messages, naming --e, --v0, ...).
py::dict collide_py(const std::string& law, double e, double v0, double m1, double m2, double kh, double n,
                    const std::string& damping, const std::string& stepper, int steps) {
  ContactModel cm;
  cm.law = parse_contact_law(law);
  cm.damping = parse_damping_law(damping);
  cm.n = n;
  const Stepper st = parse_stepper(stepper);
  check_impact_inputs(cm, e, true, v0, m1, m2, kh);
  if (steps < 100) throw py::value_error("steps: at least 100 integration steps per contact duration are needed");
  ImpactResult r;
  {
    py::gil_scoped_release unlocked;
    r = single_impact(cm, st, e, v0, m1, m2, kh, steps);
  }
  py::dict d;
  d["e_effective"] = r.e_effective, d["peak_force"] = r.peak_force, d["peak_penetration"] = r.peak_penetration;
  d["duration"] = r.duration, d["energy_lost"] = r.energy_lost, d["energy_lost_fraction"] = r.energy_lost_fraction;
  d["clamps"] = r.clamps, d["h_omega_contact"] = r.h_omega_contact, d["status"] = static_cast<int>(r.status);
  d["restitution_promise"] = restitution_promise(cm).note;
  return d;
}

py::list status_names() {
  py::list names;
  for (const auto& e : lane_status_table) names.append(py::make_tuple(std::string(e.name), static_cast<int>(e.value)));
  return names;
}

}  // namespace

void bind_kernel(py::module_& m) {
  m.def("check_batch_memory", &check_batch_memory, py::arg("width"),
        "ValueError unless a batch of `width` pairs fits in the memory available (before any column is copied)");
  m.def("run_batch", &run_batch_py, py::arg("pairs"), py::arg("ag"), py::arg("dt"),
        py::arg("stepper") = "central-difference", py::arg("contact") = "hertzdamp",
        py::arg("damping") = "lankarani-nikravesh", py::arg("n") = 1.5, py::arg("substeps") = 1,
        py::arg("energy") = false, py::arg("duration") = 0.0, py::arg("displacement_limit") = 10.0,
        "One kernel call on a dict of 1-D arrays (m1 k1 c1 fy1 alpha1 m2 k2 c2 fy2 alpha2 gap kc e [u1_0 v1_0 u2_0 "
        "v2_0]; SI) through ag (m/s^2, spacing dt s); returns per-pair arrays (status: pounding.Status).");
  m.def("analyze", &analyze_py, py::arg("pairs"), py::arg("ag"), py::arg("dt"), py::arg("stepper"),
        py::arg("contact"), py::arg("damping"), py::arg("n"), py::arg("substeps"), py::arg("energy"),
        py::arg("duration"), py::arg("displacement_limit"), py::arg("batch"), py::arg("threads"),
        "run_batch over threads in batches (use pounding.analyze)");
  m.def("simulate", &simulate_py, py::arg("pair"), py::arg("ag"), py::arg("dt"), py::arg("stepper"),
        py::arg("contact"), py::arg("damping"), py::arg("n"), py::arg("substeps"), py::arg("energy"),
        py::arg("duration"), py::arg("displacement_limit"), "one pair with its time series (use pounding.simulate)");
  m.def("collide", &collide_py, py::arg("law"), py::arg("e"), py::arg("v0"), py::arg("m1"), py::arg("m2"),
        py::arg("kh"), py::arg("n"), py::arg("damping"), py::arg("stepper"), py::arg("steps"),
        "one free impact (use pounding.collide)");
  m.def("status_names", &status_names, "(name, value) of every lane status (kernel/batch.hpp LaneStatus)");
  m.def("contact_law_names", [] { return std::string(contact_law_names); });
  m.def("contact_needs", [](const std::string& law) {
    const auto& t = contact::traits(parse_contact_law(law));
    return py::make_tuple(t.needs_stiffness, t.needs_restitution, std::string(t.stiffness_unit));
  }, py::arg("law"), "(needs a stiffness, needs a restitution, stiffness unit) of a contact law (contact/law.hpp)");
  py::module_ t = m.def_submodule("testing", "deterministic workloads (the kernel digests' inputs)");
  t.def("benchmark_batch", [](std::size_t width) { return batch_to_dict(benchmark_batch(width)); }, py::arg("width"));
  t.def("builtin_motion", [](double dt, double duration) { return to_numpy(builtin_motion(dt, duration)); },
        py::arg("dt"), py::arg("duration"));
}

}  // namespace pounding::python
