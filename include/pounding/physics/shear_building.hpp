#pragma once
// Per-lane numbers of shear buildings (docs/architecture.md §2.2.3 "Bodies and damping", "Stiffness and strength
// profiles"; ../shared/research/systems-and-bridges.md §1): floor masses, storey stiffnesses (given, or a profile
// scaled to T1), storey strengths, and damping -- Rayleigh C = a0 M + a1 K0 on two modes stored as dashpots (a0 m_j
// on every floor to the ground, a1 k_i on every storey spring; K0 the INITIAL storey stiffnesses, contact excluded,
// SB §1 pitfalls 1-2). A one-storey building is today's SDOF bit for bit: k and c from Structure::from_period (or
// c = 2 zeta sqrt(k m) for a given k), fy as given or Cy m g, a floor dashpot and no storey dashpot.
//
// The topology comes from model::shear_buildings (model/shear_building.hpp); these functions fill one lane.
// Bad numbers are the caller's to refuse (the command line and the study validate); these throw
// std::invalid_argument (a programming error) for what they cannot compute.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "pounding/model/modes.hpp"
#include "pounding/model/shear_building.hpp"
#include "pounding/physics/system_batch.hpp"

namespace pounding::physics {

inline constexpr double standard_gravity = 9.80665;  // m/s^2: Vy = Cy M g

struct ShearSpec {
  std::vector<double> floor_mass;        // kg: one value for every floor, or one per floor (bottom first)
  std::vector<double> storey_stiffness;  // N/m: one value for every storey, or one per storey; empty: from `period`
  double period = 0.0;                   // T1 (s) when storey_stiffness is empty: `profile` scaled to it
  model::StiffnessProfile profile = model::StiffnessProfile::uniform;
  // Storey strength, the first given wins: storey_yield (Vy, N; one or one per storey), yield_drift (theta_y:
  // Vy_i = k_i (theta_y h_i)), yield_coefficient (Cy: Vy_i = Cy M_total g V_i / V_1, V the shear profile's storey
  // shears, model::stiffness_shape); none: linear elastic (fy = inf).
  std::vector<double> storey_yield;
  double yield_drift = 0.0;
  double yield_coefficient = 0.0;
  double alpha = 0.0;  // post-yield stiffness ratio of every storey
  double zeta = 0.05;  // the damping ratio at modes mode_i and mode_j (Rayleigh), or of the SDOF
  int mode_i = 1, mode_j = 2;  // Rayleigh's modes, from 1 (ignored for one storey)
  // Classical modal damping instead of Rayleigh (docs/architecture.md §2.2.3): C = M Phi diag(2 zeta_j omega_j / M_j)
  // Phi' M with zeta_j = modal_zeta[j] from mode 1, the last value repeating (empty: every mode `zeta`); the body
  // must have DampingForm::dense (model::StickTopology::damping). One storey: the SDOF with ratio zeta_1.
  bool modal = false;
  std::vector<double> modal_zeta;
};

// What the numbers came to (per floor / per storey, bottom first) and the damping ratio each mode gets.
struct ShearNumbers {
  std::vector<double> m, k, fy;
  std::vector<double> c_floor, c_storey;  // c_storey all 0 for one storey (and for modal damping, c_floor too)
  std::vector<double> c_dense;            // modal damping (n > 1): C row-major n x n; empty otherwise
  model::Rayleigh rayleigh{0.0, 0.0};     // a0, a1 (0, 0 for one storey)
  model::Modes modes;
  std::vector<double> zeta_modes;  // a0/(2 omega_n) + a1 omega_n / 2 (modal: zeta_n); one storey c / (2 sqrt(k m))
};

// The numbers of a stick with these storey heights (m, bottom first; their count is the storey count).
ShearNumbers shear_numbers(std::span<const double> storey_heights, const ShearSpec& spec);

// Fills lane `lane` of body `body` of batch.system (a body of model::shear_buildings): masses, floor dashpots,
// springs {k, fy, alpha} and storey dashpots (when the batch has them; a body without storey dashpots takes only
// a0 M, and refuses a1 != 0), or the dense C of modal damping (a body with DampingForm::dense: spec.modal and more
// than one storey, else std::invalid_argument). Storey heights from the body's floor levels. Returns the numbers.
ShearNumbers set_shear_building(SystemBatch& batch, std::size_t lane, int body, const ShearSpec& spec);

// Base isolation (docs/architecture.md §2.2.3 "Isolated stick", "Isolated building"; ../shared/research/
// systems-and-bridges.md §2, T2.1): a linear bearing (k_eff, zeta_eff: a dashpot c_b = 2 zeta_eff sqrt(k_eff
// M_total) on the base to ground, i.e. on the isolator's deformation rate, M_total = base + superstructure) or a
// bilinear lead-rubber bearing (k1, k2, Qd: k = k1, fy = Qd k1 / (k1 - k2) = Qd / (1 - k2/k1), alpha = k2/k1 -- SB §2
// "F_y = Q_d/(1 - k2/k1)", AASHTO Guide Spec. for Seismic Isolation Design, Naeim & Kelly 1999; no viscous damping
// of its own: its hysteresis is the damping).
//
// Friction pendulum (model/hysteresis/friction_pendulum.hpp, law 2): F = (W/R) u + mu(v) W z, W = g M_total (the
// building's whole weight on its bearings, constant: vertical motion not modelled), mu(v) = mu_fast - (mu_fast -
// mu_slow) exp(-rate |v|) (Constantinou et al. 1990), z the Bouc-Wen smoothing (A = 1, beta = gamma = 0.5, eta = 2)
// with yield displacement u_y. Bouc-Wen (model/hysteresis/bouc_wen.hpp, law 1): given as the lead-rubber bearing's
// k1, k2, Qd plus A, beta, gamma, eta: the standard form's k = k1, alpha = k2/k1, u_y = Qd / (k1 - k2) (so Q = Qd and,
// for A = 1, the initial tangent is k1). Neither has a viscous dashpot: the hysteresis is the damping.
enum class Bearing { linear, lead_rubber, friction_pendulum, bouc_wen };
// A linear bearing's damping ratio when none is given: ONE default for the study's isolation table, simulate's
// --bearing-zeta and Python's isolation dicts (10 %, the order of a high-damping rubber bearing's zeta_eff).
inline constexpr double default_bearing_zeta = 0.1;
struct IsolationSpec {
  Bearing bearing = Bearing::linear;
  double base_mass = 0.0;               // kg, > 0 (a massless base makes the system singular, SB §2 pitfalls)
  // linear: N/m, ratio; lead-rubber: zeta_eff the rubber's viscous ratio on the post-yield stiffness, a dashpot
  // c_b = 2 zeta_eff sqrt(k2 M_total) beside the hysteresis (0: none, the bearing of every earlier run)
  double k_eff = 0.0, zeta_eff = 0.0;
  double k1 = 0.0, k2 = 0.0, qd = 0.0;  // lead-rubber and Bouc-Wen: N/m, N/m (0 <= k2 < k1), N (> 0)
  // friction pendulum: radius R (m), friction at rest and at high speed, rate (s/m), smoothing u_y (m)
  double radius = 0.0, mu_slow = 0.0, mu_fast = 0.0, rate = 0.0, uy = 2.5e-4;
  // Bouc-Wen: A, beta (on |du|), gamma, eta (an integer in [1, model::smooth_max_eta])
  double bw_a = 1.0, bw_beta = 0.5, bw_gamma = 0.5;
  int bw_eta = 1;
};
// The hysteresis law of the isolator spring of `bearing` (model/hysteresis/registry.hpp): what
// model::StickTopology::isolator_law takes.
int isolator_law(Bearing bearing);
struct IsolationNumbers {
  double m_base = 0.0, m_total = 0.0;
  SpringSpec isolator;  // packed by the bearing's model (BilinearKinematic, BoucWen or FrictionPendulum::pack)
  double c_base = 0.0;  // the linear bearing's dashpot (N s/m), 0 for the hysteretic bearings
  double weight = 0.0;  // W = g M_total (N): the friction pendulum's normal force
  ShearNumbers super;   // the FIXED-BASE superstructure's numbers (its Rayleigh from its own modes)
};
// The numbers of an isolated stick: superstructure storey heights (m, bottom first), its spec and the bearing's.
IsolationNumbers isolation_numbers(std::span<const double> storey_heights, const ShearSpec& spec,
                                   const IsolationSpec& iso);
// Fills lane `lane` of isolated body `body` (model::StickTopology::isolated): the base mass and dashpot, the
// isolator spring, and the superstructure as set_shear_building does, its floor dashpots referencing the base
// (Body::floor_dashpot_ref, so the rigid-body mode on the isolators gets no superstructure damping); with modal
// damping (ShearSpec::modal, a dense body) the whole C of isolated_damping_matrix instead of dashpots.
// Classical modal damping of an isolated building (StickTopology::damping = dense): its superstructure's fixed-base
// modal C_s (n x n, row-major, ShearNumbers::c_dense) acting on the floors' velocities relative to the base, and the
// bearing's dashpot c_b to the ground, as one (n + 1) x (n + 1) matrix over (base, floor 1, ..., floor n):
// C = T' C_s T + c_b e0 e0', T = [-1 | I]. Symmetric; a rigid-body translation on the bearings gets only c_b.
std::vector<double> isolated_damping_matrix(std::span<const double> c_super, double c_base);
IsolationNumbers set_isolated_building(SystemBatch& batch, std::size_t lane, int body, const ShearSpec& spec,
                                       const IsolationSpec& iso);
// Moat walls of isolated body `body` (StickTopology::moat): gaps (m) left and right of the base, kc and e.
void set_moat(SystemBatch& batch, std::size_t lane, int body, double gap_left, double gap_right, double kc, double e);

// Contact numbers of lane `lane` for every element: gap = study gap (+ level_offsets[level - 1] when given, for
// elements of study-gap groups; elements of other groups keep their own gap), kc, e, and the weight of an
// interpolated side (a floor against a column) = model::column_weight(xi, shape): xi for linear shape functions.
void set_contacts(SystemBatch& batch, std::size_t lane, double gap, double kc, double e,
                  std::span<const double> level_offsets = {},
                  model::ShapeFunctions shape = model::ShapeFunctions::linear);

// The two floor masses (kg) an element of lane `lane` joins, left and right, for the equivalent-sphere Hertz stiffness:
// a point side's floor; a column side's nearer floor (xi < 0.5: the floor below unless it is the ground, else the
// floor above), so xi -> 0 / 1 gives the floor-to-floor element's masses; a wall: the other side's.
std::array<double, 2> contact_masses(const SystemBatch& batch, std::size_t lane, int element);

// The default contact stiffness of lane `lane`'s pounding elements (those of study-gap groups; a moat keeps its own):
// kc = the equivalent-sphere Hertz stiffness (contact::hertz_stiffness_spheres) of the two floor masses each joins
// (contact_masses) -- `pounding simulate` without --kh and Python's analyze_storeys without kh, one rule. Call after
// the buildings' masses are set.
void set_sphere_stiffness(SystemBatch& batch, std::size_t lane, double density, double youngs, double poisson);

// The struck column's fixed-end shears per unit contact force at xi (a fixed-fixed column, no floor rotation, point
// load at a = xi h: V_below = (1 - xi)^2 (1 + 2 xi), V_above = xi^2 (3 - 2 xi), summing to 1; Karayannis & Favvata
// 2005, ../shared/research/systems-and-bridges.md §3) -- the extra shear the impact puts into the column below and
// above the contact point, beside the storey shear of the drift.
struct ColumnShear {
  double below, above;
};
inline ColumnShear column_shear_per_force(double xi) {
  return {(1.0 - xi) * (1.0 - xi) * (1.0 + 2.0 * xi), xi * xi * (3.0 - 2.0 * xi)};
}

}  // namespace pounding::physics
