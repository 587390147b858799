// The codes' own design displacements and separations: see code_displacement.hpp.
#include "pounding/analysis/code_displacement.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace pounding::separation {

double spectral_displacement(double sa_g, double period) {
  return sa_g * standard_gravity * period * period / (4.0 * std::numbers::pi * std::numbers::pi);
}

double asce7_design_displacement(const Asce7Spectrum& s, double period, double r, double cd, double ie) {
  const double delta_xe = ie / r * spectral_displacement(sa(s, period), period);  // under Cs = Sa / (R / Ie)
  return cd * delta_xe / ie;                                                      // eq. 12.8-15
}

double ec8_design_sa(const Ec8Spectrum& s, double q, double period) {
  const Ec8GroundParams p = ec8_ground_params(s.type, s.ground);
  const double ag = s.importance * s.agr, beta = 0.2;
  if (period <= p.tb) return ag * p.s * (2.0 / 3.0 + period / p.tb * (2.5 / q - 2.0 / 3.0));  // eq. 3.13
  if (period <= p.tc) return ag * p.s * 2.5 / q;                                              // eq. 3.14
  if (period <= p.td) return std::max(ag * p.s * 2.5 / q * p.tc / period, beta * ag);        // eq. 3.15
  return std::max(ag * p.s * 2.5 / q * p.tc * p.td / (period * period), beta * ag);          // eq. 3.16
}

double ec8_design_displacement(const Ec8Spectrum& s, double q, double period) {
  return q * spectral_displacement(ec8_design_sa(s, q, period), period);  // eq. 4.23, q_d = q
}

double s2800_design_displacement(const Iran2800Spectrum& s, double importance, double ru, double cd, double period) {
  Iran2800Spectrum b = s;
  b.importance = importance;
  return cd * spectral_displacement(sa(b, period), period) / ru;
}

long BuildingCode::resolved_storeys() const {
  if (storeys > 0) return storeys;
  const double sh = storey_height > 0 ? storey_height : 3.2;
  return std::max(1L, std::lround(height / sh));
}

namespace {

// "10 storeys (> 8; height 32 m / storey height 3.2 m)"
std::string storeys_text(const BuildingCode& b) {
  return b.storeys > 0 ? fmt::format("{} storeys (> 8)", b.storeys)
                       : fmt::format("{} storeys (> 8; height {:.3g} m / storey height {:g} m)", b.resolved_storeys(),
                                     b.height, b.storey_height > 0 ? b.storey_height : 3.2);
}

}  // namespace

Scope s2800_coefficient_scope(const BuildingCode& b1, const BuildingCode& b2, double target_importance) {
  Scope s;
  std::vector<std::string> outside, assumed;
  for (int i = 0; i < 2; ++i) {
    const BuildingCode& b = i == 0 ? b1 : b2;
    const long n = b.resolved_storeys();
    if (n > 8) outside.push_back(fmt::format("building {} has {}", i + 1, storeys_text(b)));
    const double imp = b.s2800_importance > 0 ? b.s2800_importance : target_importance;
    if (imp >= 1.2 - 1e-9)
      outside.push_back(fmt::format("building {} is of {} importance (I = {:g})", i + 1, imp > 1.3 ? "very high" : "high", imp));
    if (imp <= 0) assumed.push_back(fmt::format("building {} of ordinary importance (s2800_importance not given)", i + 1));
  }
  s.inside = outside.empty();
  std::string text;
  for (const auto& o : s.inside ? assumed : outside) text += (text.empty() ? "" : "; ") + o;
  s.reason = text;
  return s;
}

namespace {

std::string m(double v) { return fmt::format("{:.4f} m", v); }

void pair_rows(CodeDesign& out, const std::string& code, const std::string& symbol, double d1, double d2,
               const std::string& how, bool coincide_row, const std::string& same, const std::string& separate) {
  const std::string values = fmt::format("{}1 = {}, {}2 = {}; {}", symbol, m(d1), symbol, m(d2), how);
  out.rules.push_back({code + " design, separate lots", separate + "; " + values,
                       symbol + "1 + " + symbol + "2", d1 + d2});
  out.rules.push_back({code + " design, same property", same + "; " + values,
                       fmt::format("sqrt({0}1^2 + {0}2^2)", symbol), std::hypot(d1, d2)});
  if (coincide_row)
    out.rules.push_back({code + " design, same property, floor levels coincide",
                         "EN 1998-1 sec. 4.4.2.7(3): 0.7 x the SRSS distance; " + values,
                         fmt::format("0.7 sqrt({0}1^2 + {0}2^2)", symbol), 0.7 * std::hypot(d1, d2)});
}

}  // namespace

