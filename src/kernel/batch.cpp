// The kernel's value types (kernel/batch.hpp): sizing, lane access, durations.
#include "pounding/kernel/batch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pounding {

bool kernel_fuses_multiply_add() {
#if defined(__FMA__) || defined(__AVX512F__)
  return true;
#else
  return false;
#endif
}

Structure Structure::from_period(double m, double T, double zeta, double fy, double alpha) {
  Structure s;
  s.m = m;
  s.k = 4.0 * std::numbers::pi * std::numbers::pi * m / (T * T);
  s.c = 2.0 * zeta * std::sqrt(s.k * m);
  s.fy = fy;
  s.alpha = alpha;
  return s;
}

void PairBatch::resize(std::size_t n) {
  for (auto* v : {&m1, &k1, &c1, &fy1, &alpha1, &m2, &k2, &c2, &fy2, &alpha2, &gap, &kc, &e, &u1_0, &v1_0, &u2_0,
                  &v2_0})
    v->resize(n);
}

void PairBatch::set(std::size_t i, const PairParams& p) {
  m1[i] = p.s1.m, k1[i] = p.s1.k, c1[i] = p.s1.c, fy1[i] = p.s1.fy, alpha1[i] = p.s1.alpha;
  m2[i] = p.s2.m, k2[i] = p.s2.k, c2[i] = p.s2.c, fy2[i] = p.s2.fy, alpha2[i] = p.s2.alpha;
  gap[i] = p.gap, kc[i] = p.kc, e[i] = p.e;
  u1_0[i] = p.u1, v1_0[i] = p.v1, u2_0[i] = p.u2, v2_0[i] = p.v2;
}

PairParams PairBatch::get(std::size_t i) const {
  PairParams p;
  p.s1 = {m1[i], k1[i], c1[i], fy1[i], alpha1[i]};
  p.s2 = {m2[i], k2[i], c2[i], fy2[i], alpha2[i]};
  p.gap = gap[i], p.kc = kc[i], p.e = e[i];
  p.u1 = u1_0[i], p.v1 = v1_0[i], p.u2 = u2_0[i], p.v2 = v2_0[i];
  return p;
}

double GroundMotion::total_duration() const {
  double own = ag.empty() ? 0.0 : static_cast<double>(ag.size() - 1) * dt;
  return std::max(own, duration);
}

void SeriesRecorder::reserve_for(std::size_t n) {
  for (auto* v : {&t, &u1, &u2, &v1, &v2, &a1_abs, &a2_abs, &fs1, &fs2, &force, &ag}) v->reserve(n + 1);
}
void SeriesRecorder::clear() {
  for (auto* v : {&t, &u1, &u2, &v1, &v2, &a1_abs, &a2_abs, &fs1, &fs2, &force, &ag}) v->clear();
}

void BatchResult::resize(std::size_t n) {
  for (auto* v : {&peak_u1, &peak_u2, &peak_closing, &t_peak_closing, &t_first_impact, &peak_force,
                  &peak_penetration, &contact_energy, &contact_time, &peak_acc1, &peak_acc2, &final_u1, &final_v1,
                  &final_u2, &final_v2, &e_input, &e_kinetic, &e_strain, &e_viscous, &e_hysteretic,
                  &e_contact_stored, &h_omega_contact})
    v->assign(n, 0.0);
  impact_count.assign(n, 0);
  clamp_count.assign(n, 0);
  restitution_outside.assign(n, 0);
  status.assign(n, 0);
}

}  // namespace pounding
