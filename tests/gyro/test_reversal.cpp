// Reversal-point estimators (spec §3) and tracking recovery (spec §8.4).

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/reversal.hpp"
#include "meridian/gyro/tracking.hpp"

using namespace meridian;
using namespace meridian::gyro;

namespace {

// (R1) evaluated directly — the independent reference.
std::vector<double> r1(double m, double a, double kappa, int n) {
  std::vector<double> r;
  for (int i = 1; i <= n; ++i) r.push_back(m + ((i % 2 == 0) ? 1.0 : -1.0) * a * std::exp(-i * kappa));
  return r;
}
}  // namespace

TEST(Reversal, ClosedFormsOfTheSpec) {
  const std::vector<double> r{-8.1, 9.3, -7.9, 9.0, -7.7};
  const double nan = std::nan("");
  EXPECT_DOUBLE_EQ(estimate_centre(ReversalMethod::TwoPoint, r, nan).centre.value, 0.5 * (-8.1 + 9.3));
  const std::vector<double> r3(r.begin(), r.begin() + 3);
  const double schuler3 = (r[0] + 2 * r[1] + r[2]) / 4;
  EXPECT_NEAR(estimate_centre(ReversalMethod::Schuler, r3, nan).centre.value, schuler3, 1e-14);
  // n = 5: (r1 + 3r2 + 4r3 + 3r4 + r5)/12.
  const double schuler5 = (r[0] + 3 * r[1] + 4 * r[2] + 3 * r[3] + r[4]) / 12;
  const auto s5 = estimate_centre(ReversalMethod::Schuler, r, nan);
  EXPECT_NEAR(s5.centre.value, schuler5, 1e-14);
  ASSERT_EQ(s5.partial_means.size(), 3u);
  // Linear LS reproduces the Schuler mean for n = 3 and the spec's n = 5 weights.
  const auto l3 = estimate_centre(ReversalMethod::LinearLsq, r3, 0.05);
  EXPECT_NEAR(l3.centre.value, schuler3, 1e-12);
  EXPECT_NEAR(l3.cofactor_centre, 0.375, 1e-12);
  EXPECT_NEAR(l3.centre.sigma, 0.05 * std::sqrt(0.375), 1e-12);  // a-priori, no redundancy
  EXPECT_FALSE(l3.sigma_is_aposteriori);
  const auto l5 = estimate_centre(ReversalMethod::LinearLsq, r, nan);
  EXPECT_NEAR(l5.centre.value, (2 * r[0] + 3 * r[1] + 2 * r[2] + 3 * r[3] + 2 * r[4]) / 12, 1e-12);
  EXPECT_NEAR(l5.cofactor_centre, 5.0 / 24.0, 1e-12);  // 0.2083
  EXPECT_EQ(l5.dof, 2);
  EXPECT_TRUE(l5.sigma_is_aposteriori);
  EXPECT_NEAR(l5.centre.sigma, l5.sigma0 * std::sqrt(5.0 / 24.0), 1e-15);
}

TEST(Reversal, TrackingRecoveryScenario4) {
  // M = 0°12'34", A = 8 div·τ (τ = 600"), κ = 0.002, no noise.
  const double m = (12 * 60 + 34) * units::kArcsecond;
  const double a = 8 * 600 * units::kArcsecond;
  for (int n : {3, 5, 7}) {
    const auto r = r1(m, a, 0.002, n);
    const auto nl = estimate_centre(ReversalMethod::NonlinearLsq, r, std::nan(""));
    EXPECT_NEAR(nl.centre.value / units::kArcsecond, m / units::kArcsecond, 0.01) << "n = " << n;
    EXPECT_NEAR(nl.damping->value, 0.002, 1e-9);
    EXPECT_NEAR(nl.amplitude->value, a, 1e-9);
    // The linearised estimators carry the second-order damping error only:
    // a few hundredths of an arc-second for κ = 0.002 and A = 80'.
    EXPECT_NEAR(estimate_centre(ReversalMethod::Schuler, r, 0).centre.value / units::kArcsecond,
                m / units::kArcsecond, 0.5);
    EXPECT_NEAR(estimate_centre(ReversalMethod::LinearLsq, r, 0).centre.value / units::kArcsecond,
                m / units::kArcsecond, 0.5);
  }
  // Without damping the linear forms are exact.
  const auto r = r1(m, a, 0.0, 5);
  EXPECT_NEAR(estimate_centre(ReversalMethod::Schuler, r, 0).centre.value / units::kArcsecond,
              m / units::kArcsecond, 1e-9);
  EXPECT_NEAR(estimate_centre(ReversalMethod::LinearLsq, r, 0).centre.value / units::kArcsecond,
              m / units::kArcsecond, 1e-9);
}

