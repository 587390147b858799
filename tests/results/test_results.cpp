// The results module (include/pounding/results/): a Results written to a file and read back is the same,
// every dataset and attribute; the file holds exactly the items format 2 defines, with their shapes, and every
// dataset says its units and meaning; a format-1 file still reads into the same Results; typed settings look-ups.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "pounding/core/error.hpp"
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
            (std::set<std::string>{"build", "contact_law", "cpu_cores", "cpu_model", "damping_law", "date",
                                   "exclusion_warning", "excluded_analyses", "format_version", "git_commit", "host",
                                   "max_dt", "max_excluded_fraction", "program_version", "ranks", "restitution", "scene",
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
  // format 3: /system's datasets, the per-element rows and the per-floor rows of any building
  const results::SystemTable table = testdata::sample_system_table();
  results::visit_system(table, [](const char* name, const auto&) {
    EXPECT_TRUE(results::describe("system", name)) << "/system/" << name << " has no row in describe.cpp";
  });
  for (const auto& spec : results::element_fields) EXPECT_TRUE(results::describe(spec.group, spec.name)) << spec.name;
  EXPECT_EQ(std::string(results::describe("uncoupled", "peak_acc_floors12")->units), "g");
  EXPECT_NE(std::string(results::describe("uncoupled", "peak_drift3")->description).find("building 3"), std::string::npos);
  EXPECT_FALSE(results::describe("uncoupled", "peak_drift"));
  EXPECT_FALSE(results::describe("uncoupled", "peak_drift0"));
  EXPECT_FALSE(results::describe("uncoupled", "peak_drift1x"));
  EXPECT_FALSE(results::describe("uncoupled", "peak_drift99999999999999999999999"));  // no throw either
  EXPECT_FALSE(results::describe("system", "peak_u1"));
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
  EXPECT_EQ(std::tie(a.header.host, a.header.cpu_model, a.header.cpu_cores), std::tuple("", "", 0));  // not stored then
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

// Format 3 (architecture.md 2.6.3): a 3- vs 5-storey pair's per-floor and per-element fields and /system, written
// and read back, every value (NaN padding above a shorter sample's roof included) and every /system column equal.
TEST(Results, FormatThreeRoundTripKeepsEveryValue) {
  TempDir t;
  const results::Results a = testdata::sample_system_results();
  results::write(t.file("a.h5"), a);
  const results::Results b = results::load(t.file("a.h5"));
  EXPECT_EQ(b.header.format_version, 3);
  testdata::expect_same_results(a, b);
  EXPECT_EQ(b.system, a.system);
  for (const results::Field& f : a.fields) {  // the rows read back carry their extents
    const results::Field* g = b.find(f.spec.group, f.spec.name);
    ASSERT_NE(g, nullptr) << f.spec.name;
    EXPECT_EQ(g->spec.extent, f.spec.extent) << f.spec.name;
    EXPECT_EQ(g->spec.count, f.spec.count) << f.spec.name;
    EXPECT_EQ(g->spec.building, f.spec.building) << f.spec.name;
    EXPECT_EQ(std::string(g->spec.units), std::string(f.spec.units)) << f.spec.name;
  }
  const auto& u2 = b.column<double>("uncoupled", "peak_u_floors2");
  ASSERT_EQ(u2.size(), 2u * 4u * 5u);
  EXPECT_TRUE(std::isnan(u2[1 * 5 + 4]) && std::isnan(u2[(4 + 1) * 5 + 4]));  // model 1's 5th floor, both records
  EXPECT_FALSE(std::isnan(u2[1 * 5 + 3]));
  // the report reads a format-3 file as it reads the pair's: the same tables from the [R, M] fields, then the
  // per-floor amplification from the per-floor rows with and without contact
  results::Results pair = testdata::sample_results();
  pair.path = b.path;
  const std::string md = report_markdown(b), pair_md = report_markdown(pair);
  ASSERT_TRUE(md.starts_with(pair_md));
  EXPECT_TRUE(md.substr(pair_md.size()).starts_with("\n## Per-floor amplification")) << md.substr(pair_md.size());
  // and again: what was read writes the same file
  results::write(t.file("b.h5"), b);
  const results::Results c = results::load(t.file("b.h5"));
  testdata::expect_same_results(a, c);
  EXPECT_EQ(c.system, a.system);

  // the layout: /system, the datasets' shapes ([records, models, floors | elements | gaps, elements]), units, axes
  auto f = h5::open_read(t.file("a.h5"));
  const h5::hid root = f.get();
  EXPECT_EQ(h5::read_int64_attribute(root, "format_version"), 3);
  auto sys = h5::open_group(root, "system");
  EXPECT_EQ(h5::member_names(sys.get()).size(), 30u);
  EXPECT_EQ(h5::read_strings(sys.get(), "element_label"), (std::vector<std::string>{"level 1", "level 2", "level 3"}));
  auto unc = h5::open_group(root, "uncoupled");
  auto imp = h5::open_group(root, "impacts");
  EXPECT_EQ(h5::read_string_attribute(unc.get(), "shape"), "[records, models]");  // the [R, M] fields' as in format 2
  EXPECT_EQ(h5::dataset_shape(unc.get(), "peak_u_floors1"), (Shape{2, 4, 3}));
  EXPECT_EQ(h5::dataset_shape(unc.get(), "peak_drift2"), (Shape{2, 4, 5}));
  EXPECT_EQ(h5::dataset_shape(unc.get(), "peak_acc_floors2"), (Shape{2, 4, 5}));
  EXPECT_EQ(h5::dataset_shape(unc.get(), "peak_closing_elements"), (Shape{2, 4, 3}));
  EXPECT_EQ(h5::dataset_shape(imp.get(), "element_peak_force"), (Shape{2, 4, 2, 3}));
  EXPECT_EQ(h5::dataset_shape(imp.get(), "element_impact_count"), (Shape{2, 4, 2, 3}));
  EXPECT_EQ(h5::dataset_shape(imp.get(), "peak_u_floors1"), (Shape{2, 4, 2, 3}));  // with contact: [R, M, G, floors]
  EXPECT_EQ(h5::dataset_shape(imp.get(), "peak_acc_floors2"), (Shape{2, 4, 2, 5}));
  const auto attr = [](h5::hid g, const char* ds, const char* a) {
    return h5::read_string_attribute(h5::open_dataset(g, ds).get(), a);
  };
  EXPECT_EQ(attr(unc.get(), "peak_acc_floors1", "units"), "g");
  EXPECT_EQ(attr(unc.get(), "peak_u_floors2", "units"), "m");
  EXPECT_NE(attr(unc.get(), "peak_u_floors2", "description").find("building 2"), std::string::npos);
  EXPECT_EQ(attr(unc.get(), "peak_u_floors2", "axes"), "[records, models, floors of building 2 (bottom first)]");
  EXPECT_EQ(attr(imp.get(), "element_energy", "units"), "J");
  EXPECT_EQ(attr(imp.get(), "peak_drift2", "units"), "m");
  EXPECT_EQ(attr(imp.get(), "peak_drift2", "axes"), "[records, models, gaps, floors of building 2 (bottom first)]");
  EXPECT_NE(attr(imp.get(), "peak_acc_floors1", "description").find("with contact"), std::string::npos);
  EXPECT_EQ(attr(imp.get(), "element_t_first_impact", "axes"), "[records, models, gaps, elements]");
  EXPECT_EQ(attr(sys.get(), "dof_height", "units"), "m");
  std::vector<std::array<std::string, 3>> all;
  datasets(root, "", all);
  for (const auto& [path, units, description] : all) {
    EXPECT_FALSE(units.empty()) << path << " has no units";
    EXPECT_FALSE(description.empty()) << path << " has no description";
  }
}

// An SDOF-pair Results (no SystemTable) is format 2 exactly: no /system, no per-floor or per-element dataset, no
// `axes`; a format-3 Results of the same fields without the system's extras is format 2 again.
TEST(Results, PairResultsStayFormatTwo) {
  TempDir t;
  results::write(t.file("p.h5"), testdata::sample_results());
  auto f = h5::open_read(t.file("p.h5"));
  EXPECT_EQ(h5::read_int64_attribute(f.get(), "format_version"), 2);
  EXPECT_FALSE(h5::exists(f.get(), "system"));
  const results::Results p = results::load(t.file("p.h5"));
  EXPECT_TRUE(p.system.empty());
  EXPECT_EQ(p.header.format_version, 2);
  // unit_schema without extents is today's schema, row for row
  EXPECT_EQ(results::unit_schema(true).size(), std::size(results::unit_fields));
  EXPECT_TRUE(results::system_fields({}, true).empty());
}

// The writer refuses, before any file exists, fields whose extents contradict /system, per-floor or per-element
// fields without /system, and a /system that contradicts itself.
TEST(Results, FormatThreeWriterRefusesAMismatch) {
  TempDir t;
  const std::string path = t.file("x.h5");
  const auto refused = [&](const results::Results& r, const std::string& says) {
    try {
      results::write(path, r);
      ADD_FAILURE() << "written: " << says;
    } catch (const std::logic_error& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(path));
  };
  const auto field = [](results::Results& r, const char* name) -> results::Field& {
    for (results::Field& f : r.fields)
      if (f.spec.name == name) return f;
    throw std::logic_error(name);
  };
  {  // building 1 drawn with 4 floors while /system gives it 3
    results::Results r = testdata::sample_system_results();
    results::Field& f = field(r, "peak_u_floors1");
    f.spec = results::floor_field(results::floor_fields[0], 1, 4);
    f.data = std::vector<double>(2 * 4 * 4, 0.0);
    refused(r, "/uncoupled/peak_u_floors1 has 4 floors but /system gives building 1 3");
  }
  {  // a building /system does not have
    results::Results r = testdata::sample_system_results();
    r.fields.push_back({results::floor_field(results::floor_fields[1], 3, 2), std::vector<double>(2 * 4 * 2, 0.0)});
    refused(r, "is for building 3 but /system has 2 buildings");
  }
  {  // elements
    results::Results r = testdata::sample_system_results();
    results::Field& f = field(r, "element_peak_force");
    f.spec.count = 2;
    f.data = std::vector<double>(2 * 4 * 2 * 2, 0.0);
    refused(r, "/impacts/element_peak_force has 2 elements but /system has 3");
  }
  {  // per-floor fields without /system
    results::Results r = testdata::sample_system_results();
    r.system = {};
    refused(r, "has no /system");
  }
  {  // a /system that contradicts itself
    results::Results r = testdata::sample_system_results();
    r.system.building_floors = {4, 4};
    refused(r, "/system is inconsistent: building_floors[0] = 4 but 3 DOFs name building 0");
    r = testdata::sample_system_results();
    r.system.element_group = {0, 0, 1};
    refused(r, "element_group[2] = 1 is not a group");
    r = testdata::sample_system_results();
    r.system.spring_law.pop_back();
    refused(r, "per-spring columns differ in length");
  }
  results::write(path, testdata::sample_system_results());  // and the consistent one is written
  EXPECT_TRUE(fs::exists(path));
}

// The datasets' names and units read through h5py (Python's HDF5), strings included: what a user's script sees.
TEST(Results, FormatThreeReadsWithH5py) {
  const char* env = std::getenv("POUNDING_PYTHON");
  const std::string py = env && *env ? env : "/usr/bin/python3";
  if (std::system((py + " -c 'import h5py, numpy' 2>/dev/null").c_str()) != 0)
    POUNDING_SKIP_OR_FAIL("needs " + py + " with h5py and numpy (Debian: python3-h5py python3-numpy; tools/setup.sh)");
  TempDir t;
  results::write(t.file("a.h5"), testdata::sample_system_results());
  const std::string cmd = py + " " + testdata::source_dir() + "/tests/results/check_format3.py " + t.file("a.h5");
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

// What `pounding results FILE` lists: every dataset with its type, shape and attributes, format 3's included.
TEST(Results, InventoryListsEveryDatasetWithShapeAndUnits) {
  TempDir t;
  results::write(t.file("a.h5"), testdata::sample_system_results());
  const auto all = results::inventory(t.file("a.h5"));
  const auto find = [&](const std::string& path) {
    for (const auto& d : all)
      if (d.path == path) return d;
    return results::DatasetInfo{};
  };
  const auto u2 = find("/uncoupled/peak_u_floors2");
  EXPECT_EQ(u2.type, "f64");
  EXPECT_EQ(u2.shape, (Shape{2, 4, 5}));
  EXPECT_EQ(u2.units, "m");
  EXPECT_EQ(u2.axes, "[records, models, floors of building 2 (bottom first)]");
  const auto count = find("/impacts/element_impact_count");
  EXPECT_EQ(count.type, "i32");
  EXPECT_EQ(count.shape, (Shape{2, 4, 2, 3}));
  const auto label = find("/system/element_label");
  EXPECT_EQ(label.type, "string");
  EXPECT_EQ(label.shape, Shape{3});
  EXPECT_EQ(find("/system/dof_height").units, "m");
  EXPECT_EQ(find("/uncoupled/peak_u1").axes, "");
  std::vector<std::array<std::string, 3>> files;
  datasets(h5::open_read(t.file("a.h5")).get(), "", files);
  EXPECT_EQ(all.size(), files.size());
  EXPECT_THROW(results::inventory(t.file("none.h5")), InputError);
}
