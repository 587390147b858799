#pragma once
// What every contact law is written against (architecture.md 2.3): the lane-generic kinematics, parameters
// and latched state, the Hertz exponent as a type, the traits the steppers and validation read, and the
// concept every law in contact/registry.hpp satisfies. A law is a struct of static templates over the lane
// type T (double or simd::V), written once; its expression order is the kernel's (FMA contraction under
// -march follows the expression shape, architecture.md 2.12 risk 1).
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>

#include "pounding/contact/model.hpp"
#include "pounding/core/enum_names.hpp"
#include "pounding/kernel/lane.hpp"

namespace pounding::contact {

template <class T> struct Kin { T d, dd; };        // penetration delta = u1 - u2 - gap and its rate
template <class T> struct Params { T kc, cd; };    // contact stiffness; the law's damping constant
template <class T> struct State { T iv0; };        // latched 1/v0 (Hertzdamp)
template <class T> struct Shared { T sq; };        // sqrt of the penetration, reused by the stability guard
template <class T> struct Tangent { T F, dFd, dFv; };  // Newmark: force and its derivatives by d and dd

// RestitutionKind (what one free impact delivers against the e asked) is in contact/model.hpp, beside the damping
// laws that declare it too.
// How long one impact lasts, for the time step of a single-impact analysis: Hertz theory, half a period
// of the linear spring (pi sqrt(meff / kc)), or instantaneous (impulsive laws).
enum class DurationForm : std::uint8_t { hertz, linear, impulsive };

struct LawTraits {
  bool has_force = true;          // a force element (false: none, the impulsive stereomechanical)
  bool impulsive = false;         // momentum exchange at the located closing instant (stereomechanical)
  bool needs_stiffness = true;    // kc > 0 required
  bool explicit_stiffness = false; // kc must be given: the Hertz kh of equivalent spheres (N/m^1.5) is not this
                                   // law's stiffness (linear, kelvin: N/m)
  bool needs_restitution = false; // 0 < e <= 1 required
  bool latches_v0 = false;        // the force depends on the approach velocity latched at onset
  bool uses_exponent = false;     // the Hertz exponent n of ContactModel applies
  std::string_view stiffness_unit = "N/m";
  RestitutionKind restitution = RestitutionKind::exact;
  std::string_view restitution_note = "";  // one line for `pounding collide`: what it delivers and why
  bool restitution_from_damping = false;   // the damping law (ContactModel::damping) decides (Hertzdamp)
  DurationForm duration = DurationForm::hertz;
};

// The integration schemes a law's resolution limits distinguish (physics::scheme_of maps a stepper onto one):
// rk4 with located contact onset differs from rk4.
enum class Scheme : std::uint8_t { central_difference, newmark, rk4, rk4_located, nigam_jennings };
inline constexpr std::size_t scheme_count = 5;

// A law's accuracy limits on h omega_c, one per scheme (the resolution guard, physics/resolution.hpp): the
// largest h omega_c up to which one free impact's peak force stays within 1 % of the converged impact, measured
// by `pounding accuracy resolution` and checked by ctest AccuracyStability.ResolutionLimitsEqualTheMeasurement.
// Every law declares `static constexpr ResolutionLimits resolution{...}` (the contact::Law concept requires it),
// so a new law cannot run with no limit or another law's: measure it, or declare unmeasured() (no coarse status).
struct ResolutionLimits {
  double central_difference, newmark, rk4, rk4_located, nigam_jennings;
  constexpr double operator[](Scheme s) const {
    switch (s) {
      case Scheme::central_difference: return central_difference;
      case Scheme::newmark: return newmark;
      case Scheme::rk4: return rk4;
      case Scheme::rk4_located: return rk4_located;
      case Scheme::nigam_jennings: return nigam_jennings;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
  // no force element (none, stereomechanical): no contact frequency, no limit
  static constexpr ResolutionLimits no_force_element() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {inf, inf, inf, inf, inf};
  }
  // a law not (yet) measured, e.g. a test law outside the registry: no limit, so never marked coarse
  static constexpr ResolutionLimits unmeasured() { return no_force_element(); }
};
static_assert(sizeof(ResolutionLimits) == scheme_count * sizeof(double), "one limit per Scheme");

// The Hertz exponent: FixedExponent<3, 2> takes d^1.5 as d sqrt(d) and shares sqrt(d) with the guard;
// RuntimeExponent takes std::pow (replaces the kernel's former N15 flag).
template <int P, int Q> struct FixedExponent {
  static_assert(P == 3 && Q == 2, "only 3/2 has a closed form; use RuntimeExponent");
  static constexpr double value() { return 1.5; }
  template <class T> POUNDING_INLINE T power(T dp, Shared<T>& sh) const {
    sh.sq = lane::sqrt(dp);
    return dp * sh.sq;
  }
  // n kc d^(n-1), valid where d > 0 (the guard masks the rest)
  template <class T> POUNDING_INLINE T stiffness(T, T kc, const Shared<T>& sh) const { return 1.5 * kc * sh.sq; }
};
struct RuntimeExponent {
  double n = 1.5;
  double value() const { return n; }
  template <class T> POUNDING_INLINE T power(T dp, Shared<T>&) const {
    const double e = n;
    return lane::map(dp, [e](double x) { return x > 0.0 ? std::pow(x, e) : 0.0; });
  }
  template <class T> POUNDING_INLINE T stiffness(T d, T kc, const Shared<T>&) const {
    const double e = n;
    return lane::map2(d, kc, [e](double x, double k) { return x > 0.0 ? e * k * std::pow(x, e - 1.0) : 0.0; });
  }
};
using Exp15 = FixedExponent<3, 2>;

// The force-side functions of a law without a force element (none; the impulsive stereomechanical law, which
// acts through its exchange instead): zero force, tangent, stiffness and stored energy, nothing to latch.
struct NoForceElement {
  template <class T, class Exp> POUNDING_INLINE static T force(Kin<T>, Params<T>, State<T>, Exp, Shared<T>&, T& clamp) {
    clamp = T(0.0);
    return T(0.0);
  }
  template <class T, class Exp> POUNDING_INLINE static Tangent<T> tangent(Kin<T>, Params<T>, State<T>, Exp) {
    return {T(0.0), T(0.0), T(0.0)};
  }
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(Kin<T>, Params<T>, State<T>, Exp, const Shared<T>&) { return T(0.0); }
  template <class T> POUNDING_INLINE static T stored_energy(T, T, double) { return T(0.0); }
  template <class T> POUNDING_INLINE static void on_onset(State<T>&, lane::mask_t<T>, T, double) {}
  static double damping_constant(const ContactModel&, double, double, double) { return 0.0; }
};

// A law declares its resolution limits (a required trait, architecture.md 2.4.5).
template <class L>
concept DeclaresResolutionLimits = requires {
  { L::resolution } -> std::convertible_to<ResolutionLimits>;
};

// Every law: a name, traits, its resolution limits, and the five functions the kernel calls.
template <class L>
concept Law = DeclaresResolutionLimits<L> && requires(Kin<double> k, Params<double> p, State<double> s, Shared<double> sh, double x,
                       const ContactModel& cm) {
  { L::name } -> std::convertible_to<std::string_view>;
  { L::traits } -> std::convertible_to<LawTraits>;
  { L::template force<double>(k, p, s, Exp15{}, sh, x) } -> std::same_as<double>;
  { L::template force<simd::V>(Kin<simd::V>{}, Params<simd::V>{}, State<simd::V>{}, RuntimeExponent{},
                               std::declval<Shared<simd::V>&>(), std::declval<simd::V&>()) } -> std::same_as<simd::V>;
  { L::template tangent<double>(k, p, s, RuntimeExponent{}) } -> std::same_as<Tangent<double>>;
  { L::template linear_stiffness<double>(k, p, s, Exp15{}, sh) } -> std::same_as<double>;
  { L::template stored_energy<double>(x, x, 1.5) } -> std::same_as<double>;
  { L::damping_constant(cm, x, x, x) } -> std::same_as<double>;
};

// A law whose damping constant follows from the model and e alone, and may be costly (Hertzdamp's calibrated
// xibar solves the scale-free impact), also offers damping_of_e; run_batch then takes each distinct e once
// per call (physics::DampingTable) instead of a process-wide cache.
template <class L>
concept DampingFromRestitution = requires(const ContactModel& cm, double e) {
  { L::damping_of_e(cm, e) } -> std::same_as<double>;
};

// The latch every law shares unless it overrides it: Hertzdamp's v0 = max(approach speed, v0_min) at onset.
template <class T>
POUNDING_INLINE void latch_v0(State<T>& s, lane::mask_t<T> on, T approach, double v0_min) {
  s.iv0 = lane::select(on, T(1.0) / lane::max(approach, T(v0_min)), s.iv0);
}

}  // namespace pounding::contact
