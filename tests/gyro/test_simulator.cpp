#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/constants.hpp"
#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/simulator.hpp"

using meridian::InputError;
using meridian::units::arcsec_to_rad;
using meridian::units::deg_to_rad;
using namespace meridian::gyro;

namespace {

using meridian::units::kPi;

// Spec §8 scenario 2: β = −0.12 div, B = 9 div, T_B = 440 s, t0 = 50 s, k = 0.
NonTrackingSimulation scenario2() {
  NonTrackingSimulation s;
  s.beta_div = -0.12;
  s.amplitude_div = 9.0;
  s.period_s = 440.0;
  s.t0_s = 50.0;
  s.damping_per_s = 0.0;
  s.levels_div = {0.0, -2.0, 2.0};
  s.crossings_per_level = 3;
  s.start_time_s = 0.0;
  s.reversals = 2;
  return s;
}

double model(const NonTrackingSimulation& s, double t) {
  const double x = t - s.t0_s;
  return s.beta_div +
         s.amplitude_div * std::exp(-s.damping_per_s * x) * std::sin(2 * kPi * x / s.period_s);
}

double model_rate(const NonTrackingSimulation& s, double t) {
  const double x = t - s.t0_s;
  const double w = 2 * kPi / s.period_s;
  const double k = s.damping_per_s;
  return s.amplitude_div * std::exp(-k * x) * (w * std::cos(w * x) - k * std::sin(w * x));
}

double mean(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double variance(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return s / static_cast<double>(v.size() - 1);
}

double lag1_autocorrelation(const std::vector<double>& v) {
  const double m = mean(v);
  double num = 0.0;
  double den = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    den += (v[i] - m) * (v[i] - m);
    if (i > 0) num += (v[i] - m) * (v[i - 1] - m);
  }
  return num / den;
}

}  // namespace

// ---------------------------------------------------------------------------
// Non-tracking
// ---------------------------------------------------------------------------

TEST(SimulatorNonTracking, Scenario2CrossingTimesAndReversals) {
  const NonTrackingObservations obs = simulate_nontracking(scenario2(), 1);
  ASSERT_EQ(obs.crossings.size(), 3u);
  const std::vector<std::vector<double>> expected = {
      {50.934, 269.066, 490.934}, {35.263, 284.737, 475.263}, {66.652, 253.348, 506.652}};
  const std::vector<double> levels = {0.0, -2.0, 2.0};
  for (std::size_t l = 0; l < 3; ++l) {
    const Crossing& c = obs.crossings[l];
    EXPECT_EQ(c.level_div, levels[l]);
    ASSERT_EQ(c.times_s.size(), 3u);
    EXPECT_EQ(c.first_direction, +1) << "level " << levels[l];
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(c.times_s[i], expected[l][i], 1e-3);
    // Closed form with k = 0: t = t0 + T/(2π)·asin((a − β)/B), mirrored.
    const double u = 440.0 / (2 * kPi) * std::asin((levels[l] + 0.12) / 9.0);
    EXPECT_NEAR(c.times_s[0], 50.0 + u, 1e-11);
    EXPECT_NEAR(c.times_s[1], 50.0 + 220.0 - u, 1e-11);
    EXPECT_NEAR(c.times_s[2], 50.0 + 440.0 + u, 1e-11);
  }
  ASSERT_EQ(obs.reversals_div.size(), 2u);
  EXPECT_NEAR(obs.reversals_div[0], 8.88, 1e-9);
  EXPECT_NEAR(obs.reversals_div[1], -9.12, 1e-9);
  ASSERT_EQ(obs.reversal_times_s.size(), 2u);
  EXPECT_NEAR(obs.reversal_times_s[0], 160.0, 1e-9);
  EXPECT_NEAR(obs.reversal_times_s[1], 380.0, 1e-9);
  EXPECT_FALSE(obs.period_s.has_value());
  // Noise-free data carry the default observation weights.
  EXPECT_DOUBLE_EQ(obs.sigma_time_s, 0.1);
  EXPECT_DOUBLE_EQ(obs.sigma_reading_div, 0.05);
}

