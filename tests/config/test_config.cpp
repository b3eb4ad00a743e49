#include "jellysim/config/config.hpp"
#include "jellysim/core/errors.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

using jellysim::InputError;
using jellysim::config::Config;
using jellysim::config::Range;

namespace {

const char* kDefaults = R"(
duration = 10.0
[bar]
length = 0.45
segments = 10
pivot = [0.0, 0.0]
[time]
integrator = "dopri5"
adaptive = false
)";

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(Config, ReadsTypedValuesWithRanges) {
  const Config c = Config::parse(kDefaults, "defaults");
  EXPECT_DOUBLE_EQ(c.number("bar.length", Range::positive()), 0.45);
  EXPECT_EQ(c.integer("bar.segments", 1, 100), 10);
  EXPECT_EQ(c.string("time.integrator"), "dopri5");
  EXPECT_FALSE(c.boolean("time.adaptive"));
  EXPECT_EQ(c.vec2("bar.pivot").x, 0.0);
}

TEST(Config, OutOfRangeNamesFieldValueAndRange) {
  Config c = Config::parse(kDefaults, "defaults");
  c.set("bar.length=-1");
  const std::string msg = error_of([&] { c.number("bar.length", Range::positive()); });
  EXPECT_NE(msg.find("bar.length"), std::string::npos) << msg;
  EXPECT_NE(msg.find("-1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(0, inf)"), std::string::npos) << msg;
  c.set("bar.segments=0");
  EXPECT_NE(error_of([&] { c.integer("bar.segments", 1, 100); }).find("[1, 100]"), std::string::npos);
}

TEST(Config, SetAcceptsIntegerForFloatAndBareStrings) {
  Config c = Config::parse(kDefaults, "defaults");
  c.set("duration=3");
  EXPECT_DOUBLE_EQ(c.number("duration"), 3.0);
  c.set("time.integrator=rk4");
  EXPECT_EQ(c.string("time.integrator"), "rk4");
  c.set("bar.pivot=[1, -2.5]");
  EXPECT_DOUBLE_EQ(c.vec2("bar.pivot").y, -2.5);
}

TEST(Config, RejectsUnknownFieldsWrongTypesAndBadSyntax) {
  Config c = Config::parse(kDefaults, "defaults");
  EXPECT_NE(error_of([&] { c.set("bar.lenght=1"); }).find("unknown field 'bar.lenght'"), std::string::npos);
  EXPECT_NE(error_of([&] { c.set("bar.length=abc"); }).find("wrong type"), std::string::npos);
  EXPECT_NE(error_of([&] { c.set("bar.segments=2.5"); }).find("bar.segments"), std::string::npos);
  EXPECT_NE(error_of([&] { c.set("nonsense"); }).find("key=value"), std::string::npos);
  EXPECT_NE(error_of([&] { c.set("bar.length=nan"); c.number("bar.length"); }).find("out of range"),
            std::string::npos);
  EXPECT_NE(error_of([] { Config::parse("x = [1,", "broken.toml"); }).find("broken.toml:1"), std::string::npos);
  const std::string msg = error_of([&] { c.choice("time.integrator", {"rk2", "rk4"}); });
  EXPECT_NE(msg.find("rk2, rk4"), std::string::npos) << msg;
}

TEST(Config, MergeOverlaysOnlyKnownFields) {
  Config c = Config::parse(kDefaults, "defaults");
  c.merge(Config::parse("[bar]\nlength = 2.0\n", "user.toml"));
  EXPECT_DOUBLE_EQ(c.number("bar.length"), 2.0);
  EXPECT_EQ(c.integer("bar.segments", 1, 100), 10);  // untouched default
  const std::string msg = error_of([&] { c.merge(Config::parse("[barr]\nx = 1\n", "user.toml")); });
  EXPECT_NE(msg.find("user.toml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("barr"), std::string::npos) << msg;
}

TEST(Config, ResolvedConfigRoundTripsThroughTomlAndJson) {
  Config c = Config::parse(kDefaults, "defaults");
  c.set("bar.length=0.5");
  const Config again = Config::parse(c.to_toml(), "resolved");
  EXPECT_DOUBLE_EQ(again.number("bar.length"), 0.5);
  EXPECT_DOUBLE_EQ(c.to_json()["bar"]["length"].get<double>(), 0.5);
}

TEST(Config, ArraysOfIntegersAndChoicesAreChecked) {
  Config c = Config::parse("grids = [16, 32]\nsolvers = [\"a\", \"b\"]\n", "defaults");
  EXPECT_EQ(c.integers("grids", 4, 64), (std::vector<std::int64_t>{16, 32}));
  EXPECT_EQ(c.choices("solvers", {"a", "b", "c"}), (std::vector<std::string>{"a", "b"}));
  c.set("grids=[16, 128]");
  EXPECT_NE(error_of([&] { c.integers("grids", 4, 64); }).find("128 out of range [4, 64]"), std::string::npos);
  c.set("solvers=[\"a\", \"z\"]");
  EXPECT_NE(error_of([&] { c.choices("solvers", {"a", "b"}); }).find("\"z\", not one of: a, b"), std::string::npos);
  c.set("grids=[]");
  EXPECT_NE(error_of([&] { c.integers("grids", 4, 64); }).find("non-empty"), std::string::npos);
}
