#pragma once
// Bilinear kinematic hardening, closed-form return (branch-free): the trial force fs + k du is clamped into
// the band alpha k u +/- (1 - alpha) fy (issue #2; exact for a monotone increment). Written over the lane type.
#include "pounding/kernel/lane.hpp"

namespace pounding::model {

struct BilinearKinematic {
  // Per-lane constants: k, alpha k, (1 - alpha) fy (qy), (1 - alpha) k (kp, 1 when k = 0).
  template <class T> struct Params { T k, ak, qy, kp; };
  template <class T> POUNDING_INLINE static T trial(T fs_old, T k, T du) { return fs_old + k * du; }
  template <class T> POUNDING_INLINE static T returned(T trial, T ak_u_new, T qy) {
    return lane::min(lane::max(trial, ak_u_new - qy), ak_u_new + qy);
  }
  template <class T> POUNDING_INLINE static T restoring(T fs_old, T k, T du, T ak_u_new, T qy) {
    return returned(trial(fs_old, k, du), ak_u_new, qy);
  }
  // Recoverable energy: alpha k u^2 / 2 + q^2 / (2 (k - alpha k)), q = fs - alpha k u the elasto-plastic part.
  static double strain_energy(double k, double ak, double u, double fs) {
    const double q = fs - ak * u, kp = k - ak;
    return 0.5 * ak * u * u + (kp > 0 ? 0.5 * q * q / kp : 0.0);
  }
};

}  // namespace pounding::model
