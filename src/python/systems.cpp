// Multi-storey shear buildings side by side on numpy arrays (issue 28: "the same call takes multi-storey
// buildings"): model::shear_buildings for the topology, physics::set_shear_building / set_contacts per lane (the
// numbers `pounding simulate --storeys` and the studies use), physics::run_system over threads in batches.
// One topology per call (storeys and storey heights of each building); the per-lane numbers vary.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/validate.hpp"

namespace pounding::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The per-lane inputs, by name; absent optional ones are empty.
struct Lanes {
  std::size_t n = 0;
  std::vector<double> mass[2], stiffness[2], period[2], fy[2], drift[2], cy[2], alpha[2], zeta[2];
  std::vector<double> gap, kc, e;
};

std::vector<double> lane_array(const py::dict& d, const std::string& key, std::size_t n, bool required,
                               double fill = kNaN) {
  if (!d.contains(key)) {
    if (required) throw py::value_error("buildings: the key '" + key + "' is missing");
    return fill == fill ? std::vector<double>(n, fill) : std::vector<double>{};
  }
  auto v = to_vector(d[key.c_str()], "buildings['" + key + "']");
  if (v.size() != n)
    throw py::value_error("buildings['" + key + "']: " + std::to_string(n) + " values (one per pair) are needed");
  return v;
}

void check(const std::vector<double>& v, const std::string& key, double lo, double hi, bool open_lo) {
  for (std::size_t l = 0; l < v.size(); ++l)
    if (!(open_lo ? v[l] > lo : v[l] >= lo) || !(v[l] < hi || (std::isinf(hi) && v[l] == hi)))
      throw py::value_error(key + " (lane " + std::to_string(l) + ") = " + std::to_string(v[l]) + " is out of range, " +
                            key + ", give a value in " + (open_lo ? "(" : "[") + std::to_string(lo) + ", " +
                            std::to_string(hi) + ")");
}

Lanes lanes_from(const py::dict& d) {
  static const char* const keys[] = {"floor_mass", "storey_stiffness", "period", "storey_yield", "yield_drift",
                                     "yield_coefficient", "alpha", "zeta"};
  for (const auto& kv : d) {
    const auto name = py::str(kv.first).cast<std::string>();
    bool known = name == "gap" || name == "kc" || name == "e";
    for (const char* k : keys) known = known || name == std::string(k) + "1" || name == std::string(k) + "2";
    if (!known) throw py::value_error("buildings: unknown key '" + name + "'");
  }
  Lanes L;
  if (!d.contains("gap")) throw py::value_error("buildings: the key 'gap' is missing");
  L.gap = to_vector(d["gap"], "buildings['gap']");
  L.n = L.gap.size();
  for (int b = 0; b < 2; ++b) {
    const std::string s = std::to_string(b + 1);
    L.mass[b] = lane_array(d, "floor_mass" + s, L.n, true);
    L.stiffness[b] = lane_array(d, "storey_stiffness" + s, L.n, false);
    L.period[b] = lane_array(d, "period" + s, L.n, false);
    if (L.stiffness[b].empty() == L.period[b].empty())
      throw py::value_error("buildings: give storey_stiffness" + s + " or period" + s + " (one of them)");
    L.fy[b] = lane_array(d, "storey_yield" + s, L.n, false);
    L.drift[b] = lane_array(d, "yield_drift" + s, L.n, false);
    L.cy[b] = lane_array(d, "yield_coefficient" + s, L.n, false);
    L.alpha[b] = lane_array(d, "alpha" + s, L.n, false, 0.0);
    L.zeta[b] = lane_array(d, "zeta" + s, L.n, false, 0.05);
    check(L.mass[b], "floor_mass" + s, 0.0, 1e12, true);
    check(L.stiffness[b], "storey_stiffness" + s, 0.0, 1e16, true);
    check(L.period[b], "period" + s, 0.0, 100.0, true);
    check(L.fy[b], "storey_yield" + s, 0.0, std::numeric_limits<double>::infinity(), true);  // inf: elastic
    check(L.drift[b], "yield_drift" + s, 0.0, 1.0, true);
    check(L.cy[b], "yield_coefficient" + s, 0.0, 10.0, true);
    check(L.alpha[b], "alpha" + s, 0.0, 1.0, false);
    check(L.zeta[b], "zeta" + s, 0.0, 1.0, false);
  }
  L.kc = lane_array(d, "kc", L.n, false, 0.0);
  L.e = lane_array(d, "e", L.n, false, 1.0);
  return L;
}

