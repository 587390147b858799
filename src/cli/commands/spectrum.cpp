// `pounding spectrum`: a code design spectrum at given periods, as a table or CSV (issue 23 item 6).
//
//   spectrum --code CODE [the code's parameters] (--periods T1,T2,... | --range LO,HI [--count N] [--log]) [--csv]
//
// CODE and its parameters are those of a study's [target_spectrum] (study/target_spectrum.hpp), with the same
// ranges (design_spectrum.hpp, asce7_site.hpp) and as options of the same names:
//   "ASCE 7-16"      --sds, --sd1 (g) or --ss, --s1 (g) and --site-class; --tl 8 (s); --mcer (1.5 x)
//   "EC8"            --type 1|2, --ground A-E, --agr (g), --importance 1; the spectrum at --damping (0.05)
//   "Standard 2800"  --a, --soil I-IV, --importance 1
//   "csv"            --file (period,sa lines in s, g); only periods inside the table
// An option that belongs to another code is refused. Periods: a list, or COUNT (default 21) points from LO to
// HI, evenly spaced (--log: log-spaced, LO > 0). Output: Sa in g and the elastic spectral displacement
// Sd = Sa g (T / 2 pi)^2 in m; the table starts with the spectrum's description, the CSV with it as a
// "# " line, then "period_s,sa_g,sd_m".
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/commands/records_options.hpp"
#include "pounding/core/error.hpp"
#include "pounding/motion/asce7_site.hpp"
#include "pounding/motion/design_spectrum.hpp"
#include "pounding/motion/target_spectrum.hpp"

