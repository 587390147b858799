#pragma once
// The contact's tangent stiffness at a penetration, for the resolution guard (physics/resolution.hpp): each law
// carries it as its linear_stiffness (the function the stability guard already asks, contact/stability.hpp),
// evaluated at rest in the penetration (ddelta = 0), which is the state at the peak penetration of an impact:
//   linear, Kelvin: kc (Kelvin's damper ck ddelta is not a stiffness; its effect on the step is in the measured
//                   accuracy limit, which is taken with the same definition of omega_c)
//   Hertz family (hertz, hertzdamp, jankowski): n kc delta^(n-1), largest at the peak penetration (n > 1); the
//                   Hertzdamp factor (1 + xibar ddelta / v0) is 1 there (the approach phase's damped tangent can
//                   be up to 1 + xibar larger earlier in the impact: also calibrated into the measured limit)
//   none, stereomechanical: no force element, no omega_c (NaN: not applicable)
// A new law brings its own through linear_stiffness; nothing to register here.
#include <cmath>
#include <limits>

#include "pounding/contact/law.hpp"

namespace pounding::contact {

template <class L> double tangent_at_penetration(double pen, double kc, double cd, double n) {
  if constexpr (!L::traits.has_force) {
    return std::numeric_limits<double>::quiet_NaN();
  } else {
    if (!(pen > 0.0)) return 0.0;  // never touched
    Shared<double> sh{std::sqrt(pen)};
    return L::template linear_stiffness<double>({pen, 0.0}, {kc, cd}, {0.0}, RuntimeExponent{n}, sh);
  }
}

// The penetration the guard evaluates the tangent at: the lane's peak penetration, or, when a lane reports a
// contact force but no positive end-of-step penetration (seen: Nigam-Jennings with the linear law at h omega_c
// 2.49-2.77, inside its unstable contact window, 47,700 N with peak penetration <= 0), the elastic penetration
// that carries the peak force, (F / kc)^(1/n): otherwise such a lane would read as "never touched" (0).
template <class L> double guard_penetration(double pen, double peak_force, double kc, double n) {
  if (pen > 0.0 || !(peak_force > 0.0) || !(kc > 0.0)) return pen;
  const double n_law = L::traits.uses_exponent ? n : L::traits.stiffness_unit == "N/m" ? 1.0 : 1.5;
  return std::pow(peak_force / kc, 1.0 / n_law);
}

}  // namespace pounding::contact
