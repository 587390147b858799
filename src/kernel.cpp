// The batch time-history kernel. Lanes are processed in tiles of up to `tile_width` pairs; inside a tile
// the time loop is outer and the lane loop inner, written branch-free over plain arrays so that the
// compiler vectorises it (check with -fopt-info-vec: the lane loops of every step_* function vectorise).
// Every lane's arithmetic depends only on its own inputs, so a lane's result is bit-identical whatever the
// batch width or its position in the batch.
#include "pounding/kernel.hpp"

#include <algorithm>
#include <cmath>
#include <experimental/simd>
#include <memory>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "pounding/core/error.hpp"

namespace pounding {

namespace {

namespace stdx = std::experimental;

constexpr int tile_width = 64;
constexpr double inf = std::numeric_limits<double>::infinity();
// Internal stand-in for an infinite yield force: finite so that qy * 0 == 0 in the dissipation sum.
constexpr double elastic_qy = 1e300;

struct StepperName {
  Stepper s;
  std::string_view name;
};
constexpr StepperName stepper_table[] = {
    {Stepper::central_difference, "central-difference"},
    {Stepper::newmark, "newmark"},
    {Stepper::rk4, "rk4"},
    {Stepper::nigam_jennings, "nigam-jennings"},
};

// One tile of lanes: derived constants, state, observers. Members are distinct arrays, so the
// compiler knows they do not alias.
struct alignas(64) Tile {
  int n = 0;   // lanes in use
  int np = 0;  // lanes padded to the SIMD width (copies of the first lane): the array steppers run all of them,
               // so every lane goes through the same vector code whatever the batch width
  // constants
  double m1[tile_width], m2[tile_width], im1[tile_width], im2[tile_width];
  double k1[tile_width], k2[tile_width], c1[tile_width], c2[tile_width];
  double ak1[tile_width], ak2[tile_width];    // alpha k
  double qy1[tile_width], qy2[tile_width];    // (1 - alpha) fy: half-width of the kinematic band
  double kp1[tile_width], kp2[tile_width];    // (1 - alpha) k: stiffness of the elasto-plastic part
  double gap[tile_width], kc[tile_width], cd[tile_width], e[tile_width], meff[tile_width];
  // state
  double u1[tile_width], v1[tile_width], a1[tile_width], fs1[tile_width];
  double u2[tile_width], v2[tile_width], a2[tile_width], fs2[tile_width];
  double F[tile_width], v0[tile_width], dprev[tile_width];
  // observers
  double pu1[tile_width], pu2[tile_width], pclose[tile_width], tpclose[tile_width], tfirst[tile_width];
  double nimp[tile_width], nclamp[tile_width], pF[tile_width], ppen[tile_width], Wc[tile_width];
  double tcon[tile_width], pa1[tile_width], pa2[tile_width], bad[tile_width];
  // energy
  double Ein[tile_width], Evis[tile_width], Ehys[tile_width], Dimp[tile_width];
  // scratch (Newton iterates, RK4 stages, NJ coefficients)
  double x1[tile_width], x2[tile_width], y1[tile_width], y2[tile_width], conv[tile_width], sw[tile_width];
  double nj1[8][tile_width], nj2[8][tile_width];
};

// Bilinear kinematic hardening, closed-form return (branch-free): the trial force fs + k du is
// clamped into the band alpha k u +/- (1 - alpha) fy (issue #2; exact for a monotone increment).
[[gnu::always_inline]] inline double bilinear(double fs_old, double k, double du, double ak_u_new, double qy) {
  double trial = fs_old + k * du;
  return std::min(std::max(trial, ak_u_new - qy), ak_u_new + qy);
}

// Contact force for penetration d and rate dd; `clamp` is set to 1 when a tensile value was clamped.
template <ContactLaw L, bool N15>
[[gnu::always_inline]] inline double contact_force(double d, double dd, double kc, double cd, double v0, double n, double& clamp) {
  double dp = d > 0.0 ? d : 0.0;
  clamp = 0.0;
  if constexpr (L == ContactLaw::linear) {
    return kc * dp;  // muthukumar eq. 3
  } else if constexpr (L == ContactLaw::kelvin) {
    double raw = kc * dp + cd * dd;  // impact-stiffness paper eq. 1-3
    double f = d > 0.0 ? raw : 0.0;
    clamp = f < 0.0 ? 1.0 : 0.0;
    return f > 0.0 ? f : 0.0;
  } else if constexpr (L == ContactLaw::hertz || L == ContactLaw::hertzdamp || L == ContactLaw::jankowski) {
    double pw;
    if constexpr (N15 || L == ContactLaw::jankowski)
      pw = dp * std::sqrt(dp);
    else
      pw = dp > 0.0 ? std::pow(dp, n) : 0.0;
    if constexpr (L == ContactLaw::hertz) {
      return kc * pw;  // muthukumar eq. 6
    } else if constexpr (L == ContactLaw::hertzdamp) {
      const double iv0 = 1.0 / v0;  // the reciprocal, as the SIMD path (P6)
      double raw = kc * pw * (1.0 + cd * dd * iv0);  // muthukumar eq. 10 with xibar = cd
      clamp = raw < 0.0 ? 1.0 : 0.0;
      return raw > 0.0 ? raw : 0.0;
    } else {
      // rc-buildings eqs 4-5: c_h = 2 zeta sqrt(kh sqrt(delta) meff) = cd delta^(1/4), approach only
      double damp = dd > 0.0 ? cd * std::sqrt(std::sqrt(dp)) * dd : 0.0;
      return kc * pw + damp;
    }
  } else {
    return 0.0;  // none, stereomechanical
  }
}

// The contact law as Newton sees it while the contact is active: linear and Kelvin without the d > 0 gate,
// Hertzdamp without the clamp, so that the residual is smooth; the active-set passes decide activity.
template <ContactLaw L, bool N15>
[[gnu::always_inline]] inline void contact_force_raw(double d, double dd, double kc, double cd, double v0, double n,
                                                     double& F, double& dFd, double& dFv) {
  if constexpr (L == ContactLaw::linear) {
    F = kc * d, dFd = kc, dFv = 0.0;
  } else if constexpr (L == ContactLaw::kelvin) {
    F = kc * d + cd * dd, dFd = kc, dFv = cd;
  } else if constexpr (L == ContactLaw::hertz || L == ContactLaw::hertzdamp || L == ContactLaw::jankowski) {
    double dp = d > 0.0 ? d : 0.0;
    double nn = (N15 || L == ContactLaw::jankowski) ? 1.5 : n;
    double pw = dp > 0.0 ? std::pow(dp, nn) : 0.0, dpw = dp > 0.0 ? nn * std::pow(dp, nn - 1.0) : 0.0;
    if constexpr (L == ContactLaw::hertz) {
      F = kc * pw, dFd = kc * dpw, dFv = 0.0;
    } else if constexpr (L == ContactLaw::hertzdamp) {
      const double iv0 = 1.0 / v0;  // the reciprocal, as the SIMD path (P6)
      F = kc * pw * (1.0 + cd * dd * iv0), dFd = kc * dpw * (1.0 + cd * dd * iv0), dFv = kc * pw * cd * iv0;
    } else {
      double q = dp > 0.0 ? std::sqrt(std::sqrt(dp)) : 0.0;
      bool app = dd > 0.0;
      F = kc * pw + (app ? cd * q * dd : 0.0);
      dFd = kc * dpw + (app && dp > 0.0 ? cd * 0.25 * q / dp * dd : 0.0);
      dFv = app ? cd * q : 0.0;
    }
  } else {
    (void)d, (void)dd, (void)kc, (void)cd, (void)v0, (void)n;
    F = dFd = dFv = 0.0;
  }
}

// Stability guard of the explicit treatment of contact: the linearised contact stiffness k_lin (for
// Hertzdamp scaled by its damping factor while approaching) gives omega = sqrt(k_lin / meff); omega h above
// the stepper's limit (2 for central difference and the Nigam-Jennings predictor-corrector, 2.8 for RK4)
// amplifies every contact step, so the lane is marked diverged instead of returning numbers.
template <ContactLaw L, bool N15>
[[gnu::always_inline]] inline bool contact_unstable(double d, double dd, double kc, double cd, double v0, double n,
                                                    double h2_meff, double limit2) {
  if (!(d > 0.0)) return false;
  double klin = 0.0;
  if constexpr (L == ContactLaw::linear || L == ContactLaw::kelvin) {
    klin = kc;
  } else if constexpr (L == ContactLaw::hertz || L == ContactLaw::hertzdamp || L == ContactLaw::jankowski) {
    klin = (N15 || L == ContactLaw::jankowski) ? 1.5 * kc * std::sqrt(d) : n * kc * std::pow(d, n - 1.0);
    if constexpr (L == ContactLaw::hertzdamp) klin *= std::max(1.0, 1.0 + cd * dd * (1.0 / v0));  // reciprocal (P6)
  }
  return klin * h2_meff > limit2;
}

struct Context {
  const ContactModel* contact;
  const KernelSettings* settings;
  const double* ag;  // ground acceleration at every integration step (size nsteps + 1)
  long nsteps;
  double h;
  double v0_min;
  double lim;
  SeriesRecorder* rec;  // null unless the recorded lane is in this tile
  int rec_lane;
};

// Observers after a step that ended at time t (lane i, new state already stored in the tile).
[[gnu::always_inline]] inline void observe(Tile& T, int i, double t, double ag, double fclamp, double onset) {
  double u1 = T.u1[i], u2 = T.u2[i];
  T.pu1[i] = std::max(T.pu1[i], std::abs(u1));
  T.pu2[i] = std::max(T.pu2[i], std::abs(u2));
  double cl = u1 - u2;
  bool up = cl > T.pclose[i];
  T.pclose[i] = up ? cl : T.pclose[i];
  T.tpclose[i] = up ? t : T.tpclose[i];
  double d = cl - T.gap[i];
  T.tfirst[i] = std::min(T.tfirst[i], onset > 0.0 ? t : inf);
  T.nimp[i] += onset;
  T.nclamp[i] += fclamp;
  T.pF[i] = std::max(T.pF[i], T.F[i]);
  T.ppen[i] = std::max(T.ppen[i], d);
  T.pa1[i] = std::max(T.pa1[i], std::abs(T.a1[i] + ag));
  T.pa2[i] = std::max(T.pa2[i], std::abs(T.a2[i] + ag));
}

// Divergence check: |u1| + |u2| above the limit (1) or non-finite (2); a bad lane is frozen at rest so
// that it neither slows the tile with inf/NaN arithmetic nor pollutes anything.
[[gnu::always_inline]] inline void check_lane(Tile& T, int i, double lim) {
  double s = std::abs(T.u1[i]) + std::abs(T.u2[i]);
  double sv = std::abs(T.v1[i]) + std::abs(T.v2[i]) + std::abs(T.a1[i]) + std::abs(T.a2[i]);
  double code = (s <= lim) ? 0.0 : ((s - s == 0.0) ? 1.0 : 2.0);
  code = (sv - sv == 0.0) ? code : 2.0;
  double b = std::max(T.bad[i], code);
  T.bad[i] = b;
  bool frozen = b > 0.0;
  T.u1[i] = frozen ? 0.0 : T.u1[i];
  T.u2[i] = frozen ? 0.0 : T.u2[i];
  T.v1[i] = frozen ? 0.0 : T.v1[i];
  T.v2[i] = frozen ? 0.0 : T.v2[i];
  T.a1[i] = frozen ? 0.0 : T.a1[i];
  T.a2[i] = frozen ? 0.0 : T.a2[i];
  T.fs1[i] = frozen ? 0.0 : T.fs1[i];
  T.fs2[i] = frozen ? 0.0 : T.fs2[i];
  T.F[i] = frozen ? 0.0 : T.F[i];
}

// Stereomechanical impact (muthukumar eq. 2) located inside the step just taken: the gap closed at the
// fraction s of the step, where the velocities are interpolated; the momentum exchange is applied there
// and the rest of the step is flown with the new velocities. Returns 1 when an impact happened.
[[gnu::always_inline]] inline double stereomechanical(Tile& T, int i, double h, double v1_old, double v2_old, double d_old) {
  double d = T.u1[i] - T.u2[i] - T.gap[i];
  double closing = T.v1[i] - T.v2[i];
  // an impact: the gap closed in this step, or the bodies still overlap and approach
  bool hit = d > 0.0 && (closing > 0.0 || !(d_old > 0.0));
  double denom = d - d_old;
  double s = d_old > 0.0 ? 0.0 : -d_old / (denom > 0.0 ? denom : 1.0);
  s = std::min(std::max(s, 0.0), 1.0);
  double w1 = v1_old + s * (T.v1[i] - v1_old), w2 = v2_old + s * (T.v2[i] - v2_old);
  double rel = w1 - w2;
  rel = rel > 0.0 ? rel : std::max(closing, 0.0);  // closing at the located instant (never pulls together)
  double M = T.m1[i] + T.m2[i];
  double dv1 = -(1.0 + T.e[i]) * T.m2[i] * rel / M;
  double dv2 = (1.0 + T.e[i]) * T.m1[i] * rel / M;
  double rest = (1.0 - s) * h;
  T.u1[i] += hit ? dv1 * rest : 0.0;
  T.u2[i] += hit ? dv2 * rest : 0.0;
  T.v1[i] += hit ? dv1 : 0.0;
  T.v2[i] += hit ? dv2 : 0.0;
  // energy lost in the exchange: meff (1 - e^2) rel^2 / 2
  T.Dimp[i] += hit ? 0.5 * T.meff[i] * (1.0 - T.e[i] * T.e[i]) * rel * rel : 0.0;
  return hit ? 1.0 : 0.0;
}

inline void record_series(const Context& C, const Tile& T, double t, double ag) {
  if (!C.rec) return;
  const int i = C.rec_lane;
  SeriesRecorder* rec = C.rec;
  rec->t.push_back(t);
  rec->u1.push_back(T.u1[i]);
  rec->u2.push_back(T.u2[i]);
  rec->v1.push_back(T.v1[i]);
  rec->v2.push_back(T.v2[i]);
  rec->a1_abs.push_back(T.a1[i] + ag);
  rec->a2_abs.push_back(T.a2[i] + ag);
  rec->fs1.push_back(T.fs1[i]);
  rec->fs2.push_back(T.fs2[i]);
  rec->force.push_back(T.F[i]);
  rec->ag.push_back(ag);
}

// ---------------------------------------------------------------------------------------------------
// Explicit central difference (velocity Verlet), the production stepper. The velocity-dependent forces at
// n+1 use the predicted velocity v_n + h a_n (error O(h^2)), which keeps the scheme second order with
// damping. Lanes run in SIMD chunks (std::experimental::native_simd) whose state stays in registers for
// the whole time loop; the contact law is evaluated only in steps where some lane of the chunk touches
// (skipping it gives exactly F = 0, so results do not depend on the chunk's other lanes).
namespace simd {
using V = stdx::native_simd<double>;
using M = V::mask_type;
constexpr int W = static_cast<int>(V::size());
[[gnu::always_inline]] inline V sel(const M& m, const V& a, const V& b) {
  V r = b;
  stdx::where(m, r) = a;
  return r;
}
[[gnu::always_inline]] inline V ld(const double* p) { return V(p, stdx::element_aligned); }
[[gnu::always_inline]] inline void st(const V& v, double* p) { v.copy_to(p, stdx::element_aligned); }
}  // namespace simd

template <ContactLaw L, bool N15>
[[gnu::always_inline]] inline simd::V contact_force_v(const simd::V& d, const simd::V& dd, const simd::V& kc,
                                                      const simd::V& cd, const simd::V& iv0, double n,
                                                      simd::V& clamp, simd::V& sq) {
  using namespace simd;
  const V zero(0.0), one(1.0);
  V dp = stdx::max(d, zero);
  clamp = zero;
  if constexpr (L == ContactLaw::linear) {
    return kc * dp;  // muthukumar eq. 3
  } else if constexpr (L == ContactLaw::kelvin) {
    V raw = sel(d > zero, kc * dp + cd * dd, zero);  // impact-stiffness paper eqs 1-3
    clamp = sel(raw < zero, one, zero);
    return stdx::max(raw, zero);
  } else if constexpr (L == ContactLaw::hertz || L == ContactLaw::hertzdamp || L == ContactLaw::jankowski) {
    V pw;
    if constexpr (N15 || L == ContactLaw::jankowski) {
      sq = stdx::sqrt(dp);
      pw = dp * sq;
    } else {
      for (int j = 0; j < W; ++j) pw[j] = dp[j] > 0.0 ? std::pow(dp[j], n) : 0.0;
    }
    if constexpr (L == ContactLaw::hertz) {
      return kc * pw;  // muthukumar eq. 6
    } else if constexpr (L == ContactLaw::hertzdamp) {
      V raw = kc * pw * (one + cd * dd * iv0);  // muthukumar eq. 10, xibar = cd
      clamp = sel(raw < zero, one, zero);
      return stdx::max(raw, zero);
    } else {
      // rc-buildings eqs 4-5: c_h = 2 zeta sqrt(kh sqrt(delta) meff) = cd delta^(1/4), approach only
      V damp = sel(dd > zero, cd * stdx::sqrt(sq) * dd, zero);
      return kc * pw + damp;
    }
  } else {
    (void)n;
    return zero;
  }
}

template <ContactLaw L, bool N15, bool Energy>
void run_central_difference(Tile& T, const Context& C) {
  using namespace simd;
  const double h = C.h, hh = 0.5 * h, n_exp = C.contact->n;
  const V zero(0.0), one(1.0), vmin(C.v0_min), lim(C.lim), vinf(inf), vh(h);
  for (int base = 0; base < T.n; base += W) {
    const V m1 = ld(T.m1 + base), m2 = ld(T.m2 + base), im1 = ld(T.im1 + base), im2 = ld(T.im2 + base);
    const V k1 = ld(T.k1 + base), k2 = ld(T.k2 + base), c1 = ld(T.c1 + base), c2 = ld(T.c2 + base);
    const V ak1 = ld(T.ak1 + base), ak2 = ld(T.ak2 + base), qy1 = ld(T.qy1 + base), qy2 = ld(T.qy2 + base);
    const V kp1 = ld(T.kp1 + base), kp2 = ld(T.kp2 + base);
    const V gap = ld(T.gap + base), kc = ld(T.kc + base), cd = ld(T.cd + base), e = ld(T.e + base);
    const V meff = ld(T.meff + base), Msum = m1 + m2, h2m = vh * vh / meff;
    V u1 = ld(T.u1 + base), v1 = ld(T.v1 + base), a1 = ld(T.a1 + base), fs1 = ld(T.fs1 + base);
    V u2 = ld(T.u2 + base), v2 = ld(T.v2 + base), a2 = ld(T.a2 + base), fs2 = ld(T.fs2 + base);
    V F = ld(T.F + base), v0 = ld(T.v0 + base), iv0 = one / v0, dprev = ld(T.dprev + base);
    V pu1 = ld(T.pu1 + base), pu2 = ld(T.pu2 + base), pclose = ld(T.pclose + base), tpclose = ld(T.tpclose + base);
    V tfirst = ld(T.tfirst + base), nimp = ld(T.nimp + base), nclamp = ld(T.nclamp + base);
    V pF = ld(T.pF + base), ppen = ld(T.ppen + base), Wc = ld(T.Wc + base), tcon = ld(T.tcon + base);
    V pa1 = ld(T.pa1 + base), pa2 = ld(T.pa2 + base), bad = ld(T.bad + base);
    V Ein = ld(T.Ein + base), Evis = ld(T.Evis + base), Ehys = ld(T.Ehys + base), Dimp = ld(T.Dimp + base);
    const int rec_j = (C.rec && C.rec_lane >= base && C.rec_lane < base + W) ? C.rec_lane - base : -1;
    bool any_bad = stdx::any_of(bad > zero), force_prev = stdx::any_of(F > zero);

    for (long step = 0; step < C.nsteps; ++step) {
      const double ag0 = C.ag[step], ag1 = C.ag[step + 1];
      const V t(static_cast<double>(step + 1) * h);
      const V v1o = v1, v2o = v2;
      V vh1 = v1 + hh * a1, vh2 = v2 + hh * a2;
      V du1 = h * vh1, du2 = h * vh2;
      V nu1 = u1 + du1, nu2 = u2 + du2;
      V vp1 = vh1 + hh * a1, vp2 = vh2 + hh * a2;
      V onset = zero, clamp = zero, nF = zero;
      if constexpr (L == ContactLaw::stereomechanical) {
        // muthukumar eq. 2 at the located closing instant: gap closed at fraction s of the step, velocities
        // interpolated there; the rest of the step is flown with the exchanged velocities.
        V d = nu1 - nu2 - gap;
        V closing = vp1 - vp2;
        M hit = (d > zero) && ((closing > zero) || !(dprev > zero));
        if (stdx::any_of(hit)) {
          V den = d - dprev;
          V s = sel(dprev > zero, zero, -dprev / sel(den > zero, den, one));
          s = stdx::min(stdx::max(s, zero), one);
          V w1 = v1o + s * (vp1 - v1o), w2 = v2o + s * (vp2 - v2o);
          V rel = w1 - w2;
          rel = sel(rel > zero, rel, stdx::max(closing, zero));
          V dv1 = sel(hit, -(one + e) * m2 * rel / Msum, zero);
          V dv2 = sel(hit, (one + e) * m1 * rel / Msum, zero);
          V rest = (one - s) * vh;
          nu1 += dv1 * rest;
          nu2 += dv2 * rest;
          du1 += dv1 * rest;
          du2 += dv2 * rest;
          vp1 += dv1;
          vp2 += dv2;
          vh1 += dv1;
          vh2 += dv2;
          Dimp += sel(hit, 0.5 * meff * (one - e * e) * rel * rel, zero);
          onset = sel(hit, one, zero);
          nimp += onset;
          tfirst = stdx::min(tfirst, sel(hit, t, vinf));
        }
      }
      // bilinear kinematic hardening, closed-form return into alpha k u +/- (1 - alpha) fy
      V tr1 = fs1 + k1 * du1, tr2 = fs2 + k2 * du2;
      V cb1 = ak1 * nu1, cb2 = ak2 * nu2;
      V nfs1 = stdx::min(stdx::max(tr1, cb1 - qy1), cb1 + qy1);
      V nfs2 = stdx::min(stdx::max(tr2, cb2 - qy2), cb2 + qy2);
      V d = nu1 - nu2 - gap;
      const M touching = d > zero;
      const bool any_touch = stdx::any_of(touching);
      if constexpr (L != ContactLaw::stereomechanical && L != ContactLaw::none) {
        if (any_touch) {
          V dd = vp1 - vp2;
          M on = touching && !(dprev > zero);
          onset = sel(on, one, zero);
          if constexpr (L == ContactLaw::hertzdamp) {
            if (stdx::any_of(on)) {
              // approach velocity at the interpolated closing instant inside the step (second order)
              V den = d - dprev;
              V sc = stdx::min(stdx::max(-dprev / sel(den > zero, den, one), zero), one);
              V ddo = v1o - v2o;
              v0 = sel(on, stdx::max(ddo + sc * (dd - ddo), vmin), v0);
              iv0 = one / v0;
            }
          }
          V sq = zero;  // sqrt of the penetration, shared with the stability guard
          nF = contact_force_v<L, N15>(d, dd, kc, cd, iv0, n_exp, clamp, sq);
          // stability guard (see contact_unstable): omega_lin h > 2
          V klin;
          if constexpr (L == ContactLaw::linear || L == ContactLaw::kelvin) {
            klin = kc;
          } else if constexpr (N15 || L == ContactLaw::jankowski) {
            klin = 1.5 * kc * sq;
          } else {
            for (int j = 0; j < W; ++j) klin[j] = d[j] > 0.0 ? n_exp * kc[j] * std::pow(d[j], n_exp - 1.0) : 0.0;
          }
          if constexpr (L == ContactLaw::hertzdamp) klin *= stdx::max(one, one + cd * dd * iv0);
          const M unstable = touching && (klin * h2m > V(4.0));
          if (stdx::any_of(unstable)) {
            bad = stdx::max(bad, sel(unstable, one, zero));
            any_bad = true;
          }
        }
      }
      V na1 = -ag1 - (c1 * vp1 + nfs1 + nF) * im1;
      V na2 = -ag1 - (c2 * vp2 + nfs2 - nF) * im2;
      V nv1 = vh1 + hh * na1, nv2 = vh2 + hh * na2;
      if constexpr (Energy) {
        Ehys += qy1 * stdx::abs(tr1 - nfs1) / kp1 + qy2 * stdx::abs(tr2 - nfs2) / kp2;
        Ein -= hh * (m1 * (ag0 * v1o + ag1 * nv1) + m2 * (ag0 * v2o + ag1 * nv2));
        Evis += hh * (c1 * (v1o * v1o + nv1 * nv1) + c2 * (v2o * v2o + nv2 * nv2));
      }
      if constexpr (L != ContactLaw::none) {
        if (any_touch || force_prev) {
          Wc += 0.5 * (F + nF) * (du1 - du2);  // contact work, trapezoidal in displacement
          tcon += sel(touching, vh, zero);
          if constexpr (L != ContactLaw::stereomechanical) {
            nimp += onset;
            tfirst = stdx::min(tfirst, sel(onset > zero, t, vinf));
          }
          nclamp += clamp;
          pF = stdx::max(pF, nF);
          ppen = stdx::max(ppen, d);
        }
        force_prev = any_touch;
      }
      // divergence: |u1| + |u2| above the limit (1) or anything non-finite (2); a bad lane is frozen at rest
      // (skipping the freeze while no lane is bad gives the same bits)
      V sdisp = stdx::abs(nu1) + stdx::abs(nu2);
      V sv = stdx::abs(nv1) + stdx::abs(nv2) + stdx::abs(na1) + stdx::abs(na2);
      const M ok = (sdisp <= lim) && (sv - sv == zero);
      if (!stdx::all_of(ok) || any_bad) {
        V code = sel(sdisp <= lim, zero, sel(sdisp - sdisp == zero, one, V(2.0)));
        code = sel(sv - sv == zero, code, V(2.0));
        bad = stdx::max(bad, code);
        any_bad = true;
        const M frozen = bad > zero;
        nu1 = sel(frozen, zero, nu1), nu2 = sel(frozen, zero, nu2);
        nv1 = sel(frozen, zero, nv1), nv2 = sel(frozen, zero, nv2);
        na1 = sel(frozen, zero, na1), na2 = sel(frozen, zero, na2);
        nfs1 = sel(frozen, zero, nfs1), nfs2 = sel(frozen, zero, nfs2);
        nF = sel(frozen, zero, nF);
      }
      u1 = nu1, u2 = nu2, v1 = nv1, v2 = nv2, a1 = na1, a2 = na2, fs1 = nfs1, fs2 = nfs2, F = nF;
      dprev = d;
      // observers
      pu1 = stdx::max(pu1, stdx::abs(u1));
      pu2 = stdx::max(pu2, stdx::abs(u2));
      V cl = u1 - u2;
      M up = cl > pclose;
      pclose = sel(up, cl, pclose);
      tpclose = sel(up, t, tpclose);
      pa1 = stdx::max(pa1, stdx::abs(a1 + ag1));
      pa2 = stdx::max(pa2, stdx::abs(a2 + ag1));
      if (rec_j >= 0) {
        SeriesRecorder* rec = C.rec;
        rec->t.push_back(t[0]);
        rec->u1.push_back(u1[rec_j]);
        rec->u2.push_back(u2[rec_j]);
        rec->v1.push_back(v1[rec_j]);
        rec->v2.push_back(v2[rec_j]);
        rec->a1_abs.push_back(a1[rec_j] + ag1);
        rec->a2_abs.push_back(a2[rec_j] + ag1);
        rec->fs1.push_back(fs1[rec_j]);
        rec->fs2.push_back(fs2[rec_j]);
        rec->force.push_back(F[rec_j]);
        rec->ag.push_back(ag1);
      }
    }
    st(u1, T.u1 + base), st(v1, T.v1 + base), st(a1, T.a1 + base), st(fs1, T.fs1 + base);
    st(u2, T.u2 + base), st(v2, T.v2 + base), st(a2, T.a2 + base), st(fs2, T.fs2 + base);
    st(F, T.F + base), st(v0, T.v0 + base), st(dprev, T.dprev + base);
    st(pu1, T.pu1 + base), st(pu2, T.pu2 + base), st(pclose, T.pclose + base), st(tpclose, T.tpclose + base);
    st(tfirst, T.tfirst + base), st(nimp, T.nimp + base), st(nclamp, T.nclamp + base);
    st(pF, T.pF + base), st(ppen, T.ppen + base), st(Wc, T.Wc + base), st(tcon, T.tcon + base);
    st(pa1, T.pa1 + base), st(pa2, T.pa2 + base), st(bad, T.bad + base);
    st(Ein, T.Ein + base), st(Evis, T.Evis + base), st(Ehys, T.Ehys + base), st(Dimp, T.Dimp + base);
  }
}

// Energy terms for steppers that do not fuse them into their lane loop (trapezoidal in time, exact
// plastic dissipation); called with the state before (o) and after the step.
template <bool Energy>
[[gnu::always_inline]] inline void energy_step(Tile& T, int i, double h, double ag0, double ag1, double v1o, double v2o, double u1o,
                        double u2o, double fs1o, double fs2o, double Fo) {
  if constexpr (Energy) {
    const double du1 = T.u1[i] - u1o, du2 = T.u2[i] - u2o;
    double ae1 = fs1o + T.k1[i] * du1 - T.fs1[i], ae2 = fs2o + T.k2[i] * du2 - T.fs2[i];
    T.Ehys[i] += T.qy1[i] * std::abs(ae1) / T.kp1[i] + T.qy2[i] * std::abs(ae2) / T.kp2[i];
    double v1 = T.v1[i], v2 = T.v2[i];
    T.Ein[i] -= 0.5 * h * (T.m1[i] * (ag0 * v1o + ag1 * v1) + T.m2[i] * (ag0 * v2o + ag1 * v2));
    T.Evis[i] += 0.5 * h * (T.c1[i] * (v1o * v1o + v1 * v1) + T.c2[i] * (v2o * v2o + v2 * v2));
  }
  T.Wc[i] += 0.5 * (Fo + T.F[i]) * ((T.u1[i] - u1o) - (T.u2[i] - u2o));
}

// ---------------------------------------------------------------------------------------------------
// Newmark average acceleration (gamma = 1/2, beta = 1/4) with Newton iterations on the coupled 2-DOF
// residual; the 2x2 tangent is solved in closed form. Each lane stops iterating when its own increment is
// below tolerance, so its result does not depend on the other lanes.
template <ContactLaw L, bool N15, bool Energy>
void run_newmark(Tile& T, const Context& C) {
  const double h = C.h, n_exp = C.contact->n, vmin = C.v0_min, lim = C.lim;
  const double c4 = 4.0 / (h * h), c2 = 2.0 / h;
  const int n = T.np, maxit = C.settings->newton_max_iter;
  const double tol = C.settings->newton_tol;
  for (long step = 0; step < C.nsteps; ++step) {
    const double ag0 = C.ag[step], ag1 = C.ag[step + 1];
    const double t = static_cast<double>(step + 1) * h;
    // Contact is handled as an active set: each lane first solves with its contact state from the start
    // of the step (inactive unless already penetrating); if the converged state contradicts it (penetration
    // without force, or a force that should be zero), the lane switches and solves again (at most 4 passes).
    // An inactive lane does exactly the uncoupled arithmetic, so before the first impact the coupled run is
    // bit-identical to the uncoupled one, and the kinks of the gated/clamped laws never meet Newton.
    for (int i = 0; i < n; ++i) {  // predictor: constant acceleration
      T.x1[i] = T.u1[i] + h * T.v1[i] + 0.5 * h * h * T.a1[i];
      T.x2[i] = T.u2[i] + h * T.v2[i] + 0.5 * h * h * T.a2[i];
      T.conv[i] = 0.0;
      T.y1[i] = T.dprev[i] > 0.0 ? 1.0 : 0.0;  // active
      T.y2[i] = 1.0;                           // Newton converged in every pass so far
      T.sw[i] = 0.0;                           // switches so far
    }
    for (int pass = 0; pass < 4; ++pass) {
    for (int it = 0; it < maxit; ++it) {
      double open = 0.0;
      for (int i = 0; i < n; ++i) {
        double u1 = T.x1[i], u2 = T.x2[i];
        double a1 = c4 * (u1 - T.u1[i]) - 4.0 / h * T.v1[i] - T.a1[i];
        double a2 = c4 * (u2 - T.u2[i]) - 4.0 / h * T.v2[i] - T.a2[i];
        double v1 = c2 * (u1 - T.u1[i]) - T.v1[i];
        double v2 = c2 * (u2 - T.u2[i]) - T.v2[i];
        double fs1 = bilinear(T.fs1[i], T.k1[i], u1 - T.u1[i], T.ak1[i] * u1, T.qy1[i]);
        double fs2 = bilinear(T.fs2[i], T.k2[i], u2 - T.u2[i], T.ak2[i] * u2, T.qy2[i]);
        double tr1 = T.fs1[i] + T.k1[i] * (u1 - T.u1[i]), tr2 = T.fs2[i] + T.k2[i] * (u2 - T.u2[i]);
        double kt1 = tr1 == fs1 ? T.k1[i] : T.ak1[i];
        double kt2 = tr2 == fs2 ? T.k2[i] : T.ak2[i];
        double d = u1 - u2 - T.gap[i], dd = v1 - v2;
        double F = 0.0, dFd = 0.0, dFv = 0.0;
        if constexpr (L != ContactLaw::stereomechanical && L != ContactLaw::none) {
          double v0 = T.v0[i];
          if constexpr (L == ContactLaw::hertzdamp) v0 = T.dprev[i] > 0.0 ? v0 : std::max(dd, vmin);
          if (T.y1[i] > 0.0) contact_force_raw<L, N15>(d, dd, T.kc[i], T.cd[i], v0, n_exp, F, dFd, dFv);
        }
        double r1 = T.m1[i] * (a1 + ag1) + T.c1[i] * v1 + fs1 + F;
        double r2 = T.m2[i] * (a2 + ag1) + T.c2[i] * v2 + fs2 - F;
        double kc_ = dFd + c2 * dFv;
        double j11 = c4 * T.m1[i] + c2 * T.c1[i] + kt1 + kc_;
        double j22 = c4 * T.m2[i] + c2 * T.c2[i] + kt2 + kc_;
        double j12 = -kc_;
        double det = j11 * j22 - j12 * j12;
        double du1 = (j22 * r1 - j12 * r2) / det;
        double du2 = (j11 * r2 - j12 * r1) / det;
        bool done = T.conv[i] > 0.0;
        T.x1[i] = done ? u1 : u1 - du1;
        T.x2[i] = done ? u2 : u2 - du2;
        // relative increment, with an absolute floor far above round-off of decayed motion (1e-15 m)
        double scale = std::abs(u1) + std::abs(u2);
        bool ok = (std::abs(du1) + std::abs(du2)) <= tol * scale + 1e-19;
        T.conv[i] = (done || ok) ? 1.0 : 0.0;
        open += T.conv[i] > 0.0 ? 0.0 : 1.0;
      }
      if (open == 0.0) break;
    }
    if constexpr (L == ContactLaw::stereomechanical || L == ContactLaw::none) break;
    double switched = 0.0;
    for (int i = 0; i < n; ++i) {
      T.y2[i] = T.conv[i] > 0.0 ? T.y2[i] : 0.0;
      double u1 = T.x1[i], u2 = T.x2[i];
      double v1 = c2 * (u1 - T.u1[i]) - T.v1[i], v2 = c2 * (u2 - T.u2[i]) - T.v2[i];
      double d = u1 - u2 - T.gap[i], dd = v1 - v2, clamp = 0.0;
      double v0 = T.v0[i];
      if constexpr (L == ContactLaw::hertzdamp) v0 = T.dprev[i] > 0.0 ? v0 : std::max(dd, vmin);
      double want = contact_force<L, N15>(d, dd, T.kc[i], T.cd[i], v0, n_exp, clamp) > 0.0 ? 1.0 : 0.0;
      // activate at most once per step; a lane that flips back (grazing, or separating under a clamped
      // force) keeps the inactive solution, whose penetration is then counted and its force committed
      bool sw = want != T.y1[i] && (want == 0.0 || T.sw[i] == 0.0);
      T.sw[i] += sw ? 1.0 : 0.0;
      T.y1[i] = sw ? want : T.y1[i];
      T.conv[i] = sw ? 0.0 : T.conv[i];
      switched += sw ? 1.0 : 0.0;
    }
    if (switched == 0.0) break;
    }
    for (int i = 0; i < n; ++i) {
      double u1o = T.u1[i], u2o = T.u2[i], v1o = T.v1[i], v2o = T.v2[i], fs1o = T.fs1[i], fs2o = T.fs2[i];
      double Fo = T.F[i];
      double u1 = T.x1[i], u2 = T.x2[i];
      double a1 = c4 * (u1 - u1o) - 4.0 / h * v1o - T.a1[i];
      double a2 = c4 * (u2 - u2o) - 4.0 / h * v2o - T.a2[i];
      double v1 = c2 * (u1 - u1o) - v1o, v2 = c2 * (u2 - u2o) - v2o;
      T.fs1[i] = bilinear(fs1o, T.k1[i], u1 - u1o, T.ak1[i] * u1, T.qy1[i]);
      T.fs2[i] = bilinear(fs2o, T.k2[i], u2 - u2o, T.ak2[i] * u2, T.qy2[i]);
      T.u1[i] = u1;
      T.u2[i] = u2;
      T.v1[i] = v1;
      T.v2[i] = v2;
      T.a1[i] = a1;
      T.a2[i] = a2;
      double d_old = T.dprev[i];
      double d = u1 - u2 - T.gap[i], dd = v1 - v2;
      double onset = 0.0, clamp = 0.0, F = 0.0;
      if constexpr (L == ContactLaw::stereomechanical) {
        onset = stereomechanical(T, i, h, v1o, v2o, d_old);
        // the velocity jump changes the accelerations' history: restart Newmark from the new velocities
        T.a1[i] = onset > 0.0 ? -ag1 - (T.c1[i] * T.v1[i] + T.fs1[i]) * T.im1[i] : T.a1[i];
        T.a2[i] = onset > 0.0 ? -ag1 - (T.c2[i] * T.v2[i] + T.fs2[i]) * T.im2[i] : T.a2[i];
        d = T.u1[i] - T.u2[i] - T.gap[i];
      } else if constexpr (L != ContactLaw::none) {
        onset = (d > 0.0 && !(d_old > 0.0)) ? 1.0 : 0.0;
        if constexpr (L == ContactLaw::hertzdamp) T.v0[i] = onset > 0.0 ? std::max(dd, vmin) : T.v0[i];
        F = contact_force<L, N15>(d, dd, T.kc[i], T.cd[i], T.v0[i], n_exp, clamp);
      }
      T.F[i] = F;
      T.dprev[i] = d;
      T.tcon[i] += d > 0.0 ? h : 0.0;
      // a lane whose Newton iteration did not converge is marked diverged
      T.bad[i] = std::max(T.bad[i], (T.conv[i] > 0.0 && T.y2[i] > 0.0) ? 0.0 : 1.0);
      energy_step<Energy>(T, i, h, ag0, ag1, v1o, v2o, u1o, u2o, fs1o, fs2o, Fo);
      check_lane(T, i, lim);
      observe(T, i, t, ag1, clamp, onset);
    }
    record_series(C, T, t, ag1);
  }
}

// ---------------------------------------------------------------------------------------------------
// Classical RK4 on (u1, v1, u2, v2). The hysteretic force at a stage is the return map from the committed
// state, the Hertzdamp approach velocity is latched at the first stage that finds contact.
template <ContactLaw L, bool N15, bool Energy>
void run_rk4(Tile& T, const Context& C) {
  const double h = C.h, n_exp = C.contact->n, vmin = C.v0_min, lim = C.lim;
  const bool locate = C.settings->locate_contact;
  const int n = T.np;
  for (long step = 0; step < C.nsteps; ++step) {
    const double ag0 = C.ag[step], ag1 = C.ag[step + 1];
    const double t = static_cast<double>(step + 1) * h;
    for (int i = 0; i < n; ++i) {
      const double u1o = T.u1[i], u2o = T.u2[i], v1o = T.v1[i], v2o = T.v2[i];
      const double fs1o = T.fs1[i], fs2o = T.fs2[i], Fo = T.F[i], d_old = T.dprev[i];
      double v0 = T.v0[i];
      // mode 0: contact held inactive; 1: active with the latched v0; 2: latch v0 at the first stage in contact
      int mode = 2;
      bool redone = false;
      double stage_fmax = 0.0;  // largest contact force met at a stage (a contact can start and end in a step)
      auto deriv = [&](double u1, double v1, double u2, double v2, double ag, double& a1, double& a2) {
        double fs1 = bilinear(fs1o, T.k1[i], u1 - u1o, T.ak1[i] * u1, T.qy1[i]);
        double fs2 = bilinear(fs2o, T.k2[i], u2 - u2o, T.ak2[i] * u2, T.qy2[i]);
        double F = 0.0, clamp = 0.0;
        if constexpr (L != ContactLaw::stereomechanical && L != ContactLaw::none) {
          double d = u1 - u2 - T.gap[i], dd = v1 - v2;
          if constexpr (L == ContactLaw::hertzdamp)
            if (mode == 2) v0 = (d_old > 0.0 || !(d > 0.0)) ? v0 : std::max(dd, vmin);
          F = mode == 0 ? 0.0 : contact_force<L, N15>(d, dd, T.kc[i], T.cd[i], v0, n_exp, clamp);
          stage_fmax = std::max(stage_fmax, F);
        }
        a1 = -ag - (T.c1[i] * v1 + fs1 + F) * T.im1[i];
        a2 = -ag - (T.c2[i] * v2 + fs2 - F) * T.im2[i];
      };
      // one classical RK4 step of length hs from (x1, y1, x2, y2) with ground acceleration agA -> agB
      auto rk4 = [&](double x1, double y1, double x2, double y2, double hs, double agA, double agB, double& X1,
                     double& Y1, double& X2, double& Y2) {
        const double agM = 0.5 * (agA + agB);
        double k1a1, k1a2, k2a1, k2a2, k3a1, k3a2, k4a1, k4a2;
        deriv(x1, y1, x2, y2, agA, k1a1, k1a2);
        double k1u1 = y1, k1u2 = y2;
        double k2u1 = y1 + 0.5 * hs * k1a1, k2u2 = y2 + 0.5 * hs * k1a2;
        deriv(x1 + 0.5 * hs * k1u1, k2u1, x2 + 0.5 * hs * k1u2, k2u2, agM, k2a1, k2a2);
        double k3u1 = y1 + 0.5 * hs * k2a1, k3u2 = y2 + 0.5 * hs * k2a2;
        deriv(x1 + 0.5 * hs * k2u1, k3u1, x2 + 0.5 * hs * k2u2, k3u2, agM, k3a1, k3a2);
        double k4u1 = y1 + hs * k3a1, k4u2 = y2 + hs * k3a2;
        deriv(x1 + hs * k3u1, k4u1, x2 + hs * k3u2, k4u2, agB, k4a1, k4a2);
        X1 = x1 + hs / 6.0 * (k1u1 + 2.0 * k2u1 + 2.0 * k3u1 + k4u1);
        X2 = x2 + hs / 6.0 * (k1u2 + 2.0 * k2u2 + 2.0 * k3u2 + k4u2);
        Y1 = y1 + hs / 6.0 * (k1a1 + 2.0 * k2a1 + 2.0 * k3a1 + k4a1);
        Y2 = y2 + hs / 6.0 * (k1a2 + 2.0 * k2a2 + 2.0 * k3a2 + k4a2);
      };
      // Out of contact at the start of the step: take the step without contact first (exactly the uncoupled
      // arithmetic, so the first passage is bit-identical to the uncoupled run); only a step that ends
      // penetrating is redone with the contact law.
      mode = d_old > 0.0 ? 2 : 0;
      rk4(u1o, v1o, u2o, v2o, h, ag0, ag1, T.u1[i], T.v1[i], T.u2[i], T.v2[i]);
      if constexpr (L != ContactLaw::stereomechanical && L != ContactLaw::none) {
        const double dn = T.u1[i] - T.u2[i] - T.gap[i];
        redone = !(d_old > 0.0) && dn > 0.0;
        if (!locate && redone) {
          mode = 2;
          rk4(u1o, v1o, u2o, v2o, h, ag0, ag1, T.u1[i], T.v1[i], T.u2[i], T.v2[i]);
        }
        if (locate && !(d_old > 0.0) && dn > 0.0) {
          // Event-located contact onset: find the closing instant on the step's cubic Hermite interpolant of
          // delta, integrate up to it without contact, latch v0 there, and finish the step in contact.
          const double ddo = v1o - v2o, ddn = T.v1[i] - T.v2[i];
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
          double cu1, cv1, cu2, cv2;
          mode = 0;
          rk4(u1o, v1o, u2o, v2o, sc * h, ag0, agc, cu1, cv1, cu2, cv2);
          v0 = std::max(cv1 - cv2, vmin);
          mode = 1;
          rk4(cu1, cv1, cu2, cv2, (1.0 - sc) * h, agc, ag1, T.u1[i], T.v1[i], T.u2[i], T.v2[i]);
        }
      }
      double onset = 0.0, clamp = 0.0, F = 0.0;
      if constexpr (L == ContactLaw::stereomechanical) onset = stereomechanical(T, i, h, v1o, v2o, d_old);
      T.fs1[i] = bilinear(fs1o, T.k1[i], T.u1[i] - u1o, T.ak1[i] * T.u1[i], T.qy1[i]);
      T.fs2[i] = bilinear(fs2o, T.k2[i], T.u2[i] - u2o, T.ak2[i] * T.u2[i], T.qy2[i]);
      double d = T.u1[i] - T.u2[i] - T.gap[i], dd = T.v1[i] - T.v2[i];
      if constexpr (L != ContactLaw::stereomechanical && L != ContactLaw::none) {
        onset = ((d > 0.0 || redone) && !(d_old > 0.0)) ? 1.0 : 0.0;  // redone: touched inside the step
        if constexpr (L == ContactLaw::hertzdamp) T.v0[i] = d_old > 0.0 ? T.v0[i] : v0;
        F = contact_force<L, N15>(d, dd, T.kc[i], T.cd[i], T.v0[i], n_exp, clamp);
        const bool unstable = contact_unstable<L, N15>(d, dd, T.kc[i], T.cd[i], T.v0[i], n_exp, h * h / T.meff[i], 2.8 * 2.8);
        T.bad[i] = std::max(T.bad[i], unstable ? 1.0 : 0.0);
        T.pF[i] = std::max(T.pF[i], stage_fmax);
      }
      T.F[i] = F;
      T.a1[i] = -ag1 - (T.c1[i] * T.v1[i] + T.fs1[i] + F) * T.im1[i];
      T.a2[i] = -ag1 - (T.c2[i] * T.v2[i] + T.fs2[i] - F) * T.im2[i];
      T.dprev[i] = d;
      T.tcon[i] += d > 0.0 ? h : 0.0;
      energy_step<Energy>(T, i, h, ag0, ag1, v1o, v2o, u1o, u2o, fs1o, fs2o, Fo);
      check_lane(T, i, lim);
      observe(T, i, t, ag1, clamp, onset);
    }
    record_series(C, T, t, ag1);
  }
}

// ---------------------------------------------------------------------------------------------------
// Nigam-Jennings: each structure's linear part (m, k, c) is advanced with the exact recurrence for a
// piecewise-linear load; the nonlinear remainder g = (fs - k u) + F (contact) enters as an extra load,
// held at g_n (predictor) and then linear from g_n to g(n+1) predicted (corrector). With an elastic
// structure out of contact g = 0 and the step is exact to round-off.
template <ContactLaw L, bool N15, bool Energy>
void run_nigam_jennings(Tile& T, const Context& C) {
  const double h = C.h, n_exp = C.contact->n, vmin = C.v0_min, lim = C.lim;
  const int n = T.np;
  for (long step = 0; step < C.nsteps; ++step) {
    const double ag0 = C.ag[step], ag1 = C.ag[step + 1];
    const double t = static_cast<double>(step + 1) * h;
    for (int i = 0; i < n; ++i) {
      const double u1o = T.u1[i], u2o = T.u2[i], v1o = T.v1[i], v2o = T.v2[i];
      const double fs1o = T.fs1[i], fs2o = T.fs2[i], Fo = T.F[i], d_old = T.dprev[i];
      // load in acceleration units: u'' + 2 zeta w u' + w^2 u = -(ag + g/m)
      const double p1o = ag0 + (fs1o - T.k1[i] * u1o + Fo) * T.im1[i];
      const double p2o = ag0 + (fs2o - T.k2[i] * u2o - Fo) * T.im2[i];
      auto adv = [&](const double (*c)[tile_width], double u, double v, double pa, double pb, double& un,
                     double& vn) {
        un = c[0][i] * u + c[1][i] * v + c[4][i] * pa + c[5][i] * pb;
        vn = c[2][i] * u + c[3][i] * v + c[6][i] * pa + c[7][i] * pb;
      };
      double u1p, v1p, u2p, v2p;
      adv(T.nj1, u1o, v1o, p1o, ag1 - ag0 + p1o, u1p, v1p);
      adv(T.nj2, u2o, v2o, p2o, ag1 - ag0 + p2o, u2p, v2p);
      // corrector with the remainder evaluated at the predicted end state
      double fs1p = bilinear(fs1o, T.k1[i], u1p - u1o, T.ak1[i] * u1p, T.qy1[i]);
      double fs2p = bilinear(fs2o, T.k2[i], u2p - u2o, T.ak2[i] * u2p, T.qy2[i]);
      double Fp = 0.0, clamp = 0.0;
      double v0 = T.v0[i];
      // Out of contact at the start: correct without contact first (the uncoupled arithmetic); a step that
      // ends penetrating is corrected again with the contact force at the predicted state.
      auto correct = [&](bool with_contact) {
        Fp = 0.0;
        if constexpr (L != ContactLaw::stereomechanical && L != ContactLaw::none) {
          if (with_contact) {
            double d = u1p - u2p - T.gap[i], dd = v1p - v2p;
            if constexpr (L == ContactLaw::hertzdamp) v0 = (d_old > 0.0) ? v0 : std::max(dd, vmin);
            Fp = contact_force<L, N15>(d, dd, T.kc[i], T.cd[i], v0, n_exp, clamp);
          }
        }
        double p1n = ag1 + (fs1p - T.k1[i] * u1p + Fp) * T.im1[i];
        double p2n = ag1 + (fs2p - T.k2[i] * u2p - Fp) * T.im2[i];
        adv(T.nj1, u1o, v1o, p1o, p1n, T.u1[i], T.v1[i]);
        adv(T.nj2, u2o, v2o, p2o, p2n, T.u2[i], T.v2[i]);
      };
      correct(d_old > 0.0);
      const bool redone = !(d_old > 0.0) && T.u1[i] - T.u2[i] - T.gap[i] > 0.0;
      if (redone) correct(true);
      const double corrector_force = Fp;
      double onset = 0.0, F = 0.0;
      clamp = 0.0;
      if constexpr (L == ContactLaw::stereomechanical) onset = stereomechanical(T, i, h, v1o, v2o, d_old);
      T.fs1[i] = bilinear(fs1o, T.k1[i], T.u1[i] - u1o, T.ak1[i] * T.u1[i], T.qy1[i]);
      T.fs2[i] = bilinear(fs2o, T.k2[i], T.u2[i] - u2o, T.ak2[i] * T.u2[i], T.qy2[i]);
      double d = T.u1[i] - T.u2[i] - T.gap[i], dd = T.v1[i] - T.v2[i];
      if constexpr (L != ContactLaw::stereomechanical && L != ContactLaw::none) {
        onset = ((d > 0.0 || redone) && !(d_old > 0.0)) ? 1.0 : 0.0;  // redone: touched inside the step
        if constexpr (L == ContactLaw::hertzdamp) T.v0[i] = onset > 0.0 ? std::max(dd, vmin) : T.v0[i];
        F = contact_force<L, N15>(d, dd, T.kc[i], T.cd[i], T.v0[i], n_exp, clamp);
        const bool unstable = contact_unstable<L, N15>(d, dd, T.kc[i], T.cd[i], T.v0[i], n_exp, h * h / T.meff[i], 4.0);
        T.bad[i] = std::max(T.bad[i], unstable ? 1.0 : 0.0);
        T.pF[i] = std::max(T.pF[i], corrector_force);
      }
      T.F[i] = F;
      T.a1[i] = -ag1 - (T.c1[i] * T.v1[i] + T.fs1[i] + F) * T.im1[i];
      T.a2[i] = -ag1 - (T.c2[i] * T.v2[i] + T.fs2[i] - F) * T.im2[i];
      T.dprev[i] = d;
      T.tcon[i] += d > 0.0 ? h : 0.0;
      energy_step<Energy>(T, i, h, ag0, ag1, v1o, v2o, u1o, u2o, fs1o, fs2o, Fo);
      check_lane(T, i, lim);
      observe(T, i, t, ag1, clamp, onset);
    }
    record_series(C, T, t, ag1);
  }
}

template <ContactLaw L, bool N15, bool Energy>
void dispatch_stepper(Tile& T, const Context& C) {
  switch (C.settings->stepper) {
    case Stepper::central_difference: run_central_difference<L, N15, Energy>(T, C); break;
    case Stepper::newmark: run_newmark<L, N15, Energy>(T, C); break;
    case Stepper::rk4: run_rk4<L, N15, Energy>(T, C); break;
    case Stepper::nigam_jennings: run_nigam_jennings<L, N15, Energy>(T, C); break;
  }
}

template <ContactLaw L>
void dispatch_n(Tile& T, const Context& C) {
  bool n15 = C.contact->n == 1.5;
  bool energy = C.settings->energy;
  if (n15 && energy) dispatch_stepper<L, true, true>(T, C);
  else if (n15) dispatch_stepper<L, true, false>(T, C);
  else if (energy) dispatch_stepper<L, false, true>(T, C);
  else dispatch_stepper<L, false, false>(T, C);
}

void dispatch(Tile& T, const Context& C) {
  switch (C.contact->law) {
    case ContactLaw::none: dispatch_n<ContactLaw::none>(T, C); break;
    case ContactLaw::linear: dispatch_n<ContactLaw::linear>(T, C); break;
    case ContactLaw::kelvin: dispatch_n<ContactLaw::kelvin>(T, C); break;
    case ContactLaw::hertz: dispatch_n<ContactLaw::hertz>(T, C); break;
    case ContactLaw::hertzdamp: dispatch_n<ContactLaw::hertzdamp>(T, C); break;
    case ContactLaw::jankowski: dispatch_n<ContactLaw::jankowski>(T, C); break;
    case ContactLaw::stereomechanical: dispatch_n<ContactLaw::stereomechanical>(T, C); break;
  }
}

double contact_damping_constant(const ContactModel& cm, double kc, double e, double meff) {
  switch (cm.law) {
    case ContactLaw::kelvin: return 2.0 * kelvin_damping_ratio(e) * std::sqrt(kc * meff);
    case ContactLaw::hertzdamp: return hertzdamp_xibar(cm.damping, e, cm.n);
    case ContactLaw::jankowski: return 2.0 * jankowski_zeta(e) * std::sqrt(kc * meff);
    default: return 0.0;
  }
}

void validate_lane(const PairParams& p, const ContactModel& cm, Stepper stepper, std::size_t lane) {
  auto where = [&](const char* what) { return fmt::format("{} (lane {})", what, lane); };
  for (auto [s, tag] : {std::pair{&p.s1, "1"}, std::pair{&p.s2, "2"}}) {
    std::string sfx = tag;
    require_positive(s->m, where(("m" + sfx).c_str()));
    if (!std::isfinite(s->k) || s->k < 0) require_positive(s->k, where(("k" + sfx).c_str()));
    if (!std::isfinite(s->c) || s->c < 0)
      throw InputError(fmt::format("c{} = {} must be >= 0", sfx, s->c), where(("c" + sfx).c_str()), "give c >= 0");
    if (!(s->fy > 0)) require_positive(s->fy, where(("fy" + sfx).c_str()));
    require_range(s->alpha, 0.0, std::nextafter(1.0, 0.0), where(("alpha" + sfx).c_str()), "[0, 1)");
    if (stepper == Stepper::nigam_jennings) {
      require_positive(s->k, where(("k" + sfx + " (Nigam-Jennings needs k > 0)").c_str()));
      double zeta = s->c / (2.0 * std::sqrt(s->k * s->m));
      if (!(zeta < 1.0))
        throw InputError(fmt::format("damping ratio {} of structure {} is not below 1", zeta, sfx),
                         where("zeta"), "the Nigam-Jennings stepper needs an under-damped structure");
    }
  }
  if (!std::isfinite(p.gap) || p.gap < 0)
    throw InputError(fmt::format("gap = {} must be >= 0", p.gap), where("gap"), "give a gap >= 0 (m)");
  if (cm.law != ContactLaw::none && cm.law != ContactLaw::stereomechanical) require_positive(p.kc, where("kc"));
  if (cm.law == ContactLaw::kelvin || cm.law == ContactLaw::hertzdamp || cm.law == ContactLaw::jankowski ||
      cm.law == ContactLaw::stereomechanical)
    require_range(p.e, std::nextafter(0.0, 1.0), 1.0, where("e"), "(0, 1]");
}

}  // namespace

Stepper parse_stepper(std::string_view name) {
  for (auto& s : stepper_table)
    if (s.name == name) return s.s;
  throw InputError(fmt::format("unknown stepper '{}'", name), "stepper",
                   fmt::format("use one of: {}", stepper_names));
}
std::string_view to_string(Stepper s) {
  for (auto& t : stepper_table)
    if (t.s == s) return t.name;
  return "?";
}
std::string_view to_string(LaneStatus s) {
  switch (s) {
    case LaneStatus::ok: return "ok";
    case LaneStatus::diverged: return "diverged";
    case LaneStatus::non_finite: return "non-finite";
  }
  return "?";
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
                  &e_contact_stored})
    v->assign(n, 0.0);
  impact_count.assign(n, 0);
  clamp_count.assign(n, 0);
  status.assign(n, 0);
}

