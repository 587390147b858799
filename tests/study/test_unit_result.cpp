// The per-unit result schema (C16): a test-only field, added as one row, travels through UnitResult
// serialisation, the checkpoint (a torn last record is dropped and the unit recomputed), the Tally's scatter,
// the HDF5 writer and the reader, with every value in its place.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "pounding/model/shear_building.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/results/writer.hpp"
#include "pounding/study/checkpoint.hpp"
#include "pounding/study/make_results.hpp"
#include "pounding/study/reductions.hpp"
#include "pounding/study/study.hpp"
#include "pounding/study/tally.hpp"
#include "pounding/study/unit_result.hpp"
#include "results/sample_results.hpp"
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

// Format 3 through the study's path: a plan whose /system is a 3- vs 5-storey pair sizes the per-floor and
// per-element rows from it; a UnitComputer fills them with lane_values; the tally scatters them to
// [records, models, floors | elements | gaps, elements]; the file holds each value in its place.
TEST(UnitResult, PerFloorAndPerElementValuesReachTheirPlaceInTheFile) {
  WorkPlan plan;
  plan.records = 2, plan.pairs = 1, plan.samples = 5, plan.batch = 2, plan.blocks = 3, plan.gaps = 2, plan.impacts = true;
  plan.system = testdata::sample_system_table();
  plan.fields = results::unit_schema(true, false, false, plan.system.extents());
  EXPECT_EQ(plan.format_version(), 3);
  const std::size_t u2 = results::field_index(plan.fields, "uncoupled", results::building_name("peak_u_floors{b}", 2));
  const std::size_t acc1 = results::field_index(plan.fields, "uncoupled", "peak_acc_floors1");
  const std::size_t force = results::field_index(plan.fields, "impacts", "element_peak_force");
  const std::size_t count = results::field_index(plan.fields, "impacts", "element_impact_count");
  EXPECT_EQ(plan.per_lane(plan.fields[u2]), 5u);
  EXPECT_EQ(plan.per_lane(plan.fields[acc1]), 3u);
  EXPECT_EQ(plan.per_lane(plan.fields[force]), 2u * 3u);
  // unit_fields keep their indices (run.cpp's constexpr field numbers)
  for (std::size_t k = 0; k < std::size(results::unit_fields); ++k) EXPECT_EQ(plan.fields[k].name, results::unit_fields[k].name);
  const auto at = [](std::size_t unit, std::size_t lane, std::size_t j) {
    return static_cast<double>(100 * unit + 10 * lane + j);
  };
  Tally tally(plan);
  for (std::size_t u = 0; u < plan.units(); ++u) {
    const std::size_t lanes = plan.lanes(plan.decode(u).block);
    UnitResult r(plan, lanes);
    for (std::size_t lane = 0; lane < lanes; ++lane) {
      auto floors = r.lane_values<double>(u2, lane);
      ASSERT_EQ(floors.size(), 5u);
      for (std::size_t j = 0; j < 5; ++j) floors[j] = at(u, lane, j);
      auto e = r.lane_values<double>(force, lane);  // [gap][element]
      for (std::size_t j = 0; j < e.size(); ++j) e[j] = at(u, lane, j);
      auto c = r.lane_values<std::int32_t>(count, lane);
      for (std::size_t j = 0; j < c.size(); ++j) c[j] = static_cast<std::int32_t>(at(u, lane, j));
    }
    EXPECT_THROW(r.lane_values<double>(u2, lanes), std::out_of_range);
    EXPECT_THROW(r.lane_values<double>(count, 0), std::logic_error);  // i32
    tally.store(u, UnitResult::deserialise(plan, lanes, r.serialise()).serialise());
  }
  TempDir t;
  results::Results res;
  res.records.id = {"R1", "R2"};
  for (const auto& [name, member] : results::model_doubles) (res.models.*member).assign(plan.models(), 1.0);
  res.gap_ratios = {0.3, 0.6};
  res.fields = tally.take_fields();
  res.system = plan.system;
  results::write(t.file("r.h5"), res);
  const results::Results back = results::load(t.file("r.h5"));
  EXPECT_EQ(back.header.format_version, 3);
  const auto& fl = back.column<double>("uncoupled", "peak_u_floors2");
  const auto& ef = back.column<double>("impacts", "element_peak_force");
  const auto& ec = back.column<std::int32_t>("impacts", "element_impact_count");
  const auto& a1 = back.column<double>("uncoupled", "peak_acc_floors1");
  const std::size_t M = plan.models();
  ASSERT_EQ(fl.size(), 2 * M * 5);
  ASSERT_EQ(ef.size(), 2 * M * 2 * 3);
  for (std::size_t u = 0; u < plan.units(); ++u) {
    const UnitIndex i = plan.decode(u);
    for (std::size_t lane = 0; lane < plan.lanes(i.block); ++lane) {
      const std::size_t q = i.record * M + plan.first_model(i) + lane;
      for (std::size_t j = 0; j < 5; ++j) EXPECT_EQ(fl[q * 5 + j], at(u, lane, j)) << "unit " << u << " floor " << j;
      for (std::size_t g = 0; g < 2; ++g)
        for (std::size_t e = 0; e < 3; ++e) {
          EXPECT_EQ(ef[(q * 2 + g) * 3 + e], at(u, lane, g * 3 + e)) << "unit " << u << " gap " << g << " element " << e;
          EXPECT_EQ(ec[(q * 2 + g) * 3 + e], static_cast<std::int32_t>(at(u, lane, g * 3 + e)));
        }
      for (std::size_t j = 0; j < 3; ++j) EXPECT_TRUE(std::isnan(a1[q * 3 + j]));  // not filled: the row's fill
    }
  }
}

