// Newmark and RK4 on systems (physics/system_lane_stepper.hpp): one lane at a time in doubles.
#include "pounding/physics/system_lane_stepper.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>

#include <fmt/format.h>

#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/contact/stability.hpp"
#include "pounding/kernel/guard.hpp"
#include "pounding/kernel/observers.hpp"
#include "pounding/model/hysteresis/bilinear_kinematic.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/physics/batch.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/run_batch.hpp"

namespace pounding::physics {

namespace {

using BK = model::BilinearKinematic;
using std::size_t;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

// An element side's DOFs and weights: x = sum g_k u_dof[k] (left +, right -), up to two DOFs per side.
struct Incidence {
  std::array<int, 4> dof{};
  std::array<double, 4> g{};
  int count = 0;
  double at(const double* x) const {
    double s = 0.0;
    for (int k = 0; k < count; ++k) s = k == 0 ? g[0] * x[dof[0]] : std::fma(g[k], x[dof[k]], s);
    return s;
  }
};

// The contact law of a group at T = double with its exponent, as function pointers fixed once per run.
struct LawFns {
  double (*force)(double d, double dd, double kc, double cd, double iv0, double n, double& clamp, double& sq);
  contact::Tangent<double> (*tangent)(double d, double dd, double kc, double cd, double iv0, double n);
  double (*latch)(double iv0, bool on, double dd, double v0_min);
  bool (*unstable)(double d, double dd, double kc, double cd, double iv0, double n, double sq, double h2m, double l2);
  double (*stored)(double d, double kc, double n);
  double (*tangent_at)(double pen, double peak_force, double kc, double cd, double n);
  bool has_force;
};
template <class Law> LawFns law_fns() {
  using E = contact::RuntimeExponent;
  LawFns f{};
  f.force = [](double d, double dd, double kc, double cd, double iv0, double n, double& clamp, double& sq) {
    contact::Shared<double> sh{0.0};
    clamp = 0.0;
    const double F = Law::template force<double>({d, dd}, {kc, cd}, {iv0}, E{n}, sh, clamp);
    sq = sh.sq;
    return F;
  };
  f.tangent = [](double d, double dd, double kc, double cd, double iv0, double n) {
    return Law::template tangent<double>({d, dd}, {kc, cd}, {iv0}, E{n});
  };
  f.latch = [](double iv0, bool on, double dd, double v0_min) {
    contact::State<double> s{iv0};
    Law::template on_onset<double>(s, on, dd, v0_min);
    return s.iv0;
  };
  f.unstable = [](double d, double dd, double kc, double cd, double iv0, double n, double sq, double h2m, double l2) {
    const contact::Shared<double> sh{sq};
    return static_cast<bool>(contact::unstable<Law, double>({d, dd}, {kc, cd}, {iv0}, E{n}, sh, h2m, l2));
  };
  f.stored = [](double d, double kc, double n) { return Law::template stored_energy<double>(d, kc, n); };
  f.tangent_at = [](double pen, double peak_force, double kc, double cd, double n) {
    return contact::tangent_at_penetration<Law>(contact::guard_penetration<Law>(pen, peak_force, kc, n), kc, cd, n);
  };
  f.has_force = Law::traits.has_force;
  return f;
}

// A lane's constants.
struct Model {
  int n = 0, ns = 0, ne = 0, band = 0;
  std::vector<double> m, cf;
  std::vector<int> ref;  // floor dashpot reference (-1 ground)
  std::vector<int> si, sj;
  std::vector<BK::Params<double>> sp;
  std::vector<double> cs;  // storey dashpots (0 without)
  struct Dense {
    std::vector<int> dofs;
    std::vector<double> c;  // row-major
  };
  std::vector<Dense> dense;
  std::vector<char> dense_dof;  // DOFs whose damping is a dense row (no floor dashpot)
  std::vector<Incidence> inc;
  std::vector<double> gap, kc, cd, meff, v0_min, nexp;
  std::vector<const LawFns*> law;
  std::vector<int> law_id;
  std::vector<std::array<int, 2>> body_span;  // per body: first and one-past-last index into body_dofs
  std::vector<int> body_dofs;
};

Incidence incidence(const model::ContactElement& ce, double w) {
  Incidence x;
  auto add = [&](const model::Side& s, double sign) {
    if (s.kind == model::SideKind::wall) return;
    if (s.kind == model::SideKind::point) {
      x.dof[x.count] = s.p, x.g[x.count++] = sign;
      return;
    }
    if (s.p >= 0) x.dof[x.count] = s.p, x.g[x.count++] = sign * (1.0 - w);
    x.dof[x.count] = s.q, x.g[x.count++] = sign * w;
  };
  add(ce.left, 1.0), add(ce.right, -1.0);
  return x;
}

void model_structure(Model& M, const SystemBatch& B, size_t l) {
  const model::System& S = *B.system;
  auto at = [&](const std::vector<double>& v, int i) { return v[SystemBatch::at(i, l, B.width)]; };
  M.n = S.ndof(), M.ns = static_cast<int>(S.springs().size()), M.ne = static_cast<int>(S.contacts().size());
  M.dense_dof.assign(static_cast<size_t>(M.n), 0);
  for (int j = 0; j < M.n; ++j) {
    M.m.push_back(at(B.m, j)), M.cf.push_back(at(B.c_floor, j));
    const int r = S.bodies()[static_cast<size_t>(S.body_of(j))].floor_dashpot_ref;
    M.ref.push_back(r == j ? model::ground : r);
  }
  for (int s = 0; s < M.ns; ++s) {
    const model::Spring& sp = S.springs()[static_cast<size_t>(s)];
    const SpringSpec& spec = B.spring[SystemBatch::at(s, l, B.width)];
    Structure st;
    st.k = spec.k, st.fy = spec.fy, st.alpha = spec.alpha;
    M.si.push_back(sp.i), M.sj.push_back(sp.j), M.sp.push_back(BK::params(st));
    M.cs.push_back(B.c_storey.empty() ? 0.0 : at(B.c_storey, s));
  }
  for (size_t b = 0; b < S.bodies().size(); ++b) {
    const model::Body& body = S.bodies()[b];
    M.body_span.push_back({static_cast<int>(M.body_dofs.size()), static_cast<int>(M.body_dofs.size() + body.dofs.size())});
    for (int d : body.dofs) M.body_dofs.push_back(d);
    if (body.damping != model::DampingForm::dense) continue;
    Model::Dense D{body.dofs, {}};
    const int nb = static_cast<int>(body.dofs.size());
    for (int j = 0; j < nb; ++j)
      for (int k = 0; k < nb; ++k) D.c.push_back(at(B.c_dense, B.dense_entry(static_cast<int>(b), j, k)));
    for (int d : body.dofs) M.dense_dof[static_cast<size_t>(d)] = 1;
    M.dense.push_back(std::move(D));
  }
}

double meff_of(const Model& M, const Incidence& x) {
  if (x.count == 2 && std::abs(x.g[0]) == 1.0 && std::abs(x.g[1]) == 1.0) {
    const double a = M.m[static_cast<size_t>(x.dof[0])], b = M.m[static_cast<size_t>(x.dof[1])];
    return a * b / (a + b);
  }
  double flex = 0.0;
  for (int k = 0; k < x.count; ++k) flex += x.g[k] * x.g[k] / M.m[static_cast<size_t>(x.dof[k])];
  return 1.0 / flex;
}

Model make_model(const SystemBatch& B, size_t l, std::span<const ContactModel> models, std::span<const LawFns> fns) {
  Model M;
  model_structure(M, B, l);
  const model::System& S = *B.system;
  for (int e = 0; e < M.ne; ++e) {
    const model::ContactElement& ce = S.contacts()[static_cast<size_t>(e)];
    const size_t g = static_cast<size_t>(ce.group);
    const size_t k = SystemBatch::at(e, l, B.width);
    M.inc.push_back(incidence(ce, B.weight.empty() ? 0.0 : B.weight[k]));
    M.meff.push_back(meff_of(M, M.inc.back()));
    const double kf = contact::stiffness_factor(models[g]);
    M.gap.push_back(B.gap[k]), M.kc.push_back(kf == 1.0 ? B.kc[k] : kf * B.kc[k]);
    M.v0_min.push_back(models[g].v0_min), M.nexp.push_back(models[g].n);
    M.law.push_back(&fns[g]), M.law_id.push_back(static_cast<int>(g));
    contact::visit_law(models[g].law, [&]<class Law>() {
      DampingTable<Law> damping(models[g]);
      M.cd.push_back(damping(B.kc[k], B.e[k], M.meff.back()));
    });
  }
  return M;
}

// Banded symmetric matrix, lower band stored row by row: a(i, j) for i - band <= j <= i.
struct Band {
  int n = 0, b = 0;
  std::vector<double> a;
  void reset(int n_, int b_) { n = n_, b = b_, a.assign(static_cast<size_t>(n) * static_cast<size_t>(b + 1), 0.0); }
  double& at(int i, int j) { return a[static_cast<size_t>(i) * static_cast<size_t>(b + 1) + static_cast<size_t>(i - j)]; }
  void add(int i, int j, double x) {
    if (i < j) std::swap(i, j);
    at(i, j) += x;
  }
  // in place: L (unit lower, below the diagonal) and D (on the diagonal), no pivoting (J is SPD for h > 0)
  void factor() {
    for (int j = 0; j < n; ++j) {
      for (int k = std::max(0, j - b); k < j; ++k) at(j, j) -= at(j, k) * at(j, k) * at(k, k);
      const double d = at(j, j);
      for (int i = j + 1; i <= std::min(n - 1, j + b); ++i) {
        double s = at(i, j);
        for (int k = std::max(0, i - b); k < j; ++k) s -= at(i, k) * at(j, k) * at(k, k);
        at(i, j) = s / d;
      }
    }
  }
  void solve(double* x) {
    for (int i = 0; i < n; ++i)
      for (int k = std::max(0, i - b); k < i; ++k) x[i] -= at(i, k) * x[k];
    for (int i = 0; i < n; ++i) x[i] /= at(i, i);
    for (int i = n - 1; i >= 0; --i)
      for (int k = i + 1; k <= std::min(n - 1, i + b); ++k) x[i] -= at(k, i) * x[k];
  }
};

// A lane's state and observers.
struct State {
  std::vector<double> u, v, a, fs;                   // per DOF; fs per spring (committed)
  std::vector<double> iv0, dprev, F, sq;             // per element
  std::vector<double> pu, pa, pd, pf;                // observers per DOF / spring
  std::vector<double> pclose, tpclose, tfirst, nimp, nclamp, pforce, ppen, wc, tcon;
  double bad = 0.0, ein = 0.0, evis = 0.0, ehys = 0.0;
};

// Damping forces C v into q (added).
void add_damping(const Model& M, const double* v, double* q) {
  for (int j = 0; j < M.n; ++j) {
    if (M.dense_dof[static_cast<size_t>(j)]) continue;
    const int r = M.ref[static_cast<size_t>(j)];
    const double f = M.cf[static_cast<size_t>(j)] * (r < 0 ? v[j] : v[j] - v[r]);
    q[j] += f;
    if (r >= 0) q[r] -= f;
  }
  for (int s = 0; s < M.ns; ++s) {
    const double c = M.cs[static_cast<size_t>(s)];
    if (c == 0.0) continue;
    const int i = M.si[static_cast<size_t>(s)], j = M.sj[static_cast<size_t>(s)];
    const double f = c * (i < 0 ? v[j] : v[j] - v[i]);
    q[j] += f;
    if (i >= 0) q[i] -= f;
  }
  for (const Model::Dense& D : M.dense) {
    const size_t nb = D.dofs.size();
    for (size_t j = 0; j < nb; ++j) {
      double f = 0.0;
      for (size_t k = 0; k < nb; ++k) f = std::fma(D.c[j * nb + k], v[D.dofs[k]], f);
      q[D.dofs[j]] += f;
    }
  }
}

double deformation(const Model& M, int s, const double* u) {
  const int i = M.si[static_cast<size_t>(s)], j = M.sj[static_cast<size_t>(s)];
  return i < 0 ? u[j] : u[j] - u[i];
}

// The springs' forces at u by the return map from the committed state (S.u, S.fs) into f, and their sum into q.
void springs_at(const Model& M, const State& S, const double* u, double* f, double* q) {
  for (int s = 0; s < M.ns; ++s) {
    const double d = deformation(M, s, u), dold = deformation(M, s, S.u.data());
    const double x = BK::restoring(M.sp[static_cast<size_t>(s)], S.fs[static_cast<size_t>(s)], d - dold, d);
    f[s] = x;
    q[M.sj[static_cast<size_t>(s)]] += x;
    if (M.si[static_cast<size_t>(s)] >= 0) q[M.si[static_cast<size_t>(s)]] -= x;
  }
}

void add_element(const Incidence& x, double F, double* q) {
  for (int k = 0; k < x.count; ++k) q[x.dof[k]] = std::fma(x.g[k], F, q[x.dof[k]]);
}

// Scratch per run.
struct Work {
  std::vector<double> q, f, u, v, a, r, du, F, k1u, k1v, k2u, k2v, k3u, k3v, k4u, k4v, iv0, onset, clamp, fmax, uo, vo;
  std::vector<int> mode, latched, active, switched, redone;
  Band J;
  void size(const Model& M) {
    for (auto* x : {&q, &u, &v, &a, &r, &du, &k1u, &k1v, &k2u, &k2v, &k3u, &k3v, &k4u, &k4v, &uo, &vo})
      x->assign(static_cast<size_t>(M.n), 0.0);
    f.assign(static_cast<size_t>(M.ns), 0.0), F.assign(static_cast<size_t>(M.ne), 0.0);
    for (auto* x : {&iv0, &onset, &clamp, &fmax}) x->assign(static_cast<size_t>(M.ne), 0.0);
    for (auto* x : {&mode, &latched, &active, &switched, &redone}) x->assign(static_cast<size_t>(M.ne), 0);
  }
};

// The accelerations at (u, v) with element forces F: a = -ag - M^-1 q.
void accelerations(const Model& M, const State& S, Work& W, const double* u, const double* v, const double* F,
                   double ag, double* a) {
  std::fill(W.q.begin(), W.q.end(), 0.0);
  springs_at(M, S, u, W.f.data(), W.q.data());
  add_damping(M, v, W.q.data());
  for (int e = 0; e < M.ne; ++e) add_element(M.inc[static_cast<size_t>(e)], F[e], W.q.data());
  for (int j = 0; j < M.n; ++j) a[j] = -ag - W.q[static_cast<size_t>(j)] / M.m[static_cast<size_t>(j)];
}


// What a step needs besides the lane.
struct Ctx {
  double h, lim, tol;
  int maxit;
  bool energy;
  Stepper stepper;
};

// The lane at rest in (u0, v0): the springs' initial forces, the elements' latch, force and observers, the
// accelerations from the forces at rest.
void init_state(const Model& M, const SystemBatch& B, size_t l, double ag0, State& S, Work& W) {
  auto at = [&](const std::vector<double>& v, int i) { return v[SystemBatch::at(i, l, B.width)]; };
  const size_t n = static_cast<size_t>(M.n), ns = static_cast<size_t>(M.ns), ne = static_cast<size_t>(M.ne);
  S.u.resize(n), S.v.resize(n), S.a.assign(n, 0.0), S.pu.resize(n), S.pa.resize(n);
  for (int j = 0; j < M.n; ++j) S.u[static_cast<size_t>(j)] = at(B.u0, j), S.v[static_cast<size_t>(j)] = at(B.v0, j);
  for (int j = 0; j < M.n; ++j) S.pu[static_cast<size_t>(j)] = std::abs(S.u[static_cast<size_t>(j)]);
  S.fs.resize(ns), S.pd.resize(ns), S.pf.resize(ns);
  for (int s = 0; s < M.ns; ++s) {
    const double d0 = deformation(M, s, S.u.data());
    S.fs[static_cast<size_t>(s)] = BK::initial_force(M.sp[static_cast<size_t>(s)], d0);
    S.pd[static_cast<size_t>(s)] = std::abs(d0), S.pf[static_cast<size_t>(s)] = std::abs(S.fs[static_cast<size_t>(s)]);
  }
  for (auto* x : {&S.iv0, &S.dprev, &S.F, &S.sq, &S.pclose, &S.tpclose, &S.tfirst, &S.nimp, &S.nclamp, &S.pforce, &S.ppen,
                  &S.wc, &S.tcon})
    x->assign(ne, 0.0);
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    const double x0 = M.inc[k].at(S.u.data()), d0 = x0 - M.gap[k], dd0 = M.inc[k].at(S.v.data());
    S.iv0[k] = 1.0 / std::max(dd0, M.v0_min[k]), S.dprev[k] = d0;
    S.pclose[k] = x0, S.tfirst[k] = d0 > 0.0 ? 0.0 : inf, S.nimp[k] = d0 > 0.0 ? 1.0 : 0.0, S.ppen[k] = d0;
    double clamp = 0.0, sq = 0.0;
    if (d0 > 0.0 && M.law[k]->has_force)
      S.F[k] = M.law[k]->force(d0, dd0, M.kc[k], M.cd[k], S.iv0[k], M.nexp[k], clamp, sq);
    S.pforce[k] = S.F[k];
  }
  accelerations(M, S, W, S.u.data(), S.v.data(), S.F.data(), ag0, S.a.data());
  for (int j = 0; j < M.n; ++j) S.pa[static_cast<size_t>(j)] = std::abs(S.a[static_cast<size_t>(j)] + ag0);
}

// v' C v (the viscous power), from the damping forces.
double viscous_power(const Model& M, Work& W, const double* v) {
  std::fill(W.q.begin(), W.q.end(), 0.0);
  add_damping(M, v, W.q.data());
  double p = 0.0;
  for (int j = 0; j < M.n; ++j) p = std::fma(v[j], W.q[static_cast<size_t>(j)], p);
  return p;
}

// Energy terms of the step from (S.u, S.v, S.fs, S.F) to (W.u, W.v, W.f, W.F), before the commit.
void step_energy(const Model& M, State& S, Work& W, const Ctx& C, double ag0, double ag1) {
  const double hh = 0.5 * C.h;
  double in = 0.0;
  for (int j = 0; j < M.n; ++j) {
    const size_t k = static_cast<size_t>(j);
    in = std::fma(M.m[k], std::fma(ag1, W.v[k], ag0 * S.v[k]), in);
  }
  S.ein = std::fma(-hh, in, S.ein);
  const double pv = viscous_power(M, W, S.v.data()) + viscous_power(M, W, W.v.data());
  S.evis = std::fma(hh, pv, S.evis);
  for (int s = 0; s < M.ns; ++s) {
    const size_t k = static_cast<size_t>(s);
    const double dd = deformation(M, s, W.u.data()) - deformation(M, s, S.u.data());
    S.ehys += BK::dissipated(M.sp[k], S.fs[k], dd, W.f[k]);
  }
}

// The divergence guard (kernel/guard.hpp) over bodies: the sum of each body's largest |u|, and sum |v| + |a|.
void guard(const Model& M, State& S, double lim) {
  double dsum = 0.0, rate = 0.0;
  for (const auto& span : M.body_span) {
    double mx = 0.0;
    for (int k = span[0]; k < span[1]; ++k) mx = std::max(mx, std::abs(S.u[static_cast<size_t>(M.body_dofs[static_cast<size_t>(k)])]));
    dsum += mx;
  }
  for (int j = 0; j < M.n; ++j) rate += std::abs(S.v[static_cast<size_t>(j)]) + std::abs(S.a[static_cast<size_t>(j)]);
  S.bad = std::max(S.bad, kernel::divergence_code(dsum, rate, lim));
}

// Commits the step: W.u, W.v (and W.a when the stepper keeps its own accelerations), the elements' W.F, W.onset,
// W.clamp, W.fmax (largest force met inside the step); the observers, the energy terms and the guard.
void commit(const Model& M, State& S, Work& W, const Ctx& C, double t, double ag0, double ag1, bool own_a) {
  std::fill(W.q.begin(), W.q.end(), 0.0);
  springs_at(M, S, W.u.data(), W.f.data(), W.q.data());
  if (C.energy) step_energy(M, S, W, C, ag0, ag1);
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    const double x = M.inc[k].at(W.u.data()), d = x - M.gap[k];
    if (W.F[k] != 0.0 || S.F[k] != 0.0) S.wc[k] += kernel::contact_work(S.F[k], W.F[k], x - M.inc[k].at(S.u.data()));
    if (x > S.pclose[k]) S.pclose[k] = x, S.tpclose[k] = t;
    if (d > 0.0) S.tcon[k] += C.h;
    if (W.onset[k] > 0.0) S.tfirst[k] = std::min(S.tfirst[k], t), S.nimp[k] += 1.0;
    S.nclamp[k] += W.clamp[k];
    S.pforce[k] = std::max({S.pforce[k], W.F[k], W.fmax[k]}), S.ppen[k] = std::max(S.ppen[k], d);
    S.F[k] = W.F[k], S.dprev[k] = d;
  }
  S.u = W.u, S.v = W.v, S.fs = W.f;
  if (own_a)
    S.a = W.a;
  else
    accelerations(M, S, W, S.u.data(), S.v.data(), S.F.data(), ag1, S.a.data());
  for (int j = 0; j < M.n; ++j) {
    const size_t k = static_cast<size_t>(j);
    S.pu[k] = std::max(S.pu[k], std::abs(S.u[k])), S.pa[k] = std::max(S.pa[k], std::abs(S.a[k] + ag1));
  }
  for (int s = 0; s < M.ns; ++s) {
    const size_t k = static_cast<size_t>(s);
    S.pd[k] = std::max(S.pd[k], std::abs(deformation(M, s, S.u.data()))), S.pf[k] = std::max(S.pf[k], std::abs(S.fs[k]));
  }
  guard(M, S, C.lim);
}

