// The results module (include/pounding/results/): a Results written to a file and read back is the same,
// every dataset and attribute; the file holds exactly the items format 2 defines, with their shapes, and every
// dataset says its units and meaning; a format-1 file still reads into the same Results; typed settings look-ups.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <set>

#include "pounding/io/hdf5.hpp"
#include "pounding/report/report.hpp"
#include "pounding/results/describe.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/results/writer.hpp"
#include "results/results_compare.hpp"
#include "results/sample_results.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"

namespace fs = std::filesystem;
using namespace pounding;

namespace {

struct TempDir : testdata::TempDir {
  TempDir() : testdata::TempDir("results") {}
};

std::set<std::string> as_set(const std::vector<std::string>& v) { return {v.begin(), v.end()}; }

using Shape = std::vector<std::size_t>;

// Every dataset under `g` (recursively), as "/group/name", with its `units` and `description` (empty if absent).
void datasets(h5::hid g, const std::string& path, std::vector<std::array<std::string, 3>>& out) {
  for (const std::string& name : h5::member_names(g)) {
    if (h5::is_group(g, name)) {
      datasets(h5::open_group(g, name).get(), path + "/" + name, out);
      continue;
    }
    auto ds = h5::open_dataset(g, name);
    const auto attr = [&](const char* a) {
      return h5::attribute_exists(ds.get(), a) ? h5::read_string_attribute(ds.get(), a) : std::string();
    };
    out.push_back({path + "/" + name, attr("units"), attr("description")});
  }
}

}  // namespace

TEST(Results, RoundTripKeepsEveryDatasetAndAttribute) {
  TempDir t;
  const results::Results a = testdata::sample_results();
  results::write(t.file("a.h5"), a);
  results::Results b = results::load(t.file("a.h5"));
  EXPECT_EQ(b.path, t.file("a.h5"));
  testdata::expect_same_results(a, b);
  // and again: what was read writes the same file
  results::write(t.file("b.h5"), b);
  testdata::expect_same_results(a, results::load(t.file("b.h5")));
}

TEST(Results, FileHoldsTheFormatTwoLayout) {
  TempDir t;
  results::write(t.file("a.h5"), testdata::sample_results());
  auto f = h5::open_read(t.file("a.h5"));
  const h5::hid root = f.get();
  EXPECT_EQ(as_set(h5::member_names(root)),
            (std::set<std::string>{"gaps", "impacts", "models", "records", "settings", "uncoupled"}));
  EXPECT_EQ(as_set(h5::attribute_names(root)),
            (std::set<std::string>{"build", "contact_law", "damping_law", "date", "exclusion_warning",
                                   "excluded_analyses", "format_version", "git_commit", "max_dt",
                                   "max_excluded_fraction", "program_version", "ranks", "restitution", "scene",
                                   "scene_reason", "seed", "stepper", "study_path", "study_text", "substeps", "title",
                                   "total_analyses", "wall_time_s"}));
  auto unc = h5::open_group(root, "uncoupled");
  EXPECT_EQ(h5::read_string_attribute(unc.get(), "shape"), "[records, models]");
  EXPECT_EQ(as_set(h5::member_names(unc.get())),
            (std::set<std::string>{"peak_closing", "peak_u1", "peak_u2", "status"}));
  auto imp = h5::open_group(root, "impacts");
  EXPECT_EQ(h5::read_string_attribute(imp.get(), "shape"), "[records, models, gaps]");
  EXPECT_EQ(as_set(h5::member_names(imp.get())),
            (std::set<std::string>{"amplification_u1", "amplification_u2", "gap_ratios", "impact_count",
                                   "peak_force", "peak_u1", "peak_u2", "status", "t_first_impact"}));
  EXPECT_EQ(h5::member_names(h5::open_group(root, "models").get()).size(), std::size(results::model_doubles) + 6);  // i1, i2, sample, periods, periods1, periods2
  EXPECT_EQ(h5::member_names(h5::open_group(root, "records").get()).size(), 9u);
  // booleans are 0/1 integers; lists of strings and empty lists survive
  auto rec = h5::open_group(h5::open_group(root, "settings").get(), "records");
  EXPECT_EQ(h5::attribute_kind(rec.get(), "synthetic_only"), h5::AttributeKind::integer);
  EXPECT_EQ(h5::read_strings_attribute(rec.get(), "files"), (std::vector<std::string>{"a.AT2", "b.AT2"}));

  // format 2: status has the shape of what it qualifies, /gaps in metres
  EXPECT_EQ(h5::read_int64_attribute(root, "format_version"), 2);
  for (const std::string& name : h5::member_names(unc.get()))
    EXPECT_EQ(h5::dataset_shape(unc.get(), name), (Shape{2, 4})) << "/uncoupled/" << name;
  for (const std::string& name : h5::member_names(imp.get()))
    EXPECT_EQ(h5::dataset_shape(imp.get(), name), (name == "gap_ratios" ? Shape{2} : Shape{2, 4, 2})) << name;
  auto gaps = h5::open_group(root, "gaps");
  EXPECT_EQ(as_set(h5::member_names(gaps.get())), (std::set<std::string>{"metres", "ratios"}));
  EXPECT_EQ(h5::dataset_shape(gaps.get(), "ratios"), Shape{2});
  EXPECT_EQ(h5::dataset_shape(gaps.get(), "metres"), (Shape{4, 2}));
  // metres = ratio x code gap, model-major (code gaps 0.1 ... 0.4, ratios 0.2, 0.5)
  const std::vector<double> metres = h5::read_doubles(gaps.get(), "metres");
  EXPECT_EQ(metres[0], 0.2 * 0.1);
  EXPECT_EQ(metres[7], 0.5 * 0.4);
}

