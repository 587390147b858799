// Multi-storey shear buildings side by side on numpy arrays (issue 28: "the same call takes multi-storey and
// isolated buildings"): model::shear_buildings for the topology (a row of n >= 2 buildings; buildings 1 and 2 may
// stand on isolators inside moat walls), physics::set_shear_building / set_isolated_building / set_contacts /
// set_moat per lane (the numbers `pounding simulate --storeys/--isolation/--buildings` and the studies use),
// physics::run_system over threads in batches. The isolation and moat inputs are checked by
// sampling::validate_isolation, the check simulate uses, worded with Python's names. One topology per call
// (storeys, storey heights, bearings and moats of each building); the per-lane numbers vary.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/model/modes.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"
#include "pounding/physics/validate.hpp"
#include "pounding/sampling/isolation_check.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/core/error.hpp"

namespace pounding::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The per-lane inputs, by name; absent optional ones are empty. Per building b (0-based) of the row.
// A per-floor / per-storey input (floor_mass, storey_stiffness, storey_yield): `cols` values per lane, 1 (every floor
// or storey) or one per floor / storey, bottom first; lane l's are v[l cols, (l + 1) cols).
struct PerStorey {
  std::vector<double> v;
  std::size_t cols = 1;
  bool empty() const { return v.empty(); }
  std::vector<double> lane(std::size_t l) const {
    return {v.begin() + static_cast<std::ptrdiff_t>(l * cols), v.begin() + static_cast<std::ptrdiff_t>((l + 1) * cols)};
  }
};

struct Lanes {
  std::size_t n = 0;
  std::vector<PerStorey> mass, stiffness, fy, u0, v0;  // u0, v0: initial floor displacement / velocity (m, m/s)
  std::vector<std::vector<double>> period, drift, cy, alpha, zeta;
  std::vector<double> gap, kc, e;
  bool e_given = false, kc_given = false;  // no kc: equivalent spheres of the floor masses (simulate's default --kh)
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

// A per-storey key: one value per pair (n values), or a [pair, floor] array of n rows of 1 or `storeys` values.
PerStorey storey_array(const py::dict& d, const std::string& key, std::size_t n, int storeys, bool required) {
  if (!d.contains(key)) {
    if (required) throw py::value_error("buildings: the key '" + key + "' is missing");
    return {};
  }
  const std::string what = "buildings['" + key + "']";
  const Array a = checked_array(d[key.c_str()], what);
  const auto rows = a.ndim() >= 1 ? static_cast<std::size_t>(a.shape(0)) : 0;
  const auto cols = a.ndim() == 2 ? static_cast<std::size_t>(a.shape(1)) : 1;
  if (a.ndim() < 1 || a.ndim() > 2 || rows != n || (cols != 1 && cols != static_cast<std::size_t>(storeys)))
    throw py::value_error(fmt::format("{}: {} values (one per pair, every storey) or a [pair, storey] array of shape "
                                      "({}, {}) (one row per pair, bottom first) are needed, got shape ({})",
                                      what, n, n, storeys, fmt::join(std::span(a.shape(), a.ndim()), ", ")));
  return {{a.data(), a.data() + a.size()}, cols};
}

void check(const std::vector<double>& v, const std::string& key, double lo, double hi, bool open_lo) {
  for (std::size_t l = 0; l < v.size(); ++l)
    if (!(open_lo ? v[l] > lo : v[l] >= lo) || !(v[l] < hi || (std::isinf(hi) && v[l] == hi)))
      throw py::value_error(fmt::format("{0} (lane {1}) = {2:g} is out of range, {0}, give a value in {3}{4:g}, {5:g})", key,
                                        l, v[l], open_lo ? "(" : "[", lo, hi));
}

// A building's quantity that a study also sets: that study key's range (config/study_keys.hpp, one range per quantity
// for the studies, `pounding simulate` and Python; issue 44 item 11).
void check_key(const std::vector<double>& v, const std::string& name, std::string_view key, std::size_t cols = 1) {
  const config::StudyKey& k = config::study_key("structures.buildingN", key);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!(v[i] >= k.lo && v[i] <= k.hi))
      throw py::value_error(fmt::format("{} (lane {}{}) = {} is out of range, {}, give a value in {}{}{} (as {} in a "
                                        "study's [structures.buildingK])",
                                        name, i / cols, cols > 1 ? fmt::format(", storey {}", i % cols + 1) : "",
                                        v[i], name, k.range, k.units.empty() ? "" : " ", k.units, key));
}

