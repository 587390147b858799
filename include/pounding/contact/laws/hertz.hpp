#pragma once
// F = kc delta^n (muthukumar eq. 6); elastic.
#include "pounding/contact/laws/hertz_power.hpp"

namespace pounding::contact {

struct Hertz {
  static constexpr std::string_view name = "hertz";
  static constexpr LawTraits traits{
      .uses_exponent = true, .stiffness_unit = "N/m^n", .restitution = RestitutionKind::elastic,
      .restitution_note = "the hertz law has no damping: it delivers e = 1 whatever e is asked"};
  // measured h omega_c limits (physics/resolution.hpp; docs/resolution_limits.csv)
  static constexpr ResolutionLimits resolution{.central_difference = 0.366, .newmark = 0.215, .rk4 = 0.274,
                                               .rk4_located = 0.281, .nigam_jennings = 0.241};
  template <class T, class Exp>
  POUNDING_INLINE static T force(Kin<T> k, Params<T> p, State<T>, Exp n, Shared<T>& sh, T& clamp) {
    clamp = T(0.0);
    return p.kc * n.power(lane::max(k.d, T(0.0)), sh);
  }
  template <class T, class Exp> POUNDING_INLINE static Tangent<T> tangent(Kin<T> k, Params<T> p, State<T>, Exp n) {
    T pw, dpw;
    hertz_power::pow_and_slope(k.d, n.value(), pw, dpw);
    return {p.kc * pw, p.kc * dpw, T(0.0)};
  }
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(Kin<T> k, Params<T> p, State<T>, Exp n, const Shared<T>& sh) {
    return n.stiffness(k.d, p.kc, sh);
  }
  template <class T> POUNDING_INLINE static T stored_energy(T dp, T kc, double n) { return hertz_power::stored(dp, kc, n); }
  template <class T> POUNDING_INLINE static void on_onset(State<T>&, lane::mask_t<T>, T, double) {}
  static double damping_constant(const ContactModel&, double, double, double) { return 0.0; }
};

}  // namespace pounding::contact
