#include "pounding/report/summary.hpp"

#include <cmath>

#include <fmt/format.h>

#include "pounding/physics/resolution.hpp"

namespace pounding {

namespace {

// A per-lane observer printed as "<name>: <value / divisor>" with 6 significant digits.
struct Field {
  std::string_view name;
  std::vector<double> BatchResult::*values;
  double divisor = 1.0;
};

constexpr Field peak_fields[] = {{"peak_u1_m", &BatchResult::peak_u1},
                                 {"peak_u2_m", &BatchResult::peak_u2},
                                 {"peak_closing_m", &BatchResult::peak_closing},
                                 {"t_peak_closing_s", &BatchResult::t_peak_closing},
                                 {"t_first_impact_s", &BatchResult::t_first_impact}};
constexpr Field contact_fields[] = {{"peak_contact_force_N", &BatchResult::peak_force},
                                    {"peak_penetration_m", &BatchResult::peak_penetration},
                                    {"contact_energy_dissipated_J", &BatchResult::contact_energy},
                                    {"contact_time_s", &BatchResult::contact_time},
                                    {"peak_abs_acc1_g", &BatchResult::peak_acc1, g_accel},
                                    {"peak_abs_acc2_g", &BatchResult::peak_acc2, g_accel}};
constexpr Field energy_fields[] = {{"energy_input_J", &BatchResult::e_input},
                                   {"energy_kinetic_J", &BatchResult::e_kinetic},
                                   {"energy_strain_J", &BatchResult::e_strain},
                                   {"energy_viscous_J", &BatchResult::e_viscous},
                                   {"energy_hysteretic_J", &BatchResult::e_hysteretic},
                                   {"energy_contact_stored_J", &BatchResult::e_contact_stored},
                                   {"energy_contact_dissipated_J", &BatchResult::contact_energy}};

}  // namespace

std::string format_summary(const BatchResult& r, std::size_t i, const ContactModel& cm, const PairParams& p,
                           const Record& rec, const KernelSettings& ks) {
  std::string s;
  auto line = [&](std::string_view name, auto value) { s += fmt::format("{}: {}\n", name, value); };
  auto num = [&](std::string_view name, double v) { s += fmt::format("{}: {:.6g}\n", name, v); };
  auto fields = [&](const auto& table) {
    for (const Field& f : table) num(f.name, (r.*f.values)[i] / f.divisor);
  };
  line("record", rec.name);
  line("record_source", rec.source);
  num("record_dt_s", rec.dt);
  num("record_pga_g", rec.pga() / g_accel);
  line("stepper", to_string(ks.stepper));
  num("integration_dt_s", rec.dt / ks.substeps);
  line("contact_law", to_string(cm.law));
  if (contact::traits(cm.law).restitution_from_damping) {
    line("damping_law", to_string(cm.damping));
    num("xibar", hertzdamp_xibar(cm.damping, p.e, cm.n));
  }
  num("e_target", p.e);
  num("contact_stiffness", p.kc);
  num("gap_m", p.gap);
  num("T1_s", 2 * M_PI * std::sqrt(p.s1.m / p.s1.k));
  num("T2_s", 2 * M_PI * std::sqrt(p.s2.m / p.s2.k));
  line("status", to_string(static_cast<LaneStatus>(r.status[i])));
  // the resolution guard (physics/resolution.hpp): h omega_c at the peak penetration against the stepper x law limit
  const double limit = physics::resolution_limit(ks, cm.law);
  num("h_omega_contact", r.h_omega_contact[i]);
  num("h_omega_limit", limit);
  if (r.status[i] == static_cast<std::uint8_t>(LaneStatus::coarse))
    line("coarse", fmt::format("the contact is under-resolved (peak force off by more than {} %): use {} substeps per "
                               "record step (integration dt {:.3g} s) -- an estimate, the peak penetration changes "
                               "with the step",
                               100.0 * physics::resolution_tolerance,
                               physics::substeps_for_limit(ks.substeps, r.h_omega_contact[i], limit),
                               rec.dt / physics::substeps_for_limit(ks.substeps, r.h_omega_contact[i], limit)));
  fields(peak_fields);
  line("impact_count", r.impact_count[i]);
  fields(contact_fields);
  line("tensile_force_clamps", r.clamp_count[i]);
  if (ks.energy) {
    fields(energy_fields);
    double out = r.e_kinetic[i] + r.e_strain[i] + r.e_viscous[i] + r.e_hysteretic[i] + r.e_contact_stored[i] +
                 r.contact_energy[i];
    num("energy_balance_error_rel", (r.e_input[i] - out) / std::max(std::abs(r.e_input[i]), 1e-300));
  }
  return s;
}

}  // namespace pounding