const char* const kBuildingKeys[] = {"floor_mass", "storey_stiffness", "period", "storey_yield", "yield_drift",
                                     "yield_coefficient", "alpha", "zeta", "initial_u", "initial_v"};

void check_names(const py::dict& d, std::size_t nb) {
  for (const auto& kv : d) {
    const auto name = py::str(kv.first).cast<std::string>();
    bool known = name == "gap" || name == "kc" || name == "e";
    for (const char* k : kBuildingKeys)
      for (std::size_t b = 1; b <= nb; ++b) known = known || name == std::string(k) + std::to_string(b);
    if (!known)
      throw py::value_error("buildings: unknown key '" + name + "' (" + std::to_string(nb) +
                            " buildings: keys end in 1.." + std::to_string(nb) + ")");
  }
}

Lanes lanes_from(const py::dict& d, const std::vector<int>& storeys) {
  const std::size_t nb = storeys.size();
  check_names(d, nb);
  Lanes L;
  if (!d.contains("gap")) throw py::value_error("buildings: the key 'gap' is missing");
  L.gap = to_vector(d["gap"], "buildings['gap']");
  L.n = L.gap.size();
  for (auto* v : {&L.mass, &L.stiffness, &L.fy, &L.u0, &L.v0}) v->resize(nb);
  for (auto* v : {&L.period, &L.drift, &L.cy, &L.alpha, &L.zeta}) v->resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    const std::string s = std::to_string(b + 1);
    L.mass[b] = storey_array(d, "floor_mass" + s, L.n, storeys[b], true);
    L.stiffness[b] = storey_array(d, "storey_stiffness" + s, L.n, storeys[b], false);
    L.period[b] = lane_array(d, "period" + s, L.n, false);
    if (L.stiffness[b].empty() == L.period[b].empty())
      throw py::value_error("buildings: give storey_stiffness" + s + " or period" + s + " (one of them)");
    L.fy[b] = storey_array(d, "storey_yield" + s, L.n, storeys[b], false);
    L.u0[b] = storey_array(d, "initial_u" + s, L.n, storeys[b], false);
    L.v0[b] = storey_array(d, "initial_v" + s, L.n, storeys[b], false);
    for (const auto& [v, name] : {std::pair{&L.u0[b], "initial_u"}, {&L.v0[b], "initial_v"}})
      for (std::size_t i = 0; i < v->v.size(); ++i)
        if (!std::isfinite(v->v[i]))
          throw py::value_error(fmt::format("{}{} (lane {}) = {} is not finite, give finite numbers (m, m/s)", name, s,
                                            i / v->cols, v->v[i]));
    L.drift[b] = lane_array(d, "yield_drift" + s, L.n, false);
    L.cy[b] = lane_array(d, "yield_coefficient" + s, L.n, false);
    L.alpha[b] = lane_array(d, "alpha" + s, L.n, false, 0.0);
    L.zeta[b] = lane_array(d, "zeta" + s, L.n, false, 0.05);
    check_key(L.mass[b].v, "floor_mass" + s, "floor_mass", L.mass[b].cols);
    check_key(L.stiffness[b].v, "storey_stiffness" + s, "storey_stiffness", L.stiffness[b].cols);
    check_key(L.period[b], "period" + s, "period");
    check(L.fy[b].v, "storey_yield" + s, 0.0, std::numeric_limits<double>::infinity(), true);  // inf: elastic
    check(L.drift[b], "yield_drift" + s, 0.0, 1.0, true);
    check_key(L.cy[b], "yield_coefficient" + s, "yield_coefficient");
    check_key(L.alpha[b], "alpha" + s, "alpha");
    check_key(L.zeta[b], "zeta" + s, "zeta");
  }
  L.kc_given = d.contains("kc");
  L.kc = lane_array(d, "kc", L.n, false, 0.0);
  L.e_given = d.contains("e");
  L.e = lane_array(d, "e", L.n, false, 1.0);
  return L;
}

