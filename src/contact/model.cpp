// Contact models: the damping laws' xi(e), Hertzdamp's calibrated damping and restitution, names and checks.
#include "pounding/contact/model.hpp"

#include <charconv>
#include <iterator>
#include <cmath>
#include <string>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "pounding/core/error.hpp"

namespace pounding {

namespace {
// The shortest text that reads back as x (what fmt's "{}" prints), without fmt in the contact layer.
std::string shortest(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}
}  // namespace

namespace xibar {
double lankarani_nikravesh(double e, double) { return 3.0 * (1.0 - e * e) / 4.0; }
double hunt_crossley(double e, double) { return 3.0 * (1.0 - e) / 2.0; }
double flores(double e, double) { return 8.0 * (1.0 - e) / (5.0 * e); }
double hu_guo(double e, double) { return 3.0 * (1.0 - e) / (2.0 * e); }
double gonthier(double e, double) { return (1.0 - e * e) / e; }
double calibrated(double e, double n) { return calibrated_xibar(e, n); }
}  // namespace xibar

double hertzdamp_xibar(DampingLaw law, double e, double n) {
  if (static_cast<std::size_t>(law) >= std::size(damping_laws)) throw std::logic_error("hertzdamp_xibar: bad law");
  return damping_law(law).xibar(e, n);
}

double hertzdamp_restitution(double xi, double n) {
  // Scale-free single impact: x'' = -max(0, x^n (1 + xi x')), x(0) = 0, x'(0) = 1. Classical RK4 with a
  // fine fixed step; the exit (x back to 0) is located by cubic Hermite interpolation within the last step.
  // Once the force has vanished with x > 0 (x' <= -1/xi), the bodies fly apart at constant speed.
  auto acc = [&](double x, double v) {
    if (x <= 0.0) return 0.0;
    double f = std::pow(x, n) * (1.0 + xi * v);
    return f > 0.0 ? -f : 0.0;
  };
  const double h = 2e-4;
  double x = 0.0, v = 1.0;
  for (int step = 0; step < 10'000'000; ++step) {
    double k1x = v, k1v = acc(x, v);
    double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    double xn = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    double vn = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xn <= 0.0 && step > 0) {
      // exit inside this step: locate x(s) = 0 on the Hermite cubic, return the interpolated speed
      double lo = 0.0, hi = 1.0;
      auto herm = [&](double s) {
        double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
        double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
        return h00 * x + h10 * h * v + h01 * xn + h11 * h * vn;
      };
      for (int it = 0; it < 60; ++it) {
        double mid = 0.5 * (lo + hi);
        (herm(mid) > 0.0 ? lo : hi) = mid;
      }
      double s = 0.5 * (lo + hi);
      double dh00 = (6 * s * s - 6 * s) / h, dh10 = 3 * s * s - 4 * s + 1;
      double dh01 = (-6 * s * s + 6 * s) / h, dh11 = 3 * s * s - 2 * s;
      double vs = dh00 * x + dh10 * v + dh01 * xn + dh11 * vn;
      return -vs;
    }
    if (xi > 0.0 && x > 0.0 && 1.0 + xi * vn <= 0.0 && vn < 0.0) return -vn;  // force gone: free flight
    x = xn;
    v = vn;
  }
  throw std::runtime_error("hertzdamp_restitution: impact did not end");
}

double calibrated_xibar(double e, double n) {
  if (!(e > 0.0 && e <= 1.0)) throw InputError("e = " + shortest(e) + " is out of range", "e", "give 0 < e <= 1");
  if (e == 1.0) return 0.0;
  // e(xi) falls monotonically from 1 at xi = 0. Bracket, then secant-safeguarded bisection.
  double lo = 0.0, e_lo = 1.0;
  double hi = 1.0, e_hi = hertzdamp_restitution(hi, n);
  while (e_hi > e) {
    lo = hi;
    e_lo = e_hi;
    hi *= 2.0;
    e_hi = hertzdamp_restitution(hi, n);
    if (hi > 1e6) throw std::runtime_error("calibrated_xibar: cannot bracket e");
  }
  double xi = hi;
  for (int it = 0; it < 100; ++it) {
    double guess = lo + (e_lo - e) * (hi - lo) / (e_lo - e_hi);  // regula falsi
    double mid = 0.5 * (lo + hi);
    xi = (it % 3 == 2) ? mid : guess;  // Illinois-free safeguard: bisect every third step
    double ex = hertzdamp_restitution(xi, n);
    if (std::abs(ex - e) < 1e-12 || hi - lo < 1e-13 * hi) break;
    if (ex > e) {
      lo = xi;
      e_lo = ex;
    } else {
      hi = xi;
      e_hi = ex;
    }
  }
  return xi;
}

double kelvin_damping_ratio(double e) {
  double le = std::log(e);
  return -le / std::sqrt(std::numbers::pi * std::numbers::pi + le * le);
}

double jankowski_zeta(double e) {
  return 9.0 * std::sqrt(5.0) / 2.0 * (1.0 - e * e) / (e * (e * (9.0 * std::numbers::pi - 16.0) + 16.0));
}

double hertz_stiffness_spheres(double m1, double m2, double density, double youngs_modulus, double poisson) {
  require_positive(m1, "m1");
  require_positive(m2, "m2");
  require_positive(density, "contact density");
  require_positive(youngs_modulus, "contact Young's modulus");
  require_range(poisson, 0.0, 0.4999, "contact Poisson ratio", "[0, 0.5)");
  auto radius = [&](double m) { return std::cbrt(3.0 * m / (4.0 * std::numbers::pi * density)); };  // eq. 13
  double r1 = radius(m1), r2 = radius(m2);
  double hm = (1.0 - poisson * poisson) / youngs_modulus;                                            // eq. 12
  return 4.0 / (3.0 * (hm + hm)) * std::sqrt(r1 * r2 / (r1 + r2));                                // eq. 11
}

double hertz_peak_penetration(double meff, double v0, double kh) {
  return std::pow(5.0 * meff * v0 * v0 / (4.0 * kh), 0.4);
}

double hertz_contact_duration(double meff, double v0, double kh) {
  // 2 * int_0^1 dx / sqrt(1 - x^{5/2}) = 2 * (2/5) B(2/5, 1/2)
  double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  return 2.0 * 0.4 * beta * hertz_peak_penetration(meff, v0, kh) / v0;
}

}  // namespace pounding
