#pragma once
// Central difference (velocity Verlet with the velocity predictor) for every system of bodies: the dynamic
// layout of docs/architecture.md Part 2 (§2.3.1 pool, §2.3.3 the step, §2.3.5 inner loops, §2.4.5 guards). The
// SDOF pair keeps its own kernel (central_difference.hpp) as the fast path (revision of D3); this stepper is the
// same physics for any topology, and tests/physics/test_system_kernel.cpp runs the pair through both.
//
// Pool: one allocation per run, rows [field][index][lane] of `tile` lanes (a multiple of simd::W), index = DOF,
// spring or element. Lanes run in SIMD chunks of W lanes with the whole time loop inside the chunk loop, as the
// pair does; a chunk's W-lane column is copied into contiguous chunk rows for its run. Every sum over DOFs, springs or elements is
// left-folded in index order with the first term assigned, and each contraction that decides bits is pinned
// with lane::fma, so a lane's results depend only on its own inputs (not on its chunk neighbours, the tile width
// or the lane order).
//
// One step (the order of §2.3.3; the loops are fused where the order of the sums allows):
//  1. per DOF: vh = v + hh a, du = h vh, u <- u + du, vp = vh + hh a (vo = v kept only for the energy terms)
//  2. stereomechanical (one point-point element): the exchange at the located closing instant
//  3. per spring: increment dd = du_j (ground: no subtraction) or du_j - du_i, deformation d = u_j or u_j - u_i,
//     f = the model's step (model/hysteresis/registry.hpp; the rate is vp_j - vp_i), t = f, or
//     fma(cs, vp_j - vp_i, f) with a storey dashpot;
//     the |d| and |f| observers
//  5. per group (its law chosen once per run): per element delta = x_L - x_R - gap; the law only where some
//     lane of the chunk touches (else F = 0 exactly): Hertzdamp latch at the interpolated closing instant,
//     force, stability guard k_lin h^2 / meff > 4; contact bookkeeping; the closing observer
//  4, 6, 7. per DOF: q = t_below (assigned), q -= t_above..., q = fma(c, vp - vp_ref, q) (a body with classical
//     modal damping instead q = fma(C_jk, vp_k, q) over its DOFs k in order: the dense row), then the element forces
//     in element order (q_L += F, q_R -= F, interpolated sides N1 F, N2 F); na = -ag1 - q im, nv = vh + hh na;
//     the |a + ag| observer
//  8. energy (compile time): input, viscous (floor then storey dashpots), hysteretic
//  9. divergence guard over bodies (sum of each body's max |u|, with the |u| observer), freeze of bad lanes
// Observers updated before the freeze differ from the pair's order only in lanes that the freeze marks bad, which
// report NaN. The SDOF pair through this stepper gives the pair kernel's bits (test_system_kernel).
// Shear sticks (Layout::stick) take the stick path instead: step 5 first, then one walk per body (stick_walk) for steps
// 3, 4, 6, 7, the guard's sums and the next step's step 1, with the same operations in the same order as here;
// test_system_stick holds it to the generic path's bits.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#include "pounding/contact/laws/stereomechanical.hpp"
#include "pounding/contact/model.hpp"
#include "pounding/contact/stability.hpp"
#include "pounding/kernel/batch.hpp"
#include "pounding/kernel/guard.hpp"
#include "pounding/kernel/observers.hpp"
#include "pounding/model/hysteresis/bilinear_kinematic.hpp"
#include "pounding/model/hysteresis/registry.hpp"

