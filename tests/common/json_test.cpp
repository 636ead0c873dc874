// The runtime's JSON reader (manifests): every JSON value, and errors naming line and column for
// what is not JSON, instead of a crash, a hang or a guess.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "runtime/common/json.hpp"

namespace json = fuzzygait::common::json;
using ::testing::HasSubstr;

namespace {

std::string error_of(const std::string& text) {
  try {
    json::parse(text, "m.json");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Json, ReadsEveryKindOfValue) {
  const json::Value v = json::parse(R"({
  "name": "a\tb \"q\" \u00e9 \ud83d\ude00",
  "n": -12.5e-1, "zero": 0, "big": 1.7976931348623157e308,
  "list": [true, false, null, [], {}],
  "nested": {"x": 1}
})",
                                    "m.json");
  ASSERT_EQ(v.kind, json::Value::Kind::Object);
  EXPECT_EQ(v.find("name")->string, "a\tb \"q\" \xC3\xA9 \xF0\x9F\x98\x80");
  EXPECT_EQ(v.find("n")->number, -1.25);
  EXPECT_EQ(v.find("n")->line, 3);
  EXPECT_EQ(v.find("big")->number, 1.7976931348623157e308);
  const json::Value& list = *v.find("list");
  ASSERT_EQ(list.array.size(), 5u);
  EXPECT_TRUE(list.array[0].boolean);
  EXPECT_EQ(list.array[2].kind, json::Value::Kind::Null);
  EXPECT_EQ(v.find("nested")->find("x")->number, 1.0);
  EXPECT_EQ(v.find("missing"), nullptr);
  EXPECT_EQ(v.object.front().first, "name");  // the file's order
}

TEST(Json, RefusesWhatIsNotJsonNamingLineAndColumn) {
  EXPECT_EQ(error_of("{\"a\": 1,\n}"), "m.json:2:1: expected a member name in double quotes");
  EXPECT_EQ(error_of("{\"a\": 1, \"a\": 2}"), "m.json:1:10: duplicate member 'a'");
  EXPECT_EQ(error_of("[1 2]"), "m.json:1:4: expected ',' or ']' after an element");
  EXPECT_EQ(error_of("{} x"), "m.json:1:4: unexpected text after the JSON value");
  EXPECT_EQ(error_of(""), "m.json:1:1: expected a JSON value");
  EXPECT_EQ(error_of("{\"a\": 01}"), "m.json:1:8: expected ',' or '}' after a member");
  EXPECT_EQ(error_of("[1.]"), "m.json:1:4: expected digits after the decimal point");
  EXPECT_EQ(error_of("[1e400]"), "m.json:1:2: the number 1e400 is beyond what a double holds");
  EXPECT_EQ(error_of("[1e-400]"), "m.json:1:2: the number 1e-400 is beyond what a double holds");
  EXPECT_EQ(error_of("[nan]"), "m.json:1:2: expected a JSON value");
  EXPECT_EQ(error_of("[\"a\nb\"]"), "m.json:1:4: a control character inside a string");
  EXPECT_EQ(error_of("[\"\\ud800\"]"), "m.json:1:9: a lone UTF-16 surrogate");
  EXPECT_EQ(error_of("[\"\\x\"]"), "m.json:1:4: an unknown escape in a string");
  EXPECT_EQ(error_of("[\"abc"), "m.json:1:6: the string is not closed");
  EXPECT_EQ(error_of("// comment\n{}"), "m.json:1:1: expected a JSON value");
  EXPECT_THAT(error_of("[tru]"), HasSubstr("expected a JSON value"));
}

TEST(Json, DeepNestingIsAnErrorNotAStackOverflow) {
  EXPECT_EQ(error_of(std::string(64, '[') + std::string(64, ']')), "");
  EXPECT_THAT(error_of(std::string(100000, '[')), HasSubstr("values nested deeper than 64"));
}

}  // namespace
