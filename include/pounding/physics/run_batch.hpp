#pragma once
// A batch through the kernel with the law as a type (architecture.md 2.4): tiles of lanes are filled from
// the batch, run by the stepper chosen in the settings and reduced into a BatchResult. No validation here
// (physics/validate.hpp; pounding::run_batch validates and throws InputError). A law outside the registry
// runs with run_batch_t<Law> after including physics/tile_runner_impl.hpp (tests/contact/test_extension_law.cpp);
// a structure model other than model::Registered with run_batch_t<Law, Model> (tests/model/test_extension_model.cpp).
#include <algorithm>
#include <bit>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "pounding/contact/law.hpp"
#include "pounding/core/error.hpp"
#include "pounding/contact/resolution.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/steppers/registry.hpp"
#include "pounding/kernel/tile.hpp"
#include "pounding/physics/tile_runner.hpp"

namespace pounding::physics {

// Ground acceleration at every integration step: linear inside a record step, zero after the record.
struct Schedule {
  std::vector<double> ag;
  long nsteps = 0;
  double h = 0.0;
};
Schedule make_schedule(const GroundMotion& motion, int substeps);

// The law- and model-independent part of lane i's tile entries (masses, damping, initial state, observers at rest).
void fill_lane_common(kernel::Tile& T, int i, const PairParams& p, double v0_min);
// Nigam-Jennings' coefficients of body `body` of lane i for the linear part (m, k_lin, c).
void fill_lane_nj(kernel::Tile& T, int body, int i, const Structure& s, double k_lin, double h);

// The structure model's part: its parameters in the tile, the initial restoring forces, the NJ coefficients.
template <class Model>
void fill_lane_model(kernel::Tile& T, int i, const PairParams& p, Stepper stepper, double h) {
  const auto p1 = Model::params(p.s1), p2 = Model::params(p.s2);
  Model::store(T, 0, i, p1);
  Model::store(T, 1, i, p2);
  T.fs1[i] = Model::initial_force(p1, p.u1);
  T.fs2[i] = Model::initial_force(p2, p.u2);
  if (stepper != Stepper::nigam_jennings) return;
  fill_lane_nj(T, 0, i, p.s1, Model::template linear_stiffness<double>(p1), h);
  fill_lane_nj(T, 1, i, p.s2, Model::template linear_stiffness<double>(p2), h);
}
// Accelerations and observers that depend on the initial contact force T.F[i].
void fill_lane_initial_force(kernel::Tile& T, int i, const PairParams& p, double ag0);
// Lane i's reductions into out[L]; `stored`: contact energy stored at the end; `strain`: the structures'
// recoverable energy at the end; impulsive: no peak force.
void collect_lane(const kernel::Tile& T, int i, std::size_t L, double stored, double strain, bool impulsive,
                  BatchResult& out);

// The law's damping constant of each lane. For a law whose constant follows from e alone
// (contact::DampingFromRestitution: Hertzdamp's xibar, an ODE solve when calibrated) each distinct e is
// computed once per run_batch call and looked up by its bits; a local table, no process-wide cache.
template <class Law> class DampingTable {
 public:
  explicit DampingTable(const ContactModel& cm) : cm_(cm) {}
  double operator()(double kc, double e, double meff) {
    if constexpr (contact::DampingFromRestitution<Law>) {
      const auto [it, fresh] = seen_.try_emplace(std::bit_cast<std::uint64_t>(e), 0.0);
      if (fresh) it->second = Law::damping_of_e(cm_, e);
      return it->second;
    } else {
      return Law::damping_constant(cm_, kc, e, meff);
    }
  }

 private:
  const ContactModel& cm_;
  std::unordered_map<std::uint64_t, double> seen_;
};

template <class Law, class Model>
void fill_lane(kernel::Tile& T, int i, const PairParams& p, const ContactModel& cm, Stepper stepper, const Schedule& s,
               DampingTable<Law>& damping, bool velocity_restitution = false) {
  fill_lane_common(T, i, p, cm.v0_min);
  fill_lane_model<Model>(T, i, p, stepper, s.h);
  // with e(v0) (KernelSettings::restitution) the damping is set at each onset, in the latched 1/v0: cd = 1
  T.cd[i] = velocity_restitution ? 1.0 : damping(p.kc, p.e, T.meff[i]);
  // the initial contact force from the initial penetration (std::pow for the Hertz family)
  const double d0 = p.u1 - p.u2 - p.gap, dd0 = p.v1 - p.v2;
  double clamp = 0.0;
  contact::Shared<double> sh{0.0};
  T.F[i] = 0.0;
  if (d0 > 0.0 && Law::traits.has_force)
    T.F[i] = Law::template force<double>({d0, dd0}, {p.kc, T.cd[i]}, {T.iv0[i]}, contact::RuntimeExponent{cm.n}, sh, clamp);
  fill_lane_initial_force(T, i, p, s.ag[0]);
}

// The resolution guard, after the run (physics/resolution.hpp): lane L's h omega_c at its peak penetration, and
// status coarse where an ok lane exceeds the limit of its stepper x law.
void mark_resolution(std::size_t L, double k_t, double meff, double h, double limit, BatchResult& out);

template <class Law, class Model>
void collect(const kernel::Tile& T, std::size_t base, const ContactModel& cm, double h, double limit, BatchResult& out) {
  const double n_exp = cm.n;
  for (int i = 0; i < T.n; ++i) {
    const std::size_t L = base + static_cast<std::size_t>(i);
    const double dp = std::max(T.u1[i] - T.u2[i] - T.gap[i], 0.0);
    const double strain = Model::strain_energy(Model::template load<double>(T, 0, i), T.u1[i], T.fs1[i]) +
                          Model::strain_energy(Model::template load<double>(T, 1, i), T.u2[i], T.fs2[i]);
    collect_lane(T, i, L, Law::template stored_energy<double>(dp, T.kc[i], n_exp), strain, Law::traits.impulsive, out);
    const double pen = contact::guard_penetration<Law>(out.peak_penetration[L], out.peak_force[L], T.kc[i], n_exp);
    const double k_t = contact::tangent_at_penetration<Law>(pen, T.kc[i], T.cd[i], n_exp);
    mark_resolution(L, k_t, T.meff[i], h, limit, out);
  }
}

// The series recorder watches its lane in the tile that holds it.
kernel::Context tile_context(const kernel::Context& C, const KernelSettings& ks, const kernel::Tile& T,
                             std::size_t base, double ag0);

template <class Law, class Model = model::Registered>
void run_batch_t(const PairBatch& batch, const ContactModel& cm, const GroundMotion& motion, const KernelSettings& ks,
                 BatchResult& out) {
  const std::size_t width = batch.width();
  out.resize(width);
  if (width == 0) return;
  const Schedule s = make_schedule(motion, ks.substeps);
  if (ks.series) {
    ks.series->clear();
    ks.series->reserve_for(static_cast<std::size_t>(s.nsteps) + 1);
  }
  const kernel::Context C{&ks, s.ag.data(), s.nsteps, s.h, cm.v0_min, ks.displacement_limit, nullptr, 0};
  DampingTable<Law> damping(cm);
  // the law's declared limit (a test law outside the registry declares unmeasured(): no coarse status)
  const double limit = Law::resolution[scheme_of(ks.stepper, ks.locate_contact)];
  // a damping law that acts on a multiple of the stiffness given (three-spring: k_eq = 1.5 k, contact/model.hpp)
  const double kc_factor = Law::traits.restitution_from_damping ? damping_law(cm.damping).stiffness_factor : 1.0;
  auto tile = std::make_unique<kernel::Tile>();
  kernel::Tile& T = *tile;
  for (std::size_t base = 0; base < width; base += kernel::tile_width) {
    if (ks.stop && ks.stop->load(std::memory_order_relaxed)) throw StopRequested();  // a stop: between two tiles
    T.n = static_cast<int>(std::min<std::size_t>(kernel::tile_width, width - base));
    // lanes past n up to the SIMD chunk boundary are padded with copies of the tile's first lane
    T.np = std::min(kernel::tile_width, (T.n + simd::W - 1) / simd::W * simd::W);
    for (int i = 0; i < T.np; ++i) {
      PairParams p = batch.get(base + static_cast<std::size_t>(i < T.n ? i : 0));
      if (kc_factor != 1.0) p.kc *= kc_factor;
      fill_lane<Law, Model>(T, i, p, cm, ks.stepper, s, damping, ks.restitution != nullptr);
    }
    const kernel::Context Ct = tile_context(C, ks, T, base, s.ag[0]);
    kernel::visit_stepper(ks.stepper, [&]<class S>() { run_tile<S, Law, Model>(T, Ct, cm); });
    collect<Law, Model>(T, base, cm, s.h, limit, out);
  }
}

// The registered law of cm.law (contact/registry.hpp); preconditions are the caller's (physics::validate).
void run_batch(const PairBatch& batch, const ContactModel& cm, const GroundMotion& motion, const KernelSettings& ks,
               BatchResult& out);

}  // namespace pounding::physics
