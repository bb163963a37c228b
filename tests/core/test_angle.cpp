#include <gtest/gtest.h>

#include "meridian/core/angle.hpp"

using meridian::Angle;

TEST(Angle, UnitsRoundTrip) {
  EXPECT_NEAR(Angle::degrees(180).rad(), M_PI, 1e-15);
  EXPECT_NEAR(Angle::arcseconds(3600).deg(), 1.0, 1e-15);
  EXPECT_NEAR(Angle::arcminutes(60).deg(), 1.0, 1e-15);
  EXPECT_NEAR(Angle::gon(200).deg(), 180.0, 1e-12);
  EXPECT_NEAR(Angle::degrees(1).arcsec(), 3600.0, 1e-9);
}

TEST(Angle, Arithmetic) {
  Angle a = Angle::degrees(10) + Angle::arcminutes(30);
  EXPECT_NEAR(a.deg(), 10.5, 1e-13);
  EXPECT_NEAR((a * 2.0).deg(), 21.0, 1e-13);
  EXPECT_NEAR((a - Angle::degrees(20)).deg(), -9.5, 1e-13);
  EXPECT_NEAR(Angle::degrees(30) / Angle::degrees(15), 2.0, 1e-15);
  EXPECT_LT(Angle::degrees(1), Angle::degrees(2));
}

TEST(Angle, Normalisation) {
  EXPECT_NEAR(Angle::degrees(-1).normalized_positive().deg(), 359.0, 1e-12);
  EXPECT_NEAR(Angle::degrees(721).normalized_positive().deg(), 1.0, 1e-12);
  EXPECT_NEAR(Angle::degrees(359).normalized_signed().deg(), -1.0, 1e-12);
  EXPECT_NEAR(Angle::degrees(180).normalized_signed().deg(), -180.0, 1e-12);
  EXPECT_GE(Angle::radians(-1e-300).normalized_positive().rad(), 0.0);
  EXPECT_LT(Angle::radians(-1e-300).normalized_positive().rad(), 2 * M_PI);
}
