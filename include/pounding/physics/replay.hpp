#pragma once
// Contact-law replay (issue 26 §3): a contact law evaluated on imposed or measured kinematics (penetration and its
// rate against time), as the bridge and impact-stiffness papers computed their "theoretical" forces: the force
// history, each impact's numbers (approach velocity latched at onset, e used, peak force and penetration, the work
// done in approach and in restitution and their difference, the energy dissipated = the loop's area) and, against a
// measured force, the papers' error metrics (impact-stiffness paper eq. 10: |F_e,max - F_t,max| / F_e,max x 100 %;
// the bridge paper's time-averaged absolute difference). Pure computation: the command reads and writes the files.
#include <cstddef>
#include <vector>

#include "pounding/contact/model.hpp"
#include "pounding/contact/restitution.hpp"

namespace pounding::physics {

struct ReplayInput {
  std::vector<double> t, d, dd;  // time (s, strictly increasing), penetration u1 - u2 - gap (m), its rate (m/s)
  std::vector<double> measured;  // measured force (N), empty when none
};

struct ReplaySettings {
  ContactModel cm;
  double kc = 0.0;   // the stiffness given (N/m^n); the law acts on contact::stiffness_factor(cm) x kc
  double e = 1.0;    // restitution (when no curve)
  double meff = 0.0; // m1 m2 / (m1 + m2) (kg): Kelvin's and Jankowski's damping constants; 0 when not given
  const contact::RestitutionCurve* curve = nullptr;  // e(v0) per impact instead of e
};

struct ReplayImpact {
  std::size_t first = 0, last = 0;  // samples in contact (d > 0), inclusive
  double t_start = 0, t_end = 0;    // first and last sample in contact (s)
  double v0 = 0;                    // approach velocity latched at onset (m/s; interpolated at the crossing)
  double e = 0;                     // restitution used
  bool outside_valid = false, clamped = false;  // e(v0): v0 outside the curve's valid range; e clamped
  double peak_force = 0, peak_penetration = 0;
  double work_approach = 0, work_restitution = 0, energy_dissipated = 0;  // J: integral F dd over d rising / falling
  double measured_peak = 0, peak_error_pct = 0;  // measured peak over the same samples; eq. 10 (NaN without)
};

struct ReplayResult {
  std::vector<double> force;        // N, per sample
  std::vector<int> impact;          // impact number (1-based) per sample, 0 out of contact
  std::vector<ReplayImpact> impacts;
  int clamps = 0;                   // samples where the law's non-tensile clamp acted
  double peak_force = 0, energy_dissipated = 0;
  // against the measured force (NaN without): eq. 10 on the record's peaks, the time-averaged |F - F_measured|
  // (1/T) integral |dF| dt, its RMS
  double measured_peak = 0, peak_error_pct = 0, mean_abs_difference = 0, rms_difference = 0;
};

// Second-order central differences of y(t) on a non-uniform grid (numpy.gradient's formula), one-sided first-order
// at the two ends.
std::vector<double> differentiate(const std::vector<double>& t, const std::vector<double>& y);

// The law on the kinematics. Needs cm.law with a force element (not none, not stereomechanical), in.t.size() >= 2.
ReplayResult replay(const ReplayInput& in, const ReplaySettings& s);

}  // namespace pounding::physics
