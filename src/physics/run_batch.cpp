// The batch driver around the kernel: schedule, tile filling and reduction (law-independent parts), the
// dispatch from ContactModel::law to the law type, and pounding::run_batch (validate, then run).
#include "pounding/physics/run_batch.hpp"

#include <cmath>

#include "pounding/physics/validate.hpp"

namespace pounding::physics {

Schedule make_schedule(const GroundMotion& motion, int substeps) {
  Schedule s;
  s.h = motion.dt / substeps;
  s.nsteps = std::lround(motion.total_duration() / s.h);
  s.ag.assign(static_cast<std::size_t>(s.nsteps) + 1, 0.0);
  const long nrec = static_cast<long>(motion.ag.size());
  for (long j = 0; j <= s.nsteps; ++j) {
    long r = j / substeps, q = j % substeps;
    if (r >= nrec) break;
    double a0 = motion.ag[static_cast<std::size_t>(r)];
    double a1 = r + 1 < nrec ? motion.ag[static_cast<std::size_t>(r + 1)] : 0.0;
    s.ag[static_cast<std::size_t>(j)] = q == 0 ? a0 : a0 + (static_cast<double>(q) / substeps) * (a1 - a0);
  }
  return s;
}

void fill_lane_common(kernel::Tile& T, int i, const PairParams& p, double v0_min) {
  T.m1[i] = p.s1.m, T.m2[i] = p.s2.m, T.im1[i] = 1.0 / p.s1.m, T.im2[i] = 1.0 / p.s2.m;
  T.k1[i] = p.s1.k, T.k2[i] = p.s2.k, T.c1[i] = p.s1.c, T.c2[i] = p.s2.c;
  T.gap[i] = p.gap, T.kc[i] = p.kc, T.e[i] = p.e, T.nout[i] = 0.0;
  T.meff[i] = p.s1.m * p.s2.m / (p.s1.m + p.s2.m);
  T.u1[i] = p.u1, T.v1[i] = p.v1, T.u2[i] = p.u2, T.v2[i] = p.v2;
  const double d0 = p.u1 - p.u2 - p.gap, dd0 = p.v1 - p.v2;
  T.iv0[i] = 1.0 / std::max(dd0, v0_min);
  T.dprev[i] = d0;
  T.pu1[i] = std::abs(p.u1), T.pu2[i] = std::abs(p.u2);
  T.pclose[i] = p.u1 - p.u2, T.tpclose[i] = 0.0, T.tfirst[i] = d0 > 0.0 ? 0.0 : kernel::inf;
  T.nimp[i] = d0 > 0.0 ? 1.0 : 0.0, T.nclamp[i] = 0.0, T.ppen[i] = d0;
  T.Wc[i] = 0.0, T.tcon[i] = 0.0, T.bad[i] = 0.0;
  T.Ein[i] = 0.0, T.Evis[i] = 0.0, T.Ehys[i] = 0.0, T.Dimp[i] = 0.0;
}

void fill_lane_nj(kernel::Tile& T, int body, int i, const Structure& st, double k_lin, double h) {
  const double w = std::sqrt(k_lin / st.m), z = st.c / (2.0 * std::sqrt(k_lin * st.m));
  const NigamJennings c = nigam_jennings(w, z, h);
  double(*dst)[kernel::tile_width] = body == 0 ? T.nj1 : T.nj2;
  const double vals[8] = {c.a11, c.a12, c.a21, c.a22, c.b11, c.b12, c.b21, c.b22};
  for (int q = 0; q < 8; ++q) dst[q][i] = vals[q];
}

void fill_lane_initial_force(kernel::Tile& T, int i, const PairParams& p, double ag0) {
  T.a1[i] = -ag0 - (T.c1[i] * p.v1 + T.fs1[i] + T.F[i]) * T.im1[i];
  T.a2[i] = -ag0 - (T.c2[i] * p.v2 + T.fs2[i] - T.F[i]) * T.im2[i];
  T.pF[i] = T.F[i];
  T.pa1[i] = std::abs(T.a1[i] + ag0), T.pa2[i] = std::abs(T.a2[i] + ag0);
}

void collect_lane(const kernel::Tile& T, int i, std::size_t L, double stored, double strain, bool impulsive,
                  BatchResult& out) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool bad = T.bad[i] > 0.0;
  out.restitution_outside[L] = static_cast<std::int32_t>(T.nout[i]);
  out.status[L] = static_cast<std::uint8_t>(T.bad[i] >= 2.0 ? LaneStatus::non_finite
                                            : bad          ? LaneStatus::diverged
                                                           : LaneStatus::ok);
  auto val = [&](double x) { return bad ? nan : x; };
  out.peak_u1[L] = val(T.pu1[i]);
  out.peak_u2[L] = val(T.pu2[i]);
  out.peak_closing[L] = val(T.pclose[i]);
  out.t_peak_closing[L] = val(T.tpclose[i]);
  out.t_first_impact[L] = std::isinf(T.tfirst[i]) ? nan : val(T.tfirst[i]);
  out.impact_count[L] = bad ? -1 : static_cast<std::int32_t>(T.nimp[i]);
  out.clamp_count[L] = bad ? -1 : static_cast<std::int32_t>(T.nclamp[i]);
  out.peak_force[L] = impulsive ? nan : val(T.pF[i]);
  out.peak_penetration[L] = val(std::max(T.ppen[i], 0.0));
  out.contact_time[L] = val(T.tcon[i]);
  out.peak_acc1[L] = val(T.pa1[i]);
  out.peak_acc2[L] = val(T.pa2[i]);
  out.final_u1[L] = val(T.u1[i]), out.final_v1[L] = val(T.v1[i]);
  out.final_u2[L] = val(T.u2[i]), out.final_v2[L] = val(T.v2[i]);
  out.e_contact_stored[L] = val(stored);
  out.contact_energy[L] = val(T.Wc[i] - stored + T.Dimp[i]);
  out.e_input[L] = val(T.Ein[i]);
  out.e_kinetic[L] = val(0.5 * T.m1[i] * T.v1[i] * T.v1[i] + 0.5 * T.m2[i] * T.v2[i] * T.v2[i]);
  out.e_strain[L] = val(strain);
  out.e_viscous[L] = val(T.Evis[i]);
  out.e_hysteretic[L] = val(T.Ehys[i]);
}