TEST(Reversal, TrackingAcrossNorthWraps) {
  // The example readings straddle 0°/360°.
  TrackingObservations obs;
  for (double d : {359 + 41 / 60.0 + 12 / 3600.0, 0 + 44 / 60.0 + 50 / 3600.0, 359 + 42 / 60.0 + 4 / 3600.0})
    obs.reversals_rad.push_back(d * units::kDegree);
  Instrument inst;
  inst.scale_value_rad = 600 * units::kArcsecond;
  inst.torsion_ratio = {0.3, 0};
  const auto t = reduce_tracking(ReversalMethod::Schuler, obs, inst);
  // (r1 + 2r2 + r3)/4 with r unwrapped about r1: 0°13'14" (−0°… + 2·0°44'50" …)/4.
  const double r1v = -(18 * 60 + 48) * units::kArcsecond, r2v = (44 * 60 + 50) * units::kArcsecond,
               r3v = -(17 * 60 + 56) * units::kArcsecond;
  EXPECT_NEAR(t.north.north_rad / units::kArcsecond, (r1v + 2 * r2v + r3v) / 4 / units::kArcsecond,
              1e-6);
  // With α_p: N_G = M − λτα_p.
  const auto z = reduce_tracking(ReversalMethod::Schuler, obs, inst, Uncertain{0.5, 0.0});
  EXPECT_NEAR((z.north.north_rad - t.north.north_rad) / units::kArcsecond, -0.3 * 600 * 0.5, 1e-6);
}

