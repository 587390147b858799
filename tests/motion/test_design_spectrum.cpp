// Design spectra (issue 14 groundwork): every code spectrum against the research note's worked numbers
// (/work/shared/research/fragility-and-codes.md section 3, computed there with SciPy) and against the
// code formulas written out again here, branch by branch; continuity at the corner periods; the EC8 table
// constants for every ground type; the eta factor; the tabulated interpolation and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "pounding/core/error.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "temp_dir.hpp"

#include "input_error.hpp"

using namespace pounding;

namespace {


constexpr double eps = 1e-12;

}  // namespace

// ---------------- ASCE 7-16 ----------------

TEST(DesignSpectrumAsce7, ResearchNoteWorkedExample) {
  // Site C, Ss = 1.5, S1 = 0.6: Fa = 1.2, Fv = 1.4, SDS = 2/3 1.2 1.5 = 1.2, SD1 = 2/3 1.4 0.6 = 0.56, TL = 8.
  const Asce7Spectrum s{1.2, 0.56, 8.0};
  EXPECT_NEAR(asce7_t0(s), 0.09333, 1e-5);
  EXPECT_NEAR(asce7_ts(s), 0.46667, 1e-5);
  const std::vector<std::pair<double, double>> expect{{0, 0.48},  {0.05, 0.86571}, {0.3, 1.2},
                                                      {1, 0.56}, {2, 0.28},       {10, 0.0448}};
  for (auto [t, v] : expect) EXPECT_NEAR(sa(s, t), v, 5e-6) << "T " << t;
}

TEST(DesignSpectrumAsce7, EachBranchAndCornerByHand) {
  const double sds = 0.9, sd1 = 0.45, tl = 6.0;  // T0 = 0.1 s, TS = 0.5 s
  const Asce7Spectrum s{sds, sd1, tl};
  EXPECT_NEAR(asce7_t0(s), 0.1, eps);
  EXPECT_NEAR(asce7_ts(s), 0.5, eps);
  EXPECT_NEAR(sa(s, 0.0), 0.36, eps);                       // 0.4 SDS
  EXPECT_NEAR(sa(s, 0.05), 0.9 * (0.4 + 0.6 * 0.5), eps);   // 0.63, rising branch
  EXPECT_NEAR(sa(s, 0.1), 0.9, eps);                        // T0
  EXPECT_NEAR(sa(s, 0.3), 0.9, eps);                        // plateau
  EXPECT_NEAR(sa(s, 0.5), 0.9, eps);                        // TS
  EXPECT_NEAR(sa(s, 1.5), 0.3, eps);                        // SD1/T
  EXPECT_NEAR(sa(s, 6.0), 0.075, eps);                      // TL: SD1/TL
  EXPECT_NEAR(sa(s, 12.0), 0.45 * 6.0 / 144.0, eps);        // SD1 TL/T^2
}

TEST(DesignSpectrumAsce7, ContinuousAtCorners) {
  const Asce7Spectrum s{1.2, 0.56, 8.0};
  for (double t : {asce7_t0(s), asce7_ts(s), s.tl}) {
    EXPECT_NEAR(sa(s, t * (1 - 1e-9)), sa(s, t * (1 + 1e-9)), 1e-8) << "T " << t;
  }
}

TEST(DesignSpectrumAsce7, Validation) {
  EXPECT_EQ(testdata::input_error([] { validate(Asce7Spectrum{0.0, 0.5, 8}); }).where(), "SDS");
  EXPECT_EQ(testdata::input_error([] { validate(Asce7Spectrum{1.0, -0.5, 8}); }).where(), "SD1");
  const InputError tl = testdata::input_error([] { validate(Asce7Spectrum{1.0, 0.5, 0.5}); });
  EXPECT_EQ(tl.where(), "TL");
  EXPECT_NE(tl.fix().find("[1, 20] s"), std::string::npos) << tl.fix();
  EXPECT_EQ(testdata::input_error([] { validate(Asce7Spectrum{0.5, 3.0, 4}); }).where(), "SD1");  // TS = 6 s > TL
  EXPECT_NO_THROW(validate(Asce7Spectrum{1.2, 0.56, 8}));
  EXPECT_THROW(sa(Asce7Spectrum{1.2, 0.56, 8}, -0.1), InputError);
  EXPECT_THROW(sa(Asce7Spectrum{1.2, 0.56, 8}, std::nan("")), InputError);
}

