#pragma once
// Classical RK4 on (u1, v1, u2, v2). The hysteretic force at a stage is the return map from the committed
// state; the Hertzdamp approach velocity is latched at the first stage that finds contact. Out of contact at
// the start of the step, the step is first taken without contact (exactly the uncoupled arithmetic, so the
// first passage is bit-identical to the uncoupled run); only a step that ends penetrating is redone with
// the contact law.
#include <algorithm>
#include <string_view>

#include "pounding/physics/steppers/scalar_common.hpp"

namespace pounding::kernel {

struct Rk4 {
  static constexpr std::string_view name = "rk4";
  static constexpr double contact_limit2 = limit2_rk4;
  template <class Law, class Exp, bool WithEnergy, class Model = model::Registered>
  static void run(Tile& T, const Context& C, Exp n);
};

namespace rk4_detail {

// Loop constants by value: a load through Context inside the lane loop may alias the tile's stores (both
// double), which keeps it in the loop, makes loop distribution version the loop on a run-time alias test
// and stops if-conversion and the vectoriser (as in Newmark).
struct K {
  double h, v0_min, lim;
  bool locate;
};
inline K constants(const Context& C) { return {C.h, C.v0_min, C.lim, C.settings->locate_contact}; }

struct Y {
  double u1, v1, u2, v2;
};

// The system of one lane within one step: springs from the committed state, the contact in one of three
// modes (0 held inactive; 1 active with the latched v0; 2 latch v0 at the first stage in contact).
template <class Law, class M, class Exp> struct Lane {
  const Tile& T;
  int i;
  double fs1o, fs2o, u1o, u2o, d_old, v0_min;
  Exp n;
  int mode = 2;
  double iv0 = 0.0;
  double stage_fmax = 0.0;  // largest contact force met at a stage (a contact can start and end in a step)

  [[gnu::always_inline]] void deriv(const Y& y, double ag, double& a1, double& a2) {
    const double fs1 = scalar::spring1<M>(T, i, fs1o, u1o, y.u1), fs2 = scalar::spring2<M>(T, i, fs2o, u2o, y.u2);
    double F = 0.0, clamp = 0.0;
    if constexpr (Law::traits.has_force) {
      const double d = y.u1 - y.u2 - T.gap[i], dd = y.v1 - y.v2;
      if (mode == 2) iv0 = scalar::latched<Law>(iv0, !(d_old > 0.0 || !(d > 0.0)), dd, v0_min);
      F = mode == 0 ? 0.0 : scalar::force<Law>(T, i, d, dd, iv0, n, clamp);
      stage_fmax = std::max(stage_fmax, F);
    }
    a1 = -ag - (T.c1[i] * y.v1 + fs1 + F) * T.im1[i];
    a2 = -ag - (T.c2[i] * y.v2 + fs2 - F) * T.im2[i];
  }

  // one classical RK4 step of length hs from y with ground acceleration agA -> agB
  [[gnu::always_inline]] Y step(const Y& y, double hs, double agA, double agB) {
    const double agM = 0.5 * (agA + agB);
    double k1a1, k1a2, k2a1, k2a2, k3a1, k3a2, k4a1, k4a2;
    deriv(y, agA, k1a1, k1a2);
    const double k1u1 = y.v1, k1u2 = y.v2;
    const double k2u1 = y.v1 + 0.5 * hs * k1a1, k2u2 = y.v2 + 0.5 * hs * k1a2;
    deriv({y.u1 + 0.5 * hs * k1u1, k2u1, y.u2 + 0.5 * hs * k1u2, k2u2}, agM, k2a1, k2a2);
    const double k3u1 = y.v1 + 0.5 * hs * k2a1, k3u2 = y.v2 + 0.5 * hs * k2a2;
    deriv({y.u1 + 0.5 * hs * k2u1, k3u1, y.u2 + 0.5 * hs * k2u2, k3u2}, agM, k3a1, k3a2);
    const double k4u1 = y.v1 + hs * k3a1, k4u2 = y.v2 + hs * k3a2;
    deriv({y.u1 + hs * k3u1, k4u1, y.u2 + hs * k3u2, k4u2}, agB, k4a1, k4a2);
    Y r;
    r.u1 = y.u1 + hs / 6.0 * (k1u1 + 2.0 * k2u1 + 2.0 * k3u1 + k4u1);
    r.u2 = y.u2 + hs / 6.0 * (k1u2 + 2.0 * k2u2 + 2.0 * k3u2 + k4u2);
    r.v1 = y.v1 + hs / 6.0 * (k1a1 + 2.0 * k2a1 + 2.0 * k3a1 + k4a1);
    r.v2 = y.v2 + hs / 6.0 * (k1a2 + 2.0 * k2a2 + 2.0 * k3a2 + k4a2);
    return r;
  }

  // Event-located contact onset: the closing instant on the step's cubic Hermite interpolant of delta;
  // integrate up to it without contact, latch v0 there, and finish the step in contact. Inlined although
  // rare: an out-of-line call takes the Lane's address, which keeps the Lane in memory in every lane step.
  [[gnu::always_inline]] Y located(const Y& yo, const Y& yn, double h, double ag0, double ag1) {
    const double dn = yn.u1 - yn.u2 - T.gap[i], ddo = yo.v1 - yo.v2, ddn = yn.v1 - yn.v2;
    auto delta = [&](double s) {
      double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * d_old + (s3 - 2 * s2 + s) * h * ddo + (-2 * s3 + 3 * s2) * dn +
             (s3 - s2) * h * ddn;
    };
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 60; ++it) {
      double mid = 0.5 * (lo + hi);
      (delta(mid) > 0.0 ? hi : lo) = mid;
    }
    const double sc = 0.5 * (lo + hi), agc = ag0 + sc * (ag1 - ag0);
    mode = 0;
    const Y c = step(yo, sc * h, ag0, agc);
    iv0 = scalar::latched<Law>(iv0, true, c.v1 - c.v2, v0_min);
    mode = 1;
    return step(c, (1.0 - sc) * h, agc, ag1);
  }
};

// One lane's step: the integration (with the redo or the located onset), then the commit.
template <class Law, class M, class Exp, bool WithEnergy>
[[gnu::always_inline]] inline void lane_step(Tile& T, int i, const K& C, double t, double ag0, double ag1, Exp n) {
  const double h = C.h;
  const scalar::Old o = scalar::old_state(T, i);
  const double d_old = T.dprev[i];
  Lane<Law, M, Exp> L{T, i, o.fs1, o.fs2, o.u1, o.u2, d_old, C.v0_min, n};
  L.iv0 = T.iv0[i];
  const Y yo{o.u1, o.v1, o.u2, o.v2};
  L.mode = d_old > 0.0 ? 2 : 0;
  Y y = L.step(yo, h, ag0, ag1);
  bool redone = false;
  if constexpr (Law::traits.has_force) {
    const double dn = y.u1 - y.u2 - T.gap[i];
    redone = !(d_old > 0.0) && dn > 0.0;
    if (redone && !C.locate) {
      L.mode = 2;
      y = L.step(yo, h, ag0, ag1);
    } else if (redone) {
      y = L.located(yo, y, h, ag0, ag1);
    }
  }
  T.u1[i] = y.u1, T.v1[i] = y.v1, T.u2[i] = y.u2, T.v2[i] = y.v2;
  double onset = 0.0, clamp = 0.0, F = 0.0;
  if constexpr (Law::traits.impulsive) onset = scalar::impulsive(T, i, h, o.v1, o.v2, d_old);
  T.fs1[i] = scalar::spring1<M>(T, i, o.fs1, o.u1, T.u1[i]);
  T.fs2[i] = scalar::spring2<M>(T, i, o.fs2, o.u2, T.u2[i]);
  const double d = T.u1[i] - T.u2[i] - T.gap[i], dd = T.v1[i] - T.v2[i];
  if constexpr (Law::traits.has_force) {
    onset = ((d > 0.0 || redone) && !(d_old > 0.0)) ? 1.0 : 0.0;  // redone: touched inside the step
    if constexpr (Law::traits.latches_v0) T.iv0[i] = d_old > 0.0 ? T.iv0[i] : L.iv0;
    contact::Shared<double> sh{0.0};
    F = scalar::force<Law>(T, i, d, dd, T.iv0[i], n, clamp, sh);
    scalar::guard_contact<Law>(T, i, d, dd, n, sh, h, limit2_rk4);
    T.pF[i] = std::max(T.pF[i], L.stage_fmax);
  }
  scalar::end_step<M, WithEnergy>(T, i, h, t, ag0, ag1, o, F, d, clamp, onset, C.lim);
}

}  // namespace rk4_detail

template <class Law, class Exp, bool WithEnergy, class Model>
void Rk4::run(Tile& T, const Context& C, Exp n) {
  static_assert(model::StructureModel<Model> && Model::dofs == 1, "the pair steppers run SDOF models");
  const rk4_detail::K k = rk4_detail::constants(C);
  for (long step = 0; step < C.nsteps; ++step) {
    const double ag0 = C.ag[step], ag1 = C.ag[step + 1];
    const double t = static_cast<double>(step + 1) * C.h;
    const int np = T.np;
    for (int i = 0; i < np; ++i) rk4_detail::lane_step<Law, Model, Exp, WithEnergy>(T, i, k, t, ag0, ag1, n);
    record_lane(C, T, t, ag1);
  }
}

}  // namespace pounding::kernel
