#pragma once
// Instantaneous momentum exchange with restitution e (muthukumar eq. 2) at the closing instant located
// inside the step: the gap closed at the fraction s of the step, where the velocities are interpolated;
// the exchange is applied there and the rest of the step is flown with the new velocities.
#include "pounding/contact/law.hpp"

namespace pounding::contact {

template <class T> struct ImpactIn {
  T d, d_old;          // penetration at the end and at the start of the step
  T closing;           // v1 - v2 at the end of the step
  T v1o, v2o, v1, v2;  // velocities at the start and the end of the step
  T m1, m2, msum, meff, e;
  T h;                // step length
};
template <class T> struct ImpactOut {
  lane::mask_t<T> hit;
  T dv1, dv2;  // velocity jumps (0 where no hit)
  T rest;      // (1 - s) h: the time flown after the exchange
  T loss;      // energy lost: meff (1 - e^2) rel^2 / 2 (0 where no hit)
};

struct Stereomechanical : NoForceElement {
  static constexpr std::string_view name = "stereomechanical";
  static constexpr LawTraits traits{
      .has_force = false, .impulsive = true, .needs_stiffness = false, .needs_restitution = true,
      .restitution_note = "instantaneous momentum exchange with e: delivers e by construction",
      .duration = DurationForm::impulsive};
  static constexpr ResolutionLimits resolution = ResolutionLimits::no_force_element();

  // An impact: the gap closed in this step, or the bodies still overlap and approach.
  template <class T> POUNDING_INLINE static ImpactOut<T> exchange(const ImpactIn<T>& in) {
    const T zero(0.0), one(1.0);
    ImpactOut<T> out;
    out.hit = (in.d > zero) && ((in.closing > zero) || !(in.d_old > zero));
    const T den = in.d - in.d_old;
    T s;
    if constexpr (lane::width_v<T> == 1)  // the division only where taken: the scalar kernel's code shape
      s = in.d_old > 0.0 ? 0.0 : -in.d_old / (den > 0.0 ? den : 1.0);
    else
      s = lane::select(in.d_old > zero, zero, -in.d_old / lane::select(den > zero, den, one));
    s = lane::min(lane::max(s, zero), one);
    const T w1 = in.v1o + s * (in.v1 - in.v1o), w2 = in.v2o + s * (in.v2 - in.v2o);
    T rel = w1 - w2;
    rel = lane::select(rel > zero, rel, lane::max(in.closing, zero));  // never pulls together
    out.dv1 = lane::select(out.hit, -(one + in.e) * in.m2 * rel / in.msum, zero);
    out.dv2 = lane::select(out.hit, (one + in.e) * in.m1 * rel / in.msum, zero);
    out.rest = (one - s) * in.h;
    out.loss = lane::select(out.hit, 0.5 * in.meff * (one - in.e * in.e) * rel * rel, zero);
    return out;
  }
};

}  // namespace pounding::contact