NigamJennings nigam_jennings(double w, double z, double h) {
  // Nigam & Jennings (1969), for u'' + 2 z w u' + w^2 u = -a(t), a linear between a0 and a1 on [0, h].
  // A (free response) in closed form. B are the Duhamel integrals of the unit impulse response
  // g(s) = e^(-z w s) sin(wd s) / wd against the linear load shapes:
  //   b11 = -int g(s) s/h ds, b12 = -int g(s) (1 - s/h) ds, b21, b22 the same with g'(s), s in [0, h].
  // The textbook closed forms of B lose digits to cancellation when w h is small (1e-6 relative at
  // w h = 1e-4), so B is integrated with composite 8-point Gauss-Legendre on panels of w h <= 0.25: the
  // integrands are entire functions, so this is exact to round-off for any w h.
  const double sq = std::sqrt(1.0 - z * z), wd = w * sq;
  const double E = std::exp(-z * w * h), S = std::sin(wd * h), Cs = std::cos(wd * h);
  NigamJennings c;
  c.a11 = E * (z / sq * S + Cs);
  c.a12 = E * S / wd;
  c.a21 = -w / sq * E * S;
  c.a22 = E * (Cs - z / sq * S);
  static constexpr double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                   -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                   0.7966664774136267,  0.9602898564975363};
  static constexpr double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                   0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                   0.2223810344533745, 0.1012285362903763};
  const int panels = std::max(1, static_cast<int>(std::ceil(w * h / 0.25)));
  const double ph = h / panels;
  double i_gs = 0, i_g = 0, i_dgs = 0, i_dg = 0;  // int g s/h, int g, int g' s/h, int g'
  for (int p = 0; p < panels; ++p) {
    const double mid = (p + 0.5) * ph, half = 0.5 * ph;
    for (int q = 0; q < 8; ++q) {
      const double sv = mid + half * gx[q], wt = half * gw[q];
      const double ex = std::exp(-z * w * sv), sn = std::sin(wd * sv), cs = std::cos(wd * sv);
      const double g = ex * sn / wd, dg = ex * (cs - z * w / wd * sn);
      i_gs += wt * g * (sv / h);
      i_g += wt * g;
      i_dgs += wt * dg * (sv / h);
      i_dg += wt * dg;
    }
  }
  c.b11 = -i_gs;
  c.b12 = -(i_g - i_gs);
  c.b21 = -i_dgs;
  c.b22 = -(i_dg - i_dgs);
  return c;
}

