// Text summaries of kernel and system runs (simulate, collide): one `name: value` per line, SI units in the names.
#include "pounding/report/summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <fmt/format.h>

#include "pounding/physics/resolution.hpp"
#include "pounding/report/escape.hpp"
#include "pounding/report/json.hpp"

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

// The header lines every summary opens with: the record, the stepper and the contact law (with its damping law,
// xibar and -- for a law such as three-spring -- the stiffness factor applied to kc), for the pair and the system.
std::string run_header(const Record& rec, const KernelSettings& ks, const ContactModel& cm, double e_target) {
  std::string s;
  auto line = [&](std::string_view name, const auto& value) { s += fmt::format("{}: {}\n", name, value); };
  auto num = [&](std::string_view name, double v) { s += fmt::format("{}: {:.6g}\n", name, v); };
  line("record", report::one_line(rec.name));  // `name: value` lines: a newline in a name would forge a line
  line("record_source", report::one_line(rec.source));
  num("record_dt_s", rec.dt);
  num("record_pga_g", rec.pga() / g_accel);
  line("stepper", to_string(ks.stepper));
  num("integration_dt_s", rec.dt / ks.substeps);
  line("contact_law", to_string(cm.law));
  if (contact::traits(cm.law).restitution_from_damping) {
    line("damping_law", to_string(cm.damping));
    num("xibar", hertzdamp_xibar(cm.damping, e_target, cm.n));
    if (contact::stiffness_factor(cm) != 1.0) num("contact_stiffness_factor", contact::stiffness_factor(cm));
  }
  num("e_target", e_target);
  return s;
}

}  // namespace

