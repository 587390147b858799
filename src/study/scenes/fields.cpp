// The field writers of the unit's scenes: a lane of RunPeaks into the UnitResult by the plan's schema (scene.hpp).
#include <algorithm>
#include <cmath>
#include <utility>

#include "pounding/contact/registry.hpp"
#include "pounding/results/schema.hpp"

#include "scene.hpp"

namespace pounding::study_run {

namespace {

// The unit fields every plan has (results/schema.hpp); indices into the plan's schema.
namespace field {
constexpr std::size_t unc_status = results::unit_field("uncoupled", "status");
constexpr std::size_t unc_peak_u1 = results::unit_field("uncoupled", "peak_u1");
constexpr std::size_t unc_peak_u2 = results::unit_field("uncoupled", "peak_u2");
constexpr std::size_t unc_peak_closing = results::unit_field("uncoupled", "peak_closing");
constexpr std::size_t imp_status = results::unit_field("impacts", "status");
constexpr std::size_t imp_count = results::unit_field("impacts", "impact_count");
constexpr std::size_t imp_peak_force = results::unit_field("impacts", "peak_force");
constexpr std::size_t imp_peak_u1 = results::unit_field("impacts", "peak_u1");
constexpr std::size_t imp_peak_u2 = results::unit_field("impacts", "peak_u2");
constexpr std::size_t imp_t_first = results::unit_field("impacts", "t_first_impact");
constexpr std::size_t imp_h_omega = results::unit_field("impacts", "h_omega_contact");
}  // namespace field

constexpr std::size_t npos = std::string::npos;

// Results format 3: the fields of the per-floor and per-element rows, laid out as the study's largest topology (the
// runner's layout, the plan's /system).
void table_fields(const WorkPlan& plan, const TableLayout& layout, FieldIndex& f) {
  const std::size_t nb = layout.floors.size();  // the table topology's buildings (its bodies)
  f.floor_u.resize(nb), f.floor_drift.resize(nb), f.floor_acc.resize(nb);
  f.row_unc.assign(nb, 0), f.row_imp.assign(nb, 0);
  for (std::size_t b = 2; b < nb; ++b) {  // a row's buildings 3..n
    f.row_unc[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_u{b}", b + 1));
    if (plan.impacts)
      f.row_imp[b] = results::field_index(plan.fields, "impacts", results::building_name("peak_u{b}", b + 1));
  }
  for (std::size_t b = 0; b < nb; ++b) {
    f.floor_u[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_u_floors{b}", b + 1));
    f.floor_drift[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_drift{b}", b + 1));
    f.floor_acc[b] = results::field_index(plan.fields, "uncoupled", results::building_name("peak_acc_floors{b}", b + 1));
  }
  f.e_closing = results::field_index(plan.fields, "uncoupled", "peak_closing_elements");
  if (!plan.impacts) return;
  f.imp_floor_u.resize(nb), f.imp_floor_drift.resize(nb), f.imp_floor_acc.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    f.imp_floor_u[b] = results::field_index(plan.fields, "impacts", results::building_name("peak_u_floors{b}", b + 1));
    f.imp_floor_drift[b] = results::field_index(plan.fields, "impacts", results::building_name("peak_drift{b}", b + 1));
    f.imp_floor_acc[b] = results::field_index(plan.fields, "impacts", results::building_name("peak_acc_floors{b}", b + 1));
  }
  f.e_count = results::field_index(plan.fields, "impacts", "element_impact_count");
  f.e_force = results::field_index(plan.fields, "impacts", "element_peak_force");
  f.e_pen = results::field_index(plan.fields, "impacts", "element_peak_penetration");
  f.e_first = results::field_index(plan.fields, "impacts", "element_t_first_impact");
  f.e_hw = results::field_index(plan.fields, "impacts", "element_h_omega_contact");
}

// element e of the plan's /system belongs to a study-gap group (a moat wall does not)
bool study_gap(const WorkPlan& plan, std::size_t e) {
  const results::SystemTable& t = plan.system;
  return e >= t.element_group.size() || t.group_study_gap[static_cast<std::size_t>(t.element_group[e])] != 0;
}

// lane i's per-floor peaks at gap g: from scratch.coupled lane j, or (j = npos, a lane that never touched) its
// uncoupled peaks, as impacts/peak_u1 takes them
void put_floors_coupled(const UnitContext& c, UnitResult& out, std::size_t i, std::size_t g, std::size_t j) {
  const TableLayout& t = c.runner.layout();
  const FieldIndex& f = c.fields;
  const RunPeaks& p = j != npos ? c.scratch.coupled : c.scratch.peaks;
  const std::size_t lane = j != npos ? j : i;
  for (std::size_t b = 0; b < t.floors.size(); ++b) {
    const std::size_t F = t.floors[b];
    for (auto [field, from] : {std::pair{f.imp_floor_u[b], &p.floor_u[b]}, {f.imp_floor_drift[b], &p.floor_drift[b]},
                               {f.imp_floor_acc[b], &p.floor_acc[b]}}) {
      auto v = out.lane_values<double>(field, i);
      std::copy_n(from->begin() + static_cast<std::ptrdiff_t>(lane * F), F, v.begin() + static_cast<std::ptrdiff_t>(g * F));
    }
  }
}

// lane i's per-element impacts at gap g: from scratch.coupled lane j, or (j = npos) untouched: no impacts at the
// study-gap elements its topology has (those with an uncoupled closing), and a moat wall's of the uncoupled run (the
// walls act there too, and the coupled run of an untouched lane is the uncoupled run; they held 0, issue 45 item 2)
void put_table_coupled(const UnitContext& c, UnitResult& out, std::size_t i, std::size_t g, std::size_t j) {
  const std::size_t E = c.runner.layout().elements;
  const FieldIndex& f = c.fields;
  const RunPeaks &coupled = c.scratch.coupled, &peaks = c.scratch.peaks;
  auto count = out.lane_values<std::int32_t>(f.e_count, i);
  auto force = out.lane_values<double>(f.e_force, i), pen = out.lane_values<double>(f.e_pen, i);
  auto first = out.lane_values<double>(f.e_first, i), hw = out.lane_values<double>(f.e_hw, i);
  const bool has_force = contact::traits(c.s.contact.law).has_force;
  for (std::size_t e = 0; e < E; ++e) {
    const std::size_t o = g * E + e;
    if (j != npos) {
      const std::size_t x = j * E + e;
      count[o] = coupled.e_count[x], force[o] = coupled.e_force[x], pen[o] = coupled.e_penetration[x];
      first[o] = coupled.e_first[x], hw[o] = coupled.e_hw[x];
    } else if (!std::isnan(peaks.e_closing[i * E + e]) && !study_gap(c.plan, e)) {
      const std::size_t x = i * E + e;
      count[o] = peaks.e_count[x], force[o] = peaks.e_force[x], pen[o] = peaks.e_penetration[x];
      first[o] = peaks.e_first[x], hw[o] = peaks.e_hw[x];
    } else if (!std::isnan(peaks.e_closing[i * E + e])) {
      count[o] = 0, force[o] = 0.0, pen[o] = 0.0, first[o] = NAN;
      hw[o] = peaks.status[i] == 0 && has_force ? 0.0 : NAN;
    }
  }
  if (c.restitution) {  // per element: impacts outside the e(v0) curve's range (0 where it never touched)
    auto outside = out.lane_values<std::int32_t>(f.e_outside, i);
    for (std::size_t e = 0; e < E; ++e)
      if (j != npos) outside[g * E + e] = coupled.e_outside[j * E + e];
      else if (!std::isnan(peaks.e_closing[i * E + e])) outside[g * E + e] = 0;
  }
  put_floors_coupled(c, out, i, g, j);
}

}  // namespace

FieldIndex field_index(const Study& s, const WorkPlan& plan, const TableLayout& layout) {
  FieldIndex f;
  if (!plan.system.empty()) table_fields(plan, layout, f);
  if (s.restitution && plan.impacts) {  // e(v0) in the coupled runs (study.cpp: hertzdamp, CD, impacts scene)
    f.rest_out = results::field_index(plan.fields, "impacts", "restitution_outside");
    if (!plan.system.empty()) f.e_outside = results::field_index(plan.fields, "impacts", results::restitution_element_field.name);
  }
  if (plan.stripes) f.stripe_scaled = results::field_index(plan.fields, "uncoupled", "scaled");
  if (s.coarse == CoarsePolicy::refine && plan.impacts) f.substeps = results::field_index(plan.fields, "impacts", "substeps");
  if (plan.ida) {
    f.ida_analyses = results::field_index(plan.fields, "ida", "analyses");
    f.ida_limit = results::field_index(plan.fields, "ida", "scale_limit");
    f.ida_lo = results::field_index(plan.fields, "ida", "scale_lo");
    f.ida_hi = results::field_index(plan.fields, "ida", "scale_hi");
  }
  return f;
}

void put_uncoupled(UnitResult& out, std::size_t k, const RunPeaks& p, std::size_t i) {
  out.values<std::uint8_t>(field::unc_status)[k] = p.status[i];
  out.values<double>(field::unc_peak_u1)[k] = p.u1[i];
  out.values<double>(field::unc_peak_u2)[k] = p.u2[i];
  out.values<double>(field::unc_peak_closing)[k] = p.closing[i];
}

void put_uncoupled_rows(const UnitContext& c, UnitResult& out, std::size_t i, const RunPeaks& p, std::size_t stripe) {
  const TableLayout& t = c.runner.layout();
  const FieldIndex& f = c.fields;
  const std::size_t nb = p.buildings;
  for (std::size_t b = 2; b < nb; ++b) out.lane_values<double>(f.row_unc[b], i, stripe)[0] = p.u[i * nb + b];
  if (t.empty()) return;
  for (std::size_t b = 0; b < t.floors.size(); ++b)
    for (auto [field, from] : {std::pair{f.floor_u[b], &p.floor_u[b]}, {f.floor_drift[b], &p.floor_drift[b]},
                               {f.floor_acc[b], &p.floor_acc[b]}}) {
      auto v = out.lane_values<double>(field, i, stripe);
      std::copy_n(from->begin() + static_cast<std::ptrdiff_t>(i * t.floors[b]), t.floors[b], v.begin());
    }
  auto e = out.lane_values<double>(f.e_closing, i, stripe);
  std::copy_n(p.e_closing.begin() + static_cast<std::ptrdiff_t>(i * t.elements), t.elements, e.begin());
}

void put_coupled(const UnitContext& c, UnitResult& out, std::size_t i, std::size_t g, std::size_t j) {
  const std::size_t k = i * c.plan.gaps + g;  // [lane][gap]
  const FieldIndex& f = c.fields;
  const bool touched = j != npos;
  const RunPeaks& p = touched ? c.scratch.coupled : c.scratch.peaks;
  const std::size_t l = touched ? j : i, nb = p.buildings;
  out.values<std::uint8_t>(field::imp_status)[k] = p.status[l];
  out.values<std::int32_t>(field::imp_count)[k] = touched ? p.impact_count[l] : 0;
  out.values<double>(field::imp_peak_force)[k] = touched ? p.peak_force[l] : 0.0;
  out.values<double>(field::imp_peak_u1)[k] = p.u1[l];
  out.values<double>(field::imp_peak_u2)[k] = p.u2[l];
  out.values<double>(field::imp_t_first)[k] = touched ? p.t_first_impact[l] : NAN;
  // never touched: no contact force, h omega_c 0 (NaN for a failed lane or a law without a force element)
  out.values<double>(field::imp_h_omega)[k] =
      touched ? p.h_omega_contact[l] : p.status[l] == 0 && contact::traits(c.s.contact.law).has_force ? 0.0 : NAN;
  if (c.restitution) out.values<std::int32_t>(f.rest_out)[k] = touched ? p.restitution_outside[l] : 0;
  if (f.substeps != npos) out.values<std::int32_t>(f.substeps)[k] = touched ? p.substeps[l] : c.ks.substeps;
  for (std::size_t b = 2; b < nb; ++b) out.values<double>(f.row_imp[b])[k] = p.u[l * nb + b];
  if (!c.runner.layout().empty()) put_table_coupled(c, out, i, g, j);
}

}  // namespace pounding::study_run