void run_batch(const PairBatch& batch, const ContactModel& contact, const GroundMotion& motion,
               const KernelSettings& settings, BatchResult& out) {
  const std::size_t width = batch.width();
  if (settings.substeps < 1)
    throw InputError(fmt::format("substeps = {} must be >= 1", settings.substeps), "substeps", "give 1 or more");
  require_positive(motion.dt, "record dt");
  if (contact.law == ContactLaw::hertzdamp || contact.law == ContactLaw::hertz)
    require_range(contact.n, 1.0, 3.0, "Hertz exponent n", "[1, 3]");
  out.resize(width);
  if (width == 0) return;

  const double h = motion.dt / settings.substeps;
  const long nsteps = std::lround(motion.total_duration() / h);
  // ground acceleration at every integration step, linear inside a record step, zero after the record
  std::vector<double> ag(static_cast<std::size_t>(nsteps) + 1, 0.0);
  const long nrec = static_cast<long>(motion.ag.size());
  for (long j = 0; j <= nsteps; ++j) {
    long r = j / settings.substeps, q = j % settings.substeps;
    if (r >= nrec) break;
    double a0 = motion.ag[static_cast<std::size_t>(r)];
    double a1 = r + 1 < nrec ? motion.ag[static_cast<std::size_t>(r + 1)] : 0.0;
    ag[static_cast<std::size_t>(j)] =
        q == 0 ? a0 : a0 + (static_cast<double>(q) / settings.substeps) * (a1 - a0);
  }
  if (settings.series) {
    settings.series->clear();
    settings.series->reserve_for(static_cast<std::size_t>(nsteps) + 1);
  }
  Context C{&contact, &settings, ag.data(), nsteps, h, contact.v0_min, settings.displacement_limit, nullptr, 0};

  auto tile = std::make_unique<Tile>();
  for (std::size_t base = 0; base < width; base += tile_width) {
    Tile& T = *tile;
    T.n = static_cast<int>(std::min<std::size_t>(tile_width, width - base));
    // lanes past n up to the SIMD chunk boundary are padded with copies of the tile's first lane
    const int padded = std::min(tile_width, (T.n + simd::W - 1) / simd::W * simd::W);
    T.np = padded;
    for (int i = 0; i < padded; ++i) {
      const std::size_t L = base + static_cast<std::size_t>(i < T.n ? i : 0);
      PairParams p = batch.get(L);
      validate_lane(p, contact, settings.stepper, L);
      T.m1[i] = p.s1.m, T.m2[i] = p.s2.m, T.im1[i] = 1.0 / p.s1.m, T.im2[i] = 1.0 / p.s2.m;
      T.k1[i] = p.s1.k, T.k2[i] = p.s2.k, T.c1[i] = p.s1.c, T.c2[i] = p.s2.c;
      T.ak1[i] = p.s1.alpha * p.s1.k, T.ak2[i] = p.s2.alpha * p.s2.k;
      T.qy1[i] = std::isfinite(p.s1.fy) ? (1.0 - p.s1.alpha) * p.s1.fy : elastic_qy;
      T.qy2[i] = std::isfinite(p.s2.fy) ? (1.0 - p.s2.alpha) * p.s2.fy : elastic_qy;
      T.kp1[i] = p.s1.k > 0 ? (1.0 - p.s1.alpha) * p.s1.k : 1.0;
      T.kp2[i] = p.s2.k > 0 ? (1.0 - p.s2.alpha) * p.s2.k : 1.0;
      T.gap[i] = p.gap, T.kc[i] = p.kc, T.e[i] = p.e;
      T.meff[i] = p.s1.m * p.s2.m / (p.s1.m + p.s2.m);
      T.cd[i] = contact_damping_constant(contact, p.kc, p.e, T.meff[i]);
      T.u1[i] = p.u1, T.v1[i] = p.v1, T.u2[i] = p.u2, T.v2[i] = p.v2;
      // initial state: springs at their elastic force, contact force from the initial penetration
      T.fs1[i] = std::clamp(p.s1.k * p.u1, T.ak1[i] * p.u1 - T.qy1[i], T.ak1[i] * p.u1 + T.qy1[i]);
      T.fs2[i] = std::clamp(p.s2.k * p.u2, T.ak2[i] * p.u2 - T.qy2[i], T.ak2[i] * p.u2 + T.qy2[i]);
      double d0 = p.u1 - p.u2 - p.gap, dd0 = p.v1 - p.v2, clamp = 0;
      T.v0[i] = std::max(dd0, contact.v0_min);
      T.F[i] = 0.0;
      if (d0 > 0.0) {
        ContactModel cm = contact;
        switch (contact.law) {
          case ContactLaw::linear: T.F[i] = contact_force<ContactLaw::linear, true>(d0, dd0, p.kc, T.cd[i], T.v0[i], cm.n, clamp); break;
          case ContactLaw::kelvin: T.F[i] = contact_force<ContactLaw::kelvin, true>(d0, dd0, p.kc, T.cd[i], T.v0[i], cm.n, clamp); break;
          case ContactLaw::hertz: T.F[i] = contact_force<ContactLaw::hertz, false>(d0, dd0, p.kc, T.cd[i], T.v0[i], cm.n, clamp); break;
          case ContactLaw::hertzdamp: T.F[i] = contact_force<ContactLaw::hertzdamp, false>(d0, dd0, p.kc, T.cd[i], T.v0[i], cm.n, clamp); break;
          case ContactLaw::jankowski: T.F[i] = contact_force<ContactLaw::jankowski, true>(d0, dd0, p.kc, T.cd[i], T.v0[i], cm.n, clamp); break;
          default: break;
        }
      }
      T.dprev[i] = d0;
      const double ag0 = ag[0];
      T.a1[i] = -ag0 - (T.c1[i] * p.v1 + T.fs1[i] + T.F[i]) * T.im1[i];
      T.a2[i] = -ag0 - (T.c2[i] * p.v2 + T.fs2[i] - T.F[i]) * T.im2[i];
      T.pu1[i] = std::abs(p.u1), T.pu2[i] = std::abs(p.u2);
      T.pclose[i] = p.u1 - p.u2, T.tpclose[i] = 0.0, T.tfirst[i] = d0 > 0.0 ? 0.0 : inf;
      T.nimp[i] = d0 > 0.0 ? 1.0 : 0.0, T.nclamp[i] = 0.0, T.pF[i] = T.F[i], T.ppen[i] = d0;
      T.Wc[i] = 0.0, T.tcon[i] = 0.0;
      T.pa1[i] = std::abs(T.a1[i] + ag0), T.pa2[i] = std::abs(T.a2[i] + ag0), T.bad[i] = 0.0;
      T.Ein[i] = 0.0, T.Evis[i] = 0.0, T.Ehys[i] = 0.0, T.Dimp[i] = 0.0;
      if (settings.stepper == Stepper::nigam_jennings) {
        for (int s = 0; s < 2; ++s) {
          const Structure& st = s == 0 ? p.s1 : p.s2;
          double w = std::sqrt(st.k / st.m), z = st.c / (2.0 * std::sqrt(st.k * st.m));
          NigamJennings c = nigam_jennings(w, z, h);
          double(*dst)[tile_width] = s == 0 ? T.nj1 : T.nj2;
          double vals[8] = {c.a11, c.a12, c.a21, c.a22, c.b11, c.b12, c.b21, c.b22};
          for (int q = 0; q < 8; ++q) dst[q][i] = vals[q];
        }
      }
    }
    // The series recorder only watches its lane in the tile that holds it.
    Context Ct = C;
    Ct.rec = nullptr;
    Ct.rec_lane = 0;
    if (settings.series && settings.series->lane >= base && settings.series->lane < base + static_cast<std::size_t>(T.n)) {
      Ct.rec = settings.series;
      Ct.rec_lane = static_cast<int>(settings.series->lane - base);
      record_series(Ct, T, 0.0, ag[0]);
    }
    dispatch(T, Ct);

    const double n_exp = (contact.law == ContactLaw::jankowski) ? 1.5 : contact.n;
    for (int i = 0; i < T.n; ++i) {
      const std::size_t L = base + static_cast<std::size_t>(i);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      bool bad = T.bad[i] > 0.0;
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
      out.peak_force[L] = contact.law == ContactLaw::stereomechanical ? nan : val(T.pF[i]);
      out.peak_penetration[L] = val(std::max(T.ppen[i], 0.0));
      out.contact_time[L] = val(T.tcon[i]);
      out.peak_acc1[L] = val(T.pa1[i]);
      out.peak_acc2[L] = val(T.pa2[i]);
      out.final_u1[L] = val(T.u1[i]), out.final_v1[L] = val(T.v1[i]);
      out.final_u2[L] = val(T.u2[i]), out.final_v2[L] = val(T.v2[i]);
      // stored energies at the end
      double d = T.u1[i] - T.u2[i] - T.gap[i];
      double dp = std::max(d, 0.0);
      double stored = 0.0;
      switch (contact.law) {
        case ContactLaw::linear:
        case ContactLaw::kelvin: stored = 0.5 * T.kc[i] * dp * dp; break;
        case ContactLaw::hertz:
        case ContactLaw::hertzdamp:
        case ContactLaw::jankowski: stored = T.kc[i] * std::pow(dp, n_exp + 1.0) / (n_exp + 1.0); break;
        default: break;
      }
      auto strain = [](double k, double ak, double u, double fs) {
        double q = fs - ak * u;  // force in the elasto-plastic part (stiffness k - ak)
        double kp = k - ak;
        return 0.5 * ak * u * u + (kp > 0 ? 0.5 * q * q / kp : 0.0);
      };
      out.e_contact_stored[L] = val(stored);
      out.contact_energy[L] = val(T.Wc[i] - stored + T.Dimp[i]);
      out.e_input[L] = val(T.Ein[i]);
      out.e_kinetic[L] = val(0.5 * T.m1[i] * T.v1[i] * T.v1[i] + 0.5 * T.m2[i] * T.v2[i] * T.v2[i]);
      out.e_strain[L] = val(strain(T.k1[i], T.ak1[i], T.u1[i], T.fs1[i]) +
                            strain(T.k2[i], T.ak2[i], T.u2[i], T.fs2[i]));
      out.e_viscous[L] = val(T.Evis[i]);
      out.e_hysteretic[L] = val(T.Ehys[i]);
    }
  }
}

}  // namespace pounding
