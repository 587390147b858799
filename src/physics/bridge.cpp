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
  if (f.stiffness > 0) return f.stiffness;
  const double w = 2.0 * std::numbers::pi / f.period;
  return f.mass * w * w;
}

BridgeIndex bridge_index(const BridgeSpec& spec) {
  BridgeIndex x;
  const int n = static_cast<int>(spec.frames.size());
  int next = 0;
  for (int k = 0; k < n; ++k) {
    x.frame_spring.push_back(next++);
    const std::string& l = spec.frames[static_cast<std::size_t>(k)].label;
    x.spring_label.push_back(l.empty() ? fmt::format("frame{}", k + 1) : l);
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
  for (int k = 0; k < n; ++k) {
    const BridgeFrame& f = spec.frames[static_cast<std::size_t>(k)];
    model::Body b;
    b.dofs = {k};
    b.heights = {f.height};
    b.channel = f.support;
    b.label = x.spring_label[static_cast<std::size_t>(k)];
    P.bodies.push_back(b);
    P.springs.push_back({model::ground, k, f.qhyst ? model::law_qhyst : model::law_bilinear, model::SpringRole::storey, k, 1});
  }
  for (int k = 0; k + 1 < n; ++k) {
    const BridgeJoint& j = spec.joints[static_cast<std::size_t>(k)];
    if (j.restrainer) P.springs.push_back({k, k + 1, model::law_restrainer, model::SpringRole::link, k + 1, 0});
    if (j.bearing) P.springs.push_back({k, k + 1, model::law_bilinear, model::SpringRole::link, k + 1, 0});
  }
  for (const auto& [a, dof] : {std::pair{&spec.left, 0}, std::pair{&spec.right, n - 1}}) {
    if (a->backfill != Backfill::none)
      P.springs.push_back({model::ground, dof,
                           a->backfill == Backfill::epp ? model::law_abutment : model::law_hyperbolic_abutment,
                           model::SpringRole::link, dof, 0, a->support});
    if (a->bearing) P.springs.push_back({model::ground, dof, model::law_bilinear, model::SpringRole::link, dof, 0, a->support});
  }
  for (int k = 0; k + 1 < n; ++k) {
    model::ContactElement e;
    e.left = {model::SideKind::point, k, -1, 0};
    e.right = {model::SideKind::point, k + 1, -1, 0};
    e.group = 0, e.level = 1;
    e.label = fmt::format("joint {}", k + 1);
    P.contacts.push_back(e);
  }
  if (n > 1) P.groups.push_back(model::ContactGroup{"joints", true});
  const std::vector<Problem> problems = model::System::check(P);
  if (!problems.empty()) throw std::invalid_argument("bridge_system: " + problems.front().what + " at " + problems.front().where);
  return model::System::build(std::move(P));
}

void set_bridge(SystemBatch& B, std::size_t lane, const BridgeSpec& spec) {
  const BridgeIndex x = bridge_index(spec);
  const std::size_t w = B.width;
  auto at = [&](int i) { return SystemBatch::at(i, lane, w); };
  for (std::size_t k = 0; k < spec.frames.size(); ++k) {
    const BridgeFrame& f = spec.frames[k];
    const int d = static_cast<int>(k);
    const double kf = frame_stiffness(f);
    B.m[at(d)] = f.mass, B.c_floor[at(d)] = 2.0 * f.zeta * std::sqrt(kf * f.mass);
    B.u0[at(d)] = 0.0, B.v0[at(d)] = 0.0;
    SpringSpec s{kf, f.fy, f.alpha};
    if (f.qhyst) s = link_spring(model::QHyst::Spec{kf, f.fy, f.alpha, f.beta});
    B.spring[at(x.frame_spring[k])] = s;
  }
  for (std::size_t k = 0; k < spec.joints.size(); ++k) {
    const BridgeJoint& j = spec.joints[k];
    const int e = static_cast<int>(k);
    B.gap[at(e)] = j.gap, B.kc[at(e)] = j.kc, B.e[at(e)] = j.e, B.weight[at(e)] = 0.0;
    if (j.restrainer) {
      model::TensionGap::Spec r = *j.restrainer;
      r.side = 1;
      B.spring[at(x.restrainer[k])] = link_spring(r);
    }
    if (j.bearing) B.spring[at(x.bearing[k])] = {j.bearing->k, j.bearing->fy, j.bearing->alpha};
  }
  for (const auto& [a, side, fill, bear] : {std::tuple{&spec.left, -1, x.left_backfill, x.left_bearing},
                                            std::tuple{&spec.right, 1, x.right_backfill, x.right_bearing}}) {
    if (a->backfill == Backfill::epp) {
      model::CompressionGap::Spec c = a->epp;
      c.side = side;
      B.spring[at(fill)] = link_spring(c);
    } else if (a->backfill == Backfill::hyperbolic) {
      model::HyperbolicGap::Spec h = a->hyperbolic;
      h.side = side;
      B.spring[at(fill)] = link_spring(h);
    }
    if (a->bearing) B.spring[at(bear)] = {a->bearing->k, a->bearing->fy, a->bearing->alpha};
  }
}

}  // namespace pounding::physics