physics::ShearSpec spec_of(const Lanes& L, int b, std::size_t l, model::StiffnessProfile profile) {
  physics::ShearSpec s;
  s.floor_mass = {L.mass[b][l]};
  if (!L.stiffness[b].empty()) s.storey_stiffness = {L.stiffness[b][l]};
  else s.period = L.period[b][l], s.profile = profile;
  if (!L.fy[b].empty()) s.storey_yield = {L.fy[b][l]};
  else if (!L.drift[b].empty()) s.yield_drift = L.drift[b][l];
  else if (!L.cy[b].empty()) s.yield_coefficient = L.cy[b][l];
  s.alpha = L.alpha[b][l], s.zeta = L.zeta[b][l];
  return s;
}

// Rows [index][lane]: lanes [first, first + n) of every row of src (width W) into dst (width n), or back.
template <class T>
void copy_rows(const std::vector<T>& src, std::size_t W, std::vector<T>& dst, std::size_t n, std::size_t first,
               bool back) {
  const std::size_t rows = W ? src.size() / W : 0;
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t l = 0; l < n; ++l) {
      if (back) dst[i * W + first + l] = src[i * n + l];  // here src is the part (width n), dst the whole
      else dst[i * n + l] = src[i * W + first + l];
    }
}

physics::SystemBatch slice(const physics::SystemBatch& all, std::size_t first, std::size_t n) {
  physics::SystemBatch b;
  b.resize(*all.system, n);
  const std::size_t W = all.width;
  copy_rows(all.m, W, b.m, n, first, false), copy_rows(all.c_floor, W, b.c_floor, n, first, false);
  copy_rows(all.c_storey, W, b.c_storey, n, first, false), copy_rows(all.spring, W, b.spring, n, first, false);
  copy_rows(all.c_dense, W, b.c_dense, n, first, false);
  copy_rows(all.gap, W, b.gap, n, first, false), copy_rows(all.weight, W, b.weight, n, first, false);
  copy_rows(all.kc, W, b.kc, n, first, false), copy_rows(all.e, W, b.e, n, first, false);
  copy_rows(all.u0, W, b.u0, n, first, false), copy_rows(all.v0, W, b.v0, n, first, false);
  return b;
}

template <class F>
void visit_system_result(physics::SystemResult& r, F&& f) {
  f(r.peak_u), f(r.peak_acc), f(r.final_u), f(r.final_v), f(r.peak_drift), f(r.peak_spring_force);
  f(r.peak_closing), f(r.t_peak_closing), f(r.t_first_impact), f(r.impact_count), f(r.clamp_count);
  f(r.peak_force), f(r.peak_penetration), f(r.contact_energy), f(r.contact_time), f(r.h_omega_contact);
  f(r.status), f(r.e_input), f(r.e_kinetic), f(r.e_strain), f(r.e_viscous), f(r.e_hysteretic), f(r.e_contact_stored);
}

void place(physics::SystemResult& part, std::size_t first, physics::SystemResult& out) {
  std::size_t k = 0;
  std::vector<void*> dst;
  visit_system_result(out, [&](auto& v) { dst.push_back(&v); });
  visit_system_result(part, [&](auto& v) {
    auto* d = static_cast<std::decay_t<decltype(v)>*>(dst[k++]);
    const std::size_t rows = part.width ? v.size() / part.width : 0;
    for (std::size_t i = 0; i < rows; ++i)
      std::copy_n(v.begin() + static_cast<std::ptrdiff_t>(i * part.width), part.width,
                  d->begin() + static_cast<std::ptrdiff_t>(i * out.width + first));
  });
}

