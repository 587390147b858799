// C10 (architecture.md 4): a structure model that is not the registered one, defined here in 18 lines (the
// struct below, from its comment to its closing brace), runs on all 4 steppers through
// physics::run_batch_t<contact::None, Model> (instantiated in this TU from physics/tile_runner_impl.hpp) and
// matches the closed-form response of a damped linear oscillator: free vibration from an initial
// displacement, and the exact response to a linear ground acceleration from rest. The registered model and
// the new one satisfy model::StructureModel (static_asserts below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "kernel_test_support.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/model/sdof.hpp"
#include "pounding/physics/run_batch.hpp"
#include "pounding/physics/tile_runner_impl.hpp"

namespace pounding {
namespace {

// ---- the extension model: 18 lines (comment to closing brace; <= 50) ----
// A linear elastic SDOF: fs = k u from the displacement alone (no committed force, no dissipation). Its one
// parameter k lives in the tile's stiffness slot of its body.
struct LinearElastic {
  static constexpr int dofs = 1, contact_dof = 0;
  template <class T> struct Params { T k; };
  template <class T> struct State { T u, fs; };
  static Params<double> params(const Structure& s) { return {s.k}; }
  static void store(kernel::Tile& t, int body, int i, const Params<double>& p) { (body == 0 ? t.k1 : t.k2)[i] = p.k; }
  template <class T> POUNDING_INLINE static Params<T> load(const kernel::Tile& t, int body, int i) {
    return {lane::load<T>((body == 0 ? t.k1 : t.k2) + i)};
  }
  static double initial_force(const Params<double>& p, double u0) { return p.k * u0; }
  template <class T> POUNDING_INLINE static T restoring(const Params<T>& p, State<T>, T u_new, T) { return p.k * u_new; }
  template <class T> POUNDING_INLINE static T tangent(const Params<T>& p, State<T>, T, T, T) { return p.k; }
  template <class T> POUNDING_INLINE static T linear_stiffness(const Params<T>& p) { return p.k; }
  template <class T> POUNDING_INLINE static T hysteretic_increment(const Params<T>&, State<T>, T, T) { return T(0.0); }
  static double strain_energy(const Params<double>& p, double u, double) { return 0.5 * p.k * u * u; }
};
// ---- end of the extension model ----

static_assert(model::StructureModel<LinearElastic>);
static_assert(model::StructureModel<model::Registered>);
static_assert(model::StructureModel<model::Sdof<model::BilinearKinematic>>);

constexpr int kLanes = 11;  // one full SIMD chunk (8 on AVX-512) plus a partial one

// Lane i: body 1 with T = 0.3..0.8 s, body 2 with T = 0.9..1.9 s, damping 0..10 %; far apart (no contact).
PairBatch batch(bool displaced) {
  PairBatch b;
  b.resize(kLanes);
  for (int i = 0; i < kLanes; ++i) {
    PairParams p;
    p.s1 = Structure::from_period(2.0e5, 0.3 + 0.05 * i, 0.01 * i);
    p.s2 = Structure::from_period(3.0e5, 0.9 + 0.1 * i, 0.1 - 0.01 * i);
    p.gap = 10.0;
    p.kc = 1e7;
    if (displaced) p.u1 = 0.05, p.u2 = -0.03 - 0.002 * i;
    b.set(static_cast<std::size_t>(i), p);
  }
  return b;
}

// Closed form of u'' + 2 zeta w u' + w^2 u = -(a0 + b t) from u(0) = u0, u'(0) = 0: the particular ramp
// solution A + B t plus the damped homogeneous part. Returns {u, v} at t.
struct Exact {
  double u, v;
};
Exact closed_form(const Structure& s, double u0, double a0, double b, double t) {
  const double w = std::sqrt(s.k / s.m), z = s.c / (2.0 * std::sqrt(s.k * s.m)), wd = w * std::sqrt(1.0 - z * z);
  const double B = -b / (w * w), A = (-a0 - 2.0 * z * w * B) / (w * w);
  const double C1 = u0 - A, C2 = (-B + z * w * C1) / wd;
  const double e = std::exp(-z * w * t), cs = std::cos(wd * t), sn = std::sin(wd * t);
  const double uh = e * (C1 * cs + C2 * sn);
  const double vh = e * ((-z * w * C1 + wd * C2) * cs + (-z * w * C2 - wd * C1) * sn);
  return {A + B * t + uh, B + vh};
}

// Worst error over lanes and bodies of u and v at the end and over the recorded lane's whole history of u,
// relative to the scale of each motion (|u| and |v| peaks of the closed form).
double worst_error(Stepper st, bool displaced, double a0, double b) {
  const double dt = 0.01, duration = 6.0;
  const long n = std::lround(duration / dt) + 1;
  std::vector<double> ag(static_cast<std::size_t>(n));
  for (long j = 0; j < n; ++j) ag[static_cast<std::size_t>(j)] = a0 + b * static_cast<double>(j) * dt;
  const GroundMotion gm{dt, ag, 0.0};
  KernelSettings ks;
  ks.stepper = st;
  ks.substeps = 4;
  ks.energy = true;
  SeriesRecorder series;
  series.lane = 9;
  ks.series = &series;
  const PairBatch pb = batch(displaced);
  BatchResult r;
  physics::run_batch_t<contact::None, LinearElastic>(pb, test::contact(ContactLaw::none), gm, ks, r);
  double worst = 0.0;
  for (int i = 0; i < kLanes; ++i) {
    EXPECT_EQ(r.status[i], 0) << "lane " << i;
    EXPECT_EQ(r.e_hysteretic[i], 0.0) << "lane " << i;  // elastic: nothing dissipated by the springs
    const PairParams p = pb.get(static_cast<std::size_t>(i));
    for (int body = 0; body < 2; ++body) {
      const Structure& s = body == 0 ? p.s1 : p.s2;
      const double u0 = body == 0 ? p.u1 : p.u2;
      double su = 0.0, sv = 0.0;  // scales: peaks of the exact motion sampled at the integration steps
      for (double t = 0.0; t <= duration + 1e-9; t += dt / 4) {
        const Exact x = closed_form(s, u0, a0, b, t);
        su = std::max(su, std::abs(x.u)), sv = std::max(sv, std::abs(x.v));
      }
      const Exact x = closed_form(s, u0, a0, b, duration);
      const double fu = body == 0 ? r.final_u1[i] : r.final_u2[i], fv = body == 0 ? r.final_v1[i] : r.final_v2[i];
      worst = std::max({worst, std::abs(fu - x.u) / su, std::abs(fv - x.v) / sv});
      if (i == static_cast<int>(series.lane))
        for (std::size_t j = 0; j < series.t.size(); ++j) {
          const double u = body == 0 ? series.u1[j] : series.u2[j];
          worst = std::max(worst, std::abs(u - closed_form(s, u0, a0, b, series.t[j]).u) / su);
        }
    }
  }
  return worst;
}

// Worst relative error measured at dt/4 (h = 2.5 ms, 2400 steps, 11 lanes x 2 bodies):
//   free vibration:  central-difference 1.44e-02, newmark 2.87e-02, rk4 7.86e-06, nigam-jennings 9.45e-14
//   ramp from rest:  central-difference 1.41e-02, newmark 2.82e-02, rk4 7.73e-06, nigam-jennings 9.91e-14
// Central difference and Newmark are the second-order phase errors of ~20 cycles of the 0.3 s lanes
// (omega h ~ 0.05); Nigam-Jennings is exact for a piecewise-linear load (round-off only). Bounds are ~1.5x
// the measured worst.
struct Case {
  Stepper st;
  double tol_free, tol_ramp;
};
constexpr Case kCases[] = {{Stepper::central_difference, 2.2e-2, 2.1e-2},
                           {Stepper::newmark, 4.3e-2, 4.2e-2},
                           {Stepper::rk4, 1.2e-5, 1.2e-5},
                           {Stepper::nigam_jennings, 1.5e-13, 1.5e-13}};

TEST(ExtensionModel, LinearElasticMatchesTheClosedFormOnEveryStepper) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(std::string(to_string(c.st)));
    const double free = worst_error(c.st, true, 0.0, 0.0);
    const double ramp = worst_error(c.st, false, 0.8, -0.3);
    std::printf("%-18s worst relative error: free vibration %.2e, ramp %.2e\n",
                std::string(to_string(c.st)).c_str(), free, ramp);
    EXPECT_LE(free, c.tol_free);
    EXPECT_LE(ramp, c.tol_ramp);
  }
}

}  // namespace
}  // namespace pounding
