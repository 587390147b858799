#include "pounding/collide.hpp"

#include <cmath>
#include <numbers>
#include <vector>

namespace pounding {

ImpactResult single_impact(const ContactModel& cm, Stepper stepper, double e, double v0, double m1, double m2,
                           double kc, int steps_per_contact) {
  const double meff = m1 * m2 / (m1 + m2);
  double tc;  // estimated contact duration
  if (cm.law == ContactLaw::linear || cm.law == ContactLaw::kelvin)
    tc = std::numbers::pi * std::sqrt(meff / kc);
  else if (cm.law == ContactLaw::stereomechanical)
    tc = 1e-3;
  else
    tc = hertz_contact_duration(meff, v0, kc);  // exact for n = 3/2, an order-of-magnitude guide otherwise
  PairParams p;
  p.s1 = {m1, 0.0, 0.0};
  p.s2 = {m2, 0.0, 0.0};
  p.gap = 0.0;
  p.kc = kc;
  p.e = e;
  p.v1 = v0;
  PairBatch b;
  b.resize(1);
  b.set(0, p);
  // start a little before contact so that the onset (and the latched v0) is seen by the kernel
  const double lead = 0.05 * tc;
  p.u1 = -v0 * lead;
  b.set(0, p);
  std::vector<double> ag = {0.0, 0.0};
  GroundMotion gm{3.0 * tc, ag, 0.0};
  KernelSettings ks;
  ks.stepper = stepper;
  ks.substeps = 3 * steps_per_contact;
  ks.displacement_limit = 1e30;
  BatchResult r;
  run_batch(b, cm, gm, ks, r);
  ImpactResult out;
  out.status = static_cast<LaneStatus>(r.status[0]);
  out.e_effective = (r.final_v2[0] - r.final_v1[0]) / v0;
  out.peak_force = r.peak_force[0];
  out.peak_penetration = r.peak_penetration[0];
  out.duration = r.contact_time[0];
  double ke0 = 0.5 * m1 * v0 * v0;
  double ke1 = 0.5 * m1 * r.final_v1[0] * r.final_v1[0] + 0.5 * m2 * r.final_v2[0] * r.final_v2[0];
  out.energy_lost = ke0 - ke1;
  out.energy_lost_fraction = out.energy_lost / ke0;
  out.clamps = r.clamp_count[0];
  return out;
}

}  // namespace pounding
