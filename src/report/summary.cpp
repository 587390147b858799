#include "pounding/report/summary.hpp"

#include <cmath>

#include <fmt/format.h>

namespace pounding {

std::string format_summary(const BatchResult& r, std::size_t i, const ContactModel& cm, const PairParams& p,
                           const Record& rec, const KernelSettings& ks) {
  std::string s;
  auto line = [&](std::string_view name, auto value) { s += fmt::format("{}: {}\n", name, value); };
  auto num = [&](std::string_view name, double v) { s += fmt::format("{}: {:.6g}\n", name, v); };
  line("record", rec.name);
  line("record_source", rec.source);
  num("record_dt_s", rec.dt);
  num("record_pga_g", rec.pga() / g_accel);
  line("stepper", to_string(ks.stepper));
  num("integration_dt_s", rec.dt / ks.substeps);
  line("contact_law", to_string(cm.law));
  if (cm.law == ContactLaw::hertzdamp) {
    line("damping_law", to_string(cm.damping));
    num("xibar", hertzdamp_xibar(cm.damping, p.e, cm.n));
  }
  num("e_target", p.e);
  num("contact_stiffness", p.kc);
  num("gap_m", p.gap);
  num("T1_s", 2 * M_PI * std::sqrt(p.s1.m / p.s1.k));
  num("T2_s", 2 * M_PI * std::sqrt(p.s2.m / p.s2.k));
  line("status", to_string(static_cast<LaneStatus>(r.status[i])));
  num("peak_u1_m", r.peak_u1[i]);
  num("peak_u2_m", r.peak_u2[i]);
  num("peak_closing_m", r.peak_closing[i]);
  num("t_peak_closing_s", r.t_peak_closing[i]);
  num("t_first_impact_s", r.t_first_impact[i]);
  line("impact_count", r.impact_count[i]);
  num("peak_contact_force_N", r.peak_force[i]);
  num("peak_penetration_m", r.peak_penetration[i]);
  num("contact_energy_dissipated_J", r.contact_energy[i]);
  num("contact_time_s", r.contact_time[i]);
  num("peak_abs_acc1_g", r.peak_acc1[i] / g_accel);
  num("peak_abs_acc2_g", r.peak_acc2[i] / g_accel);
  line("tensile_force_clamps", r.clamp_count[i]);
  if (ks.energy) {
    num("energy_input_J", r.e_input[i]);
    num("energy_kinetic_J", r.e_kinetic[i]);
    num("energy_strain_J", r.e_strain[i]);
    num("energy_viscous_J", r.e_viscous[i]);
    num("energy_hysteretic_J", r.e_hysteretic[i]);
    num("energy_contact_stored_J", r.e_contact_stored[i]);
    num("energy_contact_dissipated_J", r.contact_energy[i]);
    double out = r.e_kinetic[i] + r.e_strain[i] + r.e_viscous[i] + r.e_hysteretic[i] + r.e_contact_stored[i] +
                 r.contact_energy[i];
    num("energy_balance_error_rel", (r.e_input[i] - out) / std::max(std::abs(r.e_input[i]), 1e-300));
  }
  return s;
}

}  // namespace pounding
