// Sizing of SystemBatch / SystemResult and the exact adapters between the SDOF pair's PairBatch / BatchResult and
// lane l of System::sdof_pair() (physics/system_batch.hpp; docs/architecture.md §2.2.2, §2.6.1).
#include "pounding/physics/system_batch.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace pounding::physics {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

std::size_t count(std::size_t n, std::size_t width) { return n * width; }

// `to[index][lane] = from[lane]` for one index of a [index][lane] array.
template <class T> void put(std::vector<T>& to, int index, std::size_t width, const std::vector<T>& from) {
  std::copy(from.begin(), from.end(), to.begin() + static_cast<std::ptrdiff_t>(SystemBatch::at(index, 0, width)));
}
template <class T> void take(std::vector<T>& to, int index, std::size_t width, const std::vector<T>& from) {
  const auto b = from.begin() + static_cast<std::ptrdiff_t>(SystemBatch::at(index, 0, width));
  to.assign(b, b + static_cast<std::ptrdiff_t>(width));
}

const model::System& pair_system() {
  static const model::System pair = model::System::sdof_pair();
  return pair;
}

}  // namespace

void SystemBatch::resize(const model::System& s, std::size_t w) {
  system = &s;
  width = w;
  const auto dofs = static_cast<std::size_t>(s.ndof()), springs = s.springs().size(), elements = s.contacts().size();
  m.assign(count(dofs, w), 0.0);
  c_floor.assign(count(dofs, w), 0.0);
  c_storey.assign(s.any_storey_dashpots() ? count(springs, w) : 0, 0.0);
  dense_base.assign(s.bodies().size(), -1);
  std::size_t entries = 0;
  for (std::size_t b = 0; b < s.bodies().size(); ++b)
    if (s.bodies()[b].damping == model::DampingForm::dense) {
      dense_base[b] = static_cast<int>(entries);
      entries += s.bodies()[b].dofs.size() * s.bodies()[b].dofs.size();
    }
  c_dense.assign(count(entries, w), 0.0);
  spring.assign(count(springs, w), SpringSpec{0.0, inf, 0.0});
  gap.assign(count(elements, w), 0.0);
  weight.assign(count(elements, w), 0.0);
  kc.assign(count(elements, w), 0.0);
  e.assign(count(elements, w), 1.0);
  u0.assign(count(dofs, w), 0.0);
  v0.assign(count(dofs, w), 0.0);
}

int SystemBatch::dense_entry(int body, int j, int k) const {
  const int base = dense_base.at(static_cast<std::size_t>(body));
  if (base < 0) return -1;
  const int n = static_cast<int>(system->bodies()[static_cast<std::size_t>(body)].dofs.size());
  return base + j * n + k;
}

void SystemResult::resize(const model::System& s, std::size_t w) {
  width = w;
  const auto dofs = count(static_cast<std::size_t>(s.ndof()), w), springs = count(s.springs().size(), w),
             elements = count(s.contacts().size(), w);
  for (auto* v : {&peak_u, &peak_acc, &final_u, &final_v}) v->assign(dofs, 0.0);
  for (auto* v : {&peak_drift, &peak_spring_force}) v->assign(springs, 0.0);
  for (auto* v : {&peak_closing, &t_peak_closing, &peak_force, &peak_penetration, &contact_energy, &contact_time,
                  &h_omega_contact})
    v->assign(elements, 0.0);
  t_first_impact.assign(elements, nan);  // until the element's first impact
  impact_count.assign(elements, 0);
  clamp_count.assign(elements, 0);
  restitution_outside.assign(elements, 0);
  status.assign(w, 0);
  for (auto* v : {&e_input, &e_kinetic, &e_strain, &e_viscous, &e_hysteretic, &e_contact_stored})
    v->assign(w, nan);  // not computed unless KernelSettings::energy
}

SystemBatch to_system(const PairBatch& b, const model::System& pair) {
  if (!pair.is_sdof_pair()) throw std::logic_error("to_system: the system is not the SDOF pair");
  SystemBatch s;
  const std::size_t w = b.width();
  s.resize(pair, w);
  put(s.m, 0, w, b.m1), put(s.m, 1, w, b.m2);
  put(s.c_floor, 0, w, b.c1), put(s.c_floor, 1, w, b.c2);
  for (std::size_t l = 0; l < w; ++l) {
    s.spring[SystemBatch::at(0, l, w)] = {b.k1[l], b.fy1[l], b.alpha1[l]};
    s.spring[SystemBatch::at(1, l, w)] = {b.k2[l], b.fy2[l], b.alpha2[l]};
  }
  s.gap = b.gap, s.kc = b.kc, s.e = b.e;
  put(s.u0, 0, w, b.u1_0), put(s.u0, 1, w, b.u2_0);
  put(s.v0, 0, w, b.v1_0), put(s.v0, 1, w, b.v2_0);
  return s;
}

