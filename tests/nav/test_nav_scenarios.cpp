// The validation scenarios of shared/spec/navigation.md §8 (nav::simulate), with the spec's
// qualitative results asserted numerically over 20 seeds (docs/navigation.md, "Scenarios").
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/nav/navigation.hpp"
#include "meridian/nav/simulator.hpp"

namespace meridian::nav {
namespace {

constexpr int kSeeds = 20;

// Per method: RMS over all seeds and epochs, and per minute (RMS over the seeds' epochs).
struct Curves {
  std::map<Method, double> rms_m;
  std::map<Method, std::vector<double>> per_minute_m;
  // RMS over minutes [from, to) of a method.
  double window(Method m, int from, int to) const {
    const auto& c = per_minute_m.at(m);
    double s = 0.0;
    for (int i = from; i < to; ++i) s += c[static_cast<std::size_t>(i)] * c[static_cast<std::size_t>(i)];
    return std::sqrt(s / (to - from));
  }
};

Curves curves(Scenario s) {
  Curves c;
  std::map<Method, double> total;
  std::map<Method, std::vector<double>> minute;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    SimulationOptions o;
    o.scenario = s;
    o.seed = static_cast<std::uint64_t>(seed);
    const Result r = process(simulate(o).input);
    for (const MethodResult& m : r.methods) {
      EXPECT_TRUE(m.errors.has_value());
      total[m.method] += m.errors->rms_m * m.errors->rms_m;
      auto& v = minute[m.method];
      v.resize(m.errors->per_minute_rms_m.size(), 0.0);
      for (std::size_t i = 0; i < v.size(); ++i)
        v[i] += m.errors->per_minute_rms_m[i] * m.errors->per_minute_rms_m[i];
    }
  }
  for (auto& [m, t] : total) {
    c.rms_m[m] = std::sqrt(t / kSeeds);
    for (double& v : minute[m]) v = std::sqrt(v / kSeeds);
    c.per_minute_m[m] = minute[m];
  }
  std::printf("scenario %s (%d seeds): RMS and per-minute RMS (m)\n", to_string(s).c_str(), kSeeds);
  for (const auto& [m, v] : c.per_minute_m) {
    std::printf("  %-20s %8.1f |", to_string(m).c_str(), c.rms_m.at(m));
    for (double x : v) std::printf(" %5.0f", x);
    std::printf("\n");
  }
  return c;
}

constexpr Method kForward[] = {Method::SequentialNoBias, Method::SequentialBiasI,
                               Method::SequentialBiasII, Method::Ekf};

TEST(NavScenarios, ABiasCorrectionFarBetterThanWithout) {
  const Curves c = curves(Scenario::A);
  EXPECT_LT(c.rms_m.at(Method::SequentialBiasI), c.rms_m.at(Method::SequentialNoBias) / 3.0);
  EXPECT_LT(c.rms_m.at(Method::SequentialBiasII), c.rms_m.at(Method::SequentialNoBias) / 3.0);
  // The smoothers lower the error further: RTS below every forward solution, the backward
  // correction below its forward run (bias I).
  for (Method m : kForward) EXPECT_LT(c.rms_m.at(Method::Rts), c.rms_m.at(m)) << to_string(m);
  EXPECT_LT(c.rms_m.at(Method::Backward), c.rms_m.at(Method::SequentialBiasI));
  EXPECT_LT(c.rms_m.at(Method::Ekf), c.rms_m.at(Method::SequentialBiasI));
}

TEST(NavScenarios, BNoBiasSmallErrors) {
  const Curves c = curves(Scenario::B);
  // σ = 50 m ranges from three stations: every method within 30 m RMS, dead reckoning too.
  for (const auto& [m, rms] : c.rms_m) EXPECT_LT(rms, 30.0) << to_string(m);
  for (Method m : kForward) EXPECT_LT(c.rms_m.at(Method::Rts), c.rms_m.at(m)) << to_string(m);
}

TEST(NavScenarios, CMethodTwoRecoversFasterAfterEachChange) {
  const Curves c = curves(Scenario::C);
  // Similar overall (within a factor of 2), II better in the 3 minutes after each change.
  const double i = c.rms_m.at(Method::SequentialBiasI);
  const double ii = c.rms_m.at(Method::SequentialBiasII);
  EXPECT_LT(ii, 2.0 * i);
  EXPECT_LT(i, 2.0 * ii);
  EXPECT_LT(c.window(Method::SequentialBiasII, 10, 13), c.window(Method::SequentialBiasI, 10, 13));
  EXPECT_LT(c.window(Method::SequentialBiasII, 15, 18), c.window(Method::SequentialBiasI, 15, 18));
  for (Method m : kForward) EXPECT_LT(c.rms_m.at(Method::Rts), c.rms_m.at(m)) << to_string(m);
}

TEST(NavScenarios, DConvergesFromABadStart) {
  const Curves d = curves(Scenario::D);
  const Curves a = curves(Scenario::A);
  // Steady state: scenario A's RMS over minutes 10–30 of the same method. The error of D
  // falls below 2× that within N minutes, N from these runs (docs/navigation.md): the EKF and
  // the smoother within 2 minutes and 1; sequential bias II within 8 — the time it needs in
  // scenario A too (bias_start_s = 3 min, then the running means), not the bad start: from
  // minute 2 on, D's curve stays within 1.5× A's plus 5 m.
  const std::map<Method, int> within = {
      {Method::SequentialBiasII, 8}, {Method::Ekf, 2}, {Method::Rts, 1}};
  for (const auto& [m, n] : within) {
    const double steady = a.window(m, 10, 30);
    const auto& curve = d.per_minute_m.at(m);
    int first = -1;
    for (int k = 0; k < 30; ++k)
      if (curve[static_cast<std::size_t>(k)] < 2.0 * steady) {
        first = k;
        break;
      }
    std::printf("  %s: steady %.1f m, below 2× steady from minute %d\n", to_string(m).c_str(),
                steady, first);
    EXPECT_GE(first, 0) << to_string(m);
    EXPECT_LE(first, n) << to_string(m);
  }
  for (std::size_t k = 2; k < 30; ++k)
    EXPECT_LT(d.per_minute_m.at(Method::SequentialBiasII)[k],
              1.5 * a.per_minute_m.at(Method::SequentialBiasII)[k] + 5.0)
        << "minute " << k;
  for (Method m : kForward) EXPECT_LT(d.rms_m.at(Method::Rts), d.rms_m.at(m)) << to_string(m);
}

}  // namespace
}  // namespace meridian::nav