namespace pounding::kernel::sys {

using simd::V;

enum class SideKind : std::uint8_t { point, interpolated, wall };
struct Side {
  SideKind kind = SideKind::point;
  int p = -1, q = -1;
};

// Rows of the pool. DOF: state (U holds the new displacement from step 1 on), constants, step scratch, observers.
enum DofRow : int { U, Vel, A, M, IM, CF, VO, VH, DU, VP, PU, PA, dof_rows };
// Spring: the model's rows (model::SpringRows: K, AK, QY, KP, ZA .. ZS, Z in slot order, spring_slot_row; its header
// says what each holds), storey dashpot, force, step scratch T (force + dashpot), observers (peak |d|, peak |f|).
enum SpringRow : int { K, AK, QY, KP, CS, FS, T, PD, PF, ZA, ZB, ZG, ZM, ZE, ZS, Z, spring_rows };
constexpr int spring_slot_row(int k) { return k < 4 ? K + k : ZA + (k - 4); }
static_assert(spring_slot_row(model::spring_slots - 1) == Z && Z + 1 == spring_rows);
// Element: constants (N1/N2 of interpolated sides; p = -1: a column's ground end, x = N2 u_q), state, observers.
enum ElemRow : int {
  GAP, KC, CD, E, MEFF, H2M, N1L, N2L, N1R, N2R, F, IV0, DPREV,
  PCLOSE, TPCLOSE, TFIRST, NIMP, NCLAMP, PFORCE, PPEN, WC, TCON, DIMP, NOUT, elem_rows
};
enum LaneRow : int { BAD, EIN, EVIS, EHYS, lane_rows };

// One DOF of the stick walk: its index, its spring below, their offsets in the chunk (doubles from Chunk::pd, ::ps),
// the range of its element contributions (Layout::walk_f, walk_neg), its body and place in it, the storey dashpot.
struct StickNode {
  int dof = 0, spring = 0, d_off = 0, s_off = 0, c0 = 0, c1 = 0, body = 0;
  bool first = false, top = false, dashpot = false;
};

// The topology as flat index lists, derived once per run from the System.
struct Layout {
  int ndof = 0, nspring = 0, nelem = 0;
  std::vector<int> si, sj;            // spring ends (si = -1: ground)
  std::vector<char> dashpot;          // storey dashpot on the spring
  std::vector<int> law;               // hysteresis law per spring (model/hysteresis/registry.hpp)
  bool any_smooth = false;            // some spring whose model is not fast_path (model/hysteresis/registry.hpp)
  std::vector<int> link_start, link;  // link springs with j == dof (CSR): their force acts on j as a storey's below
  bool any_link = false;
  // multi-support input (issue 26 §2; more than one channel, else all empty): the channel of each DOF's support, of
  // each spring's and element's two sides (a DOF's body channel, or the wall's), and whether they differ ("cross":
  // the side's kinematics then add the ground motions' difference, total displacements)
  std::vector<int> dof_chan, spring_ci, spring_cj, elem_cl, elem_cr;
  std::vector<char> spring_cross, elem_cross;
  std::vector<int> below;             // spring below each DOF
  std::vector<int> above_start, above;  // springs with i == dof (CSR)
  std::vector<int> ref;               // floor dashpot reference per DOF (-1: ground)
  std::vector<int> refd_start, refd;  // DOFs whose floor dashpot references this DOF (CSR): they take its reaction
  std::vector<int> body_start, body_dofs;  // DOFs per body (CSR), for the guard
  std::vector<Side> left, right;
  // per DOF, in element order, the element contributions to its force: element e and `how` (Contribution)
  std::vector<int> contrib_start, contrib_elem, contrib_how;
  bool any_dashpot = false;
  // classical modal damping (bodies with DampingForm::dense; empty without): per DOF the pool's dense row of C_j0 of
  // its body's matrix (-1: a DOF with a floor dashpot) and its body; ndense = the rows (sum of n_b^2)
  std::vector<int> dense_row, dense_body;
  int ndense = 0;
  // the stick path applies (stick_walk; src/physics/run_system.cpp's stick_layout says when), and its walk meets the
  // springs in index order (else the hysteretic increments wait in the T row for the sum in index order)
  bool stick = false, stick_ordered = false;
  // the stick walk (body by body, bottom up): per DOF its node, and its element forces' offsets and sides
  std::vector<StickNode> walk;
  std::vector<int> walk_f;
  std::vector<char> walk_neg;
  std::vector<int> walk_side;  // per element, its left and right DOF's chunk offset (-1: a wall)
};
// How an element's force enters a DOF's resisting force q (step 6): +F (left point), -F (right point),
// +N F / -N F with N the element's N1L, N2L, N1R or N2R row (interpolated sides, as pinned fmas).
enum Contribution : int { left_point, right_point, left_n1, left_n2, right_n1, right_n2 };

// The Layout's lists as raw pointers, passed by value into the step's phases: locals the compiler keeps in
// registers (the chunk's vector stores may alias any memory, so members read through a reference would be
// reloaded after every store).
struct Topo {
  int ndof, nspring, nelem, nbody;
  const int *si, *sj, *below, *above_start, *above, *ref, *refd_start, *refd, *body_start, *body_dofs, *link_start, *link;
  const char* dashpot;
  const int* law;
  bool any_smooth, any_link;
  const Side *left, *right;
  const int *contrib_start, *contrib_elem, *contrib_how;
  bool any_dashpot, stick_ordered;
  const StickNode* walk;
  const int* walk_f;
  const char* walk_neg;
  const int* walk_side;
  const int *dof_chan, *spring_ci, *spring_cj, *elem_cl, *elem_cr;  // null with one channel
  const char *spring_cross, *elem_cross;
  const int *dense_row, *dense_body;  // null without dense damping
  explicit Topo(const Layout& L)
      : ndof(L.ndof), nspring(L.nspring), nelem(L.nelem), nbody(static_cast<int>(L.body_start.size()) - 1),
        si(L.si.data()), sj(L.sj.data()), below(L.below.data()), above_start(L.above_start.data()),
        above(L.above.data()), ref(L.ref.data()), refd_start(L.refd_start.data()), refd(L.refd.data()),
        body_start(L.body_start.data()), body_dofs(L.body_dofs.data()), link_start(L.link_start.data()), link(L.link.data()),
        dashpot(L.dashpot.data()), law(L.law.data()), any_smooth(L.any_smooth), any_link(L.any_link), left(L.left.data()), right(L.right.data()),
        contrib_start(L.contrib_start.data()), contrib_elem(L.contrib_elem.data()), contrib_how(L.contrib_how.data()),
        any_dashpot(L.any_dashpot), stick_ordered(L.stick_ordered), walk(L.walk.data()),
        walk_f(L.walk_f.data()), walk_neg(L.walk_neg.data()),
        walk_side(L.walk_side.data()), dof_chan(ptr(L.dof_chan)), spring_ci(ptr(L.spring_ci)), spring_cj(ptr(L.spring_cj)),
        elem_cl(ptr(L.elem_cl)), elem_cr(ptr(L.elem_cr)), spring_cross(ptr(L.spring_cross)), elem_cross(ptr(L.elem_cross)),
        dense_row(ptr(L.dense_row)), dense_body(ptr(L.dense_body)) {}
  template <class X> static const X* ptr(const std::vector<X>& v) { return v.empty() ? nullptr : v.data(); }
};

// Where each row lives: rows [field][index] in the order DOF fields, spring fields, element fields, lane fields,
// dense damping coefficients.
struct Rows {
  int ndof = 0, nspring = 0, nelem = 0;
  int spring0 = 0, elem0 = 0, lane0 = 0, dense0 = 0, total = 0;
  explicit Rows(const Layout& L)
      : ndof(L.ndof), nspring(L.nspring), nelem(L.nelem), spring0(dof_rows * L.ndof),
        elem0(spring0 + spring_rows * L.nspring), lane0(elem0 + elem_rows * L.nelem), dense0(lane0 + lane_rows),
        total(dense0 + L.ndense) {}
  POUNDING_INLINE int dof(int f, int j) const { return f * ndof + j; }
  POUNDING_INLINE int spring(int f, int s) const { return spring0 + f * nspring + s; }
  POUNDING_INLINE int elem(int f, int e) const { return elem0 + f * nelem + e; }
  POUNDING_INLINE int lane(int f) const { return lane0 + f; }
};

// One allocation per run, 64-byte aligned: the tile's rows [field][index][lane] of `tile` lanes (filled and
// collected by the driver), then one chunk's W lanes, which the time loop walks, stored [index][field][W]: every
// field of DOF j (spring s, element e) lies at a constant offset from the DOF's base, so an access is one address
// with an immediate offset (with [field][index] rows each access cost four integer instructions, measured to be
// the bottleneck: ~190 instructions per DOF and step). A chunk's column is copied in before its run and back after.
class Pool {
 public:
  Pool(const Layout& L, std::size_t tile) : rows_(L), tile_(tile) {
    const std::size_t n = static_cast<std::size_t>(rows_.total) * (tile_ + simd::W);
    mem_.reset(static_cast<double*>(::operator new[](n * sizeof(double), std::align_val_t{64})));
    for (std::size_t i = 0; i < n; ++i) mem_[i] = 0.0;
  }
  std::size_t tile() const { return tile_; }
  const Rows& rows() const { return rows_; }
  double* dof(int f, int j) const { return row(rows_.dof(f, j)); }
  double* spring(int f, int s) const { return row(rows_.spring(f, s)); }
  double* elem(int f, int e) const { return row(rows_.elem(f, e)); }
  double* lane(int f) const { return row(rows_.lane(f)); }
  double* dense(int r) const { return row(rows_.dense0 + r); }
  double* chunk() const { return mem_.get() + static_cast<std::size_t>(rows_.total) * tile_; }
  // the W lanes from `base` into the chunk, and back
  void gather(int base) const { copy(base, true); }
  void scatter(int base) const { copy(base, false); }

