// Record readers, the AT2 writer and intensity measures (see records.hpp for the formats).
#include "pounding/motion/records.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"

namespace pounding {

AccUnits parse_units(const std::string& name) {
  if (auto u = parse_enum(acc_units_names, name)) return *u;
  throw InputError("unknown units '" + name + "'", "--units", "use " + enum_name_list(acc_units_names, " or "));
}

double to_m_s2(AccUnits u) {
  switch (u) {
    case AccUnits::g: return g_accel;
    case AccUnits::m_s2: return 1.0;
    case AccUnits::cm_s2: return 0.01;
  }
  return 1.0;
}

double Record::pga() const {
  double p = 0;
  for (double a : acc) p = std::max(p, std::abs(a));
  return p;
}

namespace {

struct Line {
  std::string_view text;  // without the line end and trailing blanks
  int number;             // 1-based
};

std::vector<Line> split_lines(std::string_view text) {
  std::vector<Line> lines;
  std::size_t pos = 0;
  int number = 1;
  while (pos < text.size()) {
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view s = text.substr(pos, end - pos);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\f' || s.back() == '\v'))
      s.remove_suffix(1);
    lines.push_back({s, number++});
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ++end;
    pos = end + 1;
  }
  return lines;
}

bool is_sep(char c, bool commas) {
  return c == ' ' || c == '\t' || c == '\f' || c == '\v' || (commas && (c == ',' || c == ';'));
}

std::vector<std::string_view> tokens(std::string_view s, bool commas) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_sep(s[i], commas)) ++i;
    std::size_t j = i;
    while (j < s.size() && !is_sep(s[j], commas)) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// Parses a whole token as a finite double: optional sign, digits with an optional point (".123" is
// fine), optional exponent with E, e, D or d (Fortran). Returns false for anything else.
bool parse_number(std::string_view tok, double& value) {
  if (tok.empty() || tok.size() > 64) return false;
  char buf[72];
  std::size_t n = 0;
  std::size_t i = 0;
  if (tok[0] == '+') i = 1;
  for (; i < tok.size(); ++i) {
    char c = tok[i];
    if (c == 'D' || c == 'd') c = 'e';
    // from_chars would also accept "inf"/"nan" and hex digits; only decimal notation is a number here.
    if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '-' || c == '+')) return false;
    buf[n++] = c;
  }
  if (n == 0) return false;
  auto [ptr, ec] = std::from_chars(buf, buf + n, value, std::chars_format::general);
  if (ec != std::errc() || ptr != buf + n) return false;
  return std::isfinite(value);
}

std::string upper(std::string_view s) {
  std::string u(s);
  for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

std::string loc(const std::string& where, int line) { return fmt::format("{}:{}", where, line); }

[[noreturn]] void bad_token(const std::string& where, int line, std::string_view tok, const char* expected) {
  const std::string shown = escaped_excerpt(tok);  // binary garbage is never echoed raw
  // A token that parses but is not finite (1e999, an overflow) gets its own message.
  bool non_finite = false;
  {
    std::string t(tok);
    for (char& c : t)
      if (c == 'D' || c == 'd') c = 'e';
    char* end = nullptr;
    double v = std::strtod(t.c_str(), &end);
    non_finite = end && *end == '\0' && !t.empty() && !std::isfinite(v);
    std::string l = upper(t);
    if (l.find("NAN") != std::string::npos || l.find("INF") != std::string::npos) non_finite = true;
  }
  if (non_finite)
    throw InputError(fmt::format("non-finite value '{}'", shown), loc(where, line),
                     "every acceleration must be a finite number; fix or remove the sample");
  throw InputError(fmt::format("'{}' is not a number", shown), loc(where, line), expected);
}

// Units named by an AT2 header's units line (PEER: line 3, "ACCELERATION TIME SERIES IN UNITS OF G");
// false when it does not say. Only that line is searched, so a station named "Galway" is not "gal".
bool header_units(const std::string& line_upper, AccUnits& u) {
  const std::string h = " " + line_upper + " ";
  auto has = [&](const char* s) { return h.find(s) != std::string::npos; };
  if (has("CM/S") || has("CM/SEC") || has(" GAL ") || has(" GALS ") || has("(GAL)") || has("UNITS OF GAL")) {
    u = AccUnits::cm_s2;
    return true;
  }
  if (has("UNITS OF G ") || has("UNITS OF G.") || has("UNITS OF G,") || has("(G)") || has(" IN G ") ||
      has("UNITS: G ")) {
    u = AccUnits::g;
    return true;
  }
  if (has("M/S/S") || has("M/S2") || has("M/S^2") || has("M/SEC/SEC")) {
    u = AccUnits::m_s2;
    return true;
  }
  return false;
}

// The value after `key` on an AT2 NPTS line: skips blanks and one '=' or ':'; returns false if none.
bool value_after(std::string_view line, std::size_t key_end, double& value) {
  std::size_t i = key_end;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (i < line.size() && (line[i] == '=' || line[i] == ':')) ++i;
  else return false;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  std::size_t j = i;
  while (j < line.size() && (std::isdigit(static_cast<unsigned char>(line[j])) || line[j] == '.' ||
                             line[j] == '-' || line[j] == '+' || line[j] == 'E' || line[j] == 'e'))
    ++j;
  // "DT= .0050 SEC": stop before a letter that is not an exponent ("5E" followed by space is not one)
  while (j > i && (line[j - 1] == 'E' || line[j - 1] == 'e' || line[j - 1] == '-' || line[j - 1] == '+')) --j;
  return parse_number(line.substr(i, j - i), value);
}

// The raw token after `key` (blanks, one '=' or ':', blanks, then up to a blank or ','); empty if none.
std::string_view raw_after(std::string_view line, std::size_t key_end) {
  std::size_t i = key_end;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (i < line.size() && (line[i] == '=' || line[i] == ':')) ++i;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  std::size_t j = i;
  while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != ',') ++j;
  return line.substr(i, j - i);
}