// ---- isolation and moats (buildings 1 and 2, as simulate) ----

// One building's isolation= and moat= dicts: every number a scalar (every lane) or one value per lane.
struct BaseInputs {
  bool isolated = false, moat = false;
  std::string bearing, moat_law = "hertzdamp";
  std::vector<std::pair<std::string, std::vector<double>>> numbers;  // "k_eff", ..., "moat.gap", ...
  const std::vector<double>* find(std::string_view key) const {
    for (const auto& [k, v] : numbers)
      if (k == key) return &v;
    return nullptr;
  }
};

const char* const kIsolationKeys[] = {"base_mass", "k_eff", "zeta_eff", "k1", "k2", "qd", "radius", "mu_slow",
                                      "mu_fast", "rate", "u_y", "a", "beta", "gamma", "eta"};
const char* const kMoatKeys[] = {"gap", "stiffness", "e"};

std::vector<double> per_lane(const py::handle& v, const std::string& what, std::size_t n) {
  if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return std::vector<double>(n, v.cast<double>());
  auto a = to_vector(v, what);
  if (a.size() == 1) return std::vector<double>(n, a[0]);
  if (a.size() != n) throw py::value_error(what + ": a number or " + std::to_string(n) + " values (one per pair)");
  return a;
}

void read_dict(const py::handle& h, const std::string& where, const char* const* keys, std::size_t nkeys,
               const std::string& prefix, std::size_t n, BaseInputs& out, std::string* text_key_value,
               const char* text_key) {
  if (!py::isinstance<py::dict>(h)) throw py::value_error(where + ": a dict or None is needed");
  std::string allowed = text_key;
  for (std::size_t i = 0; i < nkeys; ++i) allowed += std::string(", ") + keys[i];
  for (const auto& kv : py::reinterpret_borrow<py::dict>(h)) {
    const auto name = py::str(kv.first).cast<std::string>();
    if (name == text_key) {
      *text_key_value = py::str(kv.second).cast<std::string>();
      continue;
    }
    if (std::find_if(keys, keys + nkeys, [&](const char* k) { return name == k; }) == keys + nkeys)
      throw unknown_key_error(name, where, where, allowed, "key");
    out.numbers.emplace_back(prefix + name, per_lane(kv.second, where + "['" + name + "']", n));
  }
}

std::vector<BaseInputs> base_inputs(const py::list& isolation, const py::list& moat, std::size_t nb, std::size_t n) {
  if (isolation.size() != nb || moat.size() != nb)
    throw py::value_error("isolation, moat: one entry (None or a dict) per building");
  std::vector<BaseInputs> out(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    const std::string k = "[" + std::to_string(b) + "]";
    if ((!isolation[b].is_none() || !moat[b].is_none()) && b >= 2)
      throw InputError("isolation or a moat for building " + std::to_string(b + 1), "isolation" + k,
                       "isolate buildings 1 and 2 only (as pounding simulate), or give None for building " +
                           std::to_string(b + 1));
    if (!isolation[b].is_none()) {
      std::string bearing;
      read_dict(isolation[b], "isolation" + k, kIsolationKeys, std::size(kIsolationKeys), "", n, out[b], &bearing,
                "bearing");
      out[b].bearing = bearing, out[b].isolated = !bearing.empty();
      if (bearing.empty() && out[b].numbers.empty()) out[b].isolated = false;
    }
    if (!moat[b].is_none()) {
      read_dict(moat[b], "moat" + k, kMoatKeys, std::size(kMoatKeys), "moat.", n, out[b], &out[b].moat_law, "law");
      out[b].moat = true;
    }
  }
  return out;
}

