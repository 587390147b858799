// run_system (physics/system_batch.hpp): the SDOF pair through today's pair kernel (the fast path, bit for bit),
// every other system through the dynamic layout's central difference (physics/steppers/system_central_difference.hpp):
// the topology's index lists, the pool's fill per tile, the run and the reductions into SystemResult.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/contact/resolution.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/physics/run_batch.hpp"
#include "pounding/physics/steppers/system_central_difference.hpp"
#include "pounding/physics/system_lane_stepper.hpp"
#include "pounding/physics/system_series.hpp"
#include "pounding/physics/system_stepper.hpp"

namespace pounding::physics {

namespace {

namespace sys = kernel::sys;
using sys::Chunk;
using sys::Layout;
using sys::Pool;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

sys::Side side_of(const model::Side& s) {
  switch (s.kind) {
    case model::SideKind::point: return {sys::SideKind::point, s.p, -1};
    case model::SideKind::interpolated: return {sys::SideKind::interpolated, s.p, s.q};
    case model::SideKind::wall: break;
  }
  return {sys::SideKind::wall, -1, -1};
}

// Classical modal damping: each DOF's first pool row of its body's C (SystemBatch::c_dense's entry order: body by
// body, C_jk row-major) and its body; -1 for DOFs with a floor dashpot.
void dense_rows(const model::System& S, Layout& L) {
  L.dense_row.assign(static_cast<std::size_t>(L.ndof), -1), L.dense_body.assign(static_cast<std::size_t>(L.ndof), -1);
  for (std::size_t b = 0; b < S.bodies().size(); ++b) {
    const model::Body& body = S.bodies()[b];
    if (body.damping != model::DampingForm::dense) continue;
    const int n = static_cast<int>(body.dofs.size());
    for (int jl = 0; jl < n; ++jl) {
      L.dense_row[static_cast<std::size_t>(body.dofs[static_cast<std::size_t>(jl)])] = L.ndense + jl * n;
      L.dense_body[static_cast<std::size_t>(body.dofs[static_cast<std::size_t>(jl)])] = static_cast<int>(b);
    }
    L.ndense += n * n;
  }
}

// Whether the stick path (system_central_difference.hpp's stick_walk) runs this layout with the generic path's bits:
// bilinear springs only, each DOF with its own spring below (from the ground at a body's bottom, else from the DOF
// below it in the body), a spring above only toward the next DOF of its body, floor dashpots to the ground, point and
// wall sides only, one ground channel, no links, no dense damping rows. Sets Layout::stick_ordered when the walk
// (body by body, bottom up) meets the springs in index order.
bool stick_layout(Layout& L) {
  if (L.any_smooth || L.any_link || !L.dof_chan.empty() || !L.dense_row.empty() || !L.refd.empty() ||
      L.nspring != L.ndof)
    return false;
  for (int r : L.ref)
    if (r >= 0) return false;
  int next = 0;
  L.stick_ordered = true;
  for (std::size_t b = 0; b + 1 < L.body_start.size(); ++b)
    for (int k = L.body_start[b]; k < L.body_start[b + 1]; ++k) {
      const int j = L.body_dofs[static_cast<std::size_t>(k)], s = L.below[static_cast<std::size_t>(j)];
      const int lower = k == L.body_start[b] ? model::ground : L.body_dofs[static_cast<std::size_t>(k - 1)];
      L.stick_ordered = L.stick_ordered && s == next++;
      if (L.si[static_cast<std::size_t>(s)] != lower || L.sj[static_cast<std::size_t>(s)] != j) return false;
      const int na = L.above_start[static_cast<std::size_t>(j) + 1] - L.above_start[static_cast<std::size_t>(j)];
      const bool top = k + 1 == L.body_start[b + 1];
      if (na != (top ? 0 : 1)) return false;
      if (!top && L.above[static_cast<std::size_t>(L.above_start[static_cast<std::size_t>(j)])] !=
                      L.below[static_cast<std::size_t>(L.body_dofs[static_cast<std::size_t>(k + 1)])])
        return false;
    }
  for (int how : L.contrib_how)
    if (how != sys::left_point && how != sys::right_point) return false;
  for (std::size_t e = 0; e < L.left.size(); ++e)
    if (L.left[e].kind == sys::SideKind::interpolated || L.right[e].kind == sys::SideKind::interpolated) return false;
  return true;
}

// The stick walk's nodes (Layout::walk): body by body, bottom up, with the chunk offsets of each DOF's and spring's
// rows and of each element force the DOF takes (system_central_difference.hpp's Chunk layout).
void walk_nodes(Layout& L) {
  const int W = simd::W;
  for (std::size_t b = 0; b + 1 < L.body_start.size(); ++b)
    for (int k = L.body_start[b]; k < L.body_start[b + 1]; ++k) {
      sys::StickNode n;
      n.dof = L.body_dofs[static_cast<std::size_t>(k)], n.spring = L.below[static_cast<std::size_t>(n.dof)];
      n.d_off = n.dof * sys::dof_rows * W, n.s_off = n.spring * sys::spring_rows * W;
      n.body = static_cast<int>(b), n.first = k == L.body_start[b], n.top = k + 1 == L.body_start[b + 1];
      n.dashpot = L.dashpot[static_cast<std::size_t>(n.spring)] != 0;
      n.c0 = static_cast<int>(L.walk_f.size());
      for (int x = L.contrib_start[static_cast<std::size_t>(n.dof)]; x < L.contrib_start[static_cast<std::size_t>(n.dof) + 1]; ++x) {
        L.walk_f.push_back((L.contrib_elem[static_cast<std::size_t>(x)] * sys::elem_rows + sys::F) * W);
        L.walk_neg.push_back(L.contrib_how[static_cast<std::size_t>(x)] == sys::right_point ? 1 : 0);
      }
      n.c1 = static_cast<int>(L.walk_f.size());
      L.walk.push_back(n);
    }
  for (std::size_t e = 0; e < L.left.size(); ++e)
    for (const sys::Side& x : {L.left[e], L.right[e]})
      L.walk_side.push_back(x.kind == sys::SideKind::wall ? -1 : x.p * sys::dof_rows * W);
}

Layout layout_of(const model::System& S) {
  Layout L;
  L.ndof = S.ndof();
  L.nspring = static_cast<int>(S.springs().size());
  L.nelem = static_cast<int>(S.contacts().size());
  for (const model::Spring& s : S.springs()) {
    L.si.push_back(s.i), L.sj.push_back(s.j);
    const bool d = S.bodies()[static_cast<std::size_t>(s.body)].storey_dashpots;
    L.dashpot.push_back(d ? 1 : 0);
    L.any_dashpot = L.any_dashpot || d;
    L.law.push_back(s.law);
    L.any_smooth = L.any_smooth || !model::fast_path(s.law);
  }
  L.above_start.push_back(0);
  L.link_start.push_back(0);
  for (int j = 0; j < L.ndof; ++j) {
    for (std::size_t k = 0; k < S.springs().size(); ++k)
      if (S.springs()[k].role == model::SpringRole::link && S.springs()[k].j == j) L.link.push_back(static_cast<int>(k));
    L.link_start.push_back(static_cast<int>(L.link.size()));
    L.any_link = !L.link.empty();
    L.below.push_back(S.spring_below(j));
    for (int s : S.springs_above(j)) L.above.push_back(s);
    L.above_start.push_back(static_cast<int>(L.above.size()));
    const int r = S.bodies()[static_cast<std::size_t>(S.body_of(j))].floor_dashpot_ref;
    L.ref.push_back(r == j ? model::ground : r);
  }
  L.refd_start.push_back(0);
  for (int j = 0; j < L.ndof; ++j) {
    for (int d = 0; d < L.ndof; ++d)
      if (L.ref[static_cast<std::size_t>(d)] == j) L.refd.push_back(d);
    L.refd_start.push_back(static_cast<int>(L.refd.size()));
  }
  L.body_start.push_back(0);
  for (const model::Body& b : S.bodies()) {
    for (int d : b.dofs) L.body_dofs.push_back(d);
    L.body_start.push_back(static_cast<int>(L.body_dofs.size()));
  }
  if (S.any_dense_damping()) dense_rows(S, L);
  for (const model::ContactElement& e : S.contacts()) L.left.push_back(side_of(e.left)), L.right.push_back(side_of(e.right));
  if (S.channels() > 1) {  // multi-support: every side's channel, and which springs and elements cross channels
    auto chan = [&](int dof) { return S.bodies()[static_cast<std::size_t>(S.body_of(dof))].channel; };
    for (int j = 0; j < L.ndof; ++j) L.dof_chan.push_back(chan(j));
    for (const model::Spring& sp : S.springs()) {
      const int cj = chan(sp.j);
      const int ci = sp.i == model::ground ? (sp.role == model::SpringRole::link ? sp.channel : cj) : chan(sp.i);
      L.spring_ci.push_back(ci), L.spring_cj.push_back(cj), L.spring_cross.push_back(ci != cj ? 1 : 0);
    }
    for (const model::ContactElement& e : S.contacts()) {
      auto side = [&](const model::Side& x) {
        return x.kind == model::SideKind::wall ? x.channel : chan(x.p < 0 ? x.q : x.p);
      };
      const int cl = side(e.left), cr = side(e.right);
      L.elem_cl.push_back(cl), L.elem_cr.push_back(cr), L.elem_cross.push_back(cl != cr ? 1 : 0);
    }
  }
  L.contrib_start.push_back(0);
  for (int j = 0; j < L.ndof; ++j) {
    for (int e : S.elements_at(j)) {  // element order
      const sys::Side &a = L.left[static_cast<std::size_t>(e)], &b = L.right[static_cast<std::size_t>(e)];
      const bool left = a.kind != sys::SideKind::wall && (a.p == j || a.q == j);
      const sys::Side& x = left ? a : b;
      int how = left ? sys::left_point : sys::right_point;
      if (x.kind == sys::SideKind::interpolated)
        how = left ? (x.p == j ? sys::left_n1 : sys::left_n2) : (x.p == j ? sys::right_n1 : sys::right_n2);
      L.contrib_elem.push_back(e), L.contrib_how.push_back(how);
    }
    L.contrib_start.push_back(static_cast<int>(L.contrib_elem.size()));
  }
  L.stick = stick_layout(L);
  if (L.stick) walk_nodes(L);
  return L;
}

// The per-lane inputs of batch lane `l` as scalars (side values over any per-DOF array).
struct LaneView {
  const SystemBatch& B;
  const Layout& L;
  std::size_t l;
  double at(const std::vector<double>& v, int i) const { return v[SystemBatch::at(i, l, B.width)]; }
  double n2(int e) const { return B.weight.empty() ? 0.0 : at(B.weight, e); }
  double side(const sys::Side& s, int e, const std::vector<double>& x) const {
    switch (s.kind) {
      case sys::SideKind::point: return at(x, s.p);
      case sys::SideKind::interpolated:  // the ground end of a column moves with the support: x = N2 u_q
        return s.p < 0 ? n2(e) * at(x, s.q) : std::fma(n2(e), at(x, s.q), (1.0 - n2(e)) * at(x, s.p));
      case sys::SideKind::wall: break;
    }
    return 0.0;
  }
  double relative(int e, const std::vector<double>& x) const {
    const sys::Side &a = L.left[static_cast<std::size_t>(e)], &b = L.right[static_cast<std::size_t>(e)];
    if (b.kind == sys::SideKind::wall) return side(a, e, x);
    if (a.kind == sys::SideKind::wall) return -side(b, e, x);
    return side(a, e, x) - side(b, e, x);
  }
  // A side as the point it is, or reduces to: an interpolated side at an end of its column (N2 = 0: DOF p, N2 = 1:
  // DOF q), so that xi -> 0 / 1 has the floor-to-floor element's meff bit for bit; -1 for a wall (rigid), -2 for a
  // side genuinely between two floors, and for the ground end of a column at N2 = 0 (rigid too: -1).
  int as_point(const sys::Side& s, int e) const {
    if (s.kind == sys::SideKind::point) return s.p;
    if (s.kind == sys::SideKind::wall) return -1;
    if (n2(e) == 0.0) return s.p < 0 ? -1 : s.p;
    return n2(e) == 1.0 ? s.q : -2;
  }
  // 1 / (g' M^-1 g): point-point m_a m_b / (m_a + m_b) verbatim (the pair's), point-wall m_a, interpolated
  // 1 / (N1^2/m_p + N2^2/m_q + 1/m_b) (§2.2.4; the ground end of a column adds nothing)
  double meff(int e) const {
    const sys::Side &a = L.left[static_cast<std::size_t>(e)], &b = L.right[static_cast<std::size_t>(e)];
    const int pa = as_point(a, e), pb = as_point(b, e);
    if (pa >= 0 && pb >= 0) {
      const double ma = at(B.m, pa), mb = at(B.m, pb);
      return ma * mb / (ma + mb);
    }
    if (pa >= 0 && pb == -1) return at(B.m, pa);
    if (pb >= 0 && pa == -1) return at(B.m, pb);
    auto flex = [&](const sys::Side& s) {
      if (s.kind == sys::SideKind::point) return 1.0 / at(B.m, s.p);
      if (s.kind == sys::SideKind::wall) return 0.0;
      const double w = n2(e);
      return s.p < 0 ? w * w / at(B.m, s.q) : (1.0 - w) * (1.0 - w) / at(B.m, s.p) + w * w / at(B.m, s.q);
    };
    return 1.0 / (flex(a) + flex(b));
  }
};

// Per run: each group's model, runner and elements; each element's damping constant per lane (DampingTable: each
// distinct e once per group and call, as run_batch).
struct Plan {
  Layout L;
  std::vector<sys::Group> groups;
  std::vector<ContactModel> models;
  std::vector<int> group_of;
  std::vector<double> cd;  // [element][lane]
  double h = 0.0;
};

Plan make_plan(const SystemBatch& B, std::span<const ContactModel> models, double h,
               const VelocityRestitution* restitution) {
  Plan P;
  P.L = layout_of(*B.system);
  P.h = h;
  P.models.assign(models.begin(), models.end());
  P.groups.resize(models.size());
  for (std::size_t g = 0; g < models.size(); ++g) {
    sys::Group& G = P.groups[g];
    G.v0_min = models[g].v0_min, G.n = models[g].n;
    G.impulsive = contact::traits(models[g].law).impulsive;
    G.restitution = restitution;  // validate: every group hertzdamp when given
    G.run = sys::group_runner(models[g].law, models[g].n);
  }
  const auto& els = B.system->contacts();
  for (std::size_t e = 0; e < els.size(); ++e) {
    P.group_of.push_back(els[e].group);
    P.groups[static_cast<std::size_t>(els[e].group)].elems.push_back(static_cast<int>(e));
  }
  P.cd.assign(els.size() * B.width, 0.0);
  for (std::size_t g = 0; g < models.size(); ++g)
    contact::visit_law(models[g].law, [&]<class Law>() {
      DampingTable<Law> damping(models[g]);
      for (int e : P.groups[g].elems)
        for (std::size_t l = 0; l < B.width; ++l) {
          const LaneView v{B, P.L, l};
          // with e(v0) the damping is set at each onset in the latched 1/v0 (restitution_onset): cd = 1
          P.cd[SystemBatch::at(e, l, B.width)] = restitution ? 1.0 : damping(v.at(B.kc, e), v.at(B.e, e), v.meff(e));
        }
    });
  return P;
}

// Lane i of the pool from batch lane l: DOFs and springs (the initial forces at rest in u0).
void fill_structure(const Pool& T, std::size_t i, const LaneView& v) {
  const SystemBatch& B = v.B;
  const Layout& L = v.L;
  for (int j = 0; j < L.ndof; ++j) {
    T.dof(sys::U, j)[i] = v.at(B.u0, j), T.dof(sys::Vel, j)[i] = v.at(B.v0, j);
    T.dof(sys::M, j)[i] = v.at(B.m, j), T.dof(sys::IM, j)[i] = 1.0 / v.at(B.m, j);
    T.dof(sys::CF, j)[i] = v.at(B.c_floor, j), T.dof(sys::PU, j)[i] = std::abs(v.at(B.u0, j));
  }
  for (int s = 0; s < L.nspring; ++s) {
    const int a = L.si[static_cast<std::size_t>(s)], b = L.sj[static_cast<std::size_t>(s)];
    const SpringSpec& spec = B.spring[SystemBatch::at(s, v.l, B.width)];
    const double d0 = a < 0 ? v.at(B.u0, b) : v.at(B.u0, b) - v.at(B.u0, a);
    model::SpringRows r{};  // Z = 0 unless the model loads it
    const double f0 = model::visit_hysteresis(L.law[static_cast<std::size_t>(s)],
                                              [&]<class H>() { return H::load(spec, d0, r); });
    for (int k = 0; k < model::spring_slots; ++k) T.spring(sys::spring_slot_row(k), s)[i] = r[static_cast<std::size_t>(k)];
    T.spring(sys::CS, s)[i] = B.c_storey.empty() ? 0.0 : v.at(B.c_storey, s);
    T.spring(sys::FS, s)[i] = f0, T.spring(sys::PD, s)[i] = std::abs(d0), T.spring(sys::PF, s)[i] = std::abs(f0);
  }
  for (int f : {sys::BAD, sys::EIN, sys::EVIS, sys::EHYS}) T.lane(f)[i] = 0.0;
  for (int r = 0; r < L.ndense; ++r) T.dense(r)[i] = v.at(B.c_dense, r);
}

// Lane i's elements: constants, the latch and the observers at rest; the initial force from the initial
// penetration (std::pow for the Hertz family, as the pair's fill).
void fill_elements(const Pool& T, std::size_t i, const LaneView& v, const Plan& P) {
  const SystemBatch& B = v.B;
  for (int e = 0; e < P.L.nelem; ++e) {
    const auto row = [&](int f) -> double& { return T.elem(f, e)[i]; };
    const ContactModel& cm = P.models[static_cast<std::size_t>(P.group_of[static_cast<std::size_t>(e)])];
    const double meff = v.meff(e), w = v.n2(e);
    // kc times the damping law's stiffness factor where it is not 1 (three-spring: k_eq = 1.5 k), as run_batch
    const double kf = contact::stiffness_factor(cm);
    row(sys::GAP) = v.at(B.gap, e), row(sys::KC) = kf == 1.0 ? v.at(B.kc, e) : kf * v.at(B.kc, e);
    row(sys::E) = v.at(B.e, e);
    row(sys::CD) = P.cd[SystemBatch::at(e, v.l, B.width)];
    row(sys::MEFF) = meff, row(sys::H2M) = P.h * P.h / meff;
    const bool il = P.L.left[static_cast<std::size_t>(e)].kind == sys::SideKind::interpolated;
    row(il ? sys::N1L : sys::N1R) = 1.0 - w, row(il ? sys::N2L : sys::N2R) = w;
    row(il ? sys::N1R : sys::N1L) = 0.0, row(il ? sys::N2R : sys::N2L) = 0.0;
    const double x0 = v.relative(e, B.u0), d0 = x0 - row(sys::GAP), dd0 = v.relative(e, B.v0);
    row(sys::IV0) = 1.0 / std::max(dd0, cm.v0_min), row(sys::DPREV) = d0;
    row(sys::PCLOSE) = x0, row(sys::TPCLOSE) = 0.0, row(sys::TFIRST) = d0 > 0.0 ? 0.0 : kernel::inf;
    row(sys::NIMP) = d0 > 0.0 ? 1.0 : 0.0, row(sys::NCLAMP) = 0.0, row(sys::PPEN) = d0;
    row(sys::NOUT) = 0.0;
    row(sys::WC) = 0.0, row(sys::TCON) = 0.0, row(sys::DIMP) = 0.0;
    double F = 0.0, clamp = 0.0;
    contact::visit_law(cm.law, [&]<class Law>() {
      contact::Shared<double> sh{0.0};
      if (d0 > 0.0 && Law::traits.has_force)
        F = Law::template force<double>({d0, dd0}, {row(sys::KC), row(sys::CD)}, {row(sys::IV0)},
                                        contact::RuntimeExponent{cm.n}, sh, clamp);
    });
    row(sys::F) = F, row(sys::PFORCE) = F;
  }
}

// Lane i's initial accelerations from the forces at rest (the pair's -ag0 - (c v + fs + F) im).
void fill_accelerations(const Pool& T, std::size_t i, const LaneView& v, const std::vector<double>& ag0) {
  const Layout& L = v.L;
  std::vector<double> t(static_cast<std::size_t>(L.nspring)), q(static_cast<std::size_t>(L.ndof));
  for (int s = 0; s < L.nspring; ++s) {
    const int a = L.si[static_cast<std::size_t>(s)], b = L.sj[static_cast<std::size_t>(s)];
    const double rate = a < 0 ? v.at(v.B.v0, b) : v.at(v.B.v0, b) - v.at(v.B.v0, a);
    const double f = T.spring(sys::FS, s)[i];
    t[static_cast<std::size_t>(s)] = L.dashpot[static_cast<std::size_t>(s)] ? std::fma(T.spring(sys::CS, s)[i], rate, f) : f;
  }
  for (int j = 0; j < L.ndof; ++j) {
    double x = t[static_cast<std::size_t>(L.below[static_cast<std::size_t>(j)])];
    for (int k = L.link_start[static_cast<std::size_t>(j)]; k < L.link_start[static_cast<std::size_t>(j) + 1]; ++k)
      x += t[static_cast<std::size_t>(L.link[static_cast<std::size_t>(k)])];
    for (int k = L.above_start[static_cast<std::size_t>(j)]; k < L.above_start[static_cast<std::size_t>(j) + 1]; ++k)
      x -= t[static_cast<std::size_t>(L.above[static_cast<std::size_t>(k)])];
    const int r = L.ref[static_cast<std::size_t>(j)];
    const double vrel = r < 0 ? v.at(v.B.v0, j) : v.at(v.B.v0, j) - v.at(v.B.v0, r);
    q[static_cast<std::size_t>(j)] = T.dof(sys::CF, j)[i] * vrel + x;
    if (!L.dense_row.empty() && L.dense_row[static_cast<std::size_t>(j)] >= 0) {  // dense damping: C v0 in row order
      const int b = L.dense_body[static_cast<std::size_t>(j)];
      int r0 = L.dense_row[static_cast<std::size_t>(j)];
      double cv = x;
      for (int k = L.body_start[static_cast<std::size_t>(b)]; k < L.body_start[static_cast<std::size_t>(b) + 1]; ++k, ++r0)
        cv = std::fma(T.dense(r0)[i], v.at(v.B.v0, L.body_dofs[static_cast<std::size_t>(k)]), cv);
      q[static_cast<std::size_t>(j)] = cv;
    }
    for (int k = L.refd_start[static_cast<std::size_t>(j)]; k < L.refd_start[static_cast<std::size_t>(j) + 1]; ++k) {
      const int d = L.refd[static_cast<std::size_t>(k)];
      q[static_cast<std::size_t>(j)] -= T.dof(sys::CF, d)[i] * (v.at(v.B.v0, d) - v.at(v.B.v0, j));
    }
  }
  for (int e = 0; e < L.nelem; ++e) {
    const double F = T.elem(sys::F, e)[i];
    for (int sgn : {1, -1}) {
      const sys::Side& s = sgn > 0 ? L.left[static_cast<std::size_t>(e)] : L.right[static_cast<std::size_t>(e)];
      if (s.kind == sys::SideKind::wall) continue;
      const double f1 = s.kind == sys::SideKind::point ? F : T.elem(sgn > 0 ? sys::N1L : sys::N1R, e)[i] * F;
      if (s.p >= 0)  // the ground end of a column: its share goes to the support
        q[static_cast<std::size_t>(s.p)] = sgn > 0 ? q[static_cast<std::size_t>(s.p)] + f1 : q[static_cast<std::size_t>(s.p)] - f1;
      if (s.kind != sys::SideKind::interpolated) continue;
      const double f2 = T.elem(sgn > 0 ? sys::N2L : sys::N2R, e)[i] * F;
      q[static_cast<std::size_t>(s.q)] = sgn > 0 ? q[static_cast<std::size_t>(s.q)] + f2 : q[static_cast<std::size_t>(s.q)] - f2;
    }
  }
  for (int j = 0; j < L.ndof; ++j) {
    const double g = ag0[static_cast<std::size_t>(j)];
    const double a = -g - q[static_cast<std::size_t>(j)] * T.dof(sys::IM, j)[i];
    T.dof(sys::A, j)[i] = a, T.dof(sys::PA, j)[i] = std::abs(a + g);
  }
}

// Lane i's reductions into out at batch lane l; `bad` lanes report NaN (counts -1), as the pair's collect_lane.
void collect_lane(const Pool& T, std::size_t i, const LaneView& v, const Plan& P, const KernelSettings& ks,
                  SystemResult& out) {
  const Layout& L = P.L;
  const std::size_t l = v.l, w = out.width;
  const double badv = T.lane(sys::BAD)[i];
  const bool bad = badv > 0.0;
  out.status[l] = static_cast<std::uint8_t>(badv >= 2.0 ? LaneStatus::non_finite : bad ? LaneStatus::diverged : LaneStatus::ok);
  auto val = [&](double x) { return bad ? nan : x; };
  auto at = [&](int k) { return SystemBatch::at(k, l, w); };
  double ek = 0.0, es = 0.0, stored = 0.0;
  // kinetic energy folded from the last DOF down with pinned contractions: for two DOFs the pair's
  // collect_lane as GCC contracts it, fma(0.5 m1 v1, v1, 0.5 m2 v2 v2)
  for (int j = L.ndof - 1; j >= 0; --j) {
    out.peak_u[at(j)] = val(T.dof(sys::PU, j)[i]), out.peak_acc[at(j)] = val(T.dof(sys::PA, j)[i]);
    const double u = T.dof(sys::U, j)[i], vel = T.dof(sys::Vel, j)[i], m = T.dof(sys::M, j)[i];
    out.final_u[at(j)] = val(u), out.final_v[at(j)] = val(vel);
    ek = j == L.ndof - 1 ? 0.5 * m * vel * vel : std::fma(0.5 * m * vel, vel, ek);
  }
  for (int s = 0; s < L.nspring; ++s) {
    out.peak_drift[at(s)] = val(T.spring(sys::PD, s)[i]), out.peak_spring_force[at(s)] = val(T.spring(sys::PF, s)[i]);
    const int a = L.si[static_cast<std::size_t>(s)], b = L.sj[static_cast<std::size_t>(s)];
    const double d = a < 0 ? T.dof(sys::U, b)[i] : T.dof(sys::U, b)[i] - T.dof(sys::U, a)[i];
    model::SpringRows r;
    for (int k = 0; k < model::spring_slots; ++k) r[static_cast<std::size_t>(k)] = T.spring(sys::spring_slot_row(k), s)[i];
    const double f = T.spring(sys::FS, s)[i];
    const double x = model::visit_hysteresis(L.law[static_cast<std::size_t>(s)],
                                             [&]<class H>() { return H::stored_energy(r, d, f); });
    es = s == 0 ? x : es + x;
  }
  for (int e = 0; e < L.nelem; ++e) {
    const int g = P.group_of[static_cast<std::size_t>(e)];
    const ContactModel& cm = P.models[static_cast<std::size_t>(g)];
    const auto row = [&](int f) { return T.elem(f, e)[i]; };
    out.peak_closing[at(e)] = val(row(sys::PCLOSE)), out.t_peak_closing[at(e)] = val(row(sys::TPCLOSE));
    out.t_first_impact[at(e)] = std::isinf(row(sys::TFIRST)) ? nan : val(row(sys::TFIRST));
    out.impact_count[at(e)] = bad ? -1 : static_cast<std::int32_t>(row(sys::NIMP));
    out.clamp_count[at(e)] = bad ? -1 : static_cast<std::int32_t>(row(sys::NCLAMP));
    out.restitution_outside[at(e)] = bad ? -1 : static_cast<std::int32_t>(row(sys::NOUT));
    out.peak_penetration[at(e)] = val(std::max(row(sys::PPEN), 0.0)), out.contact_time[at(e)] = val(row(sys::TCON));
    contact::visit_law(cm.law, [&]<class Law>() {
      const double dp = std::max(T.elem(sys::DPREV, e)[i], 0.0);
      const double st = Law::template stored_energy<double>(dp, row(sys::KC), cm.n);
      stored = e == 0 ? st : stored + st;
      out.contact_energy[at(e)] = val(row(sys::WC) - st + row(sys::DIMP));
      out.peak_force[at(e)] = Law::traits.impulsive ? nan : val(row(sys::PFORCE));
      const double pen = contact::guard_penetration<Law>(out.peak_penetration[at(e)], out.peak_force[at(e)], row(sys::KC), cm.n);
      const double k_t = contact::tangent_at_penetration<Law>(pen, row(sys::KC), row(sys::CD), cm.n);
      out.h_omega_contact[at(e)] = bad ? nan : h_omega(P.h, k_t, row(sys::MEFF));
      if (!bad && out.h_omega_contact[at(e)] > resolution_limit(ks, cm.law))
        out.status[l] = static_cast<std::uint8_t>(LaneStatus::coarse);
    });
  }
  if (!ks.energy) return;
  out.e_input[l] = val(T.lane(sys::EIN)[i]), out.e_viscous[l] = val(T.lane(sys::EVIS)[i]);
  out.e_hysteretic[l] = val(T.lane(sys::EHYS)[i]), out.e_kinetic[l] = val(ek), out.e_strain[l] = val(es);
  out.e_contact_stored[l] = val(L.nelem > 0 ? stored : 0.0);
}

// A channel's ground velocity and displacement at every step of its schedule: the piecewise-linear acceleration
// integrated exactly (v by the trapezoid, u with h^2 (2 a_n + a_{n+1}) / 6), then baseline-corrected by the
// acceleration a0 + a1 t that brings v and u to zero at the end (the usual correction before a record's displacement
// is used; the bodies themselves are driven by the acceleration as given).
struct GroundHistory { std::vector<double> v, u; };
GroundHistory ground_history(const Schedule& s) {
  const std::size_t n = s.ag.size();
  GroundHistory g{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  const double h = s.h;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    g.v[k + 1] = g.v[k] + 0.5 * h * (s.ag[k] + s.ag[k + 1]);
    g.u[k + 1] = g.u[k] + h * g.v[k] + h * h * (2.0 * s.ag[k] + s.ag[k + 1]) / 6.0;
  }
  const double T = h * static_cast<double>(n - 1), vT = g.v[n - 1], uT = g.u[n - 1];
  if (!(T > 0)) return g;
  const double a0 = -2.0 * vT / T + 6.0 * uT / (T * T), a1 = 6.0 * vT / (T * T) - 12.0 * uT / (T * T * T);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = h * static_cast<double>(k);
    g.v[k] -= a0 * t + a1 * t * t / 2.0;
    g.u[k] -= a0 * t * t / 2.0 + a1 * t * t * t / 6.0;
  }
  return g;
}

// The series recorder's tap (Run::record): one row of the recorded lane per call, step -1 the initial state.
struct SeriesTap {
  SystemSeries* out;
  int ndof, nelem;
  double h;
  std::vector<const double*> ag;  // per DOF: its support's acceleration at every step
  const double* ag1;              // support 1's
  static void record(void* self, const sys::Chunk& c, int i, long stepi) {
    auto* t = static_cast<SeriesTap*>(self);
    const auto k = static_cast<std::size_t>(stepi + 1);
    t->out->t.push_back(static_cast<double>(k) * t->h), t->out->ag.push_back(t->ag1[k]);
    for (int j = 0; j < t->ndof; ++j) {
      const auto J = static_cast<std::size_t>(j);
      t->out->u[J].push_back(c.dof(sys::U, j)[i]);
      t->out->a_abs[J].push_back(c.dof(sys::A, j)[i] + t->ag[J][k]);
    }
    for (int e = 0; e < t->nelem; ++e) t->out->force[static_cast<std::size_t>(e)].push_back(c.elm(sys::F, e)[i]);
  }
};

void run_dynamic(const SystemBatch& B, std::span<const ContactModel> models, std::span<const GroundMotion> motions,
                 const KernelSettings& ks, SystemResult& out, std::size_t tile, bool generic = false,
                 SystemSeries* series = nullptr) {
  out.resize(*B.system, B.width);
  if (B.width == 0) return;
  const Schedule s = make_schedule(motions[0], ks.substeps);
  const Plan P = make_plan(B, models, s.h, ks.restitution);
  const std::size_t tw = tile == 0 ? default_system_tile(B.width) : tile;
  const Pool T(P.L, tw);
  sys::Run R{&P.L, sys::Topo(P.L), &P.groups, s.ag.data(), s.nsteps, s.h, ks.displacement_limit, {}, {}, {}};
  R.stop = ks.stop;
  R.stick = P.L.stick && !generic &&
            std::none_of(P.groups.begin(), P.groups.end(), [](const sys::Group& g) { return g.impulsive; });
  std::vector<Schedule> ch;
  std::vector<GroundHistory> gh;
  std::vector<double> ag0(static_cast<std::size_t>(P.L.ndof), s.ag[0]);
  if (B.system->channels() > 1) {
    for (const GroundMotion& m : motions) ch.push_back(make_schedule(m, ks.substeps)), gh.push_back(ground_history(ch.back()));
    for (std::size_t k = 0; k < ch.size(); ++k)
      R.ch_ag.push_back(ch[k].ag.data()), R.ch_vg.push_back(gh[k].v.data()), R.ch_ug.push_back(gh[k].u.data());
    for (int j = 0; j < P.L.ndof; ++j) ag0[static_cast<std::size_t>(j)] = ch[static_cast<std::size_t>(P.L.dof_chan[static_cast<std::size_t>(j)])].ag[0];
  }
  SeriesTap tap{series, P.L.ndof, P.L.nelem, s.h, {}, s.ag.data()};
  if (series) {
    series->clear();
    series->u.resize(static_cast<std::size_t>(P.L.ndof)), series->a_abs.resize(static_cast<std::size_t>(P.L.ndof));
    series->force.resize(static_cast<std::size_t>(P.L.nelem));
    for (int j = 0; j < P.L.ndof; ++j)
      tap.ag.push_back(ch.empty() ? s.ag.data() : ch[static_cast<std::size_t>(P.L.dof_chan[static_cast<std::size_t>(j)])].ag.data());
    R.record = &SeriesTap::record, R.record_self = &tap;
  }
  for (std::size_t base = 0; base < B.width; base += tw) {
    const std::size_t n = std::min(tw, B.width - base);
    // lanes past n up to the SIMD chunk boundary are copies of the tile's first lane
    const std::size_t np = (n + simd::W - 1) / simd::W * simd::W;
    for (std::size_t i = 0; i < np; ++i) {
      const LaneView v{B, P.L, base + (i < n ? i : 0)};
      fill_structure(T, i, v);
      fill_elements(T, i, v, P);
      fill_accelerations(T, i, v, ag0);
    }
    if (series)
      R.record_lane = series->lane >= base && series->lane < base + n ? static_cast<long>(series->lane - base) : -1;
    if (ks.energy)
      sys::run_tile<true>(T, static_cast<int>(np), R);
    else
      sys::run_tile<false>(T, static_cast<int>(np), R);
    if (ks.stop && ks.stop->load()) throw StopRequested();  // the tile was left unfinished: nothing of it is kept
    for (std::size_t i = 0; i < n; ++i) collect_lane(T, i, LaneView{B, P.L, base + i}, P, ks, out);
  }
}

// Newmark and RK4 run systems one lane at a time (physics/system_lane_stepper.hpp).
bool lane_stepper(const KernelSettings& ks) { return ks.stepper == Stepper::newmark || ks.stepper == Stepper::rk4; }

std::string stepper_name(Stepper s) {
  std::string name;
  kernel::visit_stepper(s, [&]<class S>() { name = std::string(S::name); });
  return name;
}

// Whether a model with roles `r` may stand where a spring of role `role` does; the role as a word.
bool plays(const model::Roles& r, model::SpringRole role) {
  return role == model::SpringRole::storey ? r.storey : role == model::SpringRole::isolator ? r.isolator : r.link;
}
const char* role_word(model::SpringRole role) {
  return role == model::SpringRole::storey ? "storey" : role == model::SpringRole::isolator ? "isolator" : "link";
}

}  // namespace

