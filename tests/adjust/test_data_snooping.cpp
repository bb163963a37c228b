// Iterated data snooping (adjust/data_snooping.hpp) against closed forms: Ω_(i) = Ω − w_i²
// against the adjustment with observation i deleted (independent observations) and with its
// mean-shift unknown (correlated), the statistic t_i against the leave-one-out σ̂, a planted
// outlier located and estimated, clean data left alone, bad options.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "meridian/adjust/data_snooping.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using meridian::InputError;
using namespace meridian::adjust;

// A line fit y = a + b·x at x = 0 … n−1 with unit-variance noise (seeded).
struct Line {
  MatrixXd A;
  VectorXd l;
};
Line line(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> z;
  Line s{MatrixXd(n, 2), VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    s.A(i, 0) = 1.0;
    s.A(i, 1) = i;
    s.l(i) = 2.0 + 0.5 * i + z(rng);
  }
  return s;
}

MatrixXd delete_row(const MatrixXd& m, int r) {
  MatrixXd o(m.rows() - 1, m.cols());
  for (int i = 0, k = 0; i < m.rows(); ++i)
    if (i != r) o.row(k++) = m.row(i);
  return o;
}

TEST(DataSnooping, LeaveOneOutSigmaIsTheDeletedAdjustment) {
  const Line s = line(12, 3);
  const auto full = solve_linear(s.A, s.l, CovarianceFactor::diagonal(VectorXd::Ones(12)));
  for (int i = 0; i < 12; ++i) {
    const auto del = solve_linear(delete_row(s.A, i), delete_row(s.l, i),
                                  CovarianceFactor::diagonal(VectorXd::Ones(11)));
    const double w = full.w_statistics(i);
    EXPECT_NEAR(del.vtpv, full.vtpv - w * w, 1e-10 * full.vtpv) << i;
  }
}

TEST(DataSnooping, MeanShiftWithCorrelatedObservations) {
  // Ω_(i) = Ω − w_i² holds for a full covariance too (the mean-shift adjustment).
  const Line s = line(10, 5);
  MatrixXd Q(10, 10);
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) Q(i, j) = std::pow(0.5, std::abs(i - j));
  const CovarianceFactor f(Q);
  const auto full = solve_linear(s.A, s.l, f);
  for (int i : {0, 4, 9}) {
    MatrixXd Ai(10, 3);
    Ai << s.A, VectorXd::Unit(10, i);
    const auto shifted = solve_linear(Ai, s.l, f);
    const double w = full.w_statistics(i);
    EXPECT_NEAR(shifted.vtpv, full.vtpv - w * w, 1e-10 * full.vtpv) << i;
  }
}

TEST(DataSnooping, LocatesAndEstimatesAPlantedOutlier) {
  Line s = line(15, 7);
  s.l(6) += 12.0;  // 12 σ
  const auto r = iterated_data_snooping(s.A, s.l, CovarianceFactor::diagonal(VectorXd::Ones(15)));
  ASSERT_EQ(r.outliers.size(), 1u);
  const auto& o = r.outliers[0];
  EXPECT_EQ(o.index, 6);
  // t = w/σ̂_(i) with σ̂_(i) from the adjustment without observation 6.
  const auto del = solve_linear(delete_row(s.A, 6), delete_row(s.l, 6),
                                CovarianceFactor::diagonal(VectorXd::Ones(14)));
  EXPECT_NEAR(std::fabs(o.t), std::fabs(o.w) / del.sigma0, 1e-9 * std::fabs(o.t));
  EXPECT_NEAR(o.critical, student_t_two_sided_critical(1e-3, 12), 1e-12);
  // ∇̂ = l_6 − (â + b̂·6) of the adjustment without it.
  EXPECT_NEAR(o.error, s.l(6) - (del.x(0) + 6.0 * del.x(1)), 1e-9);
  EXPECT_GT(o.error, 8.0);
  EXPECT_NEAR(r.final_fit.x(0), del.x(0), 1e-9);
  EXPECT_NEAR(r.final_fit.sigma0, del.sigma0, 1e-9);
}

TEST(DataSnooping, TwoOutliersAreLocatedOneAfterTheOther) {
  Line s = line(20, 11);
  s.l(3) += 15.0;
  s.l(14) -= 10.0;
  const auto r = iterated_data_snooping(s.A, s.l, CovarianceFactor::diagonal(VectorXd::Ones(20)));
  ASSERT_EQ(r.outliers.size(), 2u);
  EXPECT_EQ(r.outliers[0].index, 3);
  EXPECT_EQ(r.outliers[1].index, 14);
  EXPECT_LT(r.outliers[1].error, -6.0);
}

TEST(DataSnooping, CleanDataRarelyRejected) {
  // Under H0 a pass rejects with probability ≤ n·α0 (Bonferroni): 15 × 0.01 = 15 %.
  int rejected = 0;
  for (unsigned seed = 0; seed < 200; ++seed) {
    const Line s = line(15, 100 + seed);
    SnoopingOptions o;
    o.alpha0 = 0.01;
    rejected += iterated_data_snooping(s.A, s.l, CovarianceFactor::diagonal(VectorXd::Ones(15)), o)
                        .outliers.empty()
                    ? 0
                    : 1;
  }
  EXPECT_LE(rejected, 30);  // 15 % of 200
  EXPECT_GE(rejected, 2);   // the test does reject sometimes (α0 = 1 % per observation)
}

TEST(DataSnooping, BadOptions) {
  const Line s = line(8, 1);
  const auto f = CovarianceFactor::diagonal(VectorXd::Ones(8));
  EXPECT_THROW(iterated_data_snooping(s.A, s.l, f, {0.0, 3}), InputError);
  EXPECT_THROW(iterated_data_snooping(s.A, s.l, f, {1.0, 3}), InputError);
  EXPECT_THROW(iterated_data_snooping(s.A, s.l, f, {0.01, -1}), InputError);
}

}  // namespace
