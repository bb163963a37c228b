// The azimuth chain astronomic ↔ geodetic ↔ grid (geodesy/azimuth_chain.hpp).
// References: hand formulas (Laplace α = A − η·tan φ, T = α − γ + δ, σ in
// quadrature), and GeographicLib directly (Geodesic for the geodetic azimuth,
// TransverseMercator for the projected end points of the chord).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
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
#include "meridian/geodesy/frames.hpp"
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
      // The zenith-distance term: a 20° rise and a 20° decline, a steep 70°
      // decline with 1′ deflections; ξ without z and z without ξ (not applied).
      {deg_to_rad(37.85), eta, arcsec_to_rad(-3140.2), arcsec_to_rad(0.31),
       Uncertain{arcsec_to_rad(5.0), arcsec_to_rad(0.5)}, deg_to_rad(70.0)},
      {deg_to_rad(-33.9), eta, deg_to_rad(-1.2), std::nullopt,
       Uncertain{arcsec_to_rad(-7.0), arcsec_to_rad(1.0)}, deg_to_rad(110.0)},
      {deg_to_rad(52.0), Uncertain{arcsec_to_rad(-60.0), arcsec_to_rad(1.0)}, deg_to_rad(0.7),
       arcsec_to_rad(0.1), Uncertain{arcsec_to_rad(60.0), arcsec_to_rad(1.0)}, deg_to_rad(160.0)},
      {deg_to_rad(37.85), eta, 0.0, std::nullopt, Uncertain{arcsec_to_rad(5.0), 0.0}, std::nullopt},
      {deg_to_rad(37.85), eta, 0.0, std::nullopt, std::nullopt, deg_to_rad(70.0)},
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
          // c_z(α) evaluated at α from the forward iteration or as given.
          EXPECT_NEAR(t.zenith_correction_rad, s.zenith_correction_rad, 1e-17);
          EXPECT_EQ(t.zenith_term_applied, s.zenith_term_applied);
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

// ---------------------------------------------------------------------------
// The zenith-distance term: A − α = η·tan φ + (ξ·sin α − η·cos α)·cot z.

namespace {

mg::AzimuthReduction full(double lat_deg, double xi_as, double eta_as, double z_deg,
                          double sxi_as = 0.0, double seta_as = 0.0) {
  mg::AzimuthReduction r;
  r.latitude_rad = deg_to_rad(lat_deg);
  r.eta_rad = Uncertain{arcsec_to_rad(eta_as), arcsec_to_rad(seta_as)};
  r.xi_rad = Uncertain{arcsec_to_rad(xi_as), arcsec_to_rad(sxi_as)};
  r.zenith_distance_rad = deg_to_rad(z_deg);
  return r;
}

}  // namespace

TEST(AzimuthChainZenithTerm, HandFormulas) {
  const double phi = deg_to_rad(37.85), xi = arcsec_to_rad(6.0), eta = arcsec_to_rad(-4.2);
  const double z = deg_to_rad(70.0), cot_z = 1.0 / std::tan(z);
  for (double a_deg : {0.0, 30.0, 90.0, 123.456, 200.0, 359.9}) {
    SCOPED_TRACE(a_deg);
    const double a = deg_to_rad(a_deg);
    const mg::AzimuthSteps s = mg::azimuth_from_astronomic({a, 0.0}, full(37.85, 6.0, -4.2, 70.0));
    ASSERT_TRUE(s.laplace_applied);
    ASSERT_TRUE(s.zenith_term_applied);
    const double alpha = s.geodetic_rad.value;
    // α satisfies the equation with α in the term.
    const double rhs =
        a - eta * std::tan(phi) - (xi * std::sin(alpha) - eta * std::cos(alpha)) * cot_z;
    EXPECT_NEAR(angle_diff(alpha, rhs), 0.0, 2e-15);
    EXPECT_NEAR(s.laplace_correction_rad, -eta * std::tan(phi), 1e-20);
    EXPECT_NEAR(s.zenith_correction_rad, -(xi * std::sin(alpha) - eta * std::cos(alpha)) * cot_z,
                1e-20);
    EXPECT_NEAR(angle_diff(alpha, a), s.laplace_correction_rad + s.zenith_correction_rad, 1e-15);
    // With A in the term instead: the same to second order (θ²·cot z·(tan φ + cot z) ≈ 1e-10 rad).
    const double alpha_a = a - eta * std::tan(phi) - (xi * std::sin(a) - eta * std::cos(a)) * cot_z;
    EXPECT_NEAR(angle_diff(alpha, alpha_a), 0.0, 5e-10);
    // The inverse from α gives A back, with the same correction.
    const mg::AzimuthSteps i =
        mg::azimuth_steps(AzimuthKind::Geodetic, {alpha, 0.0}, full(37.85, 6.0, -4.2, 70.0));
    EXPECT_NEAR(angle_diff(i.astronomic_rad.value, a), 0.0, 2e-15);
    EXPECT_NEAR(i.zenith_correction_rad, s.zenith_correction_rad, 1e-17);
  }
}

