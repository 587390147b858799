#pragma once
// The link laws of bridge chains (issue 26 §1; docs/architecture.md §2.2.5, §2.5.2; ../shared/research/
// systems-and-bridges.md §5, test vectors T5.1, T5.3-T5.5): springs with role link between two DOFs or a DOF and a
// wall, in the system stepper only.
//
// Gap laws, one implementation with two envelopes. With x = side * d (d = u_j - u_i the spring's deformation, side
// +1: the law engages when d grows past the gap, -1: when d falls below minus the gap) and s the current gap (the
// slack, starting at the given gap):
//   F = max(0, min(k (x - s), H(x))),   f = side * F,
//   after a step on the envelope (k (x - s) > H(x) > 0): s <- x - F / k (the plastic elongation stays: the slack
//   grows, as OpenSees' ElasticPPGap with its `damage` flag and as a cable does; SB §5).
// TensionGap (cable restrainer: tension-only bilinear with slack, yield F_y, hardening alpha k) and CompressionGap
// (abutment backfill after the expansion gap, elastic-perfectly-plastic with alpha = 0: Caltrans SDC K_abut, P_bw)
// use the straight envelope H(x) = F_y + alpha k (x - gap - F_y / k). HyperbolicGap (Shamsabadi, Rollins & Kapuskar
// 2007; OpenSees HyperbolicGapMaterial) uses H(x) = delta / (1 / K_max + R_f delta / F_ult), delta = x - gap >= 0,
// with unloading and reloading at K_ur >= K_max (first loading follows the envelope; it approaches F_ult / R_f,
// uncapped, as OpenSees).
//
// QHyst (Saiidi & Sozen 1979, UIUC SRS 465; the rules of SB §5 "Q-Hyst", T5.5): bilinear primary curve k, F_y,
// alpha k; unloading from any point at k_u = k (d_y / d_m)^beta (beta = 0.5 in Q-Hyst; d_m the largest |d| reached
// in either direction, k_u = k before yield); after the force crosses zero, reloading on a straight line toward the
// largest excursion reached in the new direction on the primary curve ((+-d_y, +-F_y) when that side has not
// yielded), then on the primary curve; a reversal on an unloading branch before the force reaches zero retraces
// k_u to the reversal point and resumes the branch it left. The state is event-driven (branch and anchors), so the
// update is scalar code run per lane (bit-equal at both lane types by construction).
//
// Energy (both): the spring's recoverable energy is F^2 / (2 k_unload) (k for the gap laws, k_u for Q-Hyst); the
// stepper counts dissipation per step as the trapezoid work 0.5 (f0 + f1) dd minus the change of that energy, so the
// balance closes exactly to the trapezoid rule's error (second order in the step).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <string_view>

#include "pounding/kernel/lane.hpp"
#include "pounding/model/hysteresis/spring_spec.hpp"

