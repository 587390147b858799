// `pounding modes`: periods, frequencies, participation, effective masses, Rayleigh damping ratios and mode
// shapes of a shear building (issue 25 §2; docs/architecture.md §2.2.3; docs/buildings.md "Modes of a shear
// building").
//
//   modes (--storeys N --mass M | --masses m1,m2,...)
//         (--stiffness K | --stiffnesses k1,k2,... | --period T1 [--profile uniform|shear] [--storey-height h|h1,h2,...])
//         [--zeta 0.05] [--rayleigh-modes i,j | --modal-zeta z1,z2,...] [--modes K] [--csv | --json]
//
// SI: kg per floor, N/m per storey (storey i between floor i and the one below), floors bottom first. With
// --period the profile's storey stiffnesses are scaled so that the first period is T1 (model::stiffness_for_period).
// Damping: Rayleigh C = a0 M + a1 K on modes i and j (default 1 and 2) with ratio --zeta; each mode's ratio is
// printed; --modal-zeta gives classical modal damping instead (model::modal_damping_matrix). One storey: the floor dashpot c = 2 zeta sqrt(k m), the SDOF's (Structure::from_period).
// Every option is checked before any output; a bad one is one InputError naming it (exit 2).
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/commands/records_options.hpp"
#include "pounding/config/study_keys.hpp"
#include "pounding/core/error.hpp"
#include "pounding/model/modes.hpp"

