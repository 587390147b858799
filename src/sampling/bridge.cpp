// The bridge reader shared by `pounding simulate --bridge` and a study's [bridge] (sampling/bridge.hpp).
#include "pounding/sampling/bridge.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "pounding/config/config.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/core/error.hpp"
#include "pounding/model/hysteresis/bridge_links.hpp"
#include "pounding/sampling/building.hpp"

namespace pounding {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

std::string table_name(std::string_view prefix, std::string_view rest) { return std::string(prefix) + std::string(rest); }

// A required number: absent is an error naming the key.
double required(config::TableReader& r, std::string_view key, std::string_view what) {
  if (r.get(key) == nullptr)
    throw InputError(fmt::format("{} has no {}", what, key), r.where(key), fmt::format("give {} (SI units)", key));
  return r.number(key, 0.0);
}

physics::BridgeBilinear bilinear(const toml::table* t, const std::string& file, const std::string& name) {
  config::TableReader r(t, file, name, "bridge.bearing");
  physics::BridgeBilinear b;
  b.k = required(r, "stiffness", "the bearing");
  b.fy = r.number("yield_force", inf);
  b.alpha = r.number("alpha");
  r.finish("stiffness, yield_force, alpha");
  return b;
}

int support(config::TableReader& r) { return static_cast<int>(r.integer("support")) - 1; }

// A stick frame's own keys (storeys > 1; physics/bridge.hpp BridgeFrame): per-level lists, modal damping.
void stick_keys(config::TableReader& r, physics::BridgeFrame& f) {
  f.storeys = static_cast<int>(r.integer("storeys"));
  const bool stick = f.storeys > 1;
  for (const char* key : {"storey_mass", "storey_stiffness", "storey_yield", "storey_height", "modal_zeta"})
    if (!stick && r.get(key) != nullptr)
      throw InputError(fmt::format("{} describes the levels of a stick frame, and the frame has one level", key), r.where(key),
                       "give storeys = n (2 or more) or the frame's own mass, stiffness/period and yield_force");
  f.storey_mass = r.numbers("storey_mass", {});
  f.storey_stiffness = r.numbers("storey_stiffness", {});
  f.storey_yield = r.numbers("storey_yield", {});
  f.storey_height = r.numbers("storey_height", {});
  const std::string d = r.string("damping");
  if (d != "rayleigh" && d != "modal")
    throw InputError(fmt::format("unknown damping '{}'", d), r.where("damping"), "give \"rayleigh\" or \"modal\"");
  if (d == "modal" && !stick)
    throw InputError("modal damping needs a stick frame (one level: its dashpot is exact)", r.where("damping"),
                     "give storeys = n (2 or more), or drop damping");
  f.modal = d == "modal";
  f.modal_zeta = r.numbers("modal_zeta", {});
  if (!f.modal_zeta.empty() && !f.modal)
    throw InputError("modal_zeta is given and the frame's damping is Rayleigh", r.where("modal_zeta"), "add damping = \"modal\", or drop modal_zeta");
  if (!f.storey_yield.empty() && r.get("yield_force") != nullptr)
    throw InputError("a frame gives both yield_force and storey_yield", r.where("storey_yield"), "give one of them");
}

physics::BridgeFrame frame(const toml::table* t, const std::string& file, const std::string& name) {
  config::TableReader r(t, file, name, "bridge.frame");
  physics::BridgeFrame f;
  f.label = r.string("label", "");
  stick_keys(r, f);
  const bool given_k = !f.storey_stiffness.empty();
  if (f.storey_mass.empty()) f.mass = required(r, "mass", "the frame");
  else if (r.get("mass") != nullptr)
    throw InputError("a frame gives both mass and storey_mass", r.where("storey_mass"), "give one of them");
  if ((r.get("period") != nullptr) + (r.get("stiffness") != nullptr) + given_k != 1)
    throw InputError(f.storeys > 1 ? "a stick frame needs exactly one of period, stiffness and storey_stiffness"
                                   : "a frame needs exactly one of period and stiffness",
                     r.where("period"), "give period (s) or stiffness (N/m)");
  f.period = r.number("period", 0.0);
  f.stiffness = r.number("stiffness", 0.0);
  f.zeta = r.number("zeta");
  f.fy = r.number("yield_force", inf);
  f.alpha = r.number("alpha");
  const std::string h = r.string("hysteresis");
  if (h != "bilinear" && h != "q-hyst")
    throw InputError(fmt::format("unknown hysteresis '{}'", h), r.where("hysteresis"), "give \"bilinear\" or \"q-hyst\"");
  f.qhyst = h == "q-hyst";
  if (f.qhyst && !std::isfinite(f.fy) && f.storey_yield.empty())
    throw InputError("a Q-Hyst frame needs a yield force", r.where("yield_force"), "give yield_force (N)");
  f.beta = r.number("beta");
  f.height = r.number("height");
  f.support = support(r);
  r.finish("label, mass, period, stiffness, zeta, yield_force, alpha, hysteresis, beta, height, support, storeys, "
           "storey_mass, storey_stiffness, storey_yield, storey_height, damping, modal_zeta");
  return f;
}

physics::BridgeJoint joint(const toml::table* t, const std::string& file, const std::string& name,
                           const BridgeReadDefaults& d) {
  config::TableReader r(t, file, name, "bridge.joint");
  physics::BridgeJoint j;
  if (r.get("gap") == nullptr) throw InputError("a joint has no gap", r.where("gap"), "give gap (m)");
  j.gap = r.number("gap", 0.0);
  if (d.study && !(j.gap > 0))
    throw InputError("a joint's gap is 0 in a study", r.where("gap"),
                     "give gap > 0 (m): the smallest joint gap is the reference d of the [gaps] ratios");
  if (r.get("contact_stiffness") == nullptr && !std::isfinite(d.kc))
    throw InputError(fmt::format("the joint has no contact_stiffness and {} is not given", d.kc_source),
                     r.where("contact_stiffness"),
                     fmt::format("give contact_stiffness (law units: N/m^n for the Hertz family, N/m linear) or {}",
                                 d.kc_source));
  if (r.get("contact_stiffness") == nullptr)  // the default given to every joint: a joint's range (issue 44 item 11)
    config::require_key_range(d.kc, "bridge.joint", "contact_stiffness", d.kc_source,
                              "the default of every joint without its own; ");
  j.kc = r.number("contact_stiffness", d.kc);
  if (!d.restitution_given_by.empty() && r.get("restitution") != nullptr)
    throw InputError(fmt::format("the joint gives its own restitution and {} gives every joint e(v0)",
                                 d.restitution_given_by),
                     r.where("restitution"),
                     fmt::format("drop the joint's restitution (the curve replaces it at every impact), or drop {}",
                                 d.restitution_given_by));
  if (r.get("restitution") == nullptr && d.restitution_given_by.empty())
    config::require_key_range(d.e, "bridge.joint", "restitution", d.e_source, "the default of every joint without its own; ");
  j.e = r.number("restitution", d.e);
  if (const toml::table* rt = r.table("restrainer")) {
    config::TableReader rr(rt, file, name + ".restrainer", "bridge.restrainer");
    model::TensionGap::Spec s;
    s.k = required(rr, "stiffness", "the restrainer");
    s.fy = rr.number("yield_force", inf);
    s.alpha = rr.number("alpha");
    if (d.study && rr.get("slack") == nullptr)
      throw InputError("a restrainer in a study has no slack", rr.where("slack"),
                       "give slack (m): the joint gap varies over the [gaps] ratios, the slack does not follow it");
    s.slack = rr.number("slack", j.gap);
    rr.finish("stiffness, yield_force, alpha, slack");
    j.restrainer = s;
  }
  if (const toml::table* bt = r.table("bearing")) j.bearing = bilinear(bt, file, name + ".bearing");
  r.finish("gap, contact_stiffness, restitution, restrainer, bearing");
  return j;
}

physics::BridgeAbutment abutment(const toml::table* t, const std::string& file, const std::string& name) {
  config::TableReader r(t, file, name, "bridge.abutment");
  physics::BridgeAbutment a;
  const std::string b = r.string("backfill");
  if (b != "none" && b != "epp" && b != "hyperbolic")
    throw InputError(fmt::format("unknown backfill '{}'", b), r.where("backfill"), "give \"none\", \"epp\" or \"hyperbolic\"");
  a.backfill = b == "epp" ? physics::Backfill::epp : b == "hyperbolic" ? physics::Backfill::hyperbolic : physics::Backfill::none;
  const double gap = r.number("gap");
  const bool wall = r.get("width") != nullptr || r.get("height") != nullptr;
  if (a.backfill == physics::Backfill::epp) {
    if (wall) {
      const model::CaltransAbutment c = model::caltrans_abutment(required(r, "width", "the abutment"),
                                                                 required(r, "height", "the abutment"));
      a.epp.k = c.k, a.epp.fy = c.p_bw, a.width = r.number("width", 0.0), a.height = r.number("height", 0.0);
    } else {
      a.epp.k = required(r, "stiffness", "the abutment"), a.epp.fy = required(r, "capacity", "the abutment");
    }
    a.epp.alpha = r.number("alpha");
    a.epp.gap = gap;
  }
  if (a.backfill == physics::Backfill::hyperbolic) {
    a.hyperbolic.k_max = required(r, "k_max", "the abutment");
    a.hyperbolic.k_ur = r.number("k_ur", a.hyperbolic.k_max);
    if (a.hyperbolic.k_ur < a.hyperbolic.k_max)
      throw InputError("k_ur is below k_max", r.where("k_ur"), "give k_ur >= k_max (first loading follows the envelope)");
    a.hyperbolic.rf = r.number("rf");
    a.hyperbolic.f_ult = required(r, "f_ult", "the abutment");
    a.hyperbolic.gap = gap;
  }
  if (const toml::table* bt = r.table("bearing")) a.bearing = bilinear(bt, file, name + ".bearing");
  a.support = support(r);
  r.finish(a.backfill == physics::Backfill::hyperbolic ? "backfill, gap, k_max, k_ur, rf, f_ult, bearing, support"
                                                       : "backfill, gap, stiffness, capacity, width, height, alpha, bearing, support");
  return a;
}

// The tables of an array key ([[frame]], [[joint]]).
std::vector<const toml::table*> tables(config::TableReader& r, std::string_view key, std::string_view prefix) {
  std::vector<const toml::table*> out;
  const toml::node* n = r.get(key);
  if (n == nullptr) return out;
  const toml::array* a = n->as_array();
  if (a == nullptr || !a->is_array_of_tables())
    throw InputError(fmt::format("{} must be an array of tables", key), r.where(key),
                     fmt::format("write each as [[{}{}]]", prefix, key));
  for (const toml::node& x : *a) out.push_back(x.as_table());
  return out;
}

}  // namespace