// "not a number" for NaN, letters and garbage; "not finite" for an overflowing or infinite value.
std::string not_a_number(std::string_view what, std::string_view tok) {
  std::string t(tok.substr(0, 64));
  for (char& c : t)
    if (c == 'D' || c == 'd') c = 'e';
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  const bool parsed = !t.empty() && end && *end == '\0';
  if (parsed && std::isinf(v)) return fmt::format("{} = '{}' is not a finite number", what, escaped_excerpt(tok));
  return fmt::format("{} = '{}' is not a number", what, escaped_excerpt(tok));
}

// The time step of a record must lie in [record_dt_min, record_dt_max]; `source` says where dt came from.
void check_dt(double dt, const std::string& at, std::string_view source, std::string_view fix) {
  if (!(dt >= record_dt_min && dt <= record_dt_max))
    throw InputError(fmt::format("{} = {} s is outside [{}, {}] s", source, dt, record_dt_min, record_dt_max), at,
                     std::string(fix));
}

// A value times the units factor must stay finite (1e308 g overflows in m/s^2).
double converted(double v, double f, std::string_view shown, AccUnits units, const std::string& where, int line) {
  const double a = v * f;
  if (!std::isfinite(a))
    throw InputError(fmt::format("value '{}' {} overflows to infinity in m/s2", escaped_excerpt(shown), to_string(units)),
                     loc(where, line), "every acceleration must be a finite number in the file's units; fix or remove the sample");
  return a;
}

// Appends a sample, remembering the line of the largest |a| (the first one on ties).
void push_value(Record& rec, double& peak, double a, int line) {
  if (std::abs(a) > peak) peak = std::abs(a), rec.peak_line = line;
  rec.acc.push_back(a);
}

// NPTS and DT from the AT2 header line (PEER "NPTS=  7992, DT= .0050 SEC", or NGA-West1 "2000 .02000 NPTS, DT").
struct At2Header {
  std::size_t npts;
  double dt;
};

