#pragma once
// The report's Markdown as a document model (internal to src/report): the HTML report renders the very text the
// Markdown report prints, block by block, so every number in its tables is the Markdown's number, character for
// character (issue 29). Only the subset the report writes is read: headings (#, ##), paragraphs, lists ("- " and
// "  - "), block quotes ("> "), pipe tables, indented code ("    "), and inline **bold** and `code`.
#include <string>
#include <string_view>
#include <vector>

namespace pounding::report_detail {

struct MdBlock {
  enum class Kind { heading, paragraph, list, quote, table, code };
  Kind kind = Kind::paragraph;
  int level = 0;                                // heading: 1 or 2
  std::string text;                             // heading, paragraph, quote, code (Markdown inline text)
  std::vector<std::pair<int, std::string>> items;  // list: (depth 0 or 1, inline text)
  std::vector<std::vector<std::string>> rows;   // table: the header row first, then the body rows (cells trimmed)
};

std::vector<MdBlock> parse_markdown(std::string_view md);

std::string html_escape(std::string_view s);
// Inline Markdown (**bold**, `code`) to HTML, the rest escaped.
std::string inline_html(std::string_view md);
// An id for a heading: lower case letters and digits joined by '-' ("sec-" + ... when it would start otherwise).
std::string slug(std::string_view text);
// One block as HTML; headings get id = slug(text) (prefixed by `id_prefix`).
std::string block_html(const MdBlock& b, std::string_view id_prefix = "");
// A table as HTML (numeric-looking cells right-aligned), with an optional caption.
std::string table_html(const std::vector<std::vector<std::string>>& rows, std::string_view caption = "");

}  // namespace pounding::report_detail
