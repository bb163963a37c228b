#include <gtest/gtest.h>

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
