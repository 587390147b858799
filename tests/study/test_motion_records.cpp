// [records.motions] (issue 26 §2): a bridge study generates its support motions with the generator of `pounding
// motions`. Its records are spatial::simulate's realisations bit for bit (the in-memory doubles), equal to the AT2
// files the command writes to their rounding, the same made in shares by threads and ranks; a stop is honoured;
// the wave passage shows as the lag of the cross-correlation peak between the channels; bad keys are refused
// before any work with the key and the file named, by the same checks as the command line.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "input_error.hpp"
#include "pounding/core/error.hpp"
#include "pounding/motion/spatial.hpp"
#include "pounding/study/study.hpp"
#include "temp_dir.hpp"

namespace pounding {
namespace {

const std::string bridge = R"(
[bridge]
[[bridge.frame]]
mass = 1.0e6
period = 1.0
[[bridge.frame]]
mass = 1.0e6
period = 1.0
support = 2
[[bridge.joint]]
gap = 0.05
[contact]
law = "hertzdamp"
stiffness = 2.0e9
)";

// A bridge study whose [records.motions] holds `keys` (one per line).
std::string study_text(const std::string& keys) {
  return "seed = 11\nscene = \"probability\"\n[records]\npolarity = \"recorded\"\n[records.motions]\n" + keys + "\n" +
         bridge;
}

// Short motions (8 s, 3 matching updates): seconds for the whole test.
const std::string quick = "duration = 8.0\nrise = 1.0\nstrong = 4.0\niterations = 3\nsoil = [\"C\", \"D\"]\n"
                          "coherency = \"harichandran-vanmarcke\"\npositions = [0.0, 80.0]\nvelocity = 400.0\n"
                          "realisations = 3\nfirst = 4\nseed = 7";

// The same settings as the command line gives them (pounding motions --positions 0,80 --velocity 400 ...).
spatial::Settings quick_settings() {
  spatial::Request q;
  q.duration = 8, q.rise = 1, q.strong = 4, q.iterations = 3, q.soil = {"C", "D"};
  q.coherency = "harichandran-vanmarcke", q.positions = {0.0, 80.0}, q.velocity = 400, q.realisations = 3, q.first = 4;
  q.seed = 7;
  q.given = {"duration", "rise", "strong", "iterations", "soil", "coherency", "positions", "velocity", "realisations",
             "first", "seed"};
  return spatial::settings_from(q);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(MotionRecords, AreTheMotionsCommandsRealisationsBitForBit) {
  const Study s = parse_study(study_text(quick), "m.toml");
  ASSERT_TRUE(s.motions);
  EXPECT_EQ(s.supports, 2);
  const std::vector<StudyRecord> recs = make_records(plan_study_records(s), 1);
  ASSERT_EQ(recs.size(), 3u);
  const spatial::Settings cli = quick_settings();
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const spatial::Realisation r = spatial::simulate(cli, 3 + i);  // --first 4: realisations 4, 5, 6
    SCOPED_TRACE(recs[i].id);
    EXPECT_EQ(recs[i].id, fmt::format("r{:03}", 4 + i));
    ASSERT_EQ(recs[i].more_supports.size(), 1u);
    EXPECT_TRUE(same_bits(recs[i].record.acc, r.supports[0].acc));
    EXPECT_TRUE(same_bits(recs[i].more_supports[0].acc, r.supports[1].acc));
    EXPECT_EQ(recs[i].record.dt, 0.01);
  }
}

TEST(MotionRecords, EqualTheWrittenAt2FilesToTheirRounding) {
  const Study s = parse_study(study_text(quick), "m.toml");
  const std::vector<StudyRecord> recs = make_records(plan_study_records(s), 1);
  const spatial::Settings cli = quick_settings();
  testdata::TempDir dir("motion-records");
  double worst = 0.0;
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const spatial::Realisation r = spatial::simulate(cli, 3 + i);
    for (std::size_t j = 0; j < 2; ++j) {
      const std::string path = dir.file(fmt::format("r{:03}_s{:02}.AT2", 4 + i, j + 1));
      write_at2(r.supports[j], path);  // what `pounding motions` writes (%15.7E in g)
      const Record file = read_record(path);
      const std::vector<double>& ours = j == 0 ? recs[i].record.acc : recs[i].more_supports[0].acc;
      ASSERT_EQ(file.acc.size(), ours.size());
      double peak = 0.0;
      for (double a : ours) peak = std::max(peak, std::abs(a));
      for (std::size_t k = 0; k < ours.size(); ++k) {
        EXPECT_LE(std::abs(file.acc[k] - ours[k]), 5.1e-8 * std::abs(ours[k]) + 1e-14 * peak) << k;
        worst = std::max(worst, std::abs(file.acc[k] - ours[k]) / peak);
      }
    }
  }
  EXPECT_GT(worst, 0.0);  // the files do round: the study keeps the doubles
  EXPECT_LT(worst, 1e-7);
}

