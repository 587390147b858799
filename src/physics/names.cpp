// Names of the contact and damping laws (contact/model.hpp): parsing with errors that list the allowed names.
// Here rather than in the contact layer, which formats no text (tests/arch/check_layers.py).
#include <utility>

#include <fmt/format.h>

#include "pounding/contact/model.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

namespace {
constexpr std::pair<ContactLaw, std::string_view> contact_names[] = {
    {ContactLaw::none, "none"},           {ContactLaw::linear, "linear"},
    {ContactLaw::kelvin, "kelvin"},       {ContactLaw::hertz, "hertz"},
    {ContactLaw::hertzdamp, "hertzdamp"}, {ContactLaw::jankowski, "jankowski"},
    {ContactLaw::stereomechanical, "stereomechanical"},
};
constexpr std::pair<DampingLaw, std::string_view> damping_names[] = {
    {DampingLaw::lankarani_nikravesh, "lankarani-nikravesh"},
    {DampingLaw::hunt_crossley, "hunt-crossley"},
    {DampingLaw::flores, "flores"},
    {DampingLaw::hu_guo, "hu-guo"},
    {DampingLaw::gonthier, "gonthier"},
    {DampingLaw::calibrated, "calibrated"},
};
}  // namespace

ContactLaw parse_contact_law(std::string_view name) {
  for (auto& [law, s] : contact_names)
    if (s == name) return law;
  throw InputError(fmt::format("unknown contact law '{}'", name), "contact law",
                   fmt::format("use one of: {}", contact_law_names));
}
std::string_view to_string(ContactLaw law) {
  for (auto& [l, s] : contact_names)
    if (l == law) return s;
  return "?";
}
DampingLaw parse_damping_law(std::string_view name) {
  for (auto& [law, s] : damping_names)
    if (s == name) return law;
  throw InputError(fmt::format("unknown damping law '{}'", name), "damping law",
                   fmt::format("use one of: {}", damping_law_names));
}
std::string_view to_string(DampingLaw law) {
  for (auto& [l, s] : damping_names)
    if (l == law) return s;
  return "?";
}

}  // namespace pounding
