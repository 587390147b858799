#pragma once
// What the lane-loop steppers (Newmark, RK4, Nigam-Jennings) share: the law at one lane, the impulsive
// exchange, the energy terms, the guard and the observers, each a call into the lane-generic code at T = double.
#include "pounding/contact/laws/stereomechanical.hpp"
#include "pounding/contact/stability.hpp"
#include "pounding/kernel/guard.hpp"
#include "pounding/kernel/observers.hpp"
#include "pounding/model/sdof.hpp"

namespace pounding::kernel::scalar {

// The restoring force of structure `body` (0 or 1) of lane i after a displacement from u_old to u (committed
// fs_old), from the structure model M.
template <class M>
[[gnu::always_inline]] inline double spring(const Tile& T, int body, int i, double fs_old, double u_old, double u) {
  return M::template restoring<double>(M::template load<double>(T, body, i), {u_old, fs_old}, u, u - u_old);
}
template <class M> [[gnu::always_inline]] inline double spring1(const Tile& T, int i, double fs_old, double u_old, double u) {
  return spring<M>(T, 0, i, fs_old, u_old, u);
}
template <class M> [[gnu::always_inline]] inline double spring2(const Tile& T, int i, double fs_old, double u_old, double u) {
  return spring<M>(T, 1, i, fs_old, u_old, u);
}

// The law's force at lane i with latched 1/v0 `iv0`; sh receives sqrt(penetration) for the guard.
template <class Law, class Exp>
[[gnu::always_inline]] inline double force(const Tile& T, int i, double d, double dd, double iv0, Exp n, double& clamp,
                                           contact::Shared<double>& sh) {
  return Law::template force<double>({d, dd}, {T.kc[i], T.cd[i]}, {iv0}, n, sh, clamp);
}
template <class Law, class Exp>
[[gnu::always_inline]] inline double force(const Tile& T, int i, double d, double dd, double iv0, Exp n, double& clamp) {
  contact::Shared<double> sh{0.0};
  return force<Law>(T, i, d, dd, iv0, n, clamp, sh);
}
// 1/v0 as latched at an onset with approach speed `approach` (unchanged when !on or the law does not latch)
template <class Law> [[gnu::always_inline]] inline double latched(double iv0, bool on, double approach, double v0_min) {
  contact::State<double> s{iv0};
  Law::template on_onset<double>(s, on, approach, v0_min);
  return s.iv0;
}
// Marks lane i diverged when the explicit contact treatment is past the stepper's stability limit.
template <class Law, class Exp>
[[gnu::always_inline]] inline void guard_contact(Tile& T, int i, double d, double dd, Exp n,
                                                 const contact::Shared<double>& sh, double h, double limit2) {
  const bool unstable = contact::unstable<Law, double>({d, dd}, {T.kc[i], T.cd[i]}, {T.iv0[i]}, n, sh,
                                                      h * h / T.meff[i], limit2);
  T.bad[i] = std::max(T.bad[i], unstable ? 1.0 : 0.0);
}

// Stereomechanical exchange inside the step just taken (state at the end already in the tile). Returns 1 on
// an impact.
[[gnu::always_inline]] inline double impulsive(Tile& T, int i, double h, double v1_old, double v2_old, double d_old) {
  const double d = T.u1[i] - T.u2[i] - T.gap[i];
  const auto x = contact::Stereomechanical::exchange<double>(
      {d, d_old, T.v1[i] - T.v2[i], v1_old, v2_old, T.v1[i], T.v2[i], T.m1[i], T.m2[i], T.m1[i] + T.m2[i], T.meff[i],
       T.e[i], h});
  // the products stay out of the sums (no contraction across the select): the scalar kernel's bits
  T.u1[i] += x.hit ? x.dv1 * x.rest : 0.0;
  T.u2[i] += x.hit ? x.dv2 * x.rest : 0.0;
  T.v1[i] += x.hit ? x.dv1 : 0.0;
  T.v2[i] += x.hit ? x.dv2 : 0.0;
  T.Dimp[i] += x.hit ? x.loss : 0.0;
  return x.hit ? 1.0 : 0.0;
}

// Start of the step, for the energy terms and the contact work.
struct Old {
  double u1, u2, v1, v2, fs1, fs2, F;
};
[[gnu::always_inline]] inline Old old_state(const Tile& T, int i) {
  return {T.u1[i], T.u2[i], T.v1[i], T.v2[i], T.fs1[i], T.fs2[i], T.F[i]};
}

// Energy terms (trapezoidal in time, exact plastic dissipation) and contact work over the step just taken.
template <class M, bool WithEnergy>
[[gnu::always_inline]] inline void energy_step(Tile& T, int i, double h, double ag0, double ag1, const Old& o) {
  if constexpr (WithEnergy) {
    const double du1 = T.u1[i] - o.u1, du2 = T.u2[i] - o.u2;
    const double dhys =
        M::template hysteretic_increment<double>(M::template load<double>(T, 0, i), {o.u1, o.fs1}, du1, T.fs1[i]) +
        M::template hysteretic_increment<double>(M::template load<double>(T, 1, i), {o.u2, o.fs2}, du2, T.fs2[i]);
    Energy<double> en = Energy<double>::load(T, i);
    en.on_step(dhys, {T.m1[i], T.c1[i], o.v1, T.v1[i]}, {T.m2[i], T.c2[i], o.v2, T.v2[i]}, ag0, ag1, 0.5 * h);
    en.store(T, i);
  }
  T.Wc[i] += contact_work(o.F, T.F[i], (T.u1[i] - o.u1) - (T.u2[i] - o.u2));
}

// Divergence guard, then the observers, for lane i after its step (t: end of the step).
[[gnu::always_inline]] inline void finish(Tile& T, int i, double t, double ag, double clamp, double onset, double lim) {
  check_and_freeze<double>(T.bad[i], {T.u1[i], T.u2[i], T.v1[i], T.v2[i], T.a1[i], T.a2[i], T.fs1[i], T.fs2[i], T.F[i]},
                           lim);
  Peaks<double> pk = Peaks<double>::load(T, i);
  pk.on_step(t, T.u1[i], T.u2[i], T.a1[i], T.a2[i], ag);
  pk.store(T, i);
  Impacts<double> im = Impacts<double>::load(T, i);
  im.on_onset(t, onset);
  im.on_contact(T.F[i], T.u1[i] - T.u2[i] - T.gap[i], clamp);
  im.store(T, i);
}

// Accelerations from the equations of motion at the end of the step (F: contact force).
[[gnu::always_inline]] inline void accelerations(Tile& T, int i, double ag, double F) {
  T.a1[i] = -ag - (T.c1[i] * T.v1[i] + T.fs1[i] + F) * T.im1[i];
  T.a2[i] = -ag - (T.c2[i] * T.v2[i] + T.fs2[i] - F) * T.im2[i];
}

// The end of a lane-loop step once the state and the contact force F are known: the accelerations from the
// equations of motion (unless the stepper keeps its own), the contact bookkeeping, the energy terms, the
// divergence guard and the observers.
template <class M, bool WithEnergy, bool Accelerations = true>
[[gnu::always_inline]] inline void end_step(Tile& T, int i, double h, double t, double ag0, double ag1, const Old& o,
                                            double F, double d, double clamp, double onset, double lim) {
  T.F[i] = F;
  if constexpr (Accelerations) accelerations(T, i, ag1, F);
  T.dprev[i] = d;
  T.tcon[i] += d > 0.0 ? h : 0.0;
  energy_step<M, WithEnergy>(T, i, h, ag0, ag1, o);
  finish(T, i, t, ag1, clamp, onset, lim);
}

}  // namespace pounding::kernel::scalar
