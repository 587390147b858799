#pragma once
// Contact laws between structure 1 (left) and structure 2 (right).
// delta = u1 - u2 - gap is the penetration, ddelta = v1 - v2 its rate; every force law is non-tensile.
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <utility>
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

// What one free impact with a law delivers against the restitution e it is given (`pounding collide`).
namespace contact {
enum class RestitutionKind : std::uint8_t { elastic, exact, approximate, saturating };
inline constexpr EnumName<RestitutionKind> restitution_kind_table[] = {{RestitutionKind::elastic, "elastic"},
                                                                       {RestitutionKind::exact, "exact"},
                                                                       {RestitutionKind::approximate, "approximate"},
                                                                       {RestitutionKind::saturating, "saturating"}};
constexpr const auto& enum_names(RestitutionKind) { return restitution_kind_table; }
}  // namespace contact

// How Hertzdamp's xibar follows from e: one enumerator per entry of damping_laws below, in its order.
enum class DampingLaw : std::uint8_t {
  lankarani_nikravesh,
  hunt_crossley,
  flores,
  hu_guo,
  gonthier,
  calibrated,
  ye,
  three_spring,
};
// Each law's xibar(e, n), out of line (src/contact/model.cpp) so that every caller gets the bits results carry.
namespace xibar {
double lankarani_nikravesh(double e, double n);  // 3 (1 - e^2) / 4
double hunt_crossley(double e, double n);        // 3 (1 - e) / 2
double flores(double e, double n);               // 8 (1 - e) / (5 e)
double hu_guo(double e, double n);               // 3 (1 - e) / (2 e)
double gonthier(double e, double n);             // (1 - e^2) / e
double calibrated(double e, double n);           // calibrated_xibar(e, n)
}  // namespace xibar

// THE list of Hertzdamp damping laws: {name, xibar(e, n), stiffness factor, what one free impact delivers}. The
// enum's names, parse errors, help texts, the restitution promise of `pounding collide` and the restitution
// table iterate it. F = kc delta^n (1 + xibar ddelta / v0) with kc = stiffness_factor x the stiffness given, so
// zeta = kc xibar / v0 is the papers' damping coefficient c = zeta delta^n (zeta v0 / k = factor x xibar).
struct DampingLawEntry {
  DampingLaw id;
  std::string_view name;
  double (*xibar)(double e, double n);
  double stiffness_factor;        // the contact stiffness the law acts on, per unit of the stiffness given
  contact::RestitutionKind delivers;
  std::string_view formula;       // xibar (and the stiffness it acts on) as text
  std::string_view at_065;        // saturating laws: e delivered when 0.65 is asked (docs/accuracy.md)
};
inline constexpr DampingLawEntry damping_laws[] = {
    {DampingLaw::lankarani_nikravesh, "lankarani-nikravesh", xibar::lankarani_nikravesh, 1.0,
     contact::RestitutionKind::saturating, "3 (1 - e^2) / 4", "0.775"},  // the papers' choice (muthukumar eq. 10)
    {DampingLaw::hunt_crossley, "hunt-crossley", xibar::hunt_crossley, 1.0, contact::RestitutionKind::saturating,
     "3 (1 - e) / 2", "0.739"},
    {DampingLaw::flores, "flores", xibar::flores, 1.0, contact::RestitutionKind::approximate, "8 (1 - e) / (5 e)", ""},
    {DampingLaw::hu_guo, "hu-guo", xibar::hu_guo, 1.0, contact::RestitutionKind::approximate, "3 (1 - e) / (2 e)", ""},
    {DampingLaw::gonthier, "gonthier", xibar::gonthier, 1.0, contact::RestitutionKind::approximate, "(1 - e^2) / e", ""},
    // solved so that one free impact returns exactly e
    {DampingLaw::calibrated, "calibrated", xibar::calibrated, 1.0, contact::RestitutionKind::exact,
     "solved for e", ""},
    // the link-element paper's presets (rc-buildings-base-isolation-link-elements.txt section 2-3):
    // Ye et al.'s zeta = 3 k (1 - e) / (2 e v) (eq. 9), the Hu-Guo form on the stiffness given
    {DampingLaw::ye, "ye", xibar::hu_guo, 1.0, contact::RestitutionKind::approximate, "3 (1 - e) / (2 e)", ""},
    // the three-spring link: k_eq = 1.5 k (eq. 12), zeta = 12 (1 - e) k / (5 e v) (eq. 20) = Flores on k_eq
    {DampingLaw::three_spring, "three-spring", xibar::flores, 1.5, contact::RestitutionKind::approximate,
     "8 (1 - e) / (5 e) on k_eq = 1.5 k", ""},
};
inline constexpr const DampingLawEntry& damping_law(DampingLaw law) {
  return damping_laws[static_cast<std::size_t>(law)];
}
namespace detail {
template <std::size_t... I> constexpr bool damping_laws_in_enum_order(std::index_sequence<I...>) {
  return ((damping_laws[I].id == static_cast<DampingLaw>(I)) && ...);
}
template <class Seq> struct DampingLawTable;
template <std::size_t... I> struct DampingLawTable<std::index_sequence<I...>> {
  static constexpr EnumName<DampingLaw> table[] = {{damping_laws[I].id, damping_laws[I].name}...};
};
constexpr auto join_damping_law_names() {
  constexpr std::size_t N = [] {
    std::size_t n = 0;
    for (const auto& d : damping_laws) n += d.name.size() + 2;
    return n - 2;
  }();
  std::array<char, N> out{};
  std::size_t k = 0;
  for (const auto& d : damping_laws) {
    if (k > 0) out[k++] = ',', out[k++] = ' ';
    for (char c : d.name) out[k++] = c;
  }
  return out;
}
inline constexpr auto damping_law_names_text = join_damping_law_names();
}  // namespace detail
static_assert(detail::damping_laws_in_enum_order(std::make_index_sequence<std::size(damping_laws)>{}) &&
                  static_cast<std::size_t>(DampingLaw::three_spring) + 1 == std::size(damping_laws),
              "damping_laws has one entry per DampingLaw, in the enum's order");
inline constexpr const auto& damping_law_table =
    detail::DampingLawTable<std::make_index_sequence<std::size(damping_laws)>>::table;
constexpr const auto& enum_names(DampingLaw) { return damping_law_table; }
DampingLaw parse_damping_law(std::string_view name);
inline constexpr std::string_view damping_law_names{detail::damping_law_names_text.data(),
                                                    detail::damping_law_names_text.size()};

struct ContactModel {
  ContactLaw law = ContactLaw::hertzdamp;
  DampingLaw damping = DampingLaw::lankarani_nikravesh;
  double n = 1.5;        // Hertz exponent
  double v0_min = 1e-3;  // floor (m/s) on the latched approach velocity of a grazing contact
};

// xibar of Hertzdamp for restitution e and exponent n (damping_law(law).xibar).
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
