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
// ---------------------------------------------------------------- per contact level (multi-storey buildings)
// A pair of shear buildings meets at its contact levels (where floors face floors within the level tolerance, or a
// floor faces the neighbour's column; with [contact] levels = "top" only the lower roof). Each code's design
// displacement is a first-mode value there: the linear analysis each clause names (ASCE 7-16 12.9.1 modal response
// spectrum, EN 1998-1 4.3.3.3 modal analysis, Standard 2800 dynamic analysis) gives, from the first mode alone,
// u(z) = Gamma1 phi1(z) Sd(T1) -- Gamma1 phi1(z) the building's own first-mode participation at height z from its
// mass and stiffness (model/modes.hpp, what `pounding modes` prints: with phi1 = 1 at the roof, Gamma1 phi1(roof) =
// gamma_roof) -- times each code's factors as above:
//   ASCE 7-16   delta_M(z) = (Cd / R) Gamma1 phi1(z) Sd(T1)          (12.8.6 / 12.9.1.4 Cd / Ie on Ie / R)
//   EN 1998-1   d_s(z) = q Gamma1 phi1(z) S_d(T1) g T1^2 / 4 pi^2     (4.3.4, eq. 4.23)
//   Standard    Delta_M(z) = (Cd / Ru) Gamma1 phi1(z) A B I g T1^2 / 4 pi^2
//   2800
// An SDOF (one storey) has Gamma1 phi1 = 1 at its one level: the values of code_design_rules. The coefficient rule
// is linear in height (Standard 2800's 0.005 h of each building at that level: coefficient (z1 + z2)); it needs no
// mode. Combinations as above: separate lots/properties the sum, same property SRSS, EN 1998-1 4.4.2.7(3) 0.7 SRSS
// only where the two floors' levels coincide (a floor-to-floor level).
struct ContactLevel {
  std::string label;              // "level 4/5" (model::shear_buildings' element label)
  double z1 = 0, z2 = 0;          // m above the ground: each building's point of contact (a column side: the striking floor's level)
  double gphi1 = 1, gphi2 = 1;    // Gamma1 phi1 at that point (a column side: interpolated between its floors)
  bool floors_coincide = true;    // floor to floor (not a floor against a column)
};

struct LevelRow {
  std::string rule, clause, combination;  // the row's name, its clause, "ABS" | "SRSS" | "0.7 SRSS"
  double d1 = 0, d2 = 0;                  // each building's displacement at the level (m)
  double gap = 0;                         // the required separation (m)
};

// Each building's first-mode inputs of a code at period T (for the report's hand-check table): Sa in g (the code's
// design spectrum value the displacement takes), Sd = Sa g T^2 / 4 pi^2 (m), and the factor f such that the code's
// displacement at z is f Gamma1 phi1(z) Sd: ASCE Cd / R, EC8 q, Standard 2800 Cd / Ru (with its I inside Sa).
struct ModalInputs {
  double sa_g = 0, sd = 0, factor = 0;
};
ModalInputs code_modal_inputs(const TargetSpectrumSpec& spec, const BuildingCode& b);

// The rows of one contact level: the coefficient rule (coefficient > 0) and the design rows of the study's spectrum
// code (none without a spectrum or the factors: code_design_rules' notes say why), in code_design_rules' order.
std::vector<LevelRow> code_level_rows(const TargetSpectrumSpec* spec, const BuildingCode& b1, const BuildingCode& b2,
                                      const ContactLevel& level, double coefficient);

}  // namespace pounding::separation