TEST(AzimuthChainZenithTerm, Signs) {
  // ξ = +5″ (astronomic zenith north of the normal), sight due east 20°
  // upwards: A − α = +ξ·cot z, α = A − 1.820″ (η = 0); downwards the opposite.
  const double cot70 = 1.0 / std::tan(deg_to_rad(70.0));
  auto alpha_minus_a = [&](double lat, double xi, double eta, double az, double z) {
    const mg::AzimuthSteps s =
        mg::azimuth_from_astronomic({deg_to_rad(az), 0.0}, full(lat, xi, eta, z));
    return rad_to_arcsec(angle_diff(s.geodetic_rad.value, deg_to_rad(az)));
  };
  EXPECT_NEAR(alpha_minus_a(45.0, 5.0, 0.0, 90.0, 70.0), -5.0 * cot70, 1e-9);
  EXPECT_NEAR(alpha_minus_a(45.0, 5.0, 0.0, 90.0, 110.0), 5.0 * cot70, 1e-9);  // 20° decline
  EXPECT_NEAR(alpha_minus_a(45.0, -5.0, 0.0, 90.0, 70.0), 5.0 * cot70, 1e-9);
  // η = +5″ at φ = 45° N, sight due north 20° upwards: −η·tan φ + η·cot z.
  EXPECT_NEAR(alpha_minus_a(45.0, 0.0, 5.0, 0.0, 70.0), -5.0 + 5.0 * cot70, 1e-9);
  // Southern hemisphere: only the first term flips.
  EXPECT_NEAR(alpha_minus_a(-45.0, 0.0, 5.0, 0.0, 70.0), 5.0 + 5.0 * cot70, 1e-9);
  // The 20° sight with 5″ deflections: up to 5·√2·cot 70° = 2.57″ from the term.
  double worst = 0;
  for (double az = 0; az < 360; az += 1)
    worst = std::max(worst, std::abs(alpha_minus_a(45.0, 5.0, -5.0, az, 70.0) - 5.0));
  EXPECT_NEAR(worst, 5.0 * std::sqrt(2.0) * cot70, 1e-3);
}

TEST(AzimuthChainZenithTerm, SigmaPropagation) {
  // σ² = σ²_given + (tan φ − cos α·cot z)²·σ²_η + (sin α·cot z)²·σ²_ξ,
  // and the coefficients are the chain's own derivatives (finite differences).
  const double phi_deg = 50.0, t = std::tan(deg_to_rad(phi_deg));
  const double sg = arcsec_to_rad(3.0), sxi = arcsec_to_rad(0.8), seta = arcsec_to_rad(0.5);
  for (double z_deg : {70.0, 110.0, 150.0})
    for (double a_deg : {20.0, 135.0, 250.0}) {
      SCOPED_TRACE(testing::Message() << "z " << z_deg << " A " << a_deg);
      const double cot_z = 1.0 / std::tan(deg_to_rad(z_deg));
      const mg::AzimuthReduction r = full(phi_deg, 4.0, -3.0, z_deg, 0.8, 0.5);
      const mg::AzimuthSteps f =
          mg::azimuth_steps(AzimuthKind::Astronomic, {deg_to_rad(a_deg), sg}, r);
      const double alpha = f.geodetic_rad.value;
      const double k_eta = t - std::cos(alpha) * cot_z, k_xi = std::sin(alpha) * cot_z;
      const double expect =
          std::sqrt(sg * sg + k_eta * k_eta * seta * seta + k_xi * k_xi * sxi * sxi);
      EXPECT_NEAR(f.geodetic_rad.sigma / expect, 1.0, 1e-12);
      EXPECT_EQ(f.grid_rad.sigma, f.geodetic_rad.sigma);
      EXPECT_EQ(f.astronomic_rad.sigma, sg);
      // Finite differences of α with respect to η and ξ: −k_eta and −k_xi (to O(θ cot z)).
      const double h = arcsec_to_rad(1.0);
      auto alpha_with = [&](double dxi, double deta) {
        mg::AzimuthReduction q = r;
        q.xi_rad->value += dxi;
        q.eta_rad->value += deta;
        return mg::azimuth_steps(AzimuthKind::Astronomic, {deg_to_rad(a_deg), 0.0}, q)
            .geodetic_rad.value;
      };
      const double d_eta = angle_diff(alpha_with(0, h), alpha_with(0, -h)) / (2 * h);
      const double d_xi = angle_diff(alpha_with(h, 0), alpha_with(-h, 0)) / (2 * h);
      EXPECT_NEAR(d_eta, -k_eta, 1e-3 * std::abs(cot_z));
      EXPECT_NEAR(d_xi, -k_xi, 1e-3 * std::abs(cot_z));
      // The inverse: A from α carries the same σ.
      const mg::AzimuthSteps i = mg::azimuth_steps(AzimuthKind::Geodetic, {alpha, sg}, r);
      EXPECT_NEAR(i.astronomic_rad.sigma / expect, 1.0, 1e-12);
      EXPECT_EQ(i.geodetic_rad.sigma, sg);
    }
}

