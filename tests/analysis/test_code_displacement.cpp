// The codes' own design displacements (issue 23 item 5) against values computed independently, by a plain
// Python script (no SciPy) that writes each clause out again (kept in the comments):
//   Sd(T) = Sa g T^2 / (4 pi^2), g = 9.80665
//   ASCE 7-16 12.8.6 delta_M = Cd (Ie/R) Sd / Ie, spectrum SDS 1.2, SD1 0.56, TL 8 (Sa(0.75) = 0.56/0.75):
//     T 0.75 s, R 8, Cd 5.5 -> 0.07172704377; T 1.25 s -> 0.11954507295; T 0.3 s (plateau), R 6, Cd 5 -> 0.02235648118
//   EN 1998-1 4.3.4 d_s = q S_d(T) g T^2/4pi^2, S_d of eqs. 3.13-3.16 (type 1, ground C: S 1.15, TB 0.2, TC 0.6,
//   TD 2; agR 0.3 g; beta 0.2):
//     T 0.75, q 3.9: S_d 0.176923077 g, d_s 0.09641232507; T 3, q 6: S_d = beta ag = 0.06 g, d_s 0.8048333223;
//     T 0.1, q 3: S_d 0.25875 g (eq. 3.13), d_s 0.001928246501; T 1.25, q 3.9: d_s 0.1606872084
//   Standard 2800 Delta_M = Cd A B I g T^2/(4 pi^2 Ru), A 0.35, soil III (T0 0.15, Ts 0.7, S 1.75, N with 0.7):
//     T 0.75, Ru 7.5, Cd 5.5, I 1 -> 0.09302599093; T 1.25 -> 0.1713147309; T 1.25, Ru 5, Cd 4, I 1.2 -> 0.2242665569
// The rows: ASCE separate lots = the sum, same property = SRSS; EC8 the same and 0.7 SRSS; Standard 2800 the sum.
// The 0.005 h rule's scope: at most 8 storeys and not I = 1.2 or 1.4.
#include <gtest/gtest.h>

#include <cmath>

#include "pounding/analysis/code_displacement.hpp"

using namespace pounding;
using namespace pounding::separation;

namespace {

constexpr double tol = 1e-10;

TargetSpectrumSpec asce() {
  TargetSpectrumSpec s;
  s.code = TargetCode::asce7_16;
  s.asce7 = {1.2, 0.56, 8.0};
  return s;
}

TargetSpectrumSpec ec8() {
  TargetSpectrumSpec s;
  s.code = TargetCode::ec8;
  s.ec8.type = Ec8Type::type1;
  s.ec8.ground = Ec8Ground::C;
  s.ec8.agr = 0.3;
  return s;
}

TargetSpectrumSpec iran() {
  TargetSpectrumSpec s;
  s.code = TargetCode::iran2800;
  s.iran2800 = {0.35, Iran2800Soil::III, 1.0};
  return s;
}

BuildingCode building(double T, double h) {
  BuildingCode b;
  b.T = T, b.height = h;
  return b;
}

}  // namespace

TEST(CodeDisplacement, Asce7AgainstHandValues) {
  EXPECT_NEAR(asce7_design_displacement(asce().asce7, 0.75, 8, 5.5, 1.0), 0.07172704377055514, tol);
  EXPECT_NEAR(asce7_design_displacement(asce().asce7, 1.25, 8, 5.5, 1.5), 0.11954507295092522, tol);  // Ie cancels
  EXPECT_NEAR(asce7_design_displacement(asce().asce7, 0.3, 6, 5, 1.25), 0.022356481175237964, tol);
}

TEST(CodeDisplacement, Ec8AgainstHandValues) {
  const Ec8Spectrum s = ec8().ec8;
  EXPECT_NEAR(ec8_design_sa(s, 3.9, 0.75), 0.17692307692307693, tol);
  EXPECT_NEAR(ec8_design_displacement(s, 3.9, 0.75), 0.0964123250682137, tol);
  EXPECT_NEAR(ec8_design_sa(s, 6, 3.0), 0.06, tol);  // the beta ag floor of eq. 3.16
  EXPECT_NEAR(ec8_design_displacement(s, 6, 3.0), 0.8048333223085666, tol);
  EXPECT_NEAR(ec8_design_sa(s, 3, 0.1), 0.25875, tol);  // eq. 3.13
  EXPECT_NEAR(ec8_design_displacement(s, 3, 0.1), 0.0019282465013642745, tol);
  // with q = 1 and T in [TB, TD] the design spectrum is the 5 %-damped elastic one: d_s = SDe (equal displacement)
  EXPECT_NEAR(ec8_design_displacement(s, 1.0, 0.75), spectral_displacement(sa(s, 0.75), 0.75), tol);
}

