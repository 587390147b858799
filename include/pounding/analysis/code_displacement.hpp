#pragma once
// The codes' own design displacements and the separations they give (issue 23 item 5), beside the rules of
// separation.hpp that are fed the records' mean peaks. A building is an SDOF here, so each design displacement is
// the first-mode (SDOF) value at the building's period T from the study's design spectrum ([target_spectrum]),
// with the elastic spectral displacement Sd = Sa g (T / 2 pi)^2 (g = 9.80665 m/s^2):
//
//   ASCE 7-16   12.8.6: delta_x = Cd delta_xe / Ie (eq. 12.8-15), delta_xe the elastic displacement under the
//               strength-level design forces, Cs = Sa(T) / (R / Ie) (12.8.1.1; the Cs minimum of eq. 12.8-5 need
//               not be applied for drift, 12.8.6.1): delta_xe = (Ie / R) Sd, so delta_M = Cd Sd / R (Ie cancels).
//               12.12.3: same property delta_MT = sqrt(delta_M1^2 + delta_M2^2); separate lots each building is
//               set back from the property line by its own delta_M, so delta_M1 + delta_M2.
//   EN 1998-1   4.3.4: d_s = q_d d_e (eq. 4.23), q_d = q, d_e from the linear analysis with the design spectrum
//               S_d(T) of eqs. 3.13-3.16 (beta = 0.2): d_e = S_d(T) g (T / 2 pi)^2. 4.4.2.7: separate properties
//               d_s1 + d_s2 (each from the boundary), same property SRSS, x 0.7 where floor levels coincide.
//   Standard    (4th ed.) design drift Delta_M = Cd Delta_eu, Delta_eu under the design forces C = A B I / Ru:
//   2800        Delta_eu = A B I g (T / 2 pi)^2 / Ru. Buildings of at most 8 storeys and not of high or very
//               high importance (I = 1.2, 1.4) keep 0.005 h from the property line (the coefficient rule of
//               separation.hpp); the others need the joint from the design drift, each building by its own
//               Delta_M from the property line: Delta_M1 + Delta_M2. P-Delta is not included (the SDOF model has
//               none). research/fragility-and-codes.md sections 0.3 and 4.
#include <string>
#include <vector>

#include "pounding/analysis/separation.hpp"
#include "pounding/motion/target_spectrum.hpp"

namespace pounding::separation {

inline constexpr double standard_gravity = 9.80665;  // m/s^2

// Sd = Sa g T^2 / (4 pi^2) in m, Sa in g, T in s.
double spectral_displacement(double sa_g, double period);

// ASCE 7-16 delta_M = Cd delta_xe / Ie with delta_xe = (Ie / R) Sd(T), m.
double asce7_design_displacement(const Asce7Spectrum& s, double period, double r, double cd, double ie);
// EN 1998-1 design spectrum S_d(T) in g (eqs. 3.13-3.16, beta = 0.2; ag = gammaI agR; no eta).
double ec8_design_sa(const Ec8Spectrum& s, double q, double period);
// EN 1998-1 d_s = q d_e, m.
double ec8_design_displacement(const Ec8Spectrum& s, double q, double period);
// Standard 2800 Delta_M = Cd A B I g (T / 2 pi)^2 / Ru, m, with the building's importance I.
double s2800_design_displacement(const Iran2800Spectrum& s, double importance, double ru, double cd, double period);

// One building as the codes see it: its period and height (medians over a study's models) and its factors
// (sampling/code_factors.hpp; 0 = not given).
struct BuildingCode {
  double T = 0, height = 0;
  double asce7_r = 0, asce7_cd = 0, asce7_ie = 0;
  double ec8_q = 0;
  double s2800_ru = 0, s2800_cd = 0, s2800_importance = 0;
  long storeys = 0;               // given, or 0: from height / storey_height
  double storey_height = 0;       // 0: code_factors.hpp's default, 3.2 m
  long resolved_storeys() const;  // storeys, or max(1, round(height / storey_height))
};

// Whether Standard 2800's 0.005 h rule applies to the pair: both buildings of at most 8 storeys and of
// ordinary importance (I not 1.2 or 1.4; not known counts as ordinary, and `reason` says so).
struct Scope {
  bool inside = true;
  std::string reason;  // "building 2 has 10 storeys (> 8)"; the assumptions when inside
};
Scope s2800_coefficient_scope(const BuildingCode& b1, const BuildingCode& b2, double target_importance);

struct CodeDesign {
  std::vector<Rule> rules;         // the design-displacement rows, in metres
  std::vector<std::string> notes;  // why a code has no rows (no spectrum of that code, factors missing)
};
// The rows of the code whose design spectrum the study gives (spec; a csv spectrum is not a code's and gives
// none) for the buildings whose factors are given; `spec` null: no design spectrum.
CodeDesign code_design_rules(const TargetSpectrumSpec* spec, const BuildingCode& b1, const BuildingCode& b2);

}  // namespace pounding::separation
