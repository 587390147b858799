// A contact law replayed on imposed kinematics (penetration and its rate against time).
#include "pounding/physics/replay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pounding/contact/registry.hpp"

namespace pounding::physics {

std::vector<double> differentiate(const std::vector<double>& t, const std::vector<double>& y) {
  const std::size_t n = t.size();
  std::vector<double> d(n, 0.0);
  if (n < 2) return d;
  d[0] = (y[1] - y[0]) / (t[1] - t[0]);
  d[n - 1] = (y[n - 1] - y[n - 2]) / (t[n - 1] - t[n - 2]);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double hl = t[i] - t[i - 1], hr = t[i + 1] - t[i];
    d[i] = (hl * hl * y[i + 1] + (hr * hr - hl * hl) * y[i] - hr * hr * y[i - 1]) / (hl * hr * (hl + hr));
  }
  return d;
}

namespace {

template <class L, class Exp>
ReplayResult run(const ReplayInput& in, const ReplaySettings& s, Exp n) {
  const std::size_t N = in.t.size();
  const double kc = s.kc * contact::stiffness_factor(s.cm);
  auto damping = [&](double e) { return L::damping_constant(s.cm, kc, e, s.meff); };
  ReplayResult r;
  r.force.assign(N, 0.0);
  r.impact.assign(N, 0);
  contact::State<double> st{0.0};
  double cd = s.curve ? 0.0 : damping(s.e);
  for (std::size_t i = 0; i < N; ++i) {
    const double d = in.d[i], dd = in.dd[i];
    if (!(d > 0.0)) continue;
    const bool onset = i == 0 || !(in.d[i - 1] > 0.0);
    if (onset) {
      ReplayImpact im;
      im.first = i;
      im.t_start = in.t[i];
      double approach = dd;  // at the interpolated closing instant between samples i-1 and i
      if (i > 0) {
        const double sc = std::clamp(-in.d[i - 1] / (d - in.d[i - 1]), 0.0, 1.0);
        approach = in.dd[i - 1] + sc * (dd - in.dd[i - 1]);
      }
      im.v0 = std::max(approach, s.cm.v0_min);
      if constexpr (L::traits.latches_v0) L::template on_onset<double>(st, true, approach, s.cm.v0_min);
      im.e = s.e;
      if (s.curve) {
        im.e = (*s.curve)(im.v0);
        im.outside_valid = !s.curve->in_range(im.v0);
        im.clamped = s.curve->clamped(im.v0);
        cd = damping(im.e);
      }
      r.impacts.push_back(im);
    }
    ReplayImpact& im = r.impacts.back();
    im.last = i;
    im.t_end = in.t[i];
    r.impact[i] = static_cast<int>(r.impacts.size());
    contact::Shared<double> sh{0.0};
    double clamp = 0.0;
    const double F = L::template force<double>({d, dd}, {kc, cd}, st, n, sh, clamp);
    r.force[i] = F;
    r.clamps += clamp > 0.0 ? 1 : 0;
    im.peak_force = std::max(im.peak_force, F);
    im.peak_penetration = std::max(im.peak_penetration, d);
  }
  return r;
}

// Work of the contact force on each impact's segments (trapezoid in d), the samples just outside the contact
// included (their force is 0); the measured peaks and the error metrics.
void integrate(const ReplayInput& in, ReplayResult& r) {
  const std::size_t N = in.t.size();
  const bool meas = !in.measured.empty();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (ReplayImpact& im : r.impacts) {
    const std::size_t a = im.first > 0 ? im.first - 1 : 0, b = std::min(im.last + 1, N - 1);
    for (std::size_t i = a; i < b; ++i) {
      const double w = 0.5 * (r.force[i] + r.force[i + 1]) * (in.d[i + 1] - in.d[i]);
      (w >= 0.0 ? im.work_approach : im.work_restitution) += w >= 0.0 ? w : -w;
    }
    im.energy_dissipated = im.work_approach - im.work_restitution;
    im.measured_peak = nan, im.peak_error_pct = nan;
    if (meas) {
      im.measured_peak = *std::max_element(in.measured.begin() + static_cast<std::ptrdiff_t>(im.first),
                                           in.measured.begin() + static_cast<std::ptrdiff_t>(im.last) + 1);
      im.peak_error_pct = std::abs(im.measured_peak - im.peak_force) / im.measured_peak * 100.0;
    }
    r.peak_force = std::max(r.peak_force, im.peak_force);
    r.energy_dissipated += im.energy_dissipated;
  }
  r.measured_peak = r.peak_error_pct = r.mean_abs_difference = r.rms_difference = nan;
  if (!meas) return;
  r.measured_peak = *std::max_element(in.measured.begin(), in.measured.end());
  r.peak_error_pct = std::abs(r.measured_peak - r.peak_force) / r.measured_peak * 100.0;
  double abs_int = 0.0, sq_int = 0.0;
  for (std::size_t i = 0; i + 1 < N; ++i) {
    const double h = in.t[i + 1] - in.t[i];
    const double a = r.force[i] - in.measured[i], b = r.force[i + 1] - in.measured[i + 1];
    abs_int += 0.5 * h * (std::abs(a) + std::abs(b));
    sq_int += 0.5 * h * (a * a + b * b);
  }
  const double T = in.t.back() - in.t.front();
  r.mean_abs_difference = abs_int / T;
  r.rms_difference = std::sqrt(sq_int / T);
}

}  // namespace

ReplayResult replay(const ReplayInput& in, const ReplaySettings& s) {
  ReplayResult r = contact::visit_law(s.cm.law, [&]<class L>() -> ReplayResult {
    if constexpr (!L::traits.has_force) {
      return ReplayResult{};
    } else if (s.cm.n == 1.5) {
      return run<L>(in, s, contact::Exp15{});
    } else {
      return run<L>(in, s, contact::RuntimeExponent{s.cm.n});
    }
  });
  if (r.force.size() != in.t.size()) {
    r.force.assign(in.t.size(), 0.0);
    r.impact.assign(in.t.size(), 0);
  }
  integrate(in, r);
  return r;
}

}  // namespace pounding::physics