TEST(SimulatorNonTracking, CrossingsAreExactRootsAndDirectionsAlternate) {
  for (double k : {0.0, 1e-5, 4e-4}) {
    NonTrackingSimulation s = scenario2();
    s.damping_per_s = k;
    s.levels_div = {-3.0, -0.5, 0.0, 1.25, 4.0};
    s.crossings_per_level = 4;
    s.start_time_s = 13.0;
    s.reversals = 5;
    const NonTrackingObservations obs = simulate_nontracking(s, 7);
    for (const Crossing& c : obs.crossings) {
      ASSERT_EQ(c.times_s.size(), 4u);
      EXPECT_GE(c.times_s[0], 13.0);
      int dir = c.first_direction;
      for (std::size_t i = 0; i < c.times_s.size(); ++i) {
        const double t = c.times_s[i];
        EXPECT_NEAR(model(s, t), c.level_div, 1e-9) << "k " << k << " level " << c.level_div;
        EXPECT_EQ(model_rate(s, t) > 0 ? +1 : -1, dir) << "k " << k << " passage " << i;
        if (i > 0) {
          EXPECT_GT(t, c.times_s[i - 1]);
          // Consecutive passages lie in consecutive half-cycles.
          EXPECT_LT(t - c.times_s[i - 1], 440.0);
        }
        dir = -dir;
      }
      // No passage of this level was skipped between start and the first one.
      const double w = 2 * kPi / 440.0;
      for (double t = 13.0; t < c.times_s[0] - 1e-6; t += 0.01) {
        const double f0 = model(s, t) - c.level_div;
        const double f1 = model(s, std::min(t + 0.01, c.times_s[0] - 1e-6)) - c.level_div;
        ASSERT_GT(f0 * f1, 0.0) << "missed a passage near t = " << t << " (w " << w << ")";
      }
    }
    // Reversals: ȧ = 0 exactly, alternating about β, at or after start.
    ASSERT_EQ(obs.reversals_div.size(), 5u);
    for (std::size_t i = 0; i < 5; ++i) {
      const double t = obs.reversal_times_s[i];
      EXPECT_GE(t, 13.0);
      EXPECT_NEAR(model_rate(s, t), 0.0, 1e-13);
      EXPECT_NEAR(obs.reversals_div[i], model(s, t), 1e-12);
      if (i > 0) {
        EXPECT_NEAR(t - obs.reversal_times_s[i - 1], 220.0, 1e-9);
        EXPECT_LT((obs.reversals_div[i] + 0.12) * (obs.reversals_div[i - 1] + 0.12), 0.0);
      }
    }
    // The first turning point after start: 160 s for k = 0, earlier by
    // atan(k/ω)/ω with damping; never the one before 13 s.
    const double shift = std::atan(k * 440.0 / (2 * kPi)) * 440.0 / (2 * kPi);
    EXPECT_NEAR(obs.reversal_times_s[0], 160.0 - shift, 1e-9);
  }
}

TEST(SimulatorNonTracking, DampedReversalsShrink) {
  NonTrackingSimulation s = scenario2();
  s.damping_per_s = 1e-4;
  s.reversals = 6;
  const NonTrackingObservations obs = simulate_nontracking(s, 3);
  for (std::size_t i = 2; i < obs.reversals_div.size(); ++i)
    EXPECT_LT(std::abs(obs.reversals_div[i] + 0.12), std::abs(obs.reversals_div[i - 2] + 0.12));
  // Turning point of a damped sinusoid: tan(ω s) = ω/k.
  const double w = 2 * kPi / 440.0;
  const double s1 = obs.reversal_times_s[0] - 50.0;
  EXPECT_NEAR(std::tan(w * s1), w / 1e-4, 1e-6 * w / 1e-4);
}

