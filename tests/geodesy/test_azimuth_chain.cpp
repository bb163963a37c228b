// The azimuth chain astronomic ↔ geodetic ↔ grid (geodesy/azimuth_chain.hpp).
// References: hand formulas (Laplace α = A − η·tan φ, T = α − γ + δ, σ in
// quadrature), and GeographicLib directly (Geodesic for the geodetic azimuth,
// TransverseMercator for the projected end points of the chord).

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/TransverseMercator.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <vector>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/azimuth_chain.hpp"
#include "meridian/geodesy/grid.hpp"

namespace mg = meridian::geodesy;
namespace mu = meridian::units;
using meridian::Uncertain;
using mg::AzimuthKind;
using mu::arcsec_to_rad;
using mu::deg_to_rad;
using mu::rad_to_arcsec;

namespace {

constexpr AzimuthKind kKinds[] = {AzimuthKind::Astronomic, AzimuthKind::Geodetic,
                                  AzimuthKind::Grid};

// Difference of two directions, reduced to [−π, π).
double angle_diff(double a, double b) { return meridian::wrap_signed_rad(a - b); }

Uncertain of_kind(const mg::AzimuthSteps& s, AzimuthKind k) {
  switch (k) {
    case AzimuthKind::Astronomic:
      return s.astronomic_rad;
    case AzimuthKind::Geodetic:
      return s.geodetic_rad;
    case AzimuthKind::Grid:
      return s.grid_rad;
  }
  return {};
}

std::vector<mg::AzimuthReduction> reductions() {
  const Uncertain eta{arcsec_to_rad(-4.2), arcsec_to_rad(0.5)};
  return {
      {deg_to_rad(37.85), eta, arcsec_to_rad(-3140.2), arcsec_to_rad(0.31)},
      {deg_to_rad(37.85), std::nullopt, arcsec_to_rad(-3140.2), arcsec_to_rad(0.31)},
      {deg_to_rad(37.85), eta, arcsec_to_rad(1500.0), std::nullopt},
      {deg_to_rad(-33.9), Uncertain{arcsec_to_rad(12.0), arcsec_to_rad(1.0)}, deg_to_rad(-1.2),
       arcsec_to_rad(-2.5)},
      {0.0, eta, 0.0, std::nullopt},
      {deg_to_rad(89.0), Uncertain{arcsec_to_rad(3.0), 0.0}, deg_to_rad(2.0), std::nullopt},
  };
}

}  // namespace

TEST(AzimuthChain, KindNames) {
  EXPECT_EQ(mg::to_string(AzimuthKind::Astronomic), "astronomic");
  EXPECT_EQ(mg::to_string(AzimuthKind::Geodetic), "geodetic");
  EXPECT_EQ(mg::to_string(AzimuthKind::Grid), "grid");
}

TEST(AzimuthChain, HandFormulas) {
  // α = A − η·tan φ, T = α − γ + δ.
  const double phi = deg_to_rad(37.85), eta = arcsec_to_rad(-4.2);
  const double gamma = arcsec_to_rad(-3140.2), delta = arcsec_to_rad(0.31);
  const double a = deg_to_rad(123.456);
  const mg::AzimuthSteps s =
      mg::azimuth_from_astronomic({a, 0.0}, {phi, Uncertain{eta, 0.0}, gamma, delta});
  const double alpha = a - eta * std::tan(phi);
  EXPECT_NEAR(s.astronomic_rad.value, a, 0.0);
  EXPECT_NEAR(rad_to_arcsec(s.geodetic_rad.value - alpha), 0.0, 1e-9);
  EXPECT_NEAR(rad_to_arcsec(s.grid_rad.value - (alpha - gamma + delta)), 0.0, 1e-9);
  EXPECT_NEAR(rad_to_arcsec(s.laplace_correction_rad), 4.2 * std::tan(phi), 1e-12);
  EXPECT_TRUE(s.laplace_applied);
  EXPECT_TRUE(s.arc_to_chord_applied);
  EXPECT_EQ(s.convergence_rad, gamma);
  EXPECT_EQ(s.arc_to_chord_rad, delta);
  // Not applied: α = A, δ = 0.
  const mg::AzimuthSteps n =
      mg::azimuth_from_astronomic({a, 0.0}, {phi, std::nullopt, gamma, std::nullopt});
  EXPECT_EQ(n.geodetic_rad.value, a);
  EXPECT_FALSE(n.laplace_applied);
  EXPECT_FALSE(n.arc_to_chord_applied);
  EXPECT_EQ(n.laplace_correction_rad, 0.0);
  EXPECT_EQ(n.arc_to_chord_rad, 0.0);
  EXPECT_NEAR(rad_to_arcsec(n.grid_rad.value - (a - gamma)), 0.0, 1e-9);
}