 private:
  struct Free {
    void operator()(double* p) const { ::operator delete[](p, std::align_val_t{64}); }
  };
  double* row(int r) const { return mem_.get() + static_cast<std::size_t>(r) * tile_; }
  void copy(int base, bool in) const {
    auto move = [&](int r, int slot) {
      double* c = chunk() + static_cast<std::ptrdiff_t>(slot) * simd::W;
      for (int k = 0; k < simd::W; ++k) (in ? c[k] : row(r)[base + k]) = in ? row(r)[base + k] : c[k];
    };
    const Rows& R = rows_;
    for (int f = 0; f < dof_rows; ++f)
      for (int j = 0; j < R.ndof; ++j) move(R.dof(f, j), j * dof_rows + f);
    for (int f = 0; f < spring_rows; ++f)
      for (int s = 0; s < R.nspring; ++s) move(R.spring(f, s), R.spring0 + s * spring_rows + f);
    for (int f = 0; f < elem_rows; ++f)
      for (int e = 0; e < R.nelem; ++e) move(R.elem(f, e), R.elem0 + e * elem_rows + f);
    for (int f = 0; f < lane_rows; ++f) move(R.lane(f), R.lane0 + f);
    for (int r = R.dense0; r < R.total; ++r) move(r, r);
  }
  Rows rows_;
  std::size_t tile_;
  std::unique_ptr<double[], Free> mem_;
};

// The chunk: W lanes per value, [index][field] (see Pool), base pointers per kind held by value.
struct Chunk {
  double *pd, *ps, *pe, *pl, *pn;
  Chunk(double* p, const Rows& R)
      : pd(p), ps(p + static_cast<std::ptrdiff_t>(R.spring0) * simd::W),
        pe(p + static_cast<std::ptrdiff_t>(R.elem0) * simd::W), pl(p + static_cast<std::ptrdiff_t>(R.lane0) * simd::W),
        pn(p + static_cast<std::ptrdiff_t>(R.dense0) * simd::W) {}
  POUNDING_INLINE static V ld(const double* q) { return V(q, simd::stdx::vector_aligned); }
  POUNDING_INLINE static void st(const V& v, double* q) { v.copy_to(q, simd::stdx::vector_aligned); }
  POUNDING_INLINE static std::ptrdiff_t at(int i, int rows, int f) {
    return (static_cast<std::ptrdiff_t>(i) * rows + f) * simd::W;
  }
  POUNDING_INLINE V dof(int f, int j) const { return ld(pd + at(j, dof_rows, f)); }
  POUNDING_INLINE void dof(int f, int j, const V& v) const { st(v, pd + at(j, dof_rows, f)); }
  POUNDING_INLINE V spr(int f, int s) const { return ld(ps + at(s, spring_rows, f)); }
  POUNDING_INLINE void spr(int f, int s, const V& v) const { st(v, ps + at(s, spring_rows, f)); }
  POUNDING_INLINE V elm(int f, int e) const { return ld(pe + at(e, elem_rows, f)); }
  POUNDING_INLINE void elm(int f, int e, const V& v) const { st(v, pe + at(e, elem_rows, f)); }
  POUNDING_INLINE V lan(int f) const { return ld(pl + static_cast<std::ptrdiff_t>(f) * simd::W); }
  POUNDING_INLINE void lan(int f, const V& v) const { st(v, pl + static_cast<std::ptrdiff_t>(f) * simd::W); }
  POUNDING_INLINE V den(int r) const { return ld(pn + static_cast<std::ptrdiff_t>(r) * simd::W); }
};

// What one step needs besides the pool.
struct StepCtx {
  double h, hh, ag0, ag1;
  V t, vh;
  V rate;  // the divergence guard's rate measure of this step
  double lim;
  bool any_bad;
  bool* force_prev;  // per element: some lane of the chunk touched in the previous step (bool: no char aliasing)
  // multi-support: per channel c at this step, gch[6 c + k] = ag0, ag1, vg0, vg1, ug0, ug1 (null with one channel)
  double* gch = nullptr;
  bool stick = false;    // the stick path's step (elements read their sides through Layout::walk_side, rel)
  bool advance = false;  // the stick path: the walk stores the next step's predicted u (not in the last step)
};
// The ground motions' difference between the two sides of a cross-channel spring or element this step: the
// displacement at n+1 (gu1), its increment (gdu), the velocity at n+1 (gv1) and at n (gv0); side `b` minus side `a`.
struct GroundOffset { double u1, du, v1, v0; };
POUNDING_INLINE GroundOffset ground_offset(const double* g, int a, int b) {
  const double* x = g + 6 * a;
  const double* y = g + 6 * b;
  return {y[5] - x[5], (y[5] - y[4]) - (x[5] - x[4]), y[3] - x[3], y[2] - x[2]};
}

// The value itself, opaque to the optimiser: a product passed through it is never contracted into an FMA with a later
// sum. GCC fuses a * b into its adds when every use of the product is an add; the stick path recomputes values that
// the generic path stores, and pins the products the generic code keeps unfused. No instruction is emitted.
POUNDING_INLINE V opaque(const V& x) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  if constexpr (sizeof(V) >= 16) {
    using Raw = double __attribute__((vector_size(sizeof(V))));
    Raw r;
    x.copy_to(reinterpret_cast<double*>(&r), simd::stdx::element_aligned);
    asm("" : "+v"(r));
    return V(reinterpret_cast<const double*>(&r), simd::stdx::element_aligned);
  }
#endif
  return x;
}

// a b + c as predict() gets it: one FMA where the target has one (GCC contracts predict's sums), else unfused.
POUNDING_INLINE V contracted(const V& a, const V& b, const V& c) {
#if defined(__FMA__) || defined(__AVX512F__)
  return lane::fma(a, b, c);
#else
  return a * b + c;
#endif
}

// The stick path's values of DOF j at n+1 besides the rows: u from U (the predicted u the walk stored in the step
// before, or predict_u's before the first step), vh, du and vp recomputed from Vel and A (step n until the walk
// writes step n+1) by predict()'s operations: vh and vp the FMAs GCC makes of predict's sums (hh a has two adding
// uses), du = h vh unfused (predict stores it), so the bits of predict's rows; v for the energy terms (VO).
struct Kin {
  V u, v, vh, du, vp;
};
POUNDING_INLINE Kin kin(const double* pd, const V& h, const V& hh) {
  auto at = [pd](int f) { return pd + static_cast<std::ptrdiff_t>(f) * simd::W; };
  const V v = Chunk::ld(at(Vel)), a = Chunk::ld(at(A));
  const V vh = contracted(hh, a, v);
  return {Chunk::ld(at(U)), v, vh, opaque(h * vh), contracted(hh, a, vh)};
}
// predict()'s u + h (v + hh a): the displacement of the next step from this step's u, v, a.
POUNDING_INLINE V next_u(const V& u, const V& v, const V& a, const V& h, const V& hh) {
  return u + opaque(h * contracted(hh, a, v));
}

