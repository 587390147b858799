// `pounding accuracy ...`: the measurements of docs/accuracy.md and docs/validation.md (issue 6).
//   models               the model set + ground motions for tools/reference_solver.py
//   agree                engine high-accuracy mode vs a stored SciPy reference
//   chart                stepper x dt x contact law: cost and error against the reference (CSV)
//   stability            stability limits (h omega) and the stiff steel-frame contact (CSV)
//   resolution           accuracy limit h omega_c of every stepper x force law (the resolution guard's table)
//   restitution          effective e of every damping law, Kelvin's tension (CSV)
//   validate-muthukumar  Muthukumar-DesRoches (2006) parameter study on the real records (CSV)
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>

#include <fmt/format.h>

#include "pounding/accuracy/accuracy.hpp"
#include "pounding/accuracy/muthukumar.hpp"
#include "cli/commands.hpp"
#include "cli/commands/records_options.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/files.hpp"
#include "pounding/physics/resolution.hpp"

namespace pounding::cli {

namespace {

namespace A = pounding::accuracy;
using RecordsDir = std::shared_ptr<const std::string>;  // --records-dir, read when a subcommand runs


// models
void add_models(CLI::App* acc, const RecordsDir& dir) {
  struct O {
    int n = 50;
    double gap_ratio = 0.1, e = 0.65;
    std::string out = "accuracy-models/models.csv";
    std::vector<std::string> laws{"none", "hertzdamp", "kelvin", "linear", "stereomechanical"};
  };
  auto o = std::make_shared<O>();
  auto* c = acc->add_subcommand("models", "write the accuracy model set (CSV) and its ground motions (.ag)");
  c->add_option("--n", o->n, "number of sampled models")->capture_default_str();
  c->add_option("--gap-ratio", o->gap_ratio, "gap / code separation d")->capture_default_str();
  c->add_option("--e", o->e, "restitution")->capture_default_str();
  c->add_option("--laws", o->laws, "contact laws")->capture_default_str();
  c->add_option("--out", o->out, "output CSV (its directory receives <record>.ag)")->capture_default_str();
  c->callback([o, dir] {
    files::check_output_not_input(o->out, records_read({}, *dir), "--out");  // before any work
    require_positive(o->n, "--n");
    auto models = A::sample_models(o->n);
    auto recs = A::default_records();
    auto cases = A::make_cases(models, recs, o->laws, o->gap_ratio, o->e);
    auto parent = std::filesystem::path(o->out).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    A::write_cases(o->out, cases, *dir, recs);
    fmt::print("{} cases ({} models x {} records x {} laws) -> {}\n", cases.size(), models.size(), recs.size(),
               o->laws.size(), o->out);
  });
}

// agree
void add_agree(CLI::App* acc, const RecordsDir& dir) {
  struct O {
    std::string reference = "tests/data/reference/accuracy_reference.csv";  // from the repository root
    std::string stepper = "rk4";
    int substeps = 64;
    bool no_locate = false;
    std::string out;
  };
  auto o = std::make_shared<O>();
  auto* c = acc->add_subcommand("agree", "engine (default: rk4 + located contact, 64 substeps) vs the SciPy reference");
  c->add_option("--reference", o->reference, "reference CSV from tools/reference_solver.py")->capture_default_str();
  c->add_option("--stepper", o->stepper, "stepper")->capture_default_str();
  c->add_option("--substeps", o->substeps, "substeps per record step")->capture_default_str();
  c->add_flag("--no-locate", o->no_locate, "do not locate the contact onset");
  c->add_option("--out", o->out, "per-case CSV (engine beside reference)");
  c->callback([o, dir] {
    files::check_output_not_input(o->out, records_read({o->reference}, *dir), "--out");  // before any work
    auto cases = A::read_cases(o->reference);
    A::EngineSetting es{parse_stepper(o->stepper), o->substeps, !o->no_locate};
    double secs = 0;
    A::RecordCache records(*dir, A::default_records());
    auto res = A::run_cases(cases, es, records, &secs);
    fmt::print("engine: {} substeps {}{}, {} cases, {:.2f} s\n", o->stepper, o->substeps,
               o->no_locate ? "" : " located contact", cases.size(), secs);
    fmt::print("{:<17} {:>5} {:>9} {:>12} {:>12} {:>12} {:>12} {:>12} {:>8} {:>8}\n", "law", "cases", "impacting",
               "closing_med", "closing_max", "force_med", "force_p99", "force_max", "count!=", "verdict!=");
    for (const auto& a : A::agreement(cases, res))
      fmt::print("{:<17} {:>5} {:>9} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e} {:>8} {:>8}\n", a.law, a.cases,
                 a.impacting, a.closing_median, a.closing_max, a.force_median, a.force_p99, a.force_max,
                 a.count_differs, a.verdict_differs);
    if (!o->out.empty()) {
      std::ostringstream s;
      s << "record,model,law,ref_peak_closing,peak_closing,ref_peak_force,peak_force,ref_impact_count,"
           "impact_count,status\n";
      for (std::size_t i = 0; i < cases.size(); ++i)
        s << fmt::format("{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{},{},{}\n", cases[i].record, cases[i].model,
                         cases[i].law, cases[i].ref_peak_closing, res[i].peak_closing, cases[i].ref_peak_force,
                         res[i].peak_force, cases[i].ref_impact_count, res[i].impact_count, to_string(res[i].status));
      files::write_text_atomically(o->out, s.str());
    }
  });
}

// chart
void add_chart(CLI::App* acc, const RecordsDir& dir) {
  struct O {
    std::string reference = "tests/data/reference/accuracy_reference.csv";  // from the repository root
    std::string out = "accuracy_chart.csv";
    int repeats = 3, kmax = 5;
    std::string uncoupled;
    std::vector<std::string> rows;
  };
  auto o = std::make_shared<O>();
  auto* c = acc->add_subcommand("chart", "stepper x dt x contact law: cost and error against the reference");
  c->add_option("--reference", o->reference, "reference CSV")->capture_default_str();
  c->add_option("--out", o->out, "chart CSV")->capture_default_str();
  c->add_option("--repeats", o->repeats, "timing repeats (median)")->capture_default_str();
  c->add_option("--kmax", o->kmax, "dt = record dt x 2^-k, k = 0..kmax")->capture_default_str();
  c->add_option("--uncoupled", o->uncoupled, "larger uncoupled reference CSV for the probability table");
  add_list(c, "--rows", o->rows,
           "only these rows, stepper:law:k (e.g. central-difference:hertzdamp:2); each equals the full "
           "chart's row except the timing columns");
  c->callback([o, dir] {
    files::check_output_not_input(o->out, records_read({o->reference, o->uncoupled}, *dir), "--out");  // before any work
    require_positive(o->repeats, "--repeats");
    std::vector<A::ChartRowId> only;
    for (const auto& r : o->rows) only.push_back(A::parse_chart_row_id(r));
    auto cases = A::read_cases(o->reference);
    std::vector<A::Case> unc;
    if (!o->uncoupled.empty()) unc = A::read_cases(o->uncoupled);
    A::RecordCache records(*dir, A::default_records());
    auto rows = A::chart(cases, records, o->repeats, o->kmax, &unc, only);
    A::write_chart_csv(o->out, rows);
    fmt::print("{} rows -> {}\n", rows.size(), o->out);
  });
}

// stability
struct StabilityOpts {
  std::string out = "stability.csv", stiff_out = "stiff_contact.csv";
  std::vector<std::string> steppers, laws;  // stiff-contact subset (empty: all)
  std::vector<int> substeps;
  bool no_free = false, no_stiff = false;
};
void write_free_vibration(const StabilityOpts& o) {
  std::ostringstream s;
  s << "stepper,zeta,measured_h_omega,theory_h_omega\n";
  fmt::print("{:<20} {:>5} {:>10} {:>10}\n", "stepper", "zeta", "measured", "theory");
  for (const auto& r : A::stability_map()) {
    s << fmt::format("{},{},{:.6g},{:.6g}\n", r.stepper, r.zeta, r.measured, r.theory);
    fmt::print("{:<20} {:>5} {:>10.5g} {:>10.5g}\n", r.stepper, r.zeta, r.measured, r.theory);
  }
  files::write_text_atomically(o.out, s.str());
}
void write_stiff_contact(const StabilityOpts& o, const std::string& dir) {
  std::ostringstream t;
  t << "stepper,law,substeps,h_omega_contact,h_omega_lane,status,peak_force,force_error,impacts\n";
  for (const auto& r : A::stiff_contact(dir, o.steppers, o.laws, o.substeps)) {
    t << fmt::format("{},{},{},{:.4g},{:.4g},{},{:.6g},{:.4g},{}\n", r.stepper, r.law, r.substeps, r.h_omega_contact,
                     r.h_omega_lane, r.status, r.peak_force, r.force_error, r.impacts);
    fmt::print("{:<20} {:<10} {:>4} h*wc={:>8.3f} lane {:>8.3f} {:<10} F={:.4g} N ({:+.1f} %) impacts={}\n", r.stepper,
               r.law, r.substeps, r.h_omega_contact, r.h_omega_lane, r.status, r.peak_force, 100.0 * r.force_error,
               r.impacts);
  }
  files::write_text_atomically(o.stiff_out, t.str());
}
void add_stability(CLI::App* acc, const RecordsDir& dir) {
  auto o = std::make_shared<StabilityOpts>();
  auto* c = acc->add_subcommand("stability", "largest stable h omega per stepper; stiff steel-frame contact");
  c->add_option("--out", o->out, "stability CSV")->capture_default_str();
  c->add_option("--stiff-out", o->stiff_out, "stiff-contact CSV")->capture_default_str();
  c->add_option("--steppers", o->steppers, "stiff contact: only these steppers");
  c->add_option("--laws", o->laws, "stiff contact: only these laws (linear, kelvin, hertzdamp)");
  c->add_option("--substeps", o->substeps, "stiff contact: only these substep counts");
  c->add_flag("--no-free", o->no_free, "skip the free-vibration limits (stability CSV)");
  c->add_flag("--no-stiff", o->no_stiff, "skip the stiff steel-frame contact (stiff-contact CSV)");
  c->callback([o, dir] {
    const std::vector<std::string> inputs = records_read({}, *dir);  // before any work: no output over a record
    if (!o->no_free) files::check_output_not_input(o->out, inputs, "--out");
    if (!o->no_stiff) files::check_output_not_input(o->stiff_out, inputs, "--stiff-out");
    if (!o->no_free && !o->no_stiff) files::check_output_not_input(o->stiff_out, {o->out}, "--stiff-out", "the --out file");
    if (!o->no_free) write_free_vibration(*o);
    if (!o->no_stiff) write_stiff_contact(*o, *dir);
  });
}

// resolution
void add_resolution(CLI::App* acc) {
  struct O {
    std::string out = "resolution.csv", limits_out = "resolution_limits.csv";
    std::vector<std::string> schemes = A::resolution_schemes(), laws = A::resolution_laws();
    int points_per_decade = 150, phases = 8;
  };
  auto o = std::make_shared<O>();
  auto* c = acc->add_subcommand("resolution", "accuracy limit h omega_c of every stepper x force law (one free impact)");
  c->add_option("--out", o->out, "sweep CSV (one row per step)")->capture_default_str();
  c->add_option("--limits-out", o->limits_out, "limits CSV (the resolution guard's table)")->capture_default_str();
  c->add_option("--schemes", o->schemes, "central-difference, newmark, rk4, rk4-located, nigam-jennings")
      ->capture_default_str();
  c->add_option("--laws", o->laws, "force laws")->capture_default_str();
  c->add_option("--points-per-decade", o->points_per_decade, "h grid density")->capture_default_str();
  c->add_option("--phases", o->phases, "onset positions inside a step per h")->capture_default_str();
  c->callback([o] {
    files::check_output_not_input(o->limits_out, {o->out}, "--limits-out", "the --out file");  // before any work
    const auto pts = A::resolution_sweep(o->schemes, o->laws, o->points_per_decade, o->phases);
    std::ostringstream s;
    s << "scheme,law,steps,h_omega_contact,peak_force,force_error,e_effective,e_error,status\n";
    for (const auto& p : pts)
      s << fmt::format("{},{},{},{:.6g},{:.8g},{:.4g},{:.8g},{:.4g},{}\n", p.scheme, p.law, p.steps,
                       p.h_omega_contact, p.peak_force, p.force_error, p.e_effective, p.e_error, p.status);
    files::write_text_atomically(o->out, s.str());
    std::ostringstream l;
    l << "scheme,law,limit_h_omega,first_over_h_omega,tolerance\n";
    fmt::print("{:<20} {:<10} {:>8} {:>10}   (peak-force tolerance {} %)\n", "scheme", "law", "limit", "first over",
               100.0 * physics::resolution_tolerance);
    for (const auto& L : A::resolution_limits(pts, physics::resolution_tolerance)) {
      l << fmt::format("{},{},{:.3f},{:.4g},{}\n", L.scheme, L.law, L.limit, L.first_over,
                       physics::resolution_tolerance);
      fmt::print("{:<20} {:<10} {:>8.3f} {:>10.4g}\n", L.scheme, L.law, L.limit, L.first_over);
    }
    files::write_text_atomically(o->limits_out, l.str());
  });
}

// restitution
void add_restitution(CLI::App* acc) {
  struct O {
    std::string out = "restitution.csv";
    std::vector<std::string> laws;
    std::vector<double> targets;
  };
  auto o = std::make_shared<O>();
  auto* c = acc->add_subcommand("restitution", "effective vs target e for every damping law; Kelvin's tension");
  c->add_option("--out", o->out, "restitution CSV")->capture_default_str();
  add_list(c, "--laws", o->laws, "only these laws' rows (default: all eight)");
  add_list(c, "--targets", o->targets, "only these target e of the table's 0.10, 0.15, ..., 1.00");
  c->callback([o] {
    std::vector<double> targets;  // 0.05 i exactly as in the full table, so a subset gives the same rows
    for (int i = 2; i <= 20; ++i)
      if (o->targets.empty() ||
          std::any_of(o->targets.begin(), o->targets.end(), [i](double t) { return std::abs(t - 0.05 * i) < 1e-9; }))
        targets.push_back(0.05 * i);
    if (targets.size() < std::max<std::size_t>(1, o->targets.size()))
      throw InputError("a --targets value is not one of 0.10, 0.15, ..., 1.00", "--targets",
                       "give targets on the table's 0.05 grid");
    std::ostringstream s;
    s << "law,e_target,e_effective,clamps\n";
    for (const auto& r : A::restitution_table(targets, o->laws))
      s << fmt::format("{},{:.4g},{:.8g},{}\n", r.law, r.e_target, r.e_effective, r.clamps);
    files::write_text_atomically(o->out, s.str());
    fmt::print("restitution table -> {}\n", o->out);
    fmt::print("Kelvin (m1 = m2 = 1e6 kg, kc = 1e9 N/m, v0 = 1 m/s):\n");
    for (double e : {0.3, 0.5, 0.65, 0.8, 0.95}) {
      auto k = A::kelvin_tension(e);
      fmt::print("  e = {:.2f}: peak force {:.4g} N, unclamped tension {:.4g} N ({:.1f} % of peak), clamped steps "
                 "{}, smallest kernel force {:.3g} N, e delivered {:.4f}\n",
                 e, k.peak_force, k.tension_unclamped, 100.0 * -k.tension_unclamped / k.peak_force, k.clamps,
                 k.min_force_series, k.e_effective_clamped);
    }
  });
}

// validate-muthukumar
std::string muthukumar_csv(const std::vector<A::MuthukumarRow>& rows) {
  std::ostringstream s;
  s << "level,period_ratio,model,e,records,diverged,disp_amp,acc_amp\n";
  for (const auto& r : rows) {
    s << fmt::format("{},{},{},{},{},{},{:.5g},{:.5g}\n", r.level, r.period_ratio, r.model, r.e, r.records,
                     r.diverged, r.disp_amp, r.acc_amp);
    fmt::print("{:<9} T1/T2={:.1f} {:<17} e={:.1f} n={:>2} disp_amp={:.3f} acc_amp={:.3f}{}\n", r.level,
               r.period_ratio, r.model, r.e, r.records, r.disp_amp, r.acc_amp,
               r.diverged ? fmt::format(" ({} diverged)", r.diverged) : "");
  }
  return s.str();
}

void print_table_i() {
  fmt::print("level,event,station,our_files,note\n");
  for (const auto& t : A::muthukumar_table_i()) {
    std::string files;
    for (const auto& f : t.files) files += (files.empty() ? "" : " ") + f;
    fmt::print("{},{},{},{},\"{}\"\n", t.level, t.event, t.station, files.empty() ? "-" : files, t.note);
  }
}

void add_validate_muthukumar(CLI::App* acc, const RecordsDir& dir) {
  struct O {
    std::string out = "muthukumar.csv";
    A::MuthukumarOptions mo;
    bool table_i = false;
  };
  auto o = std::make_shared<O>();
  auto* c = acc->add_subcommand("validate-muthukumar", "Muthukumar-DesRoches (2006) parameter study, real records");
  c->add_option("--out", o->out, "CSV")->capture_default_str();
  c->add_option("--T2", o->mo.T2, "flexible system period (s), ASSUMED; T1 = 0.3, 0.5, 0.7 T2")
      ->capture_default_str();
  c->add_option("--kelvin-k", o->mo.kelvin_k, "Kelvin/linear stiffness (N/m); default 25,000 kip/in (ASSUMED)");
  c->add_option("--kelvin-scale", o->mo.kelvin_scale, "multiplies the Kelvin/linear stiffness (sensitivity)")
      ->capture_default_str();
  c->add_option("--records", o->mo.records,
                "all (every record in a PGA band) or matched (the paper's Table I records we hold)")
      ->capture_default_str();
  add_list(c, "--levels", o->mo.levels, "PGA levels to run (low moderate high; default all)");
  add_list(c, "--ratios", o->mo.ratios, "T1/T2 to run (0.3 0.5 0.7; default all)");
  c->add_option("--substeps", o->mo.substeps, "substeps per record step (default: h <= 0.5 ms)");
  c->add_flag("--table-i", o->table_i, "print the paper's Table I against our records (CSV) and exit");
  c->callback([o, dir] {
    if (o->table_i) return print_table_i();
    files::check_output_not_input(o->out, records_read({}, *dir), "--out");  // before any work
    std::vector<std::string> log;
    auto rows = A::muthukumar(*dir, o->mo, &log);
    files::write_text_atomically(o->out, muthukumar_csv(rows));
  });
}

}  // namespace

void add_accuracy(CLI::App& app) {
  auto* acc = app.add_subcommand("accuracy", "accuracy against speed: reference bridge, chart, stability, "
                                             "restitution, validation");
  acc->require_subcommand(1);
  auto dir = std::make_shared<std::string>(A::default_record_dir());
  if (const char* env = std::getenv("POUNDING_RECORDS_DIR"); env && *env) *dir = env;
  acc->add_option("--records-dir", *dir,
                  "directory of the real records (default: $POUNDING_RECORDS_DIR, else ../shared/records/real)")
      ->capture_default_str();
  add_models(acc, dir);
  add_agree(acc, dir);
  add_chart(acc, dir);
  add_stability(acc, dir);
  add_resolution(acc);
  add_restitution(acc);
  add_validate_muthukumar(acc, dir);
}

}  // namespace pounding::cli
