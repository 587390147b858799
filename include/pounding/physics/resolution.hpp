#pragma once
// The resolution guard (issue 12, "stable but wrong, reported ok"): a lane that ran to the end but whose contact
// was integrated with too large a step is marked LaneStatus::coarse. Per lane, h omega_c with omega_c =
// sqrt(k_t / meff), k_t the law's tangent at the lane's peak penetration (contact/resolution.hpp), is compared
// with the accuracy limit of the stepper x law below.
//
// The limits are measured, not assumed: `pounding accuracy resolution --out docs/resolution.csv` drives one free
// impact per stepper x law through the kernel at h omega_c from 0.01 to 2 and takes the largest h omega_c up to
// which the peak contact force stays within resolution_tolerance of the converged impact (docs/accuracy.md,
// "Resolution guard"). The ctest AccuracyStability.ResolutionLimitsEqualTheMeasurement re-measures them and
// compares with this table. Laws without a force element (none, stereomechanical) have no limit (inf).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "pounding/contact/model.hpp"
#include "pounding/kernel/batch.hpp"

namespace pounding::physics {

inline constexpr double resolution_tolerance = 0.01;  // relative peak-force error of one impact

// The integration schemes the limits distinguish: rk4 with located contact onset differs from rk4.
enum class Scheme : std::uint8_t { central_difference, newmark, rk4, rk4_located, nigam_jennings };
inline constexpr std::size_t scheme_count = 5;
inline constexpr std::size_t law_count = 7;  // ContactLaw's values (contact/model.hpp)
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
// [scheme][law]: none, linear, kelvin, hertz, hertzdamp, jankowski, stereomechanical (measured, see above)
inline constexpr std::array<std::array<double, law_count>, scheme_count> resolution_limits{{
    {no_limit, 0.304, 0.079, 0.366, 0.274, 0.099, no_limit},  // central-difference
    {no_limit, 0.214, 0.079, 0.215, 0.214, 0.092, no_limit},  // newmark
    {no_limit, 0.261, 0.114, 0.274, 0.268, 0.124, no_limit},  // rk4
    {no_limit, 0.285, 0.174, 0.281, 0.268, 0.181, no_limit},  // rk4 + locate_contact
    {no_limit, 0.248, 0.079, 0.241, 0.235, 0.099, no_limit},  // nigam-jennings
}};
constexpr double resolution_limit(Stepper s, bool locate_contact, ContactLaw law) {
  return resolution_limits[static_cast<std::size_t>(scheme_of(s, locate_contact))][static_cast<std::size_t>(law)];
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
