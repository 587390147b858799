// One free impact through the kernel: effective restitution, peak force, penetration, duration, energy loss.
#include "pounding/physics/single_impact.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

RestitutionPromise restitution_promise(const ContactModel& cm) {
  RestitutionPromise p;
  const contact::LawTraits& law = contact::traits(cm.law);
  if (!law.restitution_from_damping) {
    p.kind = law.restitution;
    p.note = std::string(law.restitution_note);
    return p;
  }
  // the damping law's entry says what it delivers (contact/model.hpp damping_laws)
  const DampingLawEntry& d = damping_law(cm.damping);
  p.kind = d.delivers;
  switch (d.delivers) {
    case RestitutionKind::exact:
      p.note = "xibar solved so that one free impact returns e (within 1e-6): delivers e by construction";
      break;
    case RestitutionKind::approximate:
      p.note = fmt::format("{}'s closed-form xibar delivers e within 0.05 over (0, 1] (docs/accuracy.md); "
                           "use --damping-law calibrated for e exactly",
                           d.name);
      break;
    case RestitutionKind::saturating:
      p.floor = hertzdamp_restitution(d.xibar(0.0, cm.n), cm.n);  // the bound of xibar as e -> 0
      p.note = fmt::format("{}'s xibar = {} is derived for e near 1: it delivers more than e away from 1 ({} at "
                           "e = 0.65, docs/accuracy.md) and never less than {:.3f}; use --damping-law calibrated for "
                           "e exactly",
                           d.name, d.formula, d.at_065, p.floor);
      break;
    case RestitutionKind::elastic: break;
  }
  return p;
}

double estimated_contact_duration(const ContactModel& cm, double v0, double m1, double m2, double kc_given) {
  const double meff = m1 * m2 / (m1 + m2);
  const double kc = kc_given * contact::stiffness_factor(cm);  // the stiffness the kernel uses
  const contact::DurationForm form = contact::traits(cm.law).duration;
  if (form == contact::DurationForm::linear) return std::numbers::pi * std::sqrt(meff / kc);
  if (form == contact::DurationForm::impulsive) return 1e-3;
  return hertz_contact_duration(meff, v0, kc);  // exact for n = 3/2, an order-of-magnitude guide otherwise
}

void check_impact_inputs(const ContactModel& cm, double e, bool e_given, double v0, double m1, double m2, double kc) {
  require_range(e, std::nextafter(0.0, 1.0), 1.0, "--e", "(0, 1]");
  require_positive(m1, "--m1");
  require_positive(m2, "--m2");
  require_positive(kc, "--kh");
  const contact::LawTraits& law = contact::traits(cm.law);
  if (!law.has_force && !law.impulsive)
    throw InputError("contact law 'none' has no contact element: nothing collides", "--law",
                     fmt::format("choose a contact law: {}", contact::law_names_where([](const contact::LawTraits& t) {
                                   return t.has_force || t.impulsive;
                                 })));
  const RestitutionPromise p = restitution_promise(cm);
  if (p.kind == RestitutionKind::elastic && e_given && e != 1.0)
    throw InputError(fmt::format("--e = {} with the elastic {} law: {}", e, to_string(cm.law), p.note), "--e",
                     fmt::format("drop --e (or give --e 1), or choose a damped law for e < 1 ({})",
                                 contact::law_names_where([](const contact::LawTraits& t) {
                                   return t.restitution != RestitutionKind::elastic;
                                 })));
  if (p.kind != RestitutionKind::elastic && !law.impulsive && e < collide_e_min) {
    std::string why = fmt::format(
        "below e = {} an impact is plastic for any structural purpose (it keeps less than {} of its energy) and the "
        "damped laws' damping grows like 1/e beyond what the integration resolves",
        collide_e_min, collide_e_min * collide_e_min);
    if (p.kind == RestitutionKind::saturating) why = p.note;
    throw InputError(fmt::format("--e = {} is outside the valid range [{}, 1] of {}{}: {}", e, collide_e_min,
                                 to_string(cm.law),
                                 law.restitution_from_damping ? fmt::format(" with {}", to_string(cm.damping)) : "",
                                 why),
                     "--e", fmt::format("give --e in [{}, 1], or use --law stereomechanical for a plastic impact",
                                        collide_e_min));
  }
  if (!(v0 >= cm.v0_min && v0 <= collide_v0_max))
    throw InputError(fmt::format("--v0 = {} m/s is outside [{}, {}] m/s", v0, cm.v0_min, collide_v0_max), "--v0",
                     fmt::format("give the approach speed in m/s: pounding structures meet at a few m/s; below {} m/s "
                                 "the kernel floors the latched approach speed (grazing contacts), and the contact "
                                 "duration the time step is built on needs a moderate v0",
                                 cm.v0_min));
  const double tc = estimated_contact_duration(cm, v0, m1, m2, kc);
  if (!(tc >= 1e-9 && tc <= 100.0))
    throw InputError(fmt::format("the estimated contact duration is {} s, outside [1e-9, 100] s", tc),
                     "--m1, --m2, --kh, --v0",
                     "check the masses (kg), the contact stiffness (N/m^n; N/m for linear/Kelvin) and v0 (m/s)");
}

ImpactResult single_impact(const ContactModel& cm, Stepper stepper, double e, double v0, double m1, double m2,
                           double kc, int steps_per_contact, const VelocityRestitution* restitution) {
  const double tc = estimated_contact_duration(cm, v0, m1, m2, kc);
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
  ks.restitution = restitution;
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
  out.h_omega_contact = r.h_omega_contact[0];
  out.restitution_outside = r.restitution_outside[0];
  return out;
}

}  // namespace pounding