TEST(MotionRecords, SharesOfThreadsAndRanksAreTheSerialRecords) {
  const Study s = parse_study(study_text(quick), "m.toml");
  const RecordPlan plan = plan_study_records(s);
  const std::vector<StudyRecord> serial = make_records(plan, 1);
  const std::vector<StudyRecord> threads = make_records(plan, 2);
  const std::vector<StudyRecord> ranks =
      join_record_shares({make_record_share(plan, 0, 2, 1), make_record_share(plan, 1, 2, 2)}, plan.count);
  for (const auto* other : {&threads, &ranks}) {
    ASSERT_EQ(other->size(), serial.size());
    for (std::size_t i = 0; i < serial.size(); ++i) {
      EXPECT_TRUE(same_bits((*other)[i].record.acc, serial[i].record.acc));
      EXPECT_TRUE(same_bits((*other)[i].more_supports[0].acc, serial[i].more_supports[0].acc));
      EXPECT_EQ((*other)[i].note, serial[i].note);
    }
  }
}

TEST(MotionRecords, AStopMakesNoFurtherRecordAndThrowsCancelled) {
  const Study s = parse_study(study_text(quick), "m.toml");
  const RecordPlan plan = plan_study_records(s);
  std::atomic<bool> stop{true};
  WorkHook hook;
  hook.cancel = &stop;
  EXPECT_THROW(make_records(plan, 1, &hook), Cancelled);
  // through the exchange between ranks too: the shares carry "stopped"
  EXPECT_THROW(join_record_shares({make_record_share(plan, 0, 2, 1, &hook), make_record_share(plan, 1, 2, 1)}, plan.count),
               Cancelled);
  stop = false;
  hook.progress = [](const PhaseProgress& p) { EXPECT_EQ(p.phase, "records: support motions"); };
  EXPECT_EQ(make_records(plan, 1, &hook).size(), 3u);
}

// The wave passage: support 2 (80 m downstream at 400 m/s) lags support 1 by 0.2 s = 20 steps; the lagged
// cross-correlation of the two channels, summed over the realisations, peaks there.
TEST(MotionRecords, TheCrossCorrelationPeaksAtSpacingOverVelocity) {
  const Study s = parse_study(study_text("soil = \"D\"\nloss = \"low\"\npositions = [0.0, 80.0]\nvelocity = 400.0\n"
                                         "duration = 10.0\niterations = 0\nrealisations = 4"),
                              "m.toml");
  const std::vector<StudyRecord> recs = make_records(plan_study_records(s), 0);
  const int max_lag = 60;
  std::vector<double> c(2 * max_lag + 1, 0.0);
  for (const StudyRecord& r : recs) {
    const std::vector<double>& a = r.record.acc;
    const std::vector<double>& b = r.more_supports.at(0).acc;
    for (int lag = -max_lag; lag <= max_lag; ++lag)
      for (std::size_t k = 0; k < a.size(); ++k) {
        const long m = static_cast<long>(k) + lag;
        if (m >= 0 && m < static_cast<long>(b.size())) c[static_cast<std::size_t>(lag + max_lag)] += a[k] * b[static_cast<std::size_t>(m)];
      }
  }
  const auto peak = std::max_element(c.begin(), c.end()) - c.begin() - max_lag;
  EXPECT_EQ(peak, 20) << "spacing / velocity = 80 / 400 s = 20 steps of 0.01 s";
}

struct Bad {
  std::string keys, key, what;
};