TEST(SimulatorNonTracking, StartTimeSelectsPassages) {
  NonTrackingSimulation s = scenario2();
  s.start_time_s = 100.0;
  s.levels_div = {0.0};
  const NonTrackingObservations obs = simulate_nontracking(s, 1);
  ASSERT_EQ(obs.crossings[0].times_s.size(), 3u);
  EXPECT_NEAR(obs.crossings[0].times_s[0], 269.066, 1e-3);
  EXPECT_EQ(obs.crossings[0].first_direction, -1);
  EXPECT_NEAR(obs.crossings[0].times_s[2], 709.066, 1e-3);
  EXPECT_NEAR(obs.reversals_div[0], 8.88, 1e-9);
  // Starting exactly on a turning point includes it.
  s.start_time_s = 160.0;
  EXPECT_NEAR(simulate_nontracking(s, 1).reversal_times_s[0], 160.0, 1e-9);
}

TEST(SimulatorNonTracking, UnreachedLevelIsAnInputError) {
  NonTrackingSimulation s = scenario2();
  s.levels_div = {0.0, 9.5};
  try {
    simulate_nontracking(s, 1);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.message(), testing::HasSubstr("level 9.5 div"));
    EXPECT_THAT(e.message(), testing::HasSubstr("never reached"));
  }
  // β − B exactly: touches but never crosses.
  s.levels_div = {-9.12};
  EXPECT_THROW(simulate_nontracking(s, 1), InputError);
  // Damping shrinks the amplitude below the level after a few passages.
  s.levels_div = {7.0};
  s.damping_per_s = 1e-3;
  s.crossings_per_level = 5;
  try {
    simulate_nontracking(s, 1);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.message(), testing::HasSubstr("level 7 div: only 2 of 5 passages"));
  }
}

TEST(SimulatorNonTracking, InvalidParameters) {
  auto bad = [](auto mutate) {
    NonTrackingSimulation s = scenario2();
    mutate(s);
    return s;
  };
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.amplitude_div = 0.0; }), 1), InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.period_s = -440.0; }), 1), InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.damping_per_s = -1e-5; }), 1), InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.beta_div = NAN; }), 1), InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.crossings_per_level = 0; }), 1),
               InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.reversals = -1; }), 1), InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.levels_div = {2.0, 0.0, 2.0}; }), 1),
               InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) {
                 s.levels_div.clear();
                 s.reversals = 0;
               }), 1),
               InputError);
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) { s.known_period_s = 0.0; }), 1), InputError);
  EXPECT_THROW(
      simulate_nontracking(bad([](auto& s) { s.time_noise = NoiseModel::markov1(0.1, 1.0, 0); }),
                           1),
      InputError);
  // Timing noise comparable to the half period scrambles the passages.
  EXPECT_THROW(simulate_nontracking(bad([](auto& s) {
                 s.levels_div = {8.0};
                 s.crossings_per_level = 20;
                 s.time_noise = NoiseModel::white(200.0);
               }), 5),
               InputError);
}

TEST(SimulatorNonTracking, NoiseIsSeededAndReported) {
  NonTrackingSimulation s = scenario2();
  s.time_noise = NoiseModel::white(0.1);
  s.reading_noise = NoiseModel::markov1(0.05, 0.5, 0.05);
  s.known_period_s = 440.0;
  s.known_period_sigma_s = 0.5;
  const NonTrackingObservations exact = simulate_nontracking(scenario2(), 42);
  const NonTrackingObservations a = simulate_nontracking(s, 42);
  const NonTrackingObservations b = simulate_nontracking(s, 42);
  const NonTrackingObservations c = simulate_nontracking(s, 43);
  bool any_diff = false;
  double max_dev = 0.0;
  for (std::size_t l = 0; l < a.crossings.size(); ++l)
    for (std::size_t i = 0; i < a.crossings[l].times_s.size(); ++i) {
      EXPECT_EQ(a.crossings[l].times_s[i], b.crossings[l].times_s[i]);
      any_diff |= a.crossings[l].times_s[i] != c.crossings[l].times_s[i];
      max_dev = std::max(max_dev, std::abs(a.crossings[l].times_s[i] -
                                           exact.crossings[l].times_s[i]));
    }
  EXPECT_TRUE(any_diff);
  EXPECT_GT(max_dev, 1e-4);
  EXPECT_LT(max_dev, 0.6);  // 6σ
  EXPECT_EQ(a.reversals_div, b.reversals_div);
  EXPECT_NE(a.reversals_div, c.reversals_div);
  EXPECT_NE(a.reversals_div, exact.reversals_div);
  // Reversal times are exact.
  EXPECT_EQ(a.reversal_times_s, exact.reversal_times_s);
  ASSERT_TRUE(a.period_s.has_value());
  EXPECT_DOUBLE_EQ(a.period_s->value, 440.0);
  EXPECT_DOUBLE_EQ(a.period_s->sigma, 0.5);
  EXPECT_DOUBLE_EQ(a.sigma_time_s, 0.1);
  EXPECT_NEAR(a.sigma_reading_div, 0.05 / std::sqrt(0.75), 1e-15);
  // Independent streams: more reversals leave the crossing times alone.
  NonTrackingSimulation more = s;
  more.reversals = 6;
  const NonTrackingObservations m = simulate_nontracking(more, 42);
  EXPECT_EQ(m.crossings[1].times_s, a.crossings[1].times_s);
  EXPECT_EQ(m.reversals_div[1], a.reversals_div[1]);
  // Explicit reported σ wins.
  s.reported_sigma_time_s = 0.2;
  s.reported_sigma_reading_div = 0.1;
  const NonTrackingObservations r = simulate_nontracking(s, 42);
  EXPECT_DOUBLE_EQ(r.sigma_time_s, 0.2);
  EXPECT_DOUBLE_EQ(r.sigma_reading_div, 0.1);
}

