#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"

namespace mg = meridian::geodesy;
namespace mu = meridian::units;
using mu::deg_to_rad;
using mu::rad_to_arcsec;

namespace {

std::string message_of(const auto& f) {
  try {
    f();
  } catch (const meridian::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace

TEST(GridZones, GaussKruger6) {
  EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(116.4)), 20);
  EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(114.0)), 20);  // western edge belongs to the zone
  EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(113.999999)), 19);
  EXPECT_EQ(mg::gauss_kruger_6_zone(0.0), 1);
  EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(359.9)), 60);
  EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(-0.1)), 60);
  EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(360.0 + 116.4)), 20);
  for (int n = 1; n <= 60; ++n) {
    SCOPED_TRACE(n);
    EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(6.0 * n - 6.0)), n);  // boundary, rounded
    EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(6.0 * n - 3.0)), n);  // central meridian
    EXPECT_EQ(mg::gauss_kruger_6_zone(deg_to_rad(6.0 * n - 1e-7)), n);
  }
}

TEST(GridZones, GaussKruger3) {
  EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(114.3)), 38);
  EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(112.5)), 38);
  EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(112.4999999)), 37);
  EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(115.4999999)), 38);
  EXPECT_EQ(mg::gauss_kruger_3_zone(0.0), 120);  // CM 360° = 0°
  EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(1.5)), 1);
  EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(358.5)), 120);
  EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(-1.0)), 120);
  for (int n = 1; n <= 120; ++n) {
    SCOPED_TRACE(n);
    EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(3.0 * n - 1.5)), n);
    EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(3.0 * n)), n);
    EXPECT_EQ(mg::gauss_kruger_3_zone(deg_to_rad(3.0 * n + 1.4999999)), n);
  }
}

TEST(GridZones, Utm) {
  EXPECT_EQ(mg::utm_zone(deg_to_rad(116.4)), 50);
  EXPECT_EQ(mg::utm_zone(deg_to_rad(151.2)), 56);
  EXPECT_EQ(mg::utm_zone(deg_to_rad(-180.0)), 1);
  EXPECT_EQ(mg::utm_zone(deg_to_rad(180.0)), 1);
  EXPECT_EQ(mg::utm_zone(deg_to_rad(179.99)), 60);
  EXPECT_EQ(mg::utm_zone(0.0), 31);
  EXPECT_EQ(mg::utm_zone(deg_to_rad(-0.0001)), 30);
  EXPECT_EQ(mg::utm_zone(deg_to_rad(6.0)), 32);
  for (int n = 1; n <= 60; ++n) {
    SCOPED_TRACE(n);
    EXPECT_EQ(mg::utm_zone(deg_to_rad(6.0 * n - 186.0)), n);
    EXPECT_EQ(mg::utm_zone(deg_to_rad(6.0 * n - 183.0)), n);
  }
}

TEST(GridZones, NonFiniteLongitudeThrows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(mg::gauss_kruger_3_zone(nan), meridian::InputError);
  EXPECT_THROW(mg::gauss_kruger_6_zone(inf), meridian::InputError);
  EXPECT_THROW(mg::utm_zone(-inf), meridian::InputError);
}

TEST(GridDefinitions, StandardZones) {
  const mg::GridDefinition gk3 = mg::gauss_kruger_3(38, mg::cgcs2000(), true);
  EXPECT_EQ(gk3.system, mg::ZoneSystem::GaussKruger3);
  EXPECT_DOUBLE_EQ(gk3.central_meridian_rad, deg_to_rad(114.0));
  EXPECT_EQ(gk3.scale_factor, 1.0);
  EXPECT_EQ(gk3.false_easting_m, 500000.0);
  EXPECT_EQ(gk3.false_northing_m, 0.0);
  EXPECT_TRUE(gk3.zone_prefix);
  EXPECT_EQ(gk3.ellipsoid.name, "CGCS2000");

  const mg::GridDefinition gk6 = mg::gauss_kruger_6(20, mg::krassovsky1940());
  EXPECT_DOUBLE_EQ(gk6.central_meridian_rad, deg_to_rad(117.0));
  EXPECT_FALSE(gk6.zone_prefix);

  const mg::GridDefinition s = mg::utm(56, false);
  EXPECT_DOUBLE_EQ(s.central_meridian_rad, deg_to_rad(153.0));
  EXPECT_EQ(s.scale_factor, 0.9996);
  EXPECT_EQ(s.false_northing_m, 10000000.0);
  EXPECT_EQ(s.ellipsoid.name, "WGS84");
  EXPECT_EQ(mg::utm(56, true).false_northing_m, 0.0);
  EXPECT_DOUBLE_EQ(mg::utm(1, true).central_meridian_rad, deg_to_rad(-177.0));
}