PairBatch to_pair_batch(const SystemBatch& s) {
  if (s.system == nullptr || !s.system->is_sdof_pair())
    throw std::logic_error("to_pair_batch: the batch's system is not the SDOF pair");
  const std::size_t w = s.width;
  PairBatch b;
  b.resize(w);
  take(b.m1, 0, w, s.m), take(b.m2, 1, w, s.m);
  take(b.c1, 0, w, s.c_floor), take(b.c2, 1, w, s.c_floor);
  for (std::size_t l = 0; l < w; ++l) {
    const SpringSpec& s1 = s.spring[SystemBatch::at(0, l, w)];
    const SpringSpec& s2 = s.spring[SystemBatch::at(1, l, w)];
    b.k1[l] = s1.k, b.fy1[l] = s1.fy, b.alpha1[l] = s1.alpha;
    b.k2[l] = s2.k, b.fy2[l] = s2.fy, b.alpha2[l] = s2.alpha;
  }
  b.gap = s.gap, b.kc = s.kc, b.e = s.e;
  take(b.u1_0, 0, w, s.u0), take(b.u2_0, 1, w, s.u0);
  take(b.v1_0, 0, w, s.v0), take(b.v2_0, 1, w, s.v0);
  return b;
}

SystemResult from_pair_result(const BatchResult& r) {
  SystemResult s;
  const std::size_t w = r.width();
  s.resize(pair_system(), w);
  put(s.peak_u, 0, w, r.peak_u1), put(s.peak_u, 1, w, r.peak_u2);
  put(s.peak_acc, 0, w, r.peak_acc1), put(s.peak_acc, 1, w, r.peak_acc2);
  put(s.final_u, 0, w, r.final_u1), put(s.final_u, 1, w, r.final_u2);
  put(s.final_v, 0, w, r.final_v1), put(s.final_v, 1, w, r.final_v2);
  // An SDOF's storey drift is its displacement (d = u - 0, no subtraction formed); its spring force is not
  // observed by the pair kernel: NaN.
  put(s.peak_drift, 0, w, r.peak_u1), put(s.peak_drift, 1, w, r.peak_u2);
  s.peak_spring_force.assign(s.peak_spring_force.size(), nan);
  s.peak_closing = r.peak_closing, s.t_peak_closing = r.t_peak_closing, s.t_first_impact = r.t_first_impact;
  s.impact_count = r.impact_count, s.clamp_count = r.clamp_count;
  s.restitution_outside = r.restitution_outside;
  s.peak_force = r.peak_force, s.peak_penetration = r.peak_penetration;
  s.contact_energy = r.contact_energy, s.contact_time = r.contact_time, s.h_omega_contact = r.h_omega_contact;
  s.status = r.status;
  s.e_input = r.e_input, s.e_kinetic = r.e_kinetic, s.e_strain = r.e_strain, s.e_viscous = r.e_viscous;
  s.e_hysteretic = r.e_hysteretic, s.e_contact_stored = r.e_contact_stored;
  return s;
}

BatchResult to_pair_result(const SystemResult& s) {
  const std::size_t w = s.width;
  if (s.peak_u.size() != 2 * w || s.peak_closing.size() != w)
    throw std::logic_error("to_pair_result: the result is not of the SDOF pair (2 DOFs, 1 element)");
  BatchResult r;
  r.resize(w);
  take(r.peak_u1, 0, w, s.peak_u), take(r.peak_u2, 1, w, s.peak_u);
  take(r.peak_acc1, 0, w, s.peak_acc), take(r.peak_acc2, 1, w, s.peak_acc);
  take(r.final_u1, 0, w, s.final_u), take(r.final_u2, 1, w, s.final_u);
  take(r.final_v1, 0, w, s.final_v), take(r.final_v2, 1, w, s.final_v);
  r.peak_closing = s.peak_closing, r.t_peak_closing = s.t_peak_closing, r.t_first_impact = s.t_first_impact;
  r.impact_count = s.impact_count, r.clamp_count = s.clamp_count;
  r.restitution_outside = s.restitution_outside;
  r.peak_force = s.peak_force, r.peak_penetration = s.peak_penetration;
  r.contact_energy = s.contact_energy, r.contact_time = s.contact_time, r.h_omega_contact = s.h_omega_contact;
  r.status = s.status;
  r.e_input = s.e_input, r.e_kinetic = s.e_kinetic, r.e_strain = s.e_strain, r.e_viscous = s.e_viscous;
  r.e_hysteretic = s.e_hysteretic, r.e_contact_stored = s.e_contact_stored;
  return r;
}

}  // namespace pounding::physics