namespace pounding::cli {

namespace {

constexpr int max_storeys = 200;  // as the study key `storeys` (sampling/code_factors.hpp)

struct ModesOpts {
  std::string storeys, mass, masses, stiffness, stiffnesses, period, profile, storey_height, zeta, rayleigh_modes,
      modal_zeta, modes;
  bool csv = false, json = false;
};

// The building and its damping, validated.
struct Building {
  std::vector<double> m, k, h;  // floor masses, storey stiffnesses, storey heights (with --period only)
  std::string stiffness_text;   // how k was given, for the header
  double zeta = 0.05;
  int mode_i = 1, mode_j = 2;   // Rayleigh modes (1-based); n = 1: none
  std::vector<double> modal_zeta;  // classical modal damping instead of Rayleigh: per mode, the last repeating
  int shown = 0;                // modes printed
};

struct Range {
  double lo, hi;
  std::string text;  // the range and an example, for the fix
};
// The ranges of a study's shear building (config/study_keys.hpp: one range per quantity for the studies, simulate,
// modes and Python), with an example.
Range key_range(std::string_view key, std::string_view example) {
  const config::StudyKey& k = config::study_key("structures.buildingN", key);
  return {k.lo, k.hi, fmt::format("{}{}{} ({}; as {} in a study)", k.range, k.units.empty() ? "" : " ", k.units, example, key)};
}
const Range mass_range = key_range("floor_mass", "a 1/30-scale frame floor 6.53, a concrete floor 1e5 to 1e7");
const Range stiffness_range = key_range("storey_stiffness", "a 1/30-scale frame storey 137.5e3, a real storey 1e7 to 1e10");
const Range period_range = key_range("period", "the first period T1");
const Range height_range = key_range("storey_height", "3.2 for a typical storey, 0.1 for the 1/30-scale frames");
const Range zeta_range = key_range("zeta", "0.05 for 5 %");

bool given(const std::string& s) { return !s.empty(); }

// A comma-separated list of numbers, each inside `r`.
std::vector<double> numbers(const std::string& text, const char* option, const Range& r, const char* what) {
  const std::vector<double> v =
      parse_number_list(text, option, what, fmt::format("give numbers in {}", r.text), -HUGE_VAL);
  for (double x : v)
    if (!(x >= r.lo && x <= r.hi))
      throw InputError(fmt::format("{} {} = {} is out of range", option, what, x), option,
                       fmt::format("give a value in {}", r.text));
  return v;
}

double number(const std::string& text, const char* option, const Range& r, const char* what) {
  const std::vector<double> v = numbers(text, option, r, what);
  if (v.size() != 1)
    throw InputError(fmt::format("{} '{}' is a list", option, escaped_excerpt(text)), option,
                     fmt::format("give one {}; per-storey values go to the plural option", what));
  return v.front();
}

int integer(const std::string& text, const char* option, int lo, int hi, const char* what) {
  const double v = number(text, option, {double(lo), double(hi), fmt::format("[{}, {}]", lo, hi)}, what);
  if (v != std::floor(v))
    throw InputError(fmt::format("{} {} is not a whole number", option, v), option,
                     fmt::format("give a whole number in [{}, {}]", lo, hi));
  return static_cast<int>(v);
}

std::vector<double> floor_masses(const ModesOpts& o) {
  if (given(o.mass) == given(o.masses))
    throw InputError(given(o.mass) ? "both --mass and --masses" : "no floor masses", "--mass/--masses",
                     "give --storeys N --mass M (kg per floor) or --masses m1,m2,... (kg, bottom first)");
  const std::optional<int> n =
      given(o.storeys) ? std::optional<int>(integer(o.storeys, "--storeys", 1, max_storeys, "storey count"))
                       : std::nullopt;
  if (given(o.mass)) {
    if (!n) throw InputError("--mass without --storeys", "--storeys", "give --storeys N with --mass, or --masses m1,m2,...");
    return std::vector<double>(static_cast<std::size_t>(*n), number(o.mass, "--mass", mass_range, "floor mass"));
  }
  std::vector<double> m = numbers(o.masses, "--masses", mass_range, "floor mass");
  if (m.size() > max_storeys)
    throw InputError(fmt::format("--masses has {} floors", m.size()), "--masses",
                     fmt::format("give at most {} floors", max_storeys));
  if (n && static_cast<std::size_t>(*n) != m.size())
    throw InputError(fmt::format("--storeys {} but --masses has {} values", *n, m.size()), "--masses",
                     "give one mass per floor (bottom first), or drop --storeys");
  return m;
}

// Storey heights for --period: one value for all or one per storey.
std::vector<double> storey_heights(const ModesOpts& o, std::size_t n) {
  if (!given(o.storey_height)) return {3.2};
  std::vector<double> h = numbers(o.storey_height, "--storey-height", height_range, "storey height");
  if (h.size() != 1 && h.size() != n)
    throw InputError(fmt::format("--storey-height has {} values for {} storeys", h.size(), n), "--storey-height",
                     "give one height for all storeys or one per storey (m, bottom first)");
  return h;
}

void storey_stiffnesses(const ModesOpts& o, Building& b) {
  const std::size_t n = b.m.size();
  const int count = given(o.stiffness) + given(o.stiffnesses) + given(o.period);
  if (count != 1)
    throw InputError(count ? "more than one of --stiffness, --stiffnesses, --period" : "no storey stiffness",
                     "--stiffness/--stiffnesses/--period",
                     "give one: --stiffness K (N/m, every storey), --stiffnesses k1,k2,... (bottom first) or "
                     "--period T1 (s) [--profile uniform|shear]");
  if (!given(o.period) && (given(o.profile) || given(o.storey_height)))
    throw InputError(given(o.profile) ? "--profile without --period" : "--storey-height without --period",
                     given(o.profile) ? "--profile" : "--storey-height",
                     "drop it, or derive the stiffnesses from --period T1");
  if (given(o.stiffness)) {
    b.k.assign(n, number(o.stiffness, "--stiffness", stiffness_range, "storey stiffness"));
    b.stiffness_text = fmt::format("storey stiffness {:g} N/m (uniform)", b.k.front());
  } else if (given(o.stiffnesses)) {
    b.k = numbers(o.stiffnesses, "--stiffnesses", stiffness_range, "storey stiffness");
    if (b.k.size() != n)
      throw InputError(fmt::format("--stiffnesses has {} values for {} storeys", b.k.size(), n), "--stiffnesses",
                       "give one stiffness per storey (N/m, bottom first)");
    b.stiffness_text = "storey stiffnesses as given";
  } else {
    const double T1 = number(o.period, "--period", period_range, "period");
    const std::string name = given(o.profile) ? o.profile : "uniform";
    const auto profile = parse_enum(model::stiffness_profile_names, name);
    if (!profile)
      throw InputError(fmt::format("unknown stiffness profile '{}'", escaped_excerpt(name)), "--profile",
                       "use " + enum_name_list(model::stiffness_profile_names, " or "));
    b.h = storey_heights(o, n);
    b.k = model::stiffness_for_period(b.m, b.h, *profile, T1);
    for (double k : b.k)
      if (!(k >= stiffness_range.lo && k <= stiffness_range.hi))
        throw InputError(fmt::format("--period {:g} gives a storey stiffness {:g} N/m", T1, k), "--period",
                         fmt::format("give a period (or masses) that keeps every storey in {}", stiffness_range.text));
    b.stiffness_text = fmt::format("{} profile scaled to T1 = {:g} s", to_string(*profile), T1);
  }
}

void damping(const ModesOpts& o, Building& b) {
  const int n = static_cast<int>(b.m.size());
  if (given(o.modal_zeta)) {
    if (given(o.zeta) || given(o.rayleigh_modes))
      throw InputError(fmt::format("--modal-zeta with {}", given(o.zeta) ? "--zeta" : "--rayleigh-modes"), "--modal-zeta",
                       "give either --modal-zeta z1,z2,... (classical damping) or --zeta [--rayleigh-modes i,j] (Rayleigh)");
    b.modal_zeta = numbers(o.modal_zeta, "--modal-zeta", zeta_range, "damping ratio");
    if (b.modal_zeta.size() > b.m.size())
      throw InputError(fmt::format("--modal-zeta has {} ratios for {} modes", b.modal_zeta.size(), n), "--modal-zeta",
                       "give at most one ratio per mode, from mode 1 (the last repeats for the higher modes)");
  }
  if (given(o.zeta)) b.zeta = number(o.zeta, "--zeta", zeta_range, "damping ratio");
  if (given(o.rayleigh_modes)) {
    if (n == 1)
      throw InputError("--rayleigh-modes for one storey", "--rayleigh-modes",
                       "drop it: one storey has one mode, damped by c = 2 zeta sqrt(k m)");
    const std::vector<double> v =
        numbers(o.rayleigh_modes, "--rayleigh-modes", {1.0, double(n), fmt::format("[1, {}]", n)}, "mode number");
    if (v.size() != 2 || v[0] == v[1] || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]))
      throw InputError(fmt::format("--rayleigh-modes '{}' is not two different modes", escaped_excerpt(o.rayleigh_modes)),
                       "--rayleigh-modes", fmt::format("give two mode numbers in [1, {}], e.g. 1,3", n));
    b.mode_i = static_cast<int>(std::min(v[0], v[1]));
    b.mode_j = static_cast<int>(std::max(v[0], v[1]));
  }
  b.shown = given(o.modes) ? integer(o.modes, "--modes", 1, n, "mode count") : n;
}

