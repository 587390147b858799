#pragma once
// One mechanism for the names of enum values (C9): a constexpr table of {value, name} per enum, beside the
// enum, and these generic functions over it. Names are what files and the command line say ("m/s2",
// "central-difference"); an error for an unknown name lists the table's names.
//
//   inline constexpr EnumName<AccUnits> acc_units_names[] = {{AccUnits::g, "g"}, {AccUnits::m_s2, "m/s2"}};
//   constexpr const auto& enum_names(AccUnits) { return acc_units_names; }  // found by ADL: to_string works
//
//   enum_name(acc_units_names, AccUnits::g)       -> "g"
//   parse_enum(acc_units_names, "m/s2")           -> AccUnits::m_s2 (std::nullopt for an unknown name)
//   enum_name_list(acc_units_names)               -> "g, m/s2"
//   enum_name_list(acc_units_names, " or ", "\"") -> "\"g\" or \"m/s2\""
//   to_string(AccUnits::g)                        -> "g" (any enum with an enum_names overload)
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace pounding {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

// The name of `value`, "?" when the table lacks it.
template <class E, std::size_t N>
constexpr std::string_view enum_name(const EnumName<E> (&table)[N], E value) {
  for (const auto& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

// The value named `text` (exact match), std::nullopt when no entry has that name.
template <class E, std::size_t N>
constexpr std::optional<E> parse_enum(const EnumName<E> (&table)[N], std::string_view text) {
  for (const auto& entry : table)
    if (entry.name == text) return entry.value;
  return std::nullopt;
}

// The names in table order, separated by ", " and by `last` before the final one, each between `quote`s:
// for the "use one of: ..." part of an error.
template <class E, std::size_t N>
std::string enum_name_list(const EnumName<E> (&table)[N], std::string_view last = ", ", std::string_view quote = "") {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) out += i + 1 == N ? last : std::string_view(", ");
    out += quote;
    out += table[i].name;
    out += quote;
  }
  return out;
}

// The name of any enum whose table is reachable through an `enum_names(E)` overload (ADL).
template <class E>
  requires requires(E e) { enum_names(e); }
constexpr std::string_view to_string(E value) {
  return enum_name(enum_names(value), value);
}

}  // namespace pounding