// The study's conversion of a model::System into /system (make_results.hpp system_table): the 3- vs 5-storey pair of
// model::shear_buildings is the table written out by hand; the SDOF pair gives none (format 2).
// A stick of n storeys with every other field at its default (designated initializers would warn about the rest).
static model::StickTopology stick(int n) {
  model::StickTopology t;
  t.storeys = n;
  return t;
}

TEST(SystemTable, OfAShearPairIsItsTopology) {
  const model::StickTopology sticks[] = {stick(3), stick(5)};
  const model::System s = model::shear_buildings(sticks);
  const ContactModel pounding{};  // hertzdamp, lankarani-nikravesh
  const results::SystemTable t = system_table(s, std::span(&pounding, 1));
  EXPECT_EQ(t, testdata::sample_system_table());
  EXPECT_EQ(extents_of(s), t.extents());
  EXPECT_EQ(extents_of(s), (results::Extents{{3, 5}, 3}));
  EXPECT_TRUE(system_table(model::System::sdof_pair(), std::span(&pounding, 1)).empty());
  EXPECT_TRUE(extents_of(model::System::sdof_pair()).empty());
  EXPECT_THROW(system_table(s, {}), std::logic_error);  // one ContactModel per group
  const double offsets[] = {0.0, 0.01};
  EXPECT_THROW(system_table(s, std::span(&pounding, 1), offsets), std::logic_error);  // one offset per element
}

// An isolated building with its moat beside a fixed one: the base is floor 0 at 0 m, the isolator spring storey 0,
// the moat's wall sides have no DOF, its group its own law.
TEST(SystemTable, IsolatedBaseAndMoatWalls) {
  model::StickTopology iso = stick(2);
  iso.isolated = true, iso.moat = true;
  const model::StickTopology sticks[] = {iso, stick(2)};
  const model::System s = model::shear_buildings(sticks);
  ASSERT_EQ(s.groups().size(), 2u);
  const ContactModel groups[] = {{}, {.law = ContactLaw::linear}};
  const double offsets[] = {0.0, 0.0, 0.3, 0.3};
  const results::SystemTable t = system_table(s, groups, offsets);
  EXPECT_EQ(t.building_floors, (std::vector<std::int32_t>{3, 2}));
  EXPECT_EQ(t.building_isolated, (std::vector<std::uint8_t>{1, 0}));
  const std::size_t base = static_cast<std::size_t>(s.bodies()[0].dofs[0]);
  EXPECT_EQ(t.dof_floor[base], 0);
  EXPECT_EQ(t.dof_height[base], 0.0);
  EXPECT_EQ(t.spring_role[static_cast<std::size_t>(s.spring_below(static_cast<int>(base)))], "isolator");
  EXPECT_EQ(t.spring_storey[static_cast<std::size_t>(s.spring_below(static_cast<int>(base)))], 0);
  ASSERT_EQ(t.element_label.size(), 4u);
  EXPECT_EQ(t.element_label[2], "building1 moat left");
  EXPECT_EQ(t.element_left_kind[2], "wall");
  EXPECT_EQ(t.element_left_dof[2], -1);
  EXPECT_EQ(t.element_right_dof[2], static_cast<std::int32_t>(base));
  EXPECT_EQ(t.element_level_height[2], 0.0);
  EXPECT_EQ(t.element_gap_offset[3], 0.3);
  EXPECT_EQ(t.group_name, (std::vector<std::string>{"pounding", "moat building1"}));
  EXPECT_EQ(t.group_law, (std::vector<std::string>{"hertzdamp", "linear"}));
  EXPECT_EQ(t.group_study_gap, (std::vector<std::uint8_t>{1, 0}));
  EXPECT_EQ(t.group_elements, (std::vector<std::int32_t>{2, 2}));
  EXPECT_EQ(t.check(), "");
}

