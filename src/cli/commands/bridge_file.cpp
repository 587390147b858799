// Reads the bridge description of `pounding simulate --bridge` (bridge_file.hpp).
#include "cli/commands/bridge_file.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <string_view>

#include <fmt/format.h>

#include "pounding/config/config.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"

namespace pounding::cli {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// One table of the bridge file: typed reads with "FILE:line [name] key" places, and a check of unknown keys.
struct Reader {
  const toml::table& t;
  const std::string& file;
  std::string name;
  std::set<std::string, std::less<>> keys;
  std::string where(std::string_view key) const {
    const toml::node* n = t.get(key);
    return fmt::format("{} [{}] {}", config::location(file, n ? n->source() : t.source()), name, key);
  }
  const toml::node* get(std::string_view key) {
    keys.emplace(key);
    return t.get(key);
  }
  bool has(std::string_view key) { return get(key) != nullptr; }
  double number(std::string_view key, double def, double lo, double hi, std::string_view range) {
    const toml::node* n = get(key);
    if (n == nullptr) return def;
    const double v = config::number(*n, key, where(key));
    if (!(std::isfinite(v) && v >= lo && v <= hi))
      throw InputError(fmt::format("{} = {} is out of range", key, v), where(key), fmt::format("give a value in {}", range));
    return v;
  }
  double positive(std::string_view key, double def) { return number(key, def, 1e-300, inf, "(0, inf) (SI units)"); }
  double required(std::string_view key) {
    if (!has(key))
      throw InputError(fmt::format("[{}] has no {}", name, key), where(key), fmt::format("give {} (SI units)", key));
    return positive(key, 0.0);
  }
  std::string string(std::string_view key, std::string def) {
    const toml::node* n = get(key);
    return n == nullptr ? def : config::string(*n, key, where(key));
  }
  const toml::table* table(std::string_view key) {
    const toml::node* n = get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table())
      throw InputError(fmt::format("{} must be a table, not {}", key, config::type_name(*n)), where(key),
                       fmt::format("write [{}.{}] with its keys", name, key));
    return n->as_table();
  }
  void finish(std::string_view allowed) const {
    config::check_keys(t, [&](std::string_view k) { return keys.count(k) > 0; }, name, allowed,
                       [&](std::string_view k, const toml::node& v) {
                         return fmt::format("{} [{}] {}", config::location(file, v.source()), name, k);
                       });
  }
};

physics::BridgeBilinear bilinear(Reader r) {
  physics::BridgeBilinear b;
  b.k = r.required("stiffness");
  b.fy = r.positive("yield_force", inf);
  b.alpha = r.number("alpha", 0.0, 0.0, 0.999, "[0, 1)");
  r.finish("stiffness, yield_force, alpha");
  return b;
}

int support(Reader& r) { return static_cast<int>(r.number("support", 1, 1, 1000, "[1, 1000] (a --support-record index)")) - 1; }

physics::BridgeFrame frame(Reader r) {
  physics::BridgeFrame f;
  f.label = r.string("label", "");
  f.mass = r.required("mass");
  if (r.has("period") == r.has("stiffness"))
    throw InputError("a frame needs exactly one of period and stiffness", r.where("period"),
                     "give period (s) or stiffness (N/m)");
  f.period = r.number("period", 0.0, 0.02, 20.0, "[0.02, 20] s");
  f.stiffness = r.positive("stiffness", 0.0);
  f.zeta = r.number("zeta", 0.05, 0.0, 0.5, "[0, 0.5]");
  f.fy = r.positive("yield_force", inf);
  f.alpha = r.number("alpha", 0.0, 0.0, 0.999, "[0, 1)");
  const std::string h = r.string("hysteresis", "bilinear");
  if (h != "bilinear" && h != "q-hyst")
    throw InputError(fmt::format("unknown hysteresis '{}'", h), r.where("hysteresis"), "give \"bilinear\" or \"q-hyst\"");
  f.qhyst = h == "q-hyst";
  if (f.qhyst && !std::isfinite(f.fy))
    throw InputError("a Q-Hyst frame needs a yield force", r.where("yield_force"), "give yield_force (N)");
  f.beta = r.number("beta", 0.5, 0.0, 1.0, "[0, 1]");
  f.height = r.positive("height", 10.0);
  f.support = support(r);
  r.finish("label, mass, period, stiffness, zeta, yield_force, alpha, hysteresis, beta, height, support");
  return f;
}

physics::BridgeJoint joint(Reader r, double kc_default, double e_default) {
  physics::BridgeJoint j;
  j.gap = r.number("gap", -1.0, 0.0, 10.0, "[0, 10] m");
  if (!r.has("gap")) throw InputError("a joint has no gap", r.where("gap"), "give gap (m)");
  if (!r.has("contact_stiffness") && !std::isfinite(kc_default))
    throw InputError("the joint has no contact_stiffness and --kh is not given", r.where("contact_stiffness"),
                     "give contact_stiffness (law units: N/m^n for the Hertz family, N/m linear) or --kh");
  j.kc = r.positive("contact_stiffness", kc_default);
  j.e = r.number("restitution", e_default, 1e-300, 1.0, "(0, 1]");
  if (const toml::table* t = r.table("restrainer")) {
    Reader rr{*t, r.file, r.name + ".restrainer", {}};
    model::TensionGap::Spec s;
    s.k = rr.required("stiffness");
    s.fy = rr.positive("yield_force", inf);
    s.alpha = rr.number("alpha", 0.05, 0.0, 0.999, "[0, 1)");
    s.slack = rr.number("slack", j.gap, 0.0, 10.0, "[0, 10] m");
    rr.finish("stiffness, yield_force, alpha, slack");
    j.restrainer = s;
  }
  if (const toml::table* t = r.table("bearing")) j.bearing = bilinear(Reader{*t, r.file, r.name + ".bearing", {}});
  r.finish("gap, contact_stiffness, restitution, restrainer, bearing");
  return j;
}