TEST(GridDefinitions, Describe) {
  EXPECT_EQ(mg::describe(mg::gauss_kruger_3(38, mg::cgcs2000())),
            "Gauss-Kruger 3deg zone 38 (CM 114E), CGCS2000");
  EXPECT_EQ(mg::describe(mg::gauss_kruger_6(20, mg::krassovsky1940(), true)),
            "Gauss-Kruger 6deg zone 20 (CM 117E), Krassovsky1940, eastings prefixed with zone 20");
  EXPECT_EQ(mg::describe(mg::utm(50, true)), "UTM zone 50N (CM 117E), WGS84");
  EXPECT_EQ(mg::describe(mg::utm(1, false)), "UTM zone 1S (CM 177W), WGS84");
  mg::GridDefinition c;
  c.system = mg::ZoneSystem::Custom;
  c.central_meridian_rad = deg_to_rad(117.5);
  c.scale_factor = 0.9999;
  c.false_easting_m = 300000;
  c.ellipsoid = mg::iag75();
  EXPECT_EQ(mg::describe(c),
            "Transverse Mercator (CM 117.5E, k0 0.9999, FE 300000 m, FN 0 m), IAG75");
}

TEST(GridDefinitions, InvalidDefinitionsThrow) {
  EXPECT_THROW(mg::gauss_kruger_3(0, mg::cgcs2000()), meridian::InputError);
  EXPECT_THROW(mg::gauss_kruger_3(121, mg::cgcs2000()), meridian::InputError);
  EXPECT_THROW(mg::gauss_kruger_6(61, mg::cgcs2000()), meridian::InputError);
  EXPECT_THROW(mg::utm(0, true), meridian::InputError);
  EXPECT_NE(message_of([] { mg::gauss_kruger_3(121, mg::cgcs2000()); }).find("121"),
            std::string::npos);

  auto rejects = [](auto mutate) {
    mg::GridDefinition d = mg::gauss_kruger_3(38, mg::cgcs2000());
    mutate(d);
    return message_of([&] { mg::TransverseMercatorGrid g(d); });
  };
  EXPECT_NE(rejects([](mg::GridDefinition& d) { d.zone = 39; }).find("114"), std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) { d.zone = 0; }).find("zone 0"), std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) { d.scale_factor = 0.9996; }).find("0.9996"),
            std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) { d.false_easting_m = 38500000; })
                .find("38500000"),
            std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) { d.ellipsoid.a_m = -1; }).find("-1"),
            std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) { d.ellipsoid.f = 298.257; }).find("298.257"),
            std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) {
              d.false_northing_m = std::numeric_limits<double>::quiet_NaN();
            }).find("false northing"),
            std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) {
              d.system = mg::ZoneSystem::Custom;
              d.scale_factor = 0;
            }).find("k0 = 0"),
            std::string::npos);
  EXPECT_NE(rejects([](mg::GridDefinition& d) {
              d.system = mg::ZoneSystem::Custom;
              d.zone = 0;
              d.zone_prefix = true;
            }).find("zone 0"),
            std::string::npos);
  mg::GridDefinition south = mg::utm(56, false);
  south.false_northing_m = 0;
  EXPECT_THROW(mg::TransverseMercatorGrid{south}, meridian::InputError);

  // Accepted: zone 120's central meridian written as 0° instead of 360°,
  // and a Custom grid with any central meridian, k0 and false origin.
  mg::GridDefinition z120 = mg::gauss_kruger_3(120, mg::wgs84());
  z120.central_meridian_rad = 0.0;
  EXPECT_NO_THROW(mg::TransverseMercatorGrid{z120});
  mg::GridDefinition custom = mg::gauss_kruger_3(38, mg::cgcs2000());
  custom.system = mg::ZoneSystem::Custom;
  custom.central_meridian_rad = deg_to_rad(114.25);
  custom.scale_factor = 0.9999;
  custom.false_northing_m = -3000000;
  EXPECT_NO_THROW(mg::TransverseMercatorGrid{custom});
}

