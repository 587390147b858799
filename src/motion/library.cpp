// The record directory reader, MANIFEST.tsv and the identity of a recording (see library.hpp).
#include "pounding/motion/library.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"

namespace pounding {

namespace fs = std::filesystem;

std::vector<std::string> record_files_in(const std::string& dir, const std::string& setting) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError("records directory not found", dir, "fix " + setting + " (a folder of .AT2 or .txt records)");
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    std::error_code ec2;
    if ((ext == ".at2" || ext == ".txt") && e.is_regular_file(ec2)) paths.push_back(e.path().string());
  }
  if (ec) throw InputError("cannot list the records directory: " + ec.message(), dir, "fix " + setting);
  std::sort(paths.begin(), paths.end());
  if (paths.empty())
    throw InputError("no .AT2 or .txt records in the directory", dir,
                     "point " + setting + " at a folder of PEER .AT2 or two-column time/acceleration .txt files");
  return paths;
}

namespace {

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// Lower-case words of a name: parenthesised remarks dropped, every run of non-alphanumerics a separator.
std::vector<std::string> words(const std::string& name) {
  std::vector<std::string> out;
  std::string w;
  int depth = 0;
  for (char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '(') ++depth;
    else if (ch == ')' && depth > 0) --depth;
    else if (depth == 0 && std::isalnum(c)) {
      w += static_cast<char>(std::tolower(c));
      continue;
    }
    if (!w.empty()) out.push_back(std::move(w)), w.clear();
  }
  if (!w.empty()) out.push_back(std::move(w));
  return out;
}

// One word list begins the other ("el centro" and "el centro array 9"); both non-empty.
bool prefix_match(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  if (a.empty() || b.empty()) return false;
  const auto& s = a.size() <= b.size() ? a : b;
  const auto& l = a.size() <= b.size() ? b : a;
  return std::equal(s.begin(), s.end(), l.begin());
}

// The horizontal axis of a component in degrees [0, 180), or -1 when it is not a direction.
int axis_of(const std::string& component) {
  std::string c;
  for (char ch : component)
    if (!std::isspace(static_cast<unsigned char>(ch))) c += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (c.empty()) return -1;
  if (std::all_of(c.begin(), c.end(), [](unsigned char ch) { return std::isdigit(ch); }) && c.size() <= 3)
    return std::stoi(c) % 180;
  if (c == "N" || c == "S" || c == "NS" || c == "SN" || c == "NORTH" || c == "SOUTH") return 0;
  if (c == "E" || c == "W" || c == "EW" || c == "WE" || c == "EAST" || c == "WEST") return 90;
  // bearings: N45E, S10W, N00E
  if (c.size() >= 3 && (c[0] == 'N' || c[0] == 'S') && (c.back() == 'E' || c.back() == 'W')) {
    const std::string d = c.substr(1, c.size() - 2);
    if (!d.empty() && d.size() <= 2 && std::all_of(d.begin(), d.end(), [](unsigned char ch) { return std::isdigit(ch); })) {
      const int a = std::stoi(d);
      if (a > 90) return -1;
      int az = c[0] == 'N' ? (c.back() == 'E' ? a : 360 - a) : (c.back() == 'E' ? 180 - a : 180 + a);
      return az % 180;
    }
  }
  return -1;
}

bool same_component_axis(const std::string& a, const std::string& b) {
  const int x = axis_of(a), y = axis_of(b);
  if (x >= 0 || y >= 0) return x == y;
  return words(a) == words(b) && !words(a).empty();
}

// NGA-West1 line 2: "NORTHRIDGE 01/17/94 1231, ARLETA, 360 (...)": event, date, station, component.
bool parse_west1_line(const std::string& line, RecordIdentity& id) {
  std::vector<std::string> parts;
  std::stringstream ss(line);
  for (std::string p; std::getline(ss, p, ',');) parts.push_back(trim(p));
  if (parts.size() < 3) return false;
  std::stringstream first(parts[0]);
  std::string event, tok;
  int year = 0;
  while (first >> tok) {
    int m = 0, d = 0, y = 0;
    char s1 = 0, s2 = 0;
    std::stringstream ts(tok);
    if (ts >> m >> s1 >> d >> s2 >> y && s1 == '/' && s2 == '/') {
      year = y < 100 ? (y > 30 ? 1900 + y : 2000 + y) : y;
      break;
    }
    event += (event.empty() ? "" : " ") + tok;
  }
  if (year == 0 || event.empty() || parts[1].empty()) return false;
  std::stringstream comp(parts[2]);
  std::string component;
  comp >> component;
  id.event = event, id.year = year, id.station = parts[1], id.component = component;
  return true;
}

int year_of_date(const std::string& date) {  // "5/19/1940"
  const auto p = date.rfind('/');
  if (p == std::string::npos) return 0;
  try {
    const int y = std::stoi(date.substr(p + 1));
    return y < 100 ? (y > 30 ? 1900 + y : 2000 + y) : y;
  } catch (const std::exception&) {
    return 0;
  }
}