Building building(const ModesOpts& o) {
  if (o.csv && o.json) throw InputError("both --csv and --json", "--csv/--json", "give one of them (or neither: a table)");
  Building b;
  b.m = floor_masses(o);
  storey_stiffnesses(o, b);
  if (const std::string defect = model::stick_defect(b.m, b.k); !defect.empty())
    throw InputError(defect, given(o.period) ? "--period" : "--masses/--stiffnesses",
                     "give floor masses and storey stiffnesses within 12 decades of each other");
  damping(o, b);
  return b;
}

// Each mode's damping ratio: Rayleigh on modes i, j; the SDOF's ζ for one storey.
std::vector<double> mode_ratios(const Building& b, const model::Modes& md, model::Rayleigh& r) {
  if (!b.modal_zeta.empty()) {
    std::vector<double> z;
    for (std::size_t j = 0; j < md.omega.size(); ++j) z.push_back(model::modal_ratio(b.modal_zeta, j));
    return z;
  }
  if (b.m.size() == 1) {
    r = {2.0 * b.zeta * md.omega[0], 0.0};  // c = a0 m = 2 ζ ω m = 2 ζ √(k m)
    return {b.zeta};
  }
  r = model::rayleigh(md.omega[b.mode_i - 1], b.zeta, md.omega[b.mode_j - 1], b.zeta);
  std::vector<double> z;
  for (double w : md.omega) z.push_back(model::rayleigh_ratio(r, w));
  return z;
}

std::string json_list(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += fmt::format("{}{}", i ? ", " : "", v[i]);
  return s + "]";
}

