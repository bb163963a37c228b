// Linear least squares against closed forms and direct dense formulas.
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adjust_test_support.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/core/error.hpp"

namespace {

using meridian_test::kNaN;
using meridian_test::message_of;
using meridian_test::random_spd;

using meridian::InputError;
using meridian::NumericalError;
using meridian::adjust::CovarianceFactor;
using meridian::adjust::LeastSquaresResult;
using meridian::adjust::solve_linear;
using meridian::adjust::solve_linear_diagonal;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using ::testing::HasSubstr;

MatrixXd line_design(const std::vector<double>& t) {
  MatrixXd A(static_cast<Index>(t.size()), 2);
  for (std::size_t i = 0; i < t.size(); ++i) {
    A(static_cast<Index>(i), 0) = 1.0;
    A(static_cast<Index>(i), 1) = t[i];
  }
  return A;
}

// Hand-computed regression: t = 1..5, y = 2.1 3.9 6.2 7.8 10.1.
// t̄ = 3, ȳ = 6.02, Sxx = 10, Sxy = 19.9 → slope 1.99, intercept 6.02 − 3·1.99 = 0.05.
// Fitted 2.04 4.03 6.02 8.01 10.00 → v = −0.06 0.13 −0.18 0.21 −0.10, Σv² = 0.107.
TEST(Linear, StraightLineTextbookNumbers) {
  const MatrixXd A = line_design({1, 2, 3, 4, 5});
  const VectorXd l = (VectorXd(5) << 2.1, 3.9, 6.2, 7.8, 10.1).finished();
  const double s = 0.1;  // σ of each observation
  const auto r = solve_linear_diagonal(A, l, VectorXd::Constant(5, s));
  EXPECT_NEAR(r.x(0), 0.05, 1e-12);
  EXPECT_NEAR(r.x(1), 1.99, 1e-12);
  const VectorXd v = (VectorXd(5) << -0.06, 0.13, -0.18, 0.21, -0.10).finished();
  for (Index i = 0; i < 5; ++i) EXPECT_NEAR(r.residuals(i), v(i), 1e-12) << i;
  EXPECT_NEAR(r.vtpv, 0.107 / (s * s), 1e-10);
  EXPECT_EQ(r.dof, 3);
  EXPECT_NEAR(r.sigma0, std::sqrt(10.7 / 3.0), 1e-12);
  // var(b) = σ²/Sxx, var(a) = σ²(1/n + t̄²/Sxx), cov(a,b) = −σ² t̄/Sxx.
  EXPECT_NEAR(r.cofactor(1, 1), 0.01 / 10.0, 1e-15);
  EXPECT_NEAR(r.cofactor(0, 0), 0.01 * (0.2 + 0.9), 1e-15);
  EXPECT_NEAR(r.cofactor(0, 1), -0.01 * 0.3, 1e-15);
  EXPECT_EQ(r.cofactor(0, 1), r.cofactor(1, 0));
  EXPECT_NEAR(r.sigma_apriori(1), 0.1 / std::sqrt(10.0), 1e-14);
  EXPECT_NEAR(r.sigma_aposteriori(1), std::sqrt(10.7 / 3.0) * 0.1 / std::sqrt(10.0), 1e-13);
  EXPECT_NEAR(r.covariance_aposteriori(0, 1), -0.003 * 10.7 / 3.0, 1e-13);
}

// Closed forms of simple regression for arbitrary data and equal weights.
TEST(Linear, StraightLineClosedForm) {
  const std::vector<double> t{-3.0, -1.5, 0.25, 2.0, 4.5, 7.0, 8.0};
  const std::vector<double> y{10.3, 7.9, 5.2, 2.8, -1.1, -4.6, -6.4};
  const double s = 0.4;
  const auto n = static_cast<double>(t.size());
  double tm = 0, ym = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    tm += t[i] / n;
    ym += y[i] / n;
  }
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    sxx += (t[i] - tm) * (t[i] - tm);
    sxy += (t[i] - tm) * (y[i] - ym);
  }
  const double b = sxy / sxx;
  const double a = ym - b * tm;
  double sse = 0;
  for (std::size_t i = 0; i < t.size(); ++i) sse += std::pow(a + b * t[i] - y[i], 2);

  VectorXd l(7);
  for (Index i = 0; i < 7; ++i) l(i) = y[static_cast<std::size_t>(i)];
  const auto r = solve_linear(line_design(t), l, s * s * MatrixXd::Identity(7, 7));
  EXPECT_NEAR(r.x(0), a, 1e-12);
  EXPECT_NEAR(r.x(1), b, 1e-12);
  EXPECT_NEAR(r.sigma_apriori(0), s * std::sqrt(1.0 / n + tm * tm / sxx), 1e-14);
  EXPECT_NEAR(r.sigma_apriori(1), s / std::sqrt(sxx), 1e-14);
  EXPECT_NEAR(r.sigma0, std::sqrt(sse / (n - 2)) / s, 1e-12);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto k = static_cast<Index>(i);
    const double h = 1.0 / n + (t[i] - tm) * (t[i] - tm) / sxx;  // leverage
    EXPECT_NEAR(r.residuals(k), a + b * t[i] - y[i], 1e-12);
    EXPECT_NEAR(r.redundancy(k), 1.0 - h, 1e-13);
    EXPECT_NEAR(r.standardized_residuals(k), (a + b * t[i] - y[i]) / (s * std::sqrt(1.0 - h)),
                1e-11);
  }
  EXPECT_NEAR(r.redundancy.sum(), 5.0, 1e-12);
}

