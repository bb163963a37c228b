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

using namespace meridian;
using namespace meridian::gyro;

namespace {
constexpr double kArcsec = units::kArcsecond;
constexpr double kDeg = units::kDegree;

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
double diff_arcsec(double a, double b) { return std::remainder(a - b, 2 * units::kPi) / kArcsec; }

}  // namespace

TEST(Calibration, InstrumentConstantBeforeAfter) {
  const Uncertain known{(30.0 * kDeg), 3 * kArcsec};
  const std::vector<Uncertain> before{{30 * kDeg - 20 * kArcsec, 5 * kArcsec}, {30 * kDeg - 24 * kArcsec, 5 * kArcsec}};
  const std::vector<Uncertain> after{{30 * kDeg - 26 * kArcsec, 5 * kArcsec}};
  const auto e = instrument_constant(known, before, after, 40 * kArcsec);
  EXPECT_NEAR(e.before[0].value / kArcsec, 20.0, 1e-9);
  EXPECT_NEAR(e.mean.value / kArcsec, 70.0 / 3.0, 1e-9);
  EXPECT_NEAR(*e.difference_rad / kArcsec, 26.0 - 22.0, 1e-9);
  EXPECT_TRUE(e.within_tolerance);
  // σ: max(propagated 5/√3, empirical) combined with σ(A_known) = 3".
  const double emp = std::sqrt(((20 - 70.0 / 3) * (20 - 70.0 / 3) + (24 - 70.0 / 3) * (24 - 70.0 / 3) +
                                (26 - 70.0 / 3) * (26 - 70.0 / 3)) / 6.0);
  EXPECT_NEAR(e.mean.sigma / kArcsec, std::hypot(std::max(5 / std::sqrt(3.0), emp), 3.0), 1e-9);
  const auto bad = instrument_constant(known, before, {{30 * kDeg - 80 * kArcsec, 5 * kArcsec}}, 40 * kArcsec);
  EXPECT_FALSE(bad.within_tolerance);
  EXPECT_FALSE(bad.warnings.empty());
}

TEST(Calibration, MeanDirectionAcrossNorth) {
  const auto m = mean_direction({{-10 * kArcsec + 2 * units::kPi, 1 * kArcsec}, {10 * kArcsec, 1 * kArcsec}});
  EXPECT_NEAR(diff_arcsec(m.mean.value, 0.0), 0.0, 1e-9);
  EXPECT_NEAR(m.max_difference / kArcsec, 20.0, 1e-9);
}

TEST(AzimuthChain, ClosedFormWithSigma) {
  AzimuthChainInput in;
  in.gyro_azimuth_rad = {100 * kDeg, 5 * kArcsec};
  in.instrument_constant_rad = {-30 * kArcsec, 4 * kArcsec};
  in.latitude_rad = 40 * kDeg;
  in.eta_rad = Uncertain{6 * kArcsec, 1 * kArcsec};
  in.convergence_rad = -0.5 * kDeg;
  in.arc_to_chord_rad = 0.3 * kArcsec;
  const auto r = azimuth_chain(in);
  const double t40 = std::tan(40 * kDeg);
  EXPECT_NEAR(r.astronomic_azimuth_rad.value, 100 * kDeg - 30 * kArcsec, 1e-15);
  EXPECT_NEAR(r.laplace_correction_rad / kArcsec, -6 * t40, 1e-9);
  EXPECT_NEAR(diff_arcsec(r.grid_azimuth_rad.value, 100 * kDeg - 30 * kArcsec - 6 * t40 * kArcsec + 0.5 * kDeg + 0.3 * kArcsec), 0.0, 1e-9);
  EXPECT_NEAR(r.grid_azimuth_rad.sigma / kArcsec, std::sqrt(25 + 16 + t40 * t40), 1e-9);
  in.eta_rad.reset();
  const auto r2 = azimuth_chain(in);
  EXPECT_FALSE(r2.laplace_applied);
  EXPECT_FALSE(r2.notes.empty());
}

TEST(Campaign, NoiseFreeSimulationRecoversTruth) {
  CampaignTruth t = noise_free_truth();
  const auto sim = simulate_campaign(t, 7);
  const auto r = process(sim.input);
  EXPECT_NEAR(r.instrument_constant_used_rad.value / kArcsec, t.instrument_constant_rad / kArcsec, 0.01);
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
    const double sig = r.chain.grid_azimuth_rad.sigma / kArcsec;
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
  sim.input.instrument_constant_rad = Uncertain{25 * kArcsec, 5 * kArcsec};
  EXPECT_NO_THROW(process(sim.input));
}

TEST(Campaign, LatitudeBeyondLimitIsRejected) {
  auto t = example_campaign_truth();
  t.instrument.latitude_limit_rad = 30 * kDeg;
  EXPECT_THROW(simulate_campaign(t, 1), InputError);
}

TEST(Campaign, EtaFromAGravityModelRecoversTruth) {
  // The truth's η at both stations is the model's plumb-line η; the campaign
  // gets no η but the model, and must recover the true grid azimuth.
  const auto model = gravity::make_synthetic_model({60, 5, 1e-5});
  const auto field = std::make_shared<const gravity::GravityField>(model);
  CampaignTruth t = noise_free_truth();
  t.give_eta = false;
  const geodesy::TransverseMercatorGrid grid(t.grid);
  auto eta_at = [&](const PointInput& p) {
    const auto g = grid.reverse(*p.x_north_m, *p.y_east_m);
    return field->evaluate(gravity::GeodeticPoint{g.lat_rad, g.lon_rad, p.height_m.value_or(0.0)}).eta_astro_rad;
  };
  t.eta_station_rad = eta_at(t.station);
  t.eta_known_rad = eta_at(t.known_station);
  ASSERT_GT(std::fabs(t.eta_station_rad / kArcsec), 0.5);  // a deflection worth correcting
  auto sim = simulate_campaign(t, 21);
  const DeflectionModel deflection{"synthetic (degree 60)", 1.5 * kArcsec, [&](double lat, double lon, double h) {
    return field->evaluate(gravity::GeodeticPoint{lat, lon, h}, gravity::Quantities::Deflection).eta_astro_rad;
  }};
  const auto r = process(sim.input, nullptr, &deflection);
  ASSERT_TRUE(r.chain.laplace_applied);
  EXPECT_NEAR(r.chain.laplace_correction_rad, -t.eta_station_rad * std::tan(r.station.lat_rad), 1e-12);
  EXPECT_NEAR(diff_arcsec(r.chain.grid_azimuth_rad.value, sim.true_grid_azimuth_rad), 0.0, 0.01);
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n.find("from the gravity model synthetic (degree 60)") != std::string::npos;
  EXPECT_TRUE(noted);
  // σ of η enters the geodetic azimuth: tan φ · 1.5".
  EXPECT_GT(r.chain.geodetic_azimuth_rad.sigma, r.chain.astronomic_azimuth_rad.sigma);
}
