#include <gtest/gtest.h>

#include <GeographicLib/Ellipsoid.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"

namespace mg = meridian::geodesy;
namespace mu = meridian::units;
using mu::deg_to_rad;
using mu::rad_to_arcsec;

namespace {

// Classical arc-to-chord formula (radians), k0 = 1:
//   δ ≈ −(x_D − x_C)(2y'_C + y'_D) / (6R²),  y' = easting − FE,
// R² = M·N at the mean latitude of the line.
double classical(const mg::TransverseMercatorGrid& g, double xc, double yc, double xd,
                 double yd) {
  const mg::GridDefinition& d = g.definition();
  const GeographicLib::Ellipsoid e(d.ellipsoid.a_m, d.ellipsoid.f);
  const double lat_m = g.reverse((xc + xd) / 2, (yc + yd) / 2).lat_rad / mu::kDegree;
  const double r2 = e.MeridionalCurvatureRadius(lat_m) * e.TransverseCurvatureRadius(lat_m);
  const double k0 = d.scale_factor;
  const double yc1 = (yc - d.false_easting_m) / k0;
  const double yd1 = (yd - d.false_easting_m) / k0;
  return -(xd - xc) / k0 * (2 * yc1 + yd1) / (6 * r2);
}

mg::TransverseMercatorGrid gk(int zone, bool prefix = false) {
  return mg::TransverseMercatorGrid(mg::gauss_kruger_6(zone, mg::cgcs2000(), prefix));
}

}  // namespace

// For 1 km lines up to 250 km from the central meridian the neglected terms
// (relative order (y/R)², plus η² terms for east-west lines) stay below
// 0.0004″; the tolerance is 0.001″.
TEST(ArcToChord, AgreesWithClassicalFormulaFor1kmLines) {
  constexpr double kTol_arcsec = 1e-3;
  const mg::TransverseMercatorGrid g = gk(20);  // CM 117° E
  double worst = 0;
  for (double lat : {30.0, 60.0, -30.0}) {
    const double x0 = g.forward(deg_to_rad(lat), deg_to_rad(117)).x_north_m;
    for (double yp : {-150e3, -20e3, 20e3, 50e3, 150e3, 250e3}) {
      for (double az : {0.0, 45.0, 90.0, 135.0, 180.0, 300.0}) {
        SCOPED_TRACE(testing::Message() << "lat " << lat << " y' " << yp << " az " << az);
        const double xc = x0, yc = 500000 + yp;
        const double xd = xc + 1000 * std::cos(deg_to_rad(az));
        const double yd = yc + 1000 * std::sin(deg_to_rad(az));
        const double rigorous = mg::arc_to_chord(g, xc, yc, xd, yd);
        const double approx = classical(g, xc, yc, xd, yd);
        EXPECT_NEAR(rad_to_arcsec(rigorous), rad_to_arcsec(approx), kTol_arcsec);
        worst = std::max(worst, std::abs(rad_to_arcsec(rigorous - approx)));
      }
    }
  }
  std::printf("[ geodesy  ] arc-to-chord: max |rigorous - classical| = %.6f\" (1 km lines)\n",
              worst);
}

TEST(ArcToChord, SignConvention) {
  // Projected geodesics are concave towards the central meridian: heading
  // north east of the CM the geodesic leaves C east of the chord, so
  // T_chord < α − γ and δ < 0, in either hemisphere.
  const mg::TransverseMercatorGrid g = gk(20);
  const double x = g.forward(deg_to_rad(35), deg_to_rad(117)).x_north_m;
  const double delta_ne = mg::arc_to_chord(g, x, 600000, x + 1000, 600000);
  EXPECT_LT(delta_ne, 0);
  EXPECT_NEAR(rad_to_arcsec(delta_ne), -0.254, 0.002);  // −1000·300000/(6R²)·ρ
  EXPECT_GT(mg::arc_to_chord(g, x, 600000, x - 1000, 600000), 0);   // heading south
  EXPECT_GT(mg::arc_to_chord(g, x, 400000, x + 1000, 400000), 0);   // north, west of CM
  const mg::TransverseMercatorGrid s(mg::utm(56, false));
  const double xs = s.forward(deg_to_rad(-33.9), deg_to_rad(153)).x_north_m;
  EXPECT_LT(mg::arc_to_chord(s, xs, 600000, xs + 1000, 600000), 0);  // south hemisphere too

  // Definition: T_chord = α − γ + δ, with α from C to D.
  const double xc = x, yc = 600000, xd = x + 800, yd = 600000 + 600;
  const double t_chord = std::atan2(yd - yc, xd - xc);
  const double delta = mg::arc_to_chord(g, xc, yc, xd, yd);
  const double gamma = g.reverse(xc, yc).convergence_rad;
  const double alpha = t_chord + gamma - delta;
  EXPECT_GT(alpha, t_chord);  // γ ≈ +0.4° east of the CM dominates
}

TEST(ArcToChord, CentralMeridianIsStraight) {
  const mg::TransverseMercatorGrid g = gk(20);
  const double x = g.forward(deg_to_rad(40), deg_to_rad(117)).x_north_m;
  EXPECT_NEAR(mg::arc_to_chord(g, x, 500000, x + 5000, 500000), 0, 1e-12);
  EXPECT_NEAR(mg::arc_to_chord(g, x, 500000, x - 5000, 500000), 0, 1e-12);
}

TEST(ArcToChord, PrefixAndUtmScale) {
  // The zone prefix changes nothing; UTM's k0 enters the classical formula
  // through y'/k0 and the agreement holds there too.
  const mg::TransverseMercatorGrid plain = gk(20), pref = gk(20, true);
  const double x = plain.forward(deg_to_rad(40), deg_to_rad(118)).x_north_m;
  EXPECT_NEAR(mg::arc_to_chord(plain, x, 585000, x + 700, 585300),
              mg::arc_to_chord(pref, x, 20585000, x + 700, 20585300), 1e-11);
  const mg::TransverseMercatorGrid u(mg::utm(50, true));
  const double xu = u.forward(deg_to_rad(40), deg_to_rad(118)).x_north_m;
  EXPECT_NEAR(rad_to_arcsec(mg::arc_to_chord(u, xu, 680000, xu + 1000, 680000)),
              rad_to_arcsec(classical(u, xu, 680000, xu + 1000, 680000)), 1e-3);
}

TEST(ArcToChord, BadInputThrows) {
  const mg::TransverseMercatorGrid g = gk(20);
  EXPECT_THROW(mg::arc_to_chord(g, 4e6, 500000, 4e6, 500000), meridian::InputError);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mg::arc_to_chord(g, nan, 500000, 4e6, 500000), meridian::InputError);
  EXPECT_THROW(mg::arc_to_chord(g, 4e6, 500000, 4e6, nan), meridian::InputError);
  EXPECT_THROW(mg::arc_to_chord(g, 4e6, 500000, 4e6, 9e6), meridian::InputError);
}