TEST(Linear, MeanOfEquallyWeightedObservations) {
  const VectorXd l = (VectorXd(6) << 101.2, 100.7, 101.9, 100.4, 101.1, 100.9).finished();
  const double mean = (101.2 + 100.7 + 101.9 + 100.4 + 101.1 + 100.9) / 6.0;
  double ss = 0;
  for (Index i = 0; i < 6; ++i) ss += (l(i) - mean) * (l(i) - mean);
  const auto r = solve_linear(MatrixXd::Ones(6, 1), l, MatrixXd::Identity(6, 6));
  EXPECT_NEAR(r.x(0), mean, 1e-12);
  EXPECT_NEAR(r.cofactor(0, 0), 1.0 / 6.0, 1e-15);
  EXPECT_EQ(r.dof, 5);
  EXPECT_NEAR(r.sigma0, std::sqrt(ss / 5.0), 1e-12);  // the sample standard deviation
  for (Index i = 0; i < 6; ++i) {
    EXPECT_NEAR(r.redundancy(i), 5.0 / 6.0, 1e-14);
    EXPECT_NEAR(r.residuals(i), mean - l(i), 1e-12);
    EXPECT_NEAR(r.standardized_residuals(i), (mean - l(i)) / std::sqrt(5.0 / 6.0), 1e-11);
  }
  EXPECT_NEAR(r.redundancy.sum(), r.dof, 1e-12);
}

// Direct dense formulas with Σ⁻¹ (acceptable in a test).
struct Dense {
  VectorXd x, v, r, w;
  MatrixXd qxx;
  double vtpv;
};

Dense dense_formula(const MatrixXd& A, const VectorXd& l, const MatrixXd& S) {
  const MatrixXd P = S.inverse();
  Dense d;
  d.qxx = (A.transpose() * P * A).inverse();
  d.x = d.qxx * A.transpose() * P * l;
  d.v = A * d.x - l;
  d.vtpv = d.v.dot(P * d.v);
  const MatrixXd qvv = S - A * d.qxx * A.transpose();
  d.r = (qvv * P).diagonal();
  d.w = d.v.array() / qvv.diagonal().array().sqrt();
  return d;
}