// RK4: the accelerations at a stage (u, v) with the elements in their modes (0 inactive; 2 active, latching v0 at
// the first stage in contact when the step started out of contact).
void rk4_deriv(const Model& M, const State& S, Work& W, const double* u, const double* v, double ag, double* a) {
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    W.F[k] = 0.0;
    if (W.mode[k] == 0 || !M.law[k]->has_force) continue;
    const double d = M.inc[k].at(u) - M.gap[k], dd = M.inc[k].at(v);
    if (!W.latched[k] && !(S.dprev[k] > 0.0) && d > 0.0)
      W.iv0[k] = M.law[k]->latch(W.iv0[k], true, dd, M.v0_min[k]), W.latched[k] = 1;
    double clamp = 0.0, sq = 0.0;
    W.F[k] = M.law[k]->force(d, dd, M.kc[k], M.cd[k], W.iv0[k], M.nexp[k], clamp, sq);
    W.fmax[k] = std::max(W.fmax[k], W.F[k]);
  }
  accelerations(M, S, W, u, v, W.F.data(), ag, a);
}

// One classical RK4 step of length h from the committed state into W.u, W.v.
void rk4_take(const Model& M, const State& S, Work& W, double h, double agA, double agB) {
  const double agM = 0.5 * (agA + agB);
  const size_t n = static_cast<size_t>(M.n);
  for (int e = 0; e < M.ne; ++e) W.latched[static_cast<size_t>(e)] = 0, W.iv0[static_cast<size_t>(e)] = S.iv0[static_cast<size_t>(e)];
  std::fill(W.fmax.begin(), W.fmax.end(), 0.0);
  rk4_deriv(M, S, W, S.u.data(), S.v.data(), agA, W.k1v.data());
  for (size_t j = 0; j < n; ++j) W.k1u[j] = S.v[j], W.r[j] = S.u[j] + 0.5 * h * W.k1u[j], W.du[j] = S.v[j] + 0.5 * h * W.k1v[j];
  rk4_deriv(M, S, W, W.r.data(), W.du.data(), agM, W.k2v.data());
  for (size_t j = 0; j < n; ++j) W.k2u[j] = W.du[j];
  for (size_t j = 0; j < n; ++j) W.r[j] = S.u[j] + 0.5 * h * W.k2u[j], W.du[j] = S.v[j] + 0.5 * h * W.k2v[j];
  rk4_deriv(M, S, W, W.r.data(), W.du.data(), agM, W.k3v.data());
  for (size_t j = 0; j < n; ++j) W.k3u[j] = W.du[j];
  for (size_t j = 0; j < n; ++j) W.r[j] = S.u[j] + h * W.k3u[j], W.du[j] = S.v[j] + h * W.k3v[j];
  rk4_deriv(M, S, W, W.r.data(), W.du.data(), agB, W.k4v.data());
  for (size_t j = 0; j < n; ++j) W.k4u[j] = W.du[j];
  for (size_t j = 0; j < n; ++j) {
    W.u[j] = S.u[j] + h / 6.0 * (W.k1u[j] + 2.0 * W.k2u[j] + 2.0 * W.k3u[j] + W.k4u[j]);
    W.v[j] = S.v[j] + h / 6.0 * (W.k1v[j] + 2.0 * W.k2v[j] + 2.0 * W.k3v[j] + W.k4v[j]);
  }
}