namespace {

const char* const sdof = "SDOF (first-mode) value at the building's period from the design spectrum";

std::string periods_text(const BuildingCode& b1, const BuildingCode& b2) {
  return fmt::format("T1 = {:.3f} s, T2 = {:.3f} s", b1.T, b2.T);
}

void asce7_rows(CodeDesign& out, const TargetSpectrumSpec& spec, const BuildingCode& b1, const BuildingCode& b2) {
  const double ie1 = b1.asce7_ie > 0 ? b1.asce7_ie : 1.0, ie2 = b2.asce7_ie > 0 ? b2.asce7_ie : 1.0;
  const double d1 = asce7_design_displacement(spec.asce7, b1.T, b1.asce7_r, b1.asce7_cd, ie1);
  const double d2 = asce7_design_displacement(spec.asce7, b2.T, b2.asce7_r, b2.asce7_cd, ie2);
  const std::string how = fmt::format(
      "delta_M = Cd delta_e / Ie (sec. 12.8.6), delta_e = (Ie/R) Sa(T) g T^2/4pi^2, the {} ({}; building 1: R = {:g}, "
      "Cd = {:g}, Ie = {:g}; building 2: R = {:g}, Cd = {:g}, Ie = {:g})",
      sdof, periods_text(b1, b2), b1.asce7_r, b1.asce7_cd, ie1, b2.asce7_r, b2.asce7_cd, ie2);
  pair_rows(out, "ASCE 7-16", "dM", d1, d2, how, false,
            "ASCE 7-16 sec. 12.12.3 design displacements, same property: delta_MT = sqrt(delta_M1^2 + delta_M2^2)",
            "ASCE 7-16 sec. 12.12.3 design displacements, separate lots: each set back from the property line by its "
            "own delta_M");
}

void ec8_rows(CodeDesign& out, const TargetSpectrumSpec& spec, const BuildingCode& b1, const BuildingCode& b2) {
  const double d1 = ec8_design_displacement(spec.ec8, b1.ec8_q, b1.T);
  const double d2 = ec8_design_displacement(spec.ec8, b2.ec8_q, b2.T);
  const std::string how =
      fmt::format("d_s = q_d d_e (EN 1998-1 sec. 4.3.4, eq. 4.23, q_d = q), d_e = S_d(T) g T^2/4pi^2 from the design "
                  "spectrum (eqs. 3.13-3.16, beta = 0.2), the {} ({}; q1 = {:g}, q2 = {:g})",
                  sdof, periods_text(b1, b2), b1.ec8_q, b2.ec8_q);
  pair_rows(out, "EC8", "ds", d1, d2, how, true, "EN 1998-1 sec. 4.4.2.7(2)b design displacements, same property: SRSS",
            "EN 1998-1 sec. 4.4.2.7(2)a design displacements, separate properties: each from the boundary by its own "
            "d_s");
}

void s2800_rows(CodeDesign& out, const TargetSpectrumSpec& spec, const BuildingCode& b1, const BuildingCode& b2) {
  const double i1 = b1.s2800_importance > 0 ? b1.s2800_importance : spec.iran2800.importance;
  const double i2 = b2.s2800_importance > 0 ? b2.s2800_importance : spec.iran2800.importance;
  const double d1 = s2800_design_displacement(spec.iran2800, i1, b1.s2800_ru, b1.s2800_cd, b1.T);
  const double d2 = s2800_design_displacement(spec.iran2800, i2, b2.s2800_ru, b2.s2800_cd, b2.T);
  out.rules.push_back(
      {"Standard 2800 design drift joint",
       fmt::format("Standard 2800 (4th ed.): each building from the property line by its design drift Delta_M = Cd "
                   "Delta_eu, Delta_eu = A B I g T^2/(4pi^2 Ru), the {} (P-Delta not included); Delta_M1 = {}, "
                   "Delta_M2 = {} ({}; building 1: Ru = {:g}, Cd = {:g}, I = {:g}; building 2: Ru = {:g}, Cd = {:g}, "
                   "I = {:g})",
                   sdof, m(d1), m(d2), periods_text(b1, b2), b1.s2800_ru, b1.s2800_cd, i1, b2.s2800_ru, b2.s2800_cd, i2),
       "DM1 + DM2", d1 + d2});
}

// The notes on factors given for one building only, or for a code other than the spectrum's.
void factor_notes(CodeDesign& out, const TargetSpectrumSpec* spec, const BuildingCode& b1, const BuildingCode& b2) {
  struct Code {
    TargetCode code;
    const char* name;
    const char* keys;
    bool one, both;
  };
  const Code codes[] = {
      {TargetCode::asce7_16, "ASCE 7-16", "asce7_r/asce7_cd", b1.asce7_r > 0 || b2.asce7_r > 0, b1.asce7_r > 0 && b2.asce7_r > 0},
      {TargetCode::ec8, "EC8", "ec8_q", b1.ec8_q > 0 || b2.ec8_q > 0, b1.ec8_q > 0 && b2.ec8_q > 0},
      {TargetCode::iran2800, "Standard 2800", "s2800_ru/s2800_cd", b1.s2800_ru > 0 || b2.s2800_ru > 0,
       b1.s2800_ru > 0 && b2.s2800_ru > 0}};
  for (const Code& c : codes) {
    if (c.one && !c.both)
      out.notes.push_back(fmt::format("{}: {} is given for one building only; give it for both", c.name, c.keys));
    if (c.one && spec && spec->code != c.code)
      out.notes.push_back(fmt::format("{} factors are given but the design spectrum is {}: no {} design displacements",
                                      c.name, to_string(spec->code), c.name));
  }
}

}  // namespace