void expect_matches(const LeastSquaresResult& r, const Dense& d, double tol) {
  const Index n = d.v.size();
  const Index u = d.x.size();
  for (Index j = 0; j < u; ++j) {
    EXPECT_NEAR(r.x(j), d.x(j), tol * (1 + std::abs(d.x(j)))) << j;
    for (Index k = 0; k < u; ++k)
      EXPECT_NEAR(r.cofactor(j, k), d.qxx(j, k), tol * d.qxx.cwiseAbs().maxCoeff()) << j << k;
  }
  for (Index i = 0; i < n; ++i) {
    EXPECT_NEAR(r.residuals(i), d.v(i), tol * (1 + d.v.cwiseAbs().maxCoeff())) << i;
    EXPECT_NEAR(r.redundancy(i), d.r(i), tol) << i;
    EXPECT_NEAR(r.standardized_residuals(i), d.w(i), tol * (1 + std::abs(d.w(i)))) << i;
  }
  EXPECT_NEAR(r.vtpv, d.vtpv, tol * (1 + d.vtpv));
  EXPECT_EQ(r.dof, n - u);
  EXPECT_NEAR(r.redundancy.sum(), static_cast<double>(n - u), 1e-10);
  EXPECT_NEAR(r.sigma0, std::sqrt(d.vtpv / static_cast<double>(n - u)), tol);
}

TEST(Linear, CorrelatedMatchesDenseFormula) {
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> N(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const Index n = 9, u = 3;
    MatrixXd A(n, u);
    VectorXd l(n);
    for (Index i = 0; i < n; ++i) {
      for (Index j = 0; j < u; ++j) A(i, j) = N(rng);
      l(i) = 10.0 * N(rng);
    }
    const MatrixXd S = random_spd(n, rng);
    const auto r = solve_linear(A, l, S);
    expect_matches(r, dense_formula(A, l, S), 1e-9);
    // The redundancy of correlated observations is not 1 − h_ii of the whitened problem;
    // make sure the test would notice if it were.
    const Dense d = dense_formula(A, l, S);
    EXPECT_GT((d.r - VectorXd::Constant(n, (n - u) / static_cast<double>(n))).norm(), 1e-3);
  }
}

TEST(Linear, WeightedDiagonalMatchesDenseFormula) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> N(0.0, 1.0);
  const Index n = 8, u = 2;
  MatrixXd A(n, u);
  VectorXd l(n), s(n);
  for (Index i = 0; i < n; ++i) {
    A(i, 0) = 1.0;
    A(i, 1) = static_cast<double>(i);
    l(i) = 3.0 + 0.5 * static_cast<double>(i) + N(rng);
    s(i) = 0.2 + 0.3 * static_cast<double>(i % 3);
  }
  const MatrixXd S = s.array().square().matrix().asDiagonal();
  const auto r = solve_linear_diagonal(A, l, s);
  expect_matches(r, dense_formula(A, l, S), 1e-11);
  // An exactly diagonal full matrix takes the same path.
  const auto r2 = solve_linear(A, l, S);
  EXPECT_NEAR((r.x - r2.x).norm(), 0.0, 1e-14);
  // Independent observations: r_i = 1 − h_ii ∈ [0, 1].
  EXPECT_TRUE((r.redundancy.array() >= 0.0).all() && (r.redundancy.array() <= 1.0).all());
}

TEST(Linear, FactoredCovarianceReused) {
  std::mt19937_64 rng(99);
  const MatrixXd S = random_spd(6, rng);
  const MatrixXd A = line_design({0, 1, 2, 3, 4, 5});
  const CovarianceFactor f(S);
  EXPECT_FALSE(f.is_diagonal());
  for (int k = 0; k < 3; ++k) {
    const VectorXd l = VectorXd::LinSpaced(6, 1.0 * k, 2.0 + 3.0 * k) + VectorXd::Unit(6, k);
    expect_matches(solve_linear(A, l, f), dense_formula(A, l, S), 1e-10);
  }
  // whiten/colour are inverse, whitened covariance is the identity: L⁻¹ Σ L⁻ᵀ = I.
  MatrixXd m = S;
  f.whiten(m);
  MatrixXd mt = m.transpose();
  f.whiten(mt);
  EXPECT_LT((mt - MatrixXd::Identity(6, 6)).norm(), 1e-12);
  f.colour(mt);
  EXPECT_LT((mt.transpose() - m).norm(), 1e-12);
}

