// Calibration, azimuth chain and whole campaigns (spec §5–§7, §8.5).

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/azimuth_chain.hpp"
#include "meridian/gyro/calibration.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/geodesy/grid.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

using namespace meridian;
using namespace meridian::gyro;

namespace {

// The example campaign without any noise, drift or rounding.
CampaignTruth noise_free_truth() {
  CampaignTruth t = example_campaign_truth();
  t.sigma_time_s = 0;
  t.sigma_reading_div = 0;
  t.sigma_tracking_arcsec = 0;
  t.sigma_pointing_arcsec = 0;
  t.alpha_p_drift_div = 0;
  t.round_to_field_precision = false;
  return t;
}

// Signed difference of two directions in arc-seconds.
double diff_arcsec(double a, double b) {
  return std::remainder(a - b, 2 * units::kPi) / units::kArcsecond;
}

}  // namespace

TEST(Calibration, InstrumentConstantBeforeAfter) {
  const Uncertain known{(30.0 * units::kDegree), 3 * units::kArcsecond};
  const std::vector<Uncertain> before{
      {30 * units::kDegree - 20 * units::kArcsecond, 5 * units::kArcsecond},
      {30 * units::kDegree - 24 * units::kArcsecond, 5 * units::kArcsecond}};
  const std::vector<Uncertain> after{
      {30 * units::kDegree - 26 * units::kArcsecond, 5 * units::kArcsecond}};
  const auto e = instrument_constant(known, before, after, 40 * units::kArcsecond);
  EXPECT_NEAR(e.before[0].value / units::kArcsecond, 20.0, 1e-9);
  EXPECT_NEAR(e.mean.value / units::kArcsecond, 70.0 / 3.0, 1e-9);
  EXPECT_NEAR(*e.difference_rad / units::kArcsecond, 26.0 - 22.0, 1e-9);
  EXPECT_TRUE(e.within_tolerance);
  // σ: max(propagated 5/√3, empirical) combined with σ(A_known) = 3".
  const double emp = std::sqrt(((20 - 70.0 / 3) * (20 - 70.0 / 3) + (24 - 70.0 / 3) * (24 - 70.0 / 3) +
                                (26 - 70.0 / 3) * (26 - 70.0 / 3)) / 6.0);
  EXPECT_NEAR(e.mean.sigma / units::kArcsecond, std::hypot(std::max(5 / std::sqrt(3.0), emp), 3.0),
              1e-9);
  const auto bad = instrument_constant(
      known, before, {{30 * units::kDegree - 80 * units::kArcsecond, 5 * units::kArcsecond}},
      40 * units::kArcsecond);
  EXPECT_FALSE(bad.within_tolerance);
  EXPECT_FALSE(bad.warnings.empty());
}

TEST(Calibration, MeanDirectionAcrossNorth) {
  const auto m = mean_direction({{-10 * units::kArcsecond + 2 * units::kPi, 1 * units::kArcsecond},
                                 {10 * units::kArcsecond, 1 * units::kArcsecond}});
  EXPECT_NEAR(diff_arcsec(m.mean.value, 0.0), 0.0, 1e-9);
  EXPECT_NEAR(m.max_difference / units::kArcsecond, 20.0, 1e-9);
}

TEST(AzimuthChain, ClosedFormWithSigma) {
  AzimuthChainInput in;
  in.gyro_azimuth_rad = {100 * units::kDegree, 5 * units::kArcsecond};
  in.instrument_constant_rad = {-30 * units::kArcsecond, 4 * units::kArcsecond};
  in.latitude_rad = 40 * units::kDegree;
  in.eta_rad = Uncertain{6 * units::kArcsecond, 1 * units::kArcsecond};
  in.convergence_rad = -0.5 * units::kDegree;
  in.arc_to_chord_rad = 0.3 * units::kArcsecond;
  const auto r = azimuth_chain(in);
  const double t40 = std::tan(40 * units::kDegree);
  EXPECT_NEAR(r.astronomic_azimuth_rad.value, 100 * units::kDegree - 30 * units::kArcsecond, 1e-15);
  EXPECT_NEAR(r.laplace_correction_rad / units::kArcsecond, -6 * t40, 1e-9);
  EXPECT_NEAR(
      diff_arcsec(r.grid_azimuth_rad.value, 100 * units::kDegree - 30 * units::kArcsecond -
                                                6 * t40 * units::kArcsecond + 0.5 * units::kDegree +
                                                0.3 * units::kArcsecond),
      0.0, 1e-9);
  EXPECT_NEAR(r.grid_azimuth_rad.sigma / units::kArcsecond, std::sqrt(25 + 16 + t40 * t40), 1e-9);
  in.eta_rad.reset();
  const auto r2 = azimuth_chain(in);
  EXPECT_FALSE(r2.laplace_applied);
  EXPECT_FALSE(r2.notes.empty());
}

