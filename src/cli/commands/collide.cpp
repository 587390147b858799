// `pounding collide`: two free masses meeting at v0 -> effective restitution and the impact's numbers.
// Inputs outside a law's valid range are errors (collide.hpp, check_impact_inputs); "status: ok" means the
// delivered restitution is within --e-tolerance of the target, "off-target" that it is not (with the numbers
// and, in e_law, what the law promises).
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/commands/restitution_options.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/single_impact.hpp"
#include "pounding/physics/velocity_restitution.hpp"
#include "pounding/core/error.hpp"
#include "pounding/core/machine.hpp"
#include "pounding/report/json.hpp"

namespace pounding::cli {

namespace {

// Named outputs in order: `name: text` lines, or one JSON object with the numbers at full precision.
class Outputs {
 public:
  void number(std::string name, double v, std::string_view spec) {
    items_.push_back({std::move(name), fmt::format(fmt::runtime(spec), v), v, 0, Kind::number, {}});
  }
  void integer(std::string name, std::int64_t v) {
    items_.push_back({std::move(name), std::to_string(v), 0.0, v, Kind::integer, {}});
  }
  // text: the JSON value; line: the text format's value when it says more (status)
  void text(std::string name, std::string_view value, std::string line = "") {
    std::string text(value);
    items_.push_back({std::move(name), line.empty() ? text : line, 0.0, 0, Kind::text, text});
  }
  std::string lines() const {
    std::string s;
    for (const Item& i : items_) s += fmt::format("{}: {}\n", i.name, i.line);
    return s;
  }
  std::string json() const {
    report::JsonWriter w;
    w.begin_object();
    for (const Item& i : items_) {
      w.key(i.name);
      if (i.kind == Kind::number) w.value(i.v);
      else if (i.kind == Kind::integer) w.value(i.n);
      else w.value(i.text);
      if (i.kind == Kind::text && i.line != i.text) w.member(i.name + "_note", i.line);
    }
    return w.end_object().str();
  }