TEST(AzimuthChainZenithTerm, AbsentInputsLeaveTheChainBitIdentical) {
  // ξ without z, or z without ξ: the term is not applied and every output is
  // the same double as without either.
  const double phi = 0.6606, eta = -2.03e-5, gamma = -0.0152, delta = 1.5e-6;
  const mg::AzimuthReduction none{phi, Uncertain{eta, 2.4e-6}, gamma, delta};
  mg::AzimuthReduction xi_only = none, z_only = none;
  xi_only.xi_rad = Uncertain{3e-5, 1e-6};
  z_only.zenith_distance_rad = deg_to_rad(70.0);
  for (AzimuthKind k : kKinds)
    for (double v : {0.1234567890123, 3.3, 6.2831, -0.01}) {
      const mg::AzimuthSteps a = mg::azimuth_steps(k, {v, 1e-5}, none);
      for (const mg::AzimuthReduction* r : {&xi_only, &z_only}) {
        const mg::AzimuthSteps b = mg::azimuth_steps(k, {v, 1e-5}, *r);
        EXPECT_FALSE(b.zenith_term_applied);
        EXPECT_EQ(b.zenith_correction_rad, 0.0);
        for (AzimuthKind j : kKinds) {
          EXPECT_EQ(of_kind(a, j).value, of_kind(b, j).value);
          EXPECT_EQ(of_kind(a, j).sigma, of_kind(b, j).sigma);
        }
      }
    }
}

TEST(AzimuthChainZenithTerm, Guards) {
  using meridian::InputError;
  for (AzimuthKind k : kKinds) {
    SCOPED_TRACE(mg::to_string(k));
    EXPECT_NO_THROW(mg::azimuth_steps(k, {1.0, 0.0}, full(40.0, 5.0, 5.0, 70.0)));
    // |ξ| > 0.01 rad, with or without z.
    mg::AzimuthReduction big = full(40.0, 0.0, 5.0, 70.0);
    big.xi_rad->value = 0.0101;
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, big), InputError);
    big.zenith_distance_rad.reset();
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, big), InputError);
    // Negative σ(ξ).
    mg::AzimuthReduction neg = full(40.0, 1.0, 1.0, 70.0);
    neg.xi_rad->sigma = -1e-6;
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, neg), InputError);
    // ξ without η.
    mg::AzimuthReduction no_eta = full(40.0, 5.0, 5.0, 70.0);
    no_eta.eta_rad.reset();
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, no_eta), InputError);
    // A (near) vertical sight, checked even when the term is not applied.
    for (double z : {0.0, 5.0, 175.0, 180.0}) {
      EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, full(40.0, 5.0, 5.0, z)), InputError) << z;
      mg::AzimuthReduction z_only{deg_to_rad(40.0), std::nullopt, 0.0, std::nullopt};
      z_only.zenith_distance_rad = deg_to_rad(z);
      EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, z_only), InputError) << z;
    }
    mg::AzimuthReduction nan_z = full(40.0, 5.0, 5.0, 70.0);
    nan_z.zenith_distance_rad = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(mg::azimuth_steps(k, {1.0, 0.0}, nan_z), InputError);
  }
}

