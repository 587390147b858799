// User strings escaped for Markdown, HTML and CSV (report/escape.hpp).
#include "pounding/report/escape.hpp"

#include <cctype>

namespace pounding::report {

namespace {

bool control(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

// A letter, digit or any byte of a multi-byte UTF-8 character: CommonMark's "not whitespace, not punctuation".
bool word(char c) { return std::isalnum(static_cast<unsigned char>(c)) || static_cast<unsigned char>(c) >= 0x80; }

// Characters that start inline markup or raw HTML wherever they stand. '>' opens a quote and '|' a table row only at
// the start of a line, and '~' strikes through only text: the report's own sentences that quote user strings (the
// exclusion verdict, a bridge's description, the selection's lines) hold them, and "[analysis]", so those stay as
// they are.
bool always_escaped(char c) {
  switch (c) {
    case '\\': case '`': case '*': case '<': return true;
    default: return false;
  }
}

// The length of a leading ordered-list marker's digits ("12. x", "3)"), or 0.
std::size_t list_number(std::string_view s) {
  std::size_t n = 0;
  while (n < s.size() && n < 9 && std::isdigit(static_cast<unsigned char>(s[n]))) ++n;
  const bool marker = n > 0 && n < s.size() && (s[n] == '.' || s[n] == ')') && (n + 1 == s.size() || s[n + 1] == ' ');
  return marker ? n : 0;
}

std::string markdown(std::string_view in, bool cell) {
  const std::string s = one_line(in);
  std::string o;
  o.reserve(s.size() + 8);
  const std::size_t first = s.find_first_not_of(' ');
  const std::size_t number = first == std::string::npos ? 0 : list_number(std::string_view(s).substr(first));
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const char prev = i ? s[i - 1] : ' ', next = i + 1 < s.size() ? s[i + 1] : ' ';
    bool escape = always_escaped(c) || (cell && c == '|');
    if (c == '&') escape = word(next) || next == '#';                 // an entity: "&lt;", "&#60;"
    if (c == '_') escape = !(word(prev) && word(next));               // emphasis can open or close here
    if (c == ']') escape = next == '(' || next == '[';                // a link or an image: "[x](url)"
    if (i == first) escape = escape || c == '#' || c == '+' || c == '-' || c == '=' || c == '>' || c == '|';
    if (number && i == first + number) escape = true;                 // "1. " / "1) ": an ordered list
    if (escape) o += '\\';
    o += c;
  }
  return o;
}

}  // namespace

std::string one_line(std::string_view s) {
  std::string o(s);
  for (char& c : o)
    if (control(c)) c = ' ';
  return o;
}

std::string md_text(std::string_view s) { return markdown(s, false); }

std::string md_cell(std::string_view s) { return markdown(s, true); }

std::string md_code(std::string_view s) {
  if (s.find('`') != std::string_view::npos) return md_text(s);
  return "`" + one_line(s) + "`";
}

std::string html_text(std::string_view s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string csv_field(std::string_view in) {
  const std::string s = one_line(in);
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

}  // namespace pounding::report