// Lane l's inputs of building b as sampling::IsolationInput (the flags say which were given).
sampling::IsolationInput lane_input(const BaseInputs& in, std::size_t l, bool moat_dict) {
  sampling::IsolationInput s;
  s.bearing = in.bearing, s.moat_law = in.moat_law;
  auto take = [&](const char* key, double& x) {
    const std::vector<double>* v = in.find(key);
    if (v != nullptr) x = (*v)[l];
    return v != nullptr;
  };
  double eta = s.bw_eta;
  s.base_mass_given = take("base_mass", s.base_mass);
  s.k_eff_given = take("k_eff", s.k_eff), s.zeta_given = take("zeta_eff", s.zeta_eff);
  s.lrb_given = take("k1", s.k1) | take("k2", s.k2) | take("qd", s.qd);
  s.mu_fast_given = take("mu_fast", s.mu_fast);
  s.fps_given = take("radius", s.radius) | take("mu_slow", s.mu_slow) | s.mu_fast_given | take("rate", s.rate) |
                take("u_y", s.uy);
  s.bw_given = take("a", s.bw_a) | take("beta", s.bw_beta) | take("gamma", s.bw_gamma) | take("eta", eta);
  if (!(eta == std::floor(eta) && std::abs(eta) < 1e6)) eta = -1;  // not an integer: out of range
  s.bw_eta = static_cast<int>(eta);
  s.moat_given = take("moat.gap", s.moat_gap);
  s.moat_stiffness_given = take("moat.stiffness", s.moat_stiffness), s.moat_e_given = take("moat.e", s.moat_e);
  s.moat_options_given = moat_dict;  // a moat dict without its gap: "moat options without a moat"
  return s;
}

// Python's names for sampling::validate_isolation: isolation[b]['key'] (with [lane] for a per-lane array).
std::string python_name(const BaseInputs& in, std::size_t b, std::size_t l, std::string_view key) {
  const std::string k = "[" + std::to_string(b) + "]";
  static const std::pair<std::string_view, std::string_view> groups[] = {
      {"friction-pendulum keys", "radius/mu_slow/mu_fast/rate/u_y"}, {"bouc-wen keys", "a/beta/gamma/eta"},
      {"non-pendulum keys", "k_eff/zeta_eff/k1/k2/qd"}, {"lead-rubber keys", "k1/k2/qd"},
      {"linear keys", "k_eff/zeta_eff"}};
  for (const auto& [name, text] : groups)
    if (name == key) return "isolation" + k + " keys " + std::string(text);
  if (key == "building") return "building " + std::to_string(b + 1);
  const bool moat = key.substr(0, 5) == "moat.";
  const std::string base = moat ? "moat" + k + "['" + std::string(key.substr(5)) + "']"
                                : "isolation" + k + "['" + std::string(key) + "']";
  const std::vector<double>* v = in.find(key);
  const bool varies = v != nullptr && std::any_of(v->begin(), v->end(), [&](double x) { return !(x == (*v)[0]); });
  return varies ? base + "[" + std::to_string(l) + "]" : base;
}