// ---------------- Eurocode 8 ----------------

TEST(DesignSpectrumEc8, TableConstantsEveryGroundType) {
  // EN 1998-1:2004 table 3.2 (type 1) and table 3.3 (type 2): S, TB, TC, TD.
  const double t1[5][4] = {{1.0, 0.15, 0.4, 2.0}, {1.2, 0.15, 0.5, 2.0}, {1.15, 0.20, 0.6, 2.0},
                           {1.35, 0.20, 0.8, 2.0}, {1.4, 0.15, 0.5, 2.0}};
  const double t2[5][4] = {{1.0, 0.05, 0.25, 1.2}, {1.35, 0.05, 0.25, 1.2}, {1.5, 0.10, 0.25, 1.2},
                           {1.8, 0.10, 0.30, 1.2}, {1.6, 0.05, 0.25, 1.2}};
  for (int g = 0; g < 5; ++g) {
    for (int type = 0; type < 2; ++type) {
      const auto& row = type == 0 ? t1[g] : t2[g];
      const Ec8GroundParams p = ec8_ground_params(type == 0 ? Ec8Type::type1 : Ec8Type::type2, Ec8Ground(g));
      EXPECT_EQ(p.s, row[0]) << "ground " << g << " type " << type + 1;
      EXPECT_EQ(p.tb, row[1]) << "ground " << g << " type " << type + 1;
      EXPECT_EQ(p.tc, row[2]) << "ground " << g << " type " << type + 1;
      EXPECT_EQ(p.td, row[3]) << "ground " << g << " type " << type + 1;
    }
  }
}

TEST(DesignSpectrumEc8, EtaFactor) {
  EXPECT_NEAR(ec8_eta(5.0), 1.0, eps);
  EXPECT_NEAR(ec8_eta(2.0), 1.19523, 5e-6);  // research note (computed)
  EXPECT_NEAR(ec8_eta(10.0), std::sqrt(10.0 / 15.0), eps);
  EXPECT_NEAR(ec8_eta(0.0), std::sqrt(2.0), eps);
  EXPECT_NEAR(ec8_eta(28.0), std::sqrt(10.0 / 33.0), eps);  // 0.5505, just above the floor
  EXPECT_EQ(ec8_eta(30.0), 0.55);                            // sqrt(10/35) = 0.5345 -> floor
  EXPECT_EQ(ec8_eta(50.0), 0.55);
  EXPECT_EQ(testdata::input_error([] { ec8_eta(-1.0); }).where(), "damping ratio xi (%)");
}

TEST(DesignSpectrumEc8, ResearchNoteWorkedExamples) {
  // ag = 0.3 g, ground C, xi = 5 %.
  const Ec8Spectrum t1{Ec8Type::type1, Ec8Ground::C, 0.3, 1.0, 5.0};
  const std::vector<std::pair<double, double>> e1{{0, 0.345}, {0.1, 0.60375}, {0.4, 0.8625}, {1, 0.5175}, {3, 0.115}};
  for (auto [t, v] : e1) EXPECT_NEAR(sa(t1, t), v, 1e-12) << "type 1, T " << t;
  const Ec8Spectrum t2{Ec8Type::type2, Ec8Ground::C, 0.3, 1.0, 5.0};
  const std::vector<std::pair<double, double>> e2{{0, 0.45}, {0.05, 0.7875}, {0.2, 1.125}, {1, 0.28125}, {3, 0.0375}};
  for (auto [t, v] : e2) EXPECT_NEAR(sa(t2, t), v, 1e-12) << "type 2, T " << t;
}

TEST(DesignSpectrumEc8, EachBranchByHandWithImportanceAndDamping) {
  // Type 1, ground D (S 1.35, TB 0.2, TC 0.8, TD 2.0), agR 0.25, gammaI 1.2 -> ag 0.3, xi 10 % -> eta sqrt(2/3).
  const Ec8Spectrum s{Ec8Type::type1, Ec8Ground::D, 0.25, 1.2, 10.0};
  const double ag = 0.3, S = 1.35, eta = std::sqrt(10.0 / 15.0);
  EXPECT_NEAR(sa(s, 0.0), ag * S, eps);
  EXPECT_NEAR(sa(s, 0.1), ag * S * (1 + 0.5 * (2.5 * eta - 1)), eps);
  EXPECT_NEAR(sa(s, 0.2), 2.5 * ag * S * eta, eps);
  EXPECT_NEAR(sa(s, 0.5), 2.5 * ag * S * eta, eps);
  EXPECT_NEAR(sa(s, 0.8), 2.5 * ag * S * eta, eps);
  EXPECT_NEAR(sa(s, 1.6), 2.5 * ag * S * eta * 0.5, eps);
  EXPECT_NEAR(sa(s, 2.0), 2.5 * ag * S * eta * 0.4, eps);
  EXPECT_NEAR(sa(s, 4.0), 2.5 * ag * S * eta * 0.8 * 2.0 / 16.0, eps);
}

