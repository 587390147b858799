#pragma once
// The registered contact laws, in the order of the ContactLaw enum. Names, parse errors, help lists and the
// run-time dispatch (ContactLaw -> law type) come from this list; a new law is one header plus one entry.
#include <array>
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

namespace pounding {

template <class... Ts> struct TypeList {
  static constexpr std::size_t size = sizeof...(Ts);
};

namespace contact {

using Laws = TypeList<None, Linear, Kelvin, Hertz, Hertzdamp, Jankowski, Stereomechanical>;

template <class... Ls> constexpr bool all_laws(TypeList<Ls...>) { return (Law<Ls> && ...); }
static_assert(all_laws(Laws{}), "every registered law satisfies contact::Law");

template <class... Ls> constexpr auto names_of(TypeList<Ls...>) {
  return std::array<std::string_view, sizeof...(Ls)>{Ls::name...};
}
inline constexpr auto law_names = names_of(Laws{});
template <class... Ls> constexpr auto traits_of(TypeList<Ls...>) {
  return std::array<LawTraits, sizeof...(Ls)>{Ls::traits...};
}
inline constexpr auto law_traits = traits_of(Laws{});
inline constexpr const LawTraits& traits(ContactLaw id) { return law_traits[static_cast<std::size_t>(id)]; }

// The enum and the list agree (ContactLaw's value is the index in Laws).
static_assert(law_names[static_cast<std::size_t>(ContactLaw::none)] == "none");
static_assert(law_names[static_cast<std::size_t>(ContactLaw::hertzdamp)] == "hertzdamp");
static_assert(law_names[static_cast<std::size_t>(ContactLaw::stereomechanical)] == "stereomechanical");

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
}  // namespace pounding