TEST(Results, EveryDatasetSaysItsUnitsAndMeaning) {
  TempDir t;
  results::Results a = testdata::sample_results();
  // every field of the schema, h_omega_contact included (the sample has no values for it)
  a.fields.push_back({results::unit_fields[results::unit_field("impacts", "h_omega_contact")],
                      results::make_column(results::unit_fields[results::unit_field("impacts", "h_omega_contact")], 16)});
  results::write(t.file("a.h5"), a);
  auto f = h5::open_read(t.file("a.h5"));
  std::vector<std::array<std::string, 3>> all;
  datasets(f.get(), "", all);
  // records 9, models: the doubles + i1, i2, sample, periods, periods1, periods2; gaps 2; uncoupled 4; impacts 10
  EXPECT_EQ(all.size(), 9u + std::size(results::model_doubles) + 6 + 2 + 4 + 10);
  for (const auto& [path, units, description] : all) {
    EXPECT_FALSE(units.empty()) << path << " has no units";
    EXPECT_FALSE(description.empty()) << path << " has no description";
  }
  const auto find = [&](const std::string& path) {
    for (const auto& d : all)
      if (d[0] == path) return d;
    return std::array<std::string, 3>{};
  };
  EXPECT_EQ(find("/records/pga_g")[1], "g");
  EXPECT_EQ(find("/models/kh")[1], "N/m^1.5");
  EXPECT_EQ(find("/gaps/metres")[1], "m");
  EXPECT_EQ(find("/uncoupled/status")[1], "1");
  for (const char* code : {"0 ok", "1 diverged", "2 non-finite", "3 coarse", "255 not computed"}) {
    EXPECT_NE(find("/uncoupled/status")[2].find(code), std::string::npos) << code;
    EXPECT_NE(find("/impacts/status")[2].find(code), std::string::npos) << code;
  }
}

// The vocabulary covers every name the writer can write; a dataset without a row is refused, not written bare.
TEST(Results, AnUndescribedDatasetIsRefused) {
  for (const auto& [name, member] : results::model_doubles)
    EXPECT_TRUE(results::describe("models", name)) << "/models/" << name << " has no row in describe.cpp";
  for (const auto& spec : results::unit_fields) EXPECT_TRUE(results::describe(spec.group, spec.name)) << spec.name;
  for (const auto& spec : results::derived_fields) EXPECT_TRUE(results::describe(spec.group, spec.name)) << spec.name;
  EXPECT_FALSE(results::describe("models", "no_such_dataset"));
  EXPECT_FALSE(results::describe("records", "peak_u1"));
  TempDir t;
  results::Results a = testdata::sample_results();
  constexpr results::FieldSpec bare{"impacts", "undescribed", results::Dtype::f64, results::Extent::lane_gap, 0, "", ""};
  a.fields.push_back({bare, std::vector<double>(16, 1.0)});
  EXPECT_THROW(results::write(t.file("a.h5"), a), std::logic_error);
  EXPECT_FALSE(fs::exists(t.file("a.h5")));
  a.fields.pop_back();
  a.fields.push_back({results::derived_fields[0], std::vector<double>(15, 1.0)});  // does not fill its shape
  EXPECT_THROW(results::write(t.file("a.h5"), a), std::logic_error);
}