physics::ShearSpec spec_of(const Lanes& L, std::size_t b, std::size_t l, model::StiffnessProfile profile) {
  physics::ShearSpec s;
  s.floor_mass = L.mass[b].lane(l);
  if (!L.stiffness[b].empty()) s.storey_stiffness = L.stiffness[b].lane(l);
  else s.period = L.period[b][l], s.profile = profile;
  if (!L.fy[b].empty()) s.storey_yield = L.fy[b].lane(l);
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

// An isolated building's base: the bearing's peak and final displacement, the isolator's peak force, the impacts
// and peak force at its moat walls (as simulate's peak_bearing_u{b}, ..., moat_peak_force{b}); NaN / -1 where the
// building has no isolator / no moat.
void base_columns(const model::System& sys, const physics::SystemResult& r, const model::Body& body,
                  const std::string& s, py::dict& d) {
  const std::size_t W = r.width;
  py::array_t<double> pu(W), fu(W), pf(W), mf(W);
  py::array_t<std::int64_t> mi(W);
  std::vector<int> walls;
  if (body.isolated)
    for (int e : sys.elements_at(body.dofs[0])) {
      const model::ContactElement& ce = sys.contacts()[static_cast<std::size_t>(e)];
      if (ce.left.kind == model::SideKind::wall || ce.right.kind == model::SideKind::wall) walls.push_back(e);
    }
  for (std::size_t l = 0; l < W; ++l) {
    using physics::SystemBatch;
    const int base = body.dofs[0];
    pu.mutable_at(l) = body.isolated ? r.peak_u[SystemBatch::at(base, l, W)] : kNaN;
    fu.mutable_at(l) = body.isolated ? r.final_u[SystemBatch::at(base, l, W)] : kNaN;
    pf.mutable_at(l) = body.isolated ? r.peak_spring_force[SystemBatch::at(sys.spring_below(base), l, W)] : kNaN;
    std::int64_t n = walls.empty() ? -1 : 0;
    double f = walls.empty() ? kNaN : 0.0;
    for (int e : walls) {
      const std::int32_t c = r.impact_count[SystemBatch::at(e, l, W)];
      n = n < 0 || c < 0 ? -1 : n + c;
      f = std::max(f, r.peak_force[SystemBatch::at(e, l, W)]);
    }
    mi.mutable_at(l) = n, mf.mutable_at(l) = f;
  }
  d[("peak_bearing_u" + s).c_str()] = pu, d[("final_bearing_u" + s).c_str()] = fu;
  d[("peak_bearing_force" + s).c_str()] = pf, d[("moat_impacts" + s).c_str()] = mi;
  d[("moat_peak_force" + s).c_str()] = mf;
}

void building_columns(const model::System& sys, const physics::SystemResult& r, std::size_t b, py::dict& d) {
  const std::size_t W = r.width;
  const auto& body = sys.bodies()[b];
  const std::string s = std::to_string(b + 1);
  std::vector<int> storeys;  // the body's storey springs, bottom first (an isolator is not a storey)
  for (std::size_t i = 0; i < sys.springs().size(); ++i)
    if (sys.springs()[i].body == static_cast<int>(b) && sys.springs()[i].role == model::SpringRole::storey)
      storeys.push_back(static_cast<int>(i));
  std::sort(storeys.begin(), storeys.end(),
            [&](int x, int y) { return sys.springs()[x].storey < sys.springs()[y].storey; });
  const std::vector<int> floors(body.dofs.begin() + (body.isolated ? 1 : 0), body.dofs.end());  // not the base
  d[("peak_u" + s).c_str()] = columns(r.peak_u, W, floors);
  d[("peak_acc" + s).c_str()] = columns(r.peak_acc, W, floors);
  d[("final_u" + s).c_str()] = columns(r.final_u, W, floors);
  d[("peak_drift" + s).c_str()] = columns(r.peak_drift, W, storeys);
  d[("peak_shear" + s).c_str()] = columns(r.peak_spring_force, W, storeys);
  if (b < 2) base_columns(sys, r, body, s, d);
}

py::dict result_dict(const model::System& sys, const physics::SystemResult& r, bool contact) {
  py::dict d;
  const std::size_t W = r.width;
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) building_columns(sys, r, b, d);
  std::vector<int> elems(sys.contacts().size());
  py::list labels;
  for (std::size_t e = 0; e < elems.size(); ++e) elems[e] = static_cast<int>(e), labels.append(sys.contacts()[e].label);
  d["element_labels"] = labels;
  d["peak_closing"] = columns(r.peak_closing, W, elems), d["t_peak_closing"] = columns(r.t_peak_closing, W, elems);
  // with contact="none" the pounding elements' contact values were not computed (a moat's were: its own law)
  std::vector<bool> blank(elems.size());
  for (std::size_t e = 0; e < elems.size(); ++e)
    blank[e] = !contact && sys.groups()[static_cast<std::size_t>(sys.contacts()[e].group)].study_gap;
  const char* contact_keys[] = {"t_first_impact", "peak_force", "peak_penetration", "contact_energy", "contact_time",
                                "h_omega_contact"};
  const std::vector<double>* contact_rows[] = {&r.t_first_impact, &r.peak_force, &r.peak_penetration,
                                               &r.contact_energy, &r.contact_time, &r.h_omega_contact};
  for (int i = 0; i < 6; ++i) {
    auto a = columns(*contact_rows[i], W, elems);
    auto m = a.mutable_unchecked<2>();
    for (py::ssize_t l = 0; l < m.shape(0); ++l)
      for (std::size_t e = 0; e < elems.size(); ++e)
        if (blank[e]) m(l, static_cast<py::ssize_t>(e)) = kNaN;
    d[contact_keys[i]] = a;
  }
  auto counts = columns(r.impact_count, W, elems);
  auto c = counts.mutable_unchecked<2>();
  for (py::ssize_t l = 0; l < c.shape(0); ++l)
    for (std::size_t e = 0; e < elems.size(); ++e)
      if (blank[e]) c(l, static_cast<py::ssize_t>(e)) = -1;
  d["impact_count"] = counts;
  d["status"] = to_numpy(r.status);
  d["e_input"] = to_numpy(r.e_input), d["e_kinetic"] = to_numpy(r.e_kinetic), d["e_strain"] = to_numpy(r.e_strain);
  d["e_viscous"] = to_numpy(r.e_viscous), d["e_hysteretic"] = to_numpy(r.e_hysteretic);
  return d;
}