 private:
  enum class Kind { number, integer, text };
  struct Item {
    std::string name, line;
    double v;
    std::int64_t n;
    Kind kind;
    std::string text;
  };
  std::vector<Item> items_;
};

struct Opts {
  std::string law = "hertzdamp", damping_law = "lankarani-nikravesh", stepper = "rk4";
  double e = 0.65, v0 = 1.0, m1 = 1.0e6, m2 = 1.0e6, kh = 2.808e10, n = 1.5, tolerance = default_e_tolerance;
  int steps = 20000;
  bool json = false;
  RestitutionOpts rest;  // e(v0) instead of --e (issue 26 §3)
  std::string sweep;     // "lo,hi,n": a CSV of delivered against target e over v0, per damping law
};

// One list of outputs, printed as `name: value` lines (the text format) or as one JSON object (--json); `code` the
// exit code (3 when the kernel's status is not ok).
Outputs collide_outputs(const Opts& o, const ContactModel& cm, Stepper stepper, const ImpactResult& r, double e_target,
                        const RestitutionPromise& promise, const contact::RestitutionCurve* curve, bool kernel_latch,
                        int& code) {
  Outputs out;
  out.text("law", to_string(cm.law));
  if (contact::traits(cm.law).restitution_from_damping) {
    out.text("damping_law", to_string(cm.damping));
    out.number("xibar", hertzdamp_xibar(cm.damping, curve ? e_target : o.e, cm.n), "{:.9g}");
    // the law acts on this multiple of --kh (three-spring: k_eq = 1.5 k, contact/model.hpp damping_laws)
    if (const double f = contact::stiffness_factor(cm); f != 1.0) out.number("stiffness_factor", f, "{:.9g}");
  }
  const double miss = r.e_effective - e_target;
  if (curve) {  // the single impact's latched approach velocity is v0 (mass 2 at rest, gap 0 at t = 0)
    out.text("restitution", curve->describe());
    out.number("restitution_v0", o.v0, "{:.9g}");
    out.number("restitution_e_raw", curve->raw(o.v0), "{:.9g}");
    out.integer("restitution_clamped", curve->clamped(o.v0) ? 1 : 0);
    out.integer("restitution_outside_valid", kernel_latch ? r.restitution_outside : curve->in_range(o.v0) ? 0 : 1);
    out.text("restitution_applied", kernel_latch ? "kernel (e(v0) at the onset latch of central difference)"
                                                 : "before the run (e = e(v0), the single impact's approach speed)");
  }
  out.number("e_target", e_target, "{:.9g}");
  out.number("e_effective", r.e_effective, "{:.9g}");
  out.number("e_miss", miss, "{:+.3g}");
  out.number("e_tolerance", o.tolerance, "{:.9g}");
  out.text("e_law", fmt::format("{}: {}", to_string(promise.kind), promise.note));
  out.number("peak_force_N", r.peak_force, "{:.9g}");
  out.number("peak_penetration_m", r.peak_penetration, "{:.9g}");
  out.number("contact_duration_s", r.duration, "{:.9g}");
  out.number("energy_lost_J", r.energy_lost, "{:.9g}");
  // the basis of each fraction: the whole initial kinetic energy (mass 2 at rest), and the kinetic energy of the
  // pre-impact relative motion, the most an impact can take (momentum is conserved): 1 - e^2 of it is lost
  const double ke_relative = 0.5 * o.m1 * o.m2 / (o.m1 + o.m2) * o.v0 * o.v0;
  out.number("energy_lost_fraction_of_initial_kinetic", r.energy_lost_fraction, "{:.9g}");
  out.number("energy_lost_fraction_of_relative_kinetic", r.energy_lost / ke_relative, "{:.9g}");
  out.integer("tensile_force_clamps", r.clamps);
  out.number("h_omega_contact", r.h_omega_contact, "{:.6g}");
  out.number("h_omega_limit", physics::resolution_limit(stepper, false, cm.law), "{:.6g}");
  if (r.status != LaneStatus::ok) {
    out.text("status", std::string(to_string(r.status)));
    code = 3;
  } else if (!(std::abs(miss) <= o.tolerance)) {
    out.text("status", "off-target",
             fmt::format("off-target (e_effective {:.4g} misses e_target {:.4g} by {:+.3g}, more than the tolerance "
                         "{:.3g})",
                         r.e_effective, e_target, miss, o.tolerance));
  } else {
    out.text("status", "ok");
  }
  return out;
}

// --sweep-v0 lo,hi,n: every input checked first, then one impact per (damping law, v0); a CSV on stdout.
void run_sweep(const Opts& o, const ContactModel& base, Stepper stepper, const contact::RestitutionCurve* curve,
               bool e_given) {
  if (o.json) throw InputError("--json with --sweep-v0", "--json", "drop --json: the sweep prints a CSV");
  const std::vector<double> s = parse_number_list(o.sweep, "--sweep-v0", "number", "give lo,hi,n, e.g. 0.1,3.13,20");
  if (s.size() != 3 || !(s[0] > 0.0 && s[0] < s[1]) || !(s[2] >= 2 && s[2] <= 200 && s[2] == std::floor(s[2])))
    throw InputError(fmt::format("'{}' is not lo,hi,n with 0 < lo < hi and n an integer in [2, 200]",
                                 escaped_excerpt(o.sweep)),
                     "--sweep-v0", "give e.g. 0.1,3.13,20");
  const int n = static_cast<int>(s[2]);
  std::vector<double> v0s;
  for (int i = 0; i < n; ++i) v0s.push_back(s[0] + (s[1] - s[0]) * i / (n - 1));
  std::vector<ContactModel> models;
  if (contact::traits(base.law).restitution_from_damping) {
    for (const DampingLawEntry& d : damping_laws) models.push_back(base), models.back().damping = d.id;
  } else {
    models.push_back(base);
  }
  auto e_at = [&](double v0) { return curve ? (*curve)(v0) : o.e; };
  for (const ContactModel& cm : models)
    for (double v0 : v0s) {
      try {
        check_impact_inputs(cm, e_at(v0), curve || e_given, v0, o.m1, o.m2, o.kh);
      } catch (const InputError& err) {
        throw InputError(fmt::format("at v0 = {:g} m/s: {}", v0, err.what_part()),
                         err.where() == "--v0" ? "--sweep-v0" : err.where(), err.fix());
      }
    }
  fmt::print("law,damping_law,v0_mps,e_target,e_raw,e_effective,e_miss,in_valid_range,clamped,status,valid_min_mps,"
             "valid_max_mps\n");
  const double vlo = curve ? curve->vmin / curve->per_mps : NAN, vhi = curve ? curve->vmax / curve->per_mps : NAN;
  for (const ContactModel& cm : models)
    for (double v0 : v0s) {
      const double e = e_at(v0);
      const ImpactResult r = single_impact(cm, stepper, e, v0, o.m1, o.m2, o.kh, o.steps);
      const bool damped = contact::traits(cm.law).restitution_from_damping;
      fmt::print("{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.3g},{},{},{},{:.9g},{:.9g}\n", to_string(cm.law),
                 damped ? std::string(to_string(cm.damping)) : std::string("-"), v0, e, curve ? curve->raw(v0) : e,
                 r.e_effective, r.e_effective - e, curve && !curve->in_range(v0) ? 0 : 1,
                 curve && curve->clamped(v0) ? 1 : 0, to_string(r.status), vlo, vhi);
    }
}

}  // namespace

void add_collide(CLI::App& app) {
  auto o = std::make_shared<Opts>();
  auto* c = app.add_subcommand("collide", "two free masses meeting at v0: effective restitution, peak force, "
                                          "penetration, duration, energy lost");
  c->add_option("--law", o->law, std::string("contact law: ") + std::string(contact_law_names))->capture_default_str();
  c->add_option("--damping-law", o->damping_law, std::string("Hertzdamp xibar law: ") + std::string(damping_law_names))
      ->capture_default_str();
  c->add_option("--e", o->e, "target coefficient of restitution, (0, 1]")->capture_default_str();
  c->add_option("--v0", o->v0, "approach velocity (m/s)")->capture_default_str();
  c->add_option("--m1", o->m1, "mass 1 (kg)")->capture_default_str();
  c->add_option("--m2", o->m2, "mass 2 (kg)")->capture_default_str();
  c->add_option("--kh", o->kh, "contact stiffness (N/m^n, or N/m for linear/Kelvin)")->capture_default_str();
  c->add_option("--n", o->n, "Hertz exponent")->capture_default_str();
  c->add_option("--stepper", o->stepper, std::string("integrator: ") + std::string(stepper_names))
      ->capture_default_str();
  c->add_option("--steps", o->steps, "integration steps per estimated contact duration")->capture_default_str();
  c->add_option("--e-tolerance", o->tolerance, "status is ok when |e_effective - e_target| <= this")
      ->capture_default_str();
  c->add_flag("--json", o->json, "print the outputs as one JSON object (numbers at full precision, the same names; "
                                 "status_note carries the off-target explanation)");
  c->footer("status: ok (the delivered restitution is within --e-tolerance of the target), off-target (it is not: "
            "a property of laws that do not deliver their nominal e, e.g. lankarani-nikravesh, see e_law; exit code 0), "
            "or the kernel's status (diverged, non-finite: exit code 3). Elastic laws (linear, hertz) target e = 1.\n"
            "energy_lost_fraction_of_initial_kinetic: energy_lost_J / (1/2 m1 v0^2), mass 2 at rest; "
            "energy_lost_fraction_of_relative_kinetic: energy_lost_J / (1/2 m1 m2 / (m1 + m2) v0^2), the kinetic energy "
            "of the pre-impact relative motion (= 1 - e_effective^2).");
  o->rest.add(c);
  c->add_option("--sweep-v0", o->sweep, "lo,hi,n: one impact at each of n approach speeds from lo to hi (m/s); "
                                        "prints a CSV of the target e(v0) and the delivered e per damping law "
                                        "(every damping law for hertzdamp; tools/plot_restitution_sweep.py charts it)");
  c->callback([o, c] {
    ContactModel cm;
    cm.law = as_option("--law", [&] { return parse_contact_law(o->law); });
    cm.damping = as_option("--damping-law", [&] { return parse_damping_law(o->damping_law); });
    require_range(o->n, 1.0, 3.0, "--n", "[1, 3]");
    cm.n = o->n;
    require_range(o->tolerance, 0.0, 1.0, "--e-tolerance", "[0, 1]");
    const std::optional<contact::RestitutionCurve> curve = o->rest.get(c);
    if (curve && c->count("--e") > 0)
      throw InputError("--e and a restitution curve both given", "--e", "drop --e: the curve gives e(v0)");
    if (curve && restitution_promise(cm).kind == RestitutionKind::elastic)
      throw InputError(fmt::format("a restitution curve with the elastic {} law (it delivers e = 1)", to_string(cm.law)),
                       "--law", "choose a damped law (hertzdamp, kelvin, jankowski, stereomechanical)");
    if (o->steps < 100) throw InputError(fmt::format("--steps = {} is too few", o->steps), "--steps", "give >= 100");
    // the run covers 3 contact durations at --steps per duration: one schedule row per step (physics::make_schedule)
    // -- 2e9 ended in std::bad_alloc (issue 44 item 8)
    if (const double need = 8.0 * (3.0 * o->steps + 1.0), avail = available_memory_bytes();
        std::isfinite(avail) && need > avail)
      throw InputError(fmt::format("--steps = {} needs {} for the run's {} steps, more than the {} of memory available "
                                   "on this machine (MemAvailable)",
                                   o->steps, human_bytes(need), 3.0 * o->steps, human_bytes(avail)),
                       "--steps", fmt::format("give --steps <= {:.0f} (the default 20000 resolves every law)",
                                              std::floor(avail / 24.0)));
    const Stepper stepper = as_option("--stepper", [&] { return parse_stepper(o->stepper); });
    if (!o->sweep.empty()) {
      run_sweep(*o, cm, stepper, curve ? &*curve : nullptr, c->count("--e") > 0);
      return;
    }
    const double e = curve ? (*curve)(o->v0) : o->e;
    const bool e_given = curve || c->count("--e") > 0;
    check_impact_inputs(cm, e, e_given, o->v0, o->m1, o->m2, o->kh);
    const RestitutionPromise promise = restitution_promise(cm);
    // an elastic law is asked for nothing: its target is the e = 1 it delivers
    const double e_target = promise.kind == RestitutionKind::elastic ? 1.0 : e;
    // central difference + hertzdamp: e(v0) through the kernel's onset latch; otherwise e(v0) set before the run
    const bool kernel_latch = curve && stepper == Stepper::central_difference && cm.law == ContactLaw::hertzdamp;
    std::optional<physics::HertzdampRestitution> hook;
    if (kernel_latch) hook.emplace(*curve, cm);
    ImpactResult r = single_impact(cm, stepper, e, o->v0, o->m1, o->m2, o->kh, o->steps, hook ? &hook->hook : nullptr);
    int code = 0;
    const Outputs out =
        collide_outputs(*o, cm, stepper, r, e_target, promise, curve ? &*curve : nullptr, kernel_latch, code);
    fmt::print("{}", o->json ? out.json() : out.lines());
    if (code != 0) throw ExitRequest{code};
  });
}

}  // namespace pounding::cli