// RK4 step of one lane: taken with the elements in contact at the start active, redone while some other element
// ends penetrating (it becomes active, at most 4 passes); then the elements' forces at the end and the commit.
void rk4_step(const Model& M, State& S, Work& W, const Ctx& C, double t, double ag0, double ag1) {
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    W.mode[k] = S.dprev[k] > 0.0 ? 2 : 0, W.redone[k] = 0;
  }
  rk4_take(M, S, W, C.h, ag0, ag1);
  for (int pass = 0; pass < 4; ++pass) {
    bool redo = false;
    for (int e = 0; e < M.ne; ++e) {
      const size_t k = static_cast<size_t>(e);
      if (W.mode[k] != 0 || !M.law[k]->has_force || !(M.inc[k].at(W.u.data()) - M.gap[k] > 0.0)) continue;
      W.mode[k] = 2, W.redone[k] = 1, redo = true;
    }
    if (!redo) break;
    rk4_take(M, S, W, C.h, ag0, ag1);
  }
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    const double d = M.inc[k].at(W.u.data()) - M.gap[k], dd = M.inc[k].at(W.v.data());
    W.onset[k] = ((d > 0.0 || W.redone[k]) && !(S.dprev[k] > 0.0)) ? 1.0 : 0.0;
    W.clamp[k] = 0.0, W.F[k] = 0.0;
    if (!M.law[k]->has_force) continue;
    if (!(S.dprev[k] > 0.0)) S.iv0[k] = W.iv0[k];
    double sq = 0.0;
    W.F[k] = M.law[k]->force(d, dd, M.kc[k], M.cd[k], S.iv0[k], M.nexp[k], W.clamp[k], sq);
    const double h2m = C.h * C.h / M.meff[k];
    if (M.law[k]->unstable(d, dd, M.kc[k], M.cd[k], S.iv0[k], M.nexp[k], sq, h2m, kernel::limit2_rk4)) S.bad = std::max(S.bad, 1.0);
  }
  commit(M, S, W, C, t, ag0, ag1, false);
}