TEST(SimulatorNonTracking, FromPhysics) {
  const PhysicalGyro g{0.25, 0.088, 4.5e-6};
  const double phi = deg_to_rad(34.0);
  NonTrackingSimulation s = nontracking_simulation_from_physics(scenario2(), g, phi);
  EXPECT_DOUBLE_EQ(s.period_s, periods_from_physics(g, phi).nontracking_s);
  EXPECT_EQ(s.beta_div, -0.12);
  TrackingSimulation t = tracking_simulation_from_physics({}, g, phi);
  EXPECT_DOUBLE_EQ(t.period_s, periods_from_physics(g, phi).tracking_s);
  EXPECT_THROW(nontracking_simulation_from_physics(scenario2(), g, deg_to_rad(80.0)), InputError);
}

TEST(SimulatorNonTracking, BetaForNorthInvertsTheEquilibrium) {
  Instrument inst;
  inst.scale_value_rad = arcsec_to_rad(600.0);
  inst.torsion_ratio = {0.30, 0.0};
  // Spec §8: β = −0.12 div ⇔ ΔN = (1+λ)·τ·β = −93.6″.
  const double clamp = deg_to_rad(0.01);
  EXPECT_NEAR(beta_for_north(clamp + arcsec_to_rad(-93.6), clamp, inst), -0.12, 1e-12);
  // Across north, with a zero position.
  const double clamp2 = deg_to_rad(359.0 + 58.0 / 60.0);
  const double north = deg_to_rad(1.5 / 60.0);
  const double beta = beta_for_north(north, clamp2, inst, 0.4);
  const NorthReading nr = north_from_nontracking(clamp2, {beta, 0.0}, inst, Uncertain{0.4, 0.0});
  EXPECT_NEAR(meridian::wrap_signed_rad(nr.north_rad - north), 0.0, 1e-14);
  const double m = tracking_centre_for_north(north, inst, 0.4);
  const NorthReading tr = north_from_tracking({m, 0.0}, inst, Uncertain{0.4, 0.0});
  EXPECT_NEAR(meridian::wrap_signed_rad(tr.north_rad - north), 0.0, 1e-14);
  inst.scale_value_rad = 0.0;
  EXPECT_THROW(beta_for_north(north, clamp2, inst), InputError);
}

// ---------------------------------------------------------------------------
// Tracking and zero position
// ---------------------------------------------------------------------------