TEST(DesignSpectrumEc8, ContinuousAtCornersEveryGroundAndType) {
  for (int g = 0; g < 5; ++g) {
    for (Ec8Type type : {Ec8Type::type1, Ec8Type::type2}) {
      const Ec8Spectrum s{type, Ec8Ground(g), 0.35, 1.0, 7.0};
      const Ec8GroundParams p = ec8_ground_params(type, Ec8Ground(g));
      for (double t : {p.tb, p.tc, p.td})
        EXPECT_NEAR(sa(s, t * (1 - 1e-10)), sa(s, t * (1 + 1e-10)), 1e-9) << "ground " << g << " T " << t;
    }
  }
}

TEST(DesignSpectrumEc8, Validation) {
  EXPECT_EQ(testdata::input_error([] { validate(Ec8Spectrum{Ec8Type::type1, Ec8Ground::A, 0.0, 1.0, 5}); }).where(), "agR");
  const InputError imp = testdata::input_error([] { validate(Ec8Spectrum{Ec8Type::type1, Ec8Ground::A, 0.2, 1.6, 5}); });
  EXPECT_EQ(imp.where(), "importance factor gammaI");
  EXPECT_NE(imp.fix().find("[0.8, 1.4]"), std::string::npos) << imp.fix();
  EXPECT_EQ(testdata::input_error([] { validate(Ec8Spectrum{Ec8Type::type1, Ec8Ground::A, 0.2, 1.0, 60}); }).where(),
            "damping ratio xi (%)");
  EXPECT_EQ(testdata::input_error([] { validate(Ec8Spectrum{Ec8Type::type1, Ec8Ground(7), 0.2, 1.0, 5}); }).where(),
            "ground type");
}

// ---------------- Iranian Standard 2800, 4th edition ----------------

TEST(DesignSpectrumIran2800, ResearchNoteWorkedExample) {
  // A = 0.35, soil III (T0 0.15, Ts 0.7, S 1.75, S0 1.1) -- table from a secondary source (VERIFY).
  const Iran2800Spectrum s{0.35, Iran2800Soil::III, 1.0};
  const std::vector<std::pair<double, double>> b{{0, 1.1},      {0.1, 2.2},     {0.5, 2.75},
                                                 {1, 2.0475},   {2, 1.22792},   {4.5, 0.72722}};
  for (auto [t, v] : b) EXPECT_NEAR(iran2800_b(s, t), v, 5e-6) << "T " << t;
  EXPECT_NEAR(sa(s, 1.0), 0.71662, 5e-6);
}

TEST(DesignSpectrumIran2800, EachBranchByHandLowHazardSoilIV) {
  // A = 0.25 (moderate): soil IV T0 0.15, Ts 1.0, S 2.25, S0 1.3; N rises by 0.4 to 4 s. I = 1.2.
  const Iran2800Spectrum s{0.25, Iran2800Soil::IV, 1.2};
  const Iran2800SoilParams p = iran2800_soil_params(Iran2800Soil::IV, 0.25);
  EXPECT_EQ(p.t0, 0.15);
  EXPECT_EQ(p.ts, 1.0);
  EXPECT_EQ(p.s, 2.25);
  EXPECT_EQ(p.s0, 1.3);
  EXPECT_NEAR(iran2800_b(s, 0.075), 1.3 + 1.95 * 0.5, eps);   // S0 + (S - S0 + 1) T/T0
  EXPECT_NEAR(iran2800_b(s, 0.6), 3.25, eps);                  // S + 1
  EXPECT_NEAR(iran2800_b(s, 2.5), 3.25 / 2.5 * (1 + 0.4 * 1.5 / 3.0), eps);
  EXPECT_NEAR(iran2800_b(s, 5.0), 3.25 / 5.0 * 1.4, eps);
  EXPECT_NEAR(sa(s, 0.6), 0.25 * 3.25 * 1.2, eps);
  // high hazard, soil IV: S 1.75, S0 1.1
  EXPECT_EQ(iran2800_soil_params(Iran2800Soil::IV, 0.30).s, 1.75);
  EXPECT_EQ(iran2800_soil_params(Iran2800Soil::IV, 0.30).s0, 1.1);
}