// [lane, j] of the rows `index` of a [index][lane] array.
template <class T>
py::array_t<T> columns(const std::vector<T>& v, std::size_t width, const std::vector<int>& index) {
  py::array_t<T> a({static_cast<py::ssize_t>(width), static_cast<py::ssize_t>(index.size())});
  auto m = a.template mutable_unchecked<2>();
  for (std::size_t l = 0; l < width; ++l)
    for (std::size_t j = 0; j < index.size(); ++j)
      m(static_cast<py::ssize_t>(l), static_cast<py::ssize_t>(j)) = v[static_cast<std::size_t>(index[j]) * width + l];
  return a;
}

py::dict result_dict(const model::System& sys, const physics::SystemResult& r, bool contact) {
  py::dict d;
  const std::size_t W = r.width;
  for (std::size_t b = 0; b < 2; ++b) {
    const auto& body = sys.bodies()[b];
    const std::string s = std::to_string(b + 1);
    std::vector<int> storeys;  // the body's storey springs, bottom first
    for (std::size_t i = 0; i < sys.springs().size(); ++i)
      if (sys.springs()[i].body == static_cast<int>(b) && sys.springs()[i].role == model::SpringRole::storey)
        storeys.push_back(static_cast<int>(i));
    std::sort(storeys.begin(), storeys.end(),
              [&](int x, int y) { return sys.springs()[x].storey < sys.springs()[y].storey; });
    d[("peak_u" + s).c_str()] = columns(r.peak_u, W, body.dofs);
    d[("peak_acc" + s).c_str()] = columns(r.peak_acc, W, body.dofs);
    d[("final_u" + s).c_str()] = columns(r.final_u, W, body.dofs);
    d[("peak_drift" + s).c_str()] = columns(r.peak_drift, W, storeys);
    d[("peak_shear" + s).c_str()] = columns(r.peak_spring_force, W, storeys);
  }
  std::vector<int> elems(sys.contacts().size());
  py::list labels;
  for (std::size_t e = 0; e < elems.size(); ++e) elems[e] = static_cast<int>(e), labels.append(sys.contacts()[e].label);
  d["element_labels"] = labels;
  d["peak_closing"] = columns(r.peak_closing, W, elems), d["t_peak_closing"] = columns(r.t_peak_closing, W, elems);
  const char* contact_keys[] = {"t_first_impact", "peak_force", "peak_penetration", "contact_energy", "contact_time",
                                "h_omega_contact"};
  const std::vector<double>* contact_rows[] = {&r.t_first_impact, &r.peak_force, &r.peak_penetration,
                                               &r.contact_energy, &r.contact_time, &r.h_omega_contact};
  for (int i = 0; i < 6; ++i) {
    auto a = columns(*contact_rows[i], W, elems);
    if (!contact) std::fill(a.mutable_data(), a.mutable_data() + a.size(), kNaN);  // not computed
    d[contact_keys[i]] = a;
  }
  auto counts = columns(r.impact_count, W, elems);
  if (!contact) std::fill(counts.mutable_data(), counts.mutable_data() + counts.size(), -1);
  d["impact_count"] = counts;
  d["status"] = to_numpy(r.status);
  d["e_input"] = to_numpy(r.e_input), d["e_kinetic"] = to_numpy(r.e_kinetic), d["e_strain"] = to_numpy(r.e_strain);
  d["e_viscous"] = to_numpy(r.e_viscous), d["e_hysteretic"] = to_numpy(r.e_hysteretic);
  return d;
}

struct TopologyArgs {
  int storeys1, storeys2;
  double height1, height2, level_tolerance;
  std::string levels, profile;
  std::vector<double> modal_zeta;  // classical modal damping of the multi-storey buildings (empty: Rayleigh)
};