At2Header parse_at2_header(const Line& hl, const std::string& where) {
  const std::string up = upper(hl.text);
  const std::size_t kn = up.find("NPTS");
  double npts_v = 0, dt = 0;
  bool have_n = false, have_dt = false;
  std::string_view dt_token;  // what stands where DT's value should be (for "not a number")
  if (value_after(up, kn + 4, npts_v)) {
    have_n = true;
    std::size_t kd = up.find("DT", kn + 4);
    if (kd != std::string::npos) {
      have_dt = value_after(up, kd + 2, dt);
      if (!have_dt) dt_token = raw_after(hl.text, kd + 2);
    }
  } else {
    // Old NGA-West1 style: "  2000   .02000   NPTS, DT"
    auto toks = tokens(hl.text.substr(0, kn), true);
    if (toks.size() >= 2) {
      have_n = parse_number(toks[0], npts_v);
      have_dt = parse_number(toks[1], dt);
      if (!have_dt) dt_token = toks[1];
    } else if (toks.size() == 1) {
      have_n = parse_number(toks[0], npts_v);
    }
  }
  const std::string at = loc(where, hl.number);
  constexpr const char* header_fix = "line 4 of an AT2 file must read like 'NPTS=  7992, DT= .0050 SEC'";
  if (!have_n || npts_v < 1 || npts_v != std::floor(npts_v) || npts_v > 1e9)
    throw InputError(fmt::format("NPTS missing or not a positive whole number in '{}'", escaped_excerpt(hl.text)), at,
                     header_fix);
  if (!have_dt && !dt_token.empty()) throw InputError(not_a_number("DT", dt_token), at, header_fix);
  if (!have_dt) throw InputError(fmt::format("DT missing in '{}'", escaped_excerpt(hl.text)), at, header_fix);
  if (!(dt > 0))
    throw InputError(fmt::format("DT = {} is not positive", dt), at, "give the time step in seconds (> 0)");
  check_dt(dt, at, "DT", "DT is the time step in seconds (records are sampled at 0.001-0.05 s, e.g. DT= .0050 SEC)");
  return {static_cast<std::size_t>(npts_v), dt};
}

// The values after the header line, in m/s^2; exactly NPTS of them. Returns whether any used exponent notation.
bool read_at2_values(Record& rec, const std::vector<Line>& lines, std::size_t npts_idx, std::size_t npts,
                     AccUnits units, const std::string& where) {
  const Line& hl = lines[npts_idx];
  const double f = to_m_s2(units);
  bool exp_notation = false;
  std::size_t count = 0;  // every value in the file; only the first NPTS are kept
  int first_extra = 0;    // line of value NPTS + 1
  double peak = -1.0;  // largest |a| so far
  for (std::size_t i = npts_idx + 1; i < lines.size(); ++i) {
    for (auto tok : tokens(lines[i].text, false)) {
      double v;
      if (!parse_number(tok, v))
        bad_token(where, lines[i].number, tok, "AT2 values must be numbers like .1234E-02, 5 per line");
      if (++count > npts) {
        if (first_extra == 0) first_extra = lines[i].number;
        continue;
      }
      if (tok.find_first_of("EeDd") != std::string_view::npos) exp_notation = true;
      push_value(rec, peak, converted(v, f, tok, units, where, lines[i].number), lines[i].number);
    }
  }
  if (count > npts)
    throw InputError(fmt::format("more values than NPTS: NPTS = {} on line {} but the file holds {} values (the first "
                                 "extra one on line {})",
                                 npts, hl.number, count, first_extra),
                     loc(where, hl.number), "correct NPTS on line 4 or remove the extra values");
  if (rec.acc.size() != npts)
    throw InputError(fmt::format("NPTS = {} but {} values found (data end at line {})", npts, rec.acc.size(),
                                 lines.back().number),
                     loc(where, hl.number), "the file is truncated or NPTS on line 4 is wrong");
  return exp_notation;
}

// format, units, header lines and (NGA-West2) event, date, station, component.
void at2_meta(Record& rec, const std::vector<Line>& lines, std::size_t npts_idx, bool exp_notation, AccUnits units) {
  std::string l1 = lines.empty() ? "" : upper(lines[0].text);
  if (l1.find("PEER NGA STRONG MOTION DATABASE") != std::string::npos) rec.meta["format"] = "PEER_AT2_NGAW2";
  else if (exp_notation) rec.meta["format"] = "PEER_AT2_NGAW1";
  else rec.meta["format"] = "AT2_4LINE";
  rec.meta["units"] = std::string(to_string(units));
  for (std::size_t i = 0; i < npts_idx && i < 3; ++i) rec.meta[fmt::format("header{}", i + 1)] = std::string(lines[i].text);
  if (rec.meta["format"] == "PEER_AT2_NGAW2" && npts_idx >= 1) {
    // "Duzce Turkey, 11/12/1999, Lamont 362, E"
    std::vector<std::string> parts;
    std::stringstream ss{std::string(lines[1].text)};
    std::string part;
    while (std::getline(ss, part, ',')) {
      auto b = part.find_first_not_of(' ');
      auto e = part.find_last_not_of(' ');
      parts.push_back(b == std::string::npos ? "" : part.substr(b, e - b + 1));
    }
    if (parts.size() >= 4) {
      rec.meta["event"] = parts[0];
      rec.meta["date"] = parts[1];
      rec.meta["station"] = parts[2];
      rec.meta["component"] = parts[3];
    }
  }
}