// The displacement-like value of a side from DOF rows `f` (x = N1 u_p + N2 u_q as one pinned contraction).
POUNDING_INLINE V side_value(Chunk c, const Side& s, int f, int e, bool left) {
  switch (s.kind) {
    case SideKind::point: return c.dof(f, s.p);
    case SideKind::interpolated:  // p < 0: the ground end of a column (x = N2 u_q, relative to the support)
      if (s.p < 0) return c.elm(left ? N2L : N2R, e) * c.dof(f, s.q);
      return lane::fma(c.elm(left ? N2L : N2R, e), c.dof(f, s.q), c.elm(left ? N1L : N1R, e) * c.dof(f, s.p));
    case SideKind::wall: break;
  }
  return V(0.0);
}
POUNDING_INLINE V relative(Chunk c, Topo L, int f, int e) {
  const Side &l = L.left[e], &r = L.right[e];
  if (r.kind == SideKind::wall) return side_value(c, l, f, e, true);
  if (l.kind == SideKind::wall) return -side_value(c, r, f, e, false);
  return side_value(c, l, f, e, true) - side_value(c, r, f, e, false);
}
// The stick path's relative value of element e (point and wall sides only) for rows U, Vel, VP, DU: VP and DU
// recomputed (kin), as the generic relative() reads them from predict's rows.
POUNDING_INLINE V rel(Chunk c, Topo L, int f, int e, const StepCtx& s) {
  if (!s.stick) {
    return relative(c, L, f, e);
  } else {
    auto val = [&](int off) {
      if (f != VP && f != DU) return Chunk::ld(c.pd + off + static_cast<std::ptrdiff_t>(f) * simd::W);
      const Kin k = kin(c.pd + off, V(s.h), V(s.hh));
      return f == VP ? k.vp : k.du;
    };
    const int l = L.walk_side[2 * e], r = L.walk_side[2 * e + 1];
    if (r < 0) return val(l);
    if (l < 0) return -val(r);
    return val(l) - val(r);
  }
}

// Step 1 of the stick path before its first step: only u <- u + h vh is stored (the walk recomputes vh, du and vp:
// kin); every later step's u is stored by the walk of the step before (stick_dof).
POUNDING_INLINE void predict_u(Chunk c, Topo L, const StepCtx& s) {
  const V h(s.h), hh(s.hh);
  for (int j = 0; j < L.ndof; ++j) c.dof(U, j, next_u(c.dof(U, j), c.dof(Vel, j), c.dof(A, j), h, hh));
}

// Step 1: the kinematics before the forces at n+1.
template <bool WithEnergy> POUNDING_INLINE void predict(Chunk c, Topo L, const StepCtx& s) {
  const V h(s.h), hh(s.hh);
  for (int j = 0; j < L.ndof; ++j) {
    const V v = c.dof(Vel, j), a = c.dof(A, j);
    const V vh = v + hh * a, du = h * vh;
    // du kept as a row (not recomputed from vh where read): with one use the compiler would fuse u + h vh into
    // an fma, which the pair kernel does not (its du has three uses)
    // v itself stays in Vel until step 7 writes the new one, so the exchange and the latch read it there; the
    // energy terms, after step 7, need the copy
    if constexpr (WithEnergy) c.dof(VO, j, v);
    c.dof(VH, j, vh), c.dof(DU, j, du);
    c.dof(U, j, c.dof(U, j) + du), c.dof(VP, j, vh + hh * a);
  }
}

// A spring's rows in the chunk for its model's step (model/hysteresis/registry.hpp): slot k at spring_slot_row(k).
struct SpringRowsOf {
  Chunk c;
  int s;
  POUNDING_INLINE V get(int k) const { return c.spr(spring_slot_row(k), s); }
  POUNDING_INLINE void set(int k, const V& v) const { c.spr(spring_slot_row(k), s, v); }
  POUNDING_INLINE double& lane(int k, int l) const { return c.ps[Chunk::at(s, spring_rows, spring_slot_row(k)) + l]; }
};

// Step 3: every spring's return map from the increment h vh; the hysteretic increments summed in spring order.
// A spring whose two sides lie on different ground-motion channels (a link between frames on two piers, or to a wall
// on another support) adds the ground motions' difference to its deformation, increment and rate (total
// displacements, issue 26 §2); the supports' work through it joins the input energy.
template <bool WithEnergy> POUNDING_INLINE void springs(Chunk c, Topo L, const double* gch) {
  using H = model::BilinearKinematic;
  V dhys(0.0);
  for (int s = 0; s < L.nspring; ++s) {
    const int i = L.si[s], j = L.sj[s];
    V dd = i < 0 ? c.dof(DU, j) : c.dof(DU, j) - c.dof(DU, i);
    V d = i < 0 ? c.dof(U, j) : c.dof(U, j) - c.dof(U, i);
    V rate = i < 0 ? c.dof(VP, j) : c.dof(VP, j) - c.dof(VP, i);
    const bool cross = L.spring_cross != nullptr && L.spring_cross[s];
    GroundOffset go{0, 0, 0, 0};
    if (cross) {
      go = ground_offset(gch, L.spring_ci[s], L.spring_cj[s]);
      dd = dd + V(go.du), d = d + V(go.u1), rate = rate + V(go.v1);
    }
    const V fo = c.spr(FS, s);
    const SpringRowsOf r{c, s};
    V f, x;
    if (!L.any_smooth)  // every spring fast_path: the straight bilinear loop
      f = H::step<WithEnergy, V>(r, fo, d, dd, rate, x);
    else  // per spring through the list, bilinear first
      model::visit_hysteresis(L.law[s], [&]<class M>() __attribute__((always_inline)) {
        f = M::template step<WithEnergy, V>(r, fo, d, dd, rate, x);
      });
    if constexpr (WithEnergy) dhys = s == 0 ? x : dhys + x;
    if (cross) c.lan(EIN, c.lan(EIN) + contact_work(fo, f, V(go.du)));
    c.spr(FS, s, f);
    V t = f;
    if (L.dashpot[static_cast<std::size_t>(s)]) t = lane::fma(c.spr(CS, s), rate, f);
    c.spr(T, s, t);
    c.spr(PD, s, lane::max(c.spr(PD, s), lane::abs(d)));
    c.spr(PF, s, lane::max(c.spr(PF, s), lane::abs(f)));
  }
  if constexpr (WithEnergy) c.lan(EHYS, c.lan(EHYS) + dhys);
}

// e(v0) at the onsets `on` (KernelSettings::restitution, as the pair kernel's restitution_onset): the latched 1/v0
// times the damping constant of e(v0) (the element's CD is 1), and the onsets outside the curve's valid range
// counted in NOUT.
[[gnu::noinline]] inline void restitution_onset(Chunk c, int e, V& iv0, simd::M on, const VelocityRestitution& r) {
  V out = V(0.0);
  for (int j = 0; j < simd::W; ++j) {
    if (!on[j]) continue;
    const double v0 = 1.0 / iv0[j];
    iv0[j] = iv0[j] * r.damping(r.self, v0);
    if (r.outside(r.self, v0)) out[j] = 1.0;
  }
  c.elm(NOUT, e, c.elm(NOUT, e) + out);
}