TEST(AzimuthChain, RoundTripsForEveryKind) {
  double worst = 0;
  for (const mg::AzimuthReduction& r : reductions())
    for (AzimuthKind from : kKinds)
      for (double v : {0.0, 1e-9, 0.7, 3.0, 2 * mu::kPi - 1e-9, -0.3, 7.1}) {
        SCOPED_TRACE(testing::Message()
                     << mg::to_string(from) << " " << v << " lat " << r.latitude_rad);
        const mg::AzimuthSteps s = mg::azimuth_steps(from, {v, arcsec_to_rad(2.0)}, r);
        for (AzimuthKind k : kKinds) {
          const Uncertain x = of_kind(s, k);
          EXPECT_GE(x.value, 0.0);
          EXPECT_LT(x.value, 2 * mu::kPi);
        }
        EXPECT_NEAR(angle_diff(of_kind(s, from).value, v), 0.0, 1e-15);
        // Start again from each kind of the result: every kind comes back.
        for (AzimuthKind k : kKinds) {
          const mg::AzimuthSteps t = mg::azimuth_steps(k, of_kind(s, k), r);
          for (AzimuthKind j : kKinds) {
            const double d = angle_diff(of_kind(t, j).value, of_kind(s, j).value);
            EXPECT_NEAR(d, 0.0, 4e-15) << mg::to_string(k) << " -> " << mg::to_string(j);
            worst = std::max(worst, std::abs(d));
          }
          EXPECT_EQ(t.laplace_correction_rad, s.laplace_correction_rad);
          EXPECT_EQ(t.laplace_applied, s.laplace_applied);
          EXPECT_EQ(t.arc_to_chord_applied, s.arc_to_chord_applied);
        }
      }
  std::printf("[ azimuth  ] round trips: max |diff| %.2e rad\n", worst);
}

TEST(AzimuthChain, Signs) {
  // η > 0 at φ = 45° N: α = A − η.
  const double eta = arcsec_to_rad(5.0);
  const mg::AzimuthSteps s = mg::azimuth_from_astronomic(
      {deg_to_rad(60.0), 0.0}, {deg_to_rad(45.0), Uncertain{eta, 0.0}, 0.0, std::nullopt});
  EXPECT_NEAR(rad_to_arcsec(angle_diff(s.geodetic_rad.value, deg_to_rad(60.0))), -5.0, 1e-9);
  // Inverse: a geodetic azimuth gives A = α + η.
  const mg::AzimuthSteps i =
      mg::azimuth_steps(AzimuthKind::Geodetic, {deg_to_rad(60.0), 0.0},
                        {deg_to_rad(45.0), Uncertain{eta, 0.0}, 0.0, std::nullopt});
  EXPECT_NEAR(rad_to_arcsec(angle_diff(i.astronomic_rad.value, deg_to_rad(60.0))), 5.0, 1e-9);
  // Southern hemisphere: tan φ < 0 flips it.
  const mg::AzimuthSteps south = mg::azimuth_from_astronomic(
      {deg_to_rad(60.0), 0.0}, {deg_to_rad(-45.0), Uncertain{eta, 0.0}, 0.0, std::nullopt});
  EXPECT_NEAR(rad_to_arcsec(angle_diff(south.geodetic_rad.value, deg_to_rad(60.0))), 5.0, 1e-9);

  // γ > 0 east of the central meridian in the north (a real grid): T < α.
  const mg::TransverseMercatorGrid grid(mg::gauss_kruger_3(38, mg::cgcs2000()));  // CM 114° E
  const mg::GridPoint east = grid.forward(deg_to_rad(30.6), deg_to_rad(115.2));
  ASSERT_GT(east.convergence_rad, 0.0);
  const mg::AzimuthSteps t =
      mg::azimuth_steps(AzimuthKind::Geodetic, {deg_to_rad(10.0), 0.0},
                        {deg_to_rad(30.6), std::nullopt, east.convergence_rad, std::nullopt});
  EXPECT_LT(angle_diff(t.grid_rad.value, t.geodetic_rad.value), 0.0);
  EXPECT_NEAR(angle_diff(t.grid_rad.value, t.geodetic_rad.value), -east.convergence_rad, 1e-15);
  // West of it γ < 0 and T > α.
  const mg::GridPoint west = grid.forward(deg_to_rad(30.6), deg_to_rad(112.8));
  ASSERT_LT(west.convergence_rad, 0.0);
  const mg::AzimuthSteps w =
      mg::azimuth_steps(AzimuthKind::Geodetic, {deg_to_rad(10.0), 0.0},
                        {deg_to_rad(30.6), std::nullopt, west.convergence_rad, std::nullopt});
  EXPECT_GT(angle_diff(w.grid_rad.value, w.geodetic_rad.value), 0.0);
}