namespace pounding::cli {

namespace {

constexpr double g0 = 9.80665;  // m/s^2

struct SpectrumOpts {
  std::string code, site_class, ground, soil, file, periods, range;
  double sds = 0, sd1 = 0, ss = 0, s1 = 0, tl = 8, agr = 0, importance = 1, damping = 0.05, a = 0;
  int type = 1, count = 21;
  bool mcer = false, log = false, csv = false;
  std::map<std::string, CLI::Option*> opt;  // the code-specific options, by name
  bool given(const std::string& name) const { return opt.at(name)->count() > 0; }
};

// Which code each code-specific option belongs to.
const std::map<std::string, std::vector<TargetCode>>& option_codes() {
  using C = TargetCode;
  static const std::map<std::string, std::vector<TargetCode>> m{
      {"--sds", {C::asce7_16}},   {"--sd1", {C::asce7_16}},     {"--ss", {C::asce7_16}},
      {"--s1", {C::asce7_16}},    {"--site-class", {C::asce7_16}}, {"--tl", {C::asce7_16}},
      {"--mcer", {C::asce7_16}},  {"--type", {C::ec8}},         {"--ground", {C::ec8}},
      {"--agr", {C::ec8}},        {"--damping", {C::ec8}},      {"--importance", {C::ec8, C::iran2800}},
      {"--a", {C::iran2800}},     {"--soil", {C::iran2800}},    {"--file", {C::csv}}};
  return m;
}

// The InputError of a parameter's validate() named by its option.
std::string option_of(const std::string& param) {
  static const std::map<std::string, std::string> m{
      {"SDS", "--sds"}, {"SD1", "--sd1"}, {"TL", "--tl"}, {"Ss", "--ss"}, {"S1", "--s1"},
      {"site class", "--site-class"}, {"agR", "--agr"}, {"importance factor gammaI", "--importance"},
      {"importance factor I", "--importance"}, {"damping ratio xi (%)", "--damping"}, {"A", "--a"},
      {"ground type", "--ground"}, {"soil type", "--soil"}};
  const auto it = m.find(param);
  return it == m.end() ? param : it->second;  // a csv file's own file:line stays
}

void require(const SpectrumOpts& o, const char* name, const std::string& code, const char* example) {
  if (!o.given(name))
    throw InputError(fmt::format("--code \"{}\" needs {}", code, name), name, fmt::format("give {}", example));
}

TargetSpectrumSpec spectrum_spec(const SpectrumOpts& o) {
  TargetSpectrumSpec spec;
  if (o.code.empty())
    throw InputError("no --code", "--code", "give --code " + enum_name_list(target_code_names, " | ", "\""));
  const auto code = parse_enum(target_code_names, o.code);
  if (!code)
    throw InputError(fmt::format("unknown design code '{}'", escaped_excerpt(o.code)), "--code",
                     "use " + enum_name_list(target_code_names, " or ", "\""));
  spec.code = *code;
  for (const auto& [name, codes] : option_codes())
    if (o.given(name) && std::find(codes.begin(), codes.end(), spec.code) == codes.end())
      throw InputError(fmt::format("{} is not a parameter of --code \"{}\"", name, o.code), name,
                       fmt::format("drop {} (it belongs to --code \"{}\")", name, to_string(codes.front())));
  switch (spec.code) {
    case TargetCode::asce7_16: {
      const bool design = o.given("--sds") || o.given("--sd1");
      const bool maps = o.given("--ss") || o.given("--s1") || o.given("--site-class");
      if (design && maps)
        throw InputError("both --sds/--sd1 and --ss/--s1/--site-class", "--ss",
                         "give either --sds and --sd1 (design values) or --ss, --s1 and --site-class (mapped MCER values)");
      if (maps) {
        require(o, "--ss", o.code, "--ss 1.5 (g, the mapped MCER Sa at 0.2 s)");
        require(o, "--s1", o.code, "--s1 0.6 (g, the mapped MCER Sa at 1 s)");
        require(o, "--site-class", o.code, "--site-class C (A, B, C, D, D-default, E or F)");
        spec.from_maps = true;
        spec.maps = {o.ss, o.s1, parse_asce7_site_class(o.site_class, "--site-class"), o.tl};
        spec.asce7 = asce7_from_maps(spec.maps);
      } else {
        require(o, "--sds", o.code, "--sds 1.0 --sd1 0.6 (g), or --ss, --s1 and --site-class");
        require(o, "--sd1", o.code, "--sd1 0.6 (g, the design 1-s Sa)");
        spec.asce7 = {o.sds, o.sd1, o.tl};
      }
      spec.mcer = o.mcer;
      break;
    }
    case TargetCode::ec8: {
      require(o, "--ground", o.code, "--ground C (A, B, C, D or E)");
      require(o, "--agr", o.code, "--agr 0.25 (g, the reference PGA on ground A)");
      if (o.type != 1 && o.type != 2) throw InputError(fmt::format("--type {}", o.type), "--type", "give --type 1 or 2");
      spec.ec8.type = o.type == 1 ? Ec8Type::type1 : Ec8Type::type2;
      const std::string grounds = "ABCDE";
      const std::size_t g = o.ground.size() == 1 ? grounds.find(o.ground[0]) : std::string::npos;
      if (g == std::string::npos)
        throw InputError(fmt::format("EC8 ground '{}'", escaped_excerpt(o.ground)), "--ground", "use A, B, C, D or E");
      spec.ec8.ground = static_cast<Ec8Ground>(g);
      spec.ec8.agr = o.agr, spec.ec8.importance = o.importance;
      break;
    }
    case TargetCode::iran2800: {
      require(o, "--a", o.code, "--a 0.35 (0.35, 0.30, 0.25 or 0.20)");
      require(o, "--soil", o.code, "--soil III (I, II, III or IV)");
      const char* soils[] = {"I", "II", "III", "IV"};
      const auto* it = std::find(std::begin(soils), std::end(soils), o.soil);
      if (it == std::end(soils))
        throw InputError(fmt::format("soil '{}'", escaped_excerpt(o.soil)), "--soil", "use I, II, III or IV");
      spec.iran2800 = {o.a, static_cast<Iran2800Soil>(it - std::begin(soils)), o.importance};
      break;
    }
    case TargetCode::csv:
      require(o, "--file", o.code, "--file target.csv (period,sa lines in s, g)");
      spec.table = read_tabulated_spectrum(o.file);
      break;
  }
  return spec;
}

std::vector<double> spectrum_periods(const SpectrumOpts& o) {
  const bool list = !o.periods.empty(), range = !o.range.empty();
  if (list == range)
    throw InputError(list ? "both --periods and --range" : "no periods", "--periods/--range",
                     "give --periods 0.1,0.5,1,2 or --range 0,4 [--count 41] (s)");
  if (list) {
    if (o.opt.at("--count")->count() || o.log)
      throw InputError("--count/--log with --periods", "--count", "--count and --log go with --range");
    return parse_number_list(o.periods, "--periods", "period (s, >= 0)", "give periods in s, e.g. 0.1,0.5,1,2");
  }
  const auto r = parse_number_list(o.range, "--range", "period (s, >= 0)", "give LO,HI in s, e.g. 0,4");
  if (r.size() != 2 || !(r[1] > r[0]))
    throw InputError(fmt::format("--range '{}' is not LO,HI with HI > LO", escaped_excerpt(o.range)), "--range",
                     "give two periods in s, e.g. 0,4");
  if (o.count < 2 || o.count > 100000)
    throw InputError(fmt::format("--count {} is outside [2, 100000]", o.count), "--count", "give e.g. --count 41");
  if (o.log && !(r[0] > 0)) throw InputError("--log with LO = 0", "--range", "give LO > 0 for log spacing, e.g. 0.01,4");
  std::vector<double> T;
  for (int i = 0; i < o.count; ++i) {
    const double w = static_cast<double>(i) / (o.count - 1);
    T.push_back(i == o.count - 1 ? r[1] : o.log ? r[0] * std::pow(r[1] / r[0], w) : r[0] + w * (r[1] - r[0]));
  }
  return T;
}

}  // namespace

void add_spectrum(CLI::App& app) {
  auto o = std::make_shared<SpectrumOpts>();
  auto* c = app.add_subcommand("spectrum", "a code design spectrum (ASCE 7-16, EC8, Standard 2800, csv) at given "
                                           "periods: Sa in g and Sd in m, as a table or CSV "
                                           "(docs/ground-motions.md, 'Design spectra')");
  c->add_option("--code", o->code, "\"ASCE 7-16\", \"EC8\", \"Standard 2800\" or \"csv\"");
  auto add = [&](const char* name, auto& value, const char* help) { o->opt[name] = c->add_option(name, value, help); };
  add("--sds", o->sds, "ASCE 7-16: SDS, design short-period Sa (g), (0, 5]");
  add("--sd1", o->sd1, "ASCE 7-16: SD1, design 1-s Sa (g), (0, 5]");
  add("--ss", o->ss, "ASCE 7-16: Ss, mapped MCER Sa at 0.2 s (g), (0, 5]; with --s1 and --site-class");
  add("--s1", o->s1, "ASCE 7-16: S1, mapped MCER Sa at 1 s (g), (0, 3]");
  add("--site-class", o->site_class, "ASCE 7-16: A, B, C, D, D-default, E (F and the 11.4.8 cases are refused)");
  add("--tl", o->tl, "ASCE 7-16: TL (s), [1, 20], default 8");
  o->opt["--mcer"] = c->add_flag("--mcer", o->mcer, "ASCE 7-16: the MCER spectrum, 1.5 x the design spectrum");
  add("--type", o->type, "EC8: spectrum type 1 or 2 (default 1)");
  add("--ground", o->ground, "EC8: ground type A-E");
  add("--agr", o->agr, "EC8: agR (g), (0, 2]");
  add("--damping", o->damping, "EC8: damping ratio of the spectrum (default 0.05)");
  add("--importance", o->importance, "EC8: gammaI; Standard 2800: I; [0.8, 1.4], default 1");
  add("--a", o->a, "Standard 2800: A, 0.35, 0.30, 0.25 or 0.20");
  add("--soil", o->soil, "Standard 2800: soil type I-IV");
  add("--file", o->file, "csv: period,sa lines (s, g)");
  c->add_option("--periods", o->periods, "periods in s, e.g. 0,0.05,0.3,1,2");
  c->add_option("--range", o->range, "LO,HI in s: --count periods from LO to HI");
  o->opt["--count"] = c->add_option("--count", o->count, "with --range: number of periods (default 21)");
  c->add_flag("--log", o->log, "with --range: log-spaced (LO > 0) instead of evenly spaced");
  c->add_flag("--csv", o->csv, "CSV (period_s,sa_g,sd_m) instead of a table");
  c->callback([o] {
    const TargetSpectrumSpec spec = [&] {
      try {
        return spectrum_spec(*o);
      } catch (const InputError& e) {
        throw InputError(e.what_part(), e.where().rfind("--", 0) == 0 ? e.where() : option_of(e.where()), e.fix());
      }
    }();
    if (!(o->damping >= 0 && o->damping <= 0.5))
      throw InputError(fmt::format("--damping {} is outside [0, 0.5]", o->damping), "--damping", "give e.g. 0.05");
    const DesignSpectrum s = [&] {
      try {
        return make_target_spectrum(spec, o->damping);
      } catch (const InputError& e) {
        throw InputError(e.what_part(), option_of(e.where()), e.fix());
      }
    }();
    const std::vector<double> T = spectrum_periods(*o);
    std::vector<double> sa;
    for (double t : T) {
      try {
        sa.push_back(s.sa(t));
      } catch (const InputError& e) {
        throw InputError(e.what_part(), "--periods/--range", e.fix());
      }
    }
    const std::string text = describe_target(spec, s);
    std::string out = o->csv ? fmt::format("# {}\nperiod_s,sa_g,sd_m\n", text)
                             : fmt::format("{}\n{:>10} {:>10} {:>10}\n", text, "T s", "Sa g", "Sd m");
    for (std::size_t i = 0; i < T.size(); ++i) {
      const double sd = sa[i] * g0 * T[i] * T[i] / (4 * std::numbers::pi * std::numbers::pi);
      out += o->csv ? fmt::format("{:.9g},{:.9g},{:.9g}\n", T[i], sa[i], sd)
                    : fmt::format("{:>10.4f} {:>10.5f} {:>10.5f}\n", T[i], sa[i], sd);
    }
    fmt::print("{}", out);
  });
}

}  // namespace pounding::cli
