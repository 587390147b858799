#pragma once
// One building's base isolation and moat inputs (issue 25 §2) as a front end gives them -- `pounding simulate`'s
// --isolationK/--bearing-*/--moat-* options or pounding.analyze_storeys's isolation=/moat= dicts -- and THE check of
// them (issue 28: one validation, worded with the front end's own names), and the physics::IsolationSpec they mean.
// The ranges are the study keys' (src/config/study_keys.cpp, sections "isolation" and "moat"): simulate, Python and
// a study accept the same bearings.
#include <functional>
#include <string>
#include <string_view>

#include "pounding/physics/shear_building.hpp"

namespace pounding::sampling {

struct IsolationInput {
  std::string bearing;  // "", "linear", "lead-rubber", "friction-pendulum", "bouc-wen"
  double base_mass = 0, k_eff = 0, zeta_eff = physics::default_bearing_zeta, k1 = 0, k2 = 0, qd = 0;
  double radius = 0, mu_slow = 0, mu_fast = 0, rate = 0, uy = 2.5e-4;  // friction pendulum
  double bw_a = 1.0, bw_beta = 0.5, bw_gamma = 0.5;                    // Bouc-Wen (with k1, k2, qd)
  int bw_eta = 1;
  bool fps_given = false, mu_fast_given = false, bw_given = false;
  double moat_gap = 0, moat_stiffness = 0, moat_e = 0;
  std::string moat_law = "hertzdamp";
  bool base_mass_given = false, k_eff_given = false, zeta_given = false, lrb_given = false, moat_given = false;
  bool moat_options_given = false, moat_stiffness_given = false, moat_e_given = false;
  bool any() const {
    return !bearing.empty() || base_mass_given || k_eff_given || zeta_given || lrb_given || moat_given ||
           moat_options_given || fps_given || bw_given;
  }
};

// The front end's name of an input in messages. Keys: the study keys "bearing", "base_mass", "k_eff", "zeta_eff",
// "k1", "k2", "qd", "radius", "mu_slow", "mu_fast", "rate", "u_y", "a", "beta", "gamma", "eta", "moat.gap",
// "moat.law", "moat.stiffness", "moat.e"; the groups "friction-pendulum keys" (radius..u_y), "bouc-wen keys"
// (a..eta), "non-pendulum keys" (k_eff, zeta_eff, k1, k2, qd), "lead-rubber keys" (k1, k2, qd), "linear keys"
// (k_eff, zeta_eff); "building" (e.g. "building 1").
using IsolationNames = std::function<std::string(std::string_view key)>;

// Checked before any work: a bearing named for any input, its numbers present and physical (SB §2: a massless base
// is singular; k2 < k1), the moat's gap, law, stiffness and e. InputError naming the input by `name`.
void validate_isolation(const IsolationInput& s, const IsolationNames& name);

// The bearing's numbers for physics::set_isolated_building (validated input): the base mass defaults to one floor's
// mass (floor_mass), mu_fast to mu_slow.
physics::IsolationSpec isolation_spec(const IsolationInput& s, double floor_mass);
physics::Bearing bearing_of(const std::string& name);

}  // namespace pounding::sampling
