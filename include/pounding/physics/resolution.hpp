#pragma once
// The resolution guard (issue 12, "stable but wrong, reported ok"): a lane that ran to the end but whose contact
// was integrated with too large a step is marked LaneStatus::coarse. Per lane, h omega_c with omega_c =
// sqrt(k_t / meff), k_t the law's tangent at the lane's peak penetration (contact/resolution.hpp), is compared
// with the accuracy limit of the stepper x law: a required trait of each law (`resolution`, contact/law.hpp),
// read here through contact::Laws (contact/registry.hpp).
//
// The limits are measured, not assumed: `pounding accuracy resolution --out docs/resolution.csv` drives one free
// impact per stepper x law through the kernel at h omega_c from 0.01 to 2 and takes the largest h omega_c up to
// which the peak contact force stays within resolution_tolerance of the converged impact (docs/accuracy.md,
// "Resolution guard"). The ctest AccuracyStability.ResolutionLimitsEqualTheMeasurement re-measures them and
// compares with the laws' declarations. Laws without a force element (none, stereomechanical) have no limit (inf).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>

#include "pounding/contact/registry.hpp"
#include "pounding/kernel/batch.hpp"

namespace pounding::model {
class System;
}

namespace pounding::physics {

struct SystemResult;

inline constexpr double resolution_tolerance = 0.01;  // relative peak-force error of one impact

// The integration schemes the limits distinguish (contact/law.hpp): rk4 with located contact onset differs from rk4.
using contact::Scheme;
using contact::scheme_count;
constexpr Scheme scheme_of(Stepper s, bool locate_contact) {
  switch (s) {
    case Stepper::central_difference: return Scheme::central_difference;
    case Stepper::newmark: return Scheme::newmark;
    case Stepper::rk4: return locate_contact ? Scheme::rk4_located : Scheme::rk4;
    case Stepper::nigam_jennings: return Scheme::nigam_jennings;
  }
  return Scheme::central_difference;
}

inline constexpr double no_limit = std::numeric_limits<double>::infinity();
// The limit of the stepper x law: the registered law's declared ResolutionLimits.
constexpr double resolution_limit(Stepper s, bool locate_contact, ContactLaw law) {
  return contact::resolution(law)[scheme_of(s, locate_contact)];
}
constexpr double resolution_limit(const KernelSettings& ks, ContactLaw law) {
  return resolution_limit(ks.stepper, ks.locate_contact, law);
}

// h omega_c from a tangent stiffness (NaN stays NaN: not applicable).
inline double h_omega(double h, double k_t, double meff) { return h * std::sqrt(k_t / meff); }

// The substeps that would bring hw_max under the limit at `substeps` now: ceil(substeps hw_max / limit). An
// estimate: the peak penetration, and with it the Hertz tangent, changes with the step.
inline int substeps_for_limit(int substeps, double hw_max, double limit) {
  return static_cast<int>(std::ceil(substeps * hw_max / limit - 1e-9));
}

// The step of a single run when the user gives none (`pounding simulate` without --dt): the structures' stability
// first (the fewest substeps per record step under physics::structure_step_max's bound), then the contact. The
// engine predicts the contact's h omega_c at the peak penetration by running the analysis (a pilot run at the step
// so far; the guard's h omega_c comes from the run's own peak penetration), and keeps the run when every contact
// element is resolved (h omega_c <= the limit of its stepper x law) -- so where the record step already resolves
// the contact, the result is today's, bit for bit. Otherwise it runs again at ceil(n h omega_c / (margin limit))
// substeps (margin 0.8: the peak penetration, and with it the Hertz tangent, changes with the step; a diverged run: 4 n), until resolved,
// at most `max_runs` runs or `max_substeps` substeps; the last run is the result (still coarse if it could not be
// resolved: the run says so, and which step would).
struct StepResolution {
  double hw = std::numeric_limits<double>::quiet_NaN();  // largest h omega_c / limit over the elements: its h omega_c
  double limit = no_limit;                                // ... and that element's limit (NaN hw: no contact force)
  bool diverged = false;                                  // the run diverged (or went non-finite): no h omega_c
  bool resolved() const { return !diverged && !(hw > limit); }
};
struct StepChoice {
  bool given = false;                 // the user gave the step (--dt): one run, nothing chosen
  double record_dt = 0;               // s
  int substeps = 1;                   // of the final run
  int substeps_stability = 1;         // the structures' stability alone
  double h_stability = no_limit;      // their bound, s (inf: none computed)
  int runs = 0;                       // analyses run (pilot runs + the final one)
  StepResolution first, last;         // the first and the final run's worst contact element
  int first_substeps = 1;
  double h() const { return record_dt / substeps; }
};
// A run's worst contact element, what choose_step's `run` returns (and what [analysis] coarse = "refine" reads, study/
// refine.hpp): lane `lane` of a pair kernel run (its one element, the law `law`), or of a system run (the largest
// h omega_c / limit over the elements, each with its group's law in `groups`); NaN h omega_c when no element carried a
// force, diverged for a diverged or non-finite lane.
StepResolution lane_resolution(const BatchResult& r, std::size_t lane, const KernelSettings& ks, ContactLaw law);
StepResolution worst_element(const model::System& sys, std::span<const ContactModel> groups, const KernelSettings& ks,
                             const SystemResult& r, std::size_t lane = 0);
inline constexpr double step_margin = 0.8;
inline constexpr int step_max_runs = 6;
// run(n) runs the analysis at record_dt / n and returns its worst element (largest h omega_c / limit).
StepChoice choose_step(bool given, int substeps, double record_dt, double h_stability, int max_substeps,
                       const std::function<StepResolution(int substeps)>& run);
// "0.000625 s (record step 0.005 s / 8), chosen: ..." -- how the step came about, for the run's output; and, when the
// final run is still coarse, the --dt that would resolve it (empty otherwise).
std::string describe(const StepChoice& c);
std::string coarse_advice(const StepChoice& c);

// A study's (or a run's) coarse analyses, for the report and the run output.
struct CoarseSummary {
  std::int64_t coarse = 0, analyses = 0;  // analyses marked coarse, of all coupled analyses with a force law
  double hw_max = std::numeric_limits<double>::quiet_NaN();  // largest h omega_c of any analysis that ran
  double limit = no_limit;                // of the stepper x law
  double h_at_max = 0;                    // the step (s) of the analysis with hw_max
  int substeps_at_max = 1;                // its substeps per record step
  bool kept = false;                      // [analysis] coarse = "keep"
  bool refine = false;                    // [analysis] coarse = "refine" (study/refine.hpp): `coarse` is those still
  std::int64_t refined = 0;               // coarse after it; the analyses run again at a shorter step,
  int refined_min = 0, refined_max = 0;   // ... and the fewest and most substeps of their final runs
  // One coupled analysis of a record of step dt: its h omega_c (NaN: no force law or diverged, not among `analyses`),
  // status, the substeps it ran at and the study's substeps for dt (fewer than it ran at: refined).
  void add(double hw, std::uint8_t status, int substeps, int study_substeps, double dt);
  // "; refined: N analyses run again at a shorter step (A to B substeps)" (empty when none was)
  std::string refined_text() const;
};
// "coarse: N analyses (max h·ω_c X, limit Y)", the refined ones ([analysis] coarse = "refine"), and when N > 0 the
// [analysis] substeps / max_dt that would bring hw_max under the limit (an estimate), and whether they were excluded
// or kept.
std::string describe(const CoarseSummary& c);

}  // namespace pounding::physics
