// Names of the contact and damping laws (contact/model.hpp): parsing with errors that list the allowed names.
// Here rather than in the contact layer, which formats no text (tests/arch/check_layers.py).
#include <fmt/format.h>

#include "pounding/contact/model.hpp"
#include "pounding/contact/registry.hpp"
#include "pounding/core/error.hpp"

namespace pounding {

namespace {
// The name list for help texts spells the table, in its order, joined by ", ".
template <class E, std::size_t N>
constexpr bool spells(const EnumName<E> (&table)[N], std::string_view list) {
  std::size_t at = 0;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) {
      if (list.substr(at, 2) != ", ") return false;
      at += 2;
    }
    if (list.substr(at, table[i].name.size()) != table[i].name) return false;
    at += table[i].name.size();
  }
  return at == list.size();
}
// One list of law names: the enum's table, the registry's law types and the help text agree.
constexpr bool registry_matches_table() {
  constexpr auto names = contact::names_of(contact::Laws{});
  if (names.size() != std::size(contact_law_table)) return false;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] != contact_law_table[i].name || contact_law_table[i].value != static_cast<ContactLaw>(i)) return false;
  return true;
}
static_assert(spells(contact_law_table, contact_law_names) && spells(damping_law_table, damping_law_names));
static_assert(registry_matches_table());
}  // namespace

ContactLaw parse_contact_law(std::string_view name) {
  if (const auto law = parse_enum(contact_law_table, name)) return *law;
  throw InputError(fmt::format("unknown contact law '{}'", name), "contact law",
                   fmt::format("use one of: {}", enum_name_list(contact_law_table)));
}

DampingLaw parse_damping_law(std::string_view name) {
  if (const auto law = parse_enum(damping_law_table, name)) return *law;
  throw InputError(fmt::format("unknown damping law '{}'", name), "damping law",
                   fmt::format("use one of: {}", enum_name_list(damping_law_table)));
}

}  // namespace pounding
