// The results module (include/pounding/results/): a Results written to a file and read back is the same,
// every dataset and attribute; the file holds exactly the items format 1 defines; typed settings look-ups.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "pounding/io/hdf5.hpp"
#include "pounding/results/reader.hpp"
#include "pounding/results/writer.hpp"
#include "results/results_compare.hpp"
#include "results/sample_results.hpp"
#include "temp_dir.hpp"

namespace fs = std::filesystem;
using namespace pounding;

namespace {

struct TempDir : testdata::TempDir {
  TempDir() : testdata::TempDir("results") {}
};

std::set<std::string> as_set(const std::vector<std::string>& v) { return {v.begin(), v.end()}; }

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

TEST(Results, FileHoldsTheFormatOneLayout) {
  TempDir t;
  results::write(t.file("a.h5"), testdata::sample_results());
  auto f = h5::open_read(t.file("a.h5"));
  const h5::hid root = f.get();
  EXPECT_EQ(as_set(h5::member_names(root)),
            (std::set<std::string>{"impacts", "models", "records", "settings", "uncoupled"}));
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
}

TEST(Results, ProbabilitySceneHasNoImpactsGroup) {
  TempDir t;
  results::Results a = testdata::sample_results();
  std::erase_if(a.fields, [](const results::Field& f) { return f.spec.group == "impacts"; });
  a.gap_ratios.clear();
  results::write(t.file("p.h5"), a);
  const results::Results b = results::load(t.file("p.h5"));
  EXPECT_FALSE(b.has_group("impacts"));
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