// Newmark: the Newton matrix's linear part c4 M + c2 C.
void newton_linear(const Model& M, Band& J, double c4, double c2) {
  for (int j = 0; j < M.n; ++j) J.add(j, j, c4 * M.m[static_cast<size_t>(j)]);
  auto dashpot = [&](int i, int j, double c) {
    J.add(j, j, c2 * c);
    if (i >= 0) J.add(i, i, c2 * c), J.add(j, i, -c2 * c);
  };
  for (int j = 0; j < M.n; ++j)
    if (!M.dense_dof[static_cast<size_t>(j)]) dashpot(M.ref[static_cast<size_t>(j)], j, M.cf[static_cast<size_t>(j)]);
  for (int s = 0; s < M.ns; ++s)
    if (M.cs[static_cast<size_t>(s)] != 0.0) dashpot(M.si[static_cast<size_t>(s)], M.sj[static_cast<size_t>(s)], M.cs[static_cast<size_t>(s)]);
  for (const Model::Dense& D : M.dense) {
    const size_t nb = D.dofs.size();
    for (size_t j = 0; j < nb; ++j)
      for (size_t k = 0; k < nb; ++k)
        if (D.dofs[j] >= D.dofs[k]) J.add(D.dofs[j], D.dofs[k], c2 * D.c[j * nb + k]);
  }
}

