// Validation scenarios 1–3 of gyro-theodolite spec §8 for the non-tracking
// reductions. Observations are generated here by inverting (N1) analytically;
// expected values come from the spec or from closed forms.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "meridian/core/units.hpp"
#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/nontracking.hpp"
#include "nontracking_truth.hpp"
#include "meridian/gyro/unified_fit.hpp"

namespace {

using meridian::gyro::BetaResult;
using meridian::gyro::Crossing;
using meridian::gyro::Instrument;
using meridian::gyro::NonTrackingMethod;
using meridian::gyro::NonTrackingObservations;
using meridian::gyro::Uncertain;
using meridian::units::kArcsecond;
using meridian::units::kPi;

using meridian_test::Truth;
using meridian_test::passages;
using meridian_test::add_reversals;
using meridian_test::scenario_instrument;

// Levels 0, −2, +2 timed three times each from t_from, two reversals with
// their times, T_B known.
NonTrackingObservations scenario_observations(const Truth& o, double t_from) {
  NonTrackingObservations obs;
  for (double level : {0.0, -2.0, 2.0}) obs.crossings.push_back(passages(o, level, t_from, 3));
  add_reversals(obs, o, t_from + 60.0, 2);
  obs.period_s = Uncertain{o.period, 0.0};
  return obs;
}

double delta_n_arcsec(const BetaResult& r, const Instrument& inst) {
  return meridian::gyro::north_from_nontracking(0.0, r.beta_div, inst).delta_n_rad / kArcsecond;
}

bool is_small_angle(NonTrackingMethod m) {
  return m == NonTrackingMethod::Transit || m == NonTrackingMethod::TimeDifference;
}

// ---------------------------------------------------------------------------
// Scenario 2

TEST(NonTrackingScenario2, GeneratedTimesMatchTheSpec) {
  const NonTrackingObservations obs = scenario_observations(Truth{}, 30.0);
  const std::vector<std::vector<double>> spec = {{50.934, 269.066, 490.934},
                                                 {35.263, 284.737, 475.263},
                                                 {66.652, 253.348, 506.652}};
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(obs.crossings[c].first_direction, +1);
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_NEAR(obs.crossings[c].times_s[k], spec[c][k], 1e-3) << c << " " << k;
  }
  ASSERT_EQ(obs.reversals_div.size(), 2u);
  EXPECT_NEAR(obs.reversals_div[0], 8.88, 1e-12);
  EXPECT_NEAR(obs.reversals_div[1], -9.12, 1e-12);
  EXPECT_NEAR(obs.reversal_times_s[0], 160.0, 1e-9);
}