TEST(SimulatorTracking, MatchesR1AndWrapsAroundNorth) {
  // Spec §8 scenario 4: M = 0°12′34″, A = 8 div·600″, κ = 0.002.
  TrackingSimulation sim;
  sim.centre_rad = deg_to_rad(12.0 / 60.0 + 34.0 / 3600.0);
  sim.amplitude_rad = arcsec_to_rad(8 * 600.0);
  sim.kappa = 0.002;
  sim.reversals = 7;
  const std::vector<double> r = simulate_tracking(sim, 99);
  ASSERT_EQ(r.size(), 7u);
  for (int i = 1; i <= 7; ++i) {
    const double expected = sim.centre_rad + std::pow(-1.0, i) * sim.amplitude_rad *
                                                 std::exp(-i * 0.002);
    EXPECT_GE(r[i - 1], 0.0);
    EXPECT_LT(r[i - 1], 2 * kPi);
    EXPECT_NEAR(meridian::wrap_signed_rad(r[i - 1] - expected), 0.0, 1e-12);
  }
  // Odd readings lie west of north (≈ 358°52′), even ones east (≈ 1°32′).
  EXPECT_NEAR(r[0], deg_to_rad(358.0 + 52.0 / 60.0), deg_to_rad(1.0 / 60.0));
  EXPECT_NEAR(r[1], deg_to_rad(1.0 + 32.0 / 60.0), deg_to_rad(1.0 / 60.0));
  // Like 359°41′ and 0°44′.
  sim.centre_rad = deg_to_rad(12.5 / 60.0);
  sim.amplitude_rad = deg_to_rad(31.5 / 60.0);
  sim.kappa = 0.0;
  const std::vector<double> w = simulate_tracking(sim, 1);
  EXPECT_NEAR(w[0], deg_to_rad(359.0 + 41.0 / 60.0), 1e-12);
  EXPECT_NEAR(w[1], deg_to_rad(44.0 / 60.0), 1e-12);
}

TEST(SimulatorTracking, TimesAndNoise) {
  TrackingSimulation sim;
  sim.centre_rad = deg_to_rad(157.35);
  sim.amplitude_rad = deg_to_rad(1.0);
  sim.kappa = 0.01;
  sim.reversals = 5;
  sim.period_s = 480.0;
  sim.t0_s = 30.0;
  sim.reading_noise = NoiseModel::white(arcsec_to_rad(5.0));
  const TrackingSeries a = simulate_tracking_series(sim, 5);
  ASSERT_EQ(a.times_s.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i)
    EXPECT_DOUBLE_EQ(a.times_s[i], 30.0 + static_cast<double>(i + 1) * 240.0);
  EXPECT_EQ(a.readings_rad, simulate_tracking(sim, 5));
  EXPECT_NE(a.readings_rad, simulate_tracking(sim, 6));
  sim.period_s = 0.0;
  EXPECT_TRUE(simulate_tracking_series(sim, 5).times_s.empty());
  // Noise deviates are bounded and nonzero.
  sim.reading_noise = {};
  const std::vector<double> exact = simulate_tracking(sim, 5);
  double dev = 0.0;
  for (std::size_t i = 0; i < 5; ++i) dev = std::max(dev, std::abs(a.readings_rad[i] - exact[i]));
  EXPECT_GT(dev, arcsec_to_rad(0.01));
  EXPECT_LT(dev, arcsec_to_rad(30.0));
}

TEST(SimulatorTracking, InvalidInput) {
  TrackingSimulation sim;
  sim.amplitude_rad = 0.01;
  sim.reversals = 1;
  EXPECT_THROW(simulate_tracking(sim, 1), InputError);
  sim.reversals = 3;
  sim.kappa = -0.1;
  EXPECT_THROW(simulate_tracking(sim, 1), InputError);
  sim.kappa = 0.0;
  sim.amplitude_rad = -0.01;
  EXPECT_THROW(simulate_tracking(sim, 1), InputError);
  sim.amplitude_rad = 0.01;
  sim.centre_rad = INFINITY;
  EXPECT_THROW(simulate_tracking(sim, 1), InputError);
}