// Newmark: the residual at the iterate W.u into W.r and the Newton matrix into W.J (springs' tangents, the active
// elements' tangents).
void newton_system(const Model& M, const State& S, Work& W, const Ctx& C, double ag1) {
  const double h = C.h, c4 = 4.0 / (h * h), c2 = 2.0 / h;
  const size_t n = static_cast<size_t>(M.n);
  for (size_t j = 0; j < n; ++j) {
    W.v[j] = c2 * (W.u[j] - S.u[j]) - S.v[j];
    W.a[j] = c4 * (W.u[j] - S.u[j]) - 4.0 / h * S.v[j] - S.a[j];
  }
  std::fill(W.q.begin(), W.q.end(), 0.0);
  springs_at(M, S, W.u.data(), W.f.data(), W.q.data());
  add_damping(M, W.v.data(), W.q.data());
  W.J.reset(M.n, M.band);
  newton_linear(M, W.J, c4, c2);
  for (int s = 0; s < M.ns; ++s) {
    const size_t k = static_cast<size_t>(s);
    const double dd = deformation(M, s, W.u.data()) - deformation(M, s, S.u.data());
    const double kt = BK::tangent(M.sp[k], S.fs[k], dd, W.f[k]);
    const int i = M.si[k], j = M.sj[k];
    W.J.add(j, j, kt);
    if (i >= 0) W.J.add(i, i, kt), W.J.add(j, i, -kt);
  }
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    if (!W.active[k] || !M.law[k]->has_force) continue;
    const Incidence& x = M.inc[k];
    const double d = x.at(W.u.data()) - M.gap[k], dd = x.at(W.v.data());
    const double iv0 = M.law[k]->latch(S.iv0[k], !(S.dprev[k] > 0.0), dd, M.v0_min[k]);
    const contact::Tangent<double> tg = M.law[k]->tangent(d, dd, M.kc[k], M.cd[k], iv0, M.nexp[k]);
    add_element(x, tg.F, W.q.data());
    const double kc = tg.dFd + c2 * tg.dFv;
    for (int a = 0; a < x.count; ++a)
      for (int b = 0; b < x.count; ++b)
        if (x.dof[a] >= x.dof[b]) W.J.add(x.dof[a], x.dof[b], x.g[a] * x.g[b] * kc);
  }
  for (size_t j = 0; j < n; ++j) W.r[j] = M.m[j] * (W.a[j] + ag1) + W.q[j];
}

