#pragma once
// The batch time-history kernel's value types (physics/batch.hpp adds the contact model and run_batch): pairs of SDOF structures (1 = left, 2 = right) on a common ground
// motion, with a contact law between them. Plain data in, peaks and counts out; no MPI, no HDF5,
// no I/O, no allocation inside the time loop.
//
// Symbols (SI units: m, s, kg, N):
//   u, v, a   displacement, velocity, acceleration relative to the ground
//   ag        ground acceleration (m/s^2), linear between record samples
//   m, k, c   mass, initial stiffness, viscous damping coefficient
//   fy, alpha yield force and post-yield stiffness ratio of the bilinear (kinematic hardening) spring
//   fs        restoring force of the structure
//   gap       at-rest separation; delta = u1 - u2 - gap is the penetration (contact when > 0)
//   kc        contact stiffness: N/m for linear/Kelvin, N/m^n for the Hertz family
//   e         coefficient of restitution
//   F         contact force (>= 0, pushes 1 left and 2 right)
//
// Equations of motion (muthukumar-desroches-2006-hertzdamp.txt, eq. 1):
//   m1 a1 + c1 v1 + fs1(u1) + F = -m1 ag,   m2 a2 + c2 v2 + fs2(u2) - F = -m2 ag.
#include <atomic>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pounding/core/enum_names.hpp"