std::string as_json(const Building& b, const model::Modes& md, const std::vector<double>& zeta, const model::Rayleigh& r) {
  double total = 0.0;
  for (double m : b.m) total += m;
  std::string s = fmt::format("{{\"storeys\": {}, \"masses\": {}, \"stiffnesses\": {}, \"total_mass\": {},\n",
                              b.m.size(), json_list(b.m), json_list(b.k), total);
  s += !b.modal_zeta.empty() ? fmt::format(" \"damping\": {{\"kind\": \"modal\", \"zeta\": {}}},\n", json_list(b.modal_zeta))
       : b.m.size() == 1
           ? fmt::format(" \"damping\": {{\"kind\": \"sdof\", \"zeta\": {}, \"a0\": {}, \"a1\": 0}},\n", b.zeta, r.a0)
           : fmt::format(" \"damping\": {{\"kind\": \"rayleigh\", \"modes\": [{}, {}], \"zeta\": {}, \"a0\": {}, "
                         "\"a1\": {}}},\n", b.mode_i, b.mode_j, b.zeta, r.a0, r.a1);
  s += " \"modes\": [";
  double cum = 0.0;
  for (int j = 0; j < b.shown; ++j) {
    cum += md.meff_ratio[j];
    s += fmt::format("{}\n  {{\"mode\": {}, \"period\": {}, \"frequency\": {}, \"omega\": {}, "
                     "\"gamma\": {}, \"gamma_mass_normalised\": {}, \"effective_mass\": {}, "
                     "\"effective_mass_ratio\": {}, \"cumulative_ratio\": {}, \"zeta\": {},\n"
                     "   \"shape_normalisation\": \"{}\", \"shape\": {},\n   \"shape_mass_normalised\": {}}}",
                     j ? "," : "", j + 1, md.period[j], md.omega[j] / (2 * std::numbers::pi), md.omega[j],
                     md.gamma_roof[j], md.gamma[j], md.meff[j], md.meff_ratio[j], cum, zeta[j],
                     md.roof_normalised[j] ? "roof" : "largest", json_list(md.phi_roof[j]), json_list(md.phi[j]));
  }
  return s + "]}\n";
}

std::string as_csv(const Building& b, const model::Modes& md, const std::vector<double>& zeta) {
  std::string s = "mode,period_s,frequency_hz,omega_rad_s,gamma,effective_mass_kg,effective_mass_ratio,cumulative_ratio,zeta,"
                  "normalisation";
  for (std::size_t i = 1; i <= b.m.size(); ++i) s += fmt::format(",phi_{}", i);
  s += "\n";
  double cum = 0.0;
  for (int j = 0; j < b.shown; ++j) {
    cum += md.meff_ratio[j];
    s += fmt::format("{},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g}", j + 1, md.period[j],
                     md.omega[j] / (2 * std::numbers::pi), md.omega[j], md.gamma_roof[j], md.meff[j], md.meff_ratio[j],
                     cum, zeta[j]);
    s += md.roof_normalised[j] ? ",roof" : ",largest";
    for (double v : md.phi_roof[j]) s += fmt::format(",{:.12g}", v);
    s += "\n";
  }
  return s;
}

