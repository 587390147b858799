// The report's Markdown read back as blocks and written as HTML (markdown_html.hpp).
#include "markdown_html.hpp"

#include <cctype>

#include <fmt/format.h>

#include "pounding/report/escape.hpp"

namespace pounding::report_detail {

namespace {

MdBlock block(MdBlock::Kind kind) {
  MdBlock b;
  b.kind = kind;
  return b;
}

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// "| a | b |" -> {"a", "b"}. A backslash pair stays in its cell as it is ("\\|": a backslash, then the cell ends),
// except "\|", which is a '|' of the cell (GitHub's tables: the pipe is unescaped before the inline text is read).
std::vector<std::string> table_cells(std::string_view line) {
  line = trim(line);
  if (starts_with(line, "|")) line.remove_prefix(1);
  std::vector<std::string> cells;
  std::string cell;
  bool closed = false;  // the line ended with an unescaped '|'
  for (std::size_t i = 0; i < line.size(); ++i) {
    closed = false;
    if (line[i] == '\\' && i + 1 < line.size()) {
      if (line[i + 1] != '|') cell += '\\';
      cell += line[++i];
    } else if (line[i] == '|') {
      cells.emplace_back(trim(cell)), cell.clear(), closed = true;
    } else {
      cell += line[i];
    }
  }
  if (!closed) cells.emplace_back(trim(cell));
  return cells;
}

bool is_rule_row(const std::vector<std::string>& cells) {
  for (const auto& c : cells)
    if (c.empty() || c.find_first_not_of("-: ") != std::string::npos) return false;
  return true;
}

bool numeric_cell(std::string_view s) {
  // "0.341", "59 / 100", "[0.152, 0.341]", "59.00%", "2.210e-02", "**0.341**", "5 of 25": right-aligned
  if (s.empty()) return false;
  int digits = 0, letters = 0;
  for (char c : s) {
    if (std::isdigit(static_cast<unsigned char>(c))) ++digits;
    else if (std::isalpha(static_cast<unsigned char>(c)) && c != 'e') ++letters;
  }
  return digits > 0 && letters <= 2;
}

}  // namespace

std::vector<MdBlock> parse_markdown(std::string_view md) {
  std::vector<MdBlock> out;
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at < md.size();) {
    const std::size_t nl = md.find('\n', at);
    lines.push_back(md.substr(at, nl == std::string_view::npos ? md.size() - at : nl - at));
    at = nl == std::string_view::npos ? md.size() : nl + 1;
  }
  using K = MdBlock::Kind;
  auto open = [&](K kind) -> MdBlock& {
    if (out.empty() || out.back().kind != kind || out.back().kind == K::heading) out.push_back(block(kind));
    return out.back();
  };
  bool after_blank = true;
  for (std::string_view line : lines) {
    const bool blank = trim(line).empty();
    if (blank) {
      after_blank = true;
      continue;
    }
    const bool fresh = after_blank;
    after_blank = false;
    if (starts_with(line, "# ") || starts_with(line, "## ") || starts_with(line, "### ")) {
      MdBlock h = block(K::heading);
      h.level = static_cast<int>(line.find(' '));
      h.text = std::string(trim(line.substr(static_cast<std::size_t>(h.level))));
      out.push_back(std::move(h));
    } else if (starts_with(trim(line), "|")) {
      std::vector<std::string> cells = table_cells(line);
      MdBlock& t = (fresh || out.empty() || out.back().kind != K::table) ? out.emplace_back(block(K::table)) : out.back();
      if (!is_rule_row(cells)) t.rows.push_back(std::move(cells));
    } else if (starts_with(line, "    ") && (fresh || (!out.empty() && out.back().kind == K::code))) {
      MdBlock& c = fresh ? out.emplace_back(block(K::code)) : open(K::code);
      if (!c.text.empty()) c.text += '\n';
      c.text += line.substr(4);
    } else if (starts_with(line, "- ") || starts_with(line, "  - ")) {
      const int depth = starts_with(line, "  - ") ? 1 : 0;
      MdBlock& l = (fresh && (out.empty() || out.back().kind != K::list)) ? out.emplace_back(block(K::list)) : open(K::list);
      l.items.emplace_back(depth, std::string(trim(line).substr(2)));
    } else if (starts_with(line, "> ")) {
      MdBlock& q = fresh ? out.emplace_back(block(K::quote)) : open(K::quote);
      if (!q.text.empty()) q.text += ' ';
      q.text += line.substr(2);
    } else {
      MdBlock& p = fresh ? out.emplace_back(block(K::paragraph)) : open(K::paragraph);
      if (!p.text.empty()) p.text += '\n';
      p.text += trim(line);
    }
  }
  return out;
}

