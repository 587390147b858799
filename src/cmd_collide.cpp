// `pounding collide`: two free masses meeting at v0 -> effective restitution and the impact's numbers.
#include <cmath>
#include <memory>
#include <numbers>

#include <fmt/format.h>

#include "pounding/cli.hpp"
#include "pounding/collide.hpp"
#include "pounding/error.hpp"

namespace pounding::cli {

void add_collide(CLI::App& app) {
  struct Opts {
    std::string law = "hertzdamp", damping_law = "lankarani-nikravesh", stepper = "rk4";
    double e = 0.65, v0 = 1.0, m1 = 1.0e6, m2 = 1.0e6, kh = 2.808e10, n = 1.5;
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
  c->callback([o] {
    ContactModel cm;
    cm.law = parse_contact_law(o->law);
    cm.damping = parse_damping_law(o->damping_law);
    cm.n = o->n;
    require_range(o->e, std::nextafter(0.0, 1.0), 1.0, "--e", "(0, 1]");
    require_positive(o->v0, "--v0");
    require_positive(o->m1, "--m1");
    require_positive(o->m2, "--m2");
    require_positive(o->kh, "--kh");
    require_range(o->n, 1.0, 3.0, "--n", "[1, 3]");
    if (o->steps < 100) throw InputError(fmt::format("--steps = {} is too few", o->steps), "--steps", "give >= 100");
    ImpactResult r = single_impact(cm, parse_stepper(o->stepper), o->e, o->v0, o->m1, o->m2, o->kh, o->steps);
    fmt::print("law: {}\n", to_string(cm.law));
    if (cm.law == ContactLaw::hertzdamp) {
      fmt::print("damping_law: {}\n", to_string(cm.damping));
      fmt::print("xibar: {:.9g}\n", hertzdamp_xibar(cm.damping, o->e, cm.n));
    }
    fmt::print("e_target: {:.9g}\n", o->e);
    fmt::print("e_effective: {:.9g}\n", r.e_effective);
    fmt::print("peak_force_N: {:.9g}\n", r.peak_force);
    fmt::print("peak_penetration_m: {:.9g}\n", r.peak_penetration);
    fmt::print("contact_duration_s: {:.9g}\n", r.duration);
    fmt::print("energy_lost_J: {:.9g}\n", r.energy_lost);
    fmt::print("energy_lost_fraction: {:.9g}\n", r.energy_lost_fraction);
    fmt::print("tensile_force_clamps: {}\n", r.clamps);
    fmt::print("status: {}\n", to_string(r.status));
    if (r.status != LaneStatus::ok) exit_code() = 3;
  });
}

}  // namespace pounding::cli
