// Code design spectra: see design_spectrum.hpp for the formulas and their sources.
#include "pounding/motion/design_spectrum.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cctype>
#include <cmath>
#include <string_view>
#include <utility>

#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"

namespace pounding {

namespace {

void require_period(double period) {
  if (!std::isfinite(period) || period < 0)
    throw InputError(fmt::format("period T = {} s is negative or not finite", period), "design spectrum",
                     "give a period T >= 0 s");
}

constexpr std::array<std::string_view, 5> ground_names{"A", "B", "C", "D", "E"};
constexpr std::array<std::string_view, 4> soil_names{"I", "II", "III", "IV"};

bool high_hazard(double a) { return a >= 0.275; }  // A = 0.30 or 0.35 versus 0.20 or 0.25

}  // namespace

// ---- ASCE 7-16 ----
double asce7_t0(const Asce7Spectrum& s) { return 0.2 * s.sd1 / s.sds; }
double asce7_ts(const Asce7Spectrum& s) { return s.sd1 / s.sds; }

double sa(const Asce7Spectrum& s, double period) {
  require_period(period);
  const double t0 = asce7_t0(s), ts = asce7_ts(s);
  if (period < t0) return s.sds * (0.4 + 0.6 * period / t0);
  if (period <= ts) return s.sds;
  if (period <= s.tl) return s.sd1 / period;
  return s.sd1 * s.tl / (period * period);
}

void validate(const Asce7Spectrum& s) {
  require_range(s.sds, 1e-6, 5.0, "SDS", "(0, 5] g");
  require_range(s.sd1, 1e-6, 5.0, "SD1", "(0, 5] g");
  require_range(s.tl, 1.0, 20.0, "TL", "[1, 20] s");
  if (asce7_ts(s) >= s.tl)
    throw InputError(fmt::format("TS = SD1/SDS = {} s is not below TL = {} s", asce7_ts(s), s.tl), "SD1",
                     "give SD1 < SDS TL (the spectrum's plateau must end before TL)");
}

// ---- Eurocode 8 ----
Ec8GroundParams ec8_ground_params(Ec8Type type, Ec8Ground ground) {
  // EN 1998-1:2004 table 3.2 (type 1) and table 3.3 (type 2), recommended values.
  static constexpr std::array<Ec8GroundParams, 5> type1{{
      {1.0, 0.15, 0.4, 2.0}, {1.2, 0.15, 0.5, 2.0}, {1.15, 0.20, 0.6, 2.0}, {1.35, 0.20, 0.8, 2.0},
      {1.4, 0.15, 0.5, 2.0}}};
  static constexpr std::array<Ec8GroundParams, 5> type2{{
      {1.0, 0.05, 0.25, 1.2}, {1.35, 0.05, 0.25, 1.2}, {1.5, 0.10, 0.25, 1.2}, {1.8, 0.10, 0.30, 1.2},
      {1.6, 0.05, 0.25, 1.2}}};
  const auto i = static_cast<std::size_t>(ground);
  return type == Ec8Type::type1 ? type1.at(i) : type2.at(i);
}

double ec8_eta(double damping_percent) {
  require_range(damping_percent, 0.0, 50.0, "damping ratio xi (%)", "[0, 50] %");
  return std::max(std::sqrt(10.0 / (5.0 + damping_percent)), 0.55);
}

double sa(const Ec8Spectrum& s, double period) {
  require_period(period);
  const Ec8GroundParams g = ec8_ground_params(s.type, s.ground);
  const double ag = s.importance * s.agr, eta = ec8_eta(s.damping_percent);
  if (period <= g.tb) return ag * g.s * (1.0 + period / g.tb * (2.5 * eta - 1.0));
  if (period <= g.tc) return 2.5 * ag * g.s * eta;
  if (period <= g.td) return 2.5 * ag * g.s * eta * g.tc / period;
  return 2.5 * ag * g.s * eta * g.tc * g.td / (period * period);
}

void validate(const Ec8Spectrum& s) {
  if (static_cast<std::size_t>(s.ground) >= ground_names.size())
    throw InputError("unknown EC8 ground type", "ground type", "use A, B, C, D or E");
  require_range(s.agr, 1e-6, 2.0, "agR", "(0, 2] g");
  require_range(s.importance, 0.8, 1.4, "importance factor gammaI", "[0.8, 1.4]");
  require_range(s.damping_percent, 0.0, 50.0, "damping ratio xi (%)", "[0, 50] %");
}

// ---- Iranian Standard 2800, 4th edition ----
Iran2800SoilParams iran2800_soil_params(Iran2800Soil soil, double a) {
  // VERIFY against the standard's soil table (two secondary sources agree: design_spectrum.hpp).
  static constexpr std::array<Iran2800SoilParams, 4> high{{
      {0.10, 0.4, 1.5, 1.0}, {0.10, 0.5, 1.5, 1.0}, {0.15, 0.7, 1.75, 1.1}, {0.15, 1.0, 1.75, 1.1}}};
  static constexpr std::array<Iran2800SoilParams, 4> low{{
      {0.10, 0.4, 1.5, 1.0}, {0.10, 0.5, 1.5, 1.0}, {0.15, 0.7, 1.75, 1.1}, {0.15, 1.0, 2.25, 1.3}}};
  const auto i = static_cast<std::size_t>(soil);
  return high_hazard(a) ? high.at(i) : low.at(i);
}

double iran2800_b(const Iran2800Spectrum& s, double period) {
  require_period(period);
  const Iran2800SoilParams p = iran2800_soil_params(s.soil, s.a);
  double b1 = 0;
  if (period < p.t0) b1 = p.s0 + (p.s - p.s0 + 1.0) * period / p.t0;
  else if (period < p.ts) b1 = p.s + 1.0;
  else b1 = (p.s + 1.0) * p.ts / period;
  const double k = high_hazard(s.a) ? 0.7 : 0.4;  // VERIFY (two secondary sources agree: design_spectrum.hpp)
  double n = 1.0;
  if (period >= 4.0) n = 1.0 + k;
  else if (period >= p.ts) n = 1.0 + k * (period - p.ts) / (4.0 - p.ts);
  return b1 * n;
}

double sa(const Iran2800Spectrum& s, double period) { return s.a * iran2800_b(s, period) * s.importance; }

void validate(const Iran2800Spectrum& s) {
  bool zone = false;
  for (double v : {0.20, 0.25, 0.30, 0.35}) zone = zone || std::abs(s.a - v) < 1e-9;
  if (!zone)
    throw InputError(fmt::format("design base acceleration ratio A = {} is not a zone value", s.a), "A",
                     "give A = 0.35, 0.30, 0.25 or 0.20 (very high, high, moderate, low hazard)");
  if (static_cast<std::size_t>(s.soil) >= soil_names.size())
    throw InputError("unknown Standard 2800 soil type", "soil type", "use I, II, III or IV");
  require_range(s.importance, 0.8, 1.4, "importance factor I", "[0.8, 1.4]");
}

// ---- NZS 1170.5:2004 ----
namespace {
constexpr std::array<std::string_view, 5> nzs_site_names{"A", "B", "C", "D", "E"};
}  // namespace

double nzs1170_ch(Nzs1170Site site, double t) {
  require_period(t);
  switch (site) {
    case Nzs1170Site::A:
    case Nzs1170Site::B:
      if (t < 0.1) return 1.0 + 1.35 * t / 0.1;
      if (t <= 0.3) return 2.35;
      if (t <= 1.5) return 1.6 * std::pow(0.5 / t, 0.75);
      if (t <= 3.0) return 1.05 / t;
      return 3.15 / (t * t);
    case Nzs1170Site::C:
      if (t < 0.1) return 1.33 + 1.60 * t / 0.1;
      if (t <= 0.3) return 2.93;
      if (t <= 1.5) return 2.0 * std::pow(0.5 / t, 0.75);
      if (t <= 3.0) return 1.32 / t;
      return 3.96 / (t * t);
    case Nzs1170Site::D:
      if (t < 0.1) return 1.12 + 1.88 * t / 0.1;
      if (t <= 0.56) return 3.0;
      if (t <= 1.5) return 2.4 * std::pow(0.75 / t, 0.75);
      if (t <= 3.0) return 2.14 / t;
      return 6.42 / (t * t);
    case Nzs1170Site::E:
      if (t < 0.1) return 1.12 + 1.88 * t / 0.1;
      if (t <= 1.0) return 3.0;
      if (t <= 1.5) return 3.0 / std::pow(t, 0.75);
      if (t <= 3.0) return 3.32 / t;
      return 9.96 / (t * t);
  }
  throw InputError("unknown NZS 1170.5 site class", "site class", "use A, B, C, D or E");
}

double sa(const Nzs1170Spectrum& s, double period) { return nzs1170_ch(s.site, period) * s.z * s.r; }

std::optional<Nzs1170Site> parse_nzs1170_site(std::string_view text) {
  for (std::size_t i = 0; i < nzs_site_names.size(); ++i)
    if (text.size() == 1 && std::toupper(static_cast<unsigned char>(text[0])) == nzs_site_names[i][0])
      return static_cast<Nzs1170Site>(i);
  return std::nullopt;
}

std::string_view to_string(Nzs1170Site site) { return nzs_site_names.at(static_cast<std::size_t>(site)); }

void validate(const Nzs1170Spectrum& s) {
  if (static_cast<std::size_t>(s.site) >= nzs_site_names.size())
    throw InputError("unknown NZS 1170.5 site class", "site class", "use A, B, C, D or E");
  require_range(s.z, 0.1, 0.6, "hazard factor Z", "[0.1, 0.6] (NZS 1170.5 table 3.3)");
  require_range(s.r, 0.2, 1.8, "return period factor R", "[0.2, 1.8] (NZS 1170.5 table 3.5)");
}

// ---- Tabulated ----
namespace {

// Checks point k (period t, sa v) against the previous period; where is file:line or "<source> point k".
void check_point(std::size_t k, double prev_t, double t, double v, const std::string& where) {
  if (!std::isfinite(t) || t < 0)
    throw InputError(fmt::format("period {} s is negative or not finite", t), where, "give periods >= 0 s");
  if (k > 0 && t <= prev_t)
    throw InputError(fmt::format("period {} s does not increase (previous {} s)", t, prev_t), where,
                     "list the points in strictly increasing period, each period once");
  if (!std::isfinite(v) || v < 0)
    throw InputError(fmt::format("Sa = {} g is negative or not finite", v), where, "give Sa >= 0 g");
}

void require_two_points(std::size_t n, const std::string& where) {
  if (n < 2)
    throw InputError(fmt::format("a tabulated spectrum needs at least 2 points, got {}", n), where,
                     "give at least two (period, Sa) points");
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool parse_double(std::string_view s, double& out) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && ec == std::errc() && ptr == s.data() + s.size();
}

}  // namespace

void validate(const TabulatedSpectrum& s) {
  if (s.periods.size() != s.sa.size())
    throw InputError(fmt::format("{} periods but {} Sa values", s.periods.size(), s.sa.size()), s.source,
                     "give one Sa per period");
  require_two_points(s.periods.size(), s.source);
  for (std::size_t k = 0; k < s.periods.size(); ++k)
    check_point(k, k ? s.periods[k - 1] : 0.0, s.periods[k], s.sa[k], fmt::format("{} point {}", s.source, k + 1));
}

double sa(const TabulatedSpectrum& s, double period) {
  require_period(period);
  const auto& t = s.periods;
  if (t.size() < 2 || period < t.front() || period > t.back())
    throw InputError(fmt::format("period T = {} s is outside the table [{}, {}] s", period,
                                 t.empty() ? 0.0 : t.front(), t.empty() ? 0.0 : t.back()),
                     s.source, "extend the tabulated spectrum to cover every period used");
  std::size_t k = 1;
  while (k + 1 < t.size() && t[k] < period) ++k;  // t[k-1] <= period <= t[k]
  const double w = (period - t[k - 1]) / (t[k] - t[k - 1]);
  return s.sa[k - 1] + w * (s.sa[k] - s.sa[k - 1]);
}

TabulatedSpectrum read_tabulated_spectrum(const std::string& path) {
  const std::string text = files::read_text(path, "the spectrum file");
  TabulatedSpectrum out;
  out.source = path;
  std::string_view rest = text;
  bool first = true;
  for (int line = 1; !rest.empty(); ++line) {
    const std::size_t nl = rest.find('\n');
    const std::string_view raw = trim(rest.substr(0, nl));
    rest = nl == std::string_view::npos ? std::string_view{} : rest.substr(nl + 1);
    if (raw.empty() || raw.front() == '#') continue;
    const std::string where = fmt::format("{}:{}", path, line);
    const std::size_t comma = raw.find(',');
    double t = 0, v = 0;
    const bool t_ok = parse_double(raw.substr(0, comma), t);
    if (first && !t_ok) {  // a header line
      first = false;
      continue;
    }
    first = false;
    if (comma == std::string_view::npos || raw.find(',', comma + 1) != std::string_view::npos)
      throw InputError(fmt::format("'{}' is not two comma-separated fields", escaped_excerpt(raw)), where,
                       "write each point as: period_s,sa_g");
    if (!t_ok || !parse_double(raw.substr(comma + 1), v))
      throw InputError(fmt::format("'{}' holds a field that is not a number", escaped_excerpt(raw)), where,
                       "write each point as: period_s,sa_g");
    check_point(out.periods.size(), out.periods.empty() ? 0.0 : out.periods.back(), t, v, where);
    out.periods.push_back(t);
    out.sa.push_back(v);
  }
  require_two_points(out.periods.size(), path);
  return out;
}

// ---- DesignSpectrum ----
namespace {
template <class... F>
struct Overload : F... {
  using F::operator()...;
};
template <class... F>
Overload(F...) -> Overload<F...>;
}  // namespace

DesignSpectrum::DesignSpectrum(Params params) : params_(std::move(params)) {
  std::visit([](const auto& p) { validate(p); }, params_);
}

double DesignSpectrum::sa(double period) const {
  return std::visit([period](const auto& p) { return pounding::sa(p, period); }, params_);
}

std::string DesignSpectrum::describe() const {
  return std::visit(
      Overload{
          [](const Asce7Spectrum& p) {
            return fmt::format("ASCE 7-16 11.4.6: SDS = {:g} g, SD1 = {:g} g, TL = {:g} s", p.sds, p.sd1, p.tl);
          },
          [](const Ec8Spectrum& p) {
            return fmt::format("EN 1998-1 3.2.2.2 type {}, ground {}: agR = {:g} g, gammaI = {:g}, xi = {:g} %",
                               p.type == Ec8Type::type1 ? 1 : 2, ground_names.at(static_cast<std::size_t>(p.ground)),
                               p.agr, p.importance, p.damping_percent);
          },
          [](const Iran2800Spectrum& p) {
            return fmt::format("Standard 2800 (4th ed.): A = {:g}, soil {}, I = {:g}", p.a,
                               soil_names.at(static_cast<std::size_t>(p.soil)), p.importance);
          },
          [](const Nzs1170Spectrum& p) {
            return fmt::format("NZS 1170.5:2004 3.1.1 (numerical integration), site class {}: Z = {:g}, R = {:g}, N = 1",
                               to_string(p.site), p.z, p.r);
          },
          [](const TabulatedSpectrum& p) {
            return fmt::format("tabulated: {} points, {:g}-{:g} s, from {}", p.periods.size(), p.periods.front(),
                               p.periods.back(), p.source);
          },
      },
      params_);
}

}  // namespace pounding