physics::BridgeSpec read_bridge(config::TableReader& r, const std::string& file, std::string_view prefix,
                                const BridgeReadDefaults& defaults) {
  physics::BridgeSpec spec;
  int k = 0;
  for (const toml::table* t : tables(r, "frame", prefix))
    spec.frames.push_back(frame(t, file, table_name(prefix, fmt::format("frame{}", ++k))));
  if (spec.frames.empty())
    throw InputError("the bridge has no frame", r.where("frame"),
                     fmt::format("give one [[{}frame]] table per frame, left to right", prefix));
  k = 0;
  for (const toml::table* t : tables(r, "joint", prefix))
    spec.joints.push_back(joint(t, file, table_name(prefix, fmt::format("joint{}", ++k)), defaults));
  if (spec.joints.size() + 1 != spec.frames.size())
    throw InputError(fmt::format("{} frames need {} joints, the file has {}", spec.frames.size(), spec.frames.size() - 1,
                                 spec.joints.size()),
                     r.where("joint"), fmt::format("give one [[{}joint]] between each pair of neighbouring frames", prefix));
  if (const toml::table* at = r.table("abutment")) {
    config::TableReader ar(at, file, table_name(prefix, "abutment"), "bridge.abutments");
    if (const toml::table* t = ar.table("left")) spec.left = abutment(t, file, table_name(prefix, "abutment.left"));
    if (const toml::table* t = ar.table("right")) spec.right = abutment(t, file, table_name(prefix, "abutment.right"));
    ar.finish("left, right");
  }
  const std::vector<Problem> p = physics::check_bridge(spec);
  if (!p.empty()) throw InputError(p.front().what, file + " " + std::string(prefix) + p.front().where, p.front().fix);
  return spec;
}

