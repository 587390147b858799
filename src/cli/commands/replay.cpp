// `pounding replay`: a contact law evaluated on imposed or measured kinematics (issue 26 §3; physics/replay.hpp).
//
//   replay --input kin.csv --law L --kh K [--n 1.5] [--damping-law D] [--e E | --restitution-...] [--m1 M --m2 M]
//          [--gap G] [--out forces.csv] [--json]
//
// kin.csv: a header line naming the columns, then numbers (comma-separated; '#' lines and blank lines skipped):
//   time (s, strictly increasing), and either penetration (m, u1 - u2 - gap: positive in contact) or u1 and u2 (m;
//   penetration = u1 - u2 - --gap); optional velocity (the penetration rate, m/s) or v1 and v2; optional force
//   (the measured contact force, N). Without velocities the rate is differentiated: second-order central
//   differences on the (possibly non-uniform) time grid, one-sided at the ends (numpy.gradient's formula).
// Every check comes before any output; a bad file is one InputError naming the file and line.
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/commands/restitution_options.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/physics/replay.hpp"
#include "pounding/physics/single_impact.hpp"
#include "pounding/report/json.hpp"

namespace pounding::cli {

namespace {

struct Opts {
  std::string input, out, law = "hertzdamp", damping_law = "lankarani-nikravesh";
  double kh = 0, n = 1.5, e = 0.65, m1 = 0, m2 = 0, gap = 0;
  bool json = false;
  RestitutionOpts rest;
};

struct Kinematics {
  physics::ReplayInput in;
  bool differentiated = false;
  std::string source;  // "penetration" or "u1 - u2 - gap"
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t c = line.find(',', pos);
    std::string tok = line.substr(pos, c == std::string::npos ? std::string::npos : c - pos);
    const auto a = tok.find_first_not_of(" \t\r"), b = tok.find_last_not_of(" \t\r");
    out.push_back(a == std::string::npos ? "" : tok.substr(a, b - a + 1));
    if (c == std::string::npos) return out;
    pos = c + 1;
  }
}

const char* const fix_cols = "give a header line: time, penetration (or u1, u2), optional velocity (or v1, v2), "
                             "optional force";

// The file's columns by header name (every value checked, naming FILE:LINE).
struct Columns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> cols;
  std::size_t header_line = 0;
  const std::vector<double>* col(const char* nm) const {
    for (std::size_t k = 0; k < names.size(); ++k)
      if (names[k] == nm) return &cols[k];
    return nullptr;
  }
};

Columns read_columns(const std::string& path) {
  std::string text = files::read_text(path, "the kinematics file", std::size_t{64} << 20);
  if (text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);  // the UTF-8 byte-order mark of Excel's "CSV UTF-8"
  Columns C;
  std::vector<std::string>& names = C.names;
  std::vector<std::vector<double>>& cols = C.cols;
  std::size_t lineno = 0, pos = 0, header_line = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++lineno;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t\r")] == '#') continue;
    const std::vector<std::string> f = split(line);
    const std::string where = fmt::format("{}:{}", path, lineno);
    if (names.empty()) {
      names = f;
      header_line = lineno;
      for (const std::string& nm : names) {
        static const char* known[] = {"time", "penetration", "u1", "u2", "velocity", "v1", "v2", "force"};
        if (std::find(std::begin(known), std::end(known), nm) == std::end(known))
          throw InputError(fmt::format("unknown column '{}'", escaped_excerpt(nm)), where, fix_cols);
        if (std::count(names.begin(), names.end(), nm) > 1)
          throw InputError(fmt::format("column '{}' given twice", nm), where, fix_cols);
      }
      cols.assign(names.size(), {});
      continue;
    }
    if (f.size() != names.size())
      throw InputError(fmt::format("{} values, the header has {}", f.size(), names.size()), where,
                       "give one value per column on every line");
    for (std::size_t k = 0; k < f.size(); ++k) {
      double v = NAN;
      try {
        std::size_t used = 0;
        v = std::stod(f[k], &used);
        if (used != f[k].size()) v = NAN;
      } catch (const std::exception&) {
        v = NAN;
      }
      if (!std::isfinite(v))
        throw InputError(fmt::format("'{}' is not a finite number in column {}", escaped_excerpt(f[k]), names[k]),
                         where, "give numbers in SI units (s, m, m/s, N)");
      if (names[k] == "time" && !cols[k].empty() && !(v > cols[k].back()))
        throw InputError(fmt::format("time {} does not increase (previous {})", v, cols[k].back()), where,
                         "give strictly increasing times");
      if ((names[k] != "time" && names[k] != "force" && std::abs(v) > 100.0) ||
          (names[k] == "force" && std::abs(v) > 1e12))
        throw InputError(fmt::format("{} = {} is not a pounding value (metres, m/s or N expected)", names[k], v),
                         where, "give SI units: displacements in m, velocities in m/s, force in N");
      cols[k].push_back(v);
    }
  }
  C.header_line = header_line;
  return C;
}