// Step 5 for one element of law `Law`: the force at n+1 (muthukumar eq. 10's latch for Hertzdamp), the
// stability guard, and the element's contact bookkeeping.
template <class Law, class Exp>
POUNDING_INLINE void element(Chunk c, Topo L, int e, StepCtx& s, double v0_min, Exp n,
                             const VelocityRestitution* restitution) {
  const V zero(0.0), one(1.0);
  // a cross-channel element forms its kinematics from total displacements: + (ug_L - ug_R)
  const bool cross = L.elem_cross != nullptr && L.elem_cross[e];
  const GroundOffset go = cross ? ground_offset(s.gch, L.elem_cr[e], L.elem_cl[e]) : GroundOffset{0, 0, 0, 0};
  const V cl = cross ? relative(c, L, U, e) + V(go.u1) : rel(c, L, U, e, s), d = cl - c.elm(GAP, e);
  {  // step 10's closing observer (x_L - x_R and when), on this step's unfrozen state: only bad lanes differ, and
     // they report NaN
    const V pc = c.elm(PCLOSE, e);
    const auto up = cl > pc;
    if (!s.stick || lane::any(up)) {  // the stick path skips the stores that would write the rows' own values
      c.elm(PCLOSE, e, lane::select(up, cl, pc));
      c.elm(TPCLOSE, e, lane::select(up, s.t, c.elm(TPCLOSE, e)));
    }
  }
  const simd::M touching = d > zero;
  const bool any_touch = lane::any(touching);
  const V dprev = c.elm(DPREV, e);
  V nF = zero, onset = zero, clamp = zero;
  if constexpr (Law::traits.has_force) {
    if (any_touch) {
      const V dd = cross ? relative(c, L, VP, e) + V(go.v1) : rel(c, L, VP, e, s);
      const simd::M on = (d > zero) && !(dprev > zero);
      onset = lane::select(on, one, zero);
      contact::State<V> st{c.elm(IV0, e)};
      if constexpr (Law::traits.latches_v0) {
        if (lane::any(on)) {  // approach velocity at the interpolated closing instant inside the step
          const V den = d - dprev;
          const V sc = lane::min(lane::max(-dprev / lane::select(den > zero, den, one), zero), one);
          const V ddo = cross ? relative(c, L, Vel, e) + V(go.v0) : rel(c, L, Vel, e, s);  // v at the step's start
          Law::template on_onset<V>(st, on, ddo + sc * (dd - ddo), v0_min);
          if (restitution) [[unlikely]] restitution_onset(c, e, st.iv0, on, *restitution);
          c.elm(IV0, e, st.iv0);
        }
      }
      contact::Shared<V> sh{zero};
      const contact::Kin<V> k{d, dd};
      const contact::Params<V> prm{c.elm(KC, e), c.elm(CD, e)};
      nF = Law::template force<V>(k, prm, st, n, sh, clamp);
      const simd::M bad = contact::unstable<Law>(k, prm, st, n, sh, c.elm(H2M, e), limit2_central_difference);
      if (lane::any(bad)) {
        c.lan(BAD, lane::max(c.lan(BAD), lane::select(bad, one, zero)));
        s.any_bad = true;
      }
    }
  }
  if constexpr (Law::traits.has_force || Law::traits.impulsive) {
    if (any_touch || s.force_prev[e]) {
      c.elm(WC, e, c.elm(WC, e) + contact_work(c.elm(F, e), nF, cross ? relative(c, L, DU, e) + V(go.du) : rel(c, L, DU, e, s)));
      // the supports' work through a cross element (energy input besides -m ag v): its force over the ground
      // motions' difference, by the same rule
      if (cross) c.lan(EIN, c.lan(EIN) + contact_work(c.elm(F, e), nF, V(go.du)));
      c.elm(TCON, e, c.elm(TCON, e) + lane::select(touching, s.vh, zero));
      if constexpr (!Law::traits.impulsive) {
        c.elm(TFIRST, e, lane::min(c.elm(TFIRST, e), lane::select(onset > zero, s.t, V(inf))));
        c.elm(NIMP, e, c.elm(NIMP, e) + onset);
      }
      c.elm(NCLAMP, e, c.elm(NCLAMP, e) + clamp);
      c.elm(PFORCE, e, lane::max(c.elm(PFORCE, e), nF));
      c.elm(PPEN, e, lane::max(c.elm(PPEN, e), d));
    }
    s.force_prev[e] = any_touch;
  }
  c.elm(F, e, nF);
  c.elm(DPREV, e, d);
}

// Step 2: muthukumar eq. 2 at the located closing instant, for the one point-point element e (validation
// refuses the stereomechanical law with more than one element or another side).
POUNDING_INLINE void impulsive(Chunk c, Topo L, int e, const StepCtx& s) {
  const V zero(0.0);
  const int p = L.left[e].p, q = L.right[e].p;
  const V dprev = c.elm(DPREV, e);
  const V vp1 = c.dof(VP, p), vp2 = c.dof(VP, q);
  const V d = c.dof(U, p) - c.dof(U, q) - c.elm(GAP, e), closing = vp1 - vp2;
  const simd::M hit = (d > zero) && ((closing > zero) || !(dprev > zero));
  if (!lane::any(hit)) return;
  const V m1 = c.dof(M, p), m2 = c.dof(M, q);
  const auto x = contact::Stereomechanical::exchange<V>(
      {d, dprev, closing, c.dof(Vel, p), c.dof(Vel, q), vp1, vp2, m1, m2, m1 + m2, c.elm(MEFF, e), c.elm(E, e), s.vh});
  c.dof(U, p, c.dof(U, p) + x.dv1 * x.rest), c.dof(U, q, c.dof(U, q) + x.dv2 * x.rest);
  c.dof(DU, p, c.dof(DU, p) + x.dv1 * x.rest), c.dof(DU, q, c.dof(DU, q) + x.dv2 * x.rest);
  c.dof(VP, p, vp1 + x.dv1), c.dof(VP, q, vp2 + x.dv2);
  c.dof(VH, p, c.dof(VH, p) + x.dv1), c.dof(VH, q, c.dof(VH, q) + x.dv2);
  c.elm(DIMP, e, c.elm(DIMP, e) + x.loss);
  const V onset = lane::select(x.hit, V(1.0), zero);
  c.elm(TFIRST, e, lane::min(c.elm(TFIRST, e), lane::select(onset > zero, s.t, V(inf))));
  c.elm(NIMP, e, c.elm(NIMP, e) + onset);
}