std::string BridgeModel::frame_label(std::size_t k) const {
  const std::string& l = spec.frames[k].label;
  return l.empty() ? fmt::format("frame {}", k + 1) : l;
}

std::string BridgeModel::joint_label(std::size_t j) const {
  return fmt::format("joint {} ({}|{})", j + 1, frame_label(j), frame_label(j + 1));
}

namespace {

// An abutment's numbers as the study gave them and as the model uses them (N, N/m, m): every key of
// [bridge.abutment.left/right] is stated, so /settings/bridge description holds them (tests/cli/settings_keys.py).
std::string describe_abutment(const physics::BridgeAbutment& a) {
  std::string out;
  if (a.backfill == physics::Backfill::epp)
    out = fmt::format("EPP backfill, gap {:.4g} m, k {:.4g} N/m, capacity {:.4g} N, alpha {:.4g}{}", a.epp.gap, a.epp.k,
                      a.epp.fy, a.epp.alpha,
                      a.width > 0 ? fmt::format(" (Caltrans SDC back wall width {:.4g} m, height {:.4g} m)", a.width, a.height)
                                  : std::string());
  else if (a.backfill == physics::Backfill::hyperbolic)
    out = fmt::format("hyperbolic backfill, gap {:.4g} m, k_max {:.4g} N/m, k_ur {:.4g} N/m, rf {:.4g}, f_ult {:.4g} N",
                      a.hyperbolic.gap, a.hyperbolic.k_max, a.hyperbolic.k_ur, a.hyperbolic.rf, a.hyperbolic.f_ult);
  else
    out = "no backfill";
  if (a.bearing)
    out += fmt::format(", bearing k {:.4g} N/m, yield force {:.4g} N, alpha {:.4g}", a.bearing->k, a.bearing->fy,
                       a.bearing->alpha);
  if (a.support > 0) out += fmt::format(", support {}", a.support + 1);
  return out;
}

}  // namespace

