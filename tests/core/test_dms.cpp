#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"

using meridian::Angle;
using meridian::parse_angle;

namespace {
double deg(const char* s) { return parse_angle(s).deg(); }
}  // namespace

TEST(ParseAngle, IssueExamples) {
  const double expect = 157.0 + 21.0 / 60.0;
  EXPECT_NEAR(deg("157°21'00\""), expect, 1e-12);
  EXPECT_NEAR(deg("157 21 00"), expect, 1e-12);
  EXPECT_NEAR(deg("-0 01 16.2"), -(1.0 / 60.0 + 16.2 / 3600.0), 1e-12);
  EXPECT_NEAR(deg("157.35"), 157.35, 1e-12);
}

TEST(ParseAngle, OtherForms) {
  EXPECT_NEAR(deg("157d21m30s"), 157.0 + 21.0 / 60 + 30.0 / 3600, 1e-12);
  EXPECT_NEAR(deg("157:21:30"), 157.0 + 21.0 / 60 + 30.0 / 3600, 1e-12);
  EXPECT_NEAR(deg("157°21′30.5″"), 157.0 + 21.0 / 60 + 30.5 / 3600, 1e-12);
  EXPECT_NEAR(deg("157 21.5"), 157.0 + 21.5 / 60, 1e-12);
  EXPECT_NEAR(deg("  +12.5deg "), 12.5, 1e-12);
  EXPECT_NEAR(deg("200g"), 180.0, 1e-12);
  EXPECT_NEAR(deg("100 gon"), 90.0, 1e-12);
  EXPECT_NEAR(parse_angle("93.6\"").arcsec(), 93.6, 1e-9);
  EXPECT_NEAR(parse_angle("-12.5'").arcmin(), -12.5, 1e-12);
  EXPECT_NEAR(parse_angle("1 rad").rad(), 1.0, 1e-15);
  EXPECT_NEAR(deg("359 41 12"), 359.0 + 41.0 / 60 + 12.0 / 3600, 1e-12);
}

TEST(ParseAngle, RejectsBadText) {
  for (const char* bad : {"", "  ", "abc", "12 60 00", "12 30 60", "nan", "inf", "-inf", "1e400",
                          "12 -3 00", "1 2 3 4", "12.5 30", "12°30'x", "12s 30d", "--5", "5 :"}) {
    EXPECT_THROW(parse_angle(bad), meridian::ParseError) << "text: " << bad;
  }
}

TEST(ParseAngle, ErrorNamesText) {
  try {
    parse_angle("12 75 00");
    FAIL();
  } catch (const meridian::ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("12 75 00"), std::string::npos);
  }
}

TEST(FormatDms, RoundsAndCarries) {
  EXPECT_EQ(meridian::format_dms(Angle::degrees(157.35)), "157°21'00.0\"");
  EXPECT_EQ(meridian::format_dms(Angle::degrees(-(1.0 / 60.0 + 16.2 / 3600.0))), "-0°01'16.2\"");
  EXPECT_EQ(meridian::format_dms(Angle::degrees(10.0 - 1e-9)), "10°00'00.0\"");
  EXPECT_EQ(meridian::format_dms(Angle::arcseconds(59.96)), "0°01'00.0\"");
  EXPECT_EQ(meridian::format_dms(Angle::degrees(1.5), {2, false, true}), "+1 30 00.00");
  EXPECT_EQ(meridian::format_direction_dms(Angle::degrees(-1)), "359°00'00.0\"");
  EXPECT_EQ(meridian::format_direction_dms(Angle::degrees(360.0 - 1e-9)), "0°00'00.0\"");
  EXPECT_EQ(meridian::format_dms(Angle::radians(std::numeric_limits<double>::quiet_NaN())), "nan");
}

TEST(FormatDms, ParseRoundTrip) {
  for (double d : {0.0, 12.3456789, -45.000001, 359.999, 123.4567}) {
    Angle a = Angle::degrees(d);
    EXPECT_NEAR(parse_angle(meridian::format_dms(a, {4, true, false})).arcsec(), a.arcsec(), 1e-4);
  }
}