// Steps 4, 6, 7 per DOF: q = t_below (assigned: 0 + (-0) would change a sign of zero), minus the springs above,
// the floor dashpot fma(c, vp - vp_ref, q), the element forces in element order (+F left, -F right, N F at an
// interpolated side); then na = -ag1 - q im, nv = vh + hh na, the |a + ag| observer and the rate measure's sums.
POUNDING_INLINE void forces(Chunk c, Topo L, StepCtx& s) {
  const V hh(s.hh), g1(s.ag1);
  const double ag1 = s.ag1;
  V sv(0.0), sa(0.0);
  for (int j = 0; j < L.ndof; ++j) {
    V q = c.spr(T, L.below[j]);
    if (L.any_link)
      for (int k = L.link_start[j]; k < L.link_start[j + 1]; ++k) q += c.spr(T, L.link[k]);  // links with j here
    for (int k = L.above_start[j]; k < L.above_start[j + 1]; ++k) q -= c.spr(T, L.above[k]);
    const int r = L.ref[j];
    if (L.dense_row != nullptr && L.dense_row[j] >= 0) {
      // classical modal damping: q += sum_k C_jk vp_k over the body's DOFs, left-folded in DOF order (row order)
      const int b = L.dense_body[j];
      int x = L.dense_row[j];
      for (int k = L.body_start[b]; k < L.body_start[b + 1]; ++k, ++x) q = lane::fma(c.den(x), c.dof(VP, L.body_dofs[k]), q);
    } else {
      q = lane::fma(c.dof(CF, j), r < 0 ? c.dof(VP, j) : c.dof(VP, j) - c.dof(VP, r), q);
    }
    // the reaction of the floor dashpots that reference j (an isolated base): -c_d (vp_d - vp_j), so the
    // superstructure's C acts internally (symmetric C, momentum kept; none for fixed bodies: bits unchanged)
    for (int k = L.refd_start[j]; k < L.refd_start[j + 1]; ++k)
      q = lane::fma(-c.dof(CF, L.refd[k]), c.dof(VP, L.refd[k]) - c.dof(VP, j), q);
    for (int k = L.contrib_start[j]; k < L.contrib_start[j + 1]; ++k) {
      const int e = L.contrib_elem[k];
      const V f = c.elm(F, e);
      switch (L.contrib_how[k]) {
        case left_point: q += f; break;
        case right_point: q -= f; break;
        case left_n1: q = lane::fma(c.elm(N1L, e), f, q); break;
        case left_n2: q = lane::fma(c.elm(N2L, e), f, q); break;
        case right_n1: q = lane::fma(-c.elm(N1R, e), f, q); break;
        default: q = lane::fma(-c.elm(N2R, e), f, q); break;
      }
    }
    // multi-support: each DOF with its own support's acceleration (the same value, so the same bits, when equal)
    const double agj = L.dof_chan != nullptr ? s.gch[6 * L.dof_chan[j] + 1] : ag1;
    const V na = -agj - q * c.dof(IM, j), nv = c.dof(VH, j) + hh * na;
    c.dof(A, j, na), c.dof(Vel, j, nv);
    c.dof(PA, j, lane::max(c.dof(PA, j), lane::abs(na + (L.dof_chan != nullptr ? V(agj) : g1))));
    sv = j == 0 ? lane::abs(nv) : sv + lane::abs(nv);
    sa = j == 0 ? lane::abs(na) : sa + lane::abs(na);
  }
  s.rate = sv + sa;
}

// The stick path's spring (its rows at `ps`, index sp) from its lower side lo (or the ground) to its upper side up:
// the bilinear return (springs()' operations on the same values), its |d| and |f| observers; returns t, with the
// storey dashpot.
template <bool WithEnergy>
POUNDING_INLINE V stick_spring(Topo L, double* ps, int sp, bool dashpot, const Kin& up, const Kin& lo, bool ground,
                               V& dhys) {
  using H = model::BilinearKinematic;
  auto at = [ps](int f) { return ps + static_cast<std::ptrdiff_t>(f) * simd::W; };
  const V dd = ground ? up.du : up.du - lo.du, d = ground ? up.u : up.u - lo.u;
  const V fo = Chunk::ld(at(FS));
  const H::Params<V> p{Chunk::ld(at(K)), Chunk::ld(at(AK)), Chunk::ld(at(QY)), Chunk::ld(at(KP))};
  const V f = H::restoring<V>(p, fo, dd, d);
  if constexpr (WithEnergy) {
    const V x = H::dissipated<V>(p, fo, dd, f);
    if (L.stick_ordered)
      dhys = sp == 0 ? x : dhys + x;
    else
      Chunk::st(x, at(T));
  }
  Chunk::st(f, at(FS));
  V t = f;
  if (dashpot) t = lane::fma(Chunk::ld(at(CS)), ground ? up.vp : up.vp - lo.vp, f);
  Chunk::st(lane::max(Chunk::ld(at(PD)), lane::abs(d)), at(PD));
  Chunk::st(lane::max(Chunk::ld(at(PF)), lane::abs(f)), at(PF));
  return t;
}

// A DOF's force of the stick path (its rows at `pd`) from q (the springs' share): the floor dashpot to the ground,
// the point elements in element order (F at pe + off, subtracted on a right side), then forces()' na, nv, |a + ag|
// observer; the guard's |u| observer; the next step's predicted u (predict()'s operations: the guard's freeze zeroes
// it with u, v and a, which gives the same +0); |v| + |a| into `rate`. Returns |u|.
template <bool WithEnergy>
POUNDING_INLINE V stick_dof(Chunk c, Topo L, const StickNode& n, V q, const Kin& k, const StepCtx& s, const V& h,
                            const V& hh, V& rate) {
  double* pd = c.pd + n.d_off;
  auto at = [pd](int f) { return pd + static_cast<std::ptrdiff_t>(f) * simd::W; };
  const double ag1 = s.ag1;
  q = lane::fma(Chunk::ld(at(CF)), k.vp, q);
  for (int x = n.c0; x < n.c1; ++x) {
    const V f = Chunk::ld(c.pe + L.walk_f[x]);
    if (L.walk_neg[x]) q -= f; else q += f;
  }
  const V na = -ag1 - q * Chunk::ld(at(IM)), nv = k.vh + hh * na;
  if constexpr (WithEnergy) Chunk::st(k.v, at(VO));
  Chunk::st(na, at(A)), Chunk::st(nv, at(Vel));
  Chunk::st(lane::max(Chunk::ld(at(PA)), lane::abs(na + V(ag1))), at(PA));
  const V x = lane::abs(k.u);
  Chunk::st(lane::max(Chunk::ld(at(PU)), x), at(PU));
  if (s.advance) Chunk::st(next_u(k.u, nv, na, h, hh), at(U));
  rate = rate + (lane::abs(nv) + lane::abs(na));
  return x;
}

