#pragma once
// The divergence guard, written once for both lane types (architecture.md 2.4), and the steppers' contact
// stability limits (the contact-stability test itself is contact/stability.hpp: it asks the law):
//  * divergence: |u1| + |u2| above the limit (1) or anything non-finite (2); a bad lane is frozen at rest
//    so that it neither slows the tile with inf/NaN arithmetic nor pollutes anything.
#include "pounding/kernel/lane.hpp"

namespace pounding::kernel {

// Stability limits (omega h)^2 of the explicit treatment of contact, per stepper.
inline constexpr double limit2_central_difference = 4.0;  // omega h < 2
inline constexpr double limit2_nigam_jennings = 4.0;      // its predictor-corrector, as central difference
inline constexpr double limit2_rk4 = 2.8 * 2.8;           // RK4's real-axis stability bound, omega h < 2.8

// 0 ok, 1 diverged (displacement sum above lim), 2 non-finite
template <class T> POUNDING_INLINE T divergence_code(T sdisp, T sv, T lim) {
  const T zero(0.0);
  T code = lane::select(sdisp <= lim, zero, lane::select(sdisp - sdisp == zero, T(1.0), T(2.0)));
  return lane::select(sv - sv == zero, code, T(2.0));
}
// sum of |u| and of |v| + |a| (in that order: the bits of the non-finite test)
template <class T> POUNDING_INLINE T disp_sum(T u1, T u2) { return lane::abs(u1) + lane::abs(u2); }
template <class T> POUNDING_INLINE T rate_sum(T v1, T v2, T a1, T a2) {
  return lane::abs(v1) + lane::abs(v2) + lane::abs(a1) + lane::abs(a2);
}
template <class T> POUNDING_INLINE lane::mask_t<T> within(T sdisp, T sv, T lim) {
  return (sdisp <= lim) && (sv - sv == T(0.0));
}

// The state the guard freezes.
template <class T> struct Freezable {
  T &u1, &u2, &v1, &v2, &a1, &a2, &fs1, &fs2, &F;
};
// Updates `bad` with this step's code and zeroes the state of every bad lane.
template <class T> POUNDING_INLINE void check_and_freeze(T& bad, Freezable<T> s, T lim) {
  const T zero(0.0);
  bad = lane::max(bad, divergence_code(disp_sum(s.u1, s.u2), rate_sum(s.v1, s.v2, s.a1, s.a2), lim));
  const auto frozen = bad > zero;
  s.u1 = lane::select(frozen, zero, s.u1), s.u2 = lane::select(frozen, zero, s.u2);
  s.v1 = lane::select(frozen, zero, s.v1), s.v2 = lane::select(frozen, zero, s.v2);
  s.a1 = lane::select(frozen, zero, s.a1), s.a2 = lane::select(frozen, zero, s.a2);
  s.fs1 = lane::select(frozen, zero, s.fs1), s.fs2 = lane::select(frozen, zero, s.fs2);
  s.F = lane::select(frozen, zero, s.F);
}

}  // namespace pounding::kernel
