#pragma once
// The registered contact laws, in the order of the ContactLaw enum. Names, parse errors, help lists, traits,
// resolution limits and the run-time dispatch (ContactLaw -> law type) come from this list; a new law is one
// header, one entry here and its enumerator in ContactLaw (checked below).
#include <array>
#include <iterator>
#include <string>
#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>

#include "pounding/contact/laws/hertz.hpp"
#include "pounding/contact/laws/hertzdamp.hpp"
#include "pounding/contact/laws/jankowski.hpp"
#include "pounding/contact/laws/kelvin.hpp"
#include "pounding/contact/laws/linear.hpp"
#include "pounding/contact/laws/none.hpp"
#include "pounding/contact/laws/stereomechanical.hpp"
#include "pounding/core/type_list.hpp"

namespace pounding {

namespace contact {

// THE list of contact laws. The ContactLaw enum (contact/model.hpp), the law names and their parse errors and
// help texts, the traits and resolution limits by ContactLaw, and every loop over laws (digests, benchmarks,
// the restitution and resolution tables) derive from it; the checks below refuse a list and an enum that
// disagree, and a law that lacks a required trait.
using Laws = TypeList<None, Linear, Kelvin, Hertz, Hertzdamp, Jankowski, Stereomechanical>;

template <class... Ls> constexpr bool all_declare_resolution(TypeList<Ls...>) { return (DeclaresResolutionLimits<Ls> && ...); }
static_assert(all_declare_resolution(Laws{}),
              "a registered contact law must declare its resolution limits: static constexpr ResolutionLimits "
              "resolution{.central_difference = .., .newmark = .., .rk4 = .., .rk4_located = .., .nigam_jennings = ..} "
              "measured by `pounding accuracy resolution --laws <law>` (contact/law.hpp; physics/resolution.hpp)");
template <class... Ls> constexpr bool all_laws(TypeList<Ls...>) { return (Law<Ls> && ...); }
static_assert(all_laws(Laws{}), "every registered law satisfies contact::Law (contact/law.hpp)");

template <class... Ls> constexpr auto names_of(TypeList<Ls...>) {
  return std::array<std::string_view, sizeof...(Ls)>{Ls::name...};
}
inline constexpr auto law_names = names_of(Laws{});
template <class... Ls> constexpr auto traits_of(TypeList<Ls...>) {
  return std::array<LawTraits, sizeof...(Ls)>{Ls::traits...};
}
inline constexpr auto law_traits = traits_of(Laws{});
inline constexpr const LawTraits& traits(ContactLaw id) { return law_traits[static_cast<std::size_t>(id)]; }
template <class... Ls> constexpr auto resolutions_of(TypeList<Ls...>) {
  return std::array<ResolutionLimits, sizeof...(Ls)>{Ls::resolution...};
}
inline constexpr auto law_resolution = resolutions_of(Laws{});
// Every registered law's ContactLaw, in the list's order: for loops over all laws (digests, benchmarks, tests).
template <std::size_t... I> constexpr auto ids_of(std::index_sequence<I...>) {
  return std::array<ContactLaw, sizeof...(I)>{static_cast<ContactLaw>(I)...};
}
inline constexpr auto law_ids = ids_of(std::make_index_sequence<Laws::size>{});
// The contact stiffness the kernel uses per unit of the stiffness given (PairParams::kc): the damping law's
// stiffness_factor for a law whose restitution follows from it (Hertzdamp: 1.5 for three-spring), else 1.
inline double stiffness_factor(const ContactModel& cm) {
  return traits(cm.law).restitution_from_damping ? damping_law(cm.damping).stiffness_factor : 1.0;
}
// The names of the registered laws whose traits satisfy `keep`, joined by ", " (for help texts and errors).
template <class Pred> std::string law_names_where(Pred keep) {
  std::string out;
  for (std::size_t i = 0; i < Laws::size; ++i)
    if (keep(law_traits[i])) out += (out.empty() ? "" : ", ") + std::string(law_names[i]);
  return out;
}
inline constexpr const ResolutionLimits& resolution(ContactLaw id) {
  return law_resolution[static_cast<std::size_t>(id)];
}

namespace detail {
// The enumerator's identifier as the compiler spells the template argument ("pounding::ContactLaw::kelvin" ->
// "kelvin"); "" when the value names no enumerator (GCC and Clang print "(pounding::ContactLaw)7").
template <auto V> consteval std::string_view enumerator_name() {
  const std::string_view f = __PRETTY_FUNCTION__;
  const std::size_t at = f.find("V = ") + 4;
  const std::string_view v = f.substr(at, f.find_first_of(";]", at) - at);
  if (v.empty() || v.front() == '(') return {};
  return v.substr(v.rfind(':') + 1);
}
// A law's name read as an identifier: '-' spelt '_' ("approach-dashpot" -> approach_dashpot).
consteval bool names_enumerator(std::string_view law, std::string_view id) {
  if (law.size() != id.size()) return false;
  for (std::size_t i = 0; i < law.size(); ++i)
    if ((law[i] == '-' ? '_' : law[i]) != id[i]) return false;
  return true;
}
template <std::size_t... I> consteval bool enum_follows_laws(std::index_sequence<I...>) {
  return (names_enumerator(law_names[I], enumerator_name<static_cast<ContactLaw>(I)>()) && ...) &&
         enumerator_name<static_cast<ContactLaw>(sizeof...(I))>().empty();
}
}  // namespace detail
static_assert(detail::enumerator_name<ContactLaw::hertzdamp>() == "hertzdamp" &&
                  detail::enumerator_name<static_cast<ContactLaw>(200)>().empty(),
              "this compiler spells enumerators in __PRETTY_FUNCTION__ as GCC and Clang do");
static_assert(detail::enum_follows_laws(std::make_index_sequence<Laws::size>{}),
              "ContactLaw (contact/model.hpp) must have one enumerator per entry of contact::Laws, in the same "
              "order, each named as the law (name \"a-b\" -> enumerator a_b)");

// f.template operator()<Law>() for the law registered as `id`.
template <class F, class... Ls> decltype(auto) visit_law(ContactLaw id, F&& f, TypeList<Ls...>) {
  using R = decltype(f.template operator()<None>());
  std::size_t i = 0;
  const auto want = static_cast<std::size_t>(id);
  if constexpr (std::is_void_v<R>) {
    ((i++ == want ? (f.template operator()<Ls>(), true) : false) || ...);
  } else {
    R r{};
    ((i++ == want ? (r = f.template operator()<Ls>(), true) : false) || ...);
    return r;
  }
}
template <class F> decltype(auto) visit_law(ContactLaw id, F&& f) { return visit_law(id, std::forward<F>(f), Laws{}); }

}  // namespace contact

namespace detail {
template <class List, class Seq> struct ContactLawTable;
template <class... Ls, std::size_t... I> struct ContactLawTable<TypeList<Ls...>, std::index_sequence<I...>> {
  static constexpr EnumName<ContactLaw> table[] = {{static_cast<ContactLaw>(I), Ls::name}...};
};
template <class... Ls> constexpr auto join_law_names(TypeList<Ls...>) {
  std::array<char, (Ls::name.size() + ...) + 2 * (sizeof...(Ls) - 1)> out{};
  std::size_t k = 0;
  const auto put = [&](std::string_view n) {
    if (k > 0) out[k++] = ',', out[k++] = ' ';
    for (char c : n) out[k++] = c;
  };
  (put(Ls::name), ...);
  return out;
}
inline constexpr auto contact_law_names_text = join_law_names(contact::Laws{});
}  // namespace detail

// {ContactLaw(i), name of Laws' i-th law}: to_string(ContactLaw) and parse_contact_law read it.
inline constexpr const auto& contact_law_table =
    detail::ContactLawTable<contact::Laws, std::make_index_sequence<contact::Laws::size>>::table;
constexpr const auto& enum_names(ContactLaw) { return contact_law_table; }
// "none, linear, ..." for help texts and errors
inline constexpr std::string_view contact_law_names{detail::contact_law_names_text.data(),
                                                    detail::contact_law_names_text.size()};
static_assert(std::size(contact_law_table) == contact::Laws::size);

}  // namespace pounding
