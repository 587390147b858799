// ASCE 7-16 design spectrum from the mapped values (issue 23 item 6): Fa and Fv against Tables 11.4-1 and
// 11.4-2 (Supplement 1) at every tabulated column, the straight-line interpolation between them, the research
// note's worked example (/work/shared/research/fragility-and-codes.md 3.1: site C, Ss = 1.5, S1 = 0.6 gives
// SDS = 1.2, SD1 = 0.56 and Sa(0, 0.05, 0.3, 1, 2, 10 s) = 0.48, 0.86571, 1.2, 0.56, 0.28, 0.0448 g), and the
// refused cases: site class F and the 11.4.8 site-specific ones.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "input_error.hpp"
#include "pounding/motion/asce7_site.hpp"

using namespace pounding;

namespace {

Asce7SiteCoefficients at(Asce7SiteClass c, double ss, double s1) { return asce7_site_coefficients({ss, s1, c, 8.0}); }

}  // namespace

TEST(Asce7Site, TableColumnsAsPrinted) {
  using S = Asce7SiteClass;
  // Table 11.4-1 at Ss = 0.25, 0.5, 0.75, 1.0, 1.25, 1.5 (S1 = 0.1 keeps D and E clear of 11.4.8)
  const std::array<double, 6> ss{0.25, 0.5, 0.75, 1.0, 1.25, 1.5};
  const std::array<std::pair<S, std::array<double, 6>>, 4> fa{{{S::A, {0.8, 0.8, 0.8, 0.8, 0.8, 0.8}},
                                                               {S::B, {0.9, 0.9, 0.9, 0.9, 0.9, 0.9}},
                                                               {S::C, {1.3, 1.3, 1.2, 1.2, 1.2, 1.2}},
                                                               {S::D, {1.6, 1.4, 1.2, 1.1, 1.0, 1.0}}}};
  for (const auto& [c, row] : fa)
    for (std::size_t i = 0; i < ss.size(); ++i) EXPECT_DOUBLE_EQ(at(c, ss[i], 0.1).fa, row[i]) << to_string(c) << " Ss " << ss[i];
  for (auto [v, f] : {std::pair{0.25, 2.4}, {0.5, 1.7}, {0.75, 1.3}}) EXPECT_DOUBLE_EQ(at(S::E, v, 0.1).fa, f);
  // Table 11.4-2 (Supplement 1) at S1 = 0.1 .. 0.6; D and E only below 0.2 (11.4.8 above)
  const std::array<double, 6> s1{0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
  const std::array<double, 6> fv_c{1.5, 1.5, 1.5, 1.5, 1.5, 1.4};
  for (std::size_t i = 0; i < s1.size(); ++i) {
    EXPECT_DOUBLE_EQ(at(S::A, 1.0, s1[i]).fv, 0.8);
    EXPECT_DOUBLE_EQ(at(S::B, 1.0, s1[i]).fv, 0.8);
    EXPECT_DOUBLE_EQ(at(S::C, 1.0, s1[i]).fv, fv_c[i]);
  }
  EXPECT_DOUBLE_EQ(at(S::D, 0.5, 0.1).fv, 2.4);
  EXPECT_DOUBLE_EQ(at(S::E, 0.5, 0.1).fv, 4.2);
  // beyond the columns the end values hold
  EXPECT_DOUBLE_EQ(at(S::D, 0.1, 0.05).fa, 1.6);
  EXPECT_DOUBLE_EQ(at(S::D, 0.1, 0.05).fv, 2.4);
  EXPECT_DOUBLE_EQ(at(S::C, 3.0, 1.2).fa, 1.2);
  EXPECT_DOUBLE_EQ(at(S::C, 3.0, 1.2).fv, 1.4);
}

TEST(Asce7Site, StraightLineInterpolation) {
  using S = Asce7SiteClass;
  EXPECT_NEAR(at(S::D, 0.6, 0.1).fa, 1.4 + 0.4 * (1.2 - 1.4), 1e-12);   // between 0.5 and 0.75
  EXPECT_NEAR(at(S::C, 0.625, 0.1).fa, 1.25, 1e-12);                   // half way 1.3 -> 1.2
  EXPECT_NEAR(at(S::C, 1.0, 0.55).fv, 1.45, 1e-12);                    // half way 1.5 -> 1.4
  EXPECT_NEAR(at(S::D, 0.5, 0.15).fv, 2.3, 1e-12);                     // half way 2.4 -> 2.2
  EXPECT_NEAR(at(S::E, 0.375, 0.15).fa, 2.05, 1e-12);                  // half way 2.4 -> 1.7
  EXPECT_NEAR(at(S::E, 0.375, 0.15).fv, 3.75, 1e-12);                  // half way 4.2 -> 3.3
  // 11.4.4: the default site class D takes Fa >= 1.2
  EXPECT_DOUBLE_EQ(at(S::D_default, 1.5, 0.1).fa, 1.2);
  EXPECT_DOUBLE_EQ(at(S::D_default, 0.25, 0.1).fa, 1.6);
}

TEST(Asce7Site, ResearchNoteWorkedExample) {
  const Asce7MapValues m{1.5, 0.6, Asce7SiteClass::C, 8.0};
  const Asce7SiteCoefficients c = asce7_site_coefficients(m);
  EXPECT_DOUBLE_EQ(c.fa, 1.2);
  EXPECT_DOUBLE_EQ(c.fv, 1.4);
  EXPECT_NEAR(c.sms, 1.8, 1e-12);
  EXPECT_NEAR(c.sm1, 0.84, 1e-12);
  const Asce7Spectrum s = asce7_from_maps(m);
  EXPECT_NEAR(s.sds, 1.2, 1e-12);
  EXPECT_NEAR(s.sd1, 0.56, 1e-12);
  for (auto [t, v] : {std::pair{0.0, 0.48}, {0.05, 0.86571}, {0.3, 1.2}, {1.0, 0.56}, {2.0, 0.28}, {10.0, 0.0448}})
    EXPECT_NEAR(sa(s, t), v, 5e-6) << "T " << t;
  EXPECT_NE(describe(m).find("Fa = 1.2, Fv = 1.4"), std::string::npos) << describe(m);
}

TEST(Asce7Site, SiteSpecificCasesAreRefused) {
  using S = Asce7SiteClass;
  using testdata::input_error;
  EXPECT_EQ(input_error([] { at(S::F, 0.5, 0.1); }).where(), "site class");
  const InputError e1 = input_error([] { at(S::E, 1.0, 0.1); });  // 11.4.8 item 2
  EXPECT_EQ(e1.where(), "Ss");
  EXPECT_NE(std::string(e1.what()).find("exception 1"), std::string::npos) << e1.what();
  EXPECT_EQ(input_error([] { at(S::E, 0.8, 0.1); }).where(), "Ss");  // nothing to interpolate toward
  for (S c : {S::D, S::D_default, S::E}) {  // 11.4.8 item 3: D and E with S1 >= 0.2
    const InputError e = input_error([c] { at(c, 0.5, 0.2); });
    EXPECT_EQ(e.where(), "S1");
    EXPECT_NE(std::string(e.what()).find("11.4.8"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(at(S::D, 0.5, 0.199));
  EXPECT_NO_THROW(at(S::C, 2.0, 1.0));  // site C is never site-specific here
  EXPECT_EQ(input_error([] { at(S::C, 0.0, 0.1); }).where(), "Ss");
  EXPECT_EQ(input_error([] { at(S::C, 1.0, 3.5); }).where(), "S1");
  EXPECT_EQ(input_error([] { parse_asce7_site_class("G", "here"); }).where(), "here");
  EXPECT_EQ(parse_asce7_site_class("D-default", "here"), S::D_default);
}