TEST(Reversal, RejectsNonReversalData) {
  const double nan = std::nan("");
  EXPECT_THROW(estimate_centre(ReversalMethod::TwoPoint, std::vector<double>{1.0}, nan), InputError);
  EXPECT_THROW(estimate_centre(ReversalMethod::Schuler, std::vector<double>{-1.0, 1.0}, nan), InputError);
  try {
    estimate_centre(ReversalMethod::Schuler, std::vector<double>{-1.0, 1.0, 2.0, -1.0}, nan);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reading 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(estimate_centre(ReversalMethod::Schuler, std::vector<double>{-1.0, nan, -1.0}, nan), InputError);
  EXPECT_THROW(estimate_centre(ReversalMethod::Schuler, std::vector<double>{1.0, 1.0, 1.0}, nan), InputError);
  EXPECT_THROW(reversal_method_from_string("schuller"), InputError);
}

TEST(Reversal, MonteCarloSigmaMatchesScatter) {
  // White reading noise σ = 10": the a-posteriori σ of M (mean over runs, as
  // its square) agrees with the empirical scatter of M within 10 %.
  const double m = 0.01, a = 8 * 600 * units::kArcsecond, sigma = 10 * units::kArcsecond;
  std::mt19937_64 rng(20261122);
  std::normal_distribution<double> noise(0.0, sigma);
  for (auto method : {ReversalMethod::LinearLsq, ReversalMethod::NonlinearLsq, ReversalMethod::Schuler}) {
    const int runs = 1000;
    double sum = 0, sum2 = 0, reported2 = 0;
    for (int k = 0; k < runs; ++k) {
      auto r = r1(m, a, 0.002, 7);
      for (auto& x : r) x += noise(rng);
      const auto e = estimate_centre(method, r, std::nan(""));
      sum += e.centre.value;
      sum2 += e.centre.value * e.centre.value;
      reported2 += e.centre.sigma * e.centre.sigma;
    }
    const double mean = sum / runs;
    const double empirical = std::sqrt(sum2 / runs - mean * mean);
    const double reported = std::sqrt(reported2 / runs);
    EXPECT_NEAR(reported / empirical, 1.0, 0.10) << to_string(method);
  }
}

// Which σ the centre carries (issue 15): with a stated reading σ the a-priori
// σ_r·sqrt(q_MM), guarded by the global test T = dof·σ̂0²/σ_r² against
// χ²_0.99(dof) (for dof = 2 the closed form −2·ln 0.01 = 9.2103); when it
// rejects, the larger a-posteriori σ̂0·sqrt(q_MM) and a warning.
TEST(Reversal, StatedReadingSigmaIsUsedAndTested) {
  auto r = r1(0.1, 8.0, 0.01, 5);
  const double e[] = {0.02, -0.03, 0.01, 0.04, -0.02};
  for (int i = 0; i < 5; ++i) r[static_cast<std::size_t>(i)] += e[i];
  const double chi2_99_2 = -2.0 * std::log(0.01);
  for (auto method :
       {ReversalMethod::Schuler, ReversalMethod::LinearLsq, ReversalMethod::NonlinearLsq}) {
    const auto free = estimate_centre(method, r, std::nan(""));
    ASSERT_EQ(free.dof, 2) << to_string(method);
    EXPECT_TRUE(free.sigma_is_aposteriori);
    EXPECT_FALSE(free.reading_sigma_test);
    EXPECT_NEAR(free.centre.sigma, free.sigma0 * std::sqrt(free.cofactor_centre), 1e-15);
    for (double stated : {0.05, 0.005}) {
      const auto s = estimate_centre(method, r, stated);
      ASSERT_TRUE(s.reading_sigma_test) << to_string(method);
      const auto& g = *s.reading_sigma_test;
      const double t = 2.0 * std::pow(s.sigma0 / stated, 2);
      EXPECT_NEAR(g.vtpv, t, 1e-9 * t);
      EXPECT_EQ(g.dof, 2);
      EXPECT_NEAR(g.critical_value, chi2_99_2, 1e-9);
      EXPECT_EQ(g.rejected, t > chi2_99_2);
      EXPECT_EQ(s.sigma_is_aposteriori, g.rejected);
      EXPECT_EQ(s.sigma_reading, stated);
      const double expected = (g.rejected ? s.sigma0 : stated) * std::sqrt(s.cofactor_centre);
      EXPECT_NEAR(s.centre.sigma, expected, 1e-15) << to_string(method) << " stated " << stated;
      EXPECT_EQ(reading_sigma_warning(s, 1.0, " div", 3).empty(), !g.rejected);
    }
    // 0.05 div is consistent with these readings, 0.005 div is not.
    EXPECT_FALSE(estimate_centre(method, r, 0.05).reading_sigma_test->rejected)
        << to_string(method);
    EXPECT_TRUE(estimate_centre(method, r, 0.005).reading_sigma_test->rejected)
        << to_string(method);
  }
}

// The successive Schuler means and their spread, for every three-point method.
TEST(Reversal, SuccessiveSchulerMeansAndSpread) {
  const std::vector<double> r{-8.1, 9.3, -7.9, 9.0, -7.7};
  const double m[] = {(r[0] + 2 * r[1] + r[2]) / 4, (r[1] + 2 * r[2] + r[3]) / 4,
                      (r[2] + 2 * r[3] + r[4]) / 4};
  const double spread = std::max({m[0], m[1], m[2]}) - std::min({m[0], m[1], m[2]});
  for (auto method :
       {ReversalMethod::Schuler, ReversalMethod::LinearLsq, ReversalMethod::NonlinearLsq}) {
    const auto s = estimate_centre(method, r, 0.05);
    ASSERT_EQ(s.partial_means.size(), 3u);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(s.partial_means[static_cast<std::size_t>(i)], m[i], 1e-14);
    ASSERT_TRUE(s.partial_means_spread);
    EXPECT_NEAR(*s.partial_means_spread, spread, 1e-14);
  }
  const std::vector<double> r3(r.begin(), r.begin() + 3);
  EXPECT_FALSE(estimate_centre(ReversalMethod::Schuler, r3, 0.05).partial_means_spread);
  EXPECT_TRUE(estimate_centre(ReversalMethod::TwoPoint, r, 0.05).partial_means.empty());
}

TEST(Reversal, SequenceErrorsNameTheElement) {
  const std::vector<double> r{1.0, -1.0, -1.2, 1.0};  // the third reading moves on the same way
  try {
    meridian::gyro::check_reversal_sequence(r, 3);
    ADD_FAILURE() << "no error";
  } catch (const meridian::InputError& e) {
    EXPECT_EQ(e.context().field, "[2]");
    EXPECT_NE(std::string(e.what()).find("reading 3 does not alternate"), std::string::npos) << e.what();
  }
}

TEST(Reversal, AReadingWithItsSignLostIsFound) {
  // 4.2, -3.7, … with the second sign lost still zig-zags (4.2, 3.7, 3.9, …)
  // but lies on its neighbour's side of the centre.
  const std::vector<double> r{4.2, 3.7, 3.9, -3.5, 3.7};
  try {
    meridian::gyro::check_reversal_sequence(r, 3);
    ADD_FAILURE() << "no error";
  } catch (const meridian::InputError& e) {
    EXPECT_EQ(e.context().field, "[1]");
  }
  EXPECT_NO_THROW(meridian::gyro::check_reversal_sequence(std::vector<double>{4.2, -3.7, 3.9, -3.5, 3.7}, 3));
}