// Newton iterations from the iterate W.u; true when converged (sum |du| <= tol sum |x| + 1e-19).
bool newton(const Model& M, const State& S, Work& W, const Ctx& C, double ag1) {
  for (int it = 0; it < C.maxit; ++it) {
    newton_system(M, S, W, C, ag1);
    W.J.factor();
    W.du = W.r;
    W.J.solve(W.du.data());
    double sd = 0.0, sx = 0.0;
    for (int j = 0; j < M.n; ++j) {
      const size_t k = static_cast<size_t>(j);
      sx += std::abs(W.u[k]), sd += std::abs(W.du[k]);
      W.u[k] -= W.du[k];
    }
    if (!std::isfinite(sd)) return false;
    if (sd <= C.tol * sx + 1e-19) return true;
  }
  return false;
}

// The elements whose converged state contradicts their active flag switch (at most one activation per step per
// element); returns how many switched.
int newmark_switch(const Model& M, const State& S, Work& W, const Ctx& C) {
  const double c2 = 2.0 / C.h;
  int switched = 0;
  for (size_t j = 0; j < static_cast<size_t>(M.n); ++j) W.v[j] = c2 * (W.u[j] - S.u[j]) - S.v[j];
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    if (!M.law[k]->has_force) continue;
    const double d = M.inc[k].at(W.u.data()) - M.gap[k], dd = M.inc[k].at(W.v.data());
    const double iv0 = M.law[k]->latch(S.iv0[k], !(S.dprev[k] > 0.0), dd, M.v0_min[k]);
    double clamp = 0.0, sq = 0.0;
    const int want = M.law[k]->force(d, dd, M.kc[k], M.cd[k], iv0, M.nexp[k], clamp, sq) > 0.0 ? 1 : 0;
    if (want == W.active[k] || (want == 1 && W.switched[k] > 0)) continue;
    W.active[k] = want, ++W.switched[k], ++switched;
  }
  return switched;
}

