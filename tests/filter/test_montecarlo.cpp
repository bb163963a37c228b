// Monte Carlo validation of the filter's consistency (label `montecarlo`: the Release pass of
// scripts/test.sh runs it, the sanitizer pass skips it). 300 independent replications of a
// double integrator observed in position: the average NEES and NIS lie inside their 95 %
// χ² intervals for the correct model and outside them when the process or measurement noise
// the filter assumes is wrong — the check can fail.
#include <cmath>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "example_models.hpp"
#include "meridian/filter/consistency.hpp"
#include "meridian/filter/discretisation.hpp"
#include "meridian/filter/kalman_filter.hpp"

namespace {

using meridian::filter::ConsistencyRun;
using meridian::filter::Estimate;
using meridian::filter::KalmanFilter;
using meridian::filter::Matrix;
using meridian::filter::monte_carlo_consistency;
using meridian::filter::MonteCarloConsistency;
using meridian::filter::nees;
using meridian::filter::Vector;
using namespace meridian::filter::examples;

// Oscillator-free double integrator: position observed every second, 25 epochs. The truth
// uses (q, r); the filter assumes (q_filter, r_filter).
struct Scenario {
  double q = 0.1;
  double r = 1.0;
  double q_filter = 0.1;
  double r_filter = 1.0;
};

struct S {
  static constexpr int pos = 0;
  static constexpr int vel = 1;
  static constexpr int size = 2;
};

MonteCarloConsistency run(const Scenario& s) {
  meridian::filter::ContinuousModel<S::size, 1> model;
  model.F << 0.0, 1.0, 0.0, 0.0;
  model.G << 0.0, 1.0;
  model.q_c(0, 0) = s.q;
  const auto truth_step = meridian::filter::discretise(model, 1.0);
  model.q_c(0, 0) = s.q_filter;
  const auto filter_step = meridian::filter::discretise(model, 1.0);
  Matrix<1, S::size> H;
  H << 1.0, 0.0;
  const Estimate<S::size> init{Vector<S::size>::Zero(), Vector<S::size>(10.0, 1.0).asDiagonal()};
  return monte_carlo_consistency(
      300,
      [&](int r) {
        std::mt19937_64 rng(1000 + static_cast<std::uint64_t>(r));
        std::normal_distribution<double> nd;
        Vector<S::size> x = init.x + draw<S::size>(init.P, rng);
        KalmanFilter<S::size> kf(init);
        ConsistencyRun out;
        for (int k = 0; k < 25; ++k) {
          if (k > 0) {
            x = truth_step.phi * x + draw<S::size>(truth_step.q, rng);
            kf.predict(filter_step);
          }
          const double z = x(S::pos) + std::sqrt(s.r) * nd(rng);
          const auto in = kf.update(Vector<1>::Constant(z), H, Matrix<1, 1>::Constant(s.r_filter));
          out.nis.push_back(in.nis);
          out.nees.push_back(nees(x, kf.estimate(), k));
        }
        return out;
      },
      S::size, 1.0);
}

TEST(Consistency, MonteCarloAcceptsTheCorrectModel) {
  const MonteCarloConsistency mc = run(Scenario{});
  EXPECT_EQ(mc.runs, 300);
  // Per epoch the 300 runs are independent: ~95 % of the epochs' averages inside.
  EXPECT_GE(mc.nees.fraction_inside, 0.8);
  EXPECT_GE(mc.nis.fraction_inside, 0.8);
  // NIS is white for a correct model: the average over runs and epochs is inside too.
  EXPECT_TRUE(mc.nis.overall_inside()) << mc.nis.overall_average;
  EXPECT_NEAR(mc.nees.overall_average, 2.0, 0.15);
  // The last epoch's averages (300 independent runs: an exact χ²(600)/300 interval).
  EXPECT_TRUE(mc.nees.epoch_interval.contains(mc.nees.average.back())) << mc.nees.average.back();
  EXPECT_TRUE(mc.nis.epoch_interval.contains(mc.nis.average.back())) << mc.nis.average.back();
  RecordProperty("nees_overall", std::to_string(mc.nees.overall_average));
  RecordProperty("nis_overall", std::to_string(mc.nis.overall_average));
}

TEST(Consistency, MonteCarloRejectsMisSpecifiedModels) {
  // Process noise assumed 20× too small: errors larger than P says.
  Scenario optimistic;
  optimistic.q_filter = optimistic.q / 20.0;
  const MonteCarloConsistency a = run(optimistic);
  EXPECT_LE(a.nees.fraction_inside, 0.2);
  EXPECT_LE(a.nis.fraction_inside, 0.2);
  EXPECT_GT(a.nees.overall_average, a.nees.overall_interval.upper);
  EXPECT_GT(a.nis.overall_average, a.nis.overall_interval.upper);
  // Measurement noise assumed 4× too large (σ 2×): the filter is pessimistic.
  Scenario pessimistic;
  pessimistic.r_filter = 4.0 * pessimistic.r;
  const MonteCarloConsistency b = run(pessimistic);
  EXPECT_LE(b.nis.fraction_inside, 0.2);
  EXPECT_LT(b.nis.overall_average, b.nis.overall_interval.lower);
  EXPECT_LT(b.nees.overall_average, b.nees.overall_interval.lower);
}

}  // namespace
