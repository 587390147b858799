#pragma once
// Per-lane numbers of a batch of systems (docs/architecture.md Part 2, §2.2.2) and what a run returns per DOF,
// spring, element and lane (§2.6.1). Every array is [index][lane] flattened index-major, lane fastest:
// value of index i in lane l at [i * width + l]. SI units (m, s, kg, N).
//
// run_system(batch, groups, motion, settings, out): every lane of `batch` through `motion` (one channel), with
// groups[g] the contact model of contact group g. The SDOF pair (System::sdof_pair()) runs today's pair kernel
// (physics/run_batch.hpp) through to_pair_batch / from_pair_result, bit for bit; every other topology runs the
// system stepper (central difference). Validation first (bad input: InputError naming the lane and the field).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "pounding/contact/model.hpp"
#include "pounding/kernel/batch.hpp"
#include "pounding/model/hysteresis/registry.hpp"
#include "pounding/model/system.hpp"

namespace pounding::physics {

// The description of one spring, packed by its hysteresis model (model/hysteresis/spring_spec.hpp; H::pack): k, fy,
// alpha kept un-derived so that the driver's scaling by traits reproduces today's arithmetic (§2.2.2); fy = +inf:
// linear elastic.
using model::SpringSpec;

// The registry's trait stays_elastic (model/hysteresis/registry.hpp) asked of a spring of the batch by its law: the
// spring stays on its initial elastic branch (bilinear, Q-Hyst: |d| <= margin fy / k) or inside its gap (the gap
// links: no force, so linear) at peak |deformation| `peak`; the smooth models have no elastic range and answer
// false. A response scaled from a linear run is exact only when every spring of the lane answers true (the
// fragility stripes' and IDA's shortcut, study/run.cpp).
inline bool spring_stays_elastic(int law, const SpringSpec& s, double peak, double margin) {
  return model::stays_elastic(law, s, peak, margin);
}

struct SystemBatch {
  const model::System* system = nullptr;
  std::size_t width = 0;
  std::vector<double> m;           // [dof][lane] lumped mass (kg)
  std::vector<double> c_floor;     // [dof][lane] floor dashpot to ground or to the body's base (N s/m)
  std::vector<double> c_storey;    // [spring][lane] storey dashpot on the spring's deformation rate (N s/m);
                                   // empty unless System::any_storey_dashpots()
  // [entry][lane] classical modal damping (bodies with DampingForm::dense, body order): entry dense_entry(body, j, k)
  // = C_jk of that body (j, k its DOFs 0..n-1 bottom first, N s/m); the damping force on DOF j is sum_k C_jk v_k
  // (velocities relative to the support). Empty unless System::any_dense_damping().
  std::vector<double> c_dense;
  std::vector<SpringSpec> spring;  // [spring][lane]
  std::vector<double> gap;         // [element][lane] the element's gap (m), study gap plus offset for study-gap groups
  std::vector<double> weight;      // [element][lane] N2 of an interpolated side (0 for point and wall sides)
  std::vector<double> kc, e;       // [element][lane] contact stiffness (law units) and restitution
  std::vector<double> u0, v0;      // [dof][lane] initial displacement and velocity (relative, m and m/s)

  // Sizes every array for `system` (held by pointer: it must outlive the batch) and `width` lanes, zero-filled
  // (e = 1, fy = inf, weight = 0).
  void resize(const model::System& system, std::size_t width);
  // The c_dense entry of C_jk of body `body` (a body with DampingForm::dense; j, k local DOF numbers); -1 for a body
  // without dense damping.
  int dense_entry(int body, int j, int k) const;
  std::vector<int> dense_base;  // per body: its first c_dense entry, -1 without dense damping (set by resize)
  static std::size_t at(int index, std::size_t lane, std::size_t width) {
    return static_cast<std::size_t>(index) * width + lane;
  }
};

struct SystemResult {
  std::size_t width = 0;
  // per DOF [dof][lane]
  std::vector<double> peak_u;     // max |u| (m)
  std::vector<double> peak_acc;   // max |a + ag| (absolute acceleration, m/s^2)
  std::vector<double> final_u, final_v;
  // per spring [spring][lane]
  std::vector<double> peak_drift;         // max |d| (storey drift, m)
  std::vector<double> peak_spring_force;  // max |f| (storey shear, N)
  // per element [element][lane]
  std::vector<double> peak_closing, t_peak_closing;  // max (x_L - x_R) and when (s)
  std::vector<double> t_first_impact;                // NaN when no impact
  std::vector<std::int32_t> impact_count, clamp_count;
  std::vector<std::int32_t> restitution_outside;  // impacts whose v0 lay outside the e(v0) curve's valid range
  std::vector<double> peak_force, peak_penetration;
  std::vector<double> contact_energy, contact_time;  // dissipated (J), time in contact (s)
  std::vector<double> h_omega_contact;               // the resolution guard's h omega_c (physics/resolution.hpp)
  // per lane [lane]
  std::vector<std::uint8_t> status;  // LaneStatus
  std::vector<double> e_input, e_kinetic, e_strain, e_viscous, e_hysteretic, e_contact_stored;  // NaN without energy

  // Sizes every array for `system` and `width` lanes: the observers a run always writes zero-filled, what it
  // writes only when it happens NaN -- t_first_impact (until an impact) and the energy terms (until a run with
  // KernelSettings::energy writes them); status ok, counts 0.
  void resize(const model::System& system, std::size_t width);
};

// The pair, exactly: lane l of a PairBatch is lane l of System::sdof_pair() and back (§2.2.2): plain copies, so
// PairBatch -> SystemBatch -> PairBatch and BatchResult -> SystemResult -> BatchResult are bit-identical.
// from_pair_result also sets peak_drift = peak_u (an SDOF's drift is its displacement) and peak_spring_force NaN
// (the pair kernel does not observe it). Each throws std::logic_error when its input is not the pair's.
SystemBatch to_system(const PairBatch& batch, const model::System& pair);  // pair == System::sdof_pair()
PairBatch to_pair_batch(const SystemBatch& batch);                          // batch.system->is_sdof_pair()
SystemResult from_pair_result(const BatchResult& r);
BatchResult to_pair_result(const SystemResult& r);

void run_system(const SystemBatch& batch, std::span<const ContactModel> groups, const GroundMotion& motion,
                const KernelSettings& settings, SystemResult& out);
// Multi-support input (issue 26 §2; docs/architecture.md §2.2.6): channels[c] is the ground motion of channel c (every
// one with the same dt and length). Each body is integrated relative to its own support with its channel's
// acceleration; a link spring or contact element whose two sides lie on different channels forms its deformation,
// increment and rate from total displacements (+ ug of each side, baseline-corrected: ground_history in
// run_system.cpp), and the supports' work through it is added to e_input. Same-channel parts add nothing, so
// identical records on every channel give the one-channel result bit for bit. One channel: run_system above.
void run_system(const SystemBatch& batch, std::span<const ContactModel> groups, std::span<const GroundMotion> channels,
                const KernelSettings& settings, SystemResult& out);

}  // namespace pounding::physics
