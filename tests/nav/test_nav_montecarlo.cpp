// Monte Carlo consistency of the reported σ (docs/navigation.md, "Consistency"): the EKF and
// its RTS smoother over 100 seeds of scenarios A and B with the bias modelled as it is
// simulated (constant: a random walk of 0.0002 m/s/√s), NEES of the 2-D position per epoch
// after a 5-minute burn-in (the prior σ of the bias, 1 m/s, is far wider than the simulated
// 0.5 m/s and keeps the first minutes' NEES low). A deliberately mis-specified model
// (LOP σ stated as 25 m, simulated 50 m) must fail the same check.
#include <cstdio>

#include <gtest/gtest.h>

#include "meridian/filter/consistency.hpp"
#include "meridian/nav/navigation.hpp"
#include "meridian/nav/simulator.hpp"

namespace meridian::nav {
namespace {

constexpr int kRuns = 100;
constexpr std::size_t kBurnIn = 60;  // epochs of 5 s

filter::MonteCarloConsistency consistency(Scenario s, Method m, double stated_sigma_m) {
  return filter::monte_carlo_consistency(
      kRuns,
      [&](int r) {
        SimulationOptions o;
        o.scenario = s;
        o.seed = 1000 + static_cast<std::uint64_t>(r);
        SimulatedLine line = simulate(o);
        line.input.options.bias_random_walk_m_s_per_sqrt_s = 0.0002;
        for (Lop& l : line.input.lops) l.sigma_m = stated_sigma_m;
        const Result res = process(line.input);
        const MethodResult& mr = *res.find(m);
        filter::ConsistencyRun run;
        for (std::size_t k = kBurnIn; k < mr.track.size(); ++k) {
          const TrackPoint& t = mr.track[k];
          const Eigen::Vector2d d(t.x_north_m - line.input.truth[k].x_north_m,
                                  t.y_east_m - line.input.truth[k].y_east_m);
          run.nees.push_back(d.dot(t.covariance.ldlt().solve(d)));
        }
        return run;
      },
      2.0, 1.0);
}

TEST(NavMonteCarlo, EkfAndRtsSigmasMatchTheScatter) {
  for (Scenario s : {Scenario::A, Scenario::B})
    for (Method m : {Method::Ekf, Method::Rts}) {
      const auto mc = consistency(s, m, 50.0);
      std::printf("%s %s: mean NEES %.3f, epochs inside their 95 %% interval [%.2f, %.2f]: %.2f\n",
                  to_string(s).c_str(), to_string(m).c_str(), mc.nees.overall_average,
                  mc.nees.epoch_interval.lower, mc.nees.epoch_interval.upper,
                  mc.nees.fraction_inside);
      EXPECT_GE(mc.nees.fraction_inside, 0.90) << to_string(s) << " " << to_string(m);
      EXPECT_NEAR(mc.nees.overall_average, 2.0, 0.2) << to_string(s) << " " << to_string(m);
    }
}

TEST(NavMonteCarlo, AMisSpecifiedModelFailsTheCheck) {
  const auto mc = consistency(Scenario::A, Method::Rts, 25.0);
  std::printf("LOP σ stated 25 m: mean NEES %.3f, inside %.2f\n", mc.nees.overall_average,
              mc.nees.fraction_inside);
  EXPECT_LT(mc.nees.fraction_inside, 0.2);
  EXPECT_GT(mc.nees.overall_average, 3.0);
}

}  // namespace
}  // namespace meridian::nav