// The rigorous, independent check: the astronomic local frame built from the
// exact astronomic zenith (frames.hpp astronomic_zenith_enu) and the rotation
// axis (astronomic north: in the plane perpendicular to the zenith, towards
// the celestial pole); a target direction given by its geodetic azimuth and
// zenith distance; A − α from the azimuths of that direction in the two
// frames against the chain's correction. The chain is first order: the
// residual must be second order in the deflection.
TEST(AzimuthChainZenithTerm, AgreesWithTheExactFrames) {
  struct Case {
    double lat_deg, lon_deg;
  };
  const double kDefl[] = {3.0, 10.0, 60.0};  // |ξ|, |η| in arc-seconds
  double worst[3] = {0, 0, 0}, worst_ratio = 0, worst_laplace_only = 0, worst_mine = 0;
  for (const Case c : {Case{37.85, 112.55}, Case{-33.9, 18.4}, Case{60.0, -20.0}, Case{5.0, 100.0}})
    for (int di = 0; di < 3; ++di)
      for (double sx : {-1.0, 0.0, 1.0})
        for (double se : {-1.0, 0.0, 1.0})
          for (double z_deg : {20.0, 45.0, 70.0, 90.0, 110.0, 135.0, 160.0})
            for (double az_deg = 0.0; az_deg < 360.0; az_deg += 22.5) {
              const double xi = arcsec_to_rad(sx * kDefl[di]), eta = arcsec_to_rad(se * kDefl[di]);
              const double phi = deg_to_rad(c.lat_deg), lam = deg_to_rad(c.lon_deg);
              const double alpha = deg_to_rad(az_deg), z = deg_to_rad(z_deg);
              // Geodetic ENU → ECEF; the target direction and the astronomic frame in ECEF.
              const Eigen::Matrix3d r = mg::rotation_ecef_to_enu(phi, lam);
              const Eigen::Vector3d d =
                  r.transpose() * Eigen::Vector3d(std::sin(alpha) * std::sin(z),
                                                  std::cos(alpha) * std::sin(z), std::cos(z));
              const Eigen::Vector3d up =
                  r.transpose() * mg::astronomic_zenith_enu(mg::Deflection{xi, eta}, phi);
              const Eigen::Vector3d pole(0.0, 0.0, 1.0);
              const Eigen::Vector3d north = (pole - pole.dot(up) * up).normalized();
              const Eigen::Vector3d east = north.cross(up);
              const double a_exact = std::atan2(d.dot(east), d.dot(north));
              const double z_astro = std::acos(std::clamp(d.dot(up), -1.0, 1.0));
              // The geodetic frame itself gives α back (a check on the construction).
              const Eigen::Vector3d gn = r.row(1).transpose(), ge = r.row(0).transpose();
              ASSERT_NEAR(angle_diff(std::atan2(d.dot(ge), d.dot(gn)), alpha), 0.0, 1e-14);

              mg::AzimuthReduction red{phi, Uncertain{eta, 0.0}, 0.0, std::nullopt};
              red.xi_rad = Uncertain{xi, 0.0};
              red.zenith_distance_rad = z;
              // Inverse (known line): α → A with the geodetic z; forward (the
              // gyro line): A → α with the astronomic z a theodolite books.
              const double a_chain =
                  mg::azimuth_steps(AzimuthKind::Geodetic, {alpha, 0.0}, red).astronomic_rad.value;
              red.zenith_distance_rad = z_astro;
              const double alpha_chain =
                  mg::azimuth_from_astronomic({a_exact, 0.0}, red).geodetic_rad.value;
              const double res = std::max(std::abs(angle_diff(a_chain, a_exact)),
                                          std::abs(angle_diff(alpha_chain, alpha)));
              worst[di] = std::max(worst[di], res);
              // Mine lines: sights within 20° of the horizon, |φ| ≤ 40°, 10″ deflections.
              if (di == 1 && std::abs(c.lat_deg) <= 40.0 && z_deg >= 70.0 && z_deg <= 110.0)
                worst_mine = std::max(worst_mine, res);
              const double theta = std::hypot(xi, eta);
              if (theta > 0) {
                // Second order: |res| ≤ C·θ²·(1 + tan²φ + cot²z) with C of order one.
                const double t = std::tan(phi), ct = 1.0 / std::tan(z);
                worst_ratio = std::max(worst_ratio, res / (theta * theta * (1 + t * t + ct * ct)));
              }
              if (di == 1 && z_deg >= 70.0 && z_deg <= 110.0) {
                const double laplace_only = alpha + eta * std::tan(phi);
                worst_laplace_only =
                    std::max(worst_laplace_only, std::abs(angle_diff(laplace_only, a_exact)));
              }
            }
  std::printf(
      "[ laplace  ] chain vs exact frames (|lat| to 60 deg, z 20..160 deg), max |residual|: "
      "%.2e\" (3\"), %.2e\" (10\"), %.2e\" (60\"); 10\" with |lat| <= 40 deg, z 70..110 deg: "
      "%.2e\"; max residual / (theta^2 (1 + tan^2 phi + cot^2 z)) = %.3f; without the term "
      "(10\", z 70..110 deg): %.3f\"\n",
      rad_to_arcsec(worst[0]), rad_to_arcsec(worst[1]), rad_to_arcsec(worst[2]),
      rad_to_arcsec(worst_mine), worst_ratio, rad_to_arcsec(worst_laplace_only));
  EXPECT_LT(worst_ratio, 1.0);
  EXPECT_LT(rad_to_arcsec(worst_mine), 0.001);
  EXPECT_GT(rad_to_arcsec(worst_laplace_only), 1.0);  // the term matters
}
