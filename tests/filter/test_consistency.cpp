// Consistency statistics: χ² intervals against table values, NEES against its definition, and
// the summary of replications (test_montecarlo.cpp holds the Monte Carlo check itself).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/filter/consistency.hpp"

namespace {

using meridian::InputError;
using meridian::filter::average_interval;
using meridian::filter::ConsistencyRun;
using meridian::filter::Estimate;
using meridian::filter::Matrix;
using meridian::filter::nees;
using meridian::filter::Vector;

TEST(Consistency, IntervalsMatchChiSquaredTables) {
  // χ²(1): 2.5 % and 97.5 % points 0.000982069 and 5.023886 (Abramowitz & Stegun 26.4).
  const auto one = average_interval(1.0, 1, 0.95);
  EXPECT_NEAR(one.lower, 0.000982069, 1e-9);
  EXPECT_NEAR(one.upper, 5.023886, 1e-6);
  // Average of 100 χ²(2): χ²(200) points 162.728 and 241.058, divided by 100.
  const auto avg = average_interval(2.0, 100, 0.95);
  EXPECT_NEAR(avg.lower, 1.62728, 1e-5);
  EXPECT_NEAR(avg.upper, 2.41058, 1e-5);
  EXPECT_THROW(average_interval(2.0, 0, 0.95), InputError);
  EXPECT_THROW(average_interval(2.0, 10, 1.0), InputError);
}

TEST(Consistency, NeesIsTheMahalanobisDistance) {
  const Estimate<2> e{Vector<2>(1.0, 2.0), (Matrix<2, 2>() << 4.0, 0.0, 0.0, 9.0).finished()};
  EXPECT_DOUBLE_EQ(nees(Vector<2>(3.0, -1.0), e), 2.0 * 2.0 / 4.0 + 3.0 * 3.0 / 9.0);
}

TEST(Consistency, SummaryAveragesPerEpochAndOverall) {
  // Two runs of two epochs, hand-computed: per-epoch averages 1.5 and 3, overall 2.25.
  const std::vector<ConsistencyRun> runs{{{1.0, 2.0}, {0.5}}, {{2.0, 4.0}, {1.5}}};
  const auto s = meridian::filter::summarise_consistency(runs, 2.0, 1.0, 0.95);
  EXPECT_EQ(s.runs, 2);
  ASSERT_EQ(s.nees.average.size(), 2u);
  EXPECT_DOUBLE_EQ(s.nees.average[0], 1.5);
  EXPECT_DOUBLE_EQ(s.nees.average[1], 3.0);
  EXPECT_DOUBLE_EQ(s.nees.overall_average, 2.25);
  EXPECT_DOUBLE_EQ(s.nis.overall_average, 1.0);
  const auto per_epoch = average_interval(2.0, 2, 0.95);
  EXPECT_EQ(s.nees.epoch_interval.lower, per_epoch.lower);
  EXPECT_EQ(s.nees.fraction_inside,
            (per_epoch.contains(1.5) ? 0.5 : 0.0) + (per_epoch.contains(3.0) ? 0.5 : 0.0));
  // Runs of different lengths, negative or NaN values are input errors.
  EXPECT_THROW(meridian::filter::summarise_consistency({{{1.0}, {}}, {{1.0, 2.0}, {}}}, 2.0, 1.0),
               InputError);
  EXPECT_THROW(meridian::filter::summarise_consistency({{{-1.0}, {}}}, 2.0, 1.0), InputError);
  EXPECT_THROW(meridian::filter::summarise_consistency({{{std::nan("")}, {}}}, 2.0, 1.0),
               InputError);
  EXPECT_THROW(meridian::filter::summarise_consistency({}, 2.0, 1.0), InputError);
}

}  // namespace
