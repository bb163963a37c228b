// Zero position before/after (spec §2).

#include <cmath>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/gyro/zero_position.hpp"

using namespace meridian;
using namespace meridian::gyro;

namespace {
ZeroPositionRun run(double centre, double amp, double half_period_s) {
  ZeroPositionRun r;
  for (int i = 1; i <= 5; ++i) {
    r.reversals_div.push_back(centre + ((i % 2 == 0) ? 1.0 : -1.0) * amp);
    r.times_s.push_back(10.0 + i * half_period_s);
  }
  return r;
}
}  // namespace

TEST(ZeroPosition, BeforeAfterMeanAndDifference) {
  const auto s = summarise_zero_position(run(0.2, 6.0, 200.0), run(0.4, 5.5, 200.0), ReversalMethod::Schuler, 0.05);
  ASSERT_TRUE(s.before && s.after);
  EXPECT_NEAR(s.before->fit.centre.value, 0.2, 1e-12);
  EXPECT_NEAR(s.after->fit.centre.value, 0.4, 1e-12);
  EXPECT_NEAR(s.mean_div.value, 0.3, 1e-12);
  EXPECT_NEAR(*s.difference_div, 0.2, 1e-12);
  EXPECT_TRUE(s.within_tolerance);
  // Half the drift dominates the σ of the mean here.
  EXPECT_NEAR(s.mean_div.sigma, 0.1, 1e-12);
  ASSERT_TRUE(s.before->free_period_s);
  EXPECT_NEAR(s.before->free_period_s->value, 400.0, 1e-9);
  EXPECT_NEAR(s.before->amplitude_div, 6.0, 1e-12);
}

TEST(ZeroPosition, ToleranceExceededWarns) {
  const auto s = summarise_zero_position(run(0.0, 6.0, 200.0), run(0.8, 6.0, 200.0), ReversalMethod::Schuler, 0.05);
  EXPECT_FALSE(s.within_tolerance);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("0.80"), std::string::npos);
}

TEST(ZeroPosition, BadRunsNameTheField) {
  ZeroPositionRun bad = run(0.0, 6.0, 200.0);
  bad.times_s[2] = bad.times_s[1];
  try {
    summarise_zero_position(bad, std::nullopt, ReversalMethod::Schuler, 0.05);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("before.times_s"), std::string::npos) << e.what();
  }
  EXPECT_THROW(summarise_zero_position(std::nullopt, std::nullopt, ReversalMethod::Schuler, 0.05), InputError);
}

// The reading σ of a motor-off run is the instrument's sigma_reading_div: the
// a-priori σ is used (5 reversals, Schuler: q = 36/144) unless the global test
// rejects it; then the larger a-posteriori σ and a warning naming the run.
TEST(ZeroPosition, StatedReadingSigmaPolicy) {
  ZeroPositionRun noisy = run(0.2, 6.0, 200.0);
  noisy.reversals_div[2] += 0.4;  // a misread reversal
  const auto s =
      summarise_zero_position(run(0.2, 6.0, 200.0), noisy, ReversalMethod::Schuler, 0.05);
  ASSERT_TRUE(s.before && s.after);
  EXPECT_FALSE(s.before->fit.sigma_is_aposteriori);
  EXPECT_NEAR(s.before->fit.centre.sigma, 0.05 * 0.5,
              1e-15);  // exact readings: σ̂0 = 0, a priori kept
  ASSERT_TRUE(s.after->fit.reading_sigma_test);
  EXPECT_TRUE(s.after->fit.reading_sigma_test->rejected);
  EXPECT_TRUE(s.after->fit.sigma_is_aposteriori);
  EXPECT_NEAR(s.after->fit.centre.sigma, s.after->fit.sigma0 * 0.5, 1e-15);
  bool named = false;
  for (const auto& w : s.warnings)
    named = named || w.find("zero position after the run: the reversal readings") == 0;
  EXPECT_TRUE(named);
}
