// The records of a study made in shares (issue 27 item 3, study/study.hpp RecordPlan): threads and ranks share
// the reading and synthesis, and the joined shares are the serial records bit for bit, in order, with the first
// failing record's error (in record order, not in the order of the ranks or threads that met it).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "pounding/core/error.hpp"
#include "pounding/study/study.hpp"
#include "temp_dir.hpp"

namespace pounding {
namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

void expect_same(const std::vector<StudyRecord>& a, const std::vector<StudyRecord>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(a[i].id);
    EXPECT_TRUE(same_bits(a[i].record.acc, b[i].record.acc));
    EXPECT_EQ(std::memcmp(&a[i].record.dt, &b[i].record.dt, sizeof(double)), 0);
    EXPECT_EQ(a[i].record.name, b[i].record.name);
    EXPECT_EQ(a[i].record.source, b[i].record.source);
    EXPECT_EQ(a[i].record.meta, b[i].record.meta);
    EXPECT_EQ(a[i].record.peak_line, b[i].record.peak_line);
    EXPECT_EQ(a[i].synthetic, b[i].synthetic);
    EXPECT_EQ(a[i].id, b[i].id);
    EXPECT_EQ(a[i].note, b[i].note);
    EXPECT_EQ(a[i].polarity, b[i].polarity);
    ASSERT_EQ(a[i].more_supports.size(), b[i].more_supports.size());
    for (std::size_t j = 0; j < a[i].more_supports.size(); ++j) {
      EXPECT_TRUE(same_bits(a[i].more_supports[j].acc, b[i].more_supports[j].acc));
      EXPECT_EQ(a[i].more_supports[j].source, b[i].more_supports[j].source);
      EXPECT_EQ(a[i].more_supports[j].meta, b[i].more_supports[j].meta);
    }
  }
}

// The built-in suite's synthetic stand-ins (the paper study's inputs), the first `n` entries.
RecordPlan builtin_plan(std::size_t n) {
  const Study s = parse_study("seed = 1\nscene = \"probability\"\n[records]\nsuite = \"builtin\"\n", "t.toml");
  RecordPlan p = plan_study_records(s);
  EXPECT_GE(p.count, n);
  p.count = n;
  return p;
}

TEST(RecordShares, ThreadsAndRanksGiveTheSerialRecordsBitForBit) {
  const RecordPlan plan = builtin_plan(7);
  std::vector<StudyRecord> serial;
  for (std::size_t i = 0; i < plan.count; ++i) serial.push_back(plan.make(i));
  expect_same(make_records(plan, 1), serial);
  expect_same(make_records(plan, 3), serial);
  for (int ranks : {1, 2, 3, 8}) {  // 8 ranks: some make nothing
    SCOPED_TRACE(ranks);
    std::vector<std::string> shares;
    for (int r = 0; r < ranks; ++r) shares.push_back(make_record_share(plan, r, ranks, r % 2 + 1));
    expect_same(join_record_shares(shares, plan.count), serial);
  }
}

TEST(RecordShares, MultiSupportRecordsTravelWhole) {
  // a bridge's realisation ([records] supports): every support's motion crosses between ranks with the first
  const RecordPlan base = builtin_plan(3);
  const RecordPlan plan{3, [&base](std::size_t i) {
                          StudyRecord r = base.make(i);
                          for (std::size_t j = 0; j < i; ++j) r.more_supports.push_back(base.make((i + j + 1) % 3).record);
                          return r;
                        }, {}, {}};
  const std::vector<StudyRecord> serial = make_records(plan, 1);
  EXPECT_EQ(serial[2].more_supports.size(), 2u);
  expect_same(join_record_shares({make_record_share(plan, 0, 2), make_record_share(plan, 1, 2)}, plan.count), serial);
}

TEST(RecordShares, FileRecordsKeepWhatTheReaderFound) {
  // [records] files through the plan: a PEER AT2 file's header (event, station, units) and peak line, and a file
  // scale, survive the exchange between ranks
  testdata::TempDir tmp("shares");
  {
    std::ofstream f(tmp.file("Test_1999_Station_090.AT2"));
    f << "PEER NGA STRONG MOTION DATABASE RECORD\nTest 1999-01-01, Station, 90\n"
         "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   300, DT=   .0100 SEC\n";
    for (int i = 0; i < 300; ++i)  // 3 s; the peak 0.1 g is the 4th value, on line 5
      f << (i == 3 ? 0.1 : 0.01 * ((i % 7) - 3) / 3.0) << (i % 5 == 4 ? "\n" : "  ");
  }
  const Study s = parse_study("seed = 1\nscene = \"probability\"\n[records]\nfiles = [{path = \"" +
                                  tmp.file("Test_1999_Station_090.AT2") + "\", scale = 2.0}]\n",
                              "t.toml");
  const RecordPlan plan = plan_study_records(s);
  ASSERT_EQ(plan.count, 1u);
  const std::vector<StudyRecord> one = make_records(plan, 1);
  expect_same(join_record_shares({make_record_share(plan, 0, 2), make_record_share(plan, 1, 2)}, 1), one);
  EXPECT_EQ(one[0].record.peak_line, 5);
  EXPECT_DOUBLE_EQ(one[0].record.pga(), 0.2 * 9.80665);
  EXPECT_FALSE(one[0].record.meta.empty());
}

TEST(RecordShares, TheFirstFailingRecordInOrderIsTheError) {
  // records 2 and 4 fail; with 3 ranks record 4's rank (1) is lower than record 2's (2), with 2 threads record 4
  // is met by the second thread, and the error is record 2's, what, where and fix, as the serial loop gives it
  const RecordPlan good = builtin_plan(2);
  RecordPlan plan{6, [&good](std::size_t i) -> StudyRecord {
                    if (i == 2) throw InputError("record two is bad", "suite.toml:12", "fix two");
                    if (i == 4) throw InputError("record four is bad", "suite.toml:14", "fix four");
                    return good.make(i % 2);
                  }, {}, {}};
  auto expect_two = [](auto&& f) {
    try {
      f();
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.what_part(), "record two is bad");
      EXPECT_EQ(e.where(), "suite.toml:12");
      EXPECT_EQ(e.fix(), "fix two");
    }
  };
  expect_two([&] { make_records(plan, 1); });
  expect_two([&] { make_records(plan, 2); });
  for (int ranks : {1, 3, 4}) {
    SCOPED_TRACE(ranks);
    std::vector<std::string> shares;
    for (int r = 0; r < ranks; ++r) shares.push_back(make_record_share(plan, r, ranks, 2));
    expect_two([&] { join_record_shares(shares, plan.count); });
  }
  // a share that does not cover every record, or covers one twice, is an error, not a silent hole
  EXPECT_THROW(join_record_shares({make_record_share(plan, 0, 2)}, plan.count), std::runtime_error);
  const std::string s0 = make_record_share(plan, 0, 1);
  EXPECT_THROW(join_record_shares({s0, s0}, plan.count), std::runtime_error);
  EXPECT_THROW(join_record_shares({s0.substr(0, s0.size() / 2)}, plan.count), std::runtime_error);
}

}  // namespace
}  // namespace pounding