TEST(GridProjection, BadInputThrows) {
  const mg::TransverseMercatorGrid g(mg::gauss_kruger_3(38, mg::cgcs2000()));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(g.forward(nan, deg_to_rad(114)), meridian::InputError);
  EXPECT_THROW(g.forward(deg_to_rad(30), inf), meridian::InputError);
  EXPECT_NE(message_of([&] { g.forward(deg_to_rad(91), deg_to_rad(114)); }).find("91"),
            std::string::npos);
  EXPECT_THROW(g.forward(deg_to_rad(-90.001), deg_to_rad(114)), meridian::InputError);
  const std::string far = message_of([&] { g.forward(deg_to_rad(30), deg_to_rad(160)); });
  EXPECT_NE(far.find("46.000000 deg from the central meridian"), std::string::npos) << far;
  EXPECT_THROW(g.forward(deg_to_rad(30), deg_to_rad(114 - 45.5)), meridian::InputError);
  EXPECT_NO_THROW(g.forward(deg_to_rad(30), deg_to_rad(114 + 44.9)));
  EXPECT_NO_THROW(g.forward(deg_to_rad(90), deg_to_rad(114)));
  EXPECT_NO_THROW(g.forward(-mu::kPi / 2, deg_to_rad(130)));

  EXPECT_THROW(g.reverse(nan, 500000), meridian::InputError);
  EXPECT_THROW(g.reverse(3e6, inf), meridian::InputError);
  // 7000 km east of the central meridian: outside the series' domain.
  EXPECT_NE(message_of([&] { g.reverse(0, 7.5e6); }).find("7000 km"), std::string::npos);
  // 5900 km east on the equator is about 47° from the central meridian.
  EXPECT_NE(message_of([&] { g.reverse(0, 6.4e6); }).find("deg of longitude"),
            std::string::npos);
  // Beyond the pole along the central meridian: longitude flips by 180°.
  EXPECT_THROW(g.reverse(10.5e6, 500000), meridian::InputError);
}

