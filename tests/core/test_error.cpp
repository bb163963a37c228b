#include <gtest/gtest.h>

#include <limits>
#include <span>
#include <vector>

#include "meridian/core/checks.hpp"
#include "meridian/core/error.hpp"

TEST(Error, ContextFormatting) {
  meridian::InputError e("fewer than three crossings", {"", std::nullopt, "times_s"});
  EXPECT_STREQ(e.what(), "times_s: fewer than three crossings");
  e.add_context("", std::nullopt, "crossings[0]");
  e.add_context("", std::nullopt, "[2]");
  e.add_context("", std::nullopt, "determinations");
  e.add_context("obs.yaml", 17);
  EXPECT_STREQ(e.what(), "obs.yaml:17: determinations[2].crossings[0].times_s: fewer than three crossings");
  EXPECT_EQ(e.message(), "fewer than three crossings");
  EXPECT_EQ(e.context().line.value(), 17);
}

TEST(Error, OuterContextDoesNotOverrideInner) {
  meridian::ParseError e("bad", {"inner.yaml", 3, "x"});
  e.add_context("outer.yaml", 9);
  EXPECT_STREQ(e.what(), "inner.yaml:3: x: bad");
}

TEST(Error, Hierarchy) {
  EXPECT_THROW(throw meridian::ParseError("p"), meridian::InputError);
  EXPECT_THROW(throw meridian::NumericalError("n"), meridian::Error);
  EXPECT_THROW(throw meridian::IoError("i"), std::runtime_error);
}

TEST(Error, RelocateReplacesTheContextAndKeepsTheClass) {
  // A field path of the library's Input becomes the file, line and column the user wrote; the
  // rethrown error is still a ParseError (so the CLI's exit code does not change).
  try {
    try {
      throw meridian::ParseError("is not a number", {"", std::nullopt, "dr[3].speed_m_s"});
    } catch (meridian::Error& e) {
      e.relocate({"dr.csv", 5, "speed"});
      throw;
    }
  } catch (const meridian::ParseError& e) {
    EXPECT_STREQ(e.what(), "dr.csv:5: speed: is not a number");
    EXPECT_EQ(e.context().field, "speed");
    return;
  }
  FAIL() << "the class was lost";
}

TEST(Checks, RequireFinite) {
  EXPECT_NO_THROW(meridian::require_finite(1.5, "speed"));
  try {
    meridian::require_finite(std::numeric_limits<double>::quiet_NaN(), "speed", "dr[2].speed_m_s");
    FAIL();
  } catch (const meridian::InputError& e) {
    EXPECT_STREQ(e.what(), "dr[2].speed_m_s: speed is not finite (nan)");
  }
  const std::vector<double> v = {1.0, 2.0, std::numeric_limits<double>::infinity()};
  try {
    meridian::require_finite(std::span<const double>(v), "series");
    FAIL();
  } catch (const meridian::InputError& e) {
    EXPECT_STREQ(e.what(), "series sample 2 is not finite (inf)");
  }
  EXPECT_THROW(meridian::require_finite(std::span<const double>(), "series"), meridian::InputError);
}
