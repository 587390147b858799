#pragma once
// Linear elastic response spectra of a record: u'' + 2 zeta w u' + w^2 u = -ag(t), ag linear between
// samples, solved with the exact Nigam-Jennings recurrence (kernel.hpp). For each period the step is
// the record step divided into s equal sub-steps with h <= T / 40 (ag stays the same piecewise-linear
// signal, so the recurrence stays exact; the sub-steps only make the sampled peak of |u| fall within
// (pi/40)^2/2 = 0.3 % of the continuous peak). After the record the oscillator runs one more period in
// free vibration (ag = 0), where a late peak of a long-period oscillator can occur.
//   SD = max |u|,  PSV = w SD,  PSA = w^2 SD;  T = 0 gives PSA = PGA (rigid oscillator).
#include <atomic>
#include <span>
#include <vector>

#include "pounding/motion/records.hpp"

namespace pounding {

struct Spectrum {
  double zeta = 0.05;
  std::vector<double> periods;  // s
  std::vector<double> sd;       // m
  std::vector<double> psv;      // m/s
  std::vector<double> psa;      // m/s^2
};

// Throws InputError unless 0 <= zeta < 1 and every period >= 0 and finite. `stop` (optional): raised, the call ends
// within 4096 record samples of one oscillator and throws Cancelled (core/progress.hpp).
Spectrum response_spectrum(const Record& rec, std::span<const double> periods, double zeta = 0.05,
                           const std::atomic<bool>* stop = nullptr);
// Peak |u| of one oscillator (the building block of response_spectrum); the peak is sampled at
// least `steps_per_period` times per period (40 in response_spectrum).
double peak_displacement(const Record& rec, double period, double zeta, double steps_per_period = 40.0,
                         const std::atomic<bool>* stop = nullptr);
// 0 and 100 log-spaced periods from 0.01 s to 10 s (the grid `pounding records spectrum` writes).
std::vector<double> default_periods();

}  // namespace pounding