void mark_resolution(std::size_t L, double k_t, double meff, double h, double limit, BatchResult& out) {
  const bool ran = out.status[L] == static_cast<std::uint8_t>(LaneStatus::ok);
  out.h_omega_contact[L] = ran ? h_omega(h, k_t, meff) : std::numeric_limits<double>::quiet_NaN();
  if (ran && out.h_omega_contact[L] > limit) out.status[L] = static_cast<std::uint8_t>(LaneStatus::coarse);
}

kernel::Context tile_context(const kernel::Context& C, const KernelSettings& ks, const kernel::Tile& T,
                             std::size_t base, double ag0) {
  kernel::Context Ct = C;
  if (ks.series && ks.series->lane >= base && ks.series->lane < base + static_cast<std::size_t>(T.n)) {
    Ct.rec = ks.series;
    Ct.rec_lane = static_cast<int>(ks.series->lane - base);
    kernel::record_lane(Ct, T, 0.0, ag0);
  }
  return Ct;
}

void run_batch(const PairBatch& batch, const ContactModel& cm, const GroundMotion& motion, const KernelSettings& ks,
               BatchResult& out) {
  contact::visit_law(cm.law, [&]<class Law>() { run_batch_t<Law>(batch, cm, motion, ks, out); });
}

}  // namespace pounding::physics

namespace pounding {

void run_batch(const PairBatch& batch, const ContactModel& contact, const GroundMotion& motion,
               const KernelSettings& settings, BatchResult& out) {
  physics::throw_first(physics::validate(batch, contact, motion, settings));
  physics::run_batch(batch, contact, motion, settings, out);
}

}  // namespace pounding
