#pragma once
// User strings escaped for the format they land in (issue 44 item 9): a study's title, record ids, names and files,
// building, frame and joint labels, intensity-measure names, hazard sources, file paths -- anything read from a
// study, record or results file. Without it a title holding a newline and a table row forged the answer of the
// Markdown and HTML reports, and a '|' in a record id shifted Table 2's columns. The report's own words and numbers
// are never passed through these (so a shipped study's report is the same bytes).
#include <string>
#include <string_view>

namespace pounding::report {

// Every control character (U+0000-U+001F, U+007F: newlines, tabs) as one space: the text stays on its line.
std::string one_line(std::string_view s);

// Markdown inline text on one line (a heading, a paragraph, a list item): one_line, then a backslash before every
// character that could start markup or raw HTML (\ ` * <; & before a letter, digit or '#'; _ not between two word
// characters, so "Sa_avg" stays as it is; ] before ( or [, a link) and before a first character that would open a
// block (# + - = > |, the '.' or ')' of "1. "). CommonMark and GitHub render it as the characters given;
// src/report/markdown_html.cpp reads the escapes back. The report's own sentences that quote user strings (the
// exclusion verdict, a bridge's description) come through as they are: they use none of these.
std::string md_text(std::string_view s);

// One cell of a Markdown table: md_text, and every '|' escaped (a '|' of a record id split the row).
std::string md_cell(std::string_view s);

// A Markdown code span `s`; where s holds a backtick, md_text(s) instead (plain text, never a broken span).
// Not for table cells (a '|' inside it is not escaped).
std::string md_code(std::string_view s);

// HTML text or a double- or single-quoted attribute value: & < > " ' as entities.
std::string html_text(std::string_view s);

// One CSV field (RFC 4180): control characters as spaces, and quoted (quotes doubled) when it holds a comma or a
// quote; otherwise the same bytes.
std::string csv_field(std::string_view s);

}  // namespace pounding::report