namespace pounding::model {

// Per-lane constants of a gap spring. Straight envelope: c1 = alpha k, c2 = F_y - alpha k (gap + F_y / k)
// (H = fma(c1, x, c2)); hyperbolic: c1 = 1 / K_max, c2 = R_f / F_ult, gap0 = the initial gap.
template <class T> struct GapParams { T k, c1, c2, side, gap0; };

struct GapSpring {
  // The force f = side F at deformation d from the current gap s (updated in place).
  template <bool Hyperbolic, class T> POUNDING_INLINE static T force(const GapParams<T>& p, T d, T& s) {
    const T zero(0.0);
    const T x = p.side * d;
    const T ft = p.k * (x - s);
    T env;
    if constexpr (Hyperbolic) {
      const T del = lane::max(x - p.gap0, zero);
      env = del / lane::fma(p.c2, del, p.c1);
    } else {
      env = lane::fma(p.c1, x, p.c2);
    }
    const T F = lane::max(lane::min(ft, env), zero);
    s = lane::select((ft > env) && (env > zero), x - F / p.k, s);
    return p.side * F;
  }
  // Dissipation over an increment dd from force f0 to f1 with recoverable energy f^2 / (2 k):
  // 0.5 (f0 + f1) dd - (f1^2 - f0^2) / (2 k) = 0.5 (f0 + f1) (dd - (f1 - f0) / k).
  template <class T> POUNDING_INLINE static T dissipated(T k, T f0, T f1, T dd) {
    return T(0.5) * (f0 + f1) * (dd - (f1 - f0) / k);
  }
  static double strain_energy(double k, double f) { return 0.5 * f * f / k; }
  // The system stepper's rows (k, c1, c2, side, gap0; the current gap in the last) at the given gap, and the force
  // in d0; the recoverable energy from them.
  template <bool Hyperbolic> static double load(const GapParams<double>& p, double d0, SpringRows& r) {
    r[0] = p.k, r[1] = p.c1, r[2] = p.c2, r[3] = p.side, r[4] = p.gap0;
    double g = p.gap0;
    const double f0 = force<Hyperbolic>(p, d0, g);
    r[10] = g;
    return f0;
  }
  static double stored_energy(const SpringRows& r, double, double f) { return strain_energy(r[0], f); }
  // The system stepper's step: the force from the current gap (the last row, updated); the dissipation in x.
  template <bool Hyperbolic, bool WithEnergy, class T, class R>
  POUNDING_INLINE static T step(const R& r, const T& fo, const T& d, const T& dd, T& x) {
    const GapParams<T> p{r.get(0), r.get(1), r.get(2), r.get(3), r.get(4)};
    T gap = r.get(10);
    const T f = force<Hyperbolic, T>(p, d, gap);
    r.set(10, gap);
    if constexpr (WithEnergy) x = dissipated<T>(p.k, fo, f, dd);
    return f;
  }
  // A gap law's SpringSpec numbers p[0] = gap, p[1] = side (as a double: validation reads it): gap >= 0 and side
  // +-1 (the registry's trait problems); true when one is reported.
  static constexpr std::string_view fix = "give a valid link description (model/hysteresis/bridge_links.hpp)";
  template <class Bad> static bool problems(const SpringSpec& s, Bad&& bad) {
    const double gap = s.p[0], side = s.p[1];
    if (!std::isfinite(gap) || gap < 0) return bad("link", "gap = {} must be >= 0 (m)", fix, gap), true;
    if (side != 1.0 && side != -1.0) return bad("link", "side = {} must be +1 or -1", fix, side), true;
    return false;
  }
};

// The registry's traits the gap laws share (G the law, with params and unpack): links only, not on the lane
// steppers, not fast_path; the gap's checks, rows, recoverable energy and step of GapSpring.
template <class G, bool Hyperbolic> struct GapTraits {
  static constexpr Roles roles{.link = true};
  static constexpr bool lane_stepper = false, fast_path = false;
  template <class Bad> static void problems(const SpringSpec& s, Bad&& bad) { GapSpring::problems(s, bad); }
  static double load(const SpringSpec& s, double d0, SpringRows& r) {
    return GapSpring::load<Hyperbolic>(G::params(G::unpack(s)), d0, r);
  }
  static double stored_energy(const SpringRows& r, double d, double f) { return GapSpring::stored_energy(r, d, f); }
  template <bool WithEnergy, class T, class R>
  POUNDING_INLINE static T step(const R& r, const T& fo, const T& d, const T& dd, const T&, T& x) {
    return GapSpring::step<Hyperbolic, WithEnergy, T>(r, fo, d, dd, x);
  }
};

// A cable restrainer: tension-only bilinear with slack (k = n E A / L, F_y, hardening alpha; slack usually the
// joint gap). side +1: it pulls when d = u_j - u_i exceeds the slack (j the right frame, i the left one).
struct TensionGap : GapTraits<TensionGap, false> {
  static constexpr std::string_view name = "restrainer";
  struct Spec {
    double k = 0.0, fy = std::numeric_limits<double>::infinity(), alpha = 0.0, slack = 0.0;
    int side = 1;
  };
  template <class T> using Params = GapParams<T>;
  static Params<double> params(const Spec& s) { return straight(s.k, s.fy, s.alpha, s.slack, s.side); }
  // A link (GapTraits); packed as k, fy, alpha and p = {slack, side}.
  static SpringSpec pack(const Spec& s) { return {s.k, s.fy, s.alpha, {s.slack, double(s.side)}}; }
  static Spec unpack(const SpringSpec& s) { return {s.k, s.fy, s.alpha, s.p[0], static_cast<int>(s.p[1])}; }
  static Params<double> straight(double k, double fy, double alpha, double gap, double side) {
    if (!std::isfinite(fy)) return {k, 0.0, std::numeric_limits<double>::infinity(), side, gap};
    return {k, alpha * k, fy - alpha * k * (gap + fy / k), side, gap};
  }
  // Linear (zero force) while the slack is never taken up.
  static bool stays_elastic(const Spec& s, double peak_abs_deformation, double margin) {
    return peak_abs_deformation <= margin * s.slack;
  }
  // Both branches are homogeneous of degree 1 in (d, F_y, slack).
  static std::optional<Spec> unscaled_equivalent(const Spec& s, double f) {
    Spec out = s;
    out.fy /= f, out.slack /= f;
    return out;
  }
};

// Abutment backfill (Caltrans SDC): the expansion gap, then elastic-perfectly-plastic (alpha = 0 by default) in
// compression, K_abut and P_bw (caltrans_abutment() below). side -1: a wall on the left of DOF j (it resists
// d < -gap); +1: a wall on the right.
struct CompressionGap : GapTraits<CompressionGap, false> {
  static constexpr std::string_view name = "abutment";
  struct Spec {
    double k = 0.0, fy = std::numeric_limits<double>::infinity(), alpha = 0.0, gap = 0.0;
    int side = 1;
  };
  template <class T> using Params = GapParams<T>;
  static Params<double> params(const Spec& s) { return TensionGap::straight(s.k, s.fy, s.alpha, s.gap, s.side); }
  // A link (GapTraits); packed as k, fy, alpha and p = {gap, side}.
  static SpringSpec pack(const Spec& s) { return {s.k, s.fy, s.alpha, {s.gap, double(s.side)}}; }
  static Spec unpack(const SpringSpec& s) { return {s.k, s.fy, s.alpha, s.p[0], static_cast<int>(s.p[1])}; }
  static bool stays_elastic(const Spec& s, double peak_abs_deformation, double margin) {
    return peak_abs_deformation <= margin * s.gap;
  }
  static std::optional<Spec> unscaled_equivalent(const Spec& s, double f) {
    Spec out = s;
    out.fy /= f, out.gap /= f;
    return out;
  }
};

// Caltrans SDC (v1.7 2013 §7.8.1) for a back wall of width w and height h (m): K_abut = K_i w (h / 5.5 ft) with
// K_i = 50 kip/in per ft of wall width (28.728155 kN/mm/m, exact conversion) for backfill meeting the Standard
// Specifications, P_bw = w h 5.0 ksf (h / 5.5 ft) (5 ksf = 239.401 kPa). T5.3: w 12 m, h 2 m -> 4.112835e8 N/m,
// 6.854726e6 N.
struct CaltransAbutment { double k, p_bw; };
inline CaltransAbutment caltrans_abutment(double width, double height) {
  const double ft = 0.3048, in = 0.0254, kip = 4448.2216152605;
  const double k_i = 50.0 * kip / in / ft, h_ref = 5.5 * ft, ksf5 = 5.0 * kip / (ft * ft);
  return {k_i * width * (height / h_ref), width * height * ksf5 * (height / h_ref)};
}

// The hyperbolic abutment (OpenSees HyperbolicGapMaterial; recommended per metre of wall width for a 1.68 m back
// wall: K_max 20300 kN/m, K_ur = K_max, R_f 0.7, F_ult 326 kN, gap 2.54 cm).
struct HyperbolicGap : GapTraits<HyperbolicGap, true> {
  static constexpr std::string_view name = "hyperbolic-abutment";
  struct Spec {
    double k_max = 0.0, k_ur = 0.0, rf = 0.7, f_ult = 0.0, gap = 0.0;
    int side = 1;
  };
  template <class T> using Params = GapParams<T>;
  static Params<double> params(const Spec& s) { return {s.k_ur, 1.0 / s.k_max, s.rf / s.f_ult, double(s.side), s.gap}; }
  // A link (GapTraits); packed as k = K_ur (the initial tangent validation and omega_max read), fy = F_ult, alpha = 0 and
  // p = {gap, side, K_max, R_f}.
  static SpringSpec pack(const Spec& s) { return {s.k_ur, s.f_ult, 0.0, {s.gap, double(s.side), s.k_max, s.rf}}; }
  static Spec unpack(const SpringSpec& s) { return {s.p[2], s.k, s.p[3], s.fy, s.p[0], static_cast<int>(s.p[1])}; }
  // The gap's checks, then K_max > 0, K_ur >= K_max, R_f in (0, 1], F_ult finite.
  template <class Bad> static void problems(const SpringSpec& s, Bad&& bad) {
    if (GapSpring::problems(s, bad)) return;
    const Spec h = unpack(s);
    const auto fix = GapSpring::fix;
    if (!(std::isfinite(h.k_max) && h.k_max > 0)) bad("link", "K_max = {} must be > 0 (N/m)", fix, h.k_max);
    else if (!(h.k_ur >= h.k_max))
      bad("link", "K_ur = {} is below K_max = {} (first loading would leave the envelope)", fix, h.k_ur, h.k_max);
    else if (!(h.rf > 0 && h.rf <= 1)) bad("link", "R_f = {} is outside (0, 1]", fix, h.rf);
    else if (!std::isfinite(h.f_ult)) bad("link", "F_ult = {} must be finite", fix, h.f_ult);
  }
  static bool stays_elastic(const Spec& s, double peak_abs_deformation, double margin) {
    return peak_abs_deformation <= margin * s.gap;
  }
  // F(f delta; K, R_f, F_ult) = f F(delta; K, R_f, F_ult / f), the gap scaled with it.
  static std::optional<Spec> unscaled_equivalent(const Spec& s, double f) {
    Spec out = s;
    out.f_ult /= f, out.gap /= f;
    return out;
  }
};

// Per-lane constants of a Q-Hyst spring and its state (mode: +-1 on the envelope toward +-, +-2 unloading from an
// anchor of that sign; x0 the start of the current reload line; dr, fr the anchor; dp >= d_y, dn <= -d_y the
// largest excursions).
template <class T> struct QHystParams { T k, ak, fy, beta; };
struct QHystState {
  double mode = 1.0, x0 = 0.0, dr = 0.0, fr = 0.0, dp = 0.0, dn = 0.0;
};

struct QHyst {
  static constexpr std::string_view name = "q-hyst";
  struct Spec {
    double k = 0.0, fy = 0.0, alpha = 0.0, beta = 0.5;
  };
  template <class T> using Params = QHystParams<T>;
  static Params<double> params(const Spec& s) { return {s.k, s.alpha * s.k, s.fy, s.beta}; }
  // A storey (bridge frames) or a link; packed as k, fy, alpha and p = {beta}.
  static constexpr Roles roles{.storey = true, .link = true};
  static constexpr bool lane_stepper = false;
  static SpringSpec pack(const Spec& s) { return {s.k, s.fy, s.alpha, {s.beta}}; }
  static Spec unpack(const SpringSpec& s) { return {s.k, s.fy, s.alpha, s.p[0]}; }
  // F_y finite, beta in [0, 1].
  template <class Bad> static void problems(const SpringSpec& s, Bad&& bad) {
    const auto fix = GapSpring::fix;
    if (!std::isfinite(s.fy)) bad("link", "F_y = {} must be finite for Q-Hyst", fix, s.fy);
    else if (!(s.p[0] >= 0 && s.p[0] <= 1)) bad("link", "beta = {} is outside [0, 1]", fix, s.p[0]);
  }
  // The system stepper's rows (k, alpha k, F_y, beta, then the state mode, x0, dr, fr, dp, dn), loaded from rest at
  // d = 0 to d0; the recoverable energy from them.
  static double load(const SpringSpec& s, double d0, SpringRows& r) {
    const Params<double> p = params(unpack(s));
    QHystState st = initial(p);
    const double f0 = step(p, st, 0.0, d0, 0.0);
    r[0] = p.k, r[1] = p.ak, r[2] = p.fy, r[3] = p.beta;
    r[4] = st.mode, r[5] = st.x0, r[6] = st.dr, r[7] = st.fr, r[8] = st.dp, r[9] = st.dn;
    return f0;
  }
  static double stored_energy(const SpringRows& r, double, double f) {
    return strain_energy(Params<double>{r[0], r[1], r[2], r[3]}, QHystState{r[4], r[5], r[6], r[7], r[8], r[9]}, f);
  }
  // The system stepper's step, lane by lane (the state is event-driven): the rows' numbers and state, the force at d
  // from fo over dd, the state written back (r.lane(slot, l)); the dissipation in x (WithEnergy).
  static constexpr bool fast_path = false;
  template <bool WithEnergy, class T, class R>
  POUNDING_INLINE static T step(const R& r, const T& fo, const T& d, const T& dd, const T&, T& x) {
    constexpr int W = lane::width_v<T>;
    alignas(64) double out[W], diss[W];
    for (int l = 0; l < W; ++l) {
      const Params<double> p{r.get(0)[l], r.get(1)[l], r.get(2)[l], r.get(3)[l]};
      QHystState st{r.get(4)[l], r.get(5)[l], r.get(6)[l], r.get(7)[l], r.get(8)[l], r.get(9)[l]};
      const double f0 = fo[l], e0 = strain_energy(p, st, f0);
      out[l] = step(p, st, d[l] - dd[l], d[l], f0);
      diss[l] = std::fma(0.5 * (f0 + out[l]), dd[l], -(strain_energy(p, st, out[l]) - e0));
      for (const auto& [slot, v] : {std::pair{4, st.mode}, std::pair{5, st.x0}, std::pair{6, st.dr},
                                    std::pair{7, st.fr}, std::pair{8, st.dp}, std::pair{9, st.dn}})
        r.lane(slot, l) = v;
    }
    if constexpr (WithEnergy) x = lane::load<T>(diss);
    return lane::load<T>(out);
  }
  static QHystState initial(const Params<double>& p) {
    QHystState st;
    st.dp = p.fy / p.k, st.dn = -p.fy / p.k;
    return st;
  }
  static double primary(const Params<double>& p, double d) {
    const double dy = p.fy / p.k, a = std::abs(d);
    const double f = a <= dy ? p.k * a : std::fma(p.ak, a - dy, p.fy);
    return d < 0 ? -f : f;
  }
  static double unloading_stiffness(const Params<double>& p, const QHystState& st) {
    const double dy = p.fy / p.k, dm = std::max(st.dp, -st.dn);
    return dm <= dy ? p.k : p.k * std::pow(dy / dm, p.beta);
  }
  // the envelope toward sigma: the reload line from (x0, 0) to the peak on that side, then the primary curve
  static double envelope(const Params<double>& p, const QHystState& st, double sigma, double d) {
    const double dt = sigma > 0 ? st.dp : st.dn;
    if (sigma * (d - dt) >= 0 || sigma * (dt - st.x0) <= 0) return primary(p, d);
    return primary(p, dt) * ((d - st.x0) / (dt - st.x0));
  }
  // The force at d1 after the increment from d0 (force f0), updating the state.
  static double step(const Params<double>& p, QHystState& st, double d0, double d1, double f0) {
    if (d1 == d0) return f0;
    const double dir = d1 > d0 ? 1.0 : -1.0;
    double d = d0, f = f0;
    for (int it = 0; it < 8; ++it) {
      const double sigma = st.mode > 0 ? 1.0 : -1.0;
      if (std::abs(st.mode) < 1.5) {  // on the envelope toward sigma
        if (dir == sigma) {
          const double out = envelope(p, st, sigma, d1);
          if (sigma > 0 && d1 > st.dp) st.dp = d1;
          if (sigma < 0 && d1 < st.dn) st.dn = d1;
          return out;
        }
        st.dr = d, st.fr = f, st.mode = 2.0 * sigma;  // a reversal: unload from here
        continue;
      }
      const double ku = unloading_stiffness(p, st);
      if (dir == sigma) {  // back toward the anchor: k_u up to it, then the branch it left
        if (sigma * (d1 - st.dr) <= 0) return std::fma(ku, d1 - st.dr, st.fr);
        st.mode = sigma, d = st.dr, f = st.fr;
        continue;
      }
      const double xc = st.dr - st.fr / ku;  // where the unloading line crosses zero force
      if (sigma * (d1 - xc) >= 0) return std::fma(ku, d1 - st.dr, st.fr);
      st.mode = -sigma, st.x0 = xc, d = xc, f = 0.0;
    }
    return f;
  }
  static double strain_energy(const Params<double>& p, const QHystState& st, double f) {
    return 0.5 * f * f / unloading_stiffness(p, st);
  }
  // Linear while |d| never passes d_y (k_u = k there).
  static bool stays_elastic(const Spec& s, double peak_abs_deformation, double margin) {
    return peak_abs_deformation <= margin * s.fy / s.k;
  }
  // Every branch scales with (d, F_y): d_y / d_m is invariant.
  static std::optional<Spec> unscaled_equivalent(const Spec& s, double f) {
    Spec out = s;
    out.fy /= f;
    return out;
  }
};

}  // namespace pounding::model
