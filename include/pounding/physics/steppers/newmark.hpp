#pragma once
// Newmark average acceleration (gamma = 1/2, beta = 1/4) with Newton iterations on the coupled 2-DOF
// residual; the 2x2 tangent is solved in closed form. Each lane stops iterating when its own increment is
// below tolerance, so its result does not depend on the other lanes.
//
// Contact is handled as an active set: each lane first solves with its contact state from the start of the
// step (inactive unless already penetrating); if the converged state contradicts it (penetration without
// force, or a force that should be zero), the lane switches and solves again (at most 4 passes). An inactive
// lane does exactly the uncoupled arithmetic, so before the first impact the coupled run is bit-identical to
// the uncoupled one, and the kinks of the gated/clamped laws never meet Newton.
#include <algorithm>
#include <cmath>
#include <string_view>

#include "pounding/physics/steppers/scalar_common.hpp"

namespace pounding::kernel {

struct Newmark {
  static constexpr std::string_view name = "newmark";
  template <class Law, class Exp, bool WithEnergy, class Model = model::Registered>
  static void run(Tile& T, const Context& C, Exp n);
};

namespace newmark_detail {

// Loop constants by value: a load through Context inside a lane loop may alias the tile's stores and
// stops the vectoriser (and with it the kernel's established FMA contraction).
struct K {
  double h, c4, c2, tol, v0_min, lim;
  int maxit;
};
inline K constants(const Context& C) {
  return {C.h, 4.0 / (C.h * C.h), 2.0 / C.h, C.settings->newton_tol, C.v0_min, C.lim, C.settings->newton_max_iter};
}

// One Newton iteration of lane i at the iterate (x1, x2); returns true when the lane is converged.
template <class Law, class M, class Exp>
[[gnu::always_inline]] inline bool newton_update(Tile& T, int i, const K& C, double ag1, Exp n) {
  const double h = C.h, c4 = C.c4, c2 = C.c2;
  const double u1 = T.x1[i], u2 = T.x2[i];
  const double a1 = c4 * (u1 - T.u1[i]) - 4.0 / h * T.v1[i] - T.a1[i];
  const double a2 = c4 * (u2 - T.u2[i]) - 4.0 / h * T.v2[i] - T.a2[i];
  const double v1 = c2 * (u1 - T.u1[i]) - T.v1[i];
  const double v2 = c2 * (u2 - T.u2[i]) - T.v2[i];
  const auto p1 = M::template load<double>(T, 0, i), p2 = M::template load<double>(T, 1, i);
  const typename M::template State<double> s1{T.u1[i], T.fs1[i]}, s2{T.u2[i], T.fs2[i]};
  const double fs1 = M::template restoring<double>(p1, s1, u1, u1 - T.u1[i]);
  const double fs2 = M::template restoring<double>(p2, s2, u2, u2 - T.u2[i]);
  const double kt1 = M::template tangent<double>(p1, s1, u1, u1 - T.u1[i], fs1);
  const double kt2 = M::template tangent<double>(p2, s2, u2, u2 - T.u2[i], fs2);
  const double d = u1 - u2 - T.gap[i], dd = v1 - v2;
  contact::Tangent<double> tg{0.0, 0.0, 0.0};
  if constexpr (Law::traits.has_force) {
    if (T.y1[i] > 0.0) {  // the latch (a division) only in the active lanes
      const double iv0 = scalar::latched<Law>(T.iv0[i], !(T.dprev[i] > 0.0), dd, C.v0_min);
      tg = Law::template tangent<double>({d, dd}, {T.kc[i], T.cd[i]}, {iv0}, n);
    }
  }
  const double r1 = T.m1[i] * (a1 + ag1) + T.c1[i] * v1 + fs1 + tg.F;
  const double r2 = T.m2[i] * (a2 + ag1) + T.c2[i] * v2 + fs2 - tg.F;
  const double kc_ = tg.dFd + c2 * tg.dFv;
  const double j11 = c4 * T.m1[i] + c2 * T.c1[i] + kt1 + kc_;
  const double j22 = c4 * T.m2[i] + c2 * T.c2[i] + kt2 + kc_;
  const double j12 = -kc_;
  const double det = j11 * j22 - j12 * j12;
  const double du1 = (j22 * r1 - j12 * r2) / det;
  const double du2 = (j11 * r2 - j12 * r1) / det;
  const bool done = T.conv[i] > 0.0;
  T.x1[i] = done ? u1 : u1 - du1;
  T.x2[i] = done ? u2 : u2 - du2;
  // relative increment, with an absolute floor far above round-off of decayed motion (1e-15 m)
  const double scale = std::abs(u1) + std::abs(u2);
  const bool ok = (std::abs(du1) + std::abs(du2)) <= C.tol * scale + 1e-19;
  T.conv[i] = (done || ok) ? 1.0 : 0.0;
  return T.conv[i] > 0.0;
}

// After a pass: the lanes whose converged state contradicts their contact state switch. Returns the count.
template <class Law, class Exp>
[[gnu::always_inline]] inline double switch_active(Tile& T, const K& C, Exp n) {
  const double c2 = C.c2;
  double switched = 0.0;
  const int np = T.np;
  for (int i = 0; i < np; ++i) {
    T.y2[i] = T.conv[i] > 0.0 ? T.y2[i] : 0.0;
    const double u1 = T.x1[i], u2 = T.x2[i];
    const double v1 = c2 * (u1 - T.u1[i]) - T.v1[i], v2 = c2 * (u2 - T.u2[i]) - T.v2[i];
    const double d = u1 - u2 - T.gap[i], dd = v1 - v2;
    double clamp = 0.0;
    const double iv0 = scalar::latched<Law>(T.iv0[i], !(T.dprev[i] > 0.0), dd, C.v0_min);
    const double want = scalar::force<Law>(T, i, d, dd, iv0, n, clamp) > 0.0 ? 1.0 : 0.0;
    // activate at most once per step; a lane that flips back (grazing, or separating under a clamped
    // force) keeps the inactive solution, whose penetration is then counted and its force committed
    const bool sw = want != T.y1[i] && (want == 0.0 || T.sw[i] == 0.0);
    T.sw[i] += sw ? 1.0 : 0.0;
    T.y1[i] = sw ? want : T.y1[i];
    T.conv[i] = sw ? 0.0 : T.conv[i];
    switched += sw ? 1.0 : 0.0;
  }
  return switched;
}

template <class Law, class M, class Exp> void solve(Tile& T, const K C, double ag1, Exp n) {
  const double h = C.h;
  const int np = T.np;
  for (int i = 0; i < np; ++i) {  // predictor: constant acceleration
    T.x1[i] = T.u1[i] + h * T.v1[i] + 0.5 * h * h * T.a1[i];
    T.x2[i] = T.u2[i] + h * T.v2[i] + 0.5 * h * h * T.a2[i];
    T.conv[i] = 0.0;
    T.y1[i] = T.dprev[i] > 0.0 ? 1.0 : 0.0;  // active
    T.y2[i] = 1.0;                           // Newton converged in every pass so far
    T.sw[i] = 0.0;                           // switches so far
  }
  for (int pass = 0; pass < 4; ++pass) {
    for (int it = 0; it < C.maxit; ++it) {
      double open = 0.0;
      for (int i = 0; i < np; ++i) open += newton_update<Law, M>(T, i, C, ag1, n) ? 0.0 : 1.0;
      if (open == 0.0) break;
    }
    if constexpr (!Law::traits.has_force) break;
    if (switch_active<Law>(T, C, n) == 0.0) break;
  }
}

// Commits lane i's converged iterate, applies the contact, the guard and the observers.
template <class Law, class M, class Exp, bool WithEnergy>
[[gnu::always_inline]] inline void commit(Tile& T, int i, const K& C, double t, double ag0, double ag1, Exp n) {
  const double h = C.h, c4 = C.c4, c2 = C.c2;
  const scalar::Old o = scalar::old_state(T, i);
  const double u1 = T.x1[i], u2 = T.x2[i];
  // c4 du - (4/h) v as fms(c4, du, (4/h) v): the contraction the kernel had before the redesign. Left to GCC,
  // tree sinking moves these lines into the impulsive law's branches and the other product gets fused, which
  // broke first passage for stereomechanical (in the Newton update GCC keeps fusing (4/h) v, as it always did).
  const double a1 = std::fma(c4, u1 - o.u1, -(4.0 / h * o.v1)) - T.a1[i];
  const double a2 = std::fma(c4, u2 - o.u2, -(4.0 / h * o.v2)) - T.a2[i];
  const double v1 = c2 * (u1 - o.u1) - o.v1, v2 = c2 * (u2 - o.u2) - o.v2;
  T.fs1[i] = scalar::spring1<M>(T, i, o.fs1, o.u1, u1);
  T.fs2[i] = scalar::spring2<M>(T, i, o.fs2, o.u2, u2);
  T.u1[i] = u1, T.u2[i] = u2, T.v1[i] = v1, T.v2[i] = v2, T.a1[i] = a1, T.a2[i] = a2;
  const double d_old = T.dprev[i];
  double d = u1 - u2 - T.gap[i];
  const double dd = v1 - v2;
  double onset = 0.0, clamp = 0.0, F = 0.0;
  if constexpr (Law::traits.impulsive) {
    onset = scalar::impulsive(T, i, h, o.v1, o.v2, d_old);
    // the velocity jump changes the accelerations' history: restart Newmark from the new velocities
    T.a1[i] = onset > 0.0 ? -ag1 - (T.c1[i] * T.v1[i] + T.fs1[i]) * T.im1[i] : a1;
    T.a2[i] = onset > 0.0 ? -ag1 - (T.c2[i] * T.v2[i] + T.fs2[i]) * T.im2[i] : a2;
    d = T.u1[i] - T.u2[i] - T.gap[i];
  } else if constexpr (Law::traits.has_force) {
    onset = (d > 0.0 && !(d_old > 0.0)) ? 1.0 : 0.0;
    T.iv0[i] = scalar::latched<Law>(T.iv0[i], onset > 0.0, dd, C.v0_min);
    F = scalar::force<Law>(T, i, d, dd, T.iv0[i], n, clamp);
  }
  // a lane whose Newton iteration did not converge is marked diverged
  T.bad[i] = std::max(T.bad[i], (T.conv[i] > 0.0 && T.y2[i] > 0.0) ? 0.0 : 1.0);
  // Newmark keeps its own accelerations (the average-acceleration update above)
  scalar::end_step<M, WithEnergy, false>(T, i, h, t, ag0, ag1, o, F, d, clamp, onset, C.lim);
}

}  // namespace newmark_detail

template <class Law, class Exp, bool WithEnergy, class Model>
void Newmark::run(Tile& T, const Context& C, Exp n) {
  static_assert(model::StructureModel<Model> && Model::dofs == 1, "the pair steppers run SDOF models");
  const newmark_detail::K k = newmark_detail::constants(C);
  for (long step = 0; step < C.nsteps; ++step) {
    const double ag0 = C.ag[step], ag1 = C.ag[step + 1];
    const double t = static_cast<double>(step + 1) * C.h;
    newmark_detail::solve<Law, Model>(T, k, ag1, n);
    const int np = T.np;
    for (int i = 0; i < np; ++i) newmark_detail::commit<Law, Model, Exp, WithEnergy>(T, i, k, t, ag0, ag1, n);
    record_lane(C, T, t, ag1);
  }
}

}  // namespace pounding::kernel
