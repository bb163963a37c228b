#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/laplace.hpp"

namespace mg = meridian::geodesy;
namespace mu = meridian::units;

TEST(Laplace, ClosedForm) {
  // α − A = −η·tan φ.
  const double eta = mu::arcsec_to_rad(5.0);
  EXPECT_NEAR(mu::rad_to_arcsec(mg::laplace_correction_rad(eta, mu::deg_to_rad(45.0))), -5.0,
              1e-12);
  EXPECT_NEAR(mu::rad_to_arcsec(mg::laplace_correction_rad(eta, mu::deg_to_rad(30.0))),
              -5.0 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(mu::rad_to_arcsec(mg::laplace_correction_rad(-eta, mu::deg_to_rad(60.0))),
              5.0 * std::sqrt(3.0), 1e-12);
  // Southern hemisphere: tan φ < 0 flips the sign.
  EXPECT_NEAR(mu::rad_to_arcsec(mg::laplace_correction_rad(eta, mu::deg_to_rad(-45.0))), 5.0,
              1e-12);
  EXPECT_EQ(mg::laplace_correction_rad(eta, 0.0), 0.0);
  for (double lat_deg = -85; lat_deg <= 85; lat_deg += 5) {
    const double lat = mu::deg_to_rad(lat_deg);
    EXPECT_DOUBLE_EQ(mg::laplace_correction_rad(-1.3e-5, lat), 1.3e-5 * std::tan(lat));
  }
}

TEST(Laplace, AstronomicToGeodeticAzimuth) {
  // A gyro (astronomic) azimuth of 45° at φ = 40° N with η = +3″:
  // α = A − η tan φ = 45° − 2.517″.
  const double A = mu::deg_to_rad(45.0);
  const double alpha = A + mg::laplace_correction_rad(mu::arcsec_to_rad(3.0), mu::deg_to_rad(40.0));
  EXPECT_NEAR(mu::rad_to_arcsec(alpha - A), -3.0 * std::tan(mu::deg_to_rad(40.0)), 1e-9);
  EXPECT_NEAR(mu::rad_to_arcsec(alpha - A), -2.5173, 1e-4);
}

TEST(Laplace, BadInputThrows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mg::laplace_correction_rad(nan, 0.5), meridian::InputError);
  EXPECT_THROW(mg::laplace_correction_rad(1e-5, nan), meridian::InputError);
  EXPECT_THROW(mg::laplace_correction_rad(1e-5, mu::kPi / 2), meridian::InputError);
  EXPECT_THROW(mg::laplace_correction_rad(1e-5, -2.0), meridian::InputError);
  // 5 given in arc-seconds instead of radians.
  EXPECT_THROW(mg::laplace_correction_rad(5.0, 0.5), meridian::InputError);
}