std::string format_summary(const BatchResult& r, std::size_t i, const ContactModel& cm, const PairParams& p,
                           const Record& rec, const KernelSettings& ks) {
  std::string s;
  auto line = [&](std::string_view name, auto value) { s += fmt::format("{}: {}\n", name, value); };
  auto num = [&](std::string_view name, double v) { s += fmt::format("{}: {:.6g}\n", name, v); };
  auto fields = [&](const auto& table) {
    for (const Field& f : table) num(f.name, (r.*f.values)[i] / f.divisor);
  };
  s += run_header(rec, ks, cm, p.e);
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

namespace pounding {

namespace {

// The lane's values of index i's row of a [index][lane] observer.
double at(const std::vector<double>& v, int i, const physics::SystemResult& r, std::size_t lane) {
  return v[physics::SystemBatch::at(i, lane, r.width)];
}
std::int32_t at(const std::vector<std::int32_t>& v, int i, const physics::SystemResult& r, std::size_t lane) {
  return v[physics::SystemBatch::at(i, lane, r.width)];
}

// One building's per-floor (per DOF) or per-storey (per spring below each DOF) values, bottom first; an isolated
// building's floors above its base (the base and isolator: base_values).
std::vector<double> per_floor(const SystemRunReport& run, const model::Body& b, const std::vector<double>& v,
                              double divisor = 1.0, bool springs = false) {
  std::vector<double> out;
  for (std::size_t i = b.isolated ? 1 : 0; i < b.dofs.size(); ++i) {
    const int d = b.dofs[i];
    out.push_back(at(v, springs ? run.system->spring_below(d) : d, *run.result, run.lane) / divisor);
  }
  return out;
}

// The totals over elements: impacts summed, peaks the largest, the first impact the earliest (NaN: none).
struct Totals {
  std::int64_t impacts = 0, clamps = 0;
  double peak_force = 0.0, peak_penetration = 0.0, peak_closing = std::numeric_limits<double>::quiet_NaN();
  double t_first_impact = std::numeric_limits<double>::quiet_NaN(), h_omega = 0.0, energy = 0.0;
};
Totals totals(const SystemRunReport& run) {
  Totals t;
  const auto& r = *run.result;
  for (int e = 0; e < static_cast<int>(run.system->contacts().size()); ++e) {
    // -1 marks a diverged or non-finite lane (physics/run_batch.cpp): the total says the same
    const std::int32_t n = at(r.impact_count, e, r, run.lane), c = at(r.clamp_count, e, r, run.lane);
    t.impacts = t.impacts < 0 || n < 0 ? -1 : t.impacts + n;
    t.clamps = t.clamps < 0 || c < 0 ? -1 : t.clamps + c;
    t.peak_force = std::max(t.peak_force, at(r.peak_force, e, r, run.lane));
    t.peak_penetration = std::max(t.peak_penetration, at(r.peak_penetration, e, r, run.lane));
    const double closing = at(r.peak_closing, e, r, run.lane);
    if (!(closing <= t.peak_closing)) t.peak_closing = closing;  // NaN until the first element
    const double t1 = at(r.t_first_impact, e, r, run.lane);  // NaN: no impact at this element
    if (!std::isnan(t1) && !(t1 >= t.t_first_impact)) t.t_first_impact = t1;
    const double ho = at(r.h_omega_contact, e, r, run.lane);  // NaN (no force element, diverged) wins
    if (!(ho <= t.h_omega)) t.h_omega = std::isnan(t.h_omega) ? t.h_omega : ho;
    t.energy += at(r.contact_energy, e, r, run.lane);
  }
  return t;
}

struct EnergyTerm {
  std::string_view name;
  std::vector<double> physics::SystemResult::*values;
};
constexpr EnergyTerm energy_terms[] = {{"energy_input_J", &physics::SystemResult::e_input},
                                       {"energy_kinetic_J", &physics::SystemResult::e_kinetic},
                                       {"energy_strain_J", &physics::SystemResult::e_strain},
                                       {"energy_viscous_J", &physics::SystemResult::e_viscous},
                                       {"energy_hysteretic_J", &physics::SystemResult::e_hysteretic},
                                       {"energy_contact_stored_J", &physics::SystemResult::e_contact_stored}};

double balance_error(const SystemRunReport& run, const Totals& t) {
  const auto& r = *run.result;
  const std::size_t l = run.lane;
  const double out = r.e_kinetic[l] + r.e_strain[l] + r.e_viscous[l] + r.e_hysteretic[l] + r.e_contact_stored[l] + t.energy;
  return (r.e_input[l] - out) / std::max(std::abs(r.e_input[l]), 1e-300);
}

double element_gap(const SystemRunReport& run, int e) {
  return run.contact_gap.empty() ? run.gap : run.contact_gap[static_cast<std::size_t>(e)];
}

// The amplifications of one building: coupled / uncoupled peak per floor (displacement, drift, absolute
// acceleration); NaN where the uncoupled run has no result or a zero peak.
struct Amplification {
  std::string_view name;
  std::vector<double> physics::SystemResult::*values;
  bool springs;
};
constexpr Amplification amplifications[] = {{"amplification_u", &physics::SystemResult::peak_u, false},
                                            {"amplification_drift", &physics::SystemResult::peak_drift, true},
                                            {"amplification_acc", &physics::SystemResult::peak_acc, false}};
std::vector<double> amplification(const SystemRunReport& run, const model::Body& body, const Amplification& a) {
  const std::vector<double> c = per_floor(run, body, (*run.result).*a.values, 1.0, a.springs);
  const std::vector<double> u = per_floor(run, body, (*run.uncoupled).*a.values, 1.0, a.springs);
  const bool ok = run.uncoupled->status[run.lane] == static_cast<std::uint8_t>(LaneStatus::ok);
  std::vector<double> out(c.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    out[i] = ok && u[i] > 0.0 ? c[i] / u[i] : std::numeric_limits<double>::quiet_NaN();
  return out;
}

// Peak drift / storey height per storey (the storey heights from the report's floor levels, bottom first).
std::vector<double> drift_ratios(const std::vector<double>& drift, const BuildingReport& b) {
  std::vector<double> out(drift.size());
  for (std::size_t i = 0; i < drift.size() && i < b.floor_levels.size(); ++i)
    out[i] = drift[i] / (b.floor_levels[i] - (i == 0 ? 0.0 : b.floor_levels[i - 1]));
  return out;
}

// An isolated building's base (issue 25 §2): the bearing's displacement (the base relative to the ground), its
// residual, the isolator's peak force and the impacts at its moat walls (elements with a wall side on the base).
struct BaseValues {
  double peak_u = 0, final_u = 0, peak_force = 0;
  std::int64_t moat_impacts = 0;
  double moat_peak_force = 0;
};
BaseValues base_values(const SystemRunReport& run, const model::Body& b) {
  const physics::SystemResult& r = *run.result;
  const int base = b.dofs[0];
  BaseValues v{at(r.peak_u, base, r, run.lane), at(r.final_u, base, r, run.lane),
               at(r.peak_spring_force, run.system->spring_below(base), r, run.lane), 0, 0.0};
  for (int e : run.system->elements_at(base)) {
    const model::ContactElement& ce = run.system->contacts()[static_cast<std::size_t>(e)];
    if (ce.left.kind != model::SideKind::wall && ce.right.kind != model::SideKind::wall) continue;
    v.moat_impacts += at(r.impact_count, e, r, run.lane);
    v.moat_peak_force = std::max(v.moat_peak_force, at(r.peak_force, e, r, run.lane));
  }
  return v;
}

std::string list(const std::vector<double>& v) {
  std::string s;
  for (double x : v) s += fmt::format("{}{:.6g}", s.empty() ? "" : " ", x);
  return s;
}

std::string isolation_lines(const std::string& building_label, const IsolationReport& iso) {
  const std::string label = report::one_line(building_label);
  std::string s = fmt::format("{}_bearing: {}\n", label, iso.bearing);
  s += fmt::format("{}_base_mass_kg: {:.6g}\n{}_isolator_k_N_m: {:.6g}\n", label, iso.base_mass, label, iso.k);
  s += fmt::format("{}_isolator_fy_N: {:.6g}\n{}_isolator_alpha: {:.6g}\n", label, iso.fy, label, iso.alpha);
  s += fmt::format("{}_bearing_c_N_s_m: {:.6g}\n{}_isolated_periods_s: {}\n", label, iso.c_base, label,
                   list(iso.periods));
  for (const auto& [name, v] : iso.law_numbers) s += fmt::format("{}_bearing_{}: {:.6g}\n", label, name, v);
  return s;
}

std::string base_lines(const std::string& k, const BaseValues& bv) {
  std::string s = fmt::format("peak_bearing_u{}_m: {:.6g}\nfinal_bearing_u{}_m: {:.6g}\n", k, bv.peak_u, k, bv.final_u);
  s += fmt::format("peak_bearing_force{}_N: {:.6g}\nmoat_impacts{}: {}\n", k, bv.peak_force, k, bv.moat_impacts);
  s += fmt::format("moat_peak_force{}_N: {:.6g}\n", k, bv.moat_peak_force);
  return s;
}

}  // namespace

std::string format_system_summary(const SystemRunReport& run) {
  std::string s;
  // names hold the user's labels (buildings, contact levels, link springs): kept on their line
  auto line = [&](std::string_view name, const auto& value) { s += fmt::format("{}: {}\n", report::one_line(name), value); };
  auto num = [&](std::string_view name, double v) { s += fmt::format("{}: {:.6g}\n", name, v); };
  const Record& rec = *run.record;
  const KernelSettings& ks = *run.settings;
  const ContactModel& cm = *run.contact;
  const physics::SystemResult& r = *run.result;
  const model::System& sys = *run.system;
  s += run_header(rec, ks, cm, run.e_target);
  num("gap_m", run.gap);
  for (const BuildingReport& b : run.buildings) {
    line(b.label + "_storeys", b.floor_levels.size());
    line(b.label + "_floor_levels_m", list(b.floor_levels));
    line(b.label + "_floor_mass_kg", list(b.floor_mass));
    line(b.label + "_storey_stiffness_N_m", list(b.storey_stiffness));
    line(b.label + "_storey_yield_N", list(b.storey_yield));
    line(b.label + "_periods_s", list(b.periods));
    line(b.label + "_modal_damping", list(b.modal_damping));
    if (!b.rayleigh_modes.empty()) line(b.label + "_rayleigh_modes", fmt::format("{} {}", b.rayleigh_modes[0], b.rayleigh_modes[1]));
    if (b.isolation) s += isolation_lines(b.label, *b.isolation);
  }
  line("status", to_string(static_cast<LaneStatus>(r.status[run.lane])));
  const Totals t = totals(run);
  num("h_omega_contact", t.h_omega);
  num("h_omega_limit", physics::resolution_limit(ks, cm.law));
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const model::Body& body = sys.bodies()[b];
    const std::string k = std::to_string(b + 1);
    line("peak_u" + k + "_m", list(per_floor(run, body, r.peak_u)));
    const std::vector<double> drift = per_floor(run, body, r.peak_drift, 1.0, true);
    line("peak_drift" + k + "_m", list(drift));
    line("peak_drift_ratio" + k, list(drift_ratios(drift, run.buildings[b])));
    line("peak_abs_acc" + k + "_g", list(per_floor(run, body, r.peak_acc, g_accel)));
    if (run.uncoupled != nullptr)
      for (const Amplification& a : amplifications) line(std::string(a.name) + k, list(amplification(run, body, a)));
    if (body.isolated) s += base_lines(k, base_values(run, body));
  }
  line("contact_levels", sys.contacts().empty() ? std::string("none (no floors face each other)")
                                                 : std::to_string(sys.contacts().size()));
  for (int e = 0; e < static_cast<int>(sys.contacts().size()); ++e)
    line(sys.contacts()[static_cast<std::size_t>(e)].label,
         fmt::format("impacts {}, peak_force_N {:.6g}, peak_penetration_m {:.6g}, peak_closing_m {:.6g}, "
                     "t_first_impact_s {:.6g}, contact_energy_dissipated_J {:.6g}, contact_stiffness {:.6g}, gap_m {:.6g}",
                     at(r.impact_count, e, r, run.lane), at(r.peak_force, e, r, run.lane),
                     at(r.peak_penetration, e, r, run.lane), at(r.peak_closing, e, r, run.lane),
                     at(r.t_first_impact, e, r, run.lane), at(r.contact_energy, e, r, run.lane),
                     run.contact_stiffness[static_cast<std::size_t>(e)], element_gap(run, e)));
  for (std::size_t k = 0; k < run.spring_labels.size(); ++k) {
    if (run.spring_labels[k].empty() || sys.springs()[k].role != model::SpringRole::link) continue;
    const int sk = static_cast<int>(k);
    line(run.spring_labels[k], fmt::format("peak_force_N {:.6g}, peak_deformation_m {:.6g}",
                                           at(r.peak_spring_force, sk, r, run.lane), at(r.peak_drift, sk, r, run.lane)));
  }
  line("impact_count", t.impacts);
  num("peak_contact_force_N", t.peak_force);
  num("t_first_impact_s", t.t_first_impact);
  line("tensile_force_clamps", t.clamps);
  if (ks.energy) {
    for (const EnergyTerm& e : energy_terms) num(e.name, (r.*e.values)[run.lane]);
    num("energy_contact_dissipated_J", t.energy);
    num("energy_balance_error_rel", balance_error(run, t));
  }
  return s;
}

// The link springs (restrainers, bearings, abutments: issue 26) with their peak force and deformation.
void link_json(report::JsonWriter& w, const SystemRunReport& run) {
  if (run.spring_labels.empty()) return;
  const physics::SystemResult& r = *run.result;
  w.key("links").begin_array();
  for (std::size_t k = 0; k < run.spring_labels.size(); ++k) {
    if (run.spring_labels[k].empty() || run.system->springs()[k].role != model::SpringRole::link) continue;
    const int sk = static_cast<int>(k);
    w.begin_object().member("label", run.spring_labels[k]);
    w.member("peak_force", at(r.peak_spring_force, sk, r, run.lane)).member("peak_deformation", at(r.peak_drift, sk, r, run.lane));
    w.end_object();
  }
  w.end_array();
}

// The contact elements' "levels" array of format_system_json.
static void levels_json(report::JsonWriter& w, const SystemRunReport& run) {
  const physics::SystemResult& r = *run.result;
  const model::System& sys = *run.system;
  w.key("levels").begin_array();
  for (int e = 0; e < static_cast<int>(sys.contacts().size()); ++e) {
    const model::ContactElement& ce = sys.contacts()[static_cast<std::size_t>(e)];
    w.begin_object().member("level", ce.level).member("label", ce.label);
    w.member("impacts", static_cast<std::int64_t>(at(r.impact_count, e, r, run.lane)));
    w.member("peak_force", at(r.peak_force, e, r, run.lane));
    w.member("peak_penetration", at(r.peak_penetration, e, r, run.lane));
    w.member("peak_closing", at(r.peak_closing, e, r, run.lane));
    w.member("t_peak_closing", at(r.t_peak_closing, e, r, run.lane));
    w.member("t_first_impact", at(r.t_first_impact, e, r, run.lane));
    w.member("contact_energy", at(r.contact_energy, e, r, run.lane));
    w.member("contact_time", at(r.contact_time, e, r, run.lane));
    w.member("clamps", static_cast<std::int64_t>(at(r.clamp_count, e, r, run.lane)));
    if (run.settings && run.settings->restitution)  // e(v0): this element's impacts outside the curve's valid range
      w.member("restitution_outside", static_cast<std::int64_t>(at(r.restitution_outside, e, r, run.lane)));
    w.member("h_omega_contact", at(r.h_omega_contact, e, r, run.lane));
    w.member("contact_stiffness", run.contact_stiffness[static_cast<std::size_t>(e)]);
    w.member("gap", element_gap(run, e));
    w.end_object();
  }
  w.end_array();
}

std::string format_system_json(const SystemRunReport& run) {
  const Record& rec = *run.record;
  const KernelSettings& ks = *run.settings;
  const ContactModel& cm = *run.contact;
  const physics::SystemResult& r = *run.result;
  const model::System& sys = *run.system;
  report::JsonWriter w;
  w.begin_object();
  w.member("record", rec.name).member("record_source", rec.source).member("record_dt_s", rec.dt);
  w.member("record_pga_g", rec.pga() / g_accel).member("analysis_duration_s", run.analysis_duration);
  w.member("stepper", to_string(ks.stepper)).member("integration_dt_s", rec.dt / ks.substeps);
  w.member("contact_law", to_string(cm.law));
  if (contact::traits(cm.law).restitution_from_damping)
    w.member("damping_law", to_string(cm.damping)).member("xibar", hertzdamp_xibar(cm.damping, run.e_target, cm.n));
  w.member("e_target", run.e_target).member("gap", run.gap);
  w.key("buildings").begin_array();
  for (const BuildingReport& b : run.buildings) {
    w.begin_object().member("label", b.label).member("storeys", static_cast<int>(b.floor_levels.size()));
    w.member("floor_levels", b.floor_levels).member("floor_mass", b.floor_mass);
    w.member("storey_stiffness", b.storey_stiffness).member("storey_yield", b.storey_yield);
    w.member("periods", b.periods).member("modal_damping", b.modal_damping);
    if (!b.rayleigh_modes.empty()) {
      w.key("rayleigh_modes").begin_array();
      for (int m : b.rayleigh_modes) w.value(m);
      w.end_array();
    }
    if (b.isolation) {
      const IsolationReport& iso = *b.isolation;
      w.key("isolation").begin_object().member("bearing", iso.bearing).member("base_mass", iso.base_mass);
      w.member("isolator_k", iso.k).member("isolator_fy", iso.fy).member("isolator_alpha", iso.alpha);
      w.member("bearing_c", iso.c_base).member("isolated_periods", iso.periods);
      for (const auto& [name, v] : iso.law_numbers) w.member("bearing_" + name, v);
      w.end_object();
    }
    w.end_object();
  }
  w.end_array();
  w.member("status", to_string(static_cast<LaneStatus>(r.status[run.lane])));
  const Totals t = totals(run);
  for (std::size_t b = 0; b < sys.bodies().size(); ++b) {
    const model::Body& body = sys.bodies()[b];
    const std::string k = std::to_string(b + 1);
    w.member("peak_u" + k, per_floor(run, body, r.peak_u));
    const std::vector<double> drift = per_floor(run, body, r.peak_drift, 1.0, true);
    w.member("peak_drift" + k, drift).member("peak_drift_ratio" + k, drift_ratios(drift, run.buildings[b]));
    w.member("peak_abs_acc" + k + "_g", per_floor(run, body, r.peak_acc, g_accel));
    w.member("final_u" + k, per_floor(run, body, r.final_u));
    if (run.uncoupled != nullptr)
      for (const Amplification& a : amplifications) w.member(std::string(a.name) + k, amplification(run, body, a));
    if (!body.isolated) continue;
    const BaseValues bv = base_values(run, body);
    w.member("peak_bearing_u" + k, bv.peak_u).member("final_bearing_u" + k, bv.final_u);
    w.member("peak_bearing_force" + k, bv.peak_force).member("moat_impacts" + k, bv.moat_impacts);
    w.member("moat_peak_force" + k, bv.moat_peak_force);
  }
  levels_json(w, run);
  link_json(w, run);
  w.member("impact_count", t.impacts).member("peak_force", t.peak_force);
  w.member("peak_penetration", t.peak_penetration).member("peak_closing", t.peak_closing);
  w.member("t_first_impact", t.t_first_impact).member("tensile_force_clamps", t.clamps);
  w.member("h_omega_contact", t.h_omega).member("h_omega_limit", physics::resolution_limit(ks, cm.law));
  if (ks.energy) {
    for (const EnergyTerm& e : energy_terms) w.member(e.name, (r.*e.values)[run.lane]);
    w.member("energy_contact_dissipated_J", t.energy).member("energy_balance_error_rel", balance_error(run, t));
  }
  return w.end_object().str();
}

}  // namespace pounding