Kinematics read_kinematics(const std::string& path, double gap) {
  const Columns C = read_columns(path);
  auto col = [&](const char* nm) { return C.col(nm); };
  const std::vector<std::string>& names = C.names;
  const std::string head = fmt::format("{}:{}", path, C.header_line ? C.header_line : 1);
  if (names.empty()) throw InputError("no header line", head, fix_cols);
  if (!col("time")) throw InputError("no column 'time'", head, fix_cols);
  const bool pen = col("penetration"), disp = col("u1") || col("u2");
  if (pen == disp || (disp && !(col("u1") && col("u2"))))
    throw InputError("give either a penetration column or both u1 and u2", head, fix_cols);
  if (col("velocity") && (col("v1") || col("v2")))
    throw InputError("both velocity and v1/v2 columns", head, "give the penetration rate or both velocities");
  if ((col("v1") != nullptr) != (col("v2") != nullptr)) throw InputError("v1 without v2 (or v2 without v1)", head, fix_cols);
  if (col("velocity") && disp) throw InputError("a velocity column with u1/u2", head, "give v1 and v2 with u1 and u2");
  if (col("v1") && pen) throw InputError("v1/v2 columns with a penetration column", head, "give its rate as velocity");
  if (col("time")->size() < 3) throw InputError(fmt::format("{} data lines", col("time")->size()), path,
                                                "give at least 3 samples of the motion");
  Kinematics k;
  k.in.t = *col("time");
  const std::size_t N = k.in.t.size();
  if (pen) {
    k.in.d = *col("penetration");
    k.source = "penetration";
  } else {
    for (std::size_t i = 0; i < N; ++i) k.in.d.push_back((*col("u1"))[i] - (*col("u2"))[i] - gap);
    k.source = "u1 - u2 - gap";
  }
  if (col("velocity")) {
    k.in.dd = *col("velocity");
  } else if (col("v1")) {
    for (std::size_t i = 0; i < N; ++i) k.in.dd.push_back((*col("v1"))[i] - (*col("v2"))[i]);
  } else {
    k.in.dd = physics::differentiate(k.in.t, k.in.d);
    k.differentiated = true;
  }
  if (col("force")) {
    k.in.measured = *col("force");
    if (!(*std::max_element(k.in.measured.begin(), k.in.measured.end()) > 0.0))
      throw InputError("the measured force is never positive", path + " column force",
                       "give the compressive contact force as positive numbers (N)");
  }
  return k;
}

std::string table_csv(const Kinematics& k, const physics::ReplayResult& r) {
  const bool meas = !k.in.measured.empty();
  std::string s = "time_s,penetration_m,velocity_mps,force_N,measured_force_N,impact\n";
  for (std::size_t i = 0; i < k.in.t.size(); ++i)
    s += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{},{}\n", k.in.t[i], k.in.d[i], k.in.dd[i], r.force[i],
                     meas ? fmt::format("{:.17g}", k.in.measured[i]) : std::string("nan"), r.impact[i]);
  return s;
}