TEST(GridProjection, RoundTrips) {
  // geographic → grid → geographic to 1e-12 rad (achieved: ~1e-14 rad).
  // grid → geographic → grid to 5e-9 m, not 1e-9 m: that is the floor of
  // double precision here, not a defect. A latitude in radians is quantised
  // to ~0.7 nm on the ground and a northing of 4–8 000 km to 0.93 nm (1.86 nm
  // above 8 389 km, e.g. UTM south), and GeographicLib::TransverseMercator
  // called directly in degrees already shows 1.9 nm; the wrapper's degree↔
  // radian conversion and false-origin additions add about one ulp more
  // (worst seen: 3.7 nm = 4–6 ulps).
  constexpr double kTolGrid_m = 5e-9;
  const mg::GridDefinition defs[] = {
      mg::gauss_kruger_3(38, mg::cgcs2000()),      mg::gauss_kruger_3(38, mg::cgcs2000(), true),
      mg::gauss_kruger_3(120, mg::wgs84()),        mg::gauss_kruger_6(20, mg::krassovsky1940()),
      mg::gauss_kruger_6(60, mg::iag75(), true),   mg::utm(50, true),
      mg::utm(56, false),                          mg::utm(1, false, mg::grs80()),
  };
  double max_rad = 0, max_m = 0;
  for (const mg::GridDefinition& d : defs) {
    SCOPED_TRACE(mg::describe(d));
    const mg::TransverseMercatorGrid g(d);
    const double half_width = d.system == mg::ZoneSystem::GaussKruger3 ? 1.6 : 3.5;
    for (double lat = -88; lat <= 88; lat += 4) {
      for (double dl = -half_width; dl <= half_width; dl += half_width / 7) {
        const double phi = deg_to_rad(lat);
        const double lam = d.central_meridian_rad + deg_to_rad(dl);
        const mg::GridPoint p = g.forward(phi, lam);
        const mg::GeographicPoint q = g.reverse(p.x_north_m, p.y_east_m);
        EXPECT_NEAR(q.lat_rad, phi, 1e-12);
        EXPECT_NEAR(q.lon_rad, lam, 1e-12);
        EXPECT_NEAR(q.convergence_rad, p.convergence_rad, 1e-12);
        EXPECT_NEAR(q.scale, p.scale, 1e-12);
        max_rad = std::max({max_rad, std::abs(q.lat_rad - phi), std::abs(q.lon_rad - lam)});

        const mg::GridPoint r = g.forward(q.lat_rad, q.lon_rad);
        EXPECT_NEAR(r.x_north_m, p.x_north_m, kTolGrid_m);
        EXPECT_NEAR(r.y_east_m, p.y_east_m, kTolGrid_m);
        max_m = std::max({max_m, std::abs(r.x_north_m - p.x_north_m),
                          std::abs(r.y_east_m - p.y_east_m)});
      }
    }
  }
  std::printf("[ geodesy  ] round trip: max %.2e rad, max %.2e m\n", max_rad, max_m);
}

TEST(GridProjection, ZonePrefixAddsZoneTimesMillion) {
  const mg::TransverseMercatorGrid plain(mg::gauss_kruger_3(38, mg::cgcs2000()));
  const mg::TransverseMercatorGrid pref(mg::gauss_kruger_3(38, mg::cgcs2000(), true));
  const mg::GridPoint a = plain.forward(deg_to_rad(30.5), deg_to_rad(114.3));
  const mg::GridPoint b = pref.forward(deg_to_rad(30.5), deg_to_rad(114.3));
  EXPECT_EQ(a.x_north_m, b.x_north_m);
  EXPECT_NEAR(b.y_east_m - a.y_east_m, 38e6, 1e-8);
  EXPECT_GT(b.y_east_m, 38.5e6);
  const mg::GeographicPoint q = pref.reverse(b.x_north_m, b.y_east_m);
  EXPECT_NEAR(q.lon_rad, deg_to_rad(114.3), 1e-12);
}

TEST(GridProjection, CentralMeridianScaleAndPole) {
  const mg::TransverseMercatorGrid u(mg::utm(50, true));
  const mg::GridPoint cm = u.forward(deg_to_rad(40), deg_to_rad(117));
  EXPECT_NEAR(cm.y_east_m, 500000.0, 1e-9);
  EXPECT_NEAR(cm.scale, 0.9996, 1e-15);
  EXPECT_EQ(cm.convergence_rad, 0.0);
  EXPECT_GT(u.forward(deg_to_rad(40), deg_to_rad(120)).scale, 0.9996);
  const mg::TransverseMercatorGrid gk(mg::gauss_kruger_6(20, mg::krassovsky1940()));
  EXPECT_NEAR(gk.forward(deg_to_rad(40), deg_to_rad(117)).scale, 1.0, 1e-15);
  EXPECT_NEAR(gk.forward(0, deg_to_rad(117)).x_north_m, 0.0, 1e-9);
}

