// `pounding stiffness`: the impact stiffness by every rule of the impact-stiffness and Muthukumar-DesRoches papers,
// side by side with each rule's assumptions, and the linear viscoelastic damping coefficient from e where the
// papers give it (issue 26 §4). `pounding similitude`: the scale factors of a shake-table model (bridge paper
// Table 2). Formulas: include/pounding/contact/stiffness_rules.hpp; worked values: ../shared/research/
// seeds-models.md §5 (V2, V5-V12), checked by tests/cli/stiffness.sh.
//
//   stiffness [--rule axial|lateral|sphere|jankowski|xu|experimental] [--youngs-modulus E --area A --length L]
//             [--lateral-stiffness K [--multiple 100]] [--mass1 m_i --mass2 m_j] [--density rho --poisson nu |
//             --radius1 R1 --radius2 R2 --poisson nu] [--scale lambda] [--k1 K1] [--e e | --damping-ratio xi]
//             [--json]
//   similitude --length-scale N_h --time-scale N_t --modulus-scale N_E [--mass-rule adequate|true-replica]
//              [--prototype-mass M] [--prototype-stiffness K] [--prototype-frequency f] [--json]
//
// Every option is checked before any output; a bad or missing one is one InputError naming it (exit 2).
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "pounding/contact/stiffness_rules.hpp"
#include "pounding/core/error.hpp"
#include "pounding/report/json.hpp"

