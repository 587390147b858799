// The identity behind the bisection IDA's per-lane scale factors (study/run.cpp): for elastic and bilinear
// (kinematic hardening) restoring forces R(f w; fy) = f R(w; fy / f), so the response of a pair to f ag equals f
// times its response to ag with the yield forces divided by f. Checked through the kernel for every stepper,
// with structures that do yield (otherwise the identity would be plain linearity and the test could not fail).
#include <gtest/gtest.h>

#include <cmath>

#include "kernel_test_support.hpp"

namespace pounding {
namespace {

using test::all_steppers;

PairParams yielding_pair(double fy_scale) {
  PairParams p;
  // T 0.8 s and 1.3 s, 5 % damping; yield forces low enough that both yield under the two-tone motion
  p.s1 = Structure::from_period(2.0e6, 0.8, 0.05, 0.6e6 * fy_scale, 0.05);
  p.s2 = Structure::from_period(3.0e6, 1.3, 0.05, 0.5e6 * fy_scale, 0.02);
  return p;
}

BatchResult run(const PairParams& p, const std::vector<double>& ag, Stepper stepper) {
  return test::run_one(p, test::contact(ContactLaw::none), ag, 0.005, 0.0, stepper, 1);
}

TEST(IdaScaling, ScaledRecordEqualsScaledYieldForces) {
  const std::vector<double> ag = test::two_tone(0.005, 20.0);
  for (Stepper stepper : all_steppers)
    for (double f : {0.35, 1.7, 4.2}) {
      std::vector<double> fag(ag.size());
      for (std::size_t i = 0; i < ag.size(); ++i) fag[i] = f * ag[i];
      const BatchResult a = run(yielding_pair(1.0), fag, stepper);
      const BatchResult b = run(yielding_pair(1.0 / f), ag, stepper);
      ASSERT_EQ(a.status[0], 0);
      ASSERT_EQ(b.status[0], 0);
      const PairParams p = yielding_pair(1.0);
      // they yield: the peaks exceed the yield displacements (else the identity is only linearity)
      EXPECT_GT(a.peak_u1[0], 1.5 * p.s1.fy / p.s1.k) << to_string(stepper) << " f " << f;
      EXPECT_GT(a.peak_u2[0], 1.5 * p.s2.fy / p.s2.k) << to_string(stepper) << " f " << f;
      // Newmark's Newton iterations stop at a relative tolerance of 1e-10: the identity holds to that
      const double tol = stepper == Stepper::newmark ? 1e-7 : 1e-10;
      EXPECT_NEAR(f * b.peak_closing[0], a.peak_closing[0], tol * a.peak_closing[0]) << to_string(stepper) << " f " << f;
      EXPECT_NEAR(f * b.peak_u1[0], a.peak_u1[0], tol * a.peak_u1[0]) << to_string(stepper) << " f " << f;
      EXPECT_NEAR(f * b.peak_u2[0], a.peak_u2[0], tol * a.peak_u2[0]) << to_string(stepper) << " f " << f;
      // control: without dividing fy the peak closing is clearly different (the yielding matters)
      if (f != 1.0) {
        const BatchResult c = run(yielding_pair(1.0), ag, stepper);
        EXPECT_GT(std::abs(f * c.peak_closing[0] - a.peak_closing[0]), 1e-3 * a.peak_closing[0]) << to_string(stepper);
      }
    }
}

}  // namespace
}  // namespace pounding