TEST(CodeDisplacement, Standard2800AgainstHandValues) {
  const Iran2800Spectrum s = iran().iran2800;
  EXPECT_NEAR(s2800_design_displacement(s, 1.0, 7.5, 5.5, 0.75), 0.09302599093464496, tol);
  EXPECT_NEAR(s2800_design_displacement(s, 1.0, 7.5, 5.5, 1.25), 0.17131473093161753, tol);
  EXPECT_NEAR(s2800_design_displacement(s, 1.2, 5, 4, 1.25), 0.22426655685593566, tol);
}

TEST(CodeDisplacement, RowsCombineTheDesignDisplacements) {
  BuildingCode b1 = building(0.75, 19.2), b2 = building(1.25, 32.0);
  b1.asce7_r = b2.asce7_r = 8, b1.asce7_cd = b2.asce7_cd = 5.5, b1.asce7_ie = b2.asce7_ie = 1.0;
  const TargetSpectrumSpec a = asce();
  const CodeDesign d = code_design_rules(&a, b1, b2);
  ASSERT_EQ(d.rules.size(), 2u);
  const double d1 = 0.07172704377055514, d2 = 0.11954507295092522;
  EXPECT_NEAR(d.rules[0].gap, d1 + d2, tol);  // separate lots
  EXPECT_NEAR(d.rules[1].gap, std::hypot(d1, d2), tol);  // same property
  EXPECT_NE(d.rules[0].name.find("ASCE 7-16 design"), std::string::npos);
  EXPECT_NE(d.rules[0].clause.find("R = 8, Cd = 5.5, Ie = 1"), std::string::npos) << d.rules[0].clause;
  EXPECT_TRUE(d.notes.empty());

  b1.ec8_q = b2.ec8_q = 3.9;  // EC8 factors with an ASCE spectrum: a note, no rows
  const CodeDesign e = code_design_rules(&a, b1, b2);
  EXPECT_EQ(e.rules.size(), 2u);
  ASSERT_EQ(e.notes.size(), 1u);
  EXPECT_NE(e.notes[0].find("EC8 factors are given but the design spectrum is ASCE 7-16"), std::string::npos);

  const TargetSpectrumSpec c = ec8();
  const CodeDesign f = code_design_rules(&c, b1, b2);
  ASSERT_EQ(f.rules.size(), 3u);
  const double e1 = 0.0964123250682137, e2 = 0.16068720844702283;
  EXPECT_NEAR(f.rules[0].gap, e1 + e2, tol);
  EXPECT_NEAR(f.rules[1].gap, std::hypot(e1, e2), tol);
  EXPECT_NEAR(f.rules[2].gap, 0.7 * std::hypot(e1, e2), tol);

  b1.s2800_ru = b2.s2800_ru = 7.5, b1.s2800_cd = b2.s2800_cd = 5.5;
  const TargetSpectrumSpec i = iran();
  const CodeDesign g = code_design_rules(&i, b1, b2);
  ASSERT_EQ(g.rules.size(), 1u);
  EXPECT_NEAR(g.rules[0].gap, 0.09302599093464496 + 0.17131473093161753, tol);

  const CodeDesign none = code_design_rules(nullptr, b1, b2);  // no design spectrum: no rows, a note
  EXPECT_TRUE(none.rules.empty());
  ASSERT_FALSE(none.notes.empty());
  EXPECT_NE(none.notes.back().find("no design spectrum"), std::string::npos);
  b2.asce7_r = 0;  // one building only
  const CodeDesign one = code_design_rules(&a, b1, b2);
  EXPECT_TRUE(one.rules.empty());
  EXPECT_NE(one.notes.front().find("one building only"), std::string::npos);
}

TEST(CodeDisplacement, Standard2800CoefficientRuleScope) {
  // the pair: 6 storeys (19.2 m) beside 10 storeys (32 m), storeys from height / 3.2 m
  const BuildingCode b1 = building(0.75, 19.2), b2 = building(1.25, 32.0);
  EXPECT_EQ(b1.resolved_storeys(), 6);
  EXPECT_EQ(b2.resolved_storeys(), 10);
  const Scope s = s2800_coefficient_scope(b1, b2, 0.0);
  EXPECT_FALSE(s.inside);
  EXPECT_NE(s.reason.find("building 2 has 10 storeys"), std::string::npos) << s.reason;
  BuildingCode low = building(1.25, 32.0);
  low.storeys = 8;  // given storeys win over the height
  EXPECT_TRUE(s2800_coefficient_scope(b1, low, 0.0).inside);
  EXPECT_NE(s2800_coefficient_scope(b1, low, 0.0).reason.find("ordinary importance (s2800_importance not given)"),
            std::string::npos);
  EXPECT_TRUE(s2800_coefficient_scope(b1, low, 1.0).inside);
  EXPECT_FALSE(s2800_coefficient_scope(b1, low, 1.2).inside);  // high importance from the spectrum
  low.s2800_importance = 1.4;
  const Scope v = s2800_coefficient_scope(b1, low, 1.0);
  EXPECT_FALSE(v.inside);
  EXPECT_NE(v.reason.find("very high importance"), std::string::npos) << v.reason;
  low.storey_height = 4.0, low.storeys = 0;  // 32 m / 4 m = 8 storeys
  low.s2800_importance = 1.0;
  EXPECT_TRUE(s2800_coefficient_scope(b1, low, 0.0).inside);
}

