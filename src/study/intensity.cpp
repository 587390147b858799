// The [intensity], [hazard] and [target_spectrum] sections that make a study a fragility study.
#include "pounding/study/intensity.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "pounding/config/config.hpp"
#include "pounding/config/fields.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/study_fields.hpp"

namespace pounding {

namespace fs = std::filesystem;
using config::TableReader;

double median_period(const StructureModel& structures, int b) {
  std::vector<double> p = structures.building(b).periods;  // a distribution: {its median}
  std::sort(p.begin(), p.end());
  const std::size_t n = p.size();
  return n % 2 ? p[n / 2] : std::sqrt(p[n / 2 - 1] * p[n / 2]);
}

namespace {

template <class E, std::size_t N>
E parse_named(const EnumName<E> (&table)[N], const std::string& name, std::string_view what) {
  if (auto v = parse_enum(table, name)) return *v;
  throw InputError(fmt::format("unknown {} '{}'", what, name), std::string(what), "use " + enum_name_list(table, " or ", "\""));
}

// periods = [..] or {min, max, count} (count log-spaced periods from min to max)
std::vector<double> read_periods(TableReader& r, const std::string& path) {
  const toml::node* n = r.get("periods");
  if (!n) return {};
  if (const toml::table* t = n->as_table()) {
    TableReader g(t, path, "intensity.periods");
    const double lo = g.number("min", 0.0);
    const double hi = g.number("max", 0.0);
    const long count = g.integer("count");
    g.finish("min, max, count");
    if (!(hi > lo)) throw InputError("periods: max must exceed min", r.where("periods"), "give {min = 0.2, max = 2.0, count = 10}");
    std::vector<double> p(static_cast<std::size_t>(count));
    for (long i = 0; i < count; ++i)
      p[static_cast<std::size_t>(i)] = lo * std::pow(hi / lo, static_cast<double>(i) / static_cast<double>(count - 1));
    return p;
  }
  return r.numbers("periods", {});
}

void read_period(IntensitySpec& x, TableReader& r, const std::string& path, const StructureModel& structures) {
  const bool needs = x.im.measure == ImMeasure::sa;
  const toml::node* p = r.get("period");
  std::vector<double> periods = read_periods(r, path);
  if (x.im.measure == ImMeasure::sa_avg) {
    if (p) throw InputError("Sa_avg averages over periods, not one period", r.where("period"), "write periods = [0.2, 0.5, 1.0, 2.0] or {min, max, count}");
    if (periods.size() < 2)
      throw InputError("Sa_avg needs at least two periods", r.where("periods"),
                       "write periods = [0.2, 0.5, 1.0, 2.0] or periods = {min = 0.2, max = 3.0, count = 10}");
    x.im.periods = periods;
    return;
  }
  if (!periods.empty()) throw InputError(fmt::format("{} takes no periods", to_string(x.im.measure)), r.where("periods"), "delete periods (it is for Sa_avg)");
  if (!needs) {
    if (p) throw InputError(fmt::format("{} takes no period", to_string(x.im.measure)), r.where("period"), "delete period (it is for Sa)");
    return;
  }
  if (!p) throw InputError("Sa needs a period", r.where("period"), "write period = <s> or period = \"pair\"");
  if (p->is_string()) {
    if (p->value<std::string>() != "pair")
      throw InputError(fmt::format("period = \"{}\" is not a period", *p->value<std::string>()), r.where("period"),
                       "write period = <s> or period = \"pair\" (the geometric mean of the buildings' median periods)");
    x.period_pair = true;
    const double t1 = median_period(structures, 0), t2 = median_period(structures, 1), t = std::sqrt(t1 * t2);
    // the same range as a period given as a number: Sa(T) is defined on the spectrum's [0.01, 20] s
    if (!(t >= 0.01 && t <= 20.0))
      throw InputError(fmt::format("period = \"pair\" gives {:.4g} s (the geometric mean of the buildings' median "
                                   "periods {:.4g} s and {:.4g} s), outside [0.01, 20] s",
                                   t, t1, t2),
                       r.where("period"), "give period = <s> in [0.01, 20], or check [structures] periods");
    x.im.periods = {t};
    return;
  }
  x.im.periods = {r.number("period", 0.0)};
}

void read_levels(IntensitySpec& x, TableReader& r) {
  const bool pgv = x.im.measure == ImMeasure::pgv;
  if (!r.get("levels"))
    throw InputError("[intensity] needs the stripes' levels", r.where("levels"),
                     pgv ? "write levels = [0.1, 0.2, 0.4, 0.6, 0.8, 1.0] (m/s)" : "write levels = [0.1, 0.2, 0.4, 0.6, 0.8, 1.0] (g)");
  x.levels_where = r.where("levels");
  x.levels = r.numbers("levels", {}, pgv ? 1e-4 : 1e-4, pgv ? 20.0 : 10.0, pgv ? "(0, 20] m/s" : "(0, 10] g");
  for (std::size_t i = 1; i < x.levels.size(); ++i)
    if (!(x.levels[i] > x.levels[i - 1]))
      throw InputError("levels must be strictly increasing", r.where("levels"), "sort them and remove duplicates");
  if (x.method == FragilityMethod::msa && x.levels.size() < 2)
    throw InputError("a fragility needs at least two stripes", r.where("levels"), "give 8 to 12 levels that bracket the median (Baker 2015)");
}

}  // namespace

IntensitySpec parse_intensity(const toml::table* t, const std::string& path, const StructureModel& structures) {
  IntensitySpec x;
  if (!t) return x;
  x.enabled = true;
  TableReader r(t, path, "intensity");
  x.im.measure = r.choice("measure", "Sa", [](const std::string& n) { return parse_named(im_measure_names, n, "measure"); });
  x.method = r.choice("method", "msa", [](const std::string& n) { return parse_named(fragility_method_names, n, "method"); });
  read_period(x, r, path, structures);
  x.im.damping = r.number("damping");
  read_levels(x, r);
  x.max_scale = r.number("max_scale");
  if (x.method != FragilityMethod::ida && r.get("tolerance"))
    throw InputError("tolerance is for method = \"ida\" (the bisection's bracket width)", r.where("tolerance"),
                     "delete tolerance, or set method = \"ida\"");
  x.tolerance = r.number("tolerance");
  r.finish("measure, period, periods, damping, levels, max_scale, method, tolerance");
  return x;
}

namespace {

// The fields of one CSV row (commas, spaces or tabs between them).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> f(1);
  for (char c : line) {
    if (c == ',' || c == ' ' || c == '\t' || c == '\r') {
      if (!f.back().empty()) f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  if (f.back().empty()) f.pop_back();
  return f;
}

// A whole field as a number (strtod: "nan" and "inf" are numbers too, refused afterwards by range).
bool parse_number(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

}  // namespace

void read_hazard_csv(const std::string& file, std::vector<double>& im, std::vector<double>& rate) {
  // a regular file of at most 16 MiB (a hazard table of 100,000 rows is ~3 MiB): a FIFO or /dev/zero is refused
  std::string text = files::read_text(file, "the hazard curve", std::size_t{16} << 20);
  if (text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);  // the UTF-8 byte-order mark of Excel's "CSV UTF-8"
  std::istringstream in(text);
  std::string line;
  int no = 0;
  bool header_seen = false;
  im.clear(), rate.clear();
  while (std::getline(in, line)) {
    ++no;
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    const std::string where = fmt::format("{}:{}", file, no);
    const std::vector<std::string> f = csv_fields(line);
    double x = 0, l = 0;
    const bool numbers = f.size() >= 2 && parse_number(f[0], x) && parse_number(f[1], l);
    if (!numbers) {
      // a header: the first row only, and only when no field of it is a number (IM, rate; "Sa (g)", "lambda")
      bool any_number = false;
      for (const auto& s : f) {
        double v = 0;
        any_number |= parse_number(s, v);
      }
      if (im.empty() && !header_seen && !any_number && !f.empty()) {
        header_seen = true;
        continue;
      }
      throw InputError("a hazard row must be two numbers: IM, annual rate of exceedance", where,
                       "fix the row (one header row of names is allowed before the first)");
    }
    if (f.size() > 2) throw InputError("a hazard row has more than two columns", where, "keep IM, annual rate");
    if (!(std::isfinite(x) && x > 0)) throw InputError(fmt::format("IM {} is not positive", x), where, "IM levels are > 0");
    if (!(std::isfinite(l) && l > 0 && l < 10))
      throw InputError(fmt::format("annual rate {} is not in (0, 10)", l), where, "rates of exceedance are per year, > 0");
    if (!im.empty() && !(x > im.back())) throw InputError("IM must increase down the table", where, "sort by IM, no duplicates");
    if (!rate.empty() && !(l < rate.back()))
      throw InputError("the annual rate of exceedance must decrease as IM increases", where, "check the curve (a hazard curve is strictly decreasing)");
    im.push_back(x), rate.push_back(l);
  }
  if (im.size() < 2) throw InputError("a hazard curve needs at least two rows", file, "give IM, rate rows");
}

// A table that lies wholly above or below the stripes' levels gives a rate that comes entirely from its extended end
// slopes (issue 24, item 4: 177 poundings a year, 100 % from beyond the table) -- most often a curve in other units
// (cm/s^2, m/s^2, or PGV in cm/s) or for another IM. A table that overlaps the stripes is integrated, and the share
// of the rate from beyond it is reported and warned about.
void check_hazard_covers_stripes(const HazardSpec& h, const IntensitySpec& in, const std::string& where) {
  if (in.levels.empty() || h.im.empty()) return;
  if (h.im.back() >= in.levels.front() && h.im.front() <= in.levels.back()) return;
  throw InputError(fmt::format("the hazard curve covers IM {:g} to {:g}, {} the stripes' levels {:g} to {:g}: its rate "
                               "would come entirely from extending the table's end slopes",
                               h.im.front(), h.im.back(), h.im.back() < in.levels.front() ? "wholly below" : "wholly above",
                               in.levels.front(), in.levels.back()),
                   where,
                   "give the hazard of the fragility's IM in its units (g for PGA, Sa, Sa_avg; m/s for PGV) over a range "
                   "that covers [intensity] levels");
}

HazardSpec parse_hazard(const toml::table* t, const std::string& path, const IntensitySpec& intensity) {
  HazardSpec h;
  if (!t) return h;
  TableReader r(t, path, "hazard");
  if (!intensity.enabled)
    throw InputError("[hazard] needs fragility curves", r.where("curve"), "add [intensity] (measure, levels) to the study");
  h.enabled = true;
  h.curve = r.string("curve", "");
  const bool power = r.get("k0") || r.get("k");
  if (!h.curve.empty() == power)
    throw InputError(power ? "[hazard] gives both a curve and a power law" : "[hazard] gives no hazard", r.where("curve"),
                     "give curve = \"hazard.csv\" (IM, annual rate) or k0 = <1/yr> and k = <slope>");
  if (power) {
    // both or neither: a power law lambda(x) = k0 x^-k needs both (found here, not after the work)
    if (!r.get("k0") || !r.get("k")) {
      const bool has_k0 = r.get("k0") != nullptr;
      throw InputError(fmt::format("[hazard] gives {} without {}: a power-law hazard lambda(x) = k0 x^-k needs both",
                                   has_k0 ? "k0" : "k", has_k0 ? "k" : "k0"),
                       r.where(has_k0 ? "k0" : "k"),
                       has_k0 ? "add k = <slope>, e.g. k = 3" : "add k0 = <annual rate at IM 1>, e.g. k0 = 1e-4");
    }
    h.k0 = r.number("k0", 0.0);
    h.k = r.number("k", 0.0);
  } else {
    if (!fs::path(h.curve).is_absolute()) h.curve = (fs::path(path).parent_path() / h.curve).lexically_normal().string();
    try {
      read_hazard_csv(h.curve, h.im, h.rate);
    } catch (const InputError& e) {
      throw InputError(e.what_part(), e.where(), e.fix() + fmt::format(" ({})", r.where("curve")));
    }
    check_hazard_covers_stripes(h, intensity, r.where("curve"));
  }
  config::read_fields(h, r, study_fields::hazard);
  r.finish("curve, k0, k, years, target, source");
  return h;
}

}  // namespace pounding

namespace pounding {

std::size_t StripePlan::dropped_count(std::size_t stripe) const {
  std::size_t n = 0;
  for (std::size_t r = 0; r < records; ++r) n += dropped[stripe * records + r];
  return n;
}

std::vector<double> ida_hunt_factors(const IntensitySpec& spec, double im) {
  std::vector<double> f;
  bool beyond = false;
  for (double level : spec.levels) {
    const double x = scale_to_level(im, level);
    if (x < spec.max_scale) f.push_back(x);
    else beyond = true;
  }
  if (beyond) f.push_back(spec.max_scale);
  return f;
}

void check_stripes_reachable(const IntensitySpec& spec, const StripePlan& p) {
  if (!p.stripes) return;
  std::size_t reached = 0;
  for (std::size_t s = 0; s < p.stripes; ++s) reached += p.dropped_count(s) < p.records;
  if (reached >= 2) return;
  double lo = INFINITY, hi = 0;
  for (double x : p.im)
    if (std::isfinite(x) && x > 0) lo = std::min(lo, x), hi = std::max(hi, x);
  const std::string units = im_units(spec.im.measure);
  const std::string range = hi > 0 ? fmt::format("the records' {} spans {:.4g} to {:.4g} {}, so max_scale = {:g} reaches "
                                                 "at most {:.4g} {}",
                                                 describe(spec.im), lo, hi, units, spec.max_scale, hi * spec.max_scale, units)
                                   : fmt::format("no record has a positive {}", describe(spec.im));
  throw InputError(fmt::format("every record is dropped from {} of the {} stripes ({} of {} levels reached): {}; a "
                               "fragility needs at least two stripes with records",
                               p.stripes - reached, p.stripes, reached, p.stripes, range),
                   spec.levels_where,
                   fmt::format("give levels in {} (PGV in m/s, not cm/s; Sa and PGA in g) within the records' reach, or "
                               "raise [intensity] max_scale",
                               units));
}

StripePlan plan_stripes(const IntensitySpec& spec, std::span<const double> im) {
  StripePlan p;
  p.records = im.size();
  p.im.assign(im.begin(), im.end());
  p.stripes = spec.stripes();
  p.scale.resize(p.stripes * p.records);
  p.dropped.resize(p.stripes * p.records);
  for (std::size_t s = 0; s < p.stripes; ++s)
    for (std::size_t r = 0; r < p.records; ++r) {
      const double f = scale_to_level(im[r], spec.levels[s]);
      p.scale[s * p.records + r] = f;
      p.dropped[s * p.records + r] = !(f <= spec.max_scale);  // also an IM of 0 (f infinite) or NaN
    }
  return p;
}

}  // namespace pounding