std::string as_table(const Building& b, const model::Modes& md, const std::vector<double>& zeta, const model::Rayleigh& r) {
  double total = 0.0;
  for (double m : b.m) total += m;
  std::string s = fmt::format("shear building: {} storeys, total mass {:g} kg, {}\n", b.m.size(), total, b.stiffness_text);
  if (!b.modal_zeta.empty())
    s += "damping: classical modal, C = M Phi diag(2 zeta_j omega_j / M_j) Phi' M, zeta per mode as given (the last "
         "repeating)\n";
  else if (b.m.size() == 1)
    s += fmt::format("damping: zeta {:g}, floor dashpot c = 2 zeta sqrt(k m) = {:.6g} N s/m\n", b.zeta, r.a0 * b.m[0]);
  else
    s += fmt::format("damping: Rayleigh C = a0 M + a1 K, zeta {:g} at modes {} and {}: a0 = {:.6g} 1/s, a1 = {:.6g} s\n",
                     b.zeta, b.mode_i, b.mode_j, r.a0, r.a1);
  s += fmt::format("\n{:>4} {:>11} {:>11} {:>11} {:>10} {:>11} {:>8} {:>8} {:>8}\n", "mode", "period s", "freq Hz",
                   "omega r/s", "Gamma", "M* kg", "M*/M", "cum", "zeta");
  double cum = 0.0;
  for (int j = 0; j < b.shown; ++j) {
    cum += md.meff_ratio[j];
    s += fmt::format("{:>4} {:>11.6g} {:>11.6g} {:>11.6g} {:>10.5f} {:>11.5g} {:>8.5f} {:>8.5f} {:>8.5f}\n", j + 1,
                     md.period[j], md.omega[j] / (2 * std::numbers::pi), md.omega[j], md.gamma_roof[j], md.meff[j],
                     md.meff_ratio[j], cum, zeta[j]);
  }
  s += "\nGamma: participation of the roof-normalised shape (roof = 1); M*: effective mass L^2/M_j\n";
  s += "\nmode shapes (roof = 1), floors bottom first; k: the storey below the floor\n";
  s += fmt::format("{:>5} {:>11} {:>11}", "floor", "mass kg", "k N/m");
  bool confined = false;
  for (int j = 0; j < b.shown; ++j) {
    s += fmt::format(" {:>9}", fmt::format("mode {}{}", j + 1, md.roof_normalised[j] ? "" : "*"));
    confined = confined || !md.roof_normalised[j];
  }
  s += "\n";
  for (std::size_t i = 0; i < b.m.size(); ++i) {
    s += fmt::format("{:>5} {:>11.5g} {:>11.5g}", i + 1, b.m[i], b.k[i]);
    for (int j = 0; j < b.shown; ++j) s += fmt::format(" {:>9.5f}", md.phi_roof[j][i]);
    s += "\n";
  }
  if (confined)
    s += "* the mode hardly moves the roof (roof < 1e-6 of its largest value): shape and Gamma scaled to a largest "
         "value of 1\n";
  return s;
}

}  // namespace

void add_modes(CLI::App& app) {
  auto o = std::make_shared<ModesOpts>();
  auto* c = app.add_subcommand("modes", "periods, frequencies, participation factors, effective masses, Rayleigh damping "
                                        "ratios and mode shapes of a shear building "
                                        "(docs/buildings.md, 'Modes of a shear building')");
  c->add_option("--storeys", o->storeys, "number of storeys, [1, 200] (with --mass; optional with --masses)");
  c->add_option("--mass", o->mass, "floor mass, kg, the same on every floor (with --storeys)");
  c->add_option("--masses", o->masses, "floor masses, kg, bottom first: m1,m2,...");
  c->add_option("--stiffness", o->stiffness, "storey stiffness, N/m, the same for every storey");
  c->add_option("--stiffnesses", o->stiffnesses, "storey stiffnesses, N/m, bottom first (storey i below floor i)");
  c->add_option("--period", o->period, "first period T1, s: the --profile scaled to it, instead of a stiffness");
  c->add_option("--profile", o->profile, "with --period: uniform (default) or shear (k_i in proportion to the storey "
                                         "shear of the inverted-triangle forces m_j z_j, EN 1998-1 4.3.3.2.3)");
  c->add_option("--storey-height", o->storey_height, "with --period: storey height, m, one or one per storey (default 3.2)");
  c->add_option("--zeta", o->zeta, "damping ratio, [0, 0.5] (default 0.05): Rayleigh on --rayleigh-modes");
  c->add_option("--rayleigh-modes", o->rayleigh_modes, "the two modes that get --zeta exactly (default 1,2)");
  c->add_option("--modal-zeta", o->modal_zeta, "classical modal damping instead: ratios per mode from mode 1, the "
                                               "last repeating (e.g. 0.05,0.03)");
  c->add_option("--modes", o->modes, "print the first K modes (default all)");
  c->add_flag("--csv", o->csv, "one CSV row per mode, the roof-normalised shape in columns phi_1..phi_n");
  c->add_flag("--json", o->json, "one JSON object, full precision, both normalisations of each shape");
  c->callback([o] {
    const Building b = building(*o);
    const model::Modes md = model::shear_stick_modes(b.m, b.k);
    model::Rayleigh r{};
    const std::vector<double> zeta = mode_ratios(b, md, r);
    fmt::print("{}", o->json ? as_json(b, md, zeta, r) : o->csv ? as_csv(b, md, zeta) : as_table(b, md, zeta, r));
  });
}

}  // namespace pounding::cli