TEST(Linear, ZeroDegreesOfFreedom) {
  const MatrixXd A = line_design({1.0, 3.0});
  const VectorXd l = (VectorXd(2) << 2.0, 6.0).finished();
  const auto r = solve_linear_diagonal(A, l, VectorXd::Constant(2, 0.5));
  EXPECT_NEAR(r.x(0), 0.0, 1e-14);
  EXPECT_NEAR(r.x(1), 2.0, 1e-14);
  EXPECT_EQ(r.dof, 0);
  EXPECT_TRUE(std::isnan(r.sigma0));
  EXPECT_TRUE(std::isnan(r.sigma_aposteriori(0)));
  EXPECT_EQ(r.covariance_aposteriori, r.cofactor);
  EXPECT_NEAR(r.vtpv, 0.0, 1e-24);
  for (Index i = 0; i < 2; ++i) {
    EXPECT_NEAR(r.redundancy(i), 0.0, 1e-14);
    EXPECT_TRUE(std::isnan(r.standardized_residuals(i)));
  }
  // var(b) = σ²/Sxx = 0.25/2.
  EXPECT_NEAR(r.cofactor(1, 1), 0.125, 1e-15);
}

// A single observation that alone determines a parameter has no redundancy: w is NaN there,
// defined elsewhere.
TEST(Linear, UncontrolledObservationHasNaNStandardizedResidual) {
  MatrixXd A(4, 2);
  A << 1, 0, 1, 0, 1, 0, 0, 1;
  const VectorXd l = (VectorXd(4) << 1.0, 1.2, 0.8, 5.0).finished();
  const auto r = solve_linear_diagonal(A, l, VectorXd::Ones(4));
  EXPECT_NEAR(r.redundancy(3), 0.0, 1e-14);
  EXPECT_TRUE(std::isnan(r.standardized_residuals(3)));
  EXPECT_NEAR(r.redundancy(0), 2.0 / 3.0, 1e-14);
  EXPECT_FALSE(std::isnan(r.standardized_residuals(0)));
}

TEST(Linear, RankDeficientDesignIsRejected) {
  // Parameter 1 duplicates parameter 0 (scaled by 2).
  MatrixXd A(5, 3);
  for (Index i = 0; i < 5; ++i) {
    A(i, 0) = 1.0;
    A(i, 1) = 2.0;
    A(i, 2) = static_cast<double>(i);
  }
  const VectorXd l = VectorXd::LinSpaced(5, 0.0, 4.0);
  const std::string msg =
      message_of<NumericalError>([&] { solve_linear_diagonal(A, l, VectorXd::Ones(5)); });
  EXPECT_THAT(msg, HasSubstr("normal matrix is singular"));
  EXPECT_THAT(msg, HasSubstr("parameter 1 is not determined"));

  // A column that is a rounded-off sum of two others (not exactly dependent in binary).
  MatrixXd B(6, 3);
  for (Index i = 0; i < 6; ++i) {
    B(i, 0) = 0.1 * static_cast<double>(i) + 0.3;
    B(i, 1) = std::sqrt(static_cast<double>(i) + 0.7);
    B(i, 2) = B(i, 0) + B(i, 1);
  }
  EXPECT_THROW(solve_linear_diagonal(B, VectorXd::Ones(6), VectorXd::Ones(6)), NumericalError);

  // Zero column.
  MatrixXd Z = line_design({0, 1, 2});
  Z.conservativeResize(3, 3);
  Z.col(2).setZero();
  EXPECT_THAT(message_of<NumericalError>(
                  [&] { solve_linear(Z, VectorXd::Ones(3), MatrixXd::Identity(3, 3)); }),
              HasSubstr("parameter 2 is not determined by the observations (its column of A is zero)"));
}

// Exact (to rounding) dependency with a strongly correlated, ill-conditioned covariance
// (cond ≈ 1e5): the rank test on the whitened matrix must still find it.
TEST(Linear, RankDeficientWithIllConditionedCovariance) {
  const Index n = 8;
  MatrixXd S(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) S(i, j) = std::pow(0.9999, std::abs(static_cast<double>(i - j)));
  MatrixXd A(n, 3);
  for (Index i = 0; i < n; ++i) {
    A(i, 0) = std::cos(0.3 * static_cast<double>(i));
    A(i, 1) = std::exp(0.1 * static_cast<double>(i));
    A(i, 2) = 3.0 * A(i, 0) - 0.7 * A(i, 1);
  }
  EXPECT_THROW(solve_linear(A, VectorXd::Ones(n), S), NumericalError);
  // Full rank with the same covariance is fine and matches the dense formula.
  for (Index i = 0; i < n; ++i) A(i, 2) = static_cast<double>(i * i);
  const VectorXd l = VectorXd::LinSpaced(n, 1.0, 2.0);
  expect_matches(solve_linear(A, l, S), dense_formula(A, l, S), 1e-6);
}

