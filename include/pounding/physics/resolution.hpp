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
#include <limits>
#include <string>

#include "pounding/contact/registry.hpp"
#include "pounding/kernel/batch.hpp"

namespace pounding::physics {

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

// A study's (or a run's) coarse analyses, for the report and the run output.
struct CoarseSummary {
  std::int64_t coarse = 0, analyses = 0;  // analyses marked coarse, of all coupled analyses with a force law
  double hw_max = std::numeric_limits<double>::quiet_NaN();  // largest h omega_c of any analysis that ran
  double limit = no_limit;                // of the stepper x law
  double h_at_max = 0;                    // the step (s) of the analysis with hw_max
  int substeps_at_max = 1;                // its substeps per record step
  bool kept = false;                      // [analysis] coarse = "keep"
};
// "coarse: N analyses (max h·ω_c X, limit Y)", and when N > 0 the [analysis] substeps / max_dt that would bring
// hw_max under the limit (an estimate), and whether they were excluded or kept.
std::string describe(const CoarseSummary& c);

}  // namespace pounding::physics