namespace pounding::cli {

namespace {

namespace R = contact::rules;

// Physically sensible ranges (bad input outside them): SI units.
struct Range {
  double lo, hi;
  const char* text;
};
constexpr Range modulus_range{1e5, 1e13, "[1e5, 1e13] Pa (steel 2e11, concrete 3e10, PVC 2.5e9)"};
constexpr Range area_range{1e-10, 1e3, "[1e-10, 1e3] m^2 (the impact-stiffness paper's cap 63.5e-6)"};
constexpr Range length_range{1e-4, 1e4, "[1e-4, 1e4] m (the impact-stiffness paper's 0.4)"};
constexpr Range stiffness_range{1e-3, 1e13, "[1e-3, 1e13] N/m (the 1/30-scale 5-storey frame 27.5e3)"};
constexpr Range multiple_range{1.0, 1000.0, "[1, 1000] (Naserkhaki et al.: 50 to 100)"};
constexpr Range mass_range{1e-4, 1e10, "[1e-4, 1e10] kg (a 1/30-scale floor 6.27, a bridge span 1e6)"};
constexpr Range density_range{10.0, 3e4, "[10, 3e4] kg/m^3 (concrete 2400, steel 7850, PVC 1400)"};
constexpr Range poisson_range{0.0, 0.4999, "[0, 0.5) (concrete 0.15-0.2, steel 0.3)"};
constexpr Range radius_range{1e-5, 1e3, "[1e-5, 1e3] m"};
constexpr Range e_range{0.01, 1.0, "[0.01, 1] (steel frames 0.8, concrete 0.65)"};
constexpr Range xi_range{0.0, 1.0, "[0, 1] (the impact-stiffness paper's average 0.078)"};

double checked(const CLI::App* c, const char* opt, double v, const Range& r) {
  if (c->count(opt) > 0) require_range(v, r.lo, r.hi, opt, r.text);
  return v;
}

// "1/30" or "0.0333": a length scale lambda = model / prototype in (0, 1].
double parse_scale(const std::string& text, const char* opt) {
  const std::string fix = "give the model / prototype length scale in (0, 1], e.g. 1/30 or 0.125";
  double v = NAN;
  try {
    std::size_t used = 0;
    const std::size_t slash = text.find('/');
    if (slash == std::string::npos) {
      v = std::stod(text, &used);
      if (used != text.size()) v = NAN;
    } else {
      const std::string a = text.substr(0, slash), b = text.substr(slash + 1);
      std::size_t ua = 0, ub = 0;
      const double num = std::stod(a, &ua), den = std::stod(b, &ub);
      v = (ua == a.size() && ub == b.size() && den != 0.0) ? num / den : NAN;
    }
  } catch (const std::exception&) {
    v = NAN;
  }
  if (!(std::isfinite(v) && v > 0.0 && v <= 1.0))
    throw InputError(fmt::format("'{}' is not a length scale in (0, 1]", escaped_excerpt(text)), opt, fix);
  return v;
}

// 3.175e7 (no '+', no leading zeros in the exponent); plain below 1e4 and from 1e-3
std::string sci(double v) {
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e-3 && a < 1e4) return fmt::format("{:.5g}", v);
  std::string s = fmt::format("{:.4e}", v);  // 3.1750e+07
  const std::size_t e = s.find('e');
  std::string mant = s.substr(0, e);
  while (mant.back() == '0') mant.pop_back();
  if (mant.back() == '.') mant.pop_back();
  return mant + "e" + std::to_string(std::stoi(s.substr(e + 1)));
}

struct Opts {
  std::string rule, scale;
  double E = 0, area = 0, length = 0, lateral = 0, multiple = 100, m1 = 0, m2 = 0, density = 0, poisson = 0, r1 = 0,
         r2 = 0, k1 = 0, e = 0, xi = 0;
  bool json = false;
};

struct Row {
  std::string rule, unit, formula, inputs, assumptions, source;
  double k = 0;
  std::optional<double> c;  // linear viscoelastic damping coefficient (kg/s), where e and the masses are given
};

// Which options each rule needs (names, for the error of a --rule that lacks them).
struct Need {
  const char* rule;
  std::vector<std::vector<const char*>> any_of;  // every group must be given (a group: one of its options)
};

const std::vector<std::string> rule_names{"axial", "lateral", "sphere", "jankowski", "xu", "experimental"};

void add_options(CLI::App* c, Opts& o) {
  c->add_option("--rule", o.rule, "one rule (axial, lateral, sphere, jankowski, xu, experimental); without it, every "
                                  "rule the options given allow");
  c->add_option("--youngs-modulus", o.E, "Young's modulus E (Pa) of the member that hits (axial) or of the spheres' "
                                         "material (sphere)");
  c->add_option("--area", o.area, "axial: cross-section area A of the member that hits (m^2)");
  c->add_option("--length", o.length, "axial: length L over which the member is compressed (m)");
  c->add_option("--lateral-stiffness", o.lateral, "lateral: the building's lateral stiffness (N/m)");
  c->add_option("--multiple", o.multiple, "lateral: the multiple of the lateral stiffness (Naserkhaki et al.: 50 "
                                          "to 100)")->capture_default_str();
  c->add_option("--mass1", o.m1, "mass m_i of body 1 (kg): sphere (span mass), xu, damping coefficient");
  c->add_option("--mass2", o.m2, "mass m_j of body 2 (kg): sphere, xu (k scales with m_j / (m_i + m_j)), damping");
  c->add_option("--density", o.density, "sphere: density of the bodies' material (kg/m^3), for the radius of the "
                                        "sphere of each mass");
  c->add_option("--poisson", o.poisson, "sphere: Poisson's ratio of the material");
  c->add_option("--radius1", o.r1, "sphere: radius R1 (m), instead of --mass1 with --density");
  c->add_option("--radius2", o.r2, "sphere: radius R2 (m), instead of --mass2 with --density");
  c->add_option("--scale", o.scale, "jankowski, experimental: length scale lambda = model / prototype, e.g. 1/30");
  c->add_option("--k1", o.k1, "xu: the axial stiffness k1 (N/m) if not from --youngs-modulus --area --length");
  c->add_option("--e", o.e, "coefficient of restitution: xu, and the damping coefficient C of each linear rule");
  c->add_option("--damping-ratio", o.xi, "the impact damping ratio xi for C instead of the one from --e "
                                         "(the impact-stiffness paper's Table 2 used its averaged per-impact xi = "
                                         "0.078 with e = 0.8 for Xu's k)");
  c->add_flag("--json", o.json, "print one JSON object (full precision)");
}

// Every option's range; returns lambda (0 without --scale).
double check_options(const CLI::App* c, const Opts& o) {
  auto has = [&](const char* opt) { return c->count(opt) > 0; };
  checked(c, "--youngs-modulus", o.E, modulus_range);
  checked(c, "--area", o.area, area_range);
  checked(c, "--length", o.length, length_range);
  checked(c, "--lateral-stiffness", o.lateral, stiffness_range);
  checked(c, "--multiple", o.multiple, multiple_range);
  checked(c, "--mass1", o.m1, mass_range);
  checked(c, "--mass2", o.m2, mass_range);
  checked(c, "--density", o.density, density_range);
  checked(c, "--poisson", o.poisson, poisson_range);
  checked(c, "--radius1", o.r1, radius_range);
  checked(c, "--radius2", o.r2, radius_range);
  checked(c, "--k1", o.k1, stiffness_range);
  checked(c, "--e", o.e, e_range);
  checked(c, "--damping-ratio", o.xi, xi_range);
  if (has("--k1") && has("--area") && has("--length") && has("--youngs-modulus"))
    throw InputError("--k1 and the axial stiffness (--youngs-modulus --area --length) both given", "--k1",
                     "give one of them for the Xu et al. rule's k1");
  const double lambda = has("--scale") ? parse_scale(o.scale, "--scale") : 0.0;
  if (!o.rule.empty() && std::find(rule_names.begin(), rule_names.end(), o.rule) == rule_names.end())
    throw InputError(fmt::format("unknown rule '{}'", escaped_excerpt(o.rule)), "--rule",
                     "give one of axial, lateral, sphere, jankowski, xu, experimental (or leave --rule out for all)");
  return lambda;
}

// The rules to compute: --rule (InputError when its options are missing) or every rule the options allow.
std::vector<std::string> chosen_rules(const CLI::App* c, const Opts& o) {
  auto has = [&](const char* opt) { return c->count(opt) > 0; };

  // what each rule needs: groups of alternatives
  const std::vector<Need> needs{
      {"axial", {{"--youngs-modulus"}, {"--area"}, {"--length"}}},
      {"lateral", {{"--lateral-stiffness"}}},
      {"sphere", {{"--youngs-modulus"}, {"--poisson"}, {"--radius1", "--mass1"}, {"--radius2", "--mass2"}}},
      {"jankowski", {{"--scale"}}},
      {"xu", {{"--k1", "--area"}, {"--e"}, {"--mass1"}, {"--mass2"}}},
      {"experimental", {{"--scale"}}},
  };
  auto missing = [&](const Need& n) -> std::string {
    for (const auto& group : n.any_of) {
      bool ok = false;
      for (const char* opt : group) ok = ok || has(opt);
      if (!ok) return group.size() == 1 ? group[0] : fmt::format("{} or {}", group[0], group[1]);
    }
    if (std::string(n.rule) == "xu" && !has("--k1") && !(has("--youngs-modulus") && has("--length")))
      return "--k1 or --youngs-modulus --area --length";
    if (std::string(n.rule) == "sphere") {
      if (!has("--radius1") && !has("--density")) return "--density (or --radius1)";
      if (!has("--radius2") && !has("--density")) return "--density (or --radius2)";
    }
    return "";
  };
  std::vector<std::string> chosen;
  for (const Need& n : needs) {
    if (!o.rule.empty() && o.rule != n.rule) continue;
    const std::string miss = missing(n);
    if (!o.rule.empty() && !miss.empty())
      throw InputError(fmt::format("rule '{}' needs {}", n.rule, miss), miss.substr(0, miss.find(' ')),
                       "give it (see pounding stiffness --help)");
    if (miss.empty()) chosen.push_back(n.rule);
  }
  if (chosen.empty())
    throw InputError("no rule can be computed from the options given", "pounding stiffness",
                     "give e.g. --youngs-modulus --area --length (axial), --lateral-stiffness (lateral), --scale "
                     "(jankowski, experimental); --rule NAME says what a rule needs");
  return chosen;
}

// One rule's row (its options checked).
Row make_row(const CLI::App* c, const Opts& o, const std::string& rule, double lambda) {
  auto has = [&](const char* opt) { return c->count(opt) > 0; };
  const double k_axial = (has("--youngs-modulus") && has("--area") && has("--length")) ? R::axial(o.E, o.area, o.length)
                                                                                       : o.k1;
  Row r;
  r.rule = rule;
  r.unit = "N/m";
  if (rule == "axial") {
    r.k = R::axial(o.E, o.area, o.length);
    r.formula = "k = E A / L";
    r.inputs = fmt::format("E = {} Pa, A = {} m^2, L = {} m", sci(o.E), sci(o.area), sci(o.length));
    r.assumptions = "the member that hits stays elastic and is compressed uniformly over L (a bar); an upper "
                    "bound for slab-to-slab contact (Maison & Kasai)";
    r.source = "impact-stiffness paper eqs 5, 8 (Maison & Kasai)";
  } else if (rule == "lateral") {
    r.k = R::lateral_multiple(o.lateral, o.multiple);
    r.formula = fmt::format("k = {} x K_lateral", sci(o.multiple));
    r.inputs = fmt::format("K_lateral = {} N/m, multiple {} (50x: {} N/m, 100x: {} N/m)", sci(o.lateral),
                           sci(o.multiple), sci(50.0 * o.lateral), sci(100.0 * o.lateral));
    r.assumptions = "a rule of thumb (50 to 100 x the stiffer building's lateral stiffness), no contact "
                    "mechanics; far softer than the measured contact";
    r.source = "impact-stiffness paper eqs 6, 9 (Naserkhaki et al.)";
  } else if (rule == "sphere") {
    const double r1 = has("--radius1") ? o.r1 : R::sphere_radius(o.m1, o.density);
    const double r2 = has("--radius2") ? o.r2 : R::sphere_radius(o.m2, o.density);
    r.k = R::hertz_spheres(r1, r2, o.E, o.poisson);
    r.unit = "N/m^1.5";
    r.formula = "kh = 4 / (3 (h1 + h2)) sqrt(R1 R2 / (R1 + R2)), h = (1 - nu^2) / E, R = (3 m / (4 pi rho))^(1/3)";
    r.inputs = fmt::format("R1 = {} m, R2 = {} m, E = {} Pa, nu = {}{}", sci(r1), sci(r2), sci(o.E), o.poisson,
                           has("--density") ? fmt::format(", rho = {} kg/m^3", sci(o.density)) : "");
    r.assumptions = "Hertz contact of two spheres of the bodies' masses and one material: a Hertz (n = 3/2) "
                    "stiffness for hertz/hertzdamp/jankowski, not a linear one";
    r.source = "Muthukumar & DesRoches eqs 11-13; bridge paper eqs 7-9";
  } else if (rule == "jankowski") {
    r.k = R::jankowski_scaled(lambda);
    r.formula = "k = 482 kN/mm x lambda";
    r.inputs = fmt::format("lambda = {}", sci(lambda));
    r.assumptions = "Jankowski's steel-to-steel experimental stiffness, scaled linearly with the length scale";
    r.source = "impact-stiffness paper section 3 (Jankowski)";
  } else if (rule == "xu") {
    r.k = R::xu(k_axial, o.m1, o.m2, o.e);
    r.formula = "k = m_j / (m_i + m_j) k1 exp[(2 ln e / pi) asin(pi / sqrt(pi^2 + ln^2 e))]";
    r.inputs = fmt::format("k1 = {} N/m ({}), m_i = {} kg, m_j = {} kg, e = {}", sci(k_axial),
                           has("--k1") ? "--k1" : "E A / L", sci(o.m1), sci(o.m2), o.e);
    r.assumptions = "the Kelvin contact's peak deformation matched to the axial member's (Xu et al. 2016)";
    r.source = "impact-stiffness paper eq. 7 (Xu et al.)";
  } else {
    r.k = R::experimental_scaled(lambda);
    r.formula = "k = 620 lambda kN/mm (20.66 kN/mm at 1/30)";
    r.inputs = fmt::format("lambda = {}", sci(lambda));
    r.assumptions = "identified from steel floor-to-floor impacts of 1/30-scale single-bay steel moment frames, "
                    "elastic response; scaled linearly with the length scale";
    r.source = "impact-stiffness paper eqs 11-13, section 7";
  }
  return r;
}

// Validates the options, then computes every row asked for (InputError before any output).
std::vector<Row> compute(const CLI::App* c, const Opts& o, double& xi_out, double& meff_out) {
  auto has = [&](const char* opt) { return c->count(opt) > 0; };
  const double lambda = check_options(c, o);
  const std::vector<std::string> chosen = chosen_rules(c, o);
  const bool masses = has("--mass1") && has("--mass2");
  // the damping coefficient's ratio and effective mass
  double xi = NAN;
  if (has("--damping-ratio")) xi = o.xi;
  else if (has("--e")) xi = R::kelvin_xi(o.e);
  const double meff = masses ? o.m1 * o.m2 / (o.m1 + o.m2) : NAN;
  xi_out = xi, meff_out = meff;
  const bool with_c = masses && std::isfinite(xi);

  std::vector<Row> rows;
  for (const std::string& rule : chosen) {
    Row r = make_row(c, o, rule, lambda);
    if (with_c && r.unit == "N/m") r.c = R::kelvin_c(r.k, o.m1, o.m2, xi);
    rows.push_back(std::move(r));
  }
  return rows;
}

std::string si_alt(const Row& r) {  // the papers' units
  if (r.unit == "N/m^1.5") return fmt::format("{:.6g} kN/mm^1.5", r.k * 1e-3 / std::pow(1e3, 1.5));
  return fmt::format("{:.6g} N/mm", r.k * 1e-3);
}

void print_stiffness(const Opts& o, const std::vector<Row>& rows, double xi, double meff, bool given_xi) {
  if (o.json) {
    report::JsonWriter w;
    w.begin_object();
    w.member("damping_ratio", xi);
    w.member("effective_mass_kg", meff);
    w.key("rules").begin_array();
    for (const Row& r : rows) {
      w.begin_object();
      w.member("rule", r.rule).member("k", r.k).member("unit", r.unit);
      w.member("c_kg_per_s", r.c ? *r.c : NAN);
      w.member("formula", r.formula).member("inputs", r.inputs).member("assumptions", r.assumptions);
      w.member("source", r.source);
      w.end_object();
    }
    w.end_array();
    fmt::print("{}", w.end_object().str());
    return;
  }
  for (const Row& r : rows) {
    fmt::print("{}: k = {} {} ({})", r.rule, sci(r.k), r.unit, si_alt(r));
    if (r.c) fmt::print(", C = {:.6g} kg/s", *r.c);
    fmt::print("\n  formula: {}\n  inputs: {}\n  assumes: {}\n  source: {}\n", r.formula, r.inputs, r.assumptions,
               r.source);
  }
  if (std::isfinite(xi) && std::isfinite(meff))
    fmt::print("damping: C = 2 xi sqrt(k m_i m_j / (m_i + m_j)) with xi = {:.6g}{}, m_i m_j / (m_i + m_j) = {:.6g} kg "
               "(impact-stiffness paper eqs 2-3; the linear viscoelastic law only)\n",
               xi, given_xi ? " (given)" : fmt::format(" (= -ln e / sqrt(pi^2 + ln^2 e), e = {})", o.e),
               meff);
  else
    fmt::print("damping: not computed (give --e or --damping-ratio, and --mass1 --mass2, for C of the linear rules)\n");
}

struct SimOpts {
  double length = 0, time = 0, modulus = 0, mass = 0, stiffness = 0, frequency = 0;
  std::string rule = "adequate";
  bool json = false;
};

}  // namespace