void newmark_step(const Model& M, State& S, Work& W, const Ctx& C, double t, double ag0, double ag1) {
  const double h = C.h, c4 = 4.0 / (h * h), c2 = 2.0 / h;
  const size_t n = static_cast<size_t>(M.n);
  for (size_t j = 0; j < n; ++j) W.u[j] = S.u[j] + h * S.v[j] + 0.5 * h * h * S.a[j];
  for (int e = 0; e < M.ne; ++e)
    W.active[static_cast<size_t>(e)] = S.dprev[static_cast<size_t>(e)] > 0.0 ? 1 : 0, W.switched[static_cast<size_t>(e)] = 0;
  bool ok = true;
  for (int pass = 0; pass < 4; ++pass) {
    ok = newton(M, S, W, C, ag1);
    if (!ok || newmark_switch(M, S, W, C) == 0) break;
  }
  for (size_t j = 0; j < n; ++j) {
    W.a[j] = std::fma(c4, W.u[j] - S.u[j], -(4.0 / h * S.v[j])) - S.a[j];
    W.v[j] = c2 * (W.u[j] - S.u[j]) - S.v[j];
  }
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    const double d = M.inc[k].at(W.u.data()) - M.gap[k], dd = M.inc[k].at(W.v.data());
    W.onset[k] = (d > 0.0 && !(S.dprev[k] > 0.0)) ? 1.0 : 0.0, W.clamp[k] = 0.0, W.F[k] = 0.0, W.fmax[k] = 0.0;
    if (!M.law[k]->has_force) continue;
    S.iv0[k] = M.law[k]->latch(S.iv0[k], W.onset[k] > 0.0, dd, M.v0_min[k]);
    double sq = 0.0;
    W.F[k] = M.law[k]->force(d, dd, M.kc[k], M.cd[k], S.iv0[k], M.nexp[k], W.clamp[k], sq);
  }
  if (!ok) S.bad = std::max(S.bad, 1.0);
  commit(M, S, W, C, t, ag0, ag1, true);
}

// Lane l's reductions into out; a bad lane reports NaN (counts -1), as the other steppers.
void collect(const Model& M, const State& S, size_t l, const Ctx& C, const KernelSettings& ks,
             std::span<const ContactModel> models, SystemResult& out) {
  const bool bad = S.bad > 0.0;
  out.status[l] = static_cast<std::uint8_t>(S.bad >= 2.0 ? LaneStatus::non_finite : bad ? LaneStatus::diverged : LaneStatus::ok);
  auto val = [&](double x) { return bad ? nan : x; };
  auto at = [&](int k) { return SystemBatch::at(k, l, out.width); };
  double ek = 0.0, es = 0.0, stored = 0.0;
  for (int j = 0; j < M.n; ++j) {
    const size_t k = static_cast<size_t>(j);
    out.peak_u[at(j)] = val(S.pu[k]), out.peak_acc[at(j)] = val(S.pa[k]);
    out.final_u[at(j)] = val(S.u[k]), out.final_v[at(j)] = val(S.v[k]);
    ek += 0.5 * M.m[k] * S.v[k] * S.v[k];
  }
  for (int s = 0; s < M.ns; ++s) {
    const size_t k = static_cast<size_t>(s);
    out.peak_drift[at(s)] = val(S.pd[k]), out.peak_spring_force[at(s)] = val(S.pf[k]);
    es += BK::strain_energy(M.sp[k], deformation(M, s, S.u.data()), S.fs[k]);
  }
  for (int e = 0; e < M.ne; ++e) {
    const size_t k = static_cast<size_t>(e);
    const LawFns& f = *M.law[k];
    const double st = f.stored(std::max(S.dprev[k], 0.0), M.kc[k], M.nexp[k]);
    stored += st;
    out.peak_closing[at(e)] = val(S.pclose[k]), out.t_peak_closing[at(e)] = val(S.tpclose[k]);
    out.t_first_impact[at(e)] = std::isinf(S.tfirst[k]) ? nan : val(S.tfirst[k]);
    out.impact_count[at(e)] = bad ? -1 : static_cast<std::int32_t>(S.nimp[k]);
    out.clamp_count[at(e)] = bad ? -1 : static_cast<std::int32_t>(S.nclamp[k]);
    out.restitution_outside[at(e)] = bad ? -1 : 0;
    out.peak_penetration[at(e)] = val(std::max(S.ppen[k], 0.0)), out.contact_time[at(e)] = val(S.tcon[k]);
    out.contact_energy[at(e)] = val(S.wc[k] - st), out.peak_force[at(e)] = val(S.pforce[k]);
    const ContactModel& cm = models[static_cast<size_t>(M.law_id[k])];
    const double kt = f.tangent_at(out.peak_penetration[at(e)], out.peak_force[at(e)], M.kc[k], M.cd[k], M.nexp[k]);
    out.h_omega_contact[at(e)] = bad ? nan : h_omega(C.h, kt, M.meff[k]);
    if (!bad && out.h_omega_contact[at(e)] > resolution_limit(ks, cm.law)) out.status[l] = static_cast<std::uint8_t>(LaneStatus::coarse);
  }
  if (!ks.energy) return;
  out.e_input[l] = val(S.ein), out.e_viscous[l] = val(S.evis), out.e_hysteretic[l] = val(S.ehys);
  out.e_kinetic[l] = val(ek), out.e_strain[l] = val(es), out.e_contact_stored[l] = val(stored);
}

}  // namespace