void print(const Opts& o, const ContactModel& cm, const Kinematics& k, const physics::ReplayResult& r,
           const contact::RestitutionCurve* curve) {
  const bool damped = contact::traits(cm.law).restitution_from_damping;
  int outside = 0, clamped = 0;
  for (const auto& im : r.impacts) outside += im.outside_valid ? 1 : 0, clamped += im.clamped ? 1 : 0;
  const std::string velocity = k.differentiated ? "differentiated (second-order central differences, one-sided at "
                                                  "the ends)"
                                                : "given";
  if (o.json) {
    report::JsonWriter w;
    w.begin_object();
    w.member("law", std::string(to_string(cm.law)));
    if (damped) w.member("damping_law", std::string(to_string(cm.damping)));
    w.member("stiffness", o.kh).member("samples", static_cast<std::int64_t>(k.in.t.size()));
    w.member("penetration_from", k.source).member("velocity", velocity);
    if (curve) w.member("restitution", curve->describe());
    w.member("impacts", static_cast<std::int64_t>(r.impacts.size()));
    w.member("restitution_outside_valid", static_cast<std::int64_t>(outside));
    w.member("restitution_clamped", static_cast<std::int64_t>(clamped));
    w.member("tensile_force_clamps", static_cast<std::int64_t>(r.clamps));
    w.member("peak_force", r.peak_force).member("energy_dissipated", r.energy_dissipated);
    w.member("measured_peak_force", r.measured_peak).member("peak_error_pct", r.peak_error_pct);
    w.member("mean_abs_difference", r.mean_abs_difference).member("rms_difference", r.rms_difference);
    w.key("impact_list").begin_array();
    for (const auto& im : r.impacts) {
      w.begin_object();
      w.member("t_start", im.t_start).member("t_end", im.t_end).member("v0", im.v0).member("e", im.e);
      w.member("outside_valid", im.outside_valid).member("peak_force", im.peak_force);
      w.member("peak_penetration", im.peak_penetration).member("work_approach", im.work_approach);
      w.member("work_restitution", im.work_restitution).member("energy_dissipated", im.energy_dissipated);
      w.member("measured_peak_force", im.measured_peak).member("peak_error_pct", im.peak_error_pct);
      w.end_object();
    }
    w.end_array();
    fmt::print("{}", w.end_object().str());
    return;
  }
  fmt::print("law: {}{}\n", to_string(cm.law), damped ? fmt::format(" ({})", to_string(cm.damping)) : "");
  fmt::print("stiffness: {:.9g}\nsamples: {}\npenetration_from: {}\nvelocity: {}\n", o.kh, k.in.t.size(), k.source,
             velocity);
  if (curve) fmt::print("restitution: {}\n", curve->describe());
  fmt::print("impacts: {}\n", r.impacts.size());
  if (curve) fmt::print("restitution_outside_valid: {}\nrestitution_clamped: {}\n", outside, clamped);
  fmt::print("tensile_force_clamps: {}\npeak_force_N: {:.9g}\nenergy_dissipated_J: {:.9g}\n", r.clamps, r.peak_force,
             r.energy_dissipated);
  if (!k.in.measured.empty())
    fmt::print("measured_peak_force_N: {:.9g}\npeak_error_pct: {:.6g}\nmean_abs_difference_N: {:.9g}\n"
               "rms_difference_N: {:.9g}\n",
               r.measured_peak, r.peak_error_pct, r.mean_abs_difference, r.rms_difference);
  fmt::print("impact  t_start_s  t_end_s  v0_mps  e  peak_force_N  peak_penetration_m  work_approach_J  "
             "work_restitution_J  energy_dissipated_J{}\n",
             k.in.measured.empty() ? "" : "  measured_peak_N  peak_error_pct");
  for (std::size_t i = 0; i < r.impacts.size(); ++i) {
    const auto& im = r.impacts[i];
    fmt::print("{}  {:.6g}  {:.6g}  {:.6g}{}  {:.6g}  {:.6g}  {:.6g}  {:.6g}  {:.6g}  {:.6g}", i + 1, im.t_start,
               im.t_end, im.v0, im.outside_valid ? "*" : "", im.e, im.peak_force, im.peak_penetration,
               im.work_approach, im.work_restitution, im.energy_dissipated);
    if (!k.in.measured.empty()) fmt::print("  {:.6g}  {:.4g}", im.measured_peak, im.peak_error_pct);
    fmt::print("\n");
  }
  if (outside > 0) fmt::print("(*: v0 outside the restitution curve's valid range, e extrapolated)\n");
}

}  // namespace

