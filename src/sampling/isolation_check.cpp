// The one check of a building's isolation and moat inputs (sampling/isolation_check.hpp): simulate's options and
// Python's dicts, each worded with its front end's names.
#include "pounding/sampling/isolation_check.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "pounding/config/study_keys.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/core/error.hpp"
#include "pounding/model/hysteresis/smooth.hpp"

namespace pounding::sampling {
namespace {

using config::require_key_range;  // the study keys' ranges (config/study_keys.hpp)

void check_pendulum(const IsolationInput& s, const IsolationNames& name) {
  if (s.k_eff_given || s.zeta_given || s.lrb_given)
    throw InputError(name("non-pendulum keys") + " describe other bearings and " + name("bearing") +
                         " is friction-pendulum",
                     s.lrb_given ? name("k1") : name("k_eff"),
                     "give " + name("radius") + " and " + name("mu_slow") + " (W is the building's weight)");
  require_key_range(s.radius, "isolation", "radius", name("radius"), "required, T = 2 pi sqrt(R/g); ");
  require_key_range(s.mu_slow, "isolation", "mu_slow", name("mu_slow"), "required; ");
  if (s.mu_fast_given) require_key_range(s.mu_fast, "isolation", "mu_fast", name("mu_fast"));
  require_key_range(s.rate, "isolation", "rate", name("rate"));
  if (s.mu_fast_given && s.mu_fast != s.mu_slow && !(s.rate > 0))
    throw InputError(name("mu_fast") + " differs from " + name("mu_slow") + " but " + name("rate") +
                         " is 0, so mu(v) would stay mu_slow", name("rate"),
                     "give the rate a of mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|) (s/m, e.g. 20)");
  require_key_range(s.uy, "isolation", "u_y", name("u_y"), "the smoothing's yield displacement; ");
}

void check_hysteretic(const IsolationInput& s, const IsolationNames& name) {  // lead-rubber, Bouc-Wen
  // zeta_eff: a lead-rubber bearing's rubber dashpot (on k2); Bouc-Wen's damping is its hysteresis alone
  if (s.k_eff_given || (s.zeta_given && s.bearing == "bouc-wen"))
    throw InputError(name("linear keys") + " describe a linear bearing and " + name("bearing") + " is " + s.bearing,
                     s.k_eff_given ? name("k_eff") : name("zeta_eff"),
                     "give " + name("k1") + ", " + name("k2") + " and " + name("qd"));
  if (s.zeta_given) require_key_range(s.zeta_eff, "isolation", "zeta_eff", name("zeta_eff"));
  require_key_range(s.k1, "isolation", "k1", name("k1"), "required; ");
  require_key_range(s.k2, "isolation", "k2", name("k2"));
  if (!(s.k2 < s.k1))
    throw InputError(fmt::format("{} = {} is not below {} = {}", name("k2"), s.k2, name("k1"), s.k1), name("k2"),
                     "give the post-yield stiffness k2 < k1 (typically k1 / 10)");
  require_key_range(s.qd, "isolation", "qd", name("qd"), "required; ");
  if (s.bearing != "bouc-wen") return;
  require_key_range(s.bw_a, "isolation", "a", name("a"));
  require_key_range(s.bw_beta, "isolation", "beta", name("beta"));
  if (!(std::abs(s.bw_gamma) <= s.bw_beta))
    throw InputError(fmt::format("{} = {} is outside [-beta, beta] = [{}, {}]", name("gamma"), s.bw_gamma, -s.bw_beta,
                                 s.bw_beta),
                     name("gamma"),
                     "give |gamma| <= beta (the stable, passive Bouc-Wen class; beta is the |du| term's coefficient)");
  if (s.bw_eta < 1 || s.bw_eta > model::smooth_max_eta)
    throw InputError(fmt::format("{} = {} is out of range", name("eta"), s.bw_eta), name("eta"),
                     "give an integer exponent in [1, 8]");
}

void check_moat(const IsolationInput& s, const IsolationNames& name) {
  if (s.moat_options_given && !s.moat_given)
    throw InputError("moat options without a moat", name("moat.gap"), "give " + name("moat.gap") + " (m)");
  if (!s.moat_given) return;
  require_key_range(s.moat_gap, "moat", "gap", name("moat.gap"));
  const ContactLaw law = parse_contact_law(s.moat_law);
  if (law == ContactLaw::stereomechanical || law == ContactLaw::none)
    throw InputError(name("moat.law") + " = " + s.moat_law + " cannot act at a moat wall", name("moat.law"),
                     "give a force law (linear, kelvin, hertz, hertzdamp, jankowski)");
  if (s.moat_stiffness_given) require_key_range(s.moat_stiffness, "moat", "stiffness", name("moat.stiffness"));
  if (!(s.moat_stiffness > 0) && (law == ContactLaw::linear || law == ContactLaw::kelvin))
    require_positive(0.0, name("moat.stiffness") + " (linear/Kelvin stiffness, N/m)");
  if (s.moat_e_given) require_key_range(s.moat_e, "moat", "e", name("moat.e"));
}

}  // namespace

void validate_isolation(const IsolationInput& s, const IsolationNames& name) {
  if (!s.any()) return;
  if (s.bearing.empty())
    throw InputError("isolation options without a bearing", name("bearing"),
                     "give " + name("bearing") + " linear|lead-rubber|friction-pendulum|bouc-wen, or drop the " +
                         "bearing/moat options of " + name("building"));
  if (s.bearing != "linear" && s.bearing != "lead-rubber" && s.bearing != "friction-pendulum" && s.bearing != "bouc-wen")
    throw unknown_key_error(s.bearing, name("bearing"), name("bearing"),
                            "linear, lead-rubber, friction-pendulum, bouc-wen", "argument");
  if (s.fps_given && s.bearing != "friction-pendulum")
    throw InputError(name("friction-pendulum keys") + " describe a friction pendulum and " + name("bearing") + " is " +
                         s.bearing, name("radius"),
                     "give " + name("bearing") + " friction-pendulum, or drop those options");
  if (s.bw_given && s.bearing != "bouc-wen")
    throw InputError(name("bouc-wen keys") + " describe a Bouc-Wen bearing and " + name("bearing") + " is " + s.bearing,
                     name("beta"), "give " + name("bearing") + " bouc-wen, or drop those options");
  if (s.base_mass_given) require_key_range(s.base_mass, "isolation", "base_mass", name("base_mass"));
  if (s.bearing == "friction-pendulum") {
    check_pendulum(s, name);
  } else if (s.bearing == "linear") {
    if (s.lrb_given)
      throw InputError(name("lead-rubber keys") + " describe a lead-rubber bearing and " + name("bearing") +
                           " is linear", name("k1"),
                       "give " + name("k_eff") + " (and " + name("zeta_eff") + ") for linear");
    if (!s.k_eff_given)
      throw InputError("a linear bearing needs its effective stiffness", name("k_eff"),
                       "give " + name("k_eff") + " in N/m (e.g. 4 pi^2 M_total / T_iso^2)");
    require_key_range(s.k_eff, "isolation", "k_eff", name("k_eff"));
    require_key_range(s.zeta_eff, "isolation", "zeta_eff", name("zeta_eff"));
  } else {
    check_hysteretic(s, name);
  }
  check_moat(s, name);
}

physics::Bearing bearing_of(const std::string& name) {
  if (name == "linear") return physics::Bearing::linear;
  if (name == "friction-pendulum") return physics::Bearing::friction_pendulum;
  if (name == "bouc-wen") return physics::Bearing::bouc_wen;
  return physics::Bearing::lead_rubber;
}

physics::IsolationSpec isolation_spec(const IsolationInput& s, double floor_mass) {
  physics::IsolationSpec iso;
  iso.bearing = bearing_of(s.bearing);
  iso.base_mass = s.base_mass_given ? s.base_mass : floor_mass;  // default: one floor's mass
  iso.k_eff = s.k_eff, iso.k1 = s.k1, iso.k2 = s.k2, iso.qd = s.qd;
  // the linear bearing's ratio (default 0.1); a lead-rubber bearing's rubber dashpot only where given
  iso.zeta_eff = iso.bearing == physics::Bearing::linear || s.zeta_given ? s.zeta_eff : 0.0;
  iso.radius = s.radius, iso.mu_slow = s.mu_slow, iso.mu_fast = s.mu_fast_given ? s.mu_fast : s.mu_slow;
  iso.rate = s.rate, iso.uy = s.uy;
  iso.bw_a = s.bw_a, iso.bw_beta = s.bw_beta, iso.bw_gamma = s.bw_gamma, iso.bw_eta = s.bw_eta;
  return iso;
}

}  // namespace pounding::sampling