TEST(AzimuthChain, SigmaPropagation) {
  const double phi = deg_to_rad(50.0), t = std::tan(phi);
  const double se = arcsec_to_rad(0.5), sg = arcsec_to_rad(3.0);
  const mg::AzimuthReduction r{phi, Uncertain{arcsec_to_rad(2.0), se}, deg_to_rad(0.4),
                               arcsec_to_rad(-0.2)};
  const double across = std::sqrt(sg * sg + t * se * t * se);
  // From A: α and T carry σ_A ⊕ tan φ·σ_η.
  const mg::AzimuthSteps a = mg::azimuth_steps(AzimuthKind::Astronomic, {1.0, sg}, r);
  EXPECT_EQ(a.astronomic_rad.sigma, sg);
  EXPECT_NEAR(a.geodetic_rad.sigma, across, 1e-20);
  EXPECT_NEAR(a.grid_rad.sigma, across, 1e-20);
  // From α or T: only A crosses the Laplace step.
  for (AzimuthKind k : {AzimuthKind::Geodetic, AzimuthKind::Grid}) {
    const mg::AzimuthSteps s = mg::azimuth_steps(k, {1.0, sg}, r);
    EXPECT_NEAR(s.astronomic_rad.sigma, across, 1e-20);
    EXPECT_EQ(s.geodetic_rad.sigma, sg);
    EXPECT_EQ(s.grid_rad.sigma, sg);
  }
  // Southern hemisphere: the σ term is |tan φ|·σ_η.
  mg::AzimuthReduction south = r;
  south.latitude_rad = -phi;
  EXPECT_NEAR(mg::azimuth_steps(AzimuthKind::Astronomic, {1.0, sg}, south).geodetic_rad.sigma,
              across, 1e-20);
  // Without η, or with σ_η = 0, every kind has the given σ.
  mg::AzimuthReduction none = r;
  none.eta_rad.reset();
  for (AzimuthKind k : kKinds) {
    const mg::AzimuthSteps s = mg::azimuth_steps(k, {1.0, sg}, none);
    EXPECT_EQ(s.astronomic_rad.sigma, sg);
    EXPECT_EQ(s.geodetic_rad.sigma, sg);
    EXPECT_EQ(s.grid_rad.sigma, sg);
  }
}