// Steps 3, 4, 6, 7 and the guard's sum for sticks (Layout::stick): one walk per body from the bottom (Layout::walk,
// with each DOF's and spring's row offsets and its element forces' offsets precomputed), each spring evaluated once
// as t_above of its lower DOF and t_below of its upper one (kept in a register), the walk's DOF values recomputed
// (kin). The hysteretic increments are summed in spring order (in the walk when it meets the springs in index order,
// else after it from the T row). The guard reads only whether the rate measure (sum |v| + sum |a| over DOFs in index
// order) is finite: the walk sums the same terms in its own order, and where that sum is below 1e300 in every lane
// the index-order sum (within a relative 2 (ndof + 1) eps of it) is finite too, so the walk's sum stands in for it;
// else (a lane near overflow, inf or NaN: a diverging lane) the index-order sum is formed from the rows.
// Returns the guard's sum over bodies of max |u|.
template <bool WithEnergy> POUNDING_INLINE V stick_walk(Chunk c, Topo L, StepCtx& s) {
  const V h(s.h), hh(s.hh);
  V dhys(0.0), dsum(0.0), mx(0.0), tb(0.0), rate(0.0);
  Kin cur{};
  for (int k = 0; k < L.ndof; ++k) {
    const StickNode& n = L.walk[k];
    if (n.first) {
      cur = kin(c.pd + n.d_off, h, hh);
      tb = stick_spring<WithEnergy>(L, c.ps + n.s_off, n.spring, n.dashpot, cur, cur, true, dhys);
    }
    V q = tb;
    Kin nxt = cur;
    if (!n.top) {
      const StickNode& m = L.walk[k + 1];
      nxt = kin(c.pd + m.d_off, h, hh);
      tb = stick_spring<WithEnergy>(L, c.ps + m.s_off, m.spring, m.dashpot, nxt, cur, false, dhys);
      q -= tb;
    }
    const V x = stick_dof<WithEnergy>(c, L, n, q, cur, s, h, hh, rate);
    mx = n.first ? x : lane::max(mx, x);
    if (n.top) dsum = n.body == 0 ? mx : dsum + mx;
    cur = nxt;
  }
  if constexpr (WithEnergy) {
    if (!L.stick_ordered)
      for (int k = 0; k < L.nspring; ++k) dhys = k == 0 ? c.spr(T, k) : dhys + c.spr(T, k);
    c.lan(EHYS, c.lan(EHYS) + dhys);
  }
  s.rate = rate;
  if (!lane::all(rate < V(1e300))) [[unlikely]] {
    V sv(0.0), sa(0.0);
    for (int j = 0; j < L.ndof; ++j) {
      sv = j == 0 ? lane::abs(c.dof(Vel, j)) : sv + lane::abs(c.dof(Vel, j));
      sa = j == 0 ? lane::abs(c.dof(A, j)) : sa + lane::abs(c.dof(A, j));
    }
    s.rate = sv + sa;
  }
  return dsum;
}

// Step 8: input and viscous energy, the sums over DOFs left-folded by pinned FMAs (for two DOFs exactly the
// pair's fma(m2, in2, m1 in1)); storey dashpots after the floor dashpots.
POUNDING_INLINE void energy(Chunk c, Topo L, const StepCtx& s) {
  const V g0(s.ag0), g1(s.ag1), hh(s.hh);
  V ein(0.0), evis(0.0);
  for (int j = 0; j < L.ndof; ++j) {
    const V vo = c.dof(VO, j), vn = c.dof(Vel, j);
    const V in = L.dof_chan != nullptr ? lane::fma(V(s.gch[6 * L.dof_chan[j] + 1]), vn, V(s.gch[6 * L.dof_chan[j]]) * vo)
                                       : lane::fma(g1, vn, g0 * vo);
    ein = j == 0 ? c.dof(M, j) * in : lane::fma(c.dof(M, j), in, ein);
    const int r = L.ref[static_cast<std::size_t>(j)];
    const V ro = r < 0 ? vo : vo - c.dof(VO, r), rn = r < 0 ? vn : vn - c.dof(Vel, r);
    const V sq = lane::fma(rn, rn, ro * ro);
    evis = j == 0 ? c.dof(CF, j) * sq : lane::fma(c.dof(CF, j), sq, evis);
  }
  if (L.dense_row != nullptr)  // dense damping: vo' C vo + vn' C vn in row order (CF = 0 on those DOFs)
    for (int j = 0; j < L.ndof; ++j) {
      if (L.dense_row[j] < 0) continue;
      const int b = L.dense_body[j];
      int x = L.dense_row[j];
      for (int k = L.body_start[b]; k < L.body_start[b + 1]; ++k, ++x) {
        const int d = L.body_dofs[k];
        evis = lane::fma(c.den(x), lane::fma(c.dof(Vel, j), c.dof(Vel, d), c.dof(VO, j) * c.dof(VO, d)), evis);
      }
    }
  if (L.any_dashpot)
    for (int k = 0; k < L.nspring; ++k) {
      if (!L.dashpot[static_cast<std::size_t>(k)]) continue;
      const int i = L.si[k], j = L.sj[k];
      const V ro = i < 0 ? c.dof(VO, j) : c.dof(VO, j) - c.dof(VO, i);
      const V rn = i < 0 ? c.dof(Vel, j) : c.dof(Vel, j) - c.dof(Vel, i);
      evis = lane::fma(c.spr(CS, k), lane::fma(rn, rn, ro * ro), evis);
    }
  c.lan(EIN, lane::fma(-hh, ein, c.lan(EIN)));
  c.lan(EVIS, lane::fma(hh, evis, c.lan(EVIS)));
}

// The guard's test of the sum of the bodies' largest |u| and of the rate measure; a bad lane is frozen at rest.
POUNDING_INLINE void freeze(Chunk c, Topo L, StepCtx& s, const V& dsum) {
  const V lim(s.lim), zero(0.0);
  if (lane::all(within(dsum, s.rate, lim)) && !s.any_bad) return;
  s.any_bad = true;
  const V bad = lane::max(c.lan(BAD), divergence_code(dsum, s.rate, lim));
  c.lan(BAD, bad);
  const auto frozen = bad > zero;
  for (int j = 0; j < L.ndof; ++j)
    for (int f : {U, Vel, A}) c.dof(f, j, lane::select(frozen, zero, c.dof(f, j)));
  for (int k = 0; k < L.nspring; ++k) c.spr(FS, k, lane::select(frozen, zero, c.spr(FS, k)));
  if (L.any_smooth)
    for (int k = 0; k < L.nspring; ++k) c.spr(Z, k, lane::select(frozen, zero, c.spr(Z, k)));
  for (int e = 0; e < L.nelem; ++e) c.elm(F, e, lane::select(frozen, zero, c.elm(F, e)));
}