TEST(AzimuthChain, ZenithDistanceTerm) {
  // α = A − η·tan φ − (ξ·sin α − η·cos α)·cot z, by hand at α ≈ A (second
  // order: ~1e-10 rad here), σ² + (tan φ − cos α·cot z)²σ²(η) + (sin α·cot z)²σ²(ξ).
  AzimuthChainInput in;
  in.gyro_azimuth_rad = {100 * units::kDegree, 5 * units::kArcsecond};
  in.instrument_constant_rad = {-30 * units::kArcsecond, 4 * units::kArcsecond};
  in.latitude_rad = 40 * units::kDegree;
  in.eta_rad = Uncertain{6 * units::kArcsecond, 1 * units::kArcsecond};
  in.xi_rad = Uncertain{-5 * units::kArcsecond, 2 * units::kArcsecond};
  in.zenith_distance_rad = 110 * units::kDegree;
  const auto r = azimuth_chain(in);
  ASSERT_TRUE(r.zenith_term_applied);
  ASSERT_TRUE(r.zenith_distance_rad);
  EXPECT_EQ(*r.zenith_distance_rad, 110 * units::kDegree);
  const double a = 100 * units::kDegree - 30 * units::kArcsecond,
               cot_z = 1.0 / std::tan(110 * units::kDegree), t40 = std::tan(40 * units::kDegree);
  const double cz = -(-5 * std::sin(a) - 6 * std::cos(a)) * cot_z;  // arc-seconds
  EXPECT_NEAR(r.zenith_correction_rad / units::kArcsecond, cz, 1e-3);
  EXPECT_NEAR(diff_arcsec(r.geodetic_azimuth_rad.value,
                          a - 6 * t40 * units::kArcsecond + cz * units::kArcsecond),
              0.0, 1e-3);
  const double k_eta = t40 - std::cos(a) * cot_z, k_xi = std::sin(a) * cot_z;
  EXPECT_NEAR(r.geodetic_azimuth_rad.sigma / units::kArcsecond,
              std::sqrt(25 + 16 + k_eta * k_eta + 4 * k_xi * k_xi), 1e-4);
  EXPECT_EQ(r.notes.size(), 1u);  // only δ not applied
  // ξ without z (or z without ξ): no term.
  in.zenith_distance_rad.reset();
  EXPECT_FALSE(azimuth_chain(in).zenith_term_applied);
}

TEST(Campaign, NoiseFreeSimulationRecoversTruth) {
  CampaignTruth t = noise_free_truth();
  const auto sim = simulate_campaign(t, 7);
  const auto r = process(sim.input);
  EXPECT_NEAR(r.instrument_constant_used_rad.value / units::kArcsecond,
              t.instrument_constant_rad / units::kArcsecond, 0.01);
  EXPECT_NEAR(diff_arcsec(r.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad), 0.0, 0.01);
  EXPECT_TRUE(r.all_checks_pass());
  EXPECT_TRUE(r.chain.laplace_applied);
  EXPECT_TRUE(r.chain.arc_to_chord_applied);
  for (const auto& d : r.determinations) EXPECT_TRUE(d.zero_position.has_value());
}

TEST(Campaign, NoisySimulationWithinReportedSigma) {
  // 40 noisy campaigns: the grid azimuth error stays within 3σ each time
  // and the RMS normalised error is of order one.
  double sum2 = 0;
  const int runs = 40;
  for (int s = 0; s < runs; ++s) {
    const auto sim = simulate_campaign(example_campaign_truth(), 1000 + static_cast<std::uint64_t>(s));
    const auto r = process(sim.input);
    const double err = diff_arcsec(r.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad);
    const double sig = r.chain.grid_azimuth_rad.sigma / units::kArcsecond;
    EXPECT_LT(std::fabs(err), 3.5 * sig) << "seed " << 1000 + s;
    sum2 += (err / sig) * (err / sig);
  }
  const double rms = std::sqrt(sum2 / runs);
  EXPECT_GT(rms, 0.3);
  EXPECT_LT(rms, 1.5);
}

