// report::JsonWriter (the --json outputs of simulate and collide): layout, numbers at full precision, NaN and
// infinities as null, escaping, and misuse refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "pounding/report/json.hpp"

namespace pounding::report {
namespace {

TEST(Json, ObjectsArraysAndLayout) {
  JsonWriter w;
  w.begin_object().member("a", 1).member("b", std::vector<double>{0.1, 2.0, 1e-300});
  w.key("levels").begin_array();
  w.begin_object().member("level", 1).member("ok", true).end_object();
  w.begin_object().member("level", 2).end_object();
  w.end_array().member("s", "x");
  w.end_object();
  EXPECT_EQ(w.str(),
            "{\n  \"a\": 1,\n  \"b\": [0.1, 2, 1e-300],\n  \"levels\": [{\"level\": 1, \"ok\": true}, {\"level\": 2}],"
            "\n  \"s\": \"x\"\n}\n");
  JsonWriter e;
  EXPECT_EQ(e.begin_object().end_object().str(), "{}\n");
}

TEST(Json, NumbersRoundTripAndNonFiniteIsNull) {
  const double x = 0.1 + 0.2;  // 0.30000000000000004: every digit kept
  EXPECT_EQ(json_number(x), "0.30000000000000004");
  EXPECT_EQ(std::stod(json_number(x)), x);
  EXPECT_EQ(json_number(-2.5e-8), "-2.5e-08");
  EXPECT_EQ(json_number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(json_number(std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(json_number(-std::numeric_limits<double>::infinity()), "null");
}

TEST(Json, StringsAreEscaped) {
  EXPECT_EQ(json_string("a\"b\\c\nd\te\x01"), "\"a\\\"b\\\\c\\nd\\te\\u0001\"");
  EXPECT_EQ(json_string("level 1/2"), "\"level 1/2\"");
}

TEST(Json, MisuseIsAProgrammingError) {
  JsonWriter w;
  EXPECT_THROW(w.key("x"), std::logic_error);  // a key outside an object
  JsonWriter a;
  a.begin_array();
  EXPECT_THROW(a.key("x"), std::logic_error);
  JsonWriter b;
  EXPECT_THROW(b.end_object(), std::logic_error);
  JsonWriter c;
  c.value(1.0);
  EXPECT_THROW(c.value(2.0), std::logic_error);  // a second top-level value
  JsonWriter d;
  d.begin_object();
  EXPECT_THROW(d.value(1.0), std::logic_error);  // a member without its key
  EXPECT_THROW(d.end_array(), std::logic_error);
  d.key("k");
  EXPECT_THROW(d.end_object(), std::logic_error);  // a key without its value
}

}  // namespace
}  // namespace pounding::report