std::string html_escape(std::string_view s) { return report::html_text(s); }

std::string inline_html(std::string_view md) {
  std::string o;
  bool bold = false;
  for (std::size_t i = 0; i < md.size();) {
    if (md[i] == '`') {
      const std::size_t end = md.find('`', i + 1);
      if (end != std::string_view::npos) {
        o += "<code>" + html_escape(md.substr(i + 1, end - i - 1)) + "</code>";
        i = end + 1;
        continue;
      }
    }
    if (md[i] == '\\' && i + 1 < md.size() && std::ispunct(static_cast<unsigned char>(md[i + 1]))) {
      o += html_escape(md.substr(i + 1, 1));  // an escaped character (report/escape.hpp md_text): itself
      i += 2;
      continue;
    }
    if (md.substr(i, 2) == "**" && (bold || md.find("**", i + 2) != std::string_view::npos)) {
      o += bold ? "</strong>" : "<strong>";
      bold = !bold, i += 2;
      continue;
    }
    o += html_escape(md.substr(i, 1));
    ++i;
  }
  if (bold) o += "</strong>";
  return o;
}

std::string slug(std::string_view text) {
  std::string s;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c))) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!s.empty() && s.back() != '-') s += '-';
    if (s.size() >= 60) break;
  }
  while (!s.empty() && s.back() == '-') s.pop_back();
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s.front()))) s = "sec-" + s;
  return s;
}

std::string table_html(const std::vector<std::vector<std::string>>& rows, std::string_view caption) {
  if (rows.empty()) return "";
  std::string o = "<div class=\"table-wrap\"><table>";
  if (!caption.empty()) o += "<caption>" + inline_html(caption) + "</caption>";
  o += "<thead><tr>";
  for (const auto& c : rows.front()) o += "<th scope=\"col\">" + inline_html(c) + "</th>";
  o += "</tr></thead><tbody>";
  for (std::size_t r = 1; r < rows.size(); ++r) {
    o += "<tr>";
    for (std::size_t c = 0; c < rows[r].size(); ++c)
      o += (numeric_cell(rows[r][c]) && c > 0 ? "<td class=\"num\">" : "<td>") + inline_html(rows[r][c]) + "</td>";
    o += "</tr>";
  }
  return o + "</tbody></table></div>\n";
}

std::string block_html(const MdBlock& b, std::string_view id_prefix) {
  using K = MdBlock::Kind;
  switch (b.kind) {
    case K::heading: {
      const int tag = b.level + 1;  // the page's own h1 is the title
      return fmt::format("<h{} id=\"{}{}\">{}</h{}>\n", tag, id_prefix, slug(b.text), inline_html(b.text), tag);
    }
    case K::paragraph: {
      std::string o = "<p>";
      for (char c : inline_html(b.text)) o += c == '\n' ? std::string("<br>") : std::string(1, c);
      return o + "</p>\n";
    }
    case K::quote: return "<blockquote class=\"warning\"><p>" + inline_html(b.text) + "</p></blockquote>\n";
    case K::code: return "<pre><code>" + html_escape(b.text) + "</code></pre>\n";
    case K::table: return table_html(b.rows);
    case K::list: {
      std::string o = "<ul>";
      for (std::size_t i = 0; i < b.items.size(); ++i) {
        const auto& [depth, text] = b.items[i];
        o += "<li>" + inline_html(text);
        const bool child_next = i + 1 < b.items.size() && b.items[i + 1].first > depth;
        const bool close_child = depth == 1 && (i + 1 == b.items.size() || b.items[i + 1].first == 0);
        o += child_next ? "<ul>" : "</li>";
        if (close_child) o += "</ul></li>";
      }
      return o + "</ul>\n";
    }
  }
  return "";
}

}  // namespace pounding::report_detail