TEST(NonTrackingScenario2, EveryMethodReproducesTheSpecValues) {
  const Instrument inst = scenario_instrument();
  const NonTrackingObservations obs = scenario_observations(Truth{}, 30.0);
  std::map<NonTrackingMethod, double> dn;
  for (NonTrackingMethod m : meridian::gyro::applicable_methods(obs)) {
    const BetaResult r = meridian::gyro::reduce_nontracking(m, obs, inst);
    dn[m] = delta_n_arcsec(r, inst);
    std::printf("  scenario 2  %-18s ΔN = %10.4f″  approx. error = %8.4f″\n",
                meridian::gyro::to_string(m).c_str(), dn[m],
                r.approximation_error_div * 1.3 * 600.0);
  }
  ASSERT_EQ(dn.size(), 6u);
  for (NonTrackingMethod m : {NonTrackingMethod::Direct, NonTrackingMethod::TimedAmplitude1,
                              NonTrackingMethod::TimedAmplitude2, NonTrackingMethod::LeastSquares})
    EXPECT_NEAR(dn[m], -93.600, 0.01) << meridian::gyro::to_string(m);
  // Transit: β_small = −B·asin(0.12/9) exactly for these data.
  EXPECT_NEAR(dn[NonTrackingMethod::Transit], -93.603, 0.001);
  EXPECT_NEAR(dn[NonTrackingMethod::Transit], -780.0 * 9.0 * std::asin(0.12 / 9.0), 1e-6);
  // Time difference with levels ±2: (a_i·ψ_j − a_j·ψ_i)/(ψ_j − ψ_i), ψ = asin((a − β)/B).
  const double pi_ = std::asin(-1.88 / 9.0);
  const double pj = std::asin(2.12 / 9.0);
  const double beta_td = (-2.0 * pj - 2.0 * pi_) / (pj - pi_);
  EXPECT_NEAR(dn[NonTrackingMethod::TimeDifference], -95.193, 0.001);
  EXPECT_NEAR(dn[NonTrackingMethod::TimeDifference], 780.0 * beta_td, 1e-6);

  // The reported approximation errors and the transit ΔN.
  const BetaResult td = meridian::gyro::reduce_nontracking(NonTrackingMethod::TimeDifference, obs,
                                                           inst);
  EXPECT_NEAR(td.approximation_error_div * 780.0, -1.593, 0.001);
  EXPECT_NEAR(td.approximation_error_div, beta_td + 0.12, 1e-9);
  ASSERT_TRUE(td.period_s && td.amplitude_div);
  EXPECT_NEAR(td.period_s->value, 440.0, 1e-9);
  EXPECT_NEAR(td.amplitude_div->value, 9.0, 1e-9);
  // 1.6″ is more than 0.1 of the run's σ (4.3″): a warning.
  const double td_sigma = meridian::gyro::north_from_nontracking(0.0, td.beta_div, inst).sigma_rad;
  EXPECT_NEAR(td_sigma / kArcsecond, 4.3, 0.1);
  EXPECT_FALSE(meridian::gyro::small_angle_warning(
                   td, td.approximation_error_div * 780.0 * kArcsecond, td_sigma)
                   .empty());
  const BetaResult tr = meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst);
  EXPECT_NEAR(tr.approximation_error_div * 780.0, -93.603 + 93.600, 5e-4);
  ASSERT_TRUE(tr.transit_delta_n_rad);
  EXPECT_NEAR(tr.transit_delta_n_rad->value / kArcsecond, dn[NonTrackingMethod::Transit], 1e-9);
  EXPECT_TRUE(tr.warnings.empty());
  EXPECT_TRUE(meridian::gyro::small_angle_warning(
                  tr, tr.approximation_error_div * 780.0 * kArcsecond, 6.1 * kArcsecond)
                  .empty());
  // The transit factor c = 2.785″/(div·s): ΔN = c·B·Δt.
  EXPECT_NEAR(tr.transit_delta_n_rad->value / kArcsecond,
              1.3 * 600.0 * kPi / 880.0 * 9.0 * tr.time_difference_s->value, 1e-9);
}

// ---------------------------------------------------------------------------
// Scenario 1: noise-free data over a range of β on both sides of north and
// with either first direction.

TEST(NonTrackingScenario1, NoiseFreeDataOverARangeOfBeta) {
  const Instrument inst = scenario_instrument();
  for (double beta : {-1.0, -0.6, -0.3, -0.1, -0.02, 0.0, 0.02, 0.1, 0.3, 0.6, 1.0}) {
    for (double t_from : {30.0, 150.0, 290.0}) {
      const Truth o{beta, 9.0, 440.0, 50.0};
      const NonTrackingObservations obs = scenario_observations(o, t_from);
      const double truth = 1.3 * 600.0 * beta;
      const auto methods = meridian::gyro::applicable_methods(obs);
      ASSERT_EQ(methods.size(), 6u);
      for (NonTrackingMethod m : methods) {
        const BetaResult r = meridian::gyro::reduce_nontracking(m, obs, inst);
        const double dn = delta_n_arcsec(r, inst);
        if (is_small_angle(m)) {
          EXPECT_NEAR(dn - r.approximation_error_div * 780.0, truth, 0.01)
              << meridian::gyro::to_string(m) << " β = " << beta << " from " << t_from;
        } else {
          EXPECT_EQ(r.approximation_error_div, 0.0);
          EXPECT_NEAR(dn, truth, 0.01)
              << meridian::gyro::to_string(m) << " β = " << beta << " from " << t_from;
        }
      }
    }
  }
}