// Per contact level (a 5-storey building of 4.0 m storeys, T 0.6 s, R 8, Cd 5.5, beside an 8-storey one of 3.0 m
// storeys, T 0.9 s, R 6, Cd 5; uniform storey stiffnesses, equal floor masses; the ASCE spectrum above). Gamma1 phi1
// from numpy's eigh of the uniform chain (M = I): 5 storeys [0.35627144974809083, 0.6836799054654871,
// 0.9557006812430261, 1.1502962715970573, 1.2517016991016336], 8 storeys [0.23329095290398882, 0.45863746220848983,
// 0.6683656228124866, 0.8553333937478125, ...]. Sa(0.6) = 0.56 / 0.6 g, Sd = 0.08346419638755508 m, (Cd / R) Sd =
// 0.05738163501644412 m; Sa(0.9) = 0.56 / 0.9 g, Sd = 0.1251962945813326 m, (Cd / R) Sd = 0.10433024548444385 m.
// The floors meet at 12 m (floor 3 / floor 4): delta_M1 = 0.05483966767605432, delta_M2 = 0.08923714294075173,
// separate lots 0.14407681061680605, same property 0.1047409033331689; the 0.005 h rule 0.005 (12 + 12) = 0.12.
// Building 2's floor 3 (9 m) on building 1's column between floors 2 (8 m) and 3 (12 m), xi = 0.25:
// Gamma1 phi1 = 0.75 x 0.6836799054654871 + 0.25 x 0.9557006812430261 (the report interpolates; here given).
TEST(CodeDisplacement, PerContactLevelAsce7) {
  BuildingCode b1 = building(0.6, 20.0), b2 = building(0.9, 24.0);
  b1.asce7_r = 8, b1.asce7_cd = 5.5, b2.asce7_r = 6, b2.asce7_cd = 5;
  const TargetSpectrumSpec s = asce();
  const ModalInputs x1 = code_modal_inputs(s, b1), x2 = code_modal_inputs(s, b2);
  EXPECT_NEAR(x1.sa_g, 0.56 / 0.6, 1e-14);
  EXPECT_NEAR(x1.sd, 0.08346419638755508, 1e-14);
  EXPECT_NEAR(x1.factor * x1.sd, 0.05738163501644412, 1e-14);
  EXPECT_NEAR(x2.factor * x2.sd, 0.10433024548444385, 1e-14);

  ContactLevel L;
  L.label = "level 3/4", L.z1 = 12.0, L.z2 = 12.0, L.gphi1 = 0.9557006812430261, L.gphi2 = 0.8553333937478125;
  const std::vector<LevelRow> rows = code_level_rows(&s, b1, b2, L, 0.005);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].rule, "Standard 2800 0.005 h at the level");
  EXPECT_NEAR(rows[0].gap, 0.12, 1e-15);
  EXPECT_EQ(rows[1].combination, "ABS");
  EXPECT_NEAR(rows[1].d1, 0.05483966767605432, 1e-6 * 0.0548);
  EXPECT_NEAR(rows[1].d2, 0.08923714294075173, 1e-6 * 0.0892);
  EXPECT_NEAR(rows[1].gap, 0.14407681061680605, 1e-6 * 0.144);
  EXPECT_EQ(rows[2].combination, "SRSS");
  EXPECT_NEAR(rows[2].gap, 0.1047409033331689, 1e-6 * 0.105);

  // a floor against a column: no EC8 0.7 row there; an SDOF (Gamma1 phi1 = 1) gives code_design_rules' values
  ContactLevel c;
  c.z1 = 9.0, c.z2 = 9.0, c.gphi1 = 0.75 * 0.6836799054654871 + 0.25 * 0.9557006812430261;
  c.gphi2 = 0.6683656228124866, c.floors_coincide = false;
  const std::vector<LevelRow> col = code_level_rows(&s, b1, b2, c, 0.005);
  EXPECT_NEAR(col[1].d1, 0.05738163501644412 * c.gphi1, 1e-15);
  EXPECT_NEAR(col[0].gap, 0.09, 1e-15);
  ContactLevel one;
  const std::vector<LevelRow> sdof = code_level_rows(&s, b1, b2, one, 0.0);
  const CodeDesign d = code_design_rules(&s, b1, b2);
  ASSERT_EQ(sdof.size(), d.rules.size());
  for (std::size_t i = 0; i < sdof.size(); ++i) EXPECT_NEAR(sdof[i].gap, d.rules[i].gap, 1e-15) << d.rules[i].name;

  TargetSpectrumSpec e = ec8();
  b1.ec8_q = 3.9, b2.ec8_q = 3.9;
  EXPECT_EQ(code_level_rows(&e, b1, b2, L, 0).size(), 3u);  // separate, same, 0.7 where the floors coincide
  EXPECT_EQ(code_level_rows(&e, b1, b2, c, 0).size(), 2u);
}