TEST(Linear, BadlyScaledColumnsAreAccepted) {
  // Column 0 in arc seconds (~1e3), column 1 ~1e-6, column 2 ~1: well posed.
  const Index n = 10;
  const VectorXd xt = (VectorXd(3) << 2.5e-3, 4.0e5, -1.25).finished();
  for (const double big : {1e3, 1e6}) {
    const double tiny = big == 1e3 ? 1e-6 : 1e-9;  // ratio 1e-9 and 1e-15
    MatrixXd A(n, 3);
    for (Index i = 0; i < n; ++i) {
      const double t = static_cast<double>(i);
      A(i, 0) = big * (1.0 + 0.1 * t);
      A(i, 1) = tiny * t * t;
      A(i, 2) = std::sin(t);
    }
    VectorXd x_true = xt;
    x_true(1) = 0.4 / tiny;  // keep the observations O(1)
    x_true(0) = 2.5 / big;
    const VectorXd l = A * x_true;
    LeastSquaresResult r;
    ASSERT_NO_THROW(r = solve_linear_diagonal(A, l, VectorXd::Constant(n, 0.01)));
    for (Index j = 0; j < 3; ++j) EXPECT_NEAR(r.x(j) / x_true(j), 1.0, 1e-10) << big << " " << j;
    const MatrixXd S = 1e-4 * MatrixXd::Identity(n, n);
    const Dense d = dense_formula(A, l, S);
    for (Index j = 0; j < 3; ++j) EXPECT_NEAR(r.cofactor(j, j) / d.qxx(j, j), 1.0, 1e-8);
  }
}

TEST(Linear, CovarianceNotPositiveDefinite) {
  const MatrixXd A = line_design({0, 1, 2});
  const VectorXd l = VectorXd::Ones(3);
  MatrixXd S = MatrixXd::Identity(3, 3);
  S(0, 1) = S(1, 0) = 2.0;  // eigenvalue −1
  EXPECT_THAT(message_of<NumericalError>([&] { solve_linear(A, l, S); }),
              HasSubstr("observation covariance is not positive definite"));
  S = MatrixXd::Identity(3, 3);
  S(1, 2) = S(2, 1) = 1.0;  // perfectly correlated: positive semi-definite
  EXPECT_THAT(message_of<NumericalError>([&] { solve_linear(A, l, S); }),
              HasSubstr("observation covariance is not positive definite"));
  S = MatrixXd::Identity(3, 3);
  S(2, 2) = -1.0;
  EXPECT_THAT(message_of<NumericalError>([&] { solve_linear(A, l, S); }),
              HasSubstr("variance of observation 2 is -1"));
  S(2, 2) = 0.0;
  EXPECT_THROW(solve_linear(A, l, S), NumericalError);
}

