// The per-unit result schema (C16): a test-only field, added as one row, travels through UnitResult
// serialisation, the checkpoint (a torn last record is dropped and the unit recomputed), the Tally's scatter,
// the HDF5 writer and the reader, with every value in its place.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "pounding/results/reader.hpp"
#include "pounding/results/writer.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/tally.hpp"
#include "pounding/study/unit_result.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace pounding;

namespace {

struct TempDir : testdata::TempDir {
  TempDir() : testdata::TempDir("unit") {}
};

// The test-only row: per lane and gap, 64-bit integers, in a group of its own.
constexpr results::FieldSpec probe{"test", "probe", results::Dtype::i64, results::Extent::lane_gap, -7, "1",
                                   "a test-only field"};

// 2 records x 1 period pair x 5 samples in blocks of 2 (3 blocks, the last with one lane) x 2 gaps: 6 units.
WorkPlan test_plan() {
  WorkPlan p;
  p.records = 2, p.pairs = 1, p.samples = 5, p.batch = 2, p.blocks = 3, p.gaps = 2, p.impacts = true;
  p.fields = results::unit_schema(true);
  p.fields.push_back(probe);
  return p;
}

// A value that names its place (unit, lane, gap and field) and fits every dtype (u8 included).
double value(std::size_t unit, std::size_t lane, std::size_t gap, std::size_t field) {
  return static_cast<double>(40 * unit + 10 * lane + 3 * gap + field % 3);
}

UnitResult compute(const WorkPlan& plan, std::size_t unit) {
  const std::size_t lanes = plan.lanes(plan.decode(unit).block);
  UnitResult u(plan, lanes);
  for (std::size_t k = 0; k < plan.fields.size(); ++k) {
    const std::size_t per = plan.per_lane(plan.fields[k]);
    auto fill = [&](auto span) {
      for (std::size_t i = 0; i < lanes; ++i)
        for (std::size_t g = 0; g < per; ++g)
          span[i * per + g] = static_cast<typename decltype(span)::value_type>(value(unit, i, g, k));
    };
    switch (plan.fields[k].dtype) {
      case results::Dtype::u8: fill(u.values<std::uint8_t>(k)); break;
      case results::Dtype::i32: fill(u.values<std::int32_t>(k)); break;
      case results::Dtype::i64: fill(u.values<std::int64_t>(k)); break;
      case results::Dtype::f64: fill(u.values<double>(k)); break;
    }
  }
  return u;
}

CheckpointKey key() {
  CheckpointKey k;
  k.study_hash = 1, k.units = 6, k.build_hash = 2, k.build = "unit-result test";
  return k;
}

}  // namespace

TEST(UnitResult, SerialisationIsTypedAndChecked) {
  const WorkPlan plan = test_plan();
  const UnitResult u = compute(plan, 4);  // record 1, block 1: 2 lanes
  const auto bytes = u.serialise();
  // per lane: u8 + 3 f64; per lane and gap: u8 + i32 + 5 f64 (h_omega_contact the fifth) + the probe's i64
  EXPECT_EQ(bytes.size(), 2 * (1 + 3 * 8) + 2 * 2 * (1 + 4 + 5 * 8 + 8));
  EXPECT_EQ(bytes.size(), serialised_size(plan, 2));
  UnitResult back = UnitResult::deserialise(plan, 2, bytes);
  EXPECT_EQ(back.serialise(), bytes);
  EXPECT_EQ(back.values<std::int64_t>(plan.fields.size() - 1)[3], 160 + 11 + 3 + 1);  // lane 1, gap 1, field 11
  EXPECT_THROW(UnitResult::deserialise(plan, 1, bytes), std::runtime_error);
  EXPECT_THROW(back.values<double>(0), std::logic_error);  // status is u8
}

TEST(UnitResult, TestFieldRoundTripsThroughCheckpointTallyWriterAndReader) {
  TempDir t;
  const WorkPlan plan = test_plan();
  const std::string ckpt_path = t.file("r.h5.ckpt");
  {
    Checkpoint c(ckpt_path);
    open_for_run(c, key(), false, false, {});
    for (std::size_t u = 0; u < plan.units(); ++u) c.append(u, compute(plan, u).serialise());
  }
  fs::resize_file(ckpt_path, fs::file_size(ckpt_path) - 3);  // killed while writing the last unit
  Tally tally(plan);
  {
    Checkpoint c(ckpt_path);
    const auto loaded = open_for_run(c, key(), true, false,
                                     [&](std::size_t u, std::vector<std::byte>&& d) { tally.store(u, d); });
    EXPECT_EQ(loaded, 5u);
    EXPECT_FALSE(tally.done(5));
    c.append(5, compute(plan, 5).serialise());  // --resume recomputes it
  }
  Tally resumed(plan);
  {
    Checkpoint c(ckpt_path);
    EXPECT_EQ(open_for_run(c, key(), true, false,
                           [&](std::size_t u, std::vector<std::byte>&& d) { resumed.store(u, d); }),
              6u);
  }
  EXPECT_EQ(resumed.units_done(), 6u);

  results::Results r;
  r.records.id = {"R1", "R2"};
  for (const auto& [name, member] : results::model_doubles) (r.models.*member).assign(plan.models(), 1.0);
  r.gap_ratios = {0.3, 0.6};
  r.fields = resumed.take_fields();
  results::write(t.file("r.h5"), r);
  const results::Results back = results::load(t.file("r.h5"), std::span(&probe, 1));

  const auto& got = back.column<std::int64_t>("test", "probe");
  const auto& status = back.column<std::uint8_t>("impacts", "status");
  const auto& closing = back.column<double>("uncoupled", "peak_closing");
  ASSERT_EQ(got.size(), 2u * 5u * 2u);
  const std::size_t k_probe = plan.fields.size() - 1, M = plan.models();
  for (std::size_t u = 0; u < plan.units(); ++u) {
    const UnitIndex i = plan.decode(u);
    for (std::size_t lane = 0; lane < plan.lanes(i.block); ++lane) {
      const std::size_t q = i.record * M + plan.first_model(i) + lane;
      EXPECT_EQ(closing[q], value(u, lane, 0, 3)) << "unit " << u << " lane " << lane;
      for (std::size_t g = 0; g < 2; ++g) {
        EXPECT_EQ(got[q * 2 + g], static_cast<std::int64_t>(value(u, lane, g, k_probe))) << "unit " << u;
        EXPECT_EQ(status[q * 2 + g], static_cast<std::uint8_t>(value(u, lane, g, 4))) << "unit " << u;
      }
    }
  }
}

TEST(Tally, RefusesAPayloadOfTheWrongSize) {
  const WorkPlan plan = test_plan();
  Tally tally(plan);
  auto bytes = compute(plan, 2).serialise();  // block 2: one lane
  EXPECT_THROW(tally.store(0, bytes), std::runtime_error);  // unit 0 has two lanes
  tally.store(2, bytes);
  EXPECT_TRUE(tally.done(2));
  EXPECT_EQ(tally.units_done(), 1u);
  tally.store(2, bytes);
  EXPECT_EQ(tally.units_done(), 1u);
}
