// The resolution guard's summary line (physics/resolution.hpp), shared by the study run output and the report.
#include "pounding/physics/resolution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pounding/model/system.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding::physics {

namespace {
double floor3(double x) {  // rounded down to 3 significant digits (a step cap must not round up)
  const double q = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  return std::floor(x / q) * q;
}
}  // namespace

void CoarseSummary::add(double hw, std::uint8_t status, int substeps, int study_substeps, double dt) {
  if (substeps > study_substeps) {
    refined_min = refined++ == 0 ? substeps : std::min(refined_min, substeps);
    refined_max = std::max(refined_max, substeps);
  }
  if (std::isnan(hw)) return;
  ++analyses;
  coarse += status == static_cast<std::uint8_t>(LaneStatus::coarse);
  if (!(hw <= hw_max)) hw_max = hw, substeps_at_max = substeps, h_at_max = dt / substeps;
}

std::string CoarseSummary::refined_text() const {
  if (refined == 0) return "";
  return fmt::format("; refined: {} analyses run again at a shorter step ({} substeps)", refined,
                     refined_min == refined_max ? fmt::format("{}", refined_min)
                                                : fmt::format("{} to {}", refined_min, refined_max));
}

std::string describe(const CoarseSummary& c) {
  std::string s = fmt::format("coarse: {} analyses (max h·ω_c {}, limit {}){}", c.coarse,
                              std::isnan(c.hw_max) ? std::string("-") : fmt::format("{:.3g}", c.hw_max),
                              std::isinf(c.limit) ? std::string("none") : fmt::format("{:.3g}", c.limit),
                              c.refined_text());
  if (c.coarse == 0) return s;
  s += fmt::format("; {} the statistics ([analysis] coarse = \"{}\"{})",
                   c.kept ? "kept in" : c.refine ? "still coarse after refining, excluded from" : "excluded from",
                   c.kept ? "keep" : c.refine ? "refine" : "exclude",
                   c.kept || c.refine ? "" : "; \"refine\" runs them again at a shorter step");
  if (std::isfinite(c.limit) && c.limit > 0 && c.hw_max > 0)
    s += fmt::format(". To bring the largest h·ω_c under the limit: [analysis] substeps = {} (or max_dt = {:.3g} s) "
                     "-- an estimate: the peak penetration, and with it the Hertz tangent, changes with the step",
                     substeps_for_limit(c.substeps_at_max, c.hw_max, c.limit), floor3(c.h_at_max * c.limit / c.hw_max));
  return s;
}

namespace {
bool failed(std::uint8_t status) {
  const auto s = static_cast<LaneStatus>(status);
  return s == LaneStatus::diverged || s == LaneStatus::non_finite;
}
}  // namespace

StepResolution lane_resolution(const BatchResult& r, std::size_t lane, const KernelSettings& ks, ContactLaw law) {
  StepResolution w;
  w.diverged = failed(r.status[lane]);
  if (!w.diverged && r.h_omega_contact[lane] > 0.0) w.hw = r.h_omega_contact[lane], w.limit = resolution_limit(ks, law);
  return w;
}

StepResolution worst_element(const model::System& sys, std::span<const ContactModel> groups, const KernelSettings& ks,
                             const SystemResult& r, std::size_t lane) {
  StepResolution w;
  w.diverged = failed(r.status[lane]);
  double worst = -1.0;
  for (std::size_t e = 0; e < sys.contacts().size() && !w.diverged; ++e) {
    const double hw = r.h_omega_contact[SystemBatch::at(static_cast<int>(e), lane, r.width)];
    const double limit = resolution_limit(ks, groups[static_cast<std::size_t>(sys.contacts()[e].group)].law);
    if (!(hw > 0.0) || hw / limit <= worst) continue;
    worst = hw / limit, w.hw = hw, w.limit = limit;
  }
  return w;
}

StepChoice choose_step(bool given, int substeps, double record_dt, double h_stability, int max_substeps,
                       const std::function<StepResolution(int)>& run) {
  StepChoice c;
  c.given = given, c.record_dt = record_dt, c.h_stability = h_stability;
  c.substeps_stability = c.first_substeps = substeps;
  for (;;) {
    const StepResolution r = run(substeps);
    if (++c.runs == 1) c.first = r;
    c.substeps = substeps, c.last = r;
    if (given || r.resolved() || substeps >= max_substeps || c.runs >= step_max_runs) return c;
    const int next = r.diverged ? 4 * substeps : substeps_for_limit(substeps, r.hw, step_margin * r.limit);
    substeps = std::min(max_substeps, std::max(substeps + 1, next));
  }
}

std::string describe(const StepChoice& c) {
  const std::string step = c.substeps == 1 ? fmt::format("{:.6g} s (the record step)", c.h())
                                           : fmt::format("{:.6g} s (record step {:g} s / {})", c.h(), c.record_dt,
                                                         c.substeps);
  if (c.given) return step + ", given (--dt)";
  std::string s = step + ", chosen: ";
  s += std::isfinite(c.h_stability)
           ? fmt::format("stable for the structures (h < {:.4g} s{})", c.h_stability,
                         c.substeps_stability > 1 ? fmt::format(": {} substeps at least", c.substeps_stability) : "")
           : std::string("the record step");
  auto at = [](const StepResolution& r) {
    return r.diverged ? std::string("the run diverged") : fmt::format("h·ω_c {:.3g}", r.hw);
  };
  if (c.runs == 1 && c.last.diverged) return s + "; the run diverged";
  if (c.runs == 1 && std::isnan(c.last.hw)) return s + "; no contact force to resolve";
  if (c.runs == 1)
    return s + fmt::format("; the contact resolved at it (h·ω_c {:.3g} <= {:.3g}, from the run's peak penetration)",
                           c.last.hw, c.last.limit);
  s += fmt::format("; the contact needed a shorter step: {}{} at {} substep(s), then {}{} at {} (target {:g} x the "
                   "limit; {} runs)",
                   at(c.first), c.first.diverged ? "" : fmt::format(" > {:.3g}", c.first.limit), c.first_substeps,
                   at(c.last), std::isnan(c.last.hw) && !c.last.diverged ? " (no contact force)" : "", c.substeps,
                   step_margin, c.runs);
  if (!c.last.resolved()) s += "; still not resolved";
  return s;
}

std::string coarse_advice(const StepChoice& c) {
  if (c.last.resolved()) return "";
  const std::string tail = c.given ? ", or leave --dt out to let simulate choose the step" : "";
  if (c.last.diverged)
    return fmt::format("the run diverged at {:.6g} s: give a shorter --dt (e.g. {:.6g}, record step {:g} s / {}){}",
                       c.h(), c.record_dt / (4 * c.substeps), c.record_dt, 4 * c.substeps, tail);
  if (!(c.last.limit > 0)) return "";
  const int n = substeps_for_limit(c.substeps, c.last.hw, step_margin * c.last.limit);
  return fmt::format("the contact is not resolved (h·ω_c {:.3g} > {:.3g} at {:.6g} s): give --dt {:.6g} (record step "
                     "{:g} s / {}){}",
                     c.last.hw, c.last.limit, c.h(), c.record_dt / n, c.record_dt, n, tail);
}

}  // namespace pounding::physics