TEST(GridConvergence, SignConvention) {
  // Bearing of grid north clockwise from true north: positive east of the
  // central meridian in the north, negative west; reversed in the south.
  const mg::TransverseMercatorGrid gk(mg::gauss_kruger_3(38, mg::cgcs2000()));
  const double east = gk.forward(deg_to_rad(30), deg_to_rad(115)).convergence_rad;
  const double west = gk.forward(deg_to_rad(30), deg_to_rad(113)).convergence_rad;
  EXPECT_GT(east, 0);
  EXPECT_LT(west, 0);
  EXPECT_NEAR(east, -west, 1e-15);
  // The spherical closed form γ = atan(tan Δλ · sin φ) differs from the
  // ellipsoidal value by terms in Δλ³η², here 0.002″.
  EXPECT_NEAR(rad_to_arcsec(east),
              rad_to_arcsec(std::atan(std::tan(deg_to_rad(1)) * std::sin(deg_to_rad(30)))), 0.01);
  EXPECT_NEAR(rad_to_arcsec(east), 1800.139, 5e-4);  // the example in grid.hpp and geodesy.md

  const mg::TransverseMercatorGrid s(mg::utm(56, false));
  EXPECT_LT(s.forward(deg_to_rad(-33.87), deg_to_rad(154.5)).convergence_rad, 0);
  EXPECT_GT(s.forward(deg_to_rad(-33.87), deg_to_rad(151.21)).convergence_rad, 0);

  // Applying it: a line with geodetic azimuth α has grid bearing α − γ; east
  // of the CM in the north grid north lies east of true north, so a line
  // pointing at grid north has a geodetic azimuth equal to γ > 0.
  const mg::GridPoint p = gk.forward(deg_to_rad(30), deg_to_rad(115));
  const mg::GeographicPoint up = gk.reverse(p.x_north_m + 100.0, p.y_east_m);
  EXPECT_GT(up.lon_rad, deg_to_rad(115));  // moving grid-north drifts east
}

TEST(GridAzimuth, QuadrantsSwapAndErrors) {
  using meridian::geodesy::grid_azimuth;
  // C (0, 0) to D (x -1, y +1): south-east, 135 deg; D to C: 315 deg.
  EXPECT_NEAR(grid_azimuth(0, 0, -1, 1), deg_to_rad(135.0), 1e-15);
  EXPECT_NEAR(grid_azimuth(-1, 1, 0, 0), deg_to_rad(315.0), 1e-15);
  EXPECT_NEAR(grid_azimuth(10, 10, 20, 10), 0.0, 0.0);              // due north
  EXPECT_NEAR(grid_azimuth(10, 10, 10, 0), deg_to_rad(270.0), 1e-15);  // due west
  EXPECT_THROW(grid_azimuth(5, 5, 5, 5), meridian::InputError);
  EXPECT_THROW(grid_azimuth(5, std::numeric_limits<double>::quiet_NaN(), 6, 5), meridian::InputError);
}

TEST(GridAzimuth, RoundingBoundsEveryCornerOfTheRoundingBox) {
  using meridian::geodesy::grid_azimuth;
  // Brute force: every coordinate moved by +-half a unit (1 mm booked: 0.0005 m), the largest
  // change of the azimuth against the linearised bound.
  const double xc = 3611402.317, yc = 479218.654, xd = 3612288.905, yd = 479957.112, h = 0.0005;
  const double t0 = grid_azimuth(xc, yc, xd, yd);
  double largest = 0;
  for (int m = 0; m < 16; ++m) {
    const auto s = [&](int bit) { return (m >> bit & 1) ? h : -h; };
    largest = std::max(largest, std::fabs(grid_azimuth(xc + s(0), yc + s(1), xd + s(2), yd + s(3)) - t0));
  }
  const double bound = meridian::geodesy::grid_azimuth_rounding(xc, yc, xd, yd, 2 * h, 2 * h);
  EXPECT_NEAR(bound, largest, 1e-6 * largest);
  EXPECT_NEAR(rad_to_arcsec(bound), 0.25177, 0.00001);  // 1154 m line, both points to 1 mm (by hand)
}

TEST(GridAzimuth, HalfTheLastDigitAsWritten) {
  using meridian::geodesy::half_last_digit_m;
  EXPECT_DOUBLE_EQ(half_last_digit_m("3611402.310"), 0.0005);  // trailing zero kept: booked to 1 mm
  EXPECT_DOUBLE_EQ(half_last_digit_m("3611402.31"), 0.005);
  EXPECT_DOUBLE_EQ(half_last_digit_m("39479218"), 0.5);
  EXPECT_DOUBLE_EQ(half_last_digit_m("3.6e6"), 0.5);
}