CodeDesign code_design_rules(const TargetSpectrumSpec* spec, const BuildingCode& b1, const BuildingCode& b2) {
  CodeDesign out;
  factor_notes(out, spec, b1, b2);
  if (!spec) {
    out.notes.push_back(
        "The study gives no design spectrum ([target_spectrum], with [records] select), so there are no code design "
        "displacements: the rows above feed the codes' formulas the records' mean peaks");
    return out;
  }
  switch (spec->code) {
    case TargetCode::asce7_16:
      if (b1.asce7_r > 0 && b2.asce7_r > 0) asce7_rows(out, *spec, b1, b2);
      else
        out.notes.push_back("ASCE 7-16 design displacements need asce7_r and asce7_cd (Table 12.2-1) and asce7_ie "
                            "(Table 1.5-2, default 1.0) in [structures.building1] and [structures.building2]");
      break;
    case TargetCode::ec8:
      if (b1.ec8_q > 0 && b2.ec8_q > 0) ec8_rows(out, *spec, b1, b2);
      else
        out.notes.push_back("EC8 design displacements need ec8_q (the behaviour factor) in [structures.building1] "
                            "and [structures.building2]");
      break;
    case TargetCode::iran2800:
      if (b1.s2800_ru > 0 && b2.s2800_ru > 0) s2800_rows(out, *spec, b1, b2);
      else
        out.notes.push_back("Standard 2800 design drifts need s2800_ru and s2800_cd (table 3-4) in "
                            "[structures.building1] and [structures.building2]");
      break;
    case TargetCode::csv:
      out.notes.push_back("The study's design spectrum is a table (code = \"csv\"), not a code's: no code design "
                          "displacements");
      break;
  }
  return out;
}

