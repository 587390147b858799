// Response spectra by the exact Nigam-Jennings recurrence (see spectrum.hpp).
#include "pounding/motion/spectrum.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pounding/core/error.hpp"
#include "pounding/core/progress.hpp"
#include "pounding/kernel/batch.hpp"

namespace pounding {

double peak_displacement(const Record& rec, double period, double zeta, double steps_per_period,
                         const std::atomic<bool>* stop) {
  if (!(period > 0)) return 0.0;
  const double w = 2.0 * std::numbers::pi / period;
  const auto sub = static_cast<int>(std::max(1.0, std::ceil(steps_per_period * rec.dt / period - 1e-9)));
  const double h = rec.dt / sub;
  const NigamJennings c = nigam_jennings(w, zeta, h);
  const auto& a = rec.acc;
  const std::size_t n = a.size();
  const auto tail = static_cast<std::size_t>(std::ceil(period / rec.dt)) + 1;
  double u = 0, v = 0, peak = 0;
  for (std::size_t k = 0; k + 1 < n + tail; ++k) {
    if (stop && (k & 4095) == 0 && stop->load(std::memory_order_relaxed)) throw Cancelled("the response spectrum");
    const double ag0 = k < n ? a[k] : 0.0, ag1 = k + 1 < n ? a[k + 1] : 0.0;
    for (int s = 0; s < sub; ++s) {
      // the record's linear segment evaluated at the sub-step ends (exact interpolation)
      const double p0 = ag0 + (ag1 - ag0) * s / sub, p1 = ag0 + (ag1 - ag0) * (s + 1) / sub;
      const double un = c.a11 * u + c.a12 * v + c.b11 * p0 + c.b12 * p1;
      const double vn = c.a21 * u + c.a22 * v + c.b21 * p0 + c.b22 * p1;
      u = un, v = vn;
      peak = std::max(peak, std::abs(u));
    }
  }
  return peak;
}

Spectrum response_spectrum(const Record& rec, std::span<const double> periods, double zeta,
                           const std::atomic<bool>* stop) {
  if (!(zeta >= 0 && zeta < 1))
    throw InputError(fmt::format("damping ratio {} is outside [0, 1)", zeta), "--damping", "give e.g. 0.05");
  if (!(rec.dt > 0) || rec.acc.empty()) throw InputError("empty record", rec.source, "read a record first");
  Spectrum s;
  s.zeta = zeta;
  s.periods.assign(periods.begin(), periods.end());
  for (double T : periods) {
    if (!(T >= 0) || !std::isfinite(T))
      throw InputError(fmt::format("period {} is not >= 0", T), "--periods", "give periods in seconds, >= 0");
    if (T == 0) {
      s.sd.push_back(0), s.psv.push_back(0), s.psa.push_back(rec.pga());
      continue;
    }
    const double w = 2.0 * std::numbers::pi / T, d = peak_displacement(rec, T, zeta, 40.0, stop);
    s.sd.push_back(d), s.psv.push_back(w * d), s.psa.push_back(w * w * d);
  }
  return s;
}

std::vector<double> default_periods() {
  std::vector<double> p{0.0};
  for (int i = 0; i < 100; ++i) p.push_back(0.01 * std::pow(1000.0, i / 99.0));
  return p;
}

}  // namespace pounding
