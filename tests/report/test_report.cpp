// The report from an in-memory Results (tests/results/sample_results.hpp) against a stored golden file:
// every section (tables 2 and 3, coupled counts, the period matrix, the fit and recommendation, code rules,
// the impacts table, the excluded analyses), with the settings read from the Results' /settings table.
// After an intended change of the report, regenerate with POUNDING_UPDATE_GOLDEN=1 and review the diff.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "pounding/report/report.hpp"
#include "results/sample_results.hpp"
#include "test_data.hpp"

using namespace pounding;

namespace {

const std::string golden_path = testdata::data_dir() + "/report/sample_report.md";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(Report, MarkdownMatchesTheGoldenFile) {
  const std::string md = report_markdown(testdata::sample_results());
  if (std::getenv("POUNDING_UPDATE_GOLDEN")) std::ofstream(golden_path, std::ios::binary) << md;
  const std::string golden = read_file(golden_path);
  ASSERT_FALSE(golden.empty()) << "missing " << golden_path;
  EXPECT_EQ(md, golden);
}

TEST(Report, SettingsComeFromTheResultsNotTheStudyText) {
  results::Results r = testdata::sample_results();
  r.header.study_text = "this is not a study file";  // never parsed when /settings is there
  const ReportSettings s = report_settings(r);
  EXPECT_EQ(s.code_gap_coefficient, 0.008);
  EXPECT_EQ(s.gap_ratios, (std::vector<double>{0.2, 0.5, 1.0}));
  EXPECT_EQ(s.targets, (std::vector<double>{50, 10}));
  EXPECT_EQ(s.confidence, 0.9);
  EXPECT_EQ(s.bootstrap, 200);
  EXPECT_EQ(s.compare_with, "stochastic-pounding");  // files from before [report] compare_with studied the paper
  EXPECT_EQ(report_markdown(r), report_markdown(testdata::sample_results()));
}

// Issue 29: the HTML report's Markdown and CSV come from one pass that runs the separation bootstrap ONCE (before, the
// HTML path ran report_markdown and report_csv: 2 bootstraps for a grid study, 3 for a pair), and they are the very
// bytes of report_markdown() and report_csv().
TEST(Report, TextsRunOneBootstrapForMarkdownAndCsv) {
  for (const bool pair : {false, true}) {
    results::Results r = testdata::sample_results();
    if (pair) r.settings.add("structures", "heights_specified", std::int64_t{1});
    const ReportTexts t = report_texts(r, true);
    EXPECT_EQ(t.bootstraps, 1) << (pair ? "pair" : "grid");
    EXPECT_EQ(t.markdown, report_markdown(r)) << (pair ? "pair" : "grid");
    EXPECT_EQ(t.csv, report_csv(r)) << (pair ? "pair" : "grid");
    if (pair) {
      EXPECT_NE(t.markdown.find("## Separation for this pair"), std::string::npos);
    }
    EXPECT_EQ(report_texts(r, false).csv, "");
  }
}

// Issue 29: the Markdown names the machine that ran the study (the golden file: host, CPU, CPUs), and says so when a
// file written before the machine was stored does not.
TEST(Report, MarkdownNamesTheMachine) {
  results::Results r = testdata::sample_results();
  EXPECT_NE(report_markdown(r).find("- machine: host 'sample-host', Test CPU @ 1.00GHz, 4 CPUs\n"), std::string::npos);
  r.header.host.clear(), r.header.cpu_model.clear(), r.header.cpu_cores = 0;
  EXPECT_NE(report_markdown(r).find("- machine: not recorded (the file was written before results stored the machine)"),
            std::string::npos);
}

TEST(Report, CsvCountsTheSampleModels) {
  const std::string csv = report_csv(testdata::sample_results());
  // gap ratio 0.2: z > 0.2 for 0.35, 0.62, 1.25, 0.45, 0.95 of the 7 ok models
  EXPECT_NE(csv.find("total,,0.2,,,5,7,0.714286,,,,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("per_record,EQ2,1,,,0,3,0.000000,,,,\n"), std::string::npos) << csv;
}