py::dict analyze_storeys_py(const py::dict& buildings, const Array& ag, double dt, const TopologyArgs& t,
                            const std::string& stepper, const std::string& contact, const std::string& damping,
                            double n, int substeps, bool energy, double duration, double u_limit, std::size_t width,
                            int threads) {
  const Lanes L = lanes_from(buildings);
  if (ag.ndim() != 1 || ag.size() < 2) throw py::value_error("ag: a 1-D array of at least 2 samples (m/s^2) is needed");
  if (t.storeys1 < 1 || t.storeys2 < 1 || t.storeys1 > 100 || t.storeys2 > 100)
    throw py::value_error("storeys: 1 to 100 storeys per building");
  if (t.levels != "common" && t.levels != "top") throw py::value_error("contact_levels: 'common' or 'top'");
  if (t.profile != "uniform" && t.profile != "shear") throw py::value_error("stiffness_profile: 'uniform' or 'shear'");
  for (double z : t.modal_zeta)
    if (!(z >= 0.0 && z <= 0.5)) throw py::value_error("modal_zeta: every ratio in [0, 0.5]");
  std::vector<model::StickTopology> sticks(2);
  sticks[0].storeys = t.storeys1, sticks[0].storey_heights = {t.height1};
  sticks[1].storeys = t.storeys2, sticks[1].storey_heights = {t.height2};
  for (auto& st : sticks)
    if (!t.modal_zeta.empty() && st.storeys > 1) st.damping = model::DampingForm::dense;
  const model::System sys = model::shear_buildings(
      sticks, t.level_tolerance, t.levels == "top" ? model::ContactLevels::top : model::ContactLevels::common);
  const auto profile = t.profile == "shear" ? model::StiffnessProfile::shear : model::StiffnessProfile::uniform;
  ContactModel cm;
  cm.law = parse_contact_law(contact), cm.damping = parse_damping_law(damping), cm.n = n;
  KernelSettings ks;
  ks.stepper = parse_stepper(stepper), ks.substeps = substeps, ks.energy = energy, ks.displacement_limit = u_limit;
  const std::vector<double> acc(ag.data(), ag.data() + ag.size());
  const GroundMotion gm{dt, acc, duration};
  const std::vector<ContactModel> groups(sys.groups().size(), cm);
  if (width < 1) throw py::value_error("batch: at least 1 pair per batch is needed");
  physics::SystemBatch all;
  all.resize(sys, L.n);
  const std::size_t batches = (L.n + width - 1) / width;
  run_parallel(batches, threads, [&](std::size_t b) {  // the lanes' numbers (modes, Rayleigh) on every core
    for (std::size_t l = b * width; l < std::min(L.n, (b + 1) * width); ++l) {
      for (int bi = 0; bi < 2; ++bi) {
        physics::ShearSpec s = spec_of(L, bi, l, profile);
        if (sticks[static_cast<std::size_t>(bi)].damping == model::DampingForm::dense)
          s.modal = true, s.modal_zeta = t.modal_zeta;
        physics::set_shear_building(all, l, bi, s);
      }
      physics::set_contacts(all, l, L.gap[l], L.kc[l], L.e[l]);
    }
  });
  physics::throw_first(physics::validate(all, groups, gm, ks));  // every pair before any run, numbered as given
  physics::SystemResult out;
  out.resize(sys, L.n);
  run_parallel(batches, threads, [&](std::size_t b) {
    const std::size_t first = b * width, count = std::min(width, L.n - first);
    physics::SystemResult part;
    physics::run_system(slice(all, first, count), groups, gm, ks, part);
    place(part, first, out);
  });
  return result_dict(sys, out, cm.law != ContactLaw::none);
}

}  // namespace

void bind_systems(py::module_& m) {
  py::class_<TopologyArgs>(m, "_Topology")
      .def(py::init<int, int, double, double, double, std::string, std::string, std::vector<double>>());
  m.def("analyze_storeys", &analyze_storeys_py, py::arg("buildings"), py::arg("ag"), py::arg("dt"),
        py::arg("topology"), py::arg("stepper"), py::arg("contact"), py::arg("damping"), py::arg("n"),
        py::arg("substeps"), py::arg("energy"), py::arg("duration"), py::arg("displacement_limit"), py::arg("batch"),
        py::arg("threads"), "shear buildings through run_system (use pounding.analyze_storeys)");
}

}  // namespace pounding::python