struct TopologyArgs {
  std::vector<int> storeys;
  std::vector<std::vector<double>> heights;  // per building: one height (every storey) or one per storey
  double level_tolerance;
  std::string levels, profile;
  std::vector<double> modal_zeta;  // classical modal damping of the multi-storey buildings (empty: Rayleigh)
  std::vector<int> rayleigh;       // Rayleigh's modes i < j per building, flat (i1, j1, i2, j2, ...)
};

// The equivalent-sphere material (simulate's --density, --E, --nu) of the default contact stiffness: the pounding
// elements' without kh / kc, a moat's without a stiffness.
struct MoatMaterial {
  double density, youngs, poisson;
};

std::vector<model::StickTopology> sticks_of(const TopologyArgs& t, const std::vector<BaseInputs>& base) {
  const std::size_t nb = t.storeys.size();
  if (nb < 2 || nb > 16) throw py::value_error("storeys: one count per building, 2 to 16 buildings");
  if (t.heights.size() != nb) throw py::value_error("storey_height: one height per building (or one for all)");
  if (t.levels != "common" && t.levels != "top") throw py::value_error("contact_levels: 'common' or 'top'");
  if (t.profile != "uniform" && t.profile != "shear") throw py::value_error("stiffness_profile: 'uniform' or 'shear'");
  for (double z : t.modal_zeta)
    if (!(z >= 0.0 && z <= 0.5)) throw py::value_error("modal_zeta: every ratio in [0, 0.5]");
  if (t.rayleigh.size() != 2 * nb) throw py::value_error("rayleigh_modes: one pair (i, j) for every building or one per building");
  for (std::size_t b = 0; b < nb; ++b)
    if (!(t.rayleigh[2 * b] >= 1 && t.rayleigh[2 * b] < t.rayleigh[2 * b + 1] && t.rayleigh[2 * b + 1] <= 200))
      throw py::value_error("rayleigh_modes: two different modes in [1, 200] (i, j)");
  std::vector<model::StickTopology> sticks(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    if (t.storeys[b] < 1 || t.storeys[b] > model::max_storeys)
      throw py::value_error("storeys: 1 to " + std::to_string(model::max_storeys) + " storeys per building");
    const config::StudyKey& hk = config::study_key("structures.buildingN", "storey_height");  // as simulate's
    const std::vector<double>& h = t.heights[b];
    if (h.size() != 1 && h.size() != static_cast<std::size_t>(t.storeys[b]))
      throw py::value_error(fmt::format("storey_height[{}]: {} heights and building {} has {} storeys; give one height "
                                        "(every storey) or {}, one per storey from the bottom",
                                        b, h.size(), b + 1, t.storeys[b], t.storeys[b]));
    for (double x : h)
      if (!(x >= hk.lo && x <= hk.hi))
        throw py::value_error(fmt::format("storey_height: every storey height in [{:g}, {:g}] m (as storey_height in a "
                                          "study), not {}",
                                          hk.lo, hk.hi, x));
    sticks[b].storeys = t.storeys[b], sticks[b].storey_heights = h;
    if (!t.modal_zeta.empty() && sticks[b].storeys > 1) sticks[b].damping = model::DampingForm::dense;
    if (!base[b].isolated) continue;
    sticks[b].isolated = true, sticks[b].moat = base[b].moat;
    sticks[b].isolator_law = physics::isolator_law(sampling::bearing_of(base[b].bearing));
  }
  return sticks;
}

