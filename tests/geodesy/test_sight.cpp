// The zenith distance of a sight (geodesy/sight.hpp). References:
// GeographicLib::LocalCartesian (the target in the station's ENU frame) and
// the classical spherical formula z = π/2 − atan(Δh/s) + s/(2R) with s from
// GeographicLib::Geodesic.

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/ellipsoid.hpp"
#include "meridian/geodesy/sight.hpp"

namespace mg = meridian::geodesy;
namespace mu = meridian::units;
using mu::deg_to_rad;
using mu::rad_to_arcsec;

TEST(Sight, AgreesWithLocalCartesianAndTheSphericalFormula) {
  const mg::Ellipsoid e = mg::cgcs2000();
  const GeographicLib::Geodesic geod(e.a_m, e.f);
  double worst_lc = 0, worst_sphere = 0, worst_simple = 0;
  for (double lat : {37.85, -33.9, 60.0, 0.5})
    for (double h1 : {-641.3, 0.0, 862.4})
      for (double s : {50.0, 125.0, 1000.0, 3000.0})
        for (double slope_deg : {-70.0, -20.0, -0.3, 0.0, 5.0, 20.0})
          for (double azi : {0.0, 61.0, 180.0, 250.0}) {
            SCOPED_TRACE(testing::Message() << lat << " h " << h1 << " s " << s << " slope "
                                            << slope_deg << " azi " << azi);
            double lat2, lon2;
            geod.Direct(lat, 112.55, azi, s, lat2, lon2);
            const double h2 = h1 + s * std::tan(deg_to_rad(slope_deg));
            const double z =
                mg::sight_zenith_distance_rad({deg_to_rad(lat), deg_to_rad(112.55), h1},
                                              {deg_to_rad(lat2), deg_to_rad(lon2), h2}, e);
            const GeographicLib::LocalCartesian lc(lat, 112.55, h1,
                                                   GeographicLib::Geocentric(e.a_m, e.f));
            double x, y, u;
            lc.Forward(lat2, lon2, h2, x, y, u);
            const double z_lc = std::atan2(std::hypot(x, y), u);
            EXPECT_NEAR(rad_to_arcsec(z - z_lc), 0.0, 2e-5);  // ECEF rounding (1e-9 m) over 50 m
            worst_lc = std::max(worst_lc, std::abs(rad_to_arcsec(z - z_lc)));
            // Spherical, exact on a sphere of the radius of curvature R_α of the
            // line's normal section (Euler: 1/R_α = cos²α/M + sin²α/N):
            // central angle ψ = s/R_α, elevation from the triangle of the centre
            // and both points.
            const double e2 = e.f * (2 - e.f), sp = std::sin(deg_to_rad(lat));
            const double w2 = 1 - e2 * sp * sp;
            const double m = e.a_m * (1 - e2) / (w2 * std::sqrt(w2)), n = e.a_m / std::sqrt(w2);
            const double ca = std::cos(deg_to_rad(azi)), sa = std::sin(deg_to_rad(azi));
            const double r = 1.0 / (ca * ca / m + sa * sa / n), psi = s / r;
            const double z_sphere = mu::kPi / 2 - std::atan2((r + h2) * std::cos(psi) - (r + h1),
                                                             (r + h2) * std::sin(psi));
            EXPECT_NEAR(rad_to_arcsec(z - z_sphere), 0.0, 0.01);
            worst_sphere = std::max(worst_sphere, std::abs(rad_to_arcsec(z - z_sphere)));
            // The surveyor's formula z = π/2 − atan(Δh/s) + s/(2R): it neglects
            // h/R in the horizontal distance and the factor cos²(elevation) on
            // the curvature term, so it is good to some arc-seconds only.
            const double z_simple = mu::kPi / 2 - std::atan((h2 - h1) / s) + s / (2 * r);
            const double bound = std::abs(std::sin(2 * std::atan((h2 - h1) / s))) / 2 *
                                     (std::abs(h1) + std::abs(h2)) / r +
                                 s / (2 * r) * std::pow(std::sin(std::atan((h2 - h1) / s)), 2);
            EXPECT_LE(std::abs(z - z_simple), 1.05 * bound + 1e-8);
            if (s == 1000.0 && std::abs(slope_deg) <= 20.0)
              worst_simple = std::max(worst_simple, std::abs(rad_to_arcsec(z - z_simple)));
          }
  std::printf(
      "[ sight    ] zenith distance vs LocalCartesian: max %.2e\"; vs the exact spherical "
      "triangle: max %.4f\" (lines to 3 km, slopes to 70 deg); z = 90 deg - atan(dh/s) + "
      "s/2R: max %.1f\" (1 km, slopes to 20 deg)\n",
      worst_lc, worst_sphere, worst_simple);
}

TEST(Sight, WorkedExample) {
  // Two points 1 km apart at equal heights: the chord dips by s/(2R) below
  // the horizon (16.2″ for R = 6371 km).
  const mg::Ellipsoid e = mg::cgcs2000();
  const GeographicLib::Geodesic geod(e.a_m, e.f);
  double lat2, lon2;
  geod.Direct(32.6, 117.2, 45.0, 1000.0, lat2, lon2);
  const double z = mg::sight_zenith_distance_rad({deg_to_rad(32.6), deg_to_rad(117.2), 100.0},
                                                 {deg_to_rad(lat2), deg_to_rad(lon2), 100.0}, e);
  EXPECT_GT(z, mu::kPi / 2);
  EXPECT_NEAR(rad_to_arcsec(z - mu::kPi / 2), 1000.0 / (2 * 6371000.0) / mu::kArcsecond, 0.2);
  // Upwards < 90°, downwards > 90°.
  EXPECT_LT(mg::sight_zenith_distance_rad({deg_to_rad(32.6), deg_to_rad(117.2), 100.0},
                                          {deg_to_rad(lat2), deg_to_rad(lon2), 200.0}, e),
            mu::kPi / 2);
}

TEST(Sight, BadInput) {
  using meridian::InputError;
  const mg::Ellipsoid e = mg::wgs84();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const mg::GeodeticPosition p{0.6, 2.0, 10.0};
  EXPECT_THROW(mg::sight_zenith_distance_rad(p, p, e), InputError);
  EXPECT_THROW(mg::sight_zenith_distance_rad(p, {0.6, 2.0, nan}, e), InputError);
  EXPECT_THROW(mg::sight_zenith_distance_rad({1.6, 2.0, 0.0}, p, e), InputError);
  EXPECT_THROW(mg::sight_zenith_distance_rad(p, {0.6001, 2.0, 0.0}, mg::Ellipsoid{"x", -1.0, 0.0}),
               InputError);
}