// The gyro reports must stay byte-identical to the code this chain replaced;
// these pin the floating-point order the header documents.
TEST(AzimuthChain, OperationOrder) {
  using meridian::wrap_positive_rad;
  const double phi = 0.6606, eta = -2.03e-5, gamma = -0.0152, delta = 1.5e-6;
  const mg::AzimuthReduction r{phi, Uncertain{eta, 2.4e-6}, gamma, delta};
  for (double v : {0.1234567890123, 3.3, 6.2831, -0.01}) {
    const double lc = -eta * std::tan(phi);
    const mg::AzimuthSteps f = mg::azimuth_steps(AzimuthKind::Astronomic, {v, 1e-5}, r);
    const double alpha = wrap_positive_rad(wrap_positive_rad(v) + lc);
    double t = alpha - gamma;
    t += delta;
    EXPECT_EQ(f.geodetic_rad.value, alpha);
    EXPECT_EQ(f.grid_rad.value, wrap_positive_rad(t));
    EXPECT_EQ(f.geodetic_rad.sigma, std::hypot(1e-5, std::tan(phi) * 2.4e-6));

    const mg::AzimuthSteps g = mg::azimuth_steps(AzimuthKind::Grid, {v, 1e-5}, r);
    double a = v + gamma;
    a -= delta;
    EXPECT_EQ(g.geodetic_rad.value, wrap_positive_rad(a));
    EXPECT_EQ(g.astronomic_rad.value, wrap_positive_rad(a + eta * std::tan(phi)));
    EXPECT_EQ(g.astronomic_rad.sigma, std::hypot(1e-5, 2.4e-6 * std::tan(phi)));

    const mg::AzimuthSteps d = mg::azimuth_steps(AzimuthKind::Geodetic, {v, 1e-5}, r);
    double tg = v - gamma;
    tg += delta;
    EXPECT_EQ(d.astronomic_rad.value, wrap_positive_rad(v + eta * std::tan(phi)));
    EXPECT_EQ(d.grid_rad.value, wrap_positive_rad(tg));
  }
}

TEST(AzimuthChain, LaplaceGuardAndBadInput) {
  using meridian::InputError;
  const auto with = [](double eta, double lat) {
    return mg::AzimuthReduction{lat, Uncertain{eta, 0.0}, 0.0, std::nullopt};
  };
  for (AzimuthKind k : kKinds) {
    SCOPED_TRACE(mg::to_string(k));
    // |η| > 0.01 rad (e.g. arc-seconds given as radians).
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, with(0.0101, 0.5)), InputError);
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, with(-4.2, 0.5)), InputError);
    EXPECT_NO_THROW(mg::azimuth_steps(k, {1.0, 0.0}, with(0.01, 0.5)));
    // φ = ±90°: tan φ unbounded.
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, with(1e-5, mu::kPi / 2)), InputError);
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, with(1e-5, -mu::kPi / 2)), InputError);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, with(nan, 0.5)), InputError);
    EXPECT_THROW(mg::azimuth_steps(k, {nan, 0.0}, with(0.0, 0.5)), InputError);
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, -1e-6}, with(0.0, 0.5)), InputError);
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, mg::AzimuthReduction{0.5, {}, nan, {}}),
                 InputError);
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, mg::AzimuthReduction{0.5, {}, 0.0, nan}),
                 InputError);
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, mg::AzimuthReduction{1.6, {}, 0.0, {}}),
                 InputError);
    EXPECT_THROW(
        mg::azimuth_steps(k, {1.0, 0.0}, mg::AzimuthReduction{0.5, Uncertain{1e-5, -1.0}, 0.0, {}}),
        InputError);
  }
}