void add_stiffness(CLI::App& app) {
  auto o = std::make_shared<Opts>();
  auto* c = app.add_subcommand("stiffness", "impact stiffness by every rule of the impact-stiffness and "
                                            "Muthukumar-DesRoches papers, with assumptions and the damping C from e");
  add_options(c, *o);
  c->footer("Rules: axial (k = E A / L), lateral (a multiple of the lateral stiffness), sphere (Hertz stiffness of "
            "equivalent spheres, N/m^1.5), jankowski (482 kN/mm x lambda), xu (Xu et al. from k1 and e), "
            "experimental (620 lambda kN/mm). C = 2 xi sqrt(k m_i m_j / (m_i + m_j)) for the linear rules when "
            "--e (or --damping-ratio) and both masses are given.");
  c->callback([o, c] {
    double xi = NAN, meff = NAN;
    const std::vector<Row> rows = compute(c, *o, xi, meff);
    print_stiffness(*o, rows, xi, meff, c->count("--damping-ratio") > 0);
  });
}

void add_similitude(CLI::App& app) {
  auto o = std::make_shared<SimOpts>();
  auto* c = app.add_subcommand("similitude", "scale factors (prototype / model) of a shake-table model from its "
                                             "length, time and modulus scales");
  c->add_option("--length-scale", o->length, "N_h = prototype / model length (the bridge paper: 125)")->required();
  c->add_option("--time-scale", o->time, "N_t = prototype / model time (the bridge paper: 2)")->required();
  c->add_option("--modulus-scale", o->modulus, "N_E = prototype / model elastic modulus (concrete / PVC: 12)")
      ->required();
  c->add_option("--mass-rule", o->rule, "adequate (Moncarz & Krawinkler artificial mass: N_m = N_E N_h^2, the "
                                        "bridge paper's) or true-replica (N_m = N_E N_h^2 / N_a)")
      ->capture_default_str();
  c->add_option("--prototype-mass", o->mass, "prototype mass (kg) -> the model's");
  c->add_option("--prototype-stiffness", o->stiffness, "prototype lateral stiffness (N/m) -> the model's");
  c->add_option("--prototype-frequency", o->frequency, "prototype frequency (Hz) -> the model's");
  c->add_flag("--json", o->json, "print one JSON object (full precision)");
  c->footer("Factors are prototype / model: a model value = prototype value / factor. N_a = N_h / N_t^2, "
            "N_v = N_h / N_t, N_F = N_m N_a, N_K = N_m / N_t^2 (the lateral/contact stiffness that keeps the "
            "frequencies in 1 / N_t); N_E N_h is the stiffness ratio of a geometrically scaled member of the "
            "model material, equal to N_K only for a true replica.");
  c->callback([o, c] {
    const Range scale{1e-6, 1e6, "[1e-6, 1e6] (a ratio prototype / model, e.g. 125)"};
    require_range(o->length, scale.lo, scale.hi, "--length-scale", scale.text);
    require_range(o->time, scale.lo, scale.hi, "--time-scale", scale.text);
    require_range(o->modulus, scale.lo, scale.hi, "--modulus-scale", scale.text);
    R::MassRule rule;
    if (o->rule == "adequate") rule = R::MassRule::adequate;
    else if (o->rule == "true-replica") rule = R::MassRule::true_replica;
    else
      throw InputError(fmt::format("unknown mass rule '{}'", escaped_excerpt(o->rule)), "--mass-rule",
                       "give adequate or true-replica");
    if (c->count("--prototype-mass")) require_range(o->mass, 1e-6, 1e12, "--prototype-mass", "[1e-6, 1e12] kg");
    if (c->count("--prototype-stiffness"))
      require_range(o->stiffness, 1e-6, 1e15, "--prototype-stiffness", "[1e-6, 1e15] N/m");
    if (c->count("--prototype-frequency"))
      require_range(o->frequency, 1e-4, 1e4, "--prototype-frequency", "[1e-4, 1e4] Hz");
    const R::Similitude s = R::similitude(o->length, o->time, o->modulus, rule);
    struct Item {
      const char* name;
      double v;
      const char* note;
    };
    std::vector<Item> items{
        {"length", s.length, "N_h (given)"},
        {"time", s.time, "N_t (given)"},
        {"modulus", s.modulus, "N_E (given)"},
        {"acceleration", s.acceleration, "N_a = N_h / N_t^2"},
        {"velocity", s.velocity, "N_v = N_h / N_t (divide a prototype impact velocity by it for a model-scale e(v))"},
        {"frequency", s.frequency, "N_f = 1 / N_t"},
        {"mass", s.mass, rule == R::MassRule::adequate ? "N_m = N_E N_h^2 (adequate model, artificial mass)"
                                                       : "N_m = N_E N_h^2 / N_a (true replica)"},
        {"force", s.force, "N_F = N_m N_a"},
        {"stiffness", s.stiffness, "N_K = N_m / N_t^2 (lateral and contact stiffness, N/m)"},
        {"member_stiffness", s.member_stiffness, "N_E N_h (a scaled member of the model material)"},
    };
    std::vector<Item> model;
    if (c->count("--prototype-mass")) model.push_back({"model_mass_kg", o->mass / s.mass, ""});
    if (c->count("--prototype-stiffness")) model.push_back({"model_stiffness_N_per_m", o->stiffness / s.stiffness, ""});
    if (c->count("--prototype-frequency")) model.push_back({"model_frequency_Hz", o->frequency / s.frequency, ""});
    if (o->json) {
      report::JsonWriter w;
      w.begin_object();
      w.member("mass_rule", o->rule);
      for (const Item& i : items) w.member(i.name, i.v);
      for (const Item& i : model) w.member(i.name, i.v);
      fmt::print("{}", w.end_object().str());
      return;
    }
    fmt::print("mass_rule: {}\n", o->rule);
    for (const Item& i : items) fmt::print("{}: {:.9g}  ({})\n", i.name, i.v, i.note);
    for (const Item& i : model) fmt::print("{}: {:.9g}\n", i.name, i.v);
    if (rule == R::MassRule::adequate && std::abs(s.member_stiffness / s.stiffness - 1.0) > 1e-9)
      fmt::print("note: distorted model: a geometrically scaled member of the model material is {:.4g} x as stiff as "
                 "N_K asks (stiffness / member_stiffness); size the model's members for N_K\n",
                 s.stiffness / s.member_stiffness);
  });
}

}  // namespace pounding::cli