int newton_bandwidth(const model::System& S) {
  int b = 0;
  for (const model::Spring& sp : S.springs())
    if (sp.i >= 0) b = std::max(b, std::abs(sp.j - sp.i));
  for (const model::Body& body : S.bodies()) {
    const auto [lo, hi] = std::minmax_element(body.dofs.begin(), body.dofs.end());
    if (body.damping == model::DampingForm::dense || body.floor_dashpot_ref != model::ground) b = std::max(b, *hi - *lo);
  }
  for (const model::ContactElement& ce : S.contacts()) {
    const Incidence x = incidence(ce, 0.5);
    for (int a = 0; a < x.count; ++a)
      for (int c = 0; c < x.count; ++c) b = std::max(b, std::abs(x.dof[a] - x.dof[c]));
  }
  return b;
}

std::vector<Problem> lane_stepper_problems(const SystemBatch& B, std::span<const ContactModel> groups,
                                           const KernelSettings& ks) {
  std::vector<Problem> out;
  const model::System& S = *B.system;
  const std::string st(to_string(ks.stepper));
  const std::string fix = "use --stepper central-difference (or [analysis] stepper = \"central-difference\")";
  for (std::size_t s = 0; s < S.springs().size(); ++s) {
    const model::Spring& sp = S.springs()[s];
    if (model::runs_on_lane_stepper(sp.law)) continue;
    const std::string_view law = model::is_law(sp.law) ? model::hysteresis_name(sp.law) : "unknown";
    out.push_back({fmt::format("the {} stepper runs systems of bilinear springs (storeys, linear and lead-rubber "
                               "bearings), and {}'s {} spring has the {} law", st,
                               S.bodies()[static_cast<size_t>(sp.body)].label,
                               sp.role == model::SpringRole::storey ? fmt::format("storey {}", sp.storey)
                                   : sp.role == model::SpringRole::isolator ? std::string("isolator") : std::string("link"), law),
                   "--stepper / [analysis] stepper", fix});
    break;
  }
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (contact::traits(groups[g].law).impulsive)
      out.push_back({fmt::format("the {} stepper runs force contact laws on systems, and group '{}' has {}", st,
                                 S.groups()[g].name, to_string(groups[g].law)),
                     "contact law", "use a force law (hertzdamp, kelvin, ...) or --stepper central-difference"});
  if (S.channels() > 1)
    out.push_back({fmt::format("the {} stepper runs one ground-motion channel, and the system has {}", st, S.channels()),
                   "--stepper / [analysis] stepper", fix});
  if (ks.restitution != nullptr)
    out.push_back({fmt::format("a velocity-dependent restitution e(v0) runs with central difference, not {}", st),
                   "restitution", "use a constant e, or " + fix});
  if (ks.locate_contact)
    out.push_back({"located contact onsets run for the SDOF pair only", "locate-contact",
                   "drop --locate-contact for a multi-storey system"});
  if (ks.series)
    out.push_back({"a series recording is written for the SDOF pair only", "--series",
                   "drop --series for a multi-storey system"});
  return out;
}

void run_lane_stepper(const SystemBatch& B, std::span<const ContactModel> groups, const GroundMotion& motion,
                      const KernelSettings& ks, SystemResult& out) {
  out.resize(*B.system, B.width);
  if (B.width == 0) return;
  const Schedule s = make_schedule(motion, ks.substeps);
  std::vector<LawFns> fns;
  for (const ContactModel& cm : groups) fns.push_back(contact::visit_law(cm.law, []<class Law>() { return law_fns<Law>(); }));
  const Ctx C{s.h, ks.displacement_limit, ks.newton_tol, ks.newton_max_iter, ks.energy, ks.stepper};
  const int band = newton_bandwidth(*B.system);
  for (size_t l = 0; l < B.width; ++l) {
    Model M = make_model(B, l, groups, fns);
    M.band = band;
    State S;
    Work W;
    W.size(M);
    init_state(M, B, l, s.ag[0], S, W);
    for (long k = 0; k < s.nsteps && !(S.bad > 0.0); ++k) {
      if (k % 4096 == 0 && ks.stop && ks.stop->load(std::memory_order_relaxed)) throw StopRequested();
      const double t = static_cast<double>(k + 1) * s.h;
      if (ks.stepper == Stepper::newmark)
        newmark_step(M, S, W, C, t, s.ag[static_cast<size_t>(k)], s.ag[static_cast<size_t>(k) + 1]);
      else
        rk4_step(M, S, W, C, t, s.ag[static_cast<size_t>(k)], s.ag[static_cast<size_t>(k) + 1]);
    }
    collect(M, S, l, C, ks, groups, out);
  }
}

}  // namespace pounding::physics