namespace pounding {

enum class Stepper : std::uint8_t {
  central_difference,  // explicit velocity Verlet (central difference) with a velocity predictor
  newmark,             // Newmark average acceleration, Newton iterations per step (OpenSees' usual choice)
  rk4,                 // classical 4th-order Runge-Kutta (the Muthukumar-DesRoches paper's choice)
  nigam_jennings,      // exact recurrence for linear phases, nonlinear remainder as piecewise-linear load
};
inline constexpr std::string_view stepper_names = "central-difference, newmark, rk4, nigam-jennings";

// Whether the kernel libraries were compiled for a vector unit with fused multiply-add (POUNDING_KERNEL_ARCH native on
// an FMA machine, x86-64-v3, x86-64-v4). The pair kernel's bits and the system stepper's (which pins its products as
// explicit FMAs, lane::fma) agree only there: without FMA the compiler leaves the pair kernel's a * b + c unfused while
// lane::fma stays exactly rounded (tests/physics/test_system_kernel.cpp). Defined in src/kernel/batch.cpp, compiled
// with the kernel's flags.
bool kernel_fuses_multiply_add();

// coarse: ran to the end (status ok) but the contact was not resolved: the lane's h omega_c (BatchResult::
// h_omega_contact) exceeds the accuracy limit of its stepper x law (physics/resolution.hpp); peaks are returned.
enum class LaneStatus : std::uint8_t { ok = 0, diverged = 1, non_finite = 2, coarse = 3 };
inline constexpr EnumName<LaneStatus> lane_status_table[] = {{LaneStatus::ok, "ok"},
                                                             {LaneStatus::diverged, "diverged"},
                                                             {LaneStatus::non_finite, "non-finite"},
                                                             {LaneStatus::coarse, "coarse"}};
constexpr const auto& enum_names(LaneStatus) { return lane_status_table; }  // to_string(LaneStatus) (core)

// One structure. fy = +inf (the default) makes the spring linear elastic.
struct Structure {
  double m = 0, k = 0, c = 0;
  double fy = std::numeric_limits<double>::infinity();
  double alpha = 0.0;
  // k = 4 pi^2 m / T^2, c = 2 zeta sqrt(k m)
  static Structure from_period(double m, double T, double zeta, double fy = std::numeric_limits<double>::infinity(),
                               double alpha = 0.0);
};

struct PairParams {
  Structure s1, s2;
  double gap = 0.0;
  double kc = 0.0;  // contact stiffness (see symbol table)
  double e = 1.0;   // restitution
  double u1 = 0, v1 = 0, u2 = 0, v2 = 0;  // initial conditions (at rest by default)
};

// Per-lane inputs in struct-of-arrays form.
struct PairBatch {
  std::vector<double> m1, k1, c1, fy1, alpha1;
  std::vector<double> m2, k2, c2, fy2, alpha2;
  std::vector<double> gap, kc, e;
  std::vector<double> u1_0, v1_0, u2_0, v2_0;
  void resize(std::size_t n);
  std::size_t width() const { return m1.size(); }
  void set(std::size_t lane, const PairParams& p);
  PairParams get(std::size_t lane) const;
};

// Ground motion: acceleration samples (m/s^2) at spacing dt, linear in between; zero-padded to `duration`
// when that is longer than the record (free vibration after the shaking).
struct GroundMotion {
  double dt = 0.0;
  std::span<const double> ag;
  double duration = 0.0;  // 0: the record's own length (n - 1) dt
  double total_duration() const;
};

// Optional per-step recording of one lane (for `pounding simulate --series`). Preallocated by the
// caller (reserve_for); the kernel only writes into it.
struct SeriesRecorder {
  std::size_t lane = 0;
  std::vector<double> t, u1, u2, v1, v2, a1_abs, a2_abs, fs1, fs2, force, ag;
  void reserve_for(std::size_t n_steps);
  void clear();
};

// A velocity-dependent restitution e(v0) (issue 26 §3; physics builds it from contact::RestitutionCurve): at each
// contact onset the central-difference stepper multiplies the lane's latched 1/v0 by damping(v0) (the lane's damping
// constant is then 1) and counts the onsets whose v0 lies outside the curve's valid range. Null: the kernel as
// before, bit for bit (a branch taken only at an onset).
struct VelocityRestitution {
  const void* self = nullptr;
  double (*damping)(const void* self, double v0) = nullptr;  // the law's damping constant for e(v0)
  bool (*outside)(const void* self, double v0) = nullptr;    // v0 outside the valid range
};

struct KernelSettings {
  Stepper stepper = Stepper::central_difference;
  int substeps = 1;                  // integration steps per record step
  double displacement_limit = 10.0;  // |u| above this (m) marks a lane diverged
  bool energy = false;               // track the energy terms (costs a little)
  int newton_max_iter = 30;
  double newton_tol = 1e-10;  // relative displacement increment
  // rk4 only: locate the contact onset inside the step (cubic Hermite interpolant of delta), integrate to it
  // without contact, latch v0 there and finish the step in contact (the high-accuracy mode)
  bool locate_contact = false;
  SeriesRecorder* series = nullptr;
  const VelocityRestitution* restitution = nullptr;  // e(v0) per impact (central difference, hertzdamp only)
  // Raised (a stop signal): the steppers return at their next check (every few thousand steps, and between tiles
  // and lanes), and physics::run_system / run_batch throw StopRequested instead of returning a partial result.
  const std::atomic<bool>* stop = nullptr;
};

// Per-lane observer reductions.
struct BatchResult {
  std::vector<double> peak_u1, peak_u2;           // max |u|
  std::vector<double> peak_closing, t_peak_closing;  // max (u1 - u2) and when
  std::vector<double> t_first_impact;             // NaN when no impact
  std::vector<std::int32_t> impact_count;         // separated -> contact transitions
  std::vector<double> peak_force, peak_penetration;
  std::vector<double> contact_energy;             // energy dissipated by the contact (J)
  std::vector<double> contact_time;               // total time in contact (s)
  std::vector<double> peak_acc1, peak_acc2;       // max |absolute acceleration| (m/s^2)
  std::vector<std::int32_t> clamp_count;          // steps where a tensile contact force was clamped to 0
  std::vector<std::int32_t> restitution_outside;  // impacts whose v0 lay outside the e(v0) curve's valid range
  std::vector<std::uint8_t> status;               // LaneStatus
  // The resolution of the contact: h omega_c with omega_c = sqrt(k_t / meff), k_t the law's tangent stiffness at
  // the lane's peak penetration (physics/resolution.hpp). 0 when the lane never touched, NaN for a law without a
  // force element (none, stereomechanical) and for a diverged lane. A post-run reduction: no cost in the loop.
  std::vector<double> h_omega_contact;
  std::vector<double> final_u1, final_v1, final_u2, final_v2;
  // Energy terms at the end (only with KernelSettings::energy): input = kinetic + strain + viscous
  // + hysteretic + contact_stored + contact_dissipated (contact_energy).
  std::vector<double> e_input, e_kinetic, e_strain, e_viscous, e_hysteretic, e_contact_stored;
  void resize(std::size_t n);
  std::size_t width() const { return status.size(); }
};

// Nigam-Jennings coefficients for u'' + 2 zeta omega u' + omega^2 u = -a(t), a linear on [0, h]:
// [u1; v1] = A [u0; v0] + B [a0; a1]. Exact; requires 0 <= zeta < 1, omega > 0, h > 0.
struct NigamJennings {
  double a11, a12, a21, a22, b11, b12, b21, b22;
};
NigamJennings nigam_jennings(double omega, double zeta, double h);

}  // namespace pounding