// Step 9: the divergence guard (kernel/guard.hpp) over bodies: the sum in body order of each body's largest |u|
// (with step 10's |u| observer), the rate measure from forces() (sum |v| + sum |a|: only its finiteness is read);
// a bad lane is frozen at rest.
POUNDING_INLINE void guard(Chunk c, Topo L, StepCtx& s) {
  V dsum(0.0);
  for (int b = 0; b < L.nbody; ++b) {
    V mx(0.0);
    for (int k = L.body_start[b]; k < L.body_start[b + 1]; ++k) {
      const int j = L.body_dofs[k];
      const V x = lane::abs(c.dof(U, j));
      c.dof(PU, j, lane::max(c.dof(PU, j), x));
      mx = k == L.body_start[b] ? x : lane::max(mx, x);
    }
    dsum = b == 0 ? mx : dsum + mx;
  }
  freeze(c, L, s, dsum);
}

// The elements of one contact group, with the group's law and exponent fixed once per run (a function pointer
// per group: one indirect call per group and step, uniform across lanes).
struct Group {
  std::vector<int> elems;
  double v0_min = 1e-3;
  double n = 1.5;
  bool impulsive = false;
  const VelocityRestitution* restitution = nullptr;  // e(v0) at each onset (Hertzdamp; null: the element's e)
  void (*run)(const Chunk&, const Topo&, const Group&, StepCtx&) = nullptr;
};
template <class Law, class Exp>
void group_elements(const Chunk& chunk, const Topo& topo, const Group& g, StepCtx& s) {
  const Chunk c = chunk;  // locals: by reference through the function pointer, no copy of the call's arguments
  const Topo L = topo;
  Exp n{};
  if constexpr (!std::is_same_v<Exp, contact::Exp15>) n = Exp{g.n};
  for (int e : g.elems) element<Law, Exp>(c, L, e, s, g.v0_min, n, g.restitution);
}

struct Run {
  const Layout* layout;
  Topo topo;
  const std::vector<Group>* groups;
  const double* ag;  // ground acceleration at every step (nsteps + 1)
  long nsteps;
  double h, lim;
  // multi-support: per channel, acceleration, velocity and baseline-corrected displacement at every step (empty: one
  // channel, `ag`)
  std::vector<const double*> ch_ag, ch_vg, ch_ug;
  bool stick = false;  // the stick path (Layout::stick, no impulsive group)
  // Raised: return at the next check (every stop_check steps) and leave the tile unfinished; the caller discards
  // it (physics::run_system throws StopRequested). nullptr: run to the end.
  const std::atomic<bool>* stop = nullptr;
  // A series recorder (physics/system_series.hpp): record(self, chunk, lane in the chunk, step) before the first step
  // (step -1: the initial state) and after every step of the chunk that holds tile lane `record_lane`; that chunk runs
  // the generic path (the stick path's bits equal it: test_system_stick). nullptr: nothing recorded.
  void (*record)(void* self, const Chunk& c, int lane, long stepi) = nullptr;
  void* record_self = nullptr;
  long record_lane = -1;
};

// Steps between two looks at Run::stop: a few ms of a long unit, nothing against a step's cost.
inline constexpr long stop_check = 4096;

template <bool WithEnergy, bool Stick> POUNDING_INLINE void step(Chunk c, const Run& R, long stepi, StepCtx& s) {
  const Topo L = R.topo;
  s.ag0 = R.ag[stepi], s.ag1 = R.ag[stepi + 1];
  s.t = V(static_cast<double>(stepi + 1) * R.h);
  for (std::size_t k = 0; k < R.ch_ag.size(); ++k) {
    double* x = s.gch + 6 * k;
    x[0] = R.ch_ag[k][stepi], x[1] = R.ch_ag[k][stepi + 1], x[2] = R.ch_vg[k][stepi], x[3] = R.ch_vg[k][stepi + 1];
    x[4] = R.ch_ug[k][stepi], x[5] = R.ch_ug[k][stepi + 1];
  }
  if constexpr (Stick) {
    s.advance = stepi + 1 < R.nsteps;
    for (const Group& g : *R.groups) g.run(c, L, g, s);
    const V dsum = stick_walk<WithEnergy>(c, L, s);
    if constexpr (WithEnergy) energy(c, L, s);
    freeze(c, L, s, dsum);
    return;
  }
  predict<WithEnergy>(c, L, s);
  for (const Group& g : *R.groups)
    if (g.impulsive) impulsive(c, L, g.elems.front(), s);
  springs<WithEnergy>(c, L, s.gch);
  for (const Group& g : *R.groups) g.run(c, L, g, s);
  forces(c, L, s);
  if constexpr (WithEnergy) energy(c, L, s);
  guard(c, L, s);
}

// Every chunk of the tile through the whole record (lanes [0, np) of the pool, np a multiple of W).
template <bool WithEnergy> void run_tile(const Pool& pool, int np, const Run& R) {
  const auto force_prev = std::make_unique<bool[]>(static_cast<std::size_t>(R.layout->nelem) + 1);
  std::vector<double> gch(6 * R.ch_ag.size() + 1);
  for (int base = 0; base < np; base += simd::W) {
    pool.gather(base);
    const Chunk c(pool.chunk(), pool.rows());
    StepCtx s{R.h, 0.5 * R.h, 0.0, 0.0, V(0.0), V(R.h), V(0.0), R.lim, lane::any(c.lan(BAD) > V(0.0)), force_prev.get(),
              R.ch_ag.empty() ? nullptr : gch.data()};
    for (int e = 0; e < R.layout->nelem; ++e) force_prev[static_cast<std::size_t>(e)] = lane::any(c.elm(F, e) > V(0.0));
    const bool rec = R.record && R.record_lane >= base && R.record_lane < base + simd::W;
    const bool stick = R.stick && !rec;
    if (stick) {
      s.stick = true;
      if (R.nsteps > 0) predict_u(c, R.topo, s);
    }
    if (rec) R.record(R.record_self, c, static_cast<int>(R.record_lane - base), -1);
    // the same steps in the same order, in blocks between two looks at the stop flag
    for (long k0 = 0; k0 < R.nsteps; k0 += stop_check) {
      if (R.stop && R.stop->load(std::memory_order_relaxed)) return;
      const long k1 = std::min(R.nsteps, k0 + stop_check);
      if (rec)
        for (long k = k0; k < k1; ++k) {
          step<WithEnergy, false>(c, R, k, s);
          R.record(R.record_self, c, static_cast<int>(R.record_lane - base), k);
        }
      else if (stick)
        for (long k = k0; k < k1; ++k) step<WithEnergy, true>(c, R, k, s);
      else
        for (long k = k0; k < k1; ++k) step<WithEnergy, false>(c, R, k, s);
    }
    pool.scatter(base);
  }
}

extern template void run_tile<true>(const Pool&, int, const Run&);
extern template void run_tile<false>(const Pool&, int, const Run&);

// The element function of a group with contact law `law` (Exp15 when n == 1.5 for a law that reads n, else
// RuntimeExponent, as run_batch does): src/physics/instantiate_system_central_difference.cpp.
using GroupFn = void (*)(const Chunk&, const Topo&, const Group&, StepCtx&);
GroupFn group_runner(ContactLaw law, double n);

}  // namespace pounding::kernel::sys