// A line on a real grid: the chain's grid azimuth equals the azimuth of the
// projected chord, atan2(Δy, Δx), with α from GeographicLib::Geodesic, the
// end points from GeographicLib::TransverseMercator, γ from the grid and δ
// from geodesy::arc_to_chord. Also the inverse (grid → geodetic) and the
// Laplace step on the way (A built by hand as α + η·tan φ).
TEST(AzimuthChain, GridLineAgreesWithGeographicLib) {
  constexpr double kTol_arcsec = 1e-3;
  const mg::GridDefinition def = mg::gauss_kruger_3(38, mg::cgcs2000());  // CM 114° E
  const mg::TransverseMercatorGrid grid(def);
  const GeographicLib::Geodesic geod(def.ellipsoid.a_m, def.ellipsoid.f);
  const GeographicLib::TransverseMercator tm(def.ellipsoid.a_m, def.ellipsoid.f, def.scale_factor);
  const double lon0_deg = def.central_meridian_rad / mu::kDegree;
  auto project = [&](double lat_deg, double lon_deg, double& x_north, double& y_east) {
    double e, n, g, k;
    tm.Forward(lon0_deg, lat_deg, lon_deg, e, n, g, k);
    x_north = n + def.false_northing_m;
    y_east = e + def.false_easting_m;
  };
  const Uncertain eta{arcsec_to_rad(-4.2), arcsec_to_rad(0.5)};
  double worst_fwd = 0, worst_inv = 0, worst_astro = 0, worst_delta = 0;
  struct Station {
    double lat_deg, lon_deg;
  };
  for (const Station c : {Station{37.85, 112.55}, Station{30.5928, 114.3055}, Station{45.1, 115.45},
                          Station{35.0, 114.0}})
    for (double s12 : {500.0, 3000.0, 15000.0})
      for (double azi : {0.0, 37.0, 90.0, 181.0, 270.0, 333.3}) {
        SCOPED_TRACE(testing::Message()
                     << c.lat_deg << " " << c.lon_deg << " s " << s12 << " azi " << azi);
        double lat_d, lon_d;
        geod.Direct(c.lat_deg, c.lon_deg, azi, s12, lat_d, lon_d);
        double s, azi1, azi2;
        geod.Inverse(c.lat_deg, c.lon_deg, lat_d, lon_d, s, azi1, azi2);
        const double alpha = deg_to_rad(azi1);
        double xc, yc, xd, yd;
        project(c.lat_deg, c.lon_deg, xc, yc);
        project(lat_d, lon_d, xd, yd);
        const double chord = meridian::wrap_positive_rad(std::atan2(yd - yc, xd - xc));

        const double phi = deg_to_rad(c.lat_deg);
        const mg::GridPoint gc = grid.forward(phi, deg_to_rad(c.lon_deg));
        const double delta = mg::arc_to_chord(grid, gc.x_north_m, gc.y_east_m, xd, yd);
        const mg::AzimuthReduction r{phi, eta, gc.convergence_rad, delta};

        const double fwd = angle_diff(
            mg::azimuth_steps(AzimuthKind::Geodetic, {alpha, 0.0}, r).grid_rad.value, chord);
        const double a = alpha + eta.value * std::tan(phi);
        const double astro =
            angle_diff(mg::azimuth_from_astronomic({a, 0.0}, r).grid_rad.value, chord);
        const mg::AzimuthSteps inv = mg::azimuth_steps(AzimuthKind::Grid, {chord, 0.0}, r);
        const double back = angle_diff(inv.geodetic_rad.value, alpha);
        EXPECT_NEAR(rad_to_arcsec(fwd), 0.0, kTol_arcsec);
        EXPECT_NEAR(rad_to_arcsec(astro), 0.0, kTol_arcsec);
        EXPECT_NEAR(rad_to_arcsec(back), 0.0, kTol_arcsec);
        EXPECT_NEAR(rad_to_arcsec(angle_diff(inv.astronomic_rad.value, a)), 0.0, kTol_arcsec);
        worst_fwd = std::max(worst_fwd, std::abs(rad_to_arcsec(fwd)));
        worst_astro = std::max(worst_astro, std::abs(rad_to_arcsec(astro)));
        worst_inv = std::max(worst_inv, std::abs(rad_to_arcsec(back)));
        // Without δ the chain gives the grid azimuth of the projected geodesic's
        // tangent, which differs from the chord by δ (up to ~5″ here).
        const mg::AzimuthReduction no_delta{phi, eta, gc.convergence_rad, std::nullopt};
        EXPECT_NEAR(
            angle_diff(
                mg::azimuth_steps(AzimuthKind::Geodetic, {alpha, 0.0}, no_delta).grid_rad.value,
                chord),
            -delta, 1e-11);
        worst_delta = std::max(worst_delta, std::abs(rad_to_arcsec(delta)));
      }
  std::printf(
      "[ azimuth  ] grid chain vs GeographicLib chord: max |dT| %.2e\" (from alpha), "
      "%.2e\" (from A); inverse max |d alpha| %.2e\"; max |delta| %.3f\"\n",
      worst_fwd, worst_astro, worst_inv, worst_delta);
}
