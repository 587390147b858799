// Inventory files: CSV rows and GeoJSON features into Buildings, one field parser for both.
#include "pounding/inventory/inventory.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"

namespace pounding::inventory {
namespace {

using Fields = std::map<std::string, std::string>;  // column or property -> its text ("" when empty or null)

const std::set<std::string> known_fields{"id", "storeys", "height", "storey_height", "system", "design_level",
                                         "year_built", "site_class", "vs30", "period", "plan_area", "unit_weight",
                                         "importance", "block", "order", "frontage", "depth", "gap_next"};

std::string text(const Fields& f, const std::string& key) {
  const auto it = f.find(key);
  return it == f.end() ? std::string() : it->second;
}

double number(const Fields& f, const std::string& key, const std::string& where) {
  const std::string t = text(f, key);
  try {
    std::size_t used = 0;
    const double v = std::stod(t, &used);
    if (used == t.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw InputError(fmt::format("{} '{}' is not a number", key, escaped_excerpt(t)), where + " " + key,
                   "write a plain number (SI units: m, s, kPa, m/s)");
}

std::optional<double> optional_number(const Fields& f, const std::string& key, const std::string& where) {
  if (text(f, key).empty()) return std::nullopt;
  return number(f, key, where);
}

int whole(const Fields& f, const std::string& key, const std::string& where) {
  const double v = number(f, key, where);
  if (v != std::floor(v) || std::abs(v) > 1e6)
    throw InputError(fmt::format("{} {} is not a whole number", key, v), where + " " + key, "write a whole number");
  return static_cast<int>(v);
}

void require(const Fields& f, const std::string& key, const std::string& where, const std::string& fix) {
  if (text(f, key).empty()) throw InputError(fmt::format("{} is missing", key), where, fix);
}

void read_storeys(Building& b, const Fields& f) {
  require(f, "storeys", b.where, "give storeys, the number of storeys above the ground");
  b.storeys = whole(f, "storeys", b.where);
  if (b.storeys < 1 || b.storeys > 200)
    throw InputError(fmt::format("storeys {} is outside [1, 200]", b.storeys), b.where + " storeys",
                     "give the number of storeys above the ground");
  const std::optional<double> h = optional_number(f, "height", b.where);
  const std::optional<double> hs = optional_number(f, "storey_height", b.where);
  if (!h && !hs) throw InputError("neither height nor storey_height is given", b.where, "give one of them (m)");
  const double each = hs ? *hs : *h / b.storeys;
  if (h && hs && std::abs(*h - *hs * b.storeys) > 0.01 * *h)
    throw InputError(fmt::format("height {} m is not storeys x storey_height = {} m", *h, *hs * b.storeys), b.where + " height",
                     "give one of them, or make them agree");
  require_range(each, 2.0, 10.0, b.where + (hs ? " storey_height" : " height / storeys"), "[2, 10] m per storey");
  b.storey_height.assign(static_cast<std::size_t>(b.storeys), each);
}

void read_level(Building& b, const Fields& f, const EraRule& eras) {
  if (!text(f, "design_level").empty()) {
    b.level = parse_design_level(text(f, "design_level"), b.where + " design_level");
    b.level_source = "design_level";
  } else if (!text(f, "year_built").empty()) {
    const int y = whole(f, "year_built", b.where);
    if (y < 1800 || y > 2100)
      throw InputError(fmt::format("year_built {} is outside [1800, 2100]", y), b.where + " year_built", "give the year of construction");
    b.level = eras.level(y);
    b.level_source = fmt::format("year_built {}", y);
  } else {
    throw InputError("neither design_level nor year_built is given", b.where,
                     "give design_level (high, moderate, low, pre-code) or year_built");
  }
}

// ASCE 7-16 Table 20.3-1 in SI: A > 1524 m/s, B 762-1524, C 366-762, D 183-366, E < 183.
Asce7SiteClass site_of_vs30(double v) {
  return v > 1524 ? Asce7SiteClass::A : v > 762 ? Asce7SiteClass::B : v > 366 ? Asce7SiteClass::C
         : v >= 183 ? Asce7SiteClass::D : Asce7SiteClass::E;
}

void read_site(Building& b, const Fields& f) {
  if (!text(f, "site_class").empty()) {
    b.site = parse_asce7_site_class(text(f, "site_class"), b.where + " site_class");
    b.site_source = "site_class";
  } else if (!text(f, "vs30").empty()) {
    const double v = number(f, "vs30", b.where);
    require_range(v, 50, 5000, b.where + " vs30", "[50, 5000] m/s");
    b.site = site_of_vs30(v);
    b.site_source = fmt::format("vs30 {:g} m/s", v);
  } else {
    throw InputError("the site class is missing", b.where, "give site_class (A to E, D-default) or vs30 (m/s)");
  }
}

Building building_of(const Fields& f, const std::string& where, const EraRule& eras) {
  Building b;
  b.where = where;
  require(f, "id", where, "give every building a unique id");
  b.id = text(f, "id");
  b.where = fmt::format("{} (id {})", where, escaped_excerpt(b.id));
  read_storeys(b, f);
  require(f, "system", b.where, "give system, e.g. rc-smf");
  b.system = text(f, "system");
  system_row(b.system, b.where + " system");
  read_level(b, f, eras);
  read_site(b, f);
  b.period = optional_number(f, "period", b.where).value_or(0);
  b.plan_area = optional_number(f, "plan_area", b.where).value_or(0);
  b.unit_weight = optional_number(f, "unit_weight", b.where).value_or(0);
  b.importance = optional_number(f, "importance", b.where).value_or(1.0);
  if (b.period != 0) require_range(b.period, 0.02, 20, b.where + " period", "[0.02, 20] s");
  if (b.plan_area != 0) require_range(b.plan_area, 10, 1e6, b.where + " plan_area", "[10, 1e6] m^2");
  if (b.unit_weight != 0) require_range(b.unit_weight, 1, 30, b.where + " unit_weight", "[1, 30] kPa");
  require_range(b.importance, 1.0, 1.5, b.where + " importance", "[1, 1.5]");
  return b;
}

void read_street(Building& b, const Fields& f) {
  for (const char* k : {"block", "order", "frontage", "depth"})
    require(f, k, b.where, "a CSV inventory places each building by block, order, frontage and depth (m)");
  b.block = text(f, "block");
  b.order = whole(f, "order", b.where);
  b.frontage = number(f, "frontage", b.where);
  b.depth = number(f, "depth", b.where);
  require_range(b.frontage, 2, 500, b.where + " frontage", "[2, 500] m");
  require_range(b.depth, 2, 500, b.where + " depth", "[2, 500] m");
  b.gap_next = optional_number(f, "gap_next", b.where);
  if (b.gap_next) require_range(*b.gap_next, 0, 10, b.where + " gap_next", "[0, 10] m");
  if (b.plan_area == 0) b.plan_area = b.frontage * b.depth;
}

// One CSV line into fields: commas, double-quoted fields with "" for a quote (RFC 4180, one line per record).
std::vector<std::string> split_csv(const std::string& line, const std::string& where) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else out.back() += c;
  }
  if (quoted) throw InputError("a quoted field is not closed", where, "close the quote on the same line");
  for (std::string& s : out) {
    const auto a = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    s = a == std::string::npos ? "" : s.substr(a, e - a + 1);
  }
  return out;
}

void note_ignored(Inventory& inv, const Fields& f) {
  for (const auto& [k, v] : f)
    if (!known_fields.count(k) && std::find(inv.ignored.begin(), inv.ignored.end(), k) == inv.ignored.end())
      inv.ignored.push_back(k);
}

Inventory read_csv(const std::string& path, const std::string& body, const EraRule& eras) {
  Inventory inv{path, {}, false, {}, "street order (block, order, frontage, gap_next)"};
  std::vector<std::string> header;
  std::size_t line_no = 0, start = 0;
  while (start <= body.size()) {
    std::size_t end = body.find('\n', start);
    if (end == std::string::npos) end = body.size();
    std::string line = body.substr(start, end - start);
    start = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t,") == std::string::npos || line[0] == '#') continue;
    const std::string where = fmt::format("{}:{}", path, line_no);
    std::vector<std::string> cells = split_csv(line, where);
    if (header.empty()) {
      header = cells;
      if (std::find(header.begin(), header.end(), "id") == header.end())
        throw InputError("the header row has no id column", where, "start the file with a header row: id,storeys,...");
      continue;
    }
    if (cells.size() != header.size())
      throw InputError(fmt::format("{} fields where the header has {}", cells.size(), header.size()), where,
                       "give every row one field per column (quote a field that holds a comma)");
    Fields f;
    for (std::size_t i = 0; i < header.size(); ++i) f[header[i]] = cells[i];
    note_ignored(inv, f);
    Building b = building_of(f, where, eras);
    read_street(b, f);
    inv.buildings.push_back(std::move(b));
  }
  return inv;
}

}  // namespace

DesignLevel EraRule::level(int year) const {
  return year >= high_from ? DesignLevel::high : year >= moderate_from ? DesignLevel::moderate : DesignLevel::pre_code;
}

double Building::height() const {
  double h = 0;
  for (double v : storey_height) h += v;
  return h;
}

std::vector<double> Building::floor_levels() const {
  std::vector<double> z;
  double s = 0;
  for (double v : storey_height) z.push_back(s += v);
  return z;
}

std::string_view to_string(Adjacency::Kind k) {
  return k == Adjacency::Kind::wall ? "shared wall" : k == Adjacency::Kind::gap ? "gap" : "corner only";
}

DesignInput design_input(const Building& b, double ss, double s1, double tl) {
  DesignInput in;
  in.system = b.system;
  in.storeys = b.storeys;
  in.storey_height = b.storey_height;
  in.plan_area = b.plan_area;
  in.unit_weight = b.unit_weight;
  in.period = b.period;
  in.ie = b.importance;
  in.level = b.level;
  in.where = b.where;
  Asce7MapValues maps;
  maps.ss = ss, maps.s1 = s1, maps.site = b.site, maps.tl = tl;
  try {
    set_design_values(in, maps);
  } catch (const InputError& e) {
    throw InputError(e.what_part(), b.where + " " + e.where(), e.fix());
  }
  return in;
}

// GeoJSON reading is in geojson.cpp (the footprints need the projection and Boost.Geometry's checks).
Inventory read_geojson(const std::string& path, const std::string& body, const EraRule& eras);

namespace detail {
Building building_from_properties(const std::map<std::string, std::string>& f, const std::string& where, const EraRule& eras,
                                  Inventory& inv) {
  note_ignored(inv, f);
  return building_of(f, where, eras);
}
}  // namespace detail

Inventory read_inventory(const std::string& path, const EraRule& eras) {
  const std::string body = files::read_text(path, "inventory");
  const auto ends = [&](std::string_view e) { return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0; };
  Inventory inv;
  if (ends(".csv")) inv = read_csv(path, body, eras);
  else if (ends(".geojson") || ends(".json")) inv = read_geojson(path, body, eras);
  else throw InputError("the inventory's format is not known from its name", path, "name it .csv, .geojson or .json");
  if (inv.buildings.empty()) throw InputError("the inventory holds no building", path, "add one row or feature per building");
  std::map<std::string, std::string> seen;
  for (const Building& b : inv.buildings)
    if (!seen.emplace(b.id, b.where).second)
      throw InputError(fmt::format("id '{}' is used twice (also {})", escaped_excerpt(b.id), seen[b.id]), b.where + " id",
                       "give every building a unique id");
  return inv;
}

}  // namespace pounding::inventory
