// `pounding collide`: two free masses meeting at v0 -> effective restitution and the impact's numbers.
// Inputs outside a law's valid range are errors (collide.hpp, check_impact_inputs); "status: ok" means the
// delivered restitution is within --e-tolerance of the target, "off-target" that it is not (with the numbers
// and, in e_law, what the law promises).
#include <cmath>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "pounding/physics/resolution.hpp"
#include "pounding/physics/single_impact.hpp"
#include "pounding/core/error.hpp"

namespace pounding::cli {

void add_collide(CLI::App& app) {
  struct Opts {
    std::string law = "hertzdamp", damping_law = "lankarani-nikravesh", stepper = "rk4";
    double e = 0.65, v0 = 1.0, m1 = 1.0e6, m2 = 1.0e6, kh = 2.808e10, n = 1.5, tolerance = default_e_tolerance;
    int steps = 20000;
  };
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
  c->footer("status: ok (the delivered restitution is within --e-tolerance of the target), off-target (it is not: "
            "a property of laws that do not deliver their nominal e, e.g. lankarani-nikravesh, see e_law; exit code 0), "
            "or the kernel's status (diverged, non-finite: exit code 3). Elastic laws (linear, hertz) target e = 1.\n"
            "energy_lost_fraction_of_initial_kinetic: energy_lost_J / (1/2 m1 v0^2), mass 2 at rest; "
            "energy_lost_fraction_of_relative_kinetic: energy_lost_J / (1/2 m1 m2 / (m1 + m2) v0^2), the kinetic energy "
            "of the pre-impact relative motion (= 1 - e_effective^2).");
  c->callback([o, c] {
    ContactModel cm;
    cm.law = as_option("--law", [&] { return parse_contact_law(o->law); });
    cm.damping = as_option("--damping-law", [&] { return parse_damping_law(o->damping_law); });
    require_range(o->n, 1.0, 3.0, "--n", "[1, 3]");
    cm.n = o->n;
    require_range(o->tolerance, 0.0, 1.0, "--e-tolerance", "[0, 1]");
    const bool e_given = c->count("--e") > 0;
    check_impact_inputs(cm, o->e, e_given, o->v0, o->m1, o->m2, o->kh);
    if (o->steps < 100) throw InputError(fmt::format("--steps = {} is too few", o->steps), "--steps", "give >= 100");
    const Stepper stepper = as_option("--stepper", [&] { return parse_stepper(o->stepper); });
    const RestitutionPromise promise = restitution_promise(cm);
    // an elastic law is asked for nothing: its target is the e = 1 it delivers
    const double e_target = promise.kind == RestitutionKind::elastic ? 1.0 : o->e;
    ImpactResult r = single_impact(cm, stepper, o->e, o->v0, o->m1, o->m2, o->kh, o->steps);
    fmt::print("law: {}\n", to_string(cm.law));
    if (contact::traits(cm.law).restitution_from_damping) {
      fmt::print("damping_law: {}\n", to_string(cm.damping));
      fmt::print("xibar: {:.9g}\n", hertzdamp_xibar(cm.damping, o->e, cm.n));
    }
    const double miss = r.e_effective - e_target;
    fmt::print("e_target: {:.9g}\n", e_target);
    fmt::print("e_effective: {:.9g}\n", r.e_effective);
    fmt::print("e_miss: {:+.3g}\n", miss);
    fmt::print("e_tolerance: {:.9g}\n", o->tolerance);
    fmt::print("e_law: {}: {}\n", to_string(promise.kind), promise.note);
    fmt::print("peak_force_N: {:.9g}\n", r.peak_force);
    fmt::print("peak_penetration_m: {:.9g}\n", r.peak_penetration);
    fmt::print("contact_duration_s: {:.9g}\n", r.duration);
    fmt::print("energy_lost_J: {:.9g}\n", r.energy_lost);
    // the basis of each fraction: the whole initial kinetic energy (mass 2 at rest), and the kinetic energy of the
    // pre-impact relative motion, the most an impact can take (momentum is conserved): 1 - e^2 of it is lost
    const double ke_relative = 0.5 * o->m1 * o->m2 / (o->m1 + o->m2) * o->v0 * o->v0;
    fmt::print("energy_lost_fraction_of_initial_kinetic: {:.9g}\n", r.energy_lost_fraction);
    fmt::print("energy_lost_fraction_of_relative_kinetic: {:.9g}\n", r.energy_lost / ke_relative);
    fmt::print("tensile_force_clamps: {}\n", r.clamps);
    fmt::print("h_omega_contact: {:.6g}\n", r.h_omega_contact);
    fmt::print("h_omega_limit: {:.6g}\n", physics::resolution_limit(stepper, false, cm.law));
    if (r.status != LaneStatus::ok) {
      fmt::print("status: {}\n", to_string(r.status));
      throw ExitRequest{3};
    } else if (!(std::abs(miss) <= o->tolerance)) {
      fmt::print("status: off-target (e_effective {:.4g} misses e_target {:.4g} by {:+.3g}, more than the tolerance "
                 "{:.3g})\n",
                 r.e_effective, e_target, miss, o->tolerance);
    } else {
      fmt::print("status: ok\n");
    }
  });
}

}  // namespace pounding::cli