Record parse_at2(const std::vector<Line>& lines, std::size_t npts_idx, const std::string& where,
                 const ReadOptions& options) {
  const At2Header h = parse_at2_header(lines[npts_idx], where);
  Record rec;
  rec.dt = h.dt;
  rec.acc.reserve(std::min<std::size_t>(h.npts, std::size_t{1} << 20));  // NPTS is not trusted before counting
  AccUnits units = options.units;
  AccUnits named;
  const std::size_t units_line = npts_idx >= 3 ? 2 : 0;
  for (std::size_t i = units_line; i < npts_idx; ++i)
    if (options.header_units && header_units(upper(lines[i].text), named)) {
      units = named;
      rec.meta["units_from"] = fmt::format("header line {}", lines[i].number);
      break;
    }
  const bool exp_notation = read_at2_values(rec, lines, npts_idx, h.npts, units, where);
  at2_meta(rec, lines, npts_idx, exp_notation, units);
  return rec;
}

// Rows of numbers (with their line numbers); comment lines and one header row of words are skipped.
std::vector<std::pair<int, std::vector<double>>> text_rows(const std::vector<Line>& lines, const std::string& where) {
  std::vector<std::pair<int, std::vector<double>>> rows;
  bool header_skipped = false;
  for (const Line& l : lines) {
    std::string_view s = l.text;
    std::size_t b = s.find_first_not_of(" \t");
    if (b == std::string_view::npos) continue;
    if (s[b] == '#' || s[b] == '%' || s[b] == '!') continue;
    auto toks = tokens(s, true);
    if (toks.empty()) continue;
    std::vector<double> vals;
    vals.reserve(toks.size());
    if (rows.empty() && !header_skipped) {
      bool any_number = false;
      for (auto t : toks) {
        double v;
        any_number = any_number || parse_number(t, v);
      }
      bool any_digit = s.find_first_of("0123456789") != std::string_view::npos;
      if (!any_number && !any_digit) {  // "time acc" style column names
        header_skipped = true;
        continue;
      }
    }
    for (auto t : toks) {
      double v;
      if (!parse_number(t, v))
        bad_token(where, l.number, t, "text records hold numbers only (comment lines start with #)");
      vals.push_back(v);
    }
    rows.emplace_back(l.number, std::move(vals));
  }
  return rows;
}

Record parse_text(const std::vector<Line>& lines, const std::string& where, const ReadOptions& options) {
  // Rows of numbers; the first row decides one or two columns. One header row of words is allowed.
  const auto rows = text_rows(lines, where);
  if (rows.empty())
    throw InputError("no acceleration values", where,
                     "give an AT2 file, two columns (time s, acceleration) or one column with --dt-record");
  Record rec;
  double peak = -1.0;
  const double f = to_m_s2(options.units);
  rec.meta["units"] = std::string(to_string(options.units));
  const std::size_t ncol = rows.front().second.size();
  if (ncol == 2) {
    rec.meta["format"] = "TIME_ACC_2COL";
    for (const auto& [ln, v] : rows)
      if (v.size() != 2)
        throw InputError(fmt::format("{} values on a row of a two-column file", v.size()), loc(where, ln),
                         "every row must be 'time acceleration'");
    if (rows.size() < 2)
      throw InputError("a two-column record needs at least two rows", where, "give time and acceleration rows");
    const double t0 = rows.front().second[0], t1 = rows.back().second[0];
    const double n1 = static_cast<double>(rows.size() - 1);
    const double dt = (t1 - t0) / n1;
    if (!(dt > 0) || !std::isfinite(dt))
      throw InputError(fmt::format("time column runs from {} to {}: no positive time step", t0, t1),
                       loc(where, rows.back().first), "the first column must be increasing time in seconds");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double expect = t0 + static_cast<double>(i) * dt;
      if (std::abs(rows[i].second[0] - expect) > 0.01 * dt)
        throw InputError(fmt::format("uneven time column: t = {} where the uniform step {} gives {}",
                                     rows[i].second[0], dt, expect),
                         loc(where, rows[i].first), "records must have a constant time step; resample first");
    }
    check_dt(dt, loc(where, rows.back().first), fmt::format("the time column's step ({} to {} s in {} steps)", t0, t1, rows.size() - 1),
             "the first column must be time in seconds, sampled at 0.001-0.05 s");
    rec.dt = dt;
    if (t0 != 0.0) rec.meta["t0"] = fmt::format("{}", t0);
    rec.acc.reserve(rows.size());
    for (const auto& r : rows) push_value(rec, peak, converted(r.second[1], f, fmt::format("{}", r.second[1]), options.units, where, r.first), r.first);
  } else {
    rec.meta["format"] = "ONE_COLUMN";
    if (!(options.dt > 0) || !std::isfinite(options.dt))
      throw InputError("one-column record without a time step", where,
                       "give the time step (--dt-record, or dt in the study's [records])");
    check_dt(options.dt, where, "the time step given for this one-column record",
             "give the time step in seconds (--dt-record, or dt in the study's [records]), e.g. 0.01");
    rec.dt = options.dt;
    for (const auto& r : rows)
      for (double v : r.second) push_value(rec, peak, converted(v, f, fmt::format("{}", v), options.units, where, r.first), r.first);
  }
  return rec;
}