std::string meta_of(const Record& rec, const char* key) {
  const auto it = rec.meta.find(key);
  return it == rec.meta.end() ? "" : it->second;
}

}  // namespace

std::string RecordIdentity::event_text() const {
  if (!known()) return "";
  return year > 0 ? fmt::format("{} ({})", event, year) : event;
}

RecordIdentity identity_of(const Record& rec) {
  RecordIdentity id;
  if (rec.synthetic()) return id;
  if (!meta_of(rec, "identity_from").empty()) {
    id.event = meta_of(rec, "event"), id.station = meta_of(rec, "station"), id.component = meta_of(rec, "component");
    const std::string y = meta_of(rec, "year");
    id.year = y.empty() ? 0 : std::atoi(y.c_str());
    id.from = meta_of(rec, "identity_from");
  } else if (meta_of(rec, "format") == "PEER_AT2_NGAW2" && !meta_of(rec, "station").empty()) {
    id.event = meta_of(rec, "event"), id.station = meta_of(rec, "station"), id.component = meta_of(rec, "component");
    id.year = year_of_date(meta_of(rec, "date"));
    if (id.year == 0) return RecordIdentity{};  // not "event, m/d/yyyy, station, component" (an AT2 pounding wrote)
    id.from = "AT2 header line 2";
  } else if (meta_of(rec, "format") == "PEER_AT2_NGAW1" && parse_west1_line(meta_of(rec, "header2"), id)) {
    id.from = "AT2 header line 2";
  }
  if (words(id.event).empty() || words(id.station).empty()) return RecordIdentity{};
  return id;
}

bool same_event(const RecordIdentity& a, const RecordIdentity& b) {
  if (!a.known() || !b.known()) return false;
  if (a.year != 0 && b.year != 0 && a.year != b.year) return false;
  // "Northridge" (NGA-West1) and "Northridge-01" (NGA-West2): one's words begin the other's
  return prefix_match(words(a.event), words(b.event));
}

bool same_station(const RecordIdentity& a, const RecordIdentity& b) {
  return same_event(a, b) && prefix_match(words(a.station), words(b.station));
}

bool same_recording(const RecordIdentity& a, const RecordIdentity& b) {
  return same_station(a, b) && same_component_axis(a.component, b.component);
}

void RecordManifests::annotate(Record& rec) {
  if (rec.source.empty() || rec.synthetic()) return;
  const fs::path p(rec.source);
  const std::string dir = p.parent_path().string();
  auto it = by_dir_.find(dir);
  if (it == by_dir_.end()) {
    std::map<std::string, Row> rows;
    const fs::path mpath = p.parent_path() / "MANIFEST.tsv";
    std::error_code ec;
    if (fs::is_regular_file(mpath, ec)) {
      const std::string text = files::read_text(mpath.string(), "the records manifest");
      std::stringstream ss(text);
      std::string line;
      std::map<std::string, std::size_t> col;
      int n = 0;
      while (std::getline(ss, line)) {
        ++n;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (trim(line).empty()) continue;
        std::vector<std::string> f;
        std::stringstream ls(line);
        for (std::string x; std::getline(ls, x, '\t');) f.push_back(trim(x));
        if (col.empty()) {
          for (std::size_t i = 0; i < f.size(); ++i) col[f[i]] = i;
          for (const char* need : {"file", "event", "station", "component"})
            if (!col.count(need))
              throw InputError(fmt::format("MANIFEST.tsv has no column '{}'", need), fmt::format("{}:{}", mpath.string(), n),
                               "give a tab-separated header row naming file, event, year, station, component");
          continue;
        }
        auto get = [&](const char* k) {
          const auto c = col.find(k);
          return c != col.end() && c->second < f.size() ? f[c->second] : std::string();
        };
        Row r{get("event"), get("station"), get("component"), std::atoi(get("year").c_str()), n};
        rows[get("file")] = r;
      }
    }
    it = by_dir_.emplace(dir, std::move(rows)).first;
  }
  const auto row = it->second.find(p.filename().string());
  if (row == it->second.end()) return;
  const Row& r = row->second;
  rec.meta["event"] = r.event;
  rec.meta["station"] = r.station;
  rec.meta["component"] = r.component;
  rec.meta["year"] = r.year > 0 ? std::to_string(r.year) : "";
  rec.meta["identity_from"] = fmt::format("MANIFEST.tsv:{}", r.line);
}

std::vector<Record> read_library(const std::vector<std::string>& paths, const ReadOptions& options) {
  RecordManifests manifests;
  std::vector<Record> out;
  out.reserve(paths.size());
  for (const auto& p : paths) {
    out.push_back(read_record(p, options));
    manifests.annotate(out.back());
  }
  return out;
}

}  // namespace pounding
