#pragma once
// Shared helpers of the kernel verification tests (tests/test_kernel_*.cpp). Only conveniences for
// driving run_batch; every reference solution lives in the test that uses it, written independently of
// the kernel's own formulas.
#include <cmath>
#include <numbers>
#include <vector>

#include "pounding/contact/model.hpp"
#include "pounding/physics/batch.hpp"

namespace pounding::test {

inline constexpr double pi = std::numbers::pi;
inline constexpr Stepper all_steppers[] = {Stepper::central_difference, Stepper::newmark, Stepper::rk4,
                                           Stepper::nigam_jennings};

inline ContactModel contact(ContactLaw law, DampingLaw damping = DampingLaw::lankarani_nikravesh) {
  ContactModel cm;
  cm.law = law;
  cm.damping = damping;
  return cm;
}

// Runs one pair; `series` (optional) records lane 0.
inline BatchResult run_one(const PairParams& p, const ContactModel& cm, const std::vector<double>& ag, double dt,
                           double duration, Stepper stepper, int substeps, bool energy = false,
                           SeriesRecorder* series = nullptr) {
  PairBatch b;
  b.resize(1);
  b.set(0, p);
  GroundMotion gm{dt, ag, duration};
  KernelSettings ks;
  ks.stepper = stepper;
  ks.substeps = substeps;
  ks.energy = energy;
  ks.series = series;
  BatchResult r;
  run_batch(b, cm, gm, ks, r);
  return r;
}

// A smooth two-tone ground motion sampled at dt (m/s^2).
inline std::vector<double> two_tone(double dt, double duration, double a1 = 3.0, double f1 = 1.1, double a2 = 2.0,
                                    double f2 = 2.7) {
  const long n = std::lround(duration / dt) + 1;
  std::vector<double> ag(static_cast<std::size_t>(n));
  for (long j = 0; j < n; ++j) {
    double t = static_cast<double>(j) * dt;
    ag[static_cast<std::size_t>(j)] = a1 * std::sin(2 * pi * f1 * t) + a2 * std::sin(2 * pi * f2 * t + 0.3);
  }
  return ag;
}

}  // namespace pounding::test