TEST(Linear, InputErrors) {
  const MatrixXd A = line_design({0, 1, 2, 3});
  const VectorXd l = VectorXd::Ones(4);
  const MatrixXd S = MatrixXd::Identity(4, 4);
  EXPECT_THROW(solve_linear(A, VectorXd::Ones(3), S), InputError);
  EXPECT_THROW(solve_linear(A, l, MatrixXd::Identity(3, 3)), InputError);
  EXPECT_THROW(solve_linear(A, l, MatrixXd::Identity(4, 3)), InputError);
  EXPECT_THROW(solve_linear(A.topRows(1), VectorXd::Ones(1), MatrixXd::Identity(1, 1)),
               InputError);  // n < u
  EXPECT_THROW(solve_linear(MatrixXd(4, 0), l, S), InputError);
  MatrixXd An = A;
  An(2, 1) = kNaN;
  EXPECT_THAT(message_of<InputError>([&] { solve_linear(An, l, S); }),
              HasSubstr("design matrix A has a non-finite value (nan) at (2, 1)"));
  VectorXd ln = l;
  ln(3) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(solve_linear(A, ln, S), InputError);
  MatrixXd Sn = S;
  Sn(0, 3) = Sn(3, 0) = kNaN;
  EXPECT_THROW(solve_linear(A, l, Sn), InputError);
  MatrixXd Sa = S;
  Sa(0, 1) = 0.5;  // not symmetric
  EXPECT_THAT(message_of<InputError>([&] { solve_linear(A, l, Sa); }),
              HasSubstr("not symmetric"));
  EXPECT_THROW(solve_linear_diagonal(A, l, VectorXd::Ones(3)), InputError);
  EXPECT_THAT(message_of<InputError>([&] {
                solve_linear_diagonal(A, l, (VectorXd(4) << 1, 1, 0, 1).finished());
              }),
              HasSubstr("standard deviation of observation 2 must be positive"));
  EXPECT_THROW(solve_linear_diagonal(A, l, (VectorXd(4) << 1, -1, 1, 1).finished()), InputError);
  EXPECT_THROW(solve_linear_diagonal(A, l, (VectorXd(4) << 1, 1, kNaN, 1).finished()),
               InputError);
  const auto r = solve_linear(A, l, S);
  EXPECT_THROW(static_cast<void>(r.sigma_apriori(2)), InputError);
  EXPECT_THROW(static_cast<void>(r.sigma_aposteriori(-1)), InputError);
}

// Monte Carlo: the a-priori σ of the slope equals the scatter of the estimates under a
// correlated Σ (AR(1), ρ = 0.8, unequal σ_i).
TEST(Linear, MonteCarloAprioriSigmaMatchesScatter) {
  const Index n = 12;
  std::vector<double> t;
  for (Index i = 0; i < n; ++i) t.push_back(static_cast<double>(i));
  const MatrixXd A = line_design(t);
  VectorXd s(n);
  for (Index i = 0; i < n; ++i) s(i) = 0.5 + 0.1 * static_cast<double>(i % 4);
  MatrixXd S(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j)
      S(i, j) = s(i) * s(j) * std::pow(0.8, std::abs(static_cast<double>(i - j)));
  const MatrixXd L = Eigen::LLT<MatrixXd>(S).matrixL();
  const VectorXd x_true = (VectorXd(2) << 4.0, -0.3).finished();

  const CovarianceFactor f(S);
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> N(0.0, 1.0);
  const int runs = 2000;
  VectorXd sum = VectorXd::Zero(2), sum2 = VectorXd::Zero(2);
  double s0sq = 0.0;
  LeastSquaresResult r;
  for (int k = 0; k < runs; ++k) {
    VectorXd z(n);
    for (Index i = 0; i < n; ++i) z(i) = N(rng);
    const VectorXd l = A * x_true + L * z;
    r = solve_linear(A, l, f);
    sum += r.x;
    sum2 += r.x.cwiseAbs2();
    s0sq += r.sigma0 * r.sigma0;
  }
  const VectorXd mean = sum / runs;
  const VectorXd sd = ((sum2 - runs * mean.cwiseAbs2()) / (runs - 1)).cwiseSqrt();
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(sd(j) / r.sigma_apriori(j), 1.0, 0.10) << j;
    EXPECT_NEAR(mean(j), x_true(j), 4.0 * r.sigma_apriori(j) / std::sqrt(runs)) << j;
  }
  EXPECT_NEAR(s0sq / runs, 1.0, 0.10);  // E(σ̂0²) = 1
  // Guard: ignoring the correlations would report a σ of the slope off by more than 10 %,
  // so the test above discriminates.
  const MatrixXd Pd = S.diagonal().cwiseInverse().asDiagonal();
  const double naive_reported = std::sqrt((A.transpose() * Pd * A).inverse()(1, 1));
  EXPECT_GT(std::abs(naive_reported / r.sigma_apriori(1) - 1.0), 0.2);
}

}  // namespace
