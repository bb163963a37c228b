// The normal field against GeographicLib's NormalGravity (independent code).

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/NormalGravity.hpp>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/normal_gravity.hpp"
#include "test_units.hpp"

namespace {

using gtest_gravity::kDeg;
using meridian::gravity::NormalGravity;

TEST(NormalGravity, Wgs84ConstantsMatchGeographicLib) {
  const NormalGravity n(meridian::gravity::wgs84_normal_field());
  const GeographicLib::NormalGravity& g = GeographicLib::NormalGravity::WGS84();
  EXPECT_NEAR(n.j2(), g.DynamicalFormFactor(2), 1e-18);
  for (int k = 0; k <= 20; ++k) EXPECT_NEAR(n.jn(k), g.DynamicalFormFactor(k), 1e-18 + 1e-14 * std::abs(g.DynamicalFormFactor(k))) << k;
  EXPECT_NEAR(n.gamma_equator_m_s2(), g.EquatorialGravity(), 1e-13);
  EXPECT_NEAR(n.gamma_equator_m_s2(), 9.7803253359, 1e-10);  // WGS84 defining table (NIMA TR8350.2)
  EXPECT_NEAR(n.gamma_pole_m_s2(), 9.8321849379, 1e-10);
}

TEST(NormalGravity, Grs80FlatteningFromJ2MatchesGeographicLib) {
  const NormalGravity n(meridian::gravity::grs80_normal_field());
  const GeographicLib::NormalGravity& g = GeographicLib::NormalGravity::GRS80();
  EXPECT_NEAR(n.flattening(), g.Flattening(), 1e-15);
  EXPECT_NEAR(1 / n.flattening(), 298.257222101, 1e-8);  // Moritz (2000), GRS80
}

TEST(NormalGravity, SurfaceGravityAndVectorMatchGeographicLib) {
  const NormalGravity n(meridian::gravity::wgs84_normal_field());
  const GeographicLib::NormalGravity& g = GeographicLib::NormalGravity::WGS84();
  const GeographicLib::Geocentric& earth = GeographicLib::Geocentric::WGS84();
  for (double lat = -90; lat <= 90; lat += 7.5) {
    EXPECT_NEAR(n.surface_gravity_m_s2(lat * kDeg), g.SurfaceGravity(lat), 1e-13) << lat;
    for (double h : {-12000.0, -500.0, 0.0, 3000.0, 10000.0, 400e3, 2e7}) {
      double x, y, z;
      earth.Forward(lat, 33.0, h, x, y, z);
      const auto e = n.to_ecef(lat * kDeg, 33.0 * kDeg, h);
      EXPECT_NEAR(e.x_m, x, 1e-8);
      EXPECT_NEAR(e.y_m, y, 1e-8);
      EXPECT_NEAR(e.z_m, z, 1e-8);
      double gx, gy, gz;
      g.U(x, y, z, gx, gy, gz);
      const auto v = n.gravity_vector_m_s2({x, y, z});
      EXPECT_NEAR(v.x_m, gx, 1e-13 * 10) << lat << " " << h;
      EXPECT_NEAR(v.y_m, gy, 1e-13 * 10) << lat << " " << h;
      EXPECT_NEAR(v.z_m, gz, 1e-13 * 10) << lat << " " << h;
    }
  }
}

TEST(NormalGravity, RejectsNonsense) {
  auto p = meridian::gravity::wgs84_normal_field();
  p.a_m = -1;
  EXPECT_THROW(NormalGravity{p}, meridian::InputError);
  p = meridian::gravity::wgs84_normal_field();
  p.flattening = 0.5;
  EXPECT_THROW(NormalGravity{p}, meridian::InputError);
}

}  // namespace