ModalInputs code_modal_inputs(const TargetSpectrumSpec& spec, const BuildingCode& b) {
  ModalInputs x;
  switch (spec.code) {
    case TargetCode::asce7_16:
      x.sa_g = sa(spec.asce7, b.T), x.factor = b.asce7_r > 0 ? b.asce7_cd / b.asce7_r : NAN;
      break;
    case TargetCode::ec8:
      x.sa_g = b.ec8_q > 0 ? ec8_design_sa(spec.ec8, b.ec8_q, b.T) : NAN, x.factor = b.ec8_q > 0 ? b.ec8_q : NAN;
      break;
    case TargetCode::iran2800: {
      Iran2800Spectrum s = spec.iran2800;
      s.importance = b.s2800_importance > 0 ? b.s2800_importance : spec.iran2800.importance;
      x.sa_g = sa(s, b.T), x.factor = b.s2800_ru > 0 ? b.s2800_cd / b.s2800_ru : NAN;
      break;
    }
    case TargetCode::csv: return {NAN, NAN, NAN};
  }
  x.sd = spectral_displacement(x.sa_g, b.T);
  return x;
}

std::vector<LevelRow> code_level_rows(const TargetSpectrumSpec* spec, const BuildingCode& b1, const BuildingCode& b2,
                                      const ContactLevel& L, double coefficient) {
  std::vector<LevelRow> rows;
  if (coefficient > 0) {
    const bool s2800 = coefficient == 0.005;
    rows.push_back({s2800 ? "Standard 2800 0.005 h at the level" : "coefficient rule at the level",
                    s2800 ? "Standard 2800 (4th ed.): each building (up to 8 storeys) 0.005 x its height at the level "
                            "from the property line; linear in height, no mode"
                          : "[structures] code_gap_coefficient x each building's height at the level; linear in height",
                    "ABS", coefficient * L.z1, coefficient * L.z2, coefficient * (L.z1 + L.z2)});
  }
  if (!spec || spec->code == TargetCode::csv) return rows;
  const ModalInputs x1 = code_modal_inputs(*spec, b1), x2 = code_modal_inputs(*spec, b2);
  if (!(x1.factor > 0) || !(x2.factor > 0)) return rows;  // code_design_rules' notes say which factors are missing
  const double d1 = x1.factor * L.gphi1 * x1.sd, d2 = x2.factor * L.gphi2 * x2.sd;
  const auto both = [&](const std::string& code, const std::string& separate, const std::string& same) {
    rows.push_back({code + " design, separate lots", separate, "ABS", d1, d2, d1 + d2});
    rows.push_back({code + " design, same property", same, "SRSS", d1, d2, std::hypot(d1, d2)});
  };
  switch (spec->code) {
    case TargetCode::asce7_16:
      both("ASCE 7-16",
           "ASCE 7-16 sec. 12.12.3, each building set back from the property line by its delta_M(z) = (Cd / R) "
           "Gamma1 phi1(z) Sd(T1) (12.8.6, 12.9.1, first mode)",
           "ASCE 7-16 sec. 12.12.3, delta_MT = sqrt(delta_M1^2 + delta_M2^2), delta_M(z) = (Cd / R) Gamma1 phi1(z) "
           "Sd(T1) (12.8.6, 12.9.1, first mode)");
      break;
    case TargetCode::ec8:
      both("EC8",
           "EN 1998-1 sec. 4.4.2.7(2)a, each building from the boundary by its d_s(z) = q Gamma1 phi1(z) S_d(T1) g "
           "T1^2/4pi^2 (4.3.4 eq. 4.23, 4.3.3.3 first mode)",
           "EN 1998-1 sec. 4.4.2.7(2)b, SRSS of d_s(z) = q Gamma1 phi1(z) S_d(T1) g T1^2/4pi^2 (4.3.4 eq. 4.23, "
           "4.3.3.3 first mode)");
      if (L.floors_coincide)
        rows.push_back({"EC8 design, same property, floor levels coincide",
                        "EN 1998-1 sec. 4.4.2.7(3), 0.7 x the SRSS distance where the floor levels coincide",
                        "0.7 SRSS", d1, d2, 0.7 * std::hypot(d1, d2)});
      break;
    case TargetCode::iran2800:
      rows.push_back({"Standard 2800 design drift joint",
                      "Standard 2800 (4th ed.), each building from the property line by its Delta_M(z) = (Cd / Ru) "
                      "Gamma1 phi1(z) A B I g T1^2/4pi^2 (first mode; P-Delta not included)",
                      "ABS", d1, d2, d1 + d2});
      break;
    case TargetCode::csv: break;
  }
  return rows;
}

}  // namespace pounding::separation