TEST(DesignSpectrumIran2800, ContinuousAtCorners) {
  for (double a : {0.20, 0.25, 0.30, 0.35}) {
    for (int soil = 0; soil < 4; ++soil) {
      const Iran2800Spectrum s{a, Iran2800Soil(soil), 1.0};
      const Iran2800SoilParams p = iran2800_soil_params(Iran2800Soil(soil), a);
      for (double t : {p.t0, p.ts, 4.0})
        EXPECT_NEAR(sa(s, t * (1 - 1e-10)), sa(s, t * (1 + 1e-10)), 1e-9)
            << "A " << a << " soil " << soil << " T " << t;
    }
  }
}

TEST(DesignSpectrumIran2800, Validation) {
  const InputError a = testdata::input_error([] { validate(Iran2800Spectrum{0.32, Iran2800Soil::I, 1.0}); });
  EXPECT_EQ(a.where(), "A");
  EXPECT_NE(a.fix().find("0.35, 0.30, 0.25 or 0.20"), std::string::npos) << a.fix();
  EXPECT_EQ(testdata::input_error([] { validate(Iran2800Spectrum{0.30, Iran2800Soil::I, 2.0}); }).where(), "importance factor I");
  EXPECT_EQ(testdata::input_error([] { validate(Iran2800Spectrum{0.30, Iran2800Soil(4), 1.0}); }).where(), "soil type");
  EXPECT_NO_THROW(validate(Iran2800Spectrum{0.20, Iran2800Soil::IV, 1.4}));
}

// ---------------- Tabulated ----------------

