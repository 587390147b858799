#pragma once
// A single free impact run through the kernel (no springs, no ground motion): the effective restitution
// and the contact's peak force, penetration, duration and energy loss.
#include <cstdint>
#include <string>
#include <string_view>

#include "pounding/contact/law.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/physics/batch.hpp"

namespace pounding {

struct ImpactResult {
  double e_effective = 0, peak_force = 0, peak_penetration = 0, duration = 0;
  // energy_lost (J) as a fraction of the initial kinetic energy 1/2 m1 v0^2 (mass 2 at rest), not of the relative
  // kinetic energy 1/2 m1 m2 / (m1 + m2) v0^2 that `pounding collide` also prints
  double energy_lost = 0, energy_lost_fraction = 0;
  int clamps = 0;
  double h_omega_contact = 0;  // the resolution guard's h omega_c (physics/resolution.hpp)
  int restitution_outside = 0;  // with an e(v0) hook: the onset's v0 outside the curve's valid range
  LaneStatus status = LaneStatus::ok;
};

// What a contact law promises about the restitution it delivers (docs/accuracy.md, "Restitution delivered",
// measured with one free impact of equal masses):
//   elastic      linear, hertz: no damping, e = 1 whatever is asked
//   exact        stereomechanical (momentum exchange with e), hertzdamp + calibrated (xibar solved for e)
//   approximate  hertzdamp + flores / hu-guo / gonthier (within 0.05 of e), jankowski (within 0.01), kelvin
//                (its damping ratio is exact only without the non-tensile clamp: 0.675 at 0.65, 0.397 at 0.3)
//   saturating   hertzdamp + lankarani-nikravesh / hunt-crossley: derived for e near 1; xibar is bounded as
//                e -> 0, so they deliver more than e (LN: 0.775 at 0.65) and never less than `floor`
using contact::RestitutionKind;  // contact/law.hpp: each law's traits say what it delivers
struct RestitutionPromise {
  RestitutionKind kind = RestitutionKind::exact;
  double floor = 0.0;  // saturating laws: the restitution delivered as e -> 0 (the smallest they can deliver)
  std::string note;    // one line: what the law delivers and why
};
RestitutionPromise restitution_promise(const ContactModel& cm);

// `pounding collide`'s valid inputs and its verdict on the delivered restitution.
inline constexpr double collide_e_min = 0.01;          // damped laws (below: plastic; damping ~ 1/e unresolved)
inline constexpr double collide_v0_max = 100.0;        // m/s; pounding approach speeds are a few m/s
inline constexpr double default_e_tolerance = 0.05;    // |e_effective - e_target| for status "ok"
// Throws InputError naming the option (--e, --v0, --law, ...), the law's valid range and the reason:
// e in (0, 1]; e >= collide_e_min for the damped laws; e = 1 (or not given) for the elastic laws; v0 in
// [cm.v0_min, collide_v0_max]; a finite, moderate estimated contact duration (m1, m2, kc, v0).
void check_impact_inputs(const ContactModel& cm, double e, bool e_given, double v0, double m1, double m2, double kc);
// The contact duration single_impact's time step is built on (exact for linear/Kelvin and Hertz n = 3/2).
double estimated_contact_duration(const ContactModel& cm, double v0, double m1, double m2, double kc);

// Masses m1 (moving at v0) and m2 (at rest) touching at t = 0 with gap 0. The run lasts three estimated
// contact durations with `steps_per_contact` integration steps per estimated duration. `restitution`: the kernel's
// e(v0) hook (KernelSettings::restitution; central difference and hertzdamp), e then only the nominal value.
ImpactResult single_impact(const ContactModel& cm, Stepper stepper, double e, double v0, double m1, double m2,
                           double kc, int steps_per_contact = 20000,
                           const VelocityRestitution* restitution = nullptr);

}  // namespace pounding