// tests/data/results-format1.h5 was written by the format-1 writer (`pounding run tests/data/results-format1.toml`
// at commit 1819a58): flat status and impacts fields, no /gaps, no attributes on datasets.
TEST(Results, FormatOneFileReadsIntoTheSameResults) {
  const std::string f1 = testdata::data_dir() + "/results-format1.h5";
  const results::Results a = results::load(f1);
  EXPECT_EQ(a.header.format_version, 1);
  const std::size_t R = 2, M = 8, G = 3;
  ASSERT_EQ(a.record_count(), R);
  ASSERT_EQ(a.model_count(), M);
  ASSERT_EQ(a.gap_ratios, (std::vector<double>{0.1, 0.3, 1.0}));
  EXPECT_EQ(a.column<std::uint8_t>("uncoupled", "status").size(), R * M);
  EXPECT_EQ(a.column<std::uint8_t>("impacts", "status").size(), R * M * G);
  EXPECT_EQ(a.column<double>("impacts", "h_omega_contact").size(), R * M * G);
  // /gaps rebuilt from the study's [gaps] ratios and the code gaps
  EXPECT_EQ(a.gaps.ratios, a.gap_ratios);
  ASSERT_EQ(a.gaps.metres.size(), M * G);
  for (std::size_t m = 0; m < M; ++m)
    for (std::size_t g = 0; g < G; ++g) EXPECT_EQ(a.gaps.metres[m * G + g], a.gap_ratios[g] * a.models.code_gap[m]);
  // rewritten, it is a format-2 file holding the same Results, and the report says the same
  TempDir t;
  results::write(t.file("f2.h5"), a);
  results::Results b = results::load(t.file("f2.h5"));
  EXPECT_EQ(b.header.format_version, 2);
  testdata::expect_same_results(a, b, false);
  auto f = h5::open_read(t.file("f2.h5"));
  EXPECT_EQ(h5::dataset_shape(h5::open_group(f.get(), "uncoupled").get(), "status"), (Shape{R, M}));
  EXPECT_EQ(h5::dataset_shape(h5::open_group(f.get(), "impacts").get(), "status"), (Shape{R, M, G}));
  b.path = a.path;
  EXPECT_EQ(report_markdown(a), report_markdown(b));
}

TEST(Results, ProbabilitySceneHasNoImpactsGroup) {
  TempDir t;
  results::Results a = testdata::sample_results();
  std::erase_if(a.fields, [](const results::Field& f) { return f.spec.group == "impacts"; });
  a.gap_ratios.clear();
  results::write(t.file("p.h5"), a);
  const results::Results b = results::load(t.file("p.h5"));
  EXPECT_FALSE(b.has_group("impacts"));
  EXPECT_EQ(b.gaps.ratios, (std::vector<double>{0.2, 0.5}));  // /gaps in every scene
  testdata::expect_same_results(a, b);
}

TEST(Results, AmplificationIsPeakWithOverPeakWithout) {
  const results::Results r = testdata::sample_results();
  const auto& amp = r.column<double>("impacts", "amplification_u1");
  const auto& with = r.column<double>("impacts", "peak_u1");
  const auto& without = r.column<double>("uncoupled", "peak_u1");
  ASSERT_EQ(amp.size(), 16u);
  for (std::size_t k = 0; k < 14; ++k) EXPECT_EQ(amp[k], with[k] / without[k / 2]) << k;
}

TEST(Results, SettingsLookUpsNameWhatIsMissing) {
  const results::Results r = testdata::sample_results();
  EXPECT_EQ(r.settings.number("structures", "code_gap_coefficient"), 0.008);
  EXPECT_EQ(r.settings.number("", "seed"), 42.0);  // an integer read as a number
  EXPECT_EQ(r.settings.numbers("gaps", "ratios"), (std::vector<double>{0.2, 0.5, 1.0}));
  EXPECT_EQ(r.settings.text("", "title"), "sample results");
  try {
    r.settings.number("report", "nothing");
    FAIL() << "no error for a missing setting";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/settings/report/nothing"), std::string::npos) << e.what();
  }
  EXPECT_THROW(r.settings.numbers("", "title"), std::runtime_error);
  EXPECT_THROW(r.column<double>("uncoupled", "status"), std::runtime_error);  // stored as u8
}
