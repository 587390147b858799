#pragma once
// Nigam-Jennings: each structure's linear part (m, k, c; k the model's linear_stiffness) is advanced with the
// exact recurrence for a piecewise-linear load; the nonlinear remainder g = (fs - k u) + F (contact) enters as an extra load,
// held at g_n (predictor) and then linear from g_n to g(n+1) predicted (corrector). With an elastic
// structure out of contact g = 0 and the step is exact to round-off. The coefficients (Tile::nj1, nj2)
// come from nigam_jennings() (kernel.hpp).
#include <algorithm>
#include <string_view>

#include "pounding/physics/steppers/scalar_common.hpp"

namespace pounding::kernel {

struct NigamJennings {
  static constexpr std::string_view name = "nigam-jennings";
  static constexpr double contact_limit2 = limit2_nigam_jennings;
  static constexpr bool needs_coefficients = true;
  template <class Law, class Exp, bool WithEnergy, class Model = model::Registered>
  static void run(Tile& T, const Context& C, Exp n);
};

namespace nj_detail {

// Loop constants by value: a load through Context inside the lane loop may alias the tile's stores (both
// double), which keeps it in the loop and stops if-conversion and the vectoriser (as in Newmark and RK4).
struct K {
  double h, v0_min, lim;
};
inline K constants(const Context& C) { return {C.h, C.v0_min, C.lim}; }

[[gnu::always_inline]] inline void advance(const double (*c)[tile_width], int i, double u, double v, double pa,
                                           double pb, double& un, double& vn) {
  un = c[0][i] * u + c[1][i] * v + c[4][i] * pa + c[5][i] * pb;
  vn = c[2][i] * u + c[3][i] * v + c[6][i] * pa + c[7][i] * pb;
}

// Predictor, then the corrector (again with contact when the step ends penetrating); returns the
// corrector's contact force. `redone`: the step touched although it started out of contact.
template <class Law, class M, class Exp>
[[gnu::always_inline]] inline double integrate(Tile& T, int i, const K& C, double ag0, double ag1,
                                               const scalar::Old& o, Exp n, bool& redone) {
  const double d_old = T.dprev[i];
  // load in acceleration units: u'' + 2 zeta w u' + w^2 u = -(ag + g/m)
  const double kl1 = M::template linear_stiffness<double>(M::template load<double>(T, 0, i));
  const double kl2 = M::template linear_stiffness<double>(M::template load<double>(T, 1, i));
  const double p1o = ag0 + (o.fs1 - kl1 * o.u1 + o.F) * T.im1[i];
  const double p2o = ag0 + (o.fs2 - kl2 * o.u2 - o.F) * T.im2[i];
  double u1p, v1p, u2p, v2p;
  advance(T.nj1, i, o.u1, o.v1, p1o, ag1 - ag0 + p1o, u1p, v1p);
  advance(T.nj2, i, o.u2, o.v2, p2o, ag1 - ag0 + p2o, u2p, v2p);
  // corrector with the remainder evaluated at the predicted end state
  const double fs1p = scalar::spring1<M>(T, i, o.fs1, o.u1, u1p), fs2p = scalar::spring2<M>(T, i, o.fs2, o.u2, u2p);
  double Fp = 0.0;
  auto correct = [&](bool with_contact) {
    Fp = 0.0;
    if constexpr (Law::traits.has_force) {
      if (with_contact) {
        const double d = u1p - u2p - T.gap[i], dd = v1p - v2p;
        double clamp = 0.0;
        const double iv0 = scalar::latched<Law>(T.iv0[i], !(d_old > 0.0), dd, C.v0_min);
        Fp = scalar::force<Law>(T, i, d, dd, iv0, n, clamp);
      }
    }
    const double p1n = ag1 + (fs1p - kl1 * u1p + Fp) * T.im1[i];
    const double p2n = ag1 + (fs2p - kl2 * u2p - Fp) * T.im2[i];
    advance(T.nj1, i, o.u1, o.v1, p1o, p1n, T.u1[i], T.v1[i]);
    advance(T.nj2, i, o.u2, o.v2, p2o, p2n, T.u2[i], T.v2[i]);
  };
  // Out of contact at the start: correct without contact first (the uncoupled arithmetic); a step that
  // ends penetrating is corrected again with the contact force at the predicted state.
  correct(d_old > 0.0);
  redone = !(d_old > 0.0) && T.u1[i] - T.u2[i] - T.gap[i] > 0.0;
  if (redone) correct(true);
  return Fp;
}

template <class Law, class M, class Exp, bool WithEnergy>
[[gnu::always_inline]] inline void lane_step(Tile& T, int i, const K& C, double t, double ag0, double ag1, Exp n) {
  const double h = C.h;
  const scalar::Old o = scalar::old_state(T, i);
  const double d_old = T.dprev[i];
  bool redone = false;
  const double corrector_force = integrate<Law, M>(T, i, C, ag0, ag1, o, n, redone);
  double onset = 0.0, F = 0.0, clamp = 0.0;
  if constexpr (Law::traits.impulsive) onset = scalar::impulsive(T, i, h, o.v1, o.v2, d_old);
  T.fs1[i] = scalar::spring1<M>(T, i, o.fs1, o.u1, T.u1[i]);
  T.fs2[i] = scalar::spring2<M>(T, i, o.fs2, o.u2, T.u2[i]);
  const double d = T.u1[i] - T.u2[i] - T.gap[i], dd = T.v1[i] - T.v2[i];
  if constexpr (Law::traits.has_force) {
    // redone: touched inside the step. One bool for both uses, with & and | (no short-circuit): tested
    // again as onset > 0.0, GCC threads the latch through it into a select between masks, which the
    // vectoriser emulates lane by lane.
    const bool on = ((d > 0.0) | redone) & !(d_old > 0.0);
    onset = on ? 1.0 : 0.0;
    T.iv0[i] = scalar::latched<Law>(T.iv0[i], on, dd, C.v0_min);
    contact::Shared<double> sh{0.0};
    F = scalar::force<Law>(T, i, d, dd, T.iv0[i], n, clamp, sh);
    scalar::guard_contact<Law>(T, i, d, dd, n, sh, h, limit2_nigam_jennings);
    T.pF[i] = std::max(T.pF[i], corrector_force);
  }
  scalar::end_step<M, WithEnergy>(T, i, h, t, ag0, ag1, o, F, d, clamp, onset, C.lim);
}

}  // namespace nj_detail

template <class Law, class Exp, bool WithEnergy, class Model>
void NigamJennings::run(Tile& T, const Context& C, Exp n) {
  static_assert(model::StructureModel<Model> && Model::dofs == 1, "the pair steppers run SDOF models");
  const nj_detail::K k = nj_detail::constants(C);
  for (long step = 0; step < C.nsteps; ++step) {
    const double ag0 = C.ag[step], ag1 = C.ag[step + 1];
    const double t = static_cast<double>(step + 1) * C.h;
    const int np = T.np;
    for (int i = 0; i < np; ++i) nj_detail::lane_step<Law, Model, Exp, WithEnergy>(T, i, k, t, ag0, ag1, n);
    record_lane(C, T, t, ag1);
  }
}

}  // namespace pounding::kernel
