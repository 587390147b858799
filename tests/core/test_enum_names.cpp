// The one enum-name mechanism (include/pounding/core/enum_names.hpp): lookups both ways, the list used in
// errors, to_string through the enum's own table, and the tables of the enums that use it.
#include <gtest/gtest.h>

#include <string>

#include "pounding/core/enum_names.hpp"
#include "pounding/core/error.hpp"
#include "pounding/motion/records.hpp"
#include "pounding/sampling/sampler.hpp"
#include "pounding/study/study.hpp"

using namespace pounding;

namespace {

enum class Colour { red, green, blue, unnamed };
constexpr EnumName<Colour> colour_names[] = {{Colour::red, "red"}, {Colour::green, "green"}, {Colour::blue, "blue"}};

// Every value of a table names itself back, and every name parses to its value.
template <class E, std::size_t N>
void expect_round_trip(const EnumName<E> (&table)[N]) {
  for (const auto& [value, name] : table) {
    EXPECT_EQ(enum_name(table, value), name);
    EXPECT_EQ(to_string(value), name);
    ASSERT_TRUE(parse_enum(table, name).has_value()) << name;
    EXPECT_EQ(*parse_enum(table, name), value) << name;
  }
}

}  // namespace

TEST(EnumNames, LooksUpBothWays) {
  static_assert(enum_name(colour_names, Colour::green) == "green");  // usable at compile time
  static_assert(*parse_enum(colour_names, "blue") == Colour::blue);
  EXPECT_EQ(enum_name(colour_names, Colour::unnamed), "?");
  EXPECT_FALSE(parse_enum(colour_names, "Red").has_value());  // exact match only
  EXPECT_FALSE(parse_enum(colour_names, "").has_value());
}

TEST(EnumNames, ListsTheNamesForErrors) {
  EXPECT_EQ(enum_name_list(colour_names), "red, green, blue");
  EXPECT_EQ(enum_name_list(colour_names, " or "), "red, green or blue");
  EXPECT_EQ(enum_name_list(colour_names, " or ", "\""), "\"red\", \"green\" or \"blue\"");
  constexpr EnumName<Colour> one[] = {{Colour::red, "red"}};
  EXPECT_EQ(enum_name_list(one, " or "), "red");
}

TEST(EnumNames, TablesOfTheEnumsThatUseIt) {
  expect_round_trip(acc_units_names);
  expect_round_trip(scene_names);
  expect_round_trip(hysteresis_names);
  EXPECT_EQ(to_string(Scene::automatic), "auto");
  EXPECT_EQ(to_string(AccUnits::m_s2), "m/s2");
}

TEST(EnumNames, UnknownUnitsListTheAllowedNames) {
  try {
    parse_units("furlong");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "unknown units 'furlong', --units, use g, m/s2 or cm/s2");
  }
}