std::string BridgeModel::describe() const {
  std::string out = fmt::format("{} frames:", frames());
  for (std::size_t k = 0; k < frames(); ++k) {
    const physics::BridgeFrame& f = spec.frames[k];
    out += fmt::format("{} {} {:.4g} t{}, T {:.3g} s, {}{}", k ? ";" : "", frame_label(k), physics::frame_mass(f) / 1e3,
                       f.storeys > 1 ? fmt::format(" on {} levels", f.storeys) : std::string(), physics::frame_period(f),
                       f.qhyst ? "Q-Hyst" : std::isfinite(f.fy) ? "bilinear" : "elastic",
                       std::isfinite(f.fy) ? fmt::format(" F_y {:.4g} kN", f.fy / 1e3) : "");
  }
  out += fmt::format(". {} joints:", spec.joints.size());
  for (std::size_t j = 0; j < spec.joints.size(); ++j) {
    const physics::BridgeJoint& x = spec.joints[j];
    out += fmt::format("{} {} gap {:.4g} m{}{}", j ? ";" : "", joint_label(j), x.gap,
                       x.restrainer ? fmt::format(", restrainer {:.4g} kN/m slack {:.4g} m", x.restrainer->k / 1e3,
                                                  x.restrainer->slack)
                                    : "",
                       x.bearing ? ", bearing" : "");
  }
  for (const auto& [a, name] : {std::pair{&spec.left, "left"}, std::pair{&spec.right, "right"}})
    if (a->present()) out += fmt::format(". Abutment {}: {}", name, describe_abutment(*a));
  if (sampled()) out += fmt::format(". Sampled per model: period CoV {:g}, mass CoV {:g} (lognormal)", period_cov, mass_cov);
  return out;
}