// Every lane's isolation and moat inputs through the one check (sampling::validate_isolation), before any work.
void validate_bases(const std::vector<BaseInputs>& base, std::size_t n, bool e_given) {
  for (std::size_t b = 0; b < base.size(); ++b) {
    for (std::size_t l = 0; l < n; ++l) {
      sampling::validate_isolation(lane_input(base[b], l, base[b].moat),
                                   [&](std::string_view key) { return python_name(base[b], b, l, key); });
    }
    if (!base[b].moat || e_given || base[b].find("moat.e") != nullptr) continue;
    const ContactLaw law = parse_contact_law(base[b].moat_law);
    if (law == ContactLaw::hertzdamp || law == ContactLaw::kelvin || law == ContactLaw::jankowski)
      throw InputError("the moat's " + base[b].moat_law + " law needs a coefficient of restitution",
                       "moat[" + std::to_string(b) + "]['e']",
                       "give moat[" + std::to_string(b) + "]['e'] (or e= / buildings['e'] for every contact)");
  }
}

// Lane l's buildings, pounding contacts and moat walls.
void set_lane(physics::SystemBatch& all, std::size_t l, const Lanes& L, const std::vector<BaseInputs>& base,
              const std::vector<model::StickTopology>& sticks, model::StiffnessProfile profile,
              const TopologyArgs& t, const MoatMaterial& mat) {
  for (std::size_t bi = 0; bi < sticks.size(); ++bi) {
    physics::ShearSpec s = spec_of(L, bi, l, profile);
    if (sticks[bi].damping == model::DampingForm::dense) s.modal = true, s.modal_zeta = t.modal_zeta;
    if (sticks[bi].storeys > 1) {  // the highest two modes the building has where it has fewer than j (as studies)
      const model::ModePair r = model::rayleigh_modes_for(t.rayleigh[2 * bi], t.rayleigh[2 * bi + 1], sticks[bi].storeys);
      s.mode_i = r.i, s.mode_j = r.j;
    }
    if (sticks[bi].isolated)
      physics::set_isolated_building(all, l, static_cast<int>(bi), s,
                                     sampling::isolation_spec(lane_input(base[bi], l, true), s.floor_mass[0]));
    else
      physics::set_shear_building(all, l, static_cast<int>(bi), s);
  }
  for (std::size_t bi = 0; bi < sticks.size(); ++bi) {  // the floors' initial state (an isolated base at rest)
    const std::vector<int>& dofs = all.system->bodies()[bi].dofs;
    const std::size_t first = sticks[bi].isolated ? 1 : 0;
    for (const auto& [in, field] : {std::pair{&L.u0[bi], &all.u0}, {&L.v0[bi], &all.v0}}) {
      if (in->empty()) continue;
      const std::vector<double> v = in->lane(l);
      for (std::size_t d = first; d < dofs.size(); ++d)
        (*field)[physics::SystemBatch::at(dofs[d], l, all.width)] = v.size() == 1 ? v[0] : v[d - first];
    }
  }
  physics::set_contacts(all, l, L.gap[l], L.kc[l], L.e[l]);
  if (!L.kc_given) physics::set_sphere_stiffness(all, l, mat.density, mat.youngs, mat.poisson);  // as simulate's
  for (std::size_t bi = 0; bi < sticks.size(); ++bi) {
    if (!sticks[bi].moat) continue;
    const sampling::IsolationInput in = lane_input(base[bi], l, true);
    const int b_dof = all.system->bodies()[bi].dofs[0];
    const double m_base = all.m[physics::SystemBatch::at(b_dof, l, all.width)];
    const double kc = in.moat_stiffness > 0 ? in.moat_stiffness  // 0 or not given: the default, as simulate's
                                            : hertz_stiffness_spheres(m_base, m_base, mat.density, mat.youngs, mat.poisson);
    physics::set_moat(all, l, static_cast<int>(bi), in.moat_gap, in.moat_gap, kc, in.moat_e_given ? in.moat_e : L.e[l]);
  }
}