TEST(NonTrackingScenario1, ApproximationErrorShrinksAsBetaGoesToZero) {
  const Instrument inst = scenario_instrument();
  for (NonTrackingMethod m : {NonTrackingMethod::Transit, NonTrackingMethod::TimeDifference}) {
    for (double sign : {1.0, -1.0}) {
      double previous = INFINITY;
      // The time-difference error (levels ±2, B = 9) is odd in β with its
      // maximum near |β| = 1.1 div (≈ 10″); from |β| = 1 div down it shrinks
      // monotonically, linearly in β; the transit error like β³.
      for (double beta : {1.0, 0.75, 0.5, 0.25, 0.1, 0.05, 0.01, 0.001}) {
        const NonTrackingObservations obs =
            scenario_observations(Truth{sign * beta, 9.0, 440.0, 50.0}, 30.0);
        const double err =
            std::abs(meridian::gyro::reduce_nontracking(m, obs, inst).approximation_error_div);
        EXPECT_LT(err, previous) << meridian::gyro::to_string(m) << " β = " << sign * beta;
        previous = err;
      }
      EXPECT_LT(previous * 780.0, 0.02) << meridian::gyro::to_string(m);
    }
  }
}

// ---------------------------------------------------------------------------
// Scenario 3: Monte Carlo, reading noise 0.05 div, timing noise 0.1 s, and a
// known T_B with σ = 0.5 s drawn afresh in every run.

TEST(NonTrackingScenario3, MonteCarloSigmaMatchesReportedSigma) {
  constexpr int kRuns = 1000;
  const double sigma_t = 0.1;
  const double sigma_a = 0.05;
  const double sigma_period = 0.5;
  const Instrument inst = scenario_instrument();
  const Truth o;
  const NonTrackingObservations exact = scenario_observations(o, 30.0);
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> gauss(0.0, 1.0);

  struct Stats {
    double sum = 0.0, sum2 = 0.0, reported2 = 0.0;
    int n = 0;
  };
  std::map<std::string, Stats> stats;
  const auto record = [&](const std::string& name, const Uncertain& beta) {
    Stats& s = stats[name];
    s.sum += beta.value;
    s.sum2 += beta.value * beta.value;
    s.reported2 += beta.sigma * beta.sigma;
    ++s.n;
  };
  for (int run = 0; run < kRuns; ++run) {
    NonTrackingObservations obs = exact;
    for (auto& c : obs.crossings)
      for (double& t : c.times_s) t += sigma_t * gauss(rng);
    for (double& a : obs.reversals_div) a += sigma_a * gauss(rng);
    obs.period_s = Uncertain{o.period + sigma_period * gauss(rng), sigma_period};
    obs.sigma_time_s = sigma_t;
    obs.sigma_reading_div = sigma_a;
    for (NonTrackingMethod m : meridian::gyro::applicable_methods(obs)) {
      if (m == NonTrackingMethod::LeastSquares) continue;  // below, without the comparison table
      record(meridian::gyro::to_string(m),
             meridian::gyro::reduce_nontracking(m, obs, inst).beta_div);
    }
    meridian::gyro::UnifiedFitOptions fit_only;  // period_s as an observation (σ 0.5 s)
    fit_only.compare_simple_methods = false;
    record("lsq", meridian::gyro::fit_nontracking(obs, inst, fit_only).beta_div);
    NonTrackingObservations free = obs;  // transit with T_B = t3 − t1 from the transits
    free.period_s.reset();
    record("transit (T from times)",
           meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, free, inst).beta_div);
  }
  ASSERT_EQ(stats.size(), 7u);
  for (const auto& [name, s] : stats) {
    ASSERT_EQ(s.n, kRuns);
    const double mean = s.sum / s.n;
    const double empirical = std::sqrt((s.sum2 - s.n * mean * mean) / (s.n - 1));
    const double reported = std::sqrt(s.reported2 / s.n);
    const double ratio = empirical / reported;
    std::printf("  scenario 3  %-24s σ empirical %.5f div, reported %.5f div (%.2f″), ratio %.3f\n",
                name.c_str(), empirical, reported, reported * 780.0, ratio);
    EXPECT_GT(ratio, 0.9) << name;
    EXPECT_LT(ratio, 1.1) << name;
  }
}

}  // namespace