TEST(SimulatorZeroPosition, MatchesReversalModel) {
  const std::vector<double> z = simulate_zero_position(0.4, 6.0, 0.01, 6, {}, 1);
  ASSERT_EQ(z.size(), 6u);
  for (int i = 1; i <= 6; ++i)
    EXPECT_NEAR(z[i - 1], 0.4 + std::pow(-1.0, i) * 6.0 * std::exp(-0.01 * i), 1e-12);
  const NoiseModel n = NoiseModel::white(0.05);
  EXPECT_EQ(simulate_zero_position(0.4, 6.0, 0.01, 6, n, 8),
            simulate_zero_position(0.4, 6.0, 0.01, 6, n, 8));
  EXPECT_NE(simulate_zero_position(0.4, 6.0, 0.01, 6, n, 8),
            simulate_zero_position(0.4, 6.0, 0.01, 6, n, 9));
  EXPECT_THROW(simulate_zero_position(0.4, 6.0, 0.01, 1, n, 8), InputError);
}

// ---------------------------------------------------------------------------
// Noise
// ---------------------------------------------------------------------------

TEST(SimulatorNoise, SeedDeterminism) {
  for (const NoiseModel& m : {NoiseModel::white(1.0), NoiseModel::markov1(1.0, 0.6, 1.0),
                              NoiseModel::markov2(1.0, 0.5, 0.3, 1.0)}) {
    std::mt19937_64 a(123);
    std::mt19937_64 b(123);
    std::mt19937_64 c(124);
    const std::vector<double> x = generate_noise(m, 50, a);
    EXPECT_EQ(x, generate_noise(m, 50, b));
    EXPECT_NE(x, generate_noise(m, 50, c));
    // The engine advances: a second call gives a new series.
    EXPECT_NE(x, generate_noise(m, 50, a));
  }
  std::mt19937_64 e(1);
  EXPECT_EQ(generate_noise(NoiseModel::white(0.0), 10, e), std::vector<double>(10, 0.0));
  EXPECT_TRUE(generate_noise(NoiseModel::white(1.0), 0, e).empty());
}

TEST(SimulatorNoise, WhiteNoiseSigma) {
  std::mt19937_64 rng(2024);
  const std::vector<double> x = generate_noise(NoiseModel::white(0.05), 20000, rng);
  EXPECT_NEAR(std::sqrt(variance(x)), 0.05, 0.05 * 0.05);
  EXPECT_NEAR(mean(x), 0.0, 4 * 0.05 / std::sqrt(20000.0));
  EXPECT_NEAR(lag1_autocorrelation(x), 0.0, 0.03);
  EXPECT_DOUBLE_EQ(stationary_sigma(NoiseModel::white(0.05)), 0.05);
}

TEST(SimulatorNoise, Markov1AutocorrelationAndVariance) {
  for (double rho : {0.3, 0.7, -0.5}) {
    const double sigma = 2.0;
    const double stat = sigma / std::sqrt(1.0 - rho * rho);
    const NoiseModel m = NoiseModel::markov1(sigma, rho, stat);
    EXPECT_NEAR(stationary_sigma(m), stat, 1e-15);
    std::mt19937_64 rng(77);
    const std::vector<double> x = generate_noise(m, 100000, rng);
    EXPECT_NEAR(lag1_autocorrelation(x), rho, 0.02) << rho;
    EXPECT_NEAR(variance(x) / (stat * stat), 1.0, 0.04) << rho;
  }
}

TEST(SimulatorNoise, Markov2Autocorrelation) {
  const double r1 = 0.5;
  const double r2 = 0.3;
  const NoiseModel m = NoiseModel::markov2(1.0, r1, r2, 1.0);
  std::mt19937_64 rng(31);
  const std::vector<double> x = generate_noise(m, 200000, rng);
  const double rho_1 = r1 / (1.0 - r2);
  EXPECT_NEAR(lag1_autocorrelation(x) / rho_1, 1.0, 0.03);
  const double s = stationary_sigma(m);
  EXPECT_NEAR(s * s, (1 - r2) / ((1 + r2) * ((1 - r2) * (1 - r2) - r1 * r1)), 1e-12);
  EXPECT_NEAR(variance(x) / (s * s), 1.0, 0.06);
}

