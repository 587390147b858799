#pragma once
// Contact laws between structure 1 (left) and structure 2 (right).
// delta = u1 - u2 - gap is the penetration, ddelta = v1 - v2 its rate; every force law is non-tensile.
#include <cstdint>
#include <string>
#include <string_view>

#include "pounding/core/enum_names.hpp"

namespace pounding {

enum class ContactLaw : std::uint8_t {
  none,              // no contact element (the uncoupled pair)
  linear,            // F = kc delta                          (muthukumar eq. 3)
  kelvin,            // F = kc delta + ck ddelta              (impact-stiffness paper eqs 2-3)
  hertz,             // F = kc delta^n                        (muthukumar eq. 6)
  hertzdamp,         // F = kc delta^n (1 + xibar ddelta/v0)  (muthukumar eq. 10, generalised)
  jankowski,         // F = kc delta^1.5 + c(delta) ddelta, damper only while approaching (rc-buildings eqs 4-5)
  stereomechanical,  // instantaneous momentum exchange with restitution e (muthukumar eq. 2)
};
// The names, to_string(ContactLaw) and contact_law_names come from contact::Laws (contact/registry.hpp), which
// checks that enumerator i names the list's i-th law: a new law adds its enumerator here, in the list's order.
ContactLaw parse_contact_law(std::string_view name);  // InputError listing the names (src/physics/names.cpp)

// How Hertzdamp's xibar follows from e.
enum class DampingLaw : std::uint8_t {
  lankarani_nikravesh,  // 3 (1 - e^2) / 4     (the papers' choice)
  hunt_crossley,        // 3 (1 - e) / 2
  flores,               // 8 (1 - e) / (5 e)
  hu_guo,               // 3 (1 - e) / (2 e)
  gonthier,             // (1 - e^2) / e
  calibrated,           // solved so that one free impact returns exactly e
};
inline constexpr EnumName<DampingLaw> damping_law_table[] = {
    {DampingLaw::lankarani_nikravesh, "lankarani-nikravesh"},
    {DampingLaw::hunt_crossley, "hunt-crossley"},
    {DampingLaw::flores, "flores"},
    {DampingLaw::hu_guo, "hu-guo"},
    {DampingLaw::gonthier, "gonthier"},
    {DampingLaw::calibrated, "calibrated"},
};
constexpr const auto& enum_names(DampingLaw) { return damping_law_table; }
DampingLaw parse_damping_law(std::string_view name);
inline constexpr std::string_view damping_law_names =
    "lankarani-nikravesh, hunt-crossley, flores, hu-guo, gonthier, calibrated";

struct ContactModel {
  ContactLaw law = ContactLaw::hertzdamp;
  DampingLaw damping = DampingLaw::lankarani_nikravesh;
  double n = 1.5;        // Hertz exponent
  double v0_min = 1e-3;  // floor (m/s) on the latched approach velocity of a grazing contact
};

// xibar of Hertzdamp for restitution e and exponent n.
double hertzdamp_xibar(DampingLaw law, double e, double n = 1.5);
// Solves x'' = -x^n (1 + xi x'), x(0) = 0, x'(0) = 1 (the scale-free single impact) for the xi whose
// rebound speed is e. A pure function, not cached: run_batch solves each distinct e once per call
// (physics::DampingTable). |e_achieved - e| < 1e-9.
double calibrated_xibar(double e, double n = 1.5);
// Rebound speed ratio of the scale-free Hertzdamp impact for a given xi (the function calibrated_xibar inverts).
double hertzdamp_restitution(double xibar, double n = 1.5);

// Kelvin damping ratio from e: xi = -ln e / sqrt(pi^2 + ln^2 e) (impact-stiffness paper eq. 3);
// ck = 2 xi sqrt(kc m1 m2 / (m1 + m2)) (eq. 2).
double kelvin_damping_ratio(double e);
// Jankowski's damping ratio zeta = 9 sqrt(5)/2 (1 - e^2) / (e (e (9 pi - 16) + 16)) (rc-buildings eq. 5).
double jankowski_zeta(double e);

// Hertz stiffness of two equivalent concrete spheres (muthukumar eqs 11-13):
// R_i = (3 m_i / (4 pi rho))^(1/3), h = (1 - nu^2)/E, kh = 4/(3 (h1 + h2)) sqrt(R1 R2 / (R1 + R2)).
double hertz_stiffness_spheres(double m1, double m2, double density, double youngs_modulus, double poisson);

// Hertz theory for a perfectly elastic impact (e = 1) of effective mass meff at speed v0:
// peak penetration (5 meff v0^2 / (4 kh))^(2/5) and contact duration 2 (delta_max / v0) B(2/5, 1/2) / (5/2)
// = 2.9432 delta_max / v0 (n = 3/2).
double hertz_peak_penetration(double meff, double v0, double kh);
double hertz_contact_duration(double meff, double v0, double kh);

}  // namespace pounding
