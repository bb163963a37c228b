// The `gyro stochastic` workflow: a field book's Input split into its reversal-point series, and
// gyro::process over them (gyro/stochastic_book.hpp). Expected values are written out by hand from
// the Inputs built here.

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/stochastic_book.hpp"

namespace {

using namespace meridian;
using namespace meridian::gyro;
using ::testing::HasSubstr;

DeterminationInput tracking_run(std::vector<double> readings_rad, double sigma_rad, std::string label = {}) {
  DeterminationInput d;
  d.mode = Mode::Tracking;
  d.label = std::move(label);
  d.tracking.reversals_rad = std::move(readings_rad);
  d.tracking.sigma_reading_rad = sigma_rad;
  return d;
}

ZeroPositionRun zero_run(std::vector<double> div) {
  ZeroPositionRun z;
  z.reversals_div = std::move(div);
  return z;
}

// Seven circle readings across 0°/360° (examples/tracking.yaml, rounded to the second).
std::vector<double> seven_readings() {
  std::vector<double> r;
  for (double s : {3152.0, 12736.0, 3168.0, 12724.0, 3185.0, 12703.0, 3216.0})
    r.push_back(std::fmod(358.0 * units::kDegree + s * units::kArcsecond, units::kTwoPi));
  return r;
}

TEST(StochasticBook, ReduceBookSeriesInTheBooksOrder) {
  ReduceInput in;
  in.instrument.sigma_reading_div = 0.05;
  in.determinations.push_back(tracking_run(seven_readings(), 8.0 * units::kArcsecond, "D1"));
  DeterminationInput nt;
  nt.mode = Mode::NonTracking;
  nt.zero_before = zero_run({4.2, -3.7, 3.9, -3.5, 3.7, -3.3, 3.5});
  nt.zero_after = zero_run({4.1, -3.6, 3.8});
  in.determinations.push_back(nt);
  in.determinations.push_back(tracking_run({}, 1.0));  // no readings: no series
  const StochasticBookInput book = stochastic_book(in);
  EXPECT_FALSE(book.campaign);
  ASSERT_EQ(book.series.size(), 3u);
  EXPECT_EQ(book.series[0].field, "determinations[0].reversals");
  EXPECT_EQ(book.series[0].label, "D1");
  EXPECT_EQ(book.series[0].input.kind, SeriesKind::Circle);
  EXPECT_EQ(book.series[0].input.readings, seven_readings());
  EXPECT_EQ(book.series[0].input.booked_sigma, 8.0 * units::kArcsecond);
  EXPECT_EQ(book.series[1].field, "determinations[1].zero_before");
  EXPECT_EQ(book.series[1].input.kind, SeriesKind::Scale);
  EXPECT_EQ(book.series[1].input.booked_sigma, 0.05);
  EXPECT_EQ(book.series[2].field, "determinations[1].zero_after");
  EXPECT_EQ(book.series[2].input.readings.size(), 3u);

  StochasticBookInput named = book;
  named.file = "book.yaml";
  const StochasticBookResult r = process(named);
  EXPECT_EQ(r.file, "book.yaml");
  EXPECT_FALSE(r.campaign);
  // The run of 3 readings is below the minimum of 6 and is not analysed.
  ASSERT_EQ(r.series.size(), 2u);
  EXPECT_EQ(r.series[0].label, "determinations[0].reversals (D1)");
  EXPECT_EQ(r.series[0].result.kind, SeriesKind::Circle);
  EXPECT_NEAR(r.series[0].result.reference_rad, 358.0 * units::kDegree, 1e-15);
  EXPECT_NEAR(r.series[0].result.fitted_readings[1], 12736.0, 1e-8);
  EXPECT_NEAR(r.series[0].result.booked_sigma, 8.0, 1e-12);
  EXPECT_EQ(r.series[1].label, "determinations[1].zero_before");
  EXPECT_EQ(r.series[1].result.kind, SeriesKind::Scale);
  EXPECT_EQ(r.series[1].result.booked_sigma, 0.05);
}

TEST(StochasticBook, CampaignBookKnownLineThenLine) {
  CampaignInput in;
  in.instrument.sigma_reading_div = 0.1;
  KnownLineInput kl;
  kl.before.push_back(tracking_run(seven_readings(), 2.0 * units::kArcsecond));
  DeterminationInput after;
  after.mode = Mode::NonTracking;
  after.zero_after = zero_run({1, -1, 1, -1, 1, -1});
  kl.after.push_back(after);
  in.known_line = kl;
  in.line.determinations.push_back(tracking_run(seven_readings(), 3.0 * units::kArcsecond, "L1"));
  const StochasticBookInput book = stochastic_book(in);
  EXPECT_TRUE(book.campaign);
  ASSERT_EQ(book.series.size(), 3u);
  EXPECT_EQ(book.series[0].field, "known_line.before[0].reversals");
  EXPECT_EQ(book.series[1].field, "known_line.after[0].zero_after");
  EXPECT_EQ(book.series[1].input.booked_sigma, 0.1);
  EXPECT_EQ(book.series[2].field, "line.determinations[0].reversals");
  EXPECT_EQ(book.series[2].label, "L1");
}

TEST(StochasticBook, ErrorsNameTheSeriesOrTheDeterminations) {
  // A series without scatter: the analysis' InputError gets the series' field.
  ReduceInput in;
  std::vector<double> flat;
  for (int i = 0; i < 7; ++i) flat.push_back((i % 2 ? 20.0 : 10.0) * units::kArcsecond);
  in.determinations.push_back(tracking_run(flat, 1.0 * units::kArcsecond));
  try {
    process(stochastic_book(in));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "determinations[0].reversals");
    EXPECT_THAT(e.message(), HasSubstr("no scatter"));
  }
  // No series long enough: how many there are, the longest, at the determinations.
  CampaignInput c;
  c.line.determinations.push_back(tracking_run({0.1, 0.2, 0.1, 0.2, 0.1}, 1.0));
  c.line.determinations.push_back(tracking_run({0.1, 0.2, 0.1}, 1.0));
  try {
    process(stochastic_book(c));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "line.determinations");
    EXPECT_THAT(e.message(), HasSubstr("this is a campaign file; none of its 2 reversal-point series"));
    EXPECT_THAT(e.message(), HasSubstr("(the longest has 5)"));
  }
}

}  // namespace
