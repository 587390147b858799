// The bridge chain builder (physics/bridge.hpp).
#include "pounding/physics/bridge.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "pounding/model/hysteresis/registry.hpp"

namespace pounding::physics {

int BridgeSpec::channels() const {
  int c = 0;
  for (const BridgeFrame& f : frames) c = std::max(c, f.support);
  if (left.present()) c = std::max(c, left.support);
  if (right.present()) c = std::max(c, right.support);
  return c + 1;
}

double frame_stiffness(const BridgeFrame& f) {
  if (f.storeys > 1) return frame_numbers(f).k[0];
  if (f.stiffness > 0) return f.stiffness;
  const double w = 2.0 * std::numbers::pi / f.period;
  return f.mass * w * w;
}

std::vector<double> frame_storey_heights(const BridgeFrame& f) {
  const auto n = static_cast<std::size_t>(std::max(f.storeys, 1));
  if (f.storey_height.size() == 1) return std::vector<double>(n, f.storey_height[0]);
  if (!f.storey_height.empty()) return f.storey_height;
  return std::vector<double>(n, f.height / static_cast<double>(n));
}

namespace {
ShearSpec frame_shear_spec(const BridgeFrame& f) {
  ShearSpec s;
  s.floor_mass = f.storey_mass.empty() ? std::vector<double>{f.mass} : f.storey_mass;
  if (!f.storey_stiffness.empty()) s.storey_stiffness = f.storey_stiffness;
  else if (f.stiffness > 0) s.storey_stiffness = {f.stiffness};
  else s.period = f.period;
  s.profile = model::StiffnessProfile::uniform;
  s.storey_yield = f.storey_yield.empty() ? std::vector<double>{f.fy} : f.storey_yield;
  s.alpha = f.alpha, s.zeta = f.zeta;
  s.modal = f.modal, s.modal_zeta = f.modal_zeta;
  return s;
}
}  // namespace

ShearNumbers frame_numbers(const BridgeFrame& f) {
  return shear_numbers(frame_storey_heights(f), frame_shear_spec(f));
}

double frame_mass(const BridgeFrame& f) {
  if (f.storeys <= 1) return f.mass;
  if (f.storey_mass.empty()) return f.mass * f.storeys;
  double m = 0.0;
  for (int i = 0; i < f.storeys; ++i) m += f.storey_mass[f.storey_mass.size() == 1 ? 0 : static_cast<std::size_t>(i)];
  return m;
}

double frame_period(const BridgeFrame& f) {
  if (f.storeys <= 1) return 2.0 * std::numbers::pi * std::sqrt(f.mass / frame_stiffness(f));
  return frame_numbers(f).modes.period[0];
}

void scale_frame(BridgeFrame& f, double fm, double fk) {
  if (f.storeys <= 1) {
    f.mass *= fm, f.stiffness = frame_stiffness(f) * fk, f.period = 0.0;
    return;
  }
  const ShearNumbers num = frame_numbers(f);
  f.storey_mass = num.m, f.storey_stiffness = num.k;
  for (double& m : f.storey_mass) m *= fm;
  for (double& k : f.storey_stiffness) k *= fk;
  f.mass = f.storey_mass.back(), f.stiffness = 0.0, f.period = 0.0;
}

BridgeIndex bridge_index(const BridgeSpec& spec) {
  BridgeIndex x;
  const int n = static_cast<int>(spec.frames.size());
  int next = 0;
  for (int k = 0; k < n; ++k) {
    const BridgeFrame& f = spec.frames[static_cast<std::size_t>(k)];
    const int levels = std::max(f.storeys, 1);
    x.frame_spring.push_back(next), x.frame_dof.push_back(next), x.deck.push_back(next + levels - 1);
    next += levels;
    const std::string l = f.label.empty() ? fmt::format("frame{}", k + 1) : f.label;
    x.frame_label.push_back(l);
    x.spring_label.push_back(l);  // one level: the frame's name (its storey spring is not a link)
    for (int s = 2; s <= levels; ++s) x.spring_label.push_back(fmt::format("{} storey {}", l, s));
    if (levels > 1) x.spring_label[static_cast<std::size_t>(x.frame_dof.back())] = l + " storey 1";
  }
  for (std::size_t k = 0; k < spec.joints.size(); ++k) {
    const BridgeJoint& j = spec.joints[k];
    x.restrainer.push_back(j.restrainer ? next++ : -1);
    if (j.restrainer) x.spring_label.push_back(fmt::format("restrainer {}", k + 1));
    x.bearing.push_back(j.bearing ? next++ : -1);
    if (j.bearing) x.spring_label.push_back(fmt::format("hinge bearing {}", k + 1));
  }
  for (const auto& [a, name, fill, bear] :
       {std::tuple{&spec.left, "left", &x.left_backfill, &x.left_bearing},
        std::tuple{&spec.right, "right", &x.right_backfill, &x.right_bearing}}) {
    if (a->backfill != Backfill::none) *fill = next++, x.spring_label.push_back(fmt::format("abutment {} backfill", name));
    if (a->bearing) *bear = next++, x.spring_label.push_back(fmt::format("abutment {} bearing", name));
  }
  return x;
}

namespace {
void positive(std::vector<Problem>& out, double v, const std::string& where, const char* unit) {
  if (!(std::isfinite(v) && v > 0))
    out.push_back({fmt::format("{} = {} must be finite and > 0", where, v), where, fmt::format("give a value > 0 ({})", unit)});
}
void yield_alpha(std::vector<Problem>& out, double fy, double alpha, const std::string& where) {
  if (!(fy > 0))
    out.push_back({fmt::format("yield force {} must be > 0", fy), where + " yield_force", "give F_y > 0 (N), or leave it out for a linear spring"});
  if (!(alpha >= 0 && alpha < 1))
    out.push_back({fmt::format("alpha = {} is outside [0, 1)", alpha), where + " alpha", "give a post-yield ratio in [0, 1)"});
}
void bilinear(std::vector<Problem>& out, const BridgeBilinear& b, const std::string& where) {
  positive(out, b.k, where + " stiffness", "N/m");
  yield_alpha(out, b.fy, b.alpha, where);
}
void gap(std::vector<Problem>& out, double g, const std::string& where) {
  if (!(std::isfinite(g) && g >= 0))
    out.push_back({fmt::format("gap = {} must be finite and >= 0", g), where, "give a gap >= 0 (m)"});
}
// A list of one value or one per level, each finite and > 0 (empty: not given).
void per_level(std::vector<Problem>& out, const std::vector<double>& v, int n, const std::string& where, const char* unit) {
  if (v.empty()) return;
  if (v.size() != 1 && v.size() != static_cast<std::size_t>(n))
    out.push_back({fmt::format("{} values for a frame of {} levels", v.size(), n), where,
                   fmt::format("give one value for every level or {} (bottom first)", n)});
  for (double x : v) positive(out, x, where, unit);
}

// A short shear stick frame (storeys > 1): its lists, its period, damping and hysteresis.
void stick(std::vector<Problem>& out, const BridgeFrame& f, const std::string& w) {
  if (f.storeys > 50) out.push_back({fmt::format("storeys = {} is above 50", f.storeys), w + " storeys", "give a short stick (2 to 50 levels)"});
  if (f.storey_mass.empty()) positive(out, f.mass, w + " mass", "kg");
  per_level(out, f.storey_mass, f.storeys, w + " storey_mass", "kg");
  per_level(out, f.storey_stiffness, f.storeys, w + " storey_stiffness", "N/m");
  per_level(out, f.storey_yield, f.storeys, w + " storey_yield", "N");
  per_level(out, f.storey_height, f.storeys, w + " storey_height", "m");
  if (f.storey_stiffness.empty() && f.stiffness > 0) positive(out, f.stiffness, w + " stiffness", "N/m");
  else if (f.storey_stiffness.empty() && !(std::isfinite(f.period) && f.period >= 0.02 && f.period <= 20))
    out.push_back({fmt::format("period = {} s is outside [0.02, 20] s", f.period), w + " period",
                   "give the frame's fundamental period (s), its storey stiffness (N/m) or storey_stiffness"});
  if (!(f.zeta >= 0 && f.zeta <= 0.5)) out.push_back({fmt::format("zeta = {} is outside [0, 0.5]", f.zeta), w + " zeta", "give a damping ratio in [0, 0.5]"});
  for (double z : f.modal_zeta)
    if (!(z >= 0 && z <= 0.5)) out.push_back({fmt::format("modal_zeta {} is outside [0, 0.5]", z), w + " modal_zeta", "give damping ratios in [0, 0.5]"});
  if (f.storey_yield.empty()) yield_alpha(out, f.fy, f.alpha, w);
  else yield_alpha(out, 1.0, f.alpha, w);
  bool finite = f.storey_yield.empty() ? std::isfinite(f.fy) : true;
  for (double y : f.storey_yield) finite = finite && std::isfinite(y);
  if (f.qhyst && !finite) out.push_back({"a Q-Hyst frame needs a finite yield force in every storey", w + " yield_force", "give yield_force or storey_yield (N)"});
  if (f.qhyst && !(f.beta >= 0 && f.beta <= 1))
    out.push_back({fmt::format("beta = {} is outside [0, 1]", f.beta), w + " beta", "give Q-Hyst's unloading exponent (0.5)"});
  positive(out, f.height, w + " height", "m");
  if (f.support < 0) out.push_back({"support < 0", w + " support", "give a support channel >= 0"});
}
}  // namespace

std::vector<Problem> check_bridge(const BridgeSpec& spec) {
  std::vector<Problem> out;
  if (spec.frames.empty()) out.push_back({"a bridge needs at least one frame", "frames", "give [[frames]] tables"});
  if (!spec.frames.empty() && spec.joints.size() + 1 != spec.frames.size())
    out.push_back({fmt::format("{} frames need {} joints, not {}", spec.frames.size(), spec.frames.size() - 1, spec.joints.size()),
                   "joints", "give one [[joints]] table between each pair of neighbouring frames"});
  for (std::size_t k = 0; k < spec.frames.size(); ++k) {
    const BridgeFrame& f = spec.frames[k];
    const std::string w = fmt::format("frames[{}]", k + 1);
    if (f.storeys < 1) {
      out.push_back({fmt::format("storeys = {} is below 1", f.storeys), w + " storeys", "give 1 (an SDOF frame) or more levels"});
      continue;
    }
    if (f.storeys > 1) {
      stick(out, f, w);
      continue;
    }
    positive(out, f.mass, w + " mass", "kg");
    if (f.stiffness > 0) positive(out, f.stiffness, w + " stiffness", "N/m");
    else if (!(std::isfinite(f.period) && f.period >= 0.02 && f.period <= 20))
      out.push_back({fmt::format("period = {} s is outside [0.02, 20] s", f.period), w + " period",
                     "give the frame's period (s) or its stiffness (N/m)"});
    if (!(f.zeta >= 0 && f.zeta <= 0.5)) out.push_back({fmt::format("zeta = {} is outside [0, 0.5]", f.zeta), w + " zeta", "give a damping ratio in [0, 0.5]"});
    yield_alpha(out, f.fy, f.alpha, w);
    if (f.qhyst && !std::isfinite(f.fy))
      out.push_back({"a Q-Hyst frame needs a finite yield force", w + " yield_force", "give yield_force (N)"});
    if (f.qhyst && !(f.beta >= 0 && f.beta <= 1))
      out.push_back({fmt::format("beta = {} is outside [0, 1]", f.beta), w + " beta", "give Q-Hyst's unloading exponent (0.5)"});
    positive(out, f.height, w + " height", "m");
    if (f.support < 0) out.push_back({"support < 0", w + " support", "give a support channel >= 0"});
  }
  for (std::size_t k = 0; k < spec.joints.size(); ++k) {
    const BridgeJoint& j = spec.joints[k];
    const std::string w = fmt::format("joints[{}]", k + 1);
    gap(out, j.gap, w + " gap");
    if (j.restrainer) {
      positive(out, j.restrainer->k, w + " restrainer stiffness", "N/m");
      yield_alpha(out, j.restrainer->fy, j.restrainer->alpha, w + " restrainer");
      gap(out, j.restrainer->slack, w + " restrainer slack");
    }
    if (j.bearing) bilinear(out, *j.bearing, w + " bearing");
  }
  for (const auto& [a, name] : {std::pair{&spec.left, "abutments.left"}, std::pair{&spec.right, "abutments.right"}}) {
    const std::string w = name;
    if (a->backfill == Backfill::epp) {
      positive(out, a->epp.k, w + " stiffness", "N/m");
      yield_alpha(out, a->epp.fy, a->epp.alpha, w);
      gap(out, a->epp.gap, w + " gap");
    }
    if (a->backfill == Backfill::hyperbolic) {
      const model::HyperbolicGap::Spec& h = a->hyperbolic;
      positive(out, h.k_max, w + " k_max", "N/m");
      positive(out, h.f_ult, w + " f_ult", "N");
      if (!(h.k_ur >= h.k_max && std::isfinite(h.k_ur)))
        out.push_back({fmt::format("k_ur = {} is below k_max = {}", h.k_ur, h.k_max), w + " k_ur", "give k_ur >= k_max (default k_max)"});
      if (!(h.rf > 0 && h.rf <= 1)) out.push_back({fmt::format("rf = {} is outside (0, 1]", h.rf), w + " rf", "give the failure ratio (0.7)"});
      gap(out, h.gap, w + " gap");
    }
    if (a->bearing) bilinear(out, *a->bearing, w + " bearing");
    if (a->support < 0) out.push_back({"support < 0", w + " support", "give a support channel >= 0"});
  }
  return out;
}

model::System bridge_system(const BridgeSpec& spec) {
  const BridgeIndex x = bridge_index(spec);
  model::System::Parts P;
  P.channels = spec.channels();
  const int n = static_cast<int>(spec.frames.size());
  constexpr int bilinear = model::law_of<model::BilinearKinematic>, qhyst = model::law_of<model::QHyst>;
  for (int k = 0; k < n; ++k) {
    const BridgeFrame& f = spec.frames[static_cast<std::size_t>(k)];
    const int levels = std::max(f.storeys, 1), d0 = x.frame_dof[static_cast<std::size_t>(k)];
    model::Body b;
    b.channel = f.support;
    b.label = x.frame_label[static_cast<std::size_t>(k)];
    if (levels == 1) {
      b.dofs = {d0}, b.heights = {f.height};
    } else {
      b.storey_dashpots = !f.modal;
      if (f.modal) b.damping = model::DampingForm::dense;
      double z = 0.0;
      for (double h : frame_storey_heights(f)) b.dofs.push_back(d0 + static_cast<int>(b.dofs.size())), b.heights.push_back(z += h);
    }
    P.bodies.push_back(b);
    for (int s = 0; s < levels; ++s)
      P.springs.push_back({s == 0 ? model::ground : d0 + s - 1, d0 + s, f.qhyst ? qhyst : bilinear,
                           model::SpringRole::storey, k, s + 1});
  }
  const auto deck = [&](int k) { return x.deck[static_cast<std::size_t>(k)]; };
  for (int k = 0; k + 1 < n; ++k) {
    const BridgeJoint& j = spec.joints[static_cast<std::size_t>(k)];
    if (j.restrainer) P.springs.push_back({deck(k), deck(k + 1), model::law_of<model::TensionGap>, model::SpringRole::link, k + 1, 0});
    if (j.bearing) P.springs.push_back({deck(k), deck(k + 1), bilinear, model::SpringRole::link, k + 1, 0});
  }
  for (const auto& [a, body] : {std::pair{&spec.left, 0}, std::pair{&spec.right, n - 1}}) {
    const int dof = deck(body);
    if (a->backfill != Backfill::none)
      P.springs.push_back({model::ground, dof,
                           a->backfill == Backfill::epp ? model::law_of<model::CompressionGap> : model::law_of<model::HyperbolicGap>,
                           model::SpringRole::link, body, 0, a->support});
    if (a->bearing) P.springs.push_back({model::ground, dof, bilinear, model::SpringRole::link, body, 0, a->support});
  }
  for (int k = 0; k + 1 < n; ++k) {
    model::ContactElement e;
    e.left = {model::SideKind::point, deck(k), -1, 0};
    e.right = {model::SideKind::point, deck(k + 1), -1, 0};
    e.group = 0, e.level = 1;
    e.label = fmt::format("joint {}", k + 1);
    P.contacts.push_back(e);
  }
  if (n > 1) P.groups.push_back(model::ContactGroup{"joints", true});
  const std::vector<Problem> problems = model::System::check(P);
  if (!problems.empty()) throw std::invalid_argument("bridge_system: " + problems.front().what + " at " + problems.front().where);
  return model::System::build(std::move(P));
}

namespace {
// A stick frame's lane (body k): the shear building's numbers (set_shear_building: masses, Rayleigh dashpots or the
// dense modal C, bilinear storey springs), then Q-Hyst storey springs in place of the bilinear ones.
void set_stick_frame(SystemBatch& B, std::size_t lane, int k, const BridgeFrame& f) {
  const ShearNumbers num = set_shear_building(B, lane, k, frame_shear_spec(f));
  if (!f.qhyst) return;
  const model::Body& b = B.system->bodies()[static_cast<std::size_t>(k)];
  for (std::size_t i = 0; i < b.dofs.size(); ++i)
    B.spring[SystemBatch::at(B.system->spring_below(b.dofs[i]), lane, B.width)] =
        model::QHyst::pack({num.k[i], num.fy[i], f.alpha, f.beta});
}
}  // namespace

void set_bridge(SystemBatch& B, std::size_t lane, const BridgeSpec& spec) {
  const BridgeIndex x = bridge_index(spec);
  const std::size_t w = B.width;
  auto at = [&](int i) { return SystemBatch::at(i, lane, w); };
  for (std::size_t k = 0; k < spec.frames.size(); ++k) {
    const BridgeFrame& f = spec.frames[k];
    if (f.storeys > 1) {
      set_stick_frame(B, lane, static_cast<int>(k), f);
      continue;
    }
    const int d = x.frame_dof[k];
    const double kf = frame_stiffness(f);
    B.m[at(d)] = f.mass, B.c_floor[at(d)] = 2.0 * f.zeta * std::sqrt(kf * f.mass);
    B.u0[at(d)] = 0.0, B.v0[at(d)] = 0.0;
    SpringSpec s{kf, f.fy, f.alpha};
    if (f.qhyst) s = model::QHyst::pack({kf, f.fy, f.alpha, f.beta});
    B.spring[at(x.frame_spring[k])] = s;
  }
  for (std::size_t k = 0; k < spec.joints.size(); ++k) {
    const BridgeJoint& j = spec.joints[k];
    const int e = static_cast<int>(k);
    B.gap[at(e)] = j.gap, B.kc[at(e)] = j.kc, B.e[at(e)] = j.e, B.weight[at(e)] = 0.0;
    if (j.restrainer) {
      model::TensionGap::Spec r = *j.restrainer;
      r.side = 1;
      B.spring[at(x.restrainer[k])] = model::TensionGap::pack(r);
    }
    if (j.bearing) B.spring[at(x.bearing[k])] = {j.bearing->k, j.bearing->fy, j.bearing->alpha};
  }
  for (const auto& [a, side, fill, bear] : {std::tuple{&spec.left, -1, x.left_backfill, x.left_bearing},
                                            std::tuple{&spec.right, 1, x.right_backfill, x.right_bearing}}) {
    if (a->backfill == Backfill::epp) {
      model::CompressionGap::Spec c = a->epp;
      c.side = side;
      B.spring[at(fill)] = model::CompressionGap::pack(c);
    } else if (a->backfill == Backfill::hyperbolic) {
      model::HyperbolicGap::Spec h = a->hyperbolic;
      h.side = side;
      B.spring[at(fill)] = model::HyperbolicGap::pack(h);
    }
    if (a->bearing) B.spring[at(bear)] = {a->bearing->k, a->bearing->fy, a->bearing->alpha};
  }
}

}  // namespace pounding::physics