TEST(Campaign, MissingInstrumentConstantIsAnError) {
  auto sim = simulate_campaign(example_campaign_truth(), 3);
  sim.input.known_line.reset();
  EXPECT_THROW(process(sim.input), InputError);
  sim.input.instrument_constant_rad = Uncertain{25 * units::kArcsecond, 5 * units::kArcsecond};
  EXPECT_NO_THROW(process(sim.input));
}

TEST(Campaign, LatitudeBeyondLimitIsRejected) {
  auto t = example_campaign_truth();
  t.instrument.latitude_limit_rad = 30 * units::kDegree;
  EXPECT_THROW(simulate_campaign(t, 1), InputError);
}

TEST(Campaign, DeflectionFromAGravityModelRecoversTruth) {
  // The truth's ξ, η at both stations are the model's plumb line; the
  // campaign gets neither but the model, and must recover the true grid
  // azimuth with the full Laplace equation (the lines slope slightly: the
  // heights of the example).
  const auto model = gravity::make_synthetic_model({60, 5, 1e-5});
  const auto field = std::make_shared<const gravity::GravityField>(model);
  CampaignTruth t = noise_free_truth();
  t.give_eta = false;
  const geodesy::TransverseMercatorGrid grid(t.grid);
  auto values_at = [&](const PointInput& p) {
    const auto g = grid.reverse(*p.x_north_m, *p.y_east_m);
    return field->evaluate(gravity::GeodeticPoint{g.lat_rad, g.lon_rad, p.height_m.value_or(0.0)});
  };
  t.eta_station_rad = values_at(t.station).eta_astro_rad;
  t.eta_known_rad = values_at(t.known_station).eta_astro_rad;
  t.xi_station_rad = values_at(t.station).xi_astro_rad;
  t.xi_known_rad = values_at(t.known_station).xi_astro_rad;
  ASSERT_GT(std::fabs(t.eta_station_rad / units::kArcsecond),
            0.5);  // a deflection worth correcting
  ASSERT_GT(std::fabs(*t.xi_station_rad / units::kArcsecond), 0.5);
  auto sim = simulate_campaign(t, 21);
  DeflectionModel deflection;
  deflection.description = "synthetic (degree 60)";
  deflection.sigma_eta_rad = 1.5 * units::kArcsecond;
  deflection.sigma_xi_rad = 2.0 * units::kArcsecond;
  deflection.deflection = [&](double lat, double lon, double h) {
    const auto v = field->evaluate(gravity::GeodeticPoint{lat, lon, h}, gravity::Quantities::Deflection);
    return geodesy::Deflection{v.xi_astro_rad, v.eta_astro_rad};
  };
  const auto r = process(sim.input, nullptr, &deflection);
  ASSERT_TRUE(r.chain.laplace_applied);
  EXPECT_NEAR(r.chain.laplace_correction_rad, -t.eta_station_rad * std::tan(r.station.lat_rad), 1e-12);
  ASSERT_TRUE(r.chain.zenith_term_applied);
  ASSERT_TRUE(r.chain.zenith_distance_rad);
  const double alpha = r.chain.geodetic_azimuth_rad.value, cot_z = 1.0 / std::tan(*r.chain.zenith_distance_rad);
  EXPECT_NEAR(r.chain.zenith_correction_rad,
              -(*t.xi_station_rad * std::sin(alpha) - t.eta_station_rad * std::cos(alpha)) * cot_z, 1e-14);
  EXPECT_NEAR(diff_arcsec(r.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad), 0.0, 0.01);
  bool noted = false;
  for (const auto& n : r.notes)
    noted = noted || (n.find("xi = ") != std::string::npos && n.find("eta = ") != std::string::npos &&
                      n.find("from the gravity model synthetic (degree 60)") != std::string::npos);
  EXPECT_TRUE(noted);
  // σ of ξ and η enter the geodetic azimuth.
  const double phi = r.station.lat_rad;
  const double k_eta = std::tan(phi) - std::cos(alpha) * cot_z, k_xi = std::sin(alpha) * cot_z;
  const double sa = r.chain.astronomic_azimuth_rad.sigma;
  EXPECT_NEAR(r.chain.geodetic_azimuth_rad.sigma,
              std::sqrt(sa * sa + std::pow(k_eta * 1.5 * units::kArcsecond, 2) +
                        std::pow(k_xi * 2.0 * units::kArcsecond, 2)),
              1e-15);
}