py::dict analyze_storeys_py(const py::dict& buildings, const py::handle& ag_values, double dt, const TopologyArgs& t,
                            const std::string& stepper, const std::string& contact, const std::string& damping,
                            double n, int substeps, bool energy, double duration, double u_limit, std::size_t width,
                            int threads, const py::list& isolation, const py::list& moat, const MoatMaterial& mat) {
  const std::size_t nb = t.storeys.size();
  check_threads(threads), check_duration(duration), check_displacement_limit(u_limit);
  if (nb < 2 || nb > 16) throw py::value_error("storeys: one count per building, 2 to 16 buildings");
  const Lanes L = lanes_from(buildings, t.storeys);
  const Array ag = checked_array(ag_values, "ag");
  if (ag.ndim() != 1 || ag.size() < 2)
    throw py::value_error("ag: a 1-D array of at least 2 samples (m/s^2) is needed, got " + given(ag_values));
  const std::vector<BaseInputs> base = base_inputs(isolation, moat, nb, L.n);
  validate_bases(base, L.n, L.e_given);
  const std::vector<model::StickTopology> sticks = sticks_of(t, base);
  const model::System sys = model::shear_buildings(
      sticks, t.level_tolerance, t.levels == "top" ? model::ContactLevels::top : model::ContactLevels::common);
  const auto profile = t.profile == "shear" ? model::StiffnessProfile::shear : model::StiffnessProfile::uniform;
  ContactModel cm;
  cm.law = parse_contact_law(contact), cm.damping = parse_damping_law(damping), cm.n = n;
  KernelSettings ks;
  ks.stepper = parse_stepper(stepper), ks.substeps = substeps, ks.energy = energy, ks.displacement_limit = u_limit;
  const std::vector<double> acc(ag.data(), ag.data() + ag.size());
  const GroundMotion gm{dt, acc, duration};
  std::vector<ContactModel> groups{cm};  // group 0 the pounding, then one per moat (left to right), as simulate
  for (std::size_t b = 0; b < nb; ++b)
    if (sticks[b].moat) groups.push_back(cm), groups.back().law = parse_contact_law(base[b].moat_law);
  if (groups.size() != sys.groups().size()) throw std::logic_error("analyze_storeys: contact groups out of step");
  if (width < 1) throw py::value_error("batch: at least 1 pair per batch is needed");
  physics::SystemBatch all;
  all.resize(sys, L.n);
  const std::size_t batches = (L.n + width - 1) / width;
  run_parallel(batches, threads, [&](std::size_t b) {  // the lanes' numbers (modes, Rayleigh) on every core
    for (std::size_t l = b * width; l < std::min(L.n, (b + 1) * width); ++l)
      set_lane(all, l, L, base, sticks, profile, t, mat);
  });
  physics::throw_first(physics::validate(all, groups, gm, ks));  // every pair before any run, numbered as given
  physics::SystemResult out;
  out.resize(sys, L.n);
  std::atomic<bool> stop{false};  // Ctrl-C reaches the steppers: a single long lane stops within 4096 steps
  ks.stop = &stop;
  run_parallel(
      batches, threads,
      [&](std::size_t b) {
        const std::size_t first = b * width, count = std::min(width, L.n - first);
        physics::SystemResult part;
        physics::run_system(slice(all, first, count), groups, gm, ks, part);
        place(part, first, out);
      },
      &stop);
  return result_dict(sys, out, cm.law != ContactLaw::none);
}

}  // namespace

void bind_systems(py::module_& m) {
  py::class_<TopologyArgs>(m, "_Topology")
      .def(py::init<std::vector<int>, std::vector<std::vector<double>>, double, std::string, std::string, std::vector<double>,
                    std::vector<int>>());
  py::class_<MoatMaterial>(m, "_MoatMaterial").def(py::init<double, double, double>());
  m.def("analyze_storeys", &analyze_storeys_py, py::arg("buildings"), py::arg("ag"), py::arg("dt"),
        py::arg("topology"), py::arg("stepper"), py::arg("contact"), py::arg("damping"), py::arg("n"),
        py::arg("substeps"), py::arg("energy"), py::arg("duration"), py::arg("displacement_limit"), py::arg("batch"),
        py::arg("threads"), py::arg("isolation"), py::arg("moat"), py::arg("moat_material"),
        "shear buildings through run_system (use pounding.analyze_storeys)");
}

}  // namespace pounding::python
