// [target_spectrum] and [records] select parsed into a Study, and the selection of a study's records
// (study/target_spectrum.hpp): the period range's defaults (a grid's median element, ASCE 7-10's 1.5), explicit
// t_min/t_max, the MCER factor, EC8's default rule and damping, and select_study_records' determinism and scaling.
#include <gtest/gtest.h>

#include <string>

#include "input_error.hpp"
#include "pounding/motion/synthetic.hpp"
#include "pounding/study/study.hpp"

namespace pounding {
namespace {

const std::string base = "seed = 1\nscene = \"probability\"\n[records]\nsuite = \"builtin\"\nselect = 3\n";

Study parse(const std::string& structures, const std::string& target) {
  return parse_study(base + structures + "\n[target_spectrum]\n" + target, "t.toml");
}

TEST(TargetSpectrum, GridRangeUsesTheMedianElement) {
  // both buildings on the grid 0.7 .. 1.5 s: the median element is 1.0 s (the mean is 1.08 s), so the range is 0.2 x 1.0 to 2 x 1.0 s
  const Study s = parse("[structures]\nperiods = [0.7, 0.8, 1.0, 1.4, 1.5]", "code = \"ASCE 7-16\"\nsds = 1\nsd1 = 0.6");
  EXPECT_TRUE(s.target.enabled);
  EXPECT_EQ(s.select, 3);
  EXPECT_DOUBLE_EQ(s.target.options.t_lo, 0.2);
  EXPECT_DOUBLE_EQ(s.target.options.t_hi, 2.0);
  EXPECT_FALSE(s.target.range_given);
  EXPECT_EQ(s.target.options.rule, ScalingRule::asce7_16);
  EXPECT_EQ(s.target.options.points, 30);
  EXPECT_DOUBLE_EQ(s.target.options.min_scale, 0.25);
  EXPECT_DOUBLE_EQ(s.target.options.max_scale, 4.0);
}

TEST(TargetSpectrum, PairRangeAndOverrides) {
  const std::string pair = "[structures.building1]\nperiod = 0.9\n[structures.building2]\nperiod = 1.3";
  const Study d = parse(pair, "code = \"ASCE 7-16\"\nsds = 1\nsd1 = 0.6\nrule = \"ASCE 7-10\"");
  EXPECT_DOUBLE_EQ(d.target.options.t_lo, 0.2 * 0.9);
  EXPECT_DOUBLE_EQ(d.target.options.t_hi, 1.5 * 1.3);  // ASCE 7-10 16.1.3.1: 0.2T-1.5T
  const Study o = parse(pair, "code = \"ASCE 7-16\"\nsds = 1\nsd1 = 0.6\nt_min = 0.3");
  EXPECT_DOUBLE_EQ(o.target.options.t_lo, 0.3);
  EXPECT_DOUBLE_EQ(o.target.options.t_hi, 2.0 * 1.3);
  EXPECT_TRUE(o.target.range_given);
}

TEST(TargetSpectrum, McerIsOneAndAHalfTimesTheDesignSpectrum) {
  const Study s = parse("", "code = \"ASCE 7-16\"\nsds = 1.2\nsd1 = 0.56\nmcer = true");
  const DesignSpectrum t = make_target_spectrum(s.target.spec, s.target.options.damping);
  EXPECT_NEAR(t.sa(0.3), 1.5 * 1.2, 1e-12);
  EXPECT_NEAR(t.sa(1.0), 1.5 * 0.56, 1e-12);
  EXPECT_NE(s.target.target_text.find("MCER"), std::string::npos);
}

TEST(TargetSpectrum, Ec8DefaultsToItsRuleAtTheSelectionDamping) {
  const Study s = parse("", "code = \"EC8\"\nground = \"C\"\nagr = 0.3\ndamping = 0.02");
  EXPECT_EQ(s.target.options.rule, ScalingRule::ec8);
  const DesignSpectrum t = make_target_spectrum(s.target.spec, s.target.options.damping);
  // research note 3.2: ag = 0.3 g, ground C type 1: plateau 2.5 ag S eta with eta(2 %) = 1.19523
  EXPECT_NEAR(t.sa(0.4), 2.5 * 0.3 * 1.15 * 1.19523, 1e-5);
}

TEST(TargetSpectrum, ErrorsNameTheStudyKey) {
  const auto e = testdata::input_error([] { parse("", "code = \"ASCE 7-16\"\nsds = 1\nsd1 = 0.6\ntl = 0.5"); });
  EXPECT_NE(e.where().find("[target_spectrum].tl"), std::string::npos) << e.where();
  const auto g = testdata::input_error([] { parse("", "code = \"EC8\"\nground = \"C\"\nagr = 0.3\nimportance = 3"); });
  EXPECT_NE(g.where().find("[target_spectrum].importance"), std::string::npos) << g.where();
}

// Three synthetic records as a library: the selection is the same twice (every rank computes it), and each chosen
// record is the library's multiplied by its factor f_i F.
TEST(TargetSpectrum, SelectStudyRecordsIsDeterministicAndScales) {
  const Study s = parse("[structures.building1]\nperiod = 0.9\n[structures.building2]\nperiod = 1.3",
                        "code = \"ASCE 7-16\"\nsds = 1\nsd1 = 0.6\nmin_scale = 0.01\nmax_scale = 100");
  std::vector<StudyRecord> lib;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    StudyRecord r;
    r.record = synthesize({6.5 + 0.1 * static_cast<double>(seed), 10.0 + 5.0 * static_cast<double>(seed), 400, 0}, seed, {});
    r.id = "R" + std::to_string(seed);
    lib.push_back(std::move(r));
  }
  StudySelection a, b;
  const auto ra = select_study_records(s, lib, a);
  const auto rb = select_study_records(s, lib, b);
  ASSERT_EQ(ra.size(), 3u);
  EXPECT_EQ(a.selection.chosen, b.selection.chosen);
  EXPECT_EQ(a.selection.scale, b.selection.scale);  // bit for bit
  EXPECT_TRUE(a.selection.meets);
  EXPECT_GE(a.selection.suite_factor, 1.0);
  for (std::size_t k = 0; k < ra.size(); ++k) {
    const StudyRecord& src = lib[a.selection.chosen[k]];
    EXPECT_EQ(ra[k].id, src.id);
    ASSERT_EQ(ra[k].record.acc.size(), src.record.acc.size());
    for (std::size_t i = 0; i < src.record.acc.size(); i += 97)
      EXPECT_EQ(ra[k].record.acc[i], src.record.acc[i] * a.selection.scale[k]);
    EXPECT_EQ(ra[k].record.acc, rb[k].record.acc);
  }
  const auto lines = a.summary();
  EXPECT_NE(lines.front().find("ASCE 7-16"), std::string::npos);
  const auto over = testdata::input_error([&] {
    Study t = s;
    t.select = 6;
    StudySelection x;
    select_study_records(t, lib, x);
  });
  EXPECT_NE(over.what_part().find("select = 6 but the library holds 5 records"), std::string::npos) << over.what_part();
}

}  // namespace
}  // namespace pounding