// A floor meeting a column between two floors: the interpolated side's weight xi = (level - h_p) / (h_q - h_p).
TEST(SystemTable, FloorToColumnWeight) {
  model::System::Parts p;
  p.bodies = {{.dofs = {0}, .heights = {4.8}, .label = "building1"},
              {.dofs = {1, 2}, .heights = {3.2, 6.4}, .label = "building2"}};
  p.springs = {{.i = model::ground, .j = 0, .body = 0, .storey = 1},
               {.i = model::ground, .j = 1, .body = 1, .storey = 1},
               {.i = 1, .j = 2, .body = 1, .storey = 2}};
  p.contacts = {{.left = {.kind = model::SideKind::point, .p = 0},
                 .right = {.kind = model::SideKind::interpolated, .p = 1, .q = 2},
                 .level = 1,
                 .label = "floor 1 to column",
                 .xi = 0.5}};  // the element's own xi (the kernel's weight), not one derived from the heights
  p.groups = {{}};
  const auto problems = model::System::check(p);
  ASSERT_TRUE(problems.empty()) << problems[0].what << " at " << problems[0].where;
  const model::System s = model::System::build(p);
  const ContactModel pounding{};
  const results::SystemTable t = system_table(s, std::span(&pounding, 1));
  EXPECT_EQ(t.element_right_kind[0], "interpolated");
  EXPECT_EQ(t.element_right_dof[0], 1);
  EXPECT_EQ(t.element_right_dof2[0], 2);
  EXPECT_DOUBLE_EQ(t.element_right_xi[0], 0.5);
  EXPECT_EQ(t.element_left_xi[0], 0.0);
  EXPECT_EQ(t.element_level_height[0], 4.8);
}

// Issue 27.4: under MPI every rank folds the units it computes into its own Reductions and rank 0 sums the counts and
// merges the summaries. Folding the units split over three "ranks" (by unit id modulo 3, one of them given none, and
// a varied pair seen only by one) and merging must equal folding every unit into one, count for count.
TEST(Reductions, MergedRanksEqualOneFold) {
  const Study study = parse_study("seed = 5\nscene = \"probability\"\n[records]\nsuite = \"builtin\"\nsynthetic_only = "
                                  "true\nlimit = 2\n[outputs]\nper_model = false\n[structures]\nperiods = [1.0, 1.2]\n"
                                  "samples_per_pair = 5\n[gaps]\nratios = [0.1, 0.5, 1.0]\n",
                                  "merge.toml");
  WorkPlan p;
  p.records = 2, p.pairs = static_cast<std::size_t>(study.structures.period_pair_count()), p.samples = 5, p.batch = 2;
  p.blocks = 3, p.gaps = 3, p.per_model = false;
  ASSERT_EQ(p.pairs, 4u);
  Reductions one(study, p), ranks[3] = {Reductions(study, p), Reductions(study, p), Reductions(study, p)};
  for (std::size_t unit = 0; unit < p.units(); ++unit) {
    const UnitIndex i = p.decode(unit);
    const std::size_t lanes = p.lanes(i.block);
    std::vector<std::uint8_t> status(lanes, 0);
    std::vector<double> closing(lanes);
    for (std::size_t j = 0; j < lanes; ++j) {
      closing[j] = 0.002 * static_cast<double>((unit * 7 + j * 3) % 40);  // 0 .. 0.078 m, some above x d
      if ((unit + j) % 9 == 4) status[j] = 1;                              // some excluded
    }
    one.fold(i, status, closing);
    ranks[unit % 3 == 2 ? 1 : 2].fold(i, status, closing);  // rank 0 (index 0) folds nothing
  }
  std::vector<std::int64_t> sum = ranks[0].counts();
  for (int r = 1; r < 3; ++r) {
    const std::vector<std::int64_t> c = ranks[r].counts();
    ASSERT_EQ(c.size(), sum.size());
    for (std::size_t k = 0; k < c.size(); ++k) sum[k] += c[k];
  }
  ranks[0].set_counts(sum);
  for (int r = 1; r < 3; ++r) ranks[0].merge_summary(ranks[r].summary());
  EXPECT_EQ(ranks[0].counts(), one.counts());
  // seen, varied, the code gaps' range (the first model kept is whichever came first: not part of the result)
  const std::vector<double> merged = ranks[0].summary(), all = one.summary();
  EXPECT_EQ(std::vector<double>(merged.begin(), merged.begin() + 4), std::vector<double>(all.begin(), all.begin() + 4));
  EXPECT_GT(one.counts()[0], 0);
  EXPECT_EQ(one.summary()[1], 1.0);  // the models vary (several period pairs): "not one fixed pair" survives a merge
  const auto has = [](const results::Group& g, const std::string& a) { return g.find(a) != nullptr; };
  EXPECT_TRUE(has(ranks[0].group(), "histogram"));
}
