#pragma once
// A single free impact run through the kernel (no springs, no ground motion): the effective restitution
// and the contact's peak force, penetration, duration and energy loss.
#include "pounding/contact.hpp"
#include "pounding/kernel.hpp"

namespace pounding {

struct ImpactResult {
  double e_effective = 0, peak_force = 0, peak_penetration = 0, duration = 0;
  double energy_lost = 0, energy_lost_fraction = 0;
  int clamps = 0;
  LaneStatus status = LaneStatus::ok;
};

// Masses m1 (moving at v0) and m2 (at rest) touching at t = 0 with gap 0. The run lasts three estimated
// contact durations with `steps_per_contact` integration steps per estimated duration.
ImpactResult single_impact(const ContactModel& cm, Stepper stepper, double e, double v0, double m1, double m2,
                           double kc, int steps_per_contact = 20000);

}  // namespace pounding