std::size_t default_system_tile(std::size_t) { return static_cast<std::size_t>(simd::W); }

std::vector<Problem> system_stepper_problems(const SystemBatch& B, std::span<const ContactModel> groups,
                                             const KernelSettings& ks) {
  // physics::validate refuses other steppers, the stereomechanical law with more than one element and a wrong
  // group count; these are what the dynamic layout adds
  if (ks.stepper == Stepper::newmark || ks.stepper == Stepper::rk4) return lane_stepper_problems(B, groups, ks);
  std::vector<Problem> out;
  const model::System& S = *B.system;
  if (ks.stepper != Stepper::central_difference)
    out.push_back({fmt::format("the {} stepper runs the SDOF pair only", stepper_name(ks.stepper)), "stepper",
                   "use central-difference for multi-storey buildings and other systems"});
  if (S.channels() > 1)
    for (std::size_t g = 0; g < groups.size(); ++g)
      if (contact::traits(groups[g].law).impulsive)
        out.push_back({"the stereomechanical exchange is not defined across ground-motion channels",
                       fmt::format("contact law of group '{}'", S.groups()[g].name),
                       "use a law with a force element (hertzdamp, kelvin, ...)"});
  for (std::size_t s = 0; s < S.springs().size(); ++s)
    if (const model::Spring& sp = S.springs()[s]; !model::is_law(sp.law))
      out.push_back({fmt::format("spring {} has hysteresis law {}; the system stepper runs laws 0 to {} "
                                 "(model/hysteresis/registry.hpp)", s, sp.law, static_cast<int>(model::Hystereses::size) - 1),
                     "system springs", "use a registered hysteresis law (model/hysteresis/registry.hpp)"});
    else if (!plays(model::hysteresis_roles[static_cast<std::size_t>(sp.law)], sp.role))
      out.push_back({fmt::format("spring {} is a {} spring of the {} model, which does not play that role", s,
                                 role_word(sp.role), model::hysteresis_name(sp.law)),
                     "system springs", "give the spring a model whose roles include it (model/hysteresis/registry.hpp)"});
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (!contact::traits(groups[g].law).impulsive) continue;
    for (const model::ContactElement& e : S.contacts())
      if (e.left.kind != model::SideKind::point || e.right.kind != model::SideKind::point)
        out.push_back({"the stereomechanical exchange is implemented between two floors (point sides) only",
                       fmt::format("contact law of group '{}' at {}", S.groups()[g].name, e.label),
                       "use a law with a force element (hertzdamp, kelvin, ...)"});
  }
  if (ks.series)
    out.push_back({"a series recording is written for the SDOF pair only", "--series",
                   "drop --series for a multi-storey system"});
  return out;
}