TEST(MotionRecords, BadKeysAreRefusedNamingTheKeyAndTheFile) {
  const std::vector<Bad> cases = {
      {"soil = \"D\"\nloss = \"high\"\ncoherency = \"smooth\"", "coherency", "unknown coherency model 'smooth'"},
      {"soil = \"D\"\nloss = \"high\"\nsupports = 1", "supports", "1 supports given"},
      {"soil = \"D\"\nloss = \"high\"\nsupports = 17", "supports", "17 supports given"},
      {"soil = \"D\"\nloss = \"high\"\nvelocity = -500.0", "velocity", "velocity = -500 is out of range"},
      {"soil = [\"A\", \"C\", \"D\"]\nloss = \"high\"", "soil", "3 site classes for 2 supports"},
      {"soil = \"F\"\nloss = \"high\"", "soil", "unknown NZS 1170.5 site class 'F'"},
      {"soil = [\"A\", 3]\nloss = \"high\"", "soil", "soil must be a site class or an array of them"},
      {"soil = \"D\"", "loss", "sobczyk needs a coherency loss level"},
      {"soil = \"D\"\nloss = \"high\"\nbeta = 0.001", "beta", "both loss and beta"},
      {"soil = \"D\"\nloss = \"high\"\ncoherency = \"harichandran-vanmarcke\"", "loss", "loss applies to coherency sobczyk only"},
      {"soil = \"D\"\nloss = \"high\"\npositions = [0.0, 100.0, 50.0]", "positions", "do not increase"},
      {"soil = \"D\"\nloss = \"high\"\npositions = [0.0, 100.0]\nspacing = 50.0", "positions", "positions with spacing"},
      {"soil = \"D\"\nloss = \"high\"\nf_max = 60.0", "f_max", "f_max 60 Hz is not below the Nyquist frequency"},
      {"soil = \"D\"\nloss = \"high\"\nrealisations = 0", "realisations", "0 realisations"},
      {"soil = \"D\"\nloss = \"high\"\nmatch_range = [4.0, 0.05]", "match_range", "not LO,HI"},
      {"soil = \"D\"\nloss = \"high\"\nz = 0.9", "z", ""},
      {"spectrum = \"csv\"\nloss = \"high\"", "spectrum_file", "spectrum csv needs a spectrum file"},
      {"spectrum = \"ec8\"\nloss = \"high\"", "spectrum", "unknown spectrum 'ec8'"},
      {"soil = \"D\"\nloss = \"high\"\nwave_passage = \"no\"", "wave_passage", "wave_passage must be true or false"},
      {"soil = \"D\"\nloss = \"high\"\nsupport = 2", "support", "unknown key 'support'"},
  };
  for (const Bad& b : cases) {
    SCOPED_TRACE(b.keys);
    const InputError e = testdata::input_error([&] { parse_study(study_text(b.keys), "bad.toml"); });
    EXPECT_NE(e.where().find("bad.toml:"), std::string::npos) << e.where();
    EXPECT_NE(e.where().find("[records.motions]." + b.key), std::string::npos) << e.where() << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(b.what), std::string::npos) << e.what();
  }
}

TEST(MotionRecords, TheRecordsTableRefusesWhatDoesNotApply) {
  const std::string motions = "soil = \"D\"\nloss = \"high\"";
  const auto where = [&](const std::string& text) {
    return testdata::input_error([&] { parse_study(text, "bad.toml"); }).where();
  };
  const std::string with_supports = "seed = 1\n[records]\nsupports = 2\n[records.motions]\n" + motions + "\n" + bridge;
  EXPECT_NE(where(with_supports).find("[records].supports"), std::string::npos);
  const std::string two_sources = "seed = 1\n[records]\nsuite = \"builtin\"\n[records.motions]\n" + motions + "\n" + bridge;
  EXPECT_NE(where(two_sources).find("bad.toml [records]"), std::string::npos);
  const std::string no_bridge = "seed = 1\n[records]\n[records.motions]\n" + motions + "\n";
  EXPECT_NE(where(no_bridge).find("[records].motions"), std::string::npos);
  // three frames on supports 1..3 and two generated supports
  std::string three = study_text(motions);
  three.insert(three.find("[contact]"), "[[bridge.frame]]\nmass = 1.0e6\nperiod = 1.0\nsupport = 3\n[[bridge.joint]]\ngap = 0.05\n");
  EXPECT_NE(where(three).find("[records].motions"), std::string::npos);
}

TEST(MotionRecords, UniformGivesEverySupportTheMotionOfSupportOne) {
  const Study s = parse_study(study_text(quick), "m.toml");
  const Study u = parse_study(study_text(quick + "\nuniform = true"), "m.toml");
  const std::vector<StudyRecord> a = make_records(plan_study_records(s), 1), b = make_records(plan_study_records(u), 1);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(same_bits(b[i].record.acc, a[i].record.acc));
    EXPECT_TRUE(same_bits(b[i].more_supports.at(0).acc, a[i].record.acc));
    EXPECT_FALSE(same_bits(a[i].more_supports.at(0).acc, a[i].record.acc));
  }
}

TEST(MotionRecords, TheStudySeedIsTheDefault) {
  const Study s = parse_study(study_text("soil = \"D\"\nloss = \"high\""), "m.toml");
  EXPECT_EQ(s.motions->settings.seed, 11u);
  EXPECT_FALSE(s.motions->seed_given);
  EXPECT_EQ(s.motions->count, 20u);
  EXPECT_EQ(s.motions->first, 0u);
}

}  // namespace
}  // namespace pounding