TEST(DesignSpectrumTabulated, LinearInterpolation) {
  const TabulatedSpectrum s{{0.0, 0.2, 1.0, 4.0}, {0.4, 1.0, 0.5, 0.1}, "t"};
  EXPECT_NO_THROW(validate(s));
  EXPECT_DOUBLE_EQ(sa(s, 0.0), 0.4);
  EXPECT_DOUBLE_EQ(sa(s, 0.1), 0.7);
  EXPECT_DOUBLE_EQ(sa(s, 0.2), 1.0);
  EXPECT_DOUBLE_EQ(sa(s, 0.6), 0.75);
  EXPECT_DOUBLE_EQ(sa(s, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(sa(s, 2.5), 0.3);
  EXPECT_DOUBLE_EQ(sa(s, 4.0), 0.1);
  EXPECT_THROW(sa(s, 4.5), InputError);
  const TabulatedSpectrum late{{0.5, 1.0}, {1.0, 0.5}, "t"};
  EXPECT_THROW(sa(late, 0.2), InputError);  // below the table: no extrapolation
}

TEST(DesignSpectrumTabulated, Errors) {
  EXPECT_EQ(testdata::input_error([] { validate(TabulatedSpectrum{{0.1, 0.1, 0.5}, {1, 1, 1}, "t"}); }).where(), "t point 2");
  EXPECT_EQ(testdata::input_error([] { validate(TabulatedSpectrum{{0.1, 0.5, 0.3}, {1, 1, 1}, "t"}); }).where(), "t point 3");
  EXPECT_EQ(testdata::input_error([] { validate(TabulatedSpectrum{{0.1, 0.5}, {1, -0.1}, "t"}); }).where(), "t point 2");
  EXPECT_EQ(testdata::input_error([] { validate(TabulatedSpectrum{{-0.1, 0.5}, {1, 1}, "t"}); }).where(), "t point 1");
  const InputError one = testdata::input_error([] { validate(TabulatedSpectrum{{0.1}, {1}, "t"}); });
  EXPECT_EQ(one.where(), "t");
  EXPECT_NE(one.what_part().find("at least 2 points"), std::string::npos);
  EXPECT_THROW(validate(TabulatedSpectrum{{0.1, 0.2}, {1}, "t"}), InputError);
}

TEST(DesignSpectrumTabulated, CsvReader) {
  testdata::TempDir dir("design-spectrum");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir.file(name)) << text;
    return dir.file(name);
  };
  const std::string good = write("good.csv", "# target\nperiod_s,sa_g\r\n0.0,0.4\n\n0.2, 1.0\n1.0,0.5\n");
  const TabulatedSpectrum s = read_tabulated_spectrum(good);
  EXPECT_EQ(s.periods, (std::vector<double>{0.0, 0.2, 1.0}));
  EXPECT_EQ(s.sa, (std::vector<double>{0.4, 1.0, 0.5}));
  EXPECT_EQ(s.source, good);
  EXPECT_DOUBLE_EQ(sa(s, 0.6), 0.75);

  const std::string dec = write("dec.csv", "period,sa\n0.1,1\n0.3,1\n0.3,0.8\n");
  EXPECT_EQ(testdata::input_error([&] { read_tabulated_spectrum(dec); }).where(), dec + ":4");
  const std::string neg = write("neg.csv", "0.1,1\n# c\n0.3,-0.2\n");
  EXPECT_EQ(testdata::input_error([&] { read_tabulated_spectrum(neg); }).where(), neg + ":3");
  const std::string bad = write("bad.csv", "0.1,1\n0.3,abc\n");
  EXPECT_EQ(testdata::input_error([&] { read_tabulated_spectrum(bad); }).where(), bad + ":2");
  const std::string junk = write("junk.csv", "0.1,1\n0.3,1.5x\n");  // trailing junk after a number
  EXPECT_EQ(testdata::input_error([&] { read_tabulated_spectrum(junk); }).where(), junk + ":2");
  const std::string three = write("three.csv", "0.1,1\n0.3,1,2\n");
  EXPECT_EQ(testdata::input_error([&] { read_tabulated_spectrum(three); }).where(), three + ":2");
  const std::string hdr2 = write("hdr2.csv", "period,sa\nT,Sa\n");  // only the first line may be a header
  EXPECT_EQ(testdata::input_error([&] { read_tabulated_spectrum(hdr2); }).where(), hdr2 + ":2");
  const std::string few = write("few.csv", "period,sa\n0.1,1\n");
  EXPECT_EQ(testdata::input_error([&] { read_tabulated_spectrum(few); }).where(), few);
  EXPECT_THROW(read_tabulated_spectrum(dir.file("missing.csv")), InputError);
}

// ---------------- DesignSpectrum ----------------

TEST(DesignSpectrum, DispatchValidateDescribe) {
  const DesignSpectrum asce(Asce7Spectrum{1.2, 0.56, 8.0});
  EXPECT_NEAR(asce.sa(2.0), 0.28, eps);
  EXPECT_EQ(asce.describe(), "ASCE 7-16 11.4.6: SDS = 1.2 g, SD1 = 0.56 g, TL = 8 s");
  const DesignSpectrum ec8(Ec8Spectrum{Ec8Type::type2, Ec8Ground::C, 0.3, 1.0, 5.0});
  EXPECT_NEAR(ec8.sa(0.2), 1.125, eps);
  EXPECT_EQ(ec8.describe(), "EN 1998-1 3.2.2.2 type 2, ground C: agR = 0.3 g, gammaI = 1, xi = 5 %");
  const DesignSpectrum iran(Iran2800Spectrum{0.35, Iran2800Soil::III, 1.0});
  EXPECT_NEAR(iran.sa(1.0), 0.71662, 5e-6);
  EXPECT_EQ(iran.describe(), "Standard 2800 (4th ed.): A = 0.35, soil III, I = 1");
  const DesignSpectrum tab(TabulatedSpectrum{{0.0, 1.0}, {1.0, 0.5}, "target.csv"});
  EXPECT_NEAR(tab.sa(0.5), 0.75, eps);
  EXPECT_EQ(tab.describe(), "tabulated: 2 points, 0-1 s, from target.csv");
  EXPECT_THROW(DesignSpectrum(Asce7Spectrum{-1.0, 0.56, 8.0}), InputError);
  EXPECT_THROW(DesignSpectrum(Iran2800Spectrum{0.4, Iran2800Soil::I, 1.0}), InputError);
  EXPECT_THROW(DesignSpectrum(TabulatedSpectrum{{1.0, 0.5}, {1, 1}, "t"}), InputError);
  EXPECT_THROW(asce.sa(-1.0), InputError);
}