TEST(SimulatorNoise, RecursionMatchesSpecUnrolling) {
  // gyro-stochastic §3 check: ε_3 = Δ_3 + ρ1Δ_2 + (ρ1²+ρ2)Δ_1
  //   + (ρ1³+2ρ1ρ2)X_1 + (ρ1²ρ2+ρ2²)X_2, with the documented draw order.
  const double r1 = 0.4;
  const double r2 = -0.35;
  const double s = 1.5;
  const double s0 = 2.5;
  std::mt19937_64 rng(555);
  const std::vector<double> eps = generate_noise(NoiseModel::markov2(s, r1, r2, s0), 3, rng);
  std::mt19937_64 ref(555);
  std::normal_distribution<double> nd(0.0, 1.0);
  const double x1 = s0 * nd(ref);
  const double x2 = s0 * nd(ref);
  const double d1 = s * nd(ref);
  const double d2 = s * nd(ref);
  const double d3 = s * nd(ref);
  EXPECT_NEAR(eps[0], d1 + r1 * x1 + r2 * x2, 1e-12);
  EXPECT_NEAR(eps[2],
              d3 + r1 * d2 + (r1 * r1 + r2) * d1 + (r1 * r1 * r1 + 2 * r1 * r2) * x1 +
                  (r1 * r1 * r2 + r2 * r2) * x2,
              1e-12);
  // Markov-1: ε = B·X_0 + C·Δ with B_i = ρ^i, C_ij = ρ^{i−j}.
  std::mt19937_64 rng1(556);
  const std::vector<double> e1 = generate_noise(NoiseModel::markov1(s, 0.6, s0), 4, rng1);
  std::mt19937_64 ref1(556);
  std::normal_distribution<double> nd1(0.0, 1.0);
  const double x0 = s0 * nd1(ref1);
  std::vector<double> d(4);
  for (double& v : d) v = s * nd1(ref1);
  for (int i = 0; i < 4; ++i) {
    double expected = std::pow(0.6, i + 1) * x0;
    for (int j = 0; j <= i; ++j) expected += std::pow(0.6, i - j) * d[j];
    EXPECT_NEAR(e1[i], expected, 1e-12);
  }
}

TEST(SimulatorNoise, NonStationaryRejected) {
  std::mt19937_64 rng(1);
  EXPECT_THROW(generate_noise(NoiseModel::markov1(1.0, 1.0, 0.0), 5, rng), InputError);
  EXPECT_THROW(generate_noise(NoiseModel::markov1(1.0, -1.2, 0.0), 5, rng), InputError);
  EXPECT_THROW(generate_noise(NoiseModel::markov2(1.0, 0.6, 0.5, 0.0), 5, rng), InputError);
  EXPECT_THROW(generate_noise(NoiseModel::markov2(1.0, -0.6, 0.5, 0.0), 5, rng), InputError);
  EXPECT_THROW(generate_noise(NoiseModel::markov2(1.0, 0.0, -1.0, 0.0), 5, rng), InputError);
  EXPECT_THROW(generate_noise(NoiseModel::markov2(1.0, 0.0, 1.0, 0.0), 5, rng), InputError);
  EXPECT_NO_THROW(generate_noise(NoiseModel::markov2(1.0, 0.5, 0.49, 0.0), 5, rng));
  EXPECT_NO_THROW(generate_noise(NoiseModel::markov2(1.0, -1.5, -0.6, 0.0), 5, rng));
  EXPECT_THROW(generate_noise(NoiseModel::white(-1.0), 5, rng), InputError);
  EXPECT_THROW(generate_noise(NoiseModel::markov1(1.0, 0.5, NAN), 5, rng), InputError);
  NoiseModel w = NoiseModel::white(1.0);
  w.rho1 = 0.5;  // a forgotten kind
  EXPECT_THROW(generate_noise(w, 5, rng), InputError);
  NoiseModel m1 = NoiseModel::markov1(1.0, 0.5, 1.0);
  m1.rho2 = 0.1;
  EXPECT_THROW(generate_noise(m1, 5, rng), InputError);
  try {
    validate_noise_model(NoiseModel::markov2(1.0, 0.6, 0.5, 0.0));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.message(), testing::HasSubstr("not stationary"));
  }
}
