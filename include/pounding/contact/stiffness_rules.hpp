#pragma once
// Impact-stiffness rules of the source papers (`pounding stiffness`, issue 26 §4) and the similitude factors of a
// shake-table model (`pounding similitude`). Pure functions in SI; no checking (the command checks its options).
//   impact-stiffness paper = ../shared/papers/impact-stiffness-linear-viscoelastic-experiment.txt (eqs 2-3, 5-9, 11-13)
//   M&D = muthukumar-desroches-2006-hertzdamp.txt (eqs 11-13); bridge paper = lindsay-2011-bridge-expansion-joints.txt
//   (eqs 7-9, Table 2); worked values: ../shared/research/seeds-models.md §1.3, §2.4-2.5, §4, §5 (V2, V5-V12).
#include <cmath>
#include <numbers>

namespace pounding::contact::rules {

// Maison & Kasai's axial stiffness of the member that hits (impact-stiffness paper eq. 5): k = E A / L (N/m).
inline double axial(double youngs_modulus, double area, double length) { return youngs_modulus * area / length; }

// Naserkhaki et al.: a multiple (50 to 100) of the lateral stiffness of the (stiffer) building (eq. 6).
inline double lateral_multiple(double lateral_stiffness, double multiple) { return multiple * lateral_stiffness; }

// Hertz stiffness of two equivalent spheres of one material (M&D eqs 11-13, bridge paper eqs 7-9):
// kh = 4/3 E* sqrt(R1 R2 / (R1 + R2)), 1/E* = 2 (1 - nu^2) / E (N/m^1.5).
inline double sphere_radius(double mass, double density) {
  return std::cbrt(3.0 * mass / (4.0 * std::numbers::pi * density));
}
inline double hertz_spheres(double r1, double r2, double youngs_modulus, double poisson) {
  const double h = (1.0 - poisson * poisson) / youngs_modulus;
  return 4.0 / (3.0 * (h + h)) * std::sqrt(r1 * r2 / (r1 + r2));
}

// Jankowski's steel-to-steel experimental stiffness, 482 kN/mm at full scale, times the length scale
// lambda = model / prototype (impact-stiffness paper §3: 482/30 = 16.07 kN/mm at 1/30).
inline constexpr double jankowski_steel_full_scale = 482.0e6;  // N/m
inline double jankowski_scaled(double lambda) { return jankowski_steel_full_scale * lambda; }

// Xu et al. (2016), impact-stiffness paper eq. 7: k = m_j / (m_i + m_j) k1 exp[(2 ln e / pi) asin(pi / sqrt(pi^2 +
// ln^2 e))], k1 the axial stiffness (eq. 5).
inline double xu(double k1, double m_i, double m_j, double e) {
  const double le = std::log(e), pi = std::numbers::pi;
  return m_j / (m_i + m_j) * k1 * std::exp(2.0 * le / pi * std::asin(pi / std::sqrt(pi * pi + le * le)));
}

// The impact-stiffness paper's own rule (eqs 11-13, §7): k = 20.66 kN/mm identified at 1/30 scale, scaled with the
// length scale: k = 20.66 x 30 lambda, rounded by the paper to 620 lambda kN/mm (its conclusion's rule, used here:
// 77.5 kN/mm at 1/8, 20.67 at 1/30).
inline constexpr double experimental_full_scale = 620.0e6;  // N/m
inline double experimental_scaled(double lambda) { return experimental_full_scale * lambda; }

// Linear viscoelastic damping (impact-stiffness paper eqs 2-3): xi = -ln e / sqrt(pi^2 + ln^2 e),
// C = 2 xi sqrt(k m_i m_j / (m_i + m_j)) (kg/s).
inline double kelvin_xi(double e) {
  const double le = std::log(e);
  return -le / std::sqrt(std::numbers::pi * std::numbers::pi + le * le);
}
inline double kelvin_c(double k, double m_i, double m_j, double xi) {
  return 2.0 * xi * std::sqrt(k * m_i * m_j / (m_i + m_j));
}

// Similitude of a shake-table model: ratios prototype / model of length N_h, time N_t and elastic modulus N_E.
// Acceleration N_a = N_h / N_t^2, velocity N_h / N_t, frequency 1 / N_t. Mass:
//   true replica (Dove et al. 1985, the bridge paper's "original" rule): N_m = N_E N_h^2 / N_a (= N_E N_h N_t^2),
//     every force scales as N_E N_h^2 and the stiffness of a member of the model material as N_E N_h;
//   adequate model with artificial mass (Moncarz & Krawinkler 1981, the bridge paper's "revised" rule, Table 2):
//     N_m = N_E N_h^2, the seismic mass decoupled from the structure's; the model's lateral stiffness must then be
//     N_m / N_t^2 (not N_E N_h) to keep the frequencies in 1 / N_t.
// In both: force N_F = N_m N_a and the dynamic (lateral, contact) stiffness N_K = N_m / N_t^2 = N_F / N_h.
enum class MassRule { true_replica, adequate };
struct Similitude {
  double length, time, modulus;             // given
  double acceleration, velocity, frequency;  // N_a, N_v, N_f (frequency: prototype / model = 1 / N_t)
  double mass, force, stiffness;             // N_m, N_F, N_K (dynamic)
  double member_stiffness;                   // N_E N_h: a geometrically scaled member of the model material
};
inline Similitude similitude(double n_h, double n_t, double n_e, MassRule rule) {
  Similitude s{};
  s.length = n_h, s.time = n_t, s.modulus = n_e;
  s.acceleration = n_h / (n_t * n_t);
  s.velocity = n_h / n_t;
  s.frequency = 1.0 / n_t;
  s.mass = rule == MassRule::true_replica ? n_e * n_h * n_h / s.acceleration : n_e * n_h * n_h;
  s.force = s.mass * s.acceleration;
  s.stiffness = s.mass / (n_t * n_t);
  s.member_stiffness = n_e * n_h;
  return s;
}

}  // namespace pounding::contact::rules
