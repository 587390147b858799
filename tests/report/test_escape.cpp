// User strings escaped for the format they land in (report/escape.hpp, issue 44 item 9): each function on its own,
// then a results file with a forged title and record ids through the Markdown and the HTML report: no forged block
// or table row, Table 2's columns in place, no raw tag, and the HTML showing each string as given (the escapes read
// back once: neither double-escaped nor unescaped).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include "pounding/report/escape.hpp"
#include "pounding/report/html.hpp"
#include "pounding/report/report.hpp"
#include "results/sample_results.hpp"

using namespace pounding;
using report::csv_field;
using report::html_text;
using report::md_cell;
using report::md_code;
using report::md_text;
using report::one_line;

namespace {

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// Unescaped '|' of a Markdown table row.
std::size_t pipes(const std::string& row) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (row[i] == '\\') ++i;
    else n += row[i] == '|';
  }
  return n;
}

const std::string forged_title = "plain\n\n## Separation for this pair\n\n| P(at least one impact) | separation m |\n"
                                 "|---|---|\n| 1% | **0.001** |\n<script>alert(1)</script>";

}  // namespace

TEST(Escape, OneLineTurnsEveryControlCharacterIntoASpace) {
  EXPECT_EQ(one_line("a\nb\r\nc\td\x01" "e\x7f"), "a b  c d e ");
  EXPECT_EQ(one_line("Muthukumar & DesRoches (2006)"), "Muthukumar & DesRoches (2006)");
}

TEST(Escape, MarkdownTextKeepsOrdinaryNamesAsTheyAre) {
  // the shipped studies' strings: the report of each stays the same bytes
  for (const char* s : {"Muthukumar & DesRoches (2006) four-frame bridge, six Loma Prieta components at 0.5 g",
                        "Fragility grid: the paper's 30,976 models, 10 Sa_avg stripes, example hazard", "RSN6_IMPVALL.I_I-ELC180",
                        "EQ13", "segment 1", "F1", "example curve generated from a second-order log-log form "
                        "(tools/example_hazard.py), not a published site", "C:/records/x.AT2", "1.5 s", "T1 > T2",
                        "more than [analysis] max_excluded_fraction = 0.1 %", "coherency Sobczyk (1991): |gamma|"})
    EXPECT_EQ(md_text(s), s);
  for (const char* s : {"EQ13", "RSN6_IMPVALL.I_I-ELC180", "segment 1", "Loma Prieta"}) EXPECT_EQ(md_cell(s), s);
}

TEST(Escape, MarkdownTextEscapesWhatWouldBeMarkup) {
  // a '|' ends a table cell; in a sentence it is a character, except where it would start a table row
  EXPECT_EQ(md_cell("a|b"), "a\\|b");
  EXPECT_EQ(md_text("a|b"), "a|b");
  EXPECT_EQ(md_cell("a\n| 1% | 0.001 |"), "a \\| 1% \\| 0.001 \\|");
  EXPECT_EQ(md_text("a\n| 1% | 0.001 |"), "a | 1% | 0.001 |");
  EXPECT_EQ(md_text("| 1% | 0.001 |"), "\\| 1% | 0.001 |");
  EXPECT_EQ(md_text("**0.001**"), "\\*\\*0.001\\*\\*");
  EXPECT_EQ(md_text("`x`"), "\\`x\\`");
  EXPECT_EQ(md_text("<script>"), "\\<script>");
  EXPECT_EQ(md_cell("a\\|b"), "a\\\\\\|b");  // a backslash, then an escaped pipe
  EXPECT_EQ(md_text("a\\|b"), "a\\\\|b");
  EXPECT_EQ(md_text("&lt; & &#60;"), "\\&lt; & \\&#60;");
  EXPECT_EQ(md_text("_x_ a_b"), "\\_x\\_ a_b");
  EXPECT_EQ(md_text("[click](http://x) [a]"), "[click\\](http://x) [a]");
  // a first character that would open a block (the string can follow "- " of a list item)
  EXPECT_EQ(md_text("# h"), "\\# h");
  EXPECT_EQ(md_text("  > q"), "  \\> q");
  EXPECT_EQ(md_text("- item"), "\\- item");
  EXPECT_EQ(md_text("+ item"), "\\+ item");
  EXPECT_EQ(md_text("==="), "\\===");
  EXPECT_EQ(md_text("12. item"), "12\\. item");
  EXPECT_EQ(md_text("3) item"), "3\\) item");
  EXPECT_EQ(md_text("12.5 s"), "12.5 s");
}

