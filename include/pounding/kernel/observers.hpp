#pragma once
// Per-lane reductions of a run, written once for both lane types: each accumulator is loaded from the
// tile at the start of a chunk (SIMD) or a lane step (scalar), updated by on_step and stored back.
// Energy is a compile-time choice (Energy<false> compiles to nothing).
#include "pounding/kernel/lane.hpp"
#include "pounding/kernel/tile.hpp"

namespace pounding::kernel {

// Motion peaks: |u|, the closing u1 - u2 and when, |absolute acceleration|.
template <class T> struct Peaks {
  T pu1, pu2, pclose, tpclose, pa1, pa2;
  POUNDING_INLINE static Peaks load(const Tile& t, int i) {
    using lane::load;
    return {load<T>(t.pu1 + i), load<T>(t.pu2 + i), load<T>(t.pclose + i),
            load<T>(t.tpclose + i), load<T>(t.pa1 + i), load<T>(t.pa2 + i)};
  }
  POUNDING_INLINE void store(Tile& t, int i) const {
    lane::store(pu1, t.pu1 + i), lane::store(pu2, t.pu2 + i), lane::store(pclose, t.pclose + i);
    lane::store(tpclose, t.tpclose + i), lane::store(pa1, t.pa1 + i), lane::store(pa2, t.pa2 + i);
  }
  POUNDING_INLINE void on_step(T t, T u1, T u2, T a1, T a2, T ag) {
    pu1 = lane::max(pu1, lane::abs(u1));
    pu2 = lane::max(pu2, lane::abs(u2));
    const T cl = u1 - u2;
    const auto up = cl > pclose;
    pclose = lane::select(up, cl, pclose);
    tpclose = lane::select(up, t, tpclose);
    pa1 = lane::max(pa1, lane::abs(a1 + ag));
    pa2 = lane::max(pa2, lane::abs(a2 + ag));
  }
};

// Contact reductions: first impact, impact and clamp counts, peak force and penetration.
template <class T> struct Impacts {
  T tfirst, nimp, nclamp, pF, ppen;
  POUNDING_INLINE static Impacts load(const Tile& t, int i) {
    using lane::load;
    return {load<T>(t.tfirst + i), load<T>(t.nimp + i), load<T>(t.nclamp + i), load<T>(t.pF + i), load<T>(t.ppen + i)};
  }
  POUNDING_INLINE void store(Tile& t, int i) const {
    lane::store(tfirst, t.tfirst + i), lane::store(nimp, t.nimp + i), lane::store(nclamp, t.nclamp + i);
    lane::store(pF, t.pF + i), lane::store(ppen, t.ppen + i);
  }
  // onset: 1 where a contact (or an impulsive impact) started in this step
  POUNDING_INLINE void on_onset(T t, T onset) {
    tfirst = lane::min(tfirst, lane::select(onset > T(0.0), t, T(inf)));
    nimp += onset;
  }
  POUNDING_INLINE void on_contact(T F, T d, T clamp) {
    nclamp += clamp;
    pF = lane::max(pF, F);
    ppen = lane::max(ppen, d);
  }
};

// Contact work (trapezoidal in displacement) and time in contact.
template <class T> POUNDING_INLINE T contact_work(T F_old, T F, T drel) { return 0.5 * (F_old + F) * drel; }

// Energy terms: input, viscous, hysteretic (exact plastic dissipation), impulsive losses.
template <bool On> struct EnergyTerms {
  static constexpr bool enabled = On;
};
template <class T> struct Energy {
  T Ein, Evis, Ehys;
  POUNDING_INLINE static Energy load(const Tile& t, int i) {
    return {lane::load<T>(t.Ein + i), lane::load<T>(t.Evis + i), lane::load<T>(t.Ehys + i)};
  }
  POUNDING_INLINE void store(Tile& t, int i) const {
    lane::store(Ein, t.Ein + i), lane::store(Evis, t.Evis + i), lane::store(Ehys, t.Ehys + i);
  }
  // excess = trial - returned spring force; hh = h / 2; o: start of the step, n: end
  struct Body { T m, c, qy, kp, excess, vo, vn; };
  // Ein -= hh (m1 (ag0 vo1 + ag1 vn1) + m2 (ag0 vo2 + ag1 vn2)), Evis += hh (c1 (vo1^2 + vn1^2) + c2 (...)),
  // with every contraction pinned to the one GCC picks in central difference's SIMD chunk (each sum of two
  // products fuses its second product, the outer update fuses hh): the same bits at both lane types, and
  // CD's digests unchanged (the scalar steppers had fused the first products and not hh).
  POUNDING_INLINE void on_step(const Body& b1, const Body& b2, double ag0, double ag1, T hh) {
    on_step(b1.qy * lane::abs(b1.excess) / b1.kp + b2.qy * lane::abs(b2.excess) / b2.kp, {b1.m, b1.c, b1.vo, b1.vn},
            {b2.m, b2.c, b2.vo, b2.vn}, ag0, ag1, hh);
  }
  // The same with the structures' hysteretic increment of the step already summed (model::StructureModel).
  struct Motion { T m, c, vo, vn; };
  POUNDING_INLINE void on_step(T dhys, const Motion& b1, const Motion& b2, double ag0, double ag1, T hh) {
    Ehys += dhys;
    const T g0(ag0), g1(ag1);
    const T in1 = lane::fma(g1, b1.vn, g0 * b1.vo), in2 = lane::fma(g1, b2.vn, g0 * b2.vo);
    Ein = lane::fma(-hh, lane::fma(b2.m, in2, b1.m * in1), Ein);
    const T sq1 = lane::fma(b1.vn, b1.vn, b1.vo * b1.vo), sq2 = lane::fma(b2.vn, b2.vn, b2.vo * b2.vo);
    Evis = lane::fma(hh, lane::fma(b2.c, sq2, b1.c * sq1), Evis);
  }
};

// One lane's state after a step, for `pounding simulate --series`.
struct SeriesPoint {
  double t, u1, u2, v1, v2, a1, a2, fs1, fs2, F, ag;
};
inline void record(SeriesRecorder* rec, const SeriesPoint& p) {
  rec->t.push_back(p.t);
  rec->u1.push_back(p.u1);
  rec->u2.push_back(p.u2);
  rec->v1.push_back(p.v1);
  rec->v2.push_back(p.v2);
  rec->a1_abs.push_back(p.a1 + p.ag);
  rec->a2_abs.push_back(p.a2 + p.ag);
  rec->fs1.push_back(p.fs1);
  rec->fs2.push_back(p.fs2);
  rec->force.push_back(p.F);
  rec->ag.push_back(p.ag);
}
inline void record_lane(const Context& C, const Tile& T, double t, double ag) {
  if (!C.rec) return;
  const int i = C.rec_lane;
  record(C.rec, {t, T.u1[i], T.u2[i], T.v1[i], T.v2[i], T.a1[i], T.a2[i], T.fs1[i], T.fs2[i], T.F[i], ag});
}

}  // namespace pounding::kernel