void run_system(const SystemBatch& batch, std::span<const ContactModel> groups, const GroundMotion& motion,
                const KernelSettings& settings, SystemResult& out) {
  if (batch.system->channels() > 1)
    throw InputError(fmt::format("the system has {} ground-motion channels and one record was given", batch.system->channels()),
                     "ground motion", "give one record per support (run_system with one GroundMotion per channel)");
  throw_first(validate(batch, groups, motion, settings));
  if (batch.system->is_sdof_pair()) {
    BatchResult r;
    pounding::run_batch(to_pair_batch(batch), groups[0], motion, settings, r);
    out = from_pair_result(r);
    return;
  }
  throw_first(system_stepper_problems(batch, groups, settings));
  if (lane_stepper(settings)) return run_lane_stepper(batch, groups, motion, settings, out);
  run_dynamic(batch, groups, std::span<const GroundMotion>(&motion, 1), settings, out, 0);
}

std::vector<Problem> channel_problems(const model::System& S, std::span<const GroundMotion> channels) {
  std::vector<Problem> out;
  if (channels.size() != static_cast<std::size_t>(S.channels()))
    out.push_back({fmt::format("{} ground motions for a system of {} channels", channels.size(), S.channels()),
                   "ground motion", "give one record per support channel"});
  for (std::size_t k = 1; k < channels.size(); ++k)
    if (channels[k].dt != channels[0].dt || channels[k].total_duration() != channels[0].total_duration())
      out.push_back({fmt::format("support {}'s record has step {} s and length {} s, support 1's {} s and {} s", k + 1,
                                 channels[k].dt, channels[k].total_duration(), channels[0].dt, channels[0].total_duration()),
                     fmt::format("ground motion of support {}", k + 1),
                     "give every support a record of the same step and length (resample or pad with zeros)"});
  return out;
}