TEST(Escape, CodeSpanFallsBackToTextWhenItHoldsABacktick) {
  EXPECT_EQ(md_code("/tmp/r.h5"), "`/tmp/r.h5`");
  EXPECT_EQ(md_code("/tmp/a\nb.h5"), "`/tmp/a b.h5`");
  EXPECT_EQ(md_code("a`b"), "a\\`b");
}

TEST(Escape, HtmlEscapesTheFiveCharacters) {
  EXPECT_EQ(html_text("<script>alert('x' & \"y\")</script>"),
            "&lt;script&gt;alert(&#39;x&#39; &amp; &quot;y&quot;)&lt;/script&gt;");
}

TEST(Escape, CsvQuotesOnlyWhereNeeded) {
  EXPECT_EQ(csv_field("EQ1"), "EQ1");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\"\nthen"), "\"say \"\"hi\"\" then\"");
}

TEST(Escape, ForgedTitleAndRecordIdsNeitherForgeNorShiftTheReport) {
  results::Results r = testdata::sample_results();
  r.header.title = forged_title;
  r.records.id = {"EQ|1 <script>", "**EQ2**\n| x |"};
  r.records.name = {"a`b & 'c'", "<b>n</b>"};
  const std::string md = report_markdown(r);
  const std::vector<std::string> lines = lines_of(md);
  // the title is one heading line; no line of the report is the forged row or heading
  EXPECT_EQ(lines.front().rfind("# Pounding study: plain  ## Separation for this pair", 0), 0u) << lines.front();
  for (const std::string& line : lines) {
    EXPECT_NE(line, "| 1% | **0.001** |");
    EXPECT_NE(line, "## Separation for this pair");
    for (std::size_t at = line.find('<'); at != std::string::npos; at = line.find('<', at + 1))
      EXPECT_TRUE((at > 0 && line[at - 1] == '\\') || at + 1 == line.size() || !std::isalpha(static_cast<unsigned char>(line[at + 1])))
          << "a raw HTML tag in the Markdown: " << line;
  }
  // Table 2: every row as many cells as its header
  const auto head = std::find_if(lines.begin(), lines.end(), [](const std::string& l) { return l.rfind("| record |", 0) == 0; });
  ASSERT_NE(head, lines.end());
  std::size_t rows = 0;
  for (auto it = head; it != lines.end() && it->rfind("|", 0) == 0; ++it, ++rows) EXPECT_EQ(pipes(*it), pipes(*head)) << *it;
  EXPECT_EQ(rows, 4u);  // header, rule, two records

  FigureOptions no_figures;
  no_figures.enabled = false;
  const std::string html = report_html(r, no_figures);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<b>n</b>"), std::string::npos);
  EXPECT_NE(html.find("<h1>" + html_text(forged_title) + "</h1>"), std::string::npos);
  // each id and name shown once as given: the Markdown's escapes read back, then HTML-escaped once
  for (const std::string& s : {std::string("EQ|1 &lt;script&gt;"), std::string("**EQ2** | x |"),
                               std::string("a`b &amp; &#39;c&#39;"), std::string("&lt;b&gt;n&lt;/b&gt;")})
    EXPECT_NE(html.find("<td>" + s + "</td>"), std::string::npos) << s;
  EXPECT_EQ(html.find("\\|"), std::string::npos);
  EXPECT_EQ(html.find("&amp;lt;"), std::string::npos);
  EXPECT_EQ(html.find("<strong>EQ2"), std::string::npos);
}

TEST(Escape, ReportCsvQuotesRecordIds) {
  results::Results r = testdata::sample_results();
  r.records.id = {"EQ,1", "EQ2"};
  const std::string csv = report_csv(r);
  EXPECT_NE(csv.find("per_record,\"EQ,1\",0.2,"), std::string::npos);
  EXPECT_EQ(csv.find("per_record,EQ,1,"), std::string::npos);
}