namespace {

// The zenith distance of the sight between two truth points, computed here
// independently of the library: GeographicLib::LocalCartesian at the station.
double zenith_distance(const CampaignTruth& t, const PointInput& from, const PointInput& to) {
  const geodesy::TransverseMercatorGrid grid(t.grid);
  const auto a = grid.reverse(*from.x_north_m, *from.y_east_m);
  const auto b = grid.reverse(*to.x_north_m, *to.y_east_m);
  const GeographicLib::LocalCartesian lc(
      a.lat_rad / units::kDegree, a.lon_rad / units::kDegree, *from.height_m,
      GeographicLib::Geocentric(t.grid.ellipsoid.a_m, t.grid.ellipsoid.f));
  double x, y, u;
  lc.Forward(b.lat_rad / units::kDegree, b.lon_rad / units::kDegree, *to.height_m, x, y, u);
  return std::atan2(std::hypot(x, y), u);
}

// A mine job down a decline: the line C→D falls 20° and the known line A→B
// rises 8°; ξ and η of a few arc-seconds at both stations.
CampaignTruth decline_truth() {
  CampaignTruth t = noise_free_truth();
  const double s_cd = std::hypot(*t.target.x_north_m - *t.station.x_north_m, *t.target.y_east_m - *t.station.y_east_m);
  const double s_ab = std::hypot(*t.known_target.x_north_m - *t.known_station.x_north_m,
                                 *t.known_target.y_east_m - *t.known_station.y_east_m);
  t.target.height_m = *t.station.height_m - s_cd * std::tan(20 * units::kDegree);
  t.known_target.height_m = *t.known_station.height_m + s_ab * std::tan(8 * units::kDegree);
  t.xi_station_rad = -6.0 * units::kArcsecond;
  t.eta_station_rad = -4.2 * units::kArcsecond;
  t.xi_known_rad = 5.0 * units::kArcsecond;
  t.eta_known_rad = -4.0 * units::kArcsecond;
  return t;
}

// −(ξ·sin α − η·cos α)·cot z by hand.
double zenith_term(double xi, double eta, double alpha, double z) {
  return -(xi * std::sin(alpha) - eta * std::cos(alpha)) / std::tan(z);
}

bool has_note(const CampaignResult& r, std::initializer_list<std::string> parts) {
  for (const auto& n : r.notes) {
    bool all = true;
    for (const auto& p : parts) all = all && n.find(p) != std::string::npos;
    if (all) return true;
  }
  return false;
}

}  // namespace

