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

TEST(LaplaceZenithTerm, ClosedForm) {
  // −(ξ·sin α − η·cos α)·cot z, by hand.
  const double cot70 = 1.0 / std::tan(mu::deg_to_rad(70.0));
  auto term = [](double xi_as, double eta_as, double az_deg, double z_deg) {
    return mu::rad_to_arcsec(
        mg::laplace_zenith_correction_rad(mu::arcsec_to_rad(xi_as), mu::arcsec_to_rad(eta_as),
                                          mu::deg_to_rad(az_deg), mu::deg_to_rad(z_deg)));
  };
  // ξ = +5″, sight due east 20° upwards: −5″·cot 70° = −1.820″; downwards +1.820″.
  EXPECT_NEAR(term(5, 0, 90, 70), -5.0 * cot70, 1e-12);
  EXPECT_NEAR(term(5, 0, 90, 70), -1.8199, 1e-4);
  EXPECT_NEAR(term(5, 0, 90, 110), 5.0 * cot70, 1e-12);
  // Due west: sin α = −1.
  EXPECT_NEAR(term(5, 0, 270, 70), 5.0 * cot70, 1e-12);
  // η = +5″, sight due north upwards: +η·cos α·cot z = +1.820″; due south −1.820″.
  EXPECT_NEAR(term(0, 5, 0, 70), 5.0 * cot70, 1e-12);
  EXPECT_NEAR(term(0, 5, 180, 70), -5.0 * cot70, 1e-12);
  // ξ = 3″, η = −4″: −(3 sin α + 4 cos α)·cot z, largest (θ·cot z, θ = 5″) at
  // sin α = 3/5, cos α = 4/5, zero across it.
  const double az = mu::rad_to_deg(std::atan2(3.0, 4.0));
  EXPECT_NEAR(term(3, -4, az, 70), -5.0 * cot70, 1e-12);
  EXPECT_NEAR(term(3, -4, az + 90, 70), 0.0, 1e-12);
  // Horizontal sight: nothing.
  EXPECT_NEAR(term(5, 5, 33, 90), 0.0, 1e-15);
}

TEST(LaplaceZenithTerm, Guards) {
  using meridian::InputError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double z = mu::deg_to_rad(70.0);
  EXPECT_THROW(mg::laplace_zenith_correction_rad(0.0101, 0.0, 1.0, z), InputError);
  EXPECT_THROW(mg::laplace_zenith_correction_rad(0.0, -0.0101, 1.0, z), InputError);
  EXPECT_THROW(mg::laplace_zenith_correction_rad(nan, 0.0, 1.0, z), InputError);
  EXPECT_THROW(mg::laplace_zenith_correction_rad(0.0, 0.0, nan, z), InputError);
  EXPECT_NO_THROW(mg::laplace_zenith_correction_rad(0.01, -0.01, 1.0, z));
  // A vertical sight has no azimuth; 10° ≤ z ≤ 170° is accepted.
  for (double zd : {0.0, 5.0, 9.99, 170.01, 175.0, 180.0, -30.0, 200.0}) {
    EXPECT_THROW(mg::laplace_zenith_correction_rad(1e-5, 1e-5, 1.0, mu::deg_to_rad(zd)), InputError)
        << zd;
    EXPECT_THROW(mg::check_zenith_distance(mu::deg_to_rad(zd)), InputError) << zd;
  }
  EXPECT_THROW(mg::check_zenith_distance(nan), InputError);
  for (double zd : {10.0, 45.0, 90.0, 135.0, 170.0})
    EXPECT_NO_THROW(mg::check_zenith_distance(mu::deg_to_rad(zd))) << zd;
}
