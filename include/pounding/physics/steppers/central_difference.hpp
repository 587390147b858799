#pragma once
// Explicit central difference (velocity Verlet), the production stepper. The velocity-dependent forces at
// n+1 use the predicted velocity v_n + h a_n (error O(h^2)), which keeps the scheme second order with
// damping. Lanes run in SIMD chunks whose state stays in registers for the whole time loop; the contact law
// is evaluated only in steps where some lane of the chunk touches (skipping it gives exactly F = 0, so
// results do not depend on the chunk's other lanes).
#include <string_view>

#include "pounding/contact/laws/stereomechanical.hpp"
#include "pounding/contact/stability.hpp"
#include "pounding/kernel/guard.hpp"
#include "pounding/kernel/observers.hpp"
#include "pounding/model/sdof.hpp"

namespace pounding::kernel {

namespace cd_detail {
using simd::V;

// One SIMD chunk: constants (the structure model's parameters p1, p2), state and accumulators, loaded once
// and kept in registers.
template <class M> struct Chunk {
  using P = typename M::template Params<V>;
  using S = typename M::template State<V>;
  V m1, m2, im1, im2, c1, c2, gap, kc, cd, e, meff, msum, h2m;
  P p1, p2;
  V u1, v1, a1, fs1, u2, v2, a2, fs2, F, iv0, dprev, Wc, tcon, bad, Dimp;
  Peaks<V> peaks;
  Impacts<V> imp;
  Energy<V> en;
  double* nout;  // T.nout + b: onsets outside the e(v0) curve's valid range
  int lanes;     // lanes of this chunk in use (the rest pad the SIMD width)
};
template <class M> [[gnu::always_inline]] inline Chunk<M> load(const Tile& T, int b, double h) {
  using lane::load;
  Chunk<M> c;
  c.m1 = load<V>(T.m1 + b), c.m2 = load<V>(T.m2 + b), c.im1 = load<V>(T.im1 + b), c.im2 = load<V>(T.im2 + b);
  c.c1 = load<V>(T.c1 + b), c.c2 = load<V>(T.c2 + b);
  c.p1 = M::template load<V>(T, 0, b), c.p2 = M::template load<V>(T, 1, b);
  c.gap = load<V>(T.gap + b), c.kc = load<V>(T.kc + b), c.cd = load<V>(T.cd + b), c.e = load<V>(T.e + b);
  c.meff = load<V>(T.meff + b), c.msum = c.m1 + c.m2, c.h2m = V(h) * V(h) / c.meff;
  c.u1 = load<V>(T.u1 + b), c.v1 = load<V>(T.v1 + b), c.a1 = load<V>(T.a1 + b), c.fs1 = load<V>(T.fs1 + b);
  c.u2 = load<V>(T.u2 + b), c.v2 = load<V>(T.v2 + b), c.a2 = load<V>(T.a2 + b), c.fs2 = load<V>(T.fs2 + b);
  c.F = load<V>(T.F + b), c.iv0 = load<V>(T.iv0 + b), c.dprev = load<V>(T.dprev + b);
  c.Wc = load<V>(T.Wc + b), c.tcon = load<V>(T.tcon + b), c.bad = load<V>(T.bad + b), c.Dimp = load<V>(T.Dimp + b);
  c.peaks = Peaks<V>::load(T, b), c.imp = Impacts<V>::load(T, b), c.en = Energy<V>::load(T, b);
  c.nout = const_cast<double*>(T.nout) + b, c.lanes = T.n - b;
  return c;
}
template <class M> [[gnu::always_inline]] inline void store(const Chunk<M>& c, Tile& T, int b) {
  using lane::store;
  store(c.u1, T.u1 + b), store(c.v1, T.v1 + b), store(c.a1, T.a1 + b), store(c.fs1, T.fs1 + b);
  store(c.u2, T.u2 + b), store(c.v2, T.v2 + b), store(c.a2, T.a2 + b), store(c.fs2, T.fs2 + b);
  store(c.F, T.F + b), store(c.iv0, T.iv0 + b), store(c.dprev, T.dprev + b);
  store(c.Wc, T.Wc + b), store(c.tcon, T.tcon + b), store(c.bad, T.bad + b), store(c.Dimp, T.Dimp + b);
  c.peaks.store(T, b), c.imp.store(T, b), c.en.store(T, b);
}

// The step's kinematics before the forces at n+1.
struct Pred {
  V v1o, v2o, vh1, vh2, du1, du2, nu1, nu2, vp1, vp2;
};

// muthukumar eq. 2 at the located closing instant (contact::Stereomechanical::exchange).
template <class C> [[gnu::always_inline]] inline void impulsive(C& c, Pred& p, V t, V vh) {
  const V zero(0.0);
  const V d = p.nu1 - p.nu2 - c.gap, closing = p.vp1 - p.vp2;
  const simd::M hit = (d > zero) && ((closing > zero) || !(c.dprev > zero));
  if (!lane::any(hit)) return;
  const auto x = contact::Stereomechanical::exchange<V>(
      {d, c.dprev, closing, p.v1o, p.v2o, p.vp1, p.vp2, c.m1, c.m2, c.msum, c.meff, c.e, vh});
  p.nu1 += x.dv1 * x.rest, p.nu2 += x.dv2 * x.rest;
  p.du1 += x.dv1 * x.rest, p.du2 += x.dv2 * x.rest;
  p.vp1 += x.dv1, p.vp2 += x.dv2;
  p.vh1 += x.dv1, p.vh2 += x.dv2;
  c.Dimp += x.loss;
  c.imp.on_onset(t, lane::select(x.hit, V(1.0), zero));
}

// e(v0) at the onsets `on` (KernelSettings::restitution): the latched 1/v0 times the damping constant of e(v0), and
// the onsets outside the curve's valid range counted per lane (padding lanes not).
template <class C>
[[gnu::noinline]] void restitution_onset(C& c, V& iv0, simd::M on, const VelocityRestitution& r) {
  for (int j = 0; j < simd::W; ++j) {
    if (!on[j]) continue;
    const double v0 = 1.0 / iv0[j];
    iv0[j] = iv0[j] * r.damping(r.self, v0);
    if (j < c.lanes && r.outside(r.self, v0)) c.nout[j] += 1.0;
  }
}

// The contact force at n+1 (laws with a force element), the Hertzdamp latch and the stability guard.
template <class Law, class Exp, class C>
[[gnu::always_inline]] inline V contact_force(C& c, const Pred& p, V d, V& onset, V& clamp, bool& any_bad,
                                              double v0_min, Exp n, const VelocityRestitution* restitution) {
  const V zero(0.0), one(1.0);
  const V dd = p.vp1 - p.vp2;
  const simd::M on = (d > zero) && !(c.dprev > zero);
  onset = lane::select(on, one, zero);
  contact::State<V> s{c.iv0};
  if constexpr (Law::traits.latches_v0) {
    if (lane::any(on)) {  // approach velocity at the interpolated closing instant inside the step
      const V den = d - c.dprev;
      const V sc = lane::min(lane::max(-c.dprev / lane::select(den > zero, den, one), zero), one);
      const V ddo = p.v1o - p.v2o;
      Law::template on_onset<V>(s, on, ddo + sc * (dd - ddo), v0_min);
      if (restitution) [[unlikely]] restitution_onset(c, s.iv0, on, *restitution);
      c.iv0 = s.iv0;
    }
  }
  contact::Shared<V> sh{zero};
  const contact::Kin<V> k{d, dd};
  const contact::Params<V> prm{c.kc, c.cd};
  const V F = Law::template force<V>(k, prm, s, n, sh, clamp);
  const simd::M unstable = contact::unstable<Law>(k, prm, s, n, sh, c.h2m, limit2_central_difference);
  if (lane::any(unstable)) {
    c.bad = lane::max(c.bad, lane::select(unstable, one, zero));
    any_bad = true;
  }
  return F;
}

}  // namespace cd_detail

struct CentralDifference {
  static constexpr std::string_view name = "central-difference";
  static constexpr double contact_limit2 = limit2_central_difference;
  template <class Law, class Exp, bool WithEnergy, class Model = model::Registered>
  static void run(Tile& T, const Context& C, Exp n);
};

namespace cd_detail {

template <class Law, class Exp, bool WithEnergy, class M>
[[gnu::always_inline]] inline void step(Chunk<M>& c, const Context& C, long stepi, bool& any_bad, bool& force_prev, Exp n) {
  const double h = C.h, hh = 0.5 * h, ag0 = C.ag[stepi], ag1 = C.ag[stepi + 1];
  const V zero(0.0), vh(h), t(static_cast<double>(stepi + 1) * h);
  Pred p;
  p.v1o = c.v1, p.v2o = c.v2;
  p.vh1 = c.v1 + hh * c.a1, p.vh2 = c.v2 + hh * c.a2;
  p.du1 = h * p.vh1, p.du2 = h * p.vh2;
  p.nu1 = c.u1 + p.du1, p.nu2 = c.u2 + p.du2;
  p.vp1 = p.vh1 + hh * c.a1, p.vp2 = p.vh2 + hh * c.a2;
  if constexpr (Law::traits.impulsive) impulsive(c, p, t, vh);
  using S = typename Chunk<M>::S;
  const S s1{c.u1, c.fs1}, s2{c.u2, c.fs2};
  V nfs1 = M::template restoring<V>(c.p1, s1, p.nu1, p.du1), nfs2 = M::template restoring<V>(c.p2, s2, p.nu2, p.du2);
  const V d = p.nu1 - p.nu2 - c.gap;
  const simd::M touching = d > zero;
  const bool any_touch = lane::any(touching);
  V onset = zero, clamp = zero, nF = zero;
  if constexpr (Law::traits.has_force)
    if (any_touch) nF = contact_force<Law>(c, p, d, onset, clamp, any_bad, C.v0_min, n, C.settings->restitution);
  V na1 = -ag1 - (c.c1 * p.vp1 + nfs1 + nF) * c.im1;
  V na2 = -ag1 - (c.c2 * p.vp2 + nfs2 - nF) * c.im2;
  V nv1 = p.vh1 + hh * na1, nv2 = p.vh2 + hh * na2;
  if constexpr (WithEnergy)
    c.en.on_step(M::template hysteretic_increment<V>(c.p1, s1, p.du1, nfs1) +
                     M::template hysteretic_increment<V>(c.p2, s2, p.du2, nfs2),
                 {c.m1, c.c1, p.v1o, nv1}, {c.m2, c.c2, p.v2o, nv2}, ag0, ag1, V(hh));
  if constexpr (Law::traits.has_force || Law::traits.impulsive) {
    if (any_touch || force_prev) {
      c.Wc += contact_work(c.F, nF, p.du1 - p.du2);
      c.tcon += lane::select(touching, vh, zero);
      if constexpr (!Law::traits.impulsive) c.imp.on_onset(t, onset);
      c.imp.on_contact(nF, d, clamp);
    }
    force_prev = any_touch;
  }
  // (skipping the freeze while no lane is bad gives the same bits)
  const V lim(C.lim);
  if (!lane::all(within(disp_sum(p.nu1, p.nu2), rate_sum(nv1, nv2, na1, na2), lim)) || any_bad) {
    check_and_freeze<V>(c.bad, {p.nu1, p.nu2, nv1, nv2, na1, na2, nfs1, nfs2, nF}, lim);
    any_bad = true;
  }
  c.u1 = p.nu1, c.u2 = p.nu2, c.v1 = nv1, c.v2 = nv2, c.a1 = na1, c.a2 = na2, c.fs1 = nfs1, c.fs2 = nfs2, c.F = nF;
  c.dprev = d;
  c.peaks.on_step(t, c.u1, c.u2, c.a1, c.a2, V(ag1));
}

}  // namespace cd_detail

template <class Law, class Exp, bool WithEnergy, class Model>
void CentralDifference::run(Tile& T, const Context& C, Exp n) {
  static_assert(model::StructureModel<Model> && Model::dofs == 1, "the pair steppers run SDOF models");
  using cd_detail::V;
  for (int base = 0; base < T.n; base += simd::W) {
    cd_detail::Chunk<Model> c = cd_detail::load<Model>(T, base, C.h);
    const int rec_j = (C.rec && C.rec_lane >= base && C.rec_lane < base + simd::W) ? C.rec_lane - base : -1;
    bool any_bad = lane::any(c.bad > V(0.0)), force_prev = lane::any(c.F > V(0.0));
    for (long step = 0; step < C.nsteps; ++step) {
      cd_detail::step<Law, Exp, WithEnergy, Model>(c, C, step, any_bad, force_prev, n);
      if (rec_j >= 0) {
        const int j = rec_j;
        record(C.rec, {static_cast<double>(step + 1) * C.h, c.u1[j], c.u2[j], c.v1[j], c.v2[j], c.a1[j], c.a2[j],
                       c.fs1[j], c.fs2[j], c.F[j], C.ag[step + 1]});
      }
    }
    cd_detail::store(c, T, base);
  }
}

}  // namespace pounding::kernel
