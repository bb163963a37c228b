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

TEST(ParseAngle, DecimalDegreesWithAnExponent) {
  // As %.17g writes a latitude near the equator (a dov line CSV crossing it was unreadable).
  EXPECT_EQ(deg("4.9838993339234222e-19"), 4.9838993339234222e-19);
  EXPECT_EQ(deg("-9.5630522950706032e-05"), -9.5630522950706032e-05);
  EXPECT_EQ(deg(" +1E-3 "), 1e-3);
  EXPECT_EQ(deg("1.5e2"), 150.0);
  for (const char* bad : {"1e", "e5", "1e5 d", "1e5deg", "--1e-3", "-+1e-3", "1e-3.5", "1e400"})
    EXPECT_THROW(parse_angle(bad), meridian::ParseError) << "text: " << bad;
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

// --- Field-book units (angle_unit) and stopwatch times, against hand-worked values.

using meridian::AngleUnit;

TEST(AngleUnit, NamesRoundTripAndUnknownIsRejected) {
  for (AngleUnit u : {AngleUnit::Dms, AngleUnit::Degrees, AngleUnit::Gon, AngleUnit::DddMmss})
    EXPECT_EQ(meridian::angle_unit_from_string(meridian::to_string(u)), u);
  EXPECT_EQ(meridian::to_string(AngleUnit::DddMmss), "ddd.mmss");
  for (const char* bad : {"", "DMS", "degrees", "grad", "dddmmss", "rad"})
    EXPECT_THROW(meridian::angle_unit_from_string(bad), meridian::ParseError) << bad;
}

TEST(ParseDddMmss, CalculatorNotation) {
  // 123.4530 = 123 + 45/60 + 30/3600 = 123.758333…°
  EXPECT_NEAR(meridian::parse_ddd_mmss("123.4530").deg(), 123.0 + 45.0 / 60 + 30.0 / 3600, 1e-12);
  EXPECT_NEAR(meridian::parse_ddd_mmss("123.45305").deg(), 123.0 + 45.0 / 60 + 30.5 / 3600, 1e-12);
  EXPECT_NEAR(meridian::parse_ddd_mmss("123.453012").arcsec(), (123 * 60 + 45) * 60 + 30.12, 1e-7);
  EXPECT_NEAR(meridian::parse_ddd_mmss("123.45").deg(), 123.75, 1e-12);
  EXPECT_NEAR(meridian::parse_ddd_mmss("123").deg(), 123.0, 0);
  EXPECT_NEAR(meridian::parse_ddd_mmss(" 359.5959 ").arcsec(), 360.0 * 3600 - 1, 1e-7);
  EXPECT_NEAR(meridian::parse_ddd_mmss("0.0005").arcsec(), 5.0, 1e-9);
  // The sign applies to the whole angle: -0.0116 = -(1'16").
  EXPECT_NEAR(meridian::parse_ddd_mmss("-0.0116").arcsec(), -76.0, 1e-9);
  EXPECT_NEAR(meridian::parse_ddd_mmss("+12.3000").deg(), 12.5, 1e-12);
  // Through the unit switch as well: 63°27'24.9" booked as 63.27249.
  EXPECT_NEAR(parse_angle("63.27249", AngleUnit::DddMmss).arcsec(),
              (63 * 60 + 27) * 3600.0 / 60 + 24.9, 1e-7);
}

TEST(ParseDddMmss, RejectsImpossibleAndAmbiguousDigits) {
  auto message = [](const char* text) {
    try {
      meridian::parse_ddd_mmss(text);
    } catch (const meridian::ParseError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // Seconds 99: decimal degrees booked in the wrong unit.
  EXPECT_NE(message("123.4599").find("seconds 99 must be below 60"), std::string::npos)
      << message("123.4599");
  EXPECT_NE(message("123.7530").find("minutes 75 must be below 60"), std::string::npos);
  EXPECT_NE(message("123.4560").find("seconds 60"), std::string::npos);
  // One or three digits after the point do not say which digit is the tens.
  EXPECT_NE(message("123.4").find("two digits"), std::string::npos);
  EXPECT_NE(message("123.453").find("two digits"), std::string::npos);
  for (const char* bad : {"", "-", ".4530", "123.", "123.45 30", "123°45'30\"", "1.2e2", "12.34x0",
                          "--1.0000", "123.45.30", "nan", "0x10"})
    EXPECT_THROW(meridian::parse_ddd_mmss(bad), meridian::ParseError) << bad;
}

TEST(FormatDddMmss, RoundsCarriesAndReadsBack) {
  EXPECT_EQ(meridian::format_ddd_mmss(Angle::degrees(123.0 + 45.0 / 60 + 30.5 / 3600)),
            "123.45305");
  EXPECT_EQ(meridian::format_ddd_mmss(Angle::degrees(123.0 + 45.0 / 60 + 30.0 / 3600), 0),
            "123.4530");
  EXPECT_EQ(meridian::format_ddd_mmss(Angle::arcseconds(-76.0), 0), "-0.0116");
  // 59.96" rounds to a whole minute, 359°59'59.96" to 360°.
  EXPECT_EQ(meridian::format_ddd_mmss(Angle::arcseconds(59.96)), "0.01000");
  EXPECT_EQ(meridian::format_ddd_mmss(Angle::degrees(360.0) - Angle::arcseconds(0.04)),
            "360.00000");
  EXPECT_EQ(meridian::format_ddd_mmss(Angle::arcseconds(-0.01)), "0.00000");  // no "-0"
  EXPECT_EQ(meridian::format_ddd_mmss(Angle::radians(std::numeric_limits<double>::quiet_NaN())),
            "nan");
  for (double d : {0.0, 12.3456789, -45.000001, 359.999, 123.4567}) {
    const Angle a = Angle::degrees(d);
    EXPECT_NEAR(meridian::parse_ddd_mmss(meridian::format_ddd_mmss(a, 4)).arcsec(), a.arcsec(),
                0.5e-4);
  }
}

TEST(ParseAngleInUnit, DegreesAndGonTakeOnlyDecimals) {
  EXPECT_NEAR(parse_angle("157.35", AngleUnit::Degrees).deg(), 157.35, 1e-12);
  EXPECT_NEAR(parse_angle("-0.5deg", AngleUnit::Degrees).deg(), -0.5, 1e-12);
  EXPECT_NEAR(parse_angle("12°", AngleUnit::Degrees).deg(), 12.0, 1e-12);
  // 174.8333 gon = 174.8333 * 0.9 deg = 157.34997 deg.
  EXPECT_NEAR(parse_angle("174.8333", AngleUnit::Gon).deg(), 157.34997, 1e-10);
  EXPECT_NEAR(parse_angle("100 gon", AngleUnit::Gon).deg(), 90.0, 1e-12);
  EXPECT_NEAR(parse_angle("-0.0100g", AngleUnit::Gon).arcsec(), -32.4, 1e-9);
  EXPECT_NEAR(parse_angle("400", AngleUnit::Gon).deg(), 360.0, 1e-12);
  // Another notation is refused, not reinterpreted.
  for (const char* bad : {"157 21 00", "157°21'", "100 gon", "1e2", "", "x", "12.5 rad", "93.6\""})
    EXPECT_THROW(parse_angle(bad, AngleUnit::Degrees), meridian::ParseError) << bad;
  for (const char* bad : {"157 21 00", "157.35°", "157.35 deg", "1e2", "12:30"})
    EXPECT_THROW(parse_angle(bad, AngleUnit::Gon), meridian::ParseError) << bad;
  // dms keeps today's rules.
  EXPECT_NEAR(parse_angle("157 21 00", AngleUnit::Dms).deg(), 157.35, 1e-12);
  EXPECT_NEAR(parse_angle("157.35", AngleUnit::Dms).deg(), 157.35, 1e-12);
  EXPECT_NEAR(parse_angle("200g", AngleUnit::Dms).deg(), 180.0, 1e-12);
}

TEST(ParseStopwatch, MinutesSecondsAndHours) {
  using meridian::parse_stopwatch_s;
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("4:07.3"), 247.3);  // 4*60 + 7.3
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("0:51.8"), 51.8);
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("18:35.4"), 1115.4);           // 18*60 + 35.4
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("75:00"), 4500.0);             // minutes may exceed 59
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("1:02:03.5"), 3723.5);         // 3600 + 120 + 3.5
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("4'39.6\""), 279.6);           // as booked by hand
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("4\u203239.6\u2033"), 279.6);  // prime and double prime
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("4'39.6"), 279.6);
  EXPECT_DOUBLE_EQ(parse_stopwatch_s(" 279.6 "), 279.6);
  EXPECT_DOUBLE_EQ(parse_stopwatch_s("6:58.0"), 418.0);
}

TEST(ParseStopwatch, RejectsSixtySecondsSignsAndGarbage) {
  using meridian::parse_stopwatch_s;
  for (const char* bad :
       {"4:60.0", "4:75", "1:60:00", "-4:07.3", "4:-07", "-279.6", "4:7.3", "4:007", "4.5:07",
        "4:", ":07", "1:2:3:4", "abc", "", "4:07.3x", "4'07'", "nan", "1e2", "4::07"})
    EXPECT_THROW(parse_stopwatch_s(bad), meridian::ParseError) << bad;
  try {
    parse_stopwatch_s("4:75.0");
    FAIL();
  } catch (const meridian::ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("\"4:75.0\": seconds must be below 60"), std::string::npos)
        << e.what();
  }
}
