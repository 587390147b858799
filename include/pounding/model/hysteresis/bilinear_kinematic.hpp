#pragma once
// Bilinear kinematic hardening, closed-form return (branch-free): the trial force fs + k du is clamped into
// the band alpha k u +/- (1 - alpha) fy (issue #2; exact for a monotone increment). Written over the lane type.
// Its per-lane parameters live in the tile's four slots of each body (k, ak, qy, kp; kernel/tile.hpp).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

#include "pounding/kernel/lane.hpp"
#include "pounding/kernel/tile.hpp"
#include "pounding/model/hysteresis/spring_spec.hpp"

namespace pounding::model {

struct BilinearKinematic {
  static constexpr std::string_view name = "bilinear";
  using Spec = Structure;  // k, fy (inf: elastic), alpha; m and c belong to the body
  // Per-lane constants: k, alpha k, (1 - alpha) fy (qy), (1 - alpha) k (kp, 1 when k = 0).
  template <class T> struct Params { T k, ak, qy, kp; };

  static Params<double> params(const Structure& s) {
    return {s.k, s.alpha * s.k, std::isfinite(s.fy) ? (1.0 - s.alpha) * s.fy : kernel::elastic_qy,
            s.k > 0 ? (1.0 - s.alpha) * s.k : 1.0};
  }
  static void store(kernel::Tile& t, int body, int i, const Params<double>& p) {
    (body == 0 ? t.k1 : t.k2)[i] = p.k, (body == 0 ? t.ak1 : t.ak2)[i] = p.ak;
    (body == 0 ? t.qy1 : t.qy2)[i] = p.qy, (body == 0 ? t.kp1 : t.kp2)[i] = p.kp;
  }
  template <class T> POUNDING_INLINE static Params<T> load(const kernel::Tile& t, int body, int i) {
    using lane::load;
    return body == 0 ? Params<T>{load<T>(t.k1 + i), load<T>(t.ak1 + i), load<T>(t.qy1 + i), load<T>(t.kp1 + i)}
                     : Params<T>{load<T>(t.k2 + i), load<T>(t.ak2 + i), load<T>(t.qy2 + i), load<T>(t.kp2 + i)};
  }
  // the spring at its elastic force from a displacement u0 at rest, returned into the band
  static double initial_force(const Params<double>& p, double u0) {
    return std::clamp(p.k * u0, p.ak * u0 - p.qy, p.ak * u0 + p.qy);
  }

  template <class T> POUNDING_INLINE static T trial(T fs_old, T k, T du) { return fs_old + k * du; }
  template <class T> POUNDING_INLINE static T returned(T trial, T ak_u_new, T qy) {
    return lane::min(lane::max(trial, ak_u_new - qy), ak_u_new + qy);
  }
  // The force after an increment du from the committed force fs_old, at the new displacement u_new.
  template <class T> POUNDING_INLINE static T restoring(const Params<T>& p, T fs_old, T du, T u_new) {
    return returned(trial(fs_old, p.k, du), p.ak * u_new, p.qy);
  }
  // Newmark's tangent: k while the return left the trial force alone (elastic), alpha k on the band.
  template <class T> POUNDING_INLINE static T tangent(const Params<T>& p, T fs_old, T du, T fs_new) {
    return lane::select(trial(fs_old, p.k, du) == fs_new, p.k, p.ak);
  }
  // Plastic dissipation of the increment, exact: qy |trial - returned| / kp.
  template <class T> POUNDING_INLINE static T dissipated(const Params<T>& p, T fs_old, T du, T fs_new) {
    return p.qy * lane::abs(trial(fs_old, p.k, du) - fs_new) / p.kp;
  }
  // Recoverable energy: alpha k u^2 / 2 + q^2 / (2 (k - alpha k)), q = fs - alpha k u the elasto-plastic part.
  // The two contractions are pinned to the ones GCC picked when this was inlined into the out-of-line
  // collect_lane (the stored digests' e_strain); left free, they follow the inlining context.
  static double strain_energy(const Params<double>& p, double u, double fs) {
    const double q = std::fma(-p.ak, u, fs), kp = p.k - p.ak;
    return std::fma(0.5 * p.ak * u, u, kp > 0 ? 0.5 * q * q / kp : 0.0);
  }

  // Driver traits (model/hysteresis/registry.hpp). Every role; the only model the lane steppers (Newmark, RK4) run,
  // as they need its tangent. Packed as k, fy, alpha alone (m and c belong to the body).
  static constexpr Roles roles{.storey = true, .isolator = true, .link = true};
  static constexpr bool lane_stepper = true;
  static SpringSpec pack(const Spec& s) { return {s.k, s.fy, s.alpha}; }
  static Spec unpack(const SpringSpec& s) { return Structure{0.0, s.k, 0.0, s.fy, s.alpha}; }
  template <class Bad> static void problems(const SpringSpec&, Bad&&) {}  // k, fy, alpha: the driver's checks
  // The system stepper's rows (k, alpha k, qy, kp) and the force at rest in d0; the recoverable energy from them.
  static double load(const SpringSpec& s, double d0, SpringRows& r) {
    const Params<double> p = params(unpack(s));
    r[0] = p.k, r[1] = p.ak, r[2] = p.qy, r[3] = p.kp;
    return initial_force(p, d0);
  }
  static double stored_energy(const SpringRows& r, double d, double f) {
    return strain_energy(Params<double>{r[0], r[1], r[2], r[3]}, d, f);
  }
  // The system stepper's step (the registry's trait): the return from the committed force fo over the increment dd
  // to the deformation d, from the rows r (r.get(slot)); the dissipation in x (WithEnergy). Every spring of this
  // model: fast_path (the driver's straight bilinear loop and the stick path, with these operations).
  static constexpr bool fast_path = true;
  template <bool WithEnergy, class T, class R>
  POUNDING_INLINE static T step(const R& r, const T& fo, const T& d, const T& dd, const T&, T& x) {
    const Params<T> p{r.get(0), r.get(1), r.get(2), r.get(3)};
    const T f = restoring<T>(p, fo, dd, d);
    if constexpr (WithEnergy) x = dissipated<T>(p, fo, dd, f);
    return f;
  }
  // Elastic while |u| <= fy / k: the expression study/run.cpp's
  // elastic_at evaluated before the registry, verbatim (margin * fy / k), so its decisions keep their bits.
  static bool stays_elastic(const Spec& s, double peak_abs_deformation, double margin) {
    return peak_abs_deformation <= margin * s.fy / s.k;
  }
  // R(f w; k, fy, alpha) = f R(w; k, fy / f, alpha): both branches are homogeneous of degree 1 in (w, fy).
  static std::optional<Spec> unscaled_equivalent(const Spec& s, double f) {
    Spec out = s;
    out.fy /= f;
    return out;
  }
};

}  // namespace pounding::model