void add_replay(CLI::App& app) {
  auto o = std::make_shared<Opts>();
  auto* c = app.add_subcommand("replay", "a contact law on imposed or measured kinematics: force history, "
                                         "force-penetration loop, energy per impact, error against a measured force");
  c->add_option("--input", o->input, "kinematics CSV: header time, penetration (or u1, u2), optional velocity (or "
                                     "v1, v2), optional force")->required();
  c->add_option("--law", o->law, std::string("contact law: ") + std::string(contact_law_names))->capture_default_str();
  c->add_option("--damping-law", o->damping_law, std::string("Hertzdamp xibar law: ") + std::string(damping_law_names))
      ->capture_default_str();
  c->add_option("--kh", o->kh, "contact stiffness (N/m^n; N/m for linear/kelvin)")->required();
  c->add_option("--n", o->n, "Hertz exponent")->capture_default_str();
  c->add_option("--e", o->e, "coefficient of restitution, (0, 1]")->capture_default_str();
  c->add_option("--m1", o->m1, "mass 1 (kg): kelvin and jankowski damping constants");
  c->add_option("--m2", o->m2, "mass 2 (kg)");
  c->add_option("--gap", o->gap, "gap (m) subtracted from u1 - u2 when the file gives displacements")
      ->capture_default_str();
  c->add_option("--out", o->out, "CSV of the force history: time_s, penetration_m, velocity_mps, force_N, "
                                 "measured_force_N, impact (tools/plot_replay.py draws it)");
  c->add_flag("--json", o->json, "print the summary as one JSON object");
  o->rest.add(c);
  c->callback([o, c] {
    if (!o->out.empty()) {
      files::check_output_not_input(o->out, {o->input}, "--out");  // never over the measured kinematics
      files::check_output_path(o->out, "--out");
    }
    ContactModel cm;
    cm.law = as_option("--law", [&] { return parse_contact_law(o->law); });
    cm.damping = as_option("--damping-law", [&] { return parse_damping_law(o->damping_law); });
    const contact::LawTraits& t = contact::traits(cm.law);
    if (!t.has_force)
      throw InputError(fmt::format("the {} law has no force to replay", to_string(cm.law)), "--law",
                       "choose a law with a force element (linear, kelvin, hertz, hertzdamp, jankowski)");
    require_range(o->n, 1.0, 3.0, "--n", "[1, 3]");
    cm.n = o->n;
    require_range(o->kh, 1.0, 1e14, "--kh", "[1, 1e14] N/m^n");
    const std::optional<contact::RestitutionCurve> curve = o->rest.get(c);
    if (curve && c->count("--e") > 0)
      throw InputError("--e and a restitution curve both given", "--e", "drop --e: the curve gives e(v0)");
    if (curve && restitution_promise(cm).kind == RestitutionKind::elastic)
      throw InputError(fmt::format("a restitution curve with the elastic {} law", to_string(cm.law)), "--law",
                       "choose a damped law (hertzdamp, kelvin, jankowski)");
    if (!curve) require_range(o->e, collide_e_min, 1.0, "--e", fmt::format("[{}, 1]", collide_e_min));
    const bool masses = c->count("--m1") > 0 && c->count("--m2") > 0;
    if (t.needs_restitution && !t.restitution_from_damping && !masses)
      throw InputError(fmt::format("the {} law's damping constant needs the two masses", to_string(cm.law)), "--m1",
                       "give --m1 and --m2 (kg)");
    if (masses) require_range(o->m1, 1e-6, 1e10, "--m1", "[1e-6, 1e10] kg"), require_range(o->m2, 1e-6, 1e10, "--m2", "[1e-6, 1e10] kg");
    require_range(o->gap, -10.0, 10.0, "--gap", "[-10, 10] m");
    const Kinematics k = read_kinematics(o->input, o->gap);
    physics::ReplaySettings s;
    s.cm = cm;
    s.kc = o->kh;
    s.e = t.needs_restitution ? o->e : 1.0;
    s.meff = masses ? o->m1 * o->m2 / (o->m1 + o->m2) : 0.0;
    s.curve = curve ? &*curve : nullptr;
    const physics::ReplayResult r = physics::replay(k.in, s);
    if (!o->out.empty()) files::write_text_atomically(o->out, table_csv(k, r));
    print(*o, cm, k, r, s.curve);
  });
}

}  // namespace pounding::cli
