// C10 (architecture.md 4): a contact law that is not in the registry, defined here in 28 lines (the struct
// below, from its comment to its closing brace), runs on all 4 steppers through physics::run_batch_t<Law>
// (instantiated in this TU from physics/tile_runner_impl.hpp), closes the energy balance
//   e_input = e_kinetic + e_strain + e_viscous + e_hysteretic + e_contact_stored + contact_energy
// and behaves physically (impacts, positive peak force, never tensile). Every registered law satisfies
// contact::Law (static_asserts below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "kernel_test_support.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/physics/run_batch.hpp"
#include "pounding/physics/tile_runner_impl.hpp"

namespace pounding {
namespace {

namespace pc = contact;

// ---- the extension law: 28 lines (comment to closing brace; <= 60) ----
// A linear spring with a viscous dashpot that acts only while the bodies approach:
// F = kc delta + c max(ddelta, 0) for delta > 0, else 0; c = 2 xi sqrt(kc meff) with Kelvin's xi(e).
// Elastic restitution stroke, so F >= 0 everywhere (no tensile clamp is ever needed).
struct ApproachDashpot {
  static constexpr std::string_view name = "approach-dashpot";
  static constexpr pc::LawTraits traits{.needs_restitution = true};
  static constexpr auto resolution = pc::ResolutionLimits::unmeasured();  // not measured: no coarse status
  template <class T, class Exp>
  POUNDING_INLINE static T force(pc::Kin<T> k, pc::Params<T> p, pc::State<T>, Exp, pc::Shared<T>&, T& clamp) {
    const T zero(0.0);
    clamp = zero;
    return lane::select(k.d > zero, lane::fma(p.cd, lane::max(k.dd, zero), p.kc * k.d), zero);
  }
  // Newton sees the law without the delta > 0 gate (the active set decides activity), as Linear does
  template <class T, class Exp> POUNDING_INLINE static pc::Tangent<T> tangent(pc::Kin<T> k, pc::Params<T> p, pc::State<T>, Exp) {
    const T zero(0.0);
    return {lane::fma(p.cd, lane::max(k.dd, zero), p.kc * k.d), p.kc, lane::select(k.dd > zero, p.cd, zero)};
  }
  template <class T, class Exp>
  POUNDING_INLINE static T linear_stiffness(pc::Kin<T>, pc::Params<T> p, pc::State<T>, Exp, const pc::Shared<T>&) {
    return p.kc;
  }
  template <class T> POUNDING_INLINE static T stored_energy(T dp, T kc, double) { return 0.5 * kc * dp * dp; }
  template <class T> POUNDING_INLINE static void on_onset(pc::State<T>&, lane::mask_t<T>, T, double) {}
  static double damping_constant(const ContactModel&, double kc, double e, double meff) {
    return 2.0 * kelvin_damping_ratio(e) * std::sqrt(kc * meff);
  }
};
// ---- end of the extension law ----

static_assert(pc::Law<ApproachDashpot>);
static_assert(pc::Law<pc::None>);
static_assert(pc::Law<pc::Linear>);
static_assert(pc::Law<pc::Kelvin>);
static_assert(pc::Law<pc::Hertz>);
static_assert(pc::Law<pc::Hertzdamp>);
static_assert(pc::Law<pc::Jankowski>);
static_assert(pc::Law<pc::Stereomechanical>);
static_assert(pc::Laws::size == 7, "a static_assert above for every registered law");

constexpr int kLanes = 11;  // one full SIMD chunk (8 on AVX-512) plus a partial one

// Two yielding bilinear frames (T 0.6 s and 1.5 s, 5 % damping) with gaps and contact stiffnesses that vary
// per lane, as in test_kernel_energy.cpp.
PairBatch batch() {
  PairBatch b;
  b.resize(kLanes);
  for (int i = 0; i < kLanes; ++i) {
    PairParams p;
    p.s1 = Structure::from_period(2.0e5, 0.6, 0.05, 0.0, 0.1);
    p.s2 = Structure::from_period(3.0e5, 1.5, 0.05, 0.0, 0.05);
    p.s1.fy = p.s1.k * 0.015;
    p.s2.fy = p.s2.k * 0.03;
    p.gap = 0.002 + 0.001 * i;
    p.kc = 2e7 * (1.0 + 0.5 * i);
    p.e = 0.5 + 0.04 * i;
    b.set(static_cast<std::size_t>(i), p);
  }
  return b;
}

struct Outcome {
  BatchResult r;
  SeriesRecorder series;
};

Outcome run(Stepper st, int substeps) {
  const double dt = 0.01;
  const std::vector<double> ag = test::two_tone(dt, 6.0, 4.0, 1.1, 3.0, 2.7);
  const GroundMotion gm{dt, ag, 0.0};  // ag: a span, so the record outlives it
  KernelSettings ks;
  ks.stepper = st;
  ks.substeps = substeps;
  ks.energy = true;
  Outcome out;
  out.series.lane = 3;
  ks.series = &out.series;
  physics::run_batch_t<ApproachDashpot>(batch(), test::contact(ContactLaw::kelvin), gm, ks, out.r);
  return out;
}

// Worst |residual| / e_input over the lanes, measured at dt/16 (h = 0.625 ms):
//   central-difference 2.32e-06, newmark 1.41e-06, rk4 1.15e-05, nigam-jennings 1.17e-06 (11 lanes, 9600 steps).
// RK4 closes only to O(h): the dashpot force jumps at the onset and the contact work is the trapezoid of
// the step's end forces (as for Kelvin in test_kernel_energy.cpp). Bounds are ~1.5x the measured worst.
struct Case {
  Stepper st;
  double tol;
};
constexpr Case kCases[] = {{Stepper::central_difference, 3.5e-6},
                           {Stepper::newmark, 2.1e-6},
                           {Stepper::rk4, 1.7e-5},
                           {Stepper::nigam_jennings, 1.8e-6}};

TEST(ExtensionLaw, RunsOnEveryStepperWithEnergyBalanceAndPhysicalForces) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(std::string(to_string(c.st)));
    const Outcome x = run(c.st, 16);
    const BatchResult& r = x.r;
    double worst = 0.0;
    int impacting = 0;
    for (int i = 0; i < kLanes; ++i) {
      ASSERT_EQ(r.status[i], 0) << "lane " << i;
      const double out = r.e_kinetic[i] + r.e_strain[i] + r.e_viscous[i] + r.e_hysteretic[i] + r.e_contact_stored[i] +
                         r.contact_energy[i];
      ASSERT_GT(r.e_input[i], 0.0);
      worst = std::max(worst, std::abs(r.e_input[i] - out) / r.e_input[i]);
      impacting += r.impact_count[i] > 0;
      if (r.impact_count[i] > 0) {
        EXPECT_GT(r.peak_force[i], 0.0) << "lane " << i;
        EXPECT_GT(r.peak_penetration[i], 0.0) << "lane " << i;
        EXPECT_GT(r.contact_energy[i], 0.0) << "lane " << i;  // the dashpot dissipates
      }
      EXPECT_EQ(r.clamp_count[i], 0) << "lane " << i;  // never tensile, so never clamped
    }
    std::printf("%-18s worst |residual|/input %.2e, %d of %d lanes impacting\n", std::string(to_string(c.st)).c_str(),
                worst, impacting, kLanes);
    EXPECT_LE(worst, c.tol);
    EXPECT_GE(impacting, kLanes - 2);
    // the recorded lane's force history: non-negative at every step, and some contact
    ASSERT_FALSE(x.series.force.empty());
    EXPECT_GE(*std::min_element(x.series.force.begin(), x.series.force.end()), 0.0);
    EXPECT_GT(*std::max_element(x.series.force.begin(), x.series.force.end()), 0.0);
  }
}

// The law itself: zero apart, F >= 0 for every sign of the rate, the dashpot only while approaching.
TEST(ExtensionLaw, ForceIsNonTensileAndDampsOnlyWhileApproaching) {
  pc::Shared<double> sh{0.0};
  double clamp = 1.0;
  auto F = [&](double d, double dd) {
    return ApproachDashpot::force<double>({d, dd}, {1e7, 1e5}, {0.0}, pc::Exp15{}, sh, clamp);
  };
  EXPECT_EQ(F(-1e-3, 1.0), 0.0);
  EXPECT_EQ(clamp, 0.0);
  EXPECT_EQ(F(1e-3, -5.0), 1e4);
  EXPECT_EQ(F(1e-3, 0.5), 1e4 + 5e4);
  for (double dd : {-100.0, -1.0, 0.0, 1.0, 100.0})
    for (double d : {1e-9, 1e-4, 1e-2}) EXPECT_GE(F(d, dd), 0.0);
}

}  // namespace
}  // namespace pounding