std::string stem_of(const std::string& path) { return std::filesystem::path(path).stem().string(); }

}  // namespace

Record parse_record(std::string_view text, const std::string& where, const ReadOptions& options) {
  const auto lines = split_lines(text);
  bool blank = true;
  for (const Line& l : lines)
    if (l.text.find_first_not_of(" \t") != std::string_view::npos) blank = false;
  if (blank) throw InputError("empty record file", where, "give a PEER .AT2 or a time/acceleration text file");
  // AT2 family: a line "NPTS ..." within the first six lines (line 4 in every PEER file).
  std::size_t npts_idx = lines.size();
  for (std::size_t i = 0; i < lines.size() && i < 6; ++i)
    if (upper(lines[i].text).find("NPTS") != std::string::npos) {
      npts_idx = i;
      break;
    }
  Record rec = npts_idx < lines.size() ? parse_at2(lines, npts_idx, where, options) : parse_text(lines, where, options);
  if (rec.acc.empty()) throw InputError("no acceleration values", where, "the file holds a header but no data");
  rec.source = where;
  rec.name = stem_of(where);
  return rec;
}

Record read_record(const std::string& path, const ReadOptions& options) {
  // read_text refuses a missing file, a folder, a FIFO, a socket or a device (/dev/zero) by what it is
  return parse_record(files::read_text(path, "the record file"), path, options);
}

void write_at2(const Record& rec, const std::string& path) {
  if (!(rec.dt > 0) || rec.acc.empty())
    throw InputError("cannot write an empty record", path, "generate or read a record first");
  std::string l2 = rec.name;
  if (auto it = rec.meta.find("description"); it != rec.meta.end()) l2 += ", " + it->second;
  std::string text = "PEER NGA STRONG MOTION DATABASE RECORD (format); written by pounding\n" + l2 +
                     "\nACCELERATION TIME SERIES IN UNITS OF G\n";
  text.reserve(text.size() + 48 + 16 * rec.acc.size());
  // The bytes of the printf writer this replaced ("NPTS=%8zu, DT=%12.6f SEC", "%15.7E"; test_records.cpp
  // compares the two on every kind of value).
  auto out = std::back_inserter(text);
  fmt::format_to(out, "NPTS={:8}, DT={:>12.6f} SEC\n", rec.acc.size(), rec.dt);
  for (std::size_t i = 0; i < rec.acc.size(); ++i) {
    fmt::format_to(out, "{:>15.7E}", rec.acc[i] / g_accel);  // ">": fmt left-aligns INF/NAN by default
    if (i % 5 == 4 || i + 1 == rec.acc.size()) text += '\n';
  }
  files::write_text_atomically(path, text);
}

