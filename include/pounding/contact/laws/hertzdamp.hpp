#pragma once
// F = kc delta^n (1 + xibar ddelta / v0), clamped non-tensile (muthukumar eq. 10, generalised);
// xibar from e by ContactModel::damping, v0 the approach speed latched at onset (as 1/v0).
#include "pounding/contact/laws/hertz_power.hpp"

namespace pounding::contact {

struct Hertzdamp {
  static constexpr std::string_view name = "hertzdamp";
  static constexpr LawTraits traits{.needs_restitution = true, .latches_v0 = true, .uses_exponent = true,
                                    .stiffness_unit = "N/m^n", .restitution_from_damping = true};
  // measured h omega_c limits (physics/resolution.hpp; docs/resolution_limits.csv)
  static constexpr ResolutionLimits resolution{.central_difference = 0.274, .newmark = 0.214, .rk4 = 0.268,
                                               .rk4_located = 0.268, .nigam_jennings = 0.235};
  template <class T, class Exp>
  POUNDING_INLINE static T force(Kin<T> k, Params<T> p, State<T> s, Exp n, Shared<T>& sh, T& clamp) {
    const T zero(0.0);
    T raw = p.kc * n.power(lane::max(k.d, zero), sh) * (T(1.0) + p.cd * k.dd * s.iv0);
    clamp = lane::select(raw < zero, T(1.0), zero);
    return lane::max(raw, zero);
  }
  // Newton: without the clamp, so the residual is smooth
  template <class T, class Exp> POUNDING_INLINE static Tangent<T> tangent(Kin<T> k, Params<T> p, State<T> s, Exp n) {
    T pw, dpw;
    hertz_power::pow_and_slope(k.d, n.value(), pw, dpw);
    return {p.kc * pw * (T(1.0) + p.cd * k.dd * s.iv0), p.kc * dpw * (T(1.0) + p.cd * k.dd * s.iv0),
            p.kc * pw * p.cd * s.iv0};
  }
  // the Hertz stiffness scaled by the damping factor while approaching
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(Kin<T> k, Params<T> p, State<T> s, Exp n, const Shared<T>& sh) {
    return n.stiffness(k.d, p.kc, sh) * lane::max(T(1.0), T(1.0) + p.cd * k.dd * s.iv0);
  }
  template <class T> POUNDING_INLINE static T stored_energy(T dp, T kc, double n) { return hertz_power::stored(dp, kc, n); }
  template <class T> POUNDING_INLINE static void on_onset(State<T>& s, lane::mask_t<T> on, T approach, double v0_min) {
    latch_v0(s, on, approach, v0_min);
  }
  static double damping_of_e(const ContactModel& cm, double e) { return hertzdamp_xibar(cm.damping, e, cm.n); }
  static double damping_constant(const ContactModel& cm, double, double e, double) { return damping_of_e(cm, e); }
};

}  // namespace pounding::contact