physics::BridgeAbutment abutment(Reader r) {
  physics::BridgeAbutment a;
  const std::string b = r.string("backfill", "none");
  if (b != "none" && b != "epp" && b != "hyperbolic")
    throw InputError(fmt::format("unknown backfill '{}'", b), r.where("backfill"), "give \"none\", \"epp\" or \"hyperbolic\"");
  a.backfill = b == "epp" ? physics::Backfill::epp : b == "hyperbolic" ? physics::Backfill::hyperbolic : physics::Backfill::none;
  const double gap = r.number("gap", 0.0, 0.0, 10.0, "[0, 10] m");
  if (a.backfill == physics::Backfill::epp) {
    if (r.has("width") || r.has("height")) {
      const model::CaltransAbutment c = model::caltrans_abutment(r.required("width"), r.required("height"));
      a.epp.k = c.k, a.epp.fy = c.p_bw;
    }
    if (!r.has("width")) a.epp.k = r.required("stiffness"), a.epp.fy = r.required("capacity");
    a.epp.alpha = r.number("alpha", 0.0, 0.0, 0.999, "[0, 1)");
    a.epp.gap = gap;
  }
  if (a.backfill == physics::Backfill::hyperbolic) {
    a.hyperbolic.k_max = r.required("k_max");
    a.hyperbolic.k_ur = r.positive("k_ur", a.hyperbolic.k_max);
    if (a.hyperbolic.k_ur < a.hyperbolic.k_max)
      throw InputError("k_ur is below k_max", r.where("k_ur"), "give k_ur >= k_max (first loading follows the envelope)");
    a.hyperbolic.rf = r.number("rf", 0.7, 1e-300, 1.0, "(0, 1]");
    a.hyperbolic.f_ult = r.required("f_ult");
    a.hyperbolic.gap = gap;
  }
  if (const toml::table* t = r.table("bearing")) a.bearing = bilinear(Reader{*t, r.file, r.name + ".bearing", {}});
  a.support = support(r);
  r.finish(a.backfill == physics::Backfill::hyperbolic ? "backfill, gap, k_max, k_ur, rf, f_ult, bearing, support"
                                                       : "backfill, gap, stiffness, capacity, width, height, alpha, bearing, support");
  return a;
}

// The tables of an array key ([[frame]], [[joint]]).
std::vector<const toml::table*> tables(const toml::table& root, std::string_view key, const std::string& file) {
  std::vector<const toml::table*> out;
  const toml::node* n = root.get(key);
  if (n == nullptr) return out;
  const toml::array* a = n->as_array();
  if (a == nullptr || !a->is_array_of_tables())
    throw InputError(fmt::format("{} must be an array of tables", key), config::location(file, n->source()) + " " + std::string(key),
                     fmt::format("write each as [[{}]]", key));
  for (const toml::node& x : *a) out.push_back(x.as_table());
  return out;
}

}  // namespace

physics::BridgeSpec read_bridge_file(const std::string& path, double kc_default, double e_default) {
  const std::string text = files::read_text(path, "bridge file", 16u << 20, true);
  const toml::table root = config::parse(text, path, "fix the bridge file's syntax");
  config::check_keys(root, [](std::string_view k) { return k == "frame" || k == "joint" || k == "abutment"; }, "",
                     "frame, joint, abutment",
                     [&](std::string_view k, const toml::node& v) { return config::location(path, v.source()) + " " + std::string(k); });
  physics::BridgeSpec spec;
  int k = 0;
  for (const toml::table* t : tables(root, "frame", path))
    spec.frames.push_back(frame(Reader{*t, path, fmt::format("frame {}", ++k), {}}));
  if (spec.frames.empty())
    throw InputError("the bridge file has no [[frame]]", path, "give one [[frame]] table per frame, left to right");
  k = 0;
  for (const toml::table* t : tables(root, "joint", path))
    spec.joints.push_back(joint(Reader{*t, path, fmt::format("joint {}", ++k), {}}, kc_default, e_default));
  if (spec.joints.size() + 1 != spec.frames.size())
    throw InputError(fmt::format("{} frames need {} joints, the file has {}", spec.frames.size(), spec.frames.size() - 1,
                                 spec.joints.size()),
                     path + " [[joint]]", "give one [[joint]] between each pair of neighbouring frames");
  if (const toml::node* n = root.get("abutment")) {
    if (!n->is_table())
      throw InputError("abutment must be a table", config::location(path, n->source()) + " abutment", "write [abutment.left] / [abutment.right]");
    Reader r{*n->as_table(), path, "abutment", {}};
    if (const toml::table* t = r.table("left")) spec.left = abutment(Reader{*t, path, "abutment.left", {}});
    if (const toml::table* t = r.table("right")) spec.right = abutment(Reader{*t, path, "abutment.right", {}});
    r.finish("left, right");
  }
  const std::vector<Problem> p = physics::check_bridge(spec);
  if (!p.empty()) throw InputError(p.front().what, path + " " + p.front().where, p.front().fix);
  return spec;
}

}  // namespace pounding::cli