std::optional<InputError> analysis_problem(const Record& rec, const AnalysisContext& ctx) {
  const std::string file = rec.source.empty() ? rec.name : rec.source;
  if (rec.acc.size() < 2 || !(rec.duration() >= record_duration_min))
    return InputError(fmt::format("the record lasts {:.4g} s ({} samples at dt = {} s), less than the {} s an analysis "
                                  "needs",
                                  rec.duration(), rec.acc.size(), rec.dt, record_duration_min),
                      file, "give the complete record (is the file truncated, or NPTS/DT in its header wrong?)");
  const double pga_g = rec.pga() / g_accel;
  if (!(pga_g <= record_pga_max_g)) {
    const double scale = ctx.scale;
    const double file_g = pga_g / scale;  // PGA before the scale, in g
    std::string what = fmt::format("PGA {:.4g} g is above the {} g of any real ground motion", pga_g, record_pga_max_g);
    if (scale != 1.0) what += fmt::format(" ({:.4g} g in the file, times scale {})", file_g, scale);
    const std::string where = rec.peak_line > 0 ? loc(file, rec.peak_line) : file;
    const auto units_it = rec.meta.find("units");
    const std::string units = units_it == rec.meta.end() ? "g" : units_it->second;
    const auto from_it = rec.meta.find("units_from");
    std::string fix;
    if (scale != 1.0 && file_g <= record_pga_max_g) {
      fix = fmt::format("{} = {} is too large: the file's own PGA is {:.4g} g; give a scale that keeps the PGA below "
                        "{} g",
                        ctx.scale_setting.empty() ? std::string("the scale") : ctx.scale_setting, scale, file_g,
                        record_pga_max_g);
    } else if (from_it != rec.meta.end()) {
      fix = fmt::format("the file's {} says its values are in {}: check the file's values and header", from_it->second,
                        units);
    } else if (units != "cm/s2") {
      // the same numbers read as cm/s^2
      const double value = file_g * g_accel / to_m_s2(parse_units(units));  // the peak as written in the file
      const double as_cm = value * 0.01 / g_accel;
      fix = fmt::format("is the file in cm/s2 (its values in {} read as cm/s2 give a PGA of {:.4g} g)? {}", units, as_cm,
                        ctx.units_setting.empty() ? std::string("read it as cm/s2") : ctx.units_setting);
      if (scale != 1.0)
        fix += fmt::format("; check {} = {} too", ctx.scale_setting.empty() ? std::string("the scale") : ctx.scale_setting,
                           scale);
    } else {
      fix = "the values exceed 4,900 cm/s2: check the file (units, corrupt samples)";
    }
    return InputError(what, where, fix);
  }
  return std::nullopt;
}

void require_analysable(const Record& rec, const AnalysisContext& ctx) {
  if (auto e = analysis_problem(rec, ctx)) throw *e;
}

std::vector<double> husid(const Record& rec) {
  const auto& a = rec.acc;
  std::vector<double> c(a.size(), 0.0);
  for (std::size_t k = 1; k < a.size(); ++k)
    c[k] = c[k - 1] + (a[k - 1] * a[k - 1] + a[k - 1] * a[k] + a[k] * a[k]) * rec.dt / 3.0;
  if (c.empty() || !(c.back() > 0)) return {};
  const double total = c.back();
  for (double& x : c) x /= total;
  return c;
}

double husid_time(const std::vector<double>& h, double dt, double fraction) {
  if (h.empty()) return 0.0;
  auto it = std::lower_bound(h.begin(), h.end(), fraction);
  if (it == h.end()) return dt * static_cast<double>(h.size() - 1);
  const std::size_t k = static_cast<std::size_t>(it - h.begin());
  if (k == 0) return 0.0;
  const double f0 = h[k - 1], f1 = h[k];
  const double s = f1 > f0 ? (fraction - f0) / (f1 - f0) : 0.0;
  return dt * (static_cast<double>(k - 1) + s);
}

Measures measure(const Record& rec) {
  Measures m;
  const auto& a = rec.acc;
  const double h = rec.dt;
  double v = 0, u = 0, e = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    m.pga = std::max(m.pga, std::abs(a[k]));
    if (k == 0) continue;
    const double a0 = a[k - 1], a1 = a[k];
    u += h * v + h * h * (a0 / 3.0 + a1 / 6.0);
    v += 0.5 * h * (a0 + a1);
    e += h * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0;
    m.pgv = std::max(m.pgv, std::abs(v));
    m.pgd = std::max(m.pgd, std::abs(u));
  }
  m.arias = std::numbers::pi / (2.0 * g_accel) * e;
  const auto H = husid(rec);
  m.t05 = husid_time(H, h, 0.05);
  m.t45 = husid_time(H, h, 0.45);
  m.t95 = husid_time(H, h, 0.95);
  return m;
}

}  // namespace pounding