BridgeModel parse_bridge_model(const toml::table* bridge, const std::string& file, double kc_default, double e_default,
                               std::int64_t* samples, const std::string& restitution_given_by) {
  config::TableReader r(bridge, file, "bridge");
  BridgeReadDefaults d;
  d.kc = kc_default, d.e = e_default, d.kc_source = "[contact] stiffness", d.e_source = "[contact] e", d.study = true;
  d.restitution_given_by = restitution_given_by;
  BridgeModel m;
  m.spec = read_bridge(r, file, "bridge.", d);
  if (m.spec.joints.empty())
    throw InputError("a bridge study needs at least one joint", r.where("frame"),
                     "give two or more [[bridge.frame]] tables and the [[bridge.joint]] between them");
  *samples = r.integer("samples");
  m.period_cov = r.number("period_cov");
  m.mass_cov = r.number("mass_cov");
  if (*samples > 1 && !m.sampled())
    throw InputError(fmt::format("samples = {} and nothing is sampled: every model would be the same bridge", *samples),
                     r.where("samples"), "give period_cov or mass_cov, or samples = 1");
  r.finish("frame, joint, abutment, samples, period_cov, mass_cov");
  m.reference_gap = inf;
  for (const physics::BridgeJoint& j : m.spec.joints) m.reference_gap = std::min(m.reference_gap, j.gap);
  for (const physics::BridgeJoint& j : m.spec.joints) m.offsets.push_back(j.gap - m.reference_gap);
  for (std::size_t k = 0; k < m.frames(); ++k) {
    const physics::BridgeFrame& f = m.spec.frames[k];
    const double T = physics::frame_period(f);
    if (!(T >= 0.02 && T <= 20.0))
      throw InputError(fmt::format("frame {}'s period {:.4g} s (from its stiffness) is outside [0.02, 20] s", k + 1, T),
                       fmt::format("{} [bridge.frame{}].stiffness", file, k + 1), "give a stiffness of a real frame");
  }
  return m;
}

SampledPair bridge_pair(const BridgeModel& b, const SampleId& id, std::span<const double> u) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  SampledPair p;
  p.id = id;
  const std::size_t n = b.frames();
  std::vector<SampledStructure> s(n);
  for (std::size_t k = 0; k < n; ++k) {
    const physics::BridgeFrame& f = b.spec.frames[k];
    const double T0 = physics::frame_period(f), m0 = physics::frame_mass(f);  // a stick: T1 and its total mass
    SampledStructure& x = s[k];
    x.T = b.period_cov > 0 ? Truncated(Distribution::lognormal(T0, b.period_cov), 0.02, 20.0).sample(u[2 * k]) : T0;
    x.m = b.mass_cov > 0 ? Truncated(Distribution::lognormal(m0, b.mass_cov), 1.0, 1e10).sample(u[2 * k + 1]) : m0;
    if (b.sampled() || f.storeys > 1) {  // a stick: the SDOF of its total mass and T1 (reports)
      const double w = 2.0 * std::numbers::pi / x.T;
      x.k = x.m * w * w;
    } else {
      x.k = physics::frame_stiffness(f);  // as pounding simulate --bridge: the given stiffness, or m (2 pi / T)^2
    }
    x.zeta = f.zeta, x.c = 2.0 * f.zeta * std::sqrt(x.k * x.m), x.fy = f.fy, x.alpha = f.alpha, x.h = f.height;
    x.aspect = x.r = x.rho = x.mbar = nan;
  }
  p.s1 = s[0];
  p.s2 = n > 1 ? s[1] : s[0];
  p.more.assign(s.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(n, 2)), s.end());
  p.d = b.reference_gap;
  p.kh = b.spec.joints.empty() ? 0.0 : b.spec.joints[0].kc;
  return p;
}

physics::BridgeSpec lane_bridge(const BridgeModel& b, const SampledPair& p, double gap) {
  physics::BridgeSpec spec = b.spec;
  for (std::size_t k = 0; k < spec.frames.size(); ++k) {
    const SampledStructure& s = p.structure(k);
    physics::BridgeFrame& f = spec.frames[k];
    if (f.storeys <= 1) {
      f.mass = s.m, f.stiffness = s.k, f.period = s.T;
    } else if (b.sampled()) {  // every level's mass by m / m0, every storey's stiffness so that T1 becomes T
      const double fm = s.m / physics::frame_mass(f), ft = s.T / physics::frame_period(f);
      physics::scale_frame(f, fm, fm / (ft * ft));
    }
  }
  for (std::size_t j = 0; j < spec.joints.size(); ++j) spec.joints[j].gap = gap + b.offsets[j];
  return spec;
}

}  // namespace pounding