void run_system(const SystemBatch& batch, std::span<const ContactModel> groups, std::span<const GroundMotion> channels,
                const KernelSettings& settings, SystemResult& out) {
  if (batch.system->channels() == 1 && channels.size() == 1) return run_system(batch, groups, channels[0], settings, out);
  throw_first(channel_problems(*batch.system, channels));
  for (const GroundMotion& m : channels) throw_first(validate(batch, groups, m, settings));
  throw_first(system_stepper_problems(batch, groups, settings));
  run_dynamic(batch, groups, channels, settings, out, 0);
}

void run_system_recorded(const SystemBatch& batch, std::span<const ContactModel> groups,
                         std::span<const GroundMotion> channels, const KernelSettings& settings, SystemResult& out,
                         SystemSeries& series) {
  if (batch.system->is_sdof_pair() || lane_stepper(settings) || settings.stepper != Stepper::central_difference)
    throw InputError("a system's series is recorded by the central-difference system stepper", "--series",
                     batch.system->is_sdof_pair() ? "give the pair's SDOF options (no --storeys) for its series"
                                                  : "use --stepper central-difference with --series");
  if (!(series.lane < batch.width)) throw InputError("the series' lane is not in the batch", "--series", "record lane 0");
  throw_first(channel_problems(*batch.system, channels));
  for (const GroundMotion& m : channels) throw_first(validate(batch, groups, m, settings));
  throw_first(system_stepper_problems(batch, groups, settings));
  run_dynamic(batch, groups, channels, settings, out, 0, false, &series);
}

namespace testing {
void run_system_dynamic(const SystemBatch& batch, std::span<const ContactModel> groups, const GroundMotion& motion,
                        const KernelSettings& settings, SystemResult& out, std::size_t tile) {
  throw_first(validate(batch, groups, motion, settings));
  throw_first(system_stepper_problems(batch, groups, settings));
  if (lane_stepper(settings)) return run_lane_stepper(batch, groups, motion, settings, out);
  run_dynamic(batch, groups, std::span<const GroundMotion>(&motion, 1), settings, out, tile);
}
void run_system_generic(const SystemBatch& batch, std::span<const ContactModel> groups, const GroundMotion& motion,
                        const KernelSettings& settings, SystemResult& out) {
  throw_first(validate(batch, groups, motion, settings));
  throw_first(system_stepper_problems(batch, groups, settings));
  run_dynamic(batch, groups, std::span<const GroundMotion>(&motion, 1), settings, out, 0, true);
}
bool stick_path(const model::System& system) { return layout_of(system).stick; }
}  // namespace testing

}  // namespace pounding::physics