TEST(Campaign, FullLaplaceOnADeclineRecoversTruth) {
  const CampaignTruth t = decline_truth();
  const auto sim = simulate_campaign(t, 7);
  const double z_cd = zenith_distance(t, t.station, t.target);
  const double z_ab = zenith_distance(t, t.known_station, t.known_target);
  ASSERT_NEAR(z_cd / units::kDegree, 110.0, 0.05);
  ASSERT_NEAR(z_ab / units::kDegree, 82.0, 0.05);

  const auto r = process(sim.input);
  ASSERT_TRUE(r.chain.zenith_term_applied);
  EXPECT_NEAR(*r.chain.zenith_distance_rad, z_cd, 1e-9);
  const double c_cd = zenith_term(*t.xi_station_rad, t.eta_station_rad, r.chain.geodetic_azimuth_rad.value, z_cd);
  EXPECT_NEAR(r.chain.zenith_correction_rad / units::kArcsecond, c_cd / units::kArcsecond, 1e-6);
  EXPECT_GT(std::fabs(c_cd / units::kArcsecond), 1.0);  // a term worth having
  EXPECT_NEAR(diff_arcsec(r.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad), 0.0, 0.01);
  EXPECT_NEAR(r.instrument_constant_used_rad.value / units::kArcsecond,
              t.instrument_constant_rad / units::kArcsecond, 0.01);
  EXPECT_TRUE(has_note(r, {"line C (shaft bottom)->D (main drift): zenith distance 110°", "from the heights of",
                           "zenith-distance term"}));
  EXPECT_TRUE(has_note(r, {"known line A (surface)->B (surface): zenith distance 82°"}));

  // Without ξ at C the term of the line is missing: T misses by −c_cd, and a note says why.
  auto no_xi = sim.input;
  no_xi.line.from.xi_rad.reset();
  const auto r1 = process(no_xi);
  EXPECT_FALSE(r1.chain.zenith_term_applied);
  EXPECT_NEAR(diff_arcsec(r1.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad),
              -c_cd / units::kArcsecond, 0.01);
  EXPECT_TRUE(has_note(r1, {"inclined -20.0 deg", "is not applied: xi unknown at C (shaft bottom)"}));

  // Without ξ anywhere, E also absorbs the known line's term (A_known is
  // then too large by c_ab): T misses by c_ab − c_cd. α of A→B from
  // GeographicLib::Geodesic between the points.
  no_xi.known_line->from.xi_rad.reset();
  const auto r2 = process(no_xi);
  const geodesy::TransverseMercatorGrid grid(t.grid);
  const auto a = grid.reverse(*t.known_station.x_north_m, *t.known_station.y_east_m);
  const auto b = grid.reverse(*t.known_target.x_north_m, *t.known_target.y_east_m);
  double s12, azi1, azi2;
  GeographicLib::Geodesic(t.grid.ellipsoid.a_m, t.grid.ellipsoid.f)
      .Inverse(a.lat_rad / units::kDegree, a.lon_rad / units::kDegree, b.lat_rad / units::kDegree,
               b.lon_rad / units::kDegree, s12, azi1, azi2);
  const double c_ab = zenith_term(*t.xi_known_rad, t.eta_known_rad, azi1 * units::kDegree, z_ab);
  EXPECT_GT(std::fabs(c_ab / units::kArcsecond), 0.3);
  EXPECT_NEAR(diff_arcsec(r2.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad),
              (c_ab - c_cd) / units::kArcsecond, 0.01);
  EXPECT_TRUE(has_note(r2, {"known line A (surface)->B (surface): the sight is inclined +8.0 deg",
                            "xi unknown at A (surface)"}));

  // A booked zenith angle (to 1″, as a crew books it) instead of D's height.
  auto booked = sim.input;
  booked.line.to->height_m.reset();
  booked.line.zenith_angle_rad = std::round(z_cd / units::kArcsecond) * units::kArcsecond;
  const auto r3 = process(booked);
  ASSERT_TRUE(r3.chain.zenith_term_applied);
  EXPECT_NEAR(diff_arcsec(r3.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad), 0.0, 0.01);
  EXPECT_TRUE(has_note(r3, {"zenith distance 110°", "booked (zenith_angle)"}));

  // Neither: the sight is taken as horizontal, with a note; T misses by −c_cd.
  auto flat = booked;
  flat.line.zenith_angle_rad.reset();
  const auto r4 = process(flat);
  EXPECT_FALSE(r4.chain.zenith_term_applied);
  EXPECT_FALSE(r4.chain.zenith_distance_rad);
  EXPECT_NEAR(diff_arcsec(r4.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad),
              -c_cd / units::kArcsecond, 0.01);
  EXPECT_TRUE(has_note(r4, {"no zenith_angle and no heights of both points", "taken as horizontal"}));
}

TEST(Campaign, NoXiNoNewNotes) {
  // The example (η given, ξ not, nearly level lines): the zenith-distance
  // term is not applied and nothing about it is noted, so the outputs of the
  // existing examples do not change.
  const auto sim = simulate_campaign(noise_free_truth(), 7);
  const auto r = process(sim.input);
  EXPECT_TRUE(r.chain.laplace_applied);
  EXPECT_FALSE(r.chain.zenith_term_applied);
  EXPECT_EQ(r.chain.zenith_correction_rad, 0.0);
  for (const auto& n : r.notes) {
    EXPECT_EQ(n.find("zenith"), std::string::npos) << n;
    EXPECT_EQ(n.find("xi"), std::string::npos) << n;
  }
}
