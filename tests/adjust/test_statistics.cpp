// Statistical tests and distribution functions against closed forms, published tables
// (NIST/SEMATECH e-Handbook of Statistical Methods §1.3.6.7), the outlier parameter of an
// extended adjustment, dense formulas with Σ⁻¹ and Monte Carlo rejection rates.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adjust_test_support.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"

namespace {

using meridian_test::kNaN;

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using meridian::InputError;
using meridian::adjust::chi_squared_gate;
using meridian::adjust::chi_squared_upper_probability;
using meridian::adjust::chi_squared_upper_quantile;
using meridian::adjust::data_snooping;
using meridian::adjust::fisher_f_upper_probability;
using meridian::adjust::fisher_f_upper_quantile;
using meridian::adjust::global_test;
using meridian::adjust::LeastSquaresResult;
using meridian::adjust::normal_two_sided_critical;
using meridian::adjust::normal_two_sided_probability;
using meridian::adjust::solve_linear;
using meridian::adjust::solve_linear_diagonal;
using meridian::adjust::student_t_two_sided_critical;
using meridian::adjust::student_t_two_sided_probability;
using meridian::adjust::w_test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

MatrixXd line_design(Index n) {
  MatrixXd A(n, 2);
  for (Index i = 0; i < n; ++i) {
    A(i, 0) = 1.0;
    A(i, 1) = static_cast<double>(i);
  }
  return A;
}

// AR(1) covariance with unequal σ_i: a correlated Σ_ll.
MatrixXd ar1_covariance(Index n, double rho) {
  MatrixXd S(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j) {
      const double si = 0.5 + 0.1 * static_cast<double>(i % 4);
      const double sj = 0.5 + 0.1 * static_cast<double>(j % 4);
      S(i, j) = si * sj * std::pow(rho, std::abs(static_cast<double>(i - j)));
    }
  return S;
}

// ---------------------------------------------------------------------------------------------
// Distribution functions.

// χ²(2) is the exponential distribution with mean 2: P(X > x) = e^{−x/2}, quantile −2·ln α.
TEST(Distributions, ChiSquaredTwoDofClosedForm) {
  for (double alpha : {0.5, 0.1, 0.05, 0.01, 1e-3, 1e-6, 1e-12}) {
    EXPECT_NEAR(chi_squared_upper_quantile(alpha, 2), -2.0 * std::log(alpha),
                1e-13 * -2.0 * std::log(alpha))
        << alpha;
  }
  for (double x : {0.0, 0.1, 1.0, 5.0, 30.0, 200.0})
    EXPECT_NEAR(chi_squared_upper_probability(x, 2), std::exp(-x / 2.0), 1e-14 * std::exp(-x / 2.0))
        << x;
}

// Even ν = 2m: P(X > x) = e^{−x/2}·Σ_{k<m} (x/2)^k/k! (Poisson sum); odd ν = 1, 3 via erfc:
// P(χ²₁ > x) = erfc(√(x/2)), P(χ²₃ > x) = erfc(√(x/2)) + √(2x/π)·e^{−x/2}.
TEST(Distributions, ChiSquaredProbabilityClosedForms) {
  for (double x : {0.5, 3.0, 10.0, 25.0, 60.0}) {
    for (int m : {2, 5, 10}) {
      double term = 1.0, sum = 0.0;
      for (int k = 0; k < m; ++k) {
        sum += term;
        term *= (x / 2.0) / (k + 1);
      }
      const double expected = std::exp(-x / 2.0) * sum;
      EXPECT_NEAR(chi_squared_upper_probability(x, 2 * m), expected, 1e-13 * expected)
          << x << " " << 2 * m;
    }
    const double e1 = std::erfc(std::sqrt(x / 2.0));
    EXPECT_NEAR(chi_squared_upper_probability(x, 1), e1, 1e-13 * e1) << x;
    const double e3 = e1 + std::sqrt(2.0 * x / kPi) * std::exp(-x / 2.0);
    EXPECT_NEAR(chi_squared_upper_probability(x, 3), e3, 1e-13 * e3) << x;
  }
}

// Upper critical values of χ² (NIST/SEMATECH e-Handbook, table 1.3.6.7.4, 3 decimals).
TEST(Distributions, ChiSquaredTableValues) {
  struct Row {
    int dof;
    double alpha;
    double value;
  };
  for (const Row& r : {Row{1, 0.05, 3.841}, Row{5, 0.05, 11.070}, Row{10, 0.05, 18.307},
                       Row{10, 0.01, 23.209}, Row{20, 0.01, 37.566}, Row{100, 0.05, 124.342},
                       Row{100, 0.01, 135.807}, Row{10, 0.95, 3.940}, Row{30, 0.10, 40.256}})
    EXPECT_NEAR(chi_squared_upper_quantile(r.alpha, r.dof), r.value, 5e-4)
        << r.dof << " " << r.alpha;
  // χ²₀.₉₉(10) = 23.2093 to four decimals, as quoted in most textbooks.
  EXPECT_NEAR(chi_squared_upper_quantile(0.01, 10), 23.2093, 5e-5);
}

TEST(Distributions, NormalClosedFormsAndTable) {
  EXPECT_NEAR(normal_two_sided_critical(0.05), 1.959963984540054, 1e-15);
  EXPECT_NEAR(normal_two_sided_critical(0.001), 3.290526731491895, 1e-14);  // Baarda's α0
  EXPECT_NEAR(normal_two_sided_critical(0.01), 2.575829303548901, 1e-14);
  // P(|Z| > |z|) = erfc(|z|/√2) (C library erfc as the independent reference).
  for (double z : {0.0, 0.5, -1.0, 1.959963984540054, 3.0, -5.0, 8.0}) {
    const double expected = std::erfc(std::abs(z) / std::sqrt(2.0));
    EXPECT_NEAR(normal_two_sided_probability(z), expected, 1e-14 * expected) << z;
  }
  // χ²(1) is Z²: its upper quantile at α is the square of the two-sided normal value.
  for (double alpha : {0.2, 0.05, 0.0027, 1e-5}) {
    const double k = normal_two_sided_critical(alpha);
    EXPECT_NEAR(chi_squared_upper_quantile(alpha, 1), k * k, 1e-12 * k * k) << alpha;
  }
}

// t(1) is Cauchy: k = tan(π(1 − α)/2); t(2): P(|T| > t) = 1 − t/√(2 + t²), so
// k = c·√(2/(1 − c²)) with c = 1 − α. Table (NIST 1.3.6.7.2): t₀.₉₇₅(10) = 2.228,
// t₀.₉₉₅(5) = 4.032, t₀.₉₇₅(30) = 2.042.
TEST(Distributions, StudentTClosedFormsAndTable) {
  for (double alpha : {0.5, 0.1, 0.05, 0.01}) {
    const double k1 = std::tan(kPi * (1.0 - alpha) / 2.0);
    EXPECT_NEAR(student_t_two_sided_critical(alpha, 1), k1, 1e-12 * k1) << alpha;
    const double c = 1.0 - alpha;
    const double k2 = c * std::sqrt(2.0 / (1.0 - c * c));
    EXPECT_NEAR(student_t_two_sided_critical(alpha, 2), k2, 1e-12 * k2) << alpha;
    EXPECT_NEAR(student_t_two_sided_probability(k2, 2), alpha, 1e-13) << alpha;
  }
  EXPECT_NEAR(student_t_two_sided_critical(0.05, 10), 2.228, 5e-4);
  EXPECT_NEAR(student_t_two_sided_critical(0.01, 5), 4.032, 5e-4);
  EXPECT_NEAR(student_t_two_sided_critical(0.05, 30), 2.042, 5e-4);
  // Many degrees of freedom approach the normal distribution.
  EXPECT_NEAR(student_t_two_sided_critical(0.05, 1e7), 1.959963984540054, 1e-6);
}

// F(2, ν2): P(F > x) = (1 + 2x/ν2)^(−ν2/2), so x = (ν2/2)·(α^(−2/ν2) − 1); F(1, ν) = t(ν)².
// Table (NIST 1.3.6.7.3): F₀.₉₅(5, 10) = 3.326, F₀.₉₉(2, 10) = 7.559, F₀.₉₅(10, 20) = 2.348.
TEST(Distributions, FisherFClosedFormsAndTable) {
  for (double d2 : {3.0, 10.0, 40.0})
    for (double alpha : {0.1, 0.05, 0.01}) {
      const double x = d2 / 2.0 * (std::pow(alpha, -2.0 / d2) - 1.0);
      EXPECT_NEAR(fisher_f_upper_quantile(alpha, 2, d2), x, 1e-12 * x) << d2 << " " << alpha;
      EXPECT_NEAR(fisher_f_upper_probability(x, 2, d2), alpha, 1e-13) << d2 << " " << alpha;
    }
  const double t = student_t_two_sided_critical(0.05, 12);
  EXPECT_NEAR(fisher_f_upper_quantile(0.05, 1, 12), t * t, 1e-11 * t * t);
  EXPECT_NEAR(fisher_f_upper_quantile(0.05, 5, 10), 3.326, 5e-4);
  EXPECT_NEAR(fisher_f_upper_quantile(0.01, 2, 10), 7.559, 5e-4);
  EXPECT_NEAR(fisher_f_upper_quantile(0.05, 10, 20), 2.348, 5e-4);
}

TEST(Distributions, QuantileInvertsProbability) {
  for (double dof : {1.0, 2.5, 7.0, 50.0, 1000.0})
    for (double x : {0.3, 1.0, 4.0, 12.0, 60.0}) {
      const double p = chi_squared_upper_probability(x, dof);
      // Inside (0, 1), and away from 1 where 1 − p (what fixes x) has lost its digits.
      if (!(p > 1e-300 && p < 0.999)) continue;
      EXPECT_NEAR(chi_squared_upper_quantile(p, dof), x, 1e-10 * x) << dof << " " << x;
      const double q = fisher_f_upper_probability(x / dof, dof, 9.0);
      EXPECT_NEAR(fisher_f_upper_quantile(q, dof, 9.0), x / dof, 1e-9 * x / dof) << dof;
      const double pt = student_t_two_sided_probability(x, dof);
      EXPECT_NEAR(student_t_two_sided_critical(pt, dof), x, 1e-9 * x) << dof << " " << x;
    }
  for (double z : {0.1, 1.0, 2.5, 6.0}) {
    EXPECT_NEAR(normal_two_sided_critical(normal_two_sided_probability(z)), z, 1e-12 * z);
    EXPECT_NEAR(normal_two_sided_critical(normal_two_sided_probability(-z)), z, 1e-12 * z);
  }
}

TEST(Distributions, ArgumentErrorsThrowInsteadOfNaN) {
  for (double alpha : {0.0, 1.0, -0.1, 1.5, kNaN, kInf}) {
    EXPECT_THROW(static_cast<void>(chi_squared_upper_quantile(alpha, 3)), InputError) << alpha;
    EXPECT_THROW(static_cast<void>(normal_two_sided_critical(alpha)), InputError) << alpha;
    EXPECT_THROW(static_cast<void>(student_t_two_sided_critical(alpha, 3)), InputError);
    EXPECT_THROW(static_cast<void>(fisher_f_upper_quantile(alpha, 3, 4)), InputError);
  }
  for (double dof : {0.0, 0.5, -2.0, kNaN, kInf}) {
    EXPECT_THROW(static_cast<void>(chi_squared_upper_quantile(0.05, dof)), InputError) << dof;
    EXPECT_THROW(static_cast<void>(chi_squared_upper_probability(1.0, dof)), InputError);
    EXPECT_THROW(static_cast<void>(student_t_two_sided_critical(0.05, dof)), InputError);
    EXPECT_THROW(static_cast<void>(student_t_two_sided_probability(1.0, dof)), InputError);
    EXPECT_THROW(static_cast<void>(fisher_f_upper_quantile(0.05, dof, 4)), InputError);
    EXPECT_THROW(static_cast<void>(fisher_f_upper_quantile(0.05, 4, dof)), InputError);
  }
  for (double x : {-1e-9, kNaN, kInf}) {
    EXPECT_THROW(static_cast<void>(chi_squared_upper_probability(x, 3)), InputError) << x;
    EXPECT_THROW(static_cast<void>(fisher_f_upper_probability(x, 3, 4)), InputError) << x;
  }
  EXPECT_THROW(static_cast<void>(normal_two_sided_probability(kNaN)), InputError);
  EXPECT_THROW(static_cast<void>(student_t_two_sided_probability(-kInf, 3)), InputError);
  EXPECT_THAT([] { chi_squared_upper_quantile(1.0, 3); },
              ThrowsMessage<InputError>(HasSubstr("must be in (0, 1), is 1")));
  EXPECT_THAT(
      [] { chi_squared_upper_quantile(0.05, 0.0); },
      ThrowsMessage<InputError>(HasSubstr("degrees of freedom must be finite and ≥ 1, is 0")));
  // Extreme but valid arguments give finite numbers.
  EXPECT_TRUE(std::isfinite(chi_squared_upper_quantile(1e-300, 1)));
  EXPECT_TRUE(std::isfinite(normal_two_sided_critical(1e-300)));
  EXPECT_EQ(chi_squared_upper_probability(1e6, 3), 0.0);
  EXPECT_EQ(chi_squared_upper_probability(0.0, 3), 1.0);
}

// ---------------------------------------------------------------------------------------------
// Solver quantities the tests use: Q_vv's diagonal and Baarda's w.

// Baarda's w_i is the test statistic of the outlier ∇ in the extended model
// l + v = A·x + e_i·∇ (an independent adjustment per observation): w_i = −∇̂/σ(∇̂) (v = A·x̂ − l
// makes w negative for a positive outlier) and w_i² = vᵀPv − vᵀPv_extended.
void expect_w_is_outlier_test(const MatrixXd& A, const VectorXd& l, const MatrixXd& S) {
  const LeastSquaresResult r = solve_linear(A, l, S);
  const Index n = A.rows();
  const Index u = A.cols();
  for (Index i = 0; i < n; ++i) {
    MatrixXd Ae(n, u + 1);
    Ae << A, VectorXd::Unit(n, i);
    const LeastSquaresResult e = solve_linear(Ae, l, S);
    const double w = -e.x(u) / e.sigma_apriori(static_cast<int>(u));
    EXPECT_NEAR(r.w_statistics(i), w, 1e-9 * (1.0 + std::abs(w))) << i;
    EXPECT_NEAR(r.w_statistics(i) * r.w_statistics(i), r.vtpv - e.vtpv, 1e-8 * (1.0 + r.vtpv)) << i;
  }
}

TEST(Statistics, WStatisticsAreTheOutlierTestCorrelated) {
  std::mt19937_64 rng(2718);
  std::normal_distribution<double> N(0.0, 1.0);
  const Index n = 10;
  const MatrixXd A = line_design(n);
  const MatrixXd S = ar1_covariance(n, 0.7);
  VectorXd l(n);
  for (Index i = 0; i < n; ++i) l(i) = 2.0 + 0.3 * static_cast<double>(i) + N(rng);
  expect_w_is_outlier_test(A, l, S);
  // With correlations v_i/σ_vi is a different statistic: the test above would notice a mix-up.
  const LeastSquaresResult r = solve_linear(A, l, S);
  EXPECT_GT((r.w_statistics - r.standardized_residuals).cwiseAbs().maxCoeff(), 0.1);
  // Dense formulas with Σ⁻¹: (Q_vv)_ii and w_i = (P·v)_i / sqrt((P·Q_vv·P)_ii).
  const MatrixXd P = S.inverse();
  const MatrixXd qvv = S - A * (A.transpose() * P * A).inverse() * A.transpose();
  const VectorXd pv = P * r.residuals;
  const MatrixXd pqp = P * qvv * P;
  for (Index i = 0; i < n; ++i) {
    EXPECT_NEAR(r.qvv_diagonal(i), qvv(i, i), 1e-12 * S(i, i)) << i;
    EXPECT_NEAR(r.w_statistics(i), pv(i) / std::sqrt(pqp(i, i)), 1e-9) << i;
  }
}

TEST(Statistics, WStatisticsEqualStandardizedResidualsWhenIndependent) {
  const Index n = 8;
  const MatrixXd A = line_design(n);
  VectorXd l(n), s(n);
  for (Index i = 0; i < n; ++i) {
    l(i) = 1.0 + 0.5 * static_cast<double>(i) + 0.1 * std::sin(3.0 * static_cast<double>(i));
    s(i) = 0.05 + 0.02 * static_cast<double>(i % 3);
  }
  const LeastSquaresResult r = solve_linear_diagonal(A, l, s);
  for (Index i = 0; i < n; ++i) {
    EXPECT_EQ(r.w_statistics(i), r.standardized_residuals(i)) << i;
    EXPECT_NEAR(r.qvv_diagonal(i), r.redundancy(i) * s(i) * s(i), 1e-15) << i;  // r_i = Q_vv,ii/σ²
  }
  expect_w_is_outlier_test(A, l, MatrixXd(s.array().square().matrix().asDiagonal()));
}

// ---------------------------------------------------------------------------------------------
// Global test.

// The straight line of test_linear.cpp: v = −0.06 0.13 −0.18 0.21 −0.10 (σ = 0.1), so
// vᵀPv = 10.7 with 3 degrees of freedom. χ²₀.₉₉(3) = 11.345, χ²₀.₉₅(3) = 7.815 (NIST table);
// P(χ²₃ > x) = erfc(√(x/2)) + √(2x/π)·e^{−x/2}.
TEST(Statistics, GlobalTestOfKnownAdjustment) {
  MatrixXd A(5, 2);
  A << 1, 1, 1, 2, 1, 3, 1, 4, 1, 5;
  const VectorXd l = (VectorXd(5) << 2.1, 3.9, 6.2, 7.8, 10.1).finished();
  const LeastSquaresResult r = solve_linear_diagonal(A, l, VectorXd::Constant(5, 0.1));
  const double x = 10.7;
  const double p = std::erfc(std::sqrt(x / 2.0)) + std::sqrt(2.0 * x / kPi) * std::exp(-x / 2.0);

  const auto g99 = global_test(r, 0.01);
  EXPECT_NEAR(g99.vtpv, x, 1e-10);
  EXPECT_EQ(g99.dof, 3);
  EXPECT_NEAR(g99.sigma0, std::sqrt(x / 3.0), 1e-11);
  EXPECT_EQ(g99.alpha, 0.01);
  EXPECT_NEAR(g99.critical_value, 11.345, 5e-4);
  EXPECT_NEAR(g99.p_value, p, 1e-12);
  EXPECT_FALSE(g99.rejected);

  const auto g95 = global_test(r, 0.05);
  EXPECT_NEAR(g95.critical_value, 7.815, 5e-4);
  EXPECT_NEAR(g95.p_value, p, 1e-12);  // ≈ 0.0135: between the two levels
  EXPECT_TRUE(g95.rejected);

  // The pieces give the same test; the statistic exactly at the limit is accepted.
  const auto g = global_test(g99.critical_value, 3, 0.01);
  EXPECT_FALSE(g.rejected);
  EXPECT_NEAR(g.p_value, 0.01, 1e-13);
  EXPECT_TRUE(global_test(std::nextafter(g99.critical_value, kInf), 3, 0.01).rejected);
}

TEST(Statistics, GlobalTestErrors) {
  MatrixXd A(2, 2);
  A << 1, 1, 1, 3;
  const LeastSquaresResult r0 = solve_linear_diagonal(A, VectorXd::Ones(2), VectorXd::Ones(2));
  ASSERT_EQ(r0.dof, 0);
  EXPECT_THAT([&] { global_test(r0, 0.05); },
              ThrowsMessage<InputError>(HasSubstr("degrees of freedom ≥ 1")));
  EXPECT_THROW(static_cast<void>(global_test(-1.0, 3, 0.05)), InputError);
  EXPECT_THROW(static_cast<void>(global_test(kNaN, 3, 0.05)), InputError);
  EXPECT_THROW(static_cast<void>(global_test(kInf, 3, 0.05)), InputError);
  EXPECT_THROW(static_cast<void>(global_test(1.0, 3, 0.0)), InputError);
  EXPECT_THROW(static_cast<void>(global_test(1.0, 3, 1.0)), InputError);
}

// Under the model (correlated Σ_ll, 8 degrees of freedom) the global test rejects in about
// α of the runs, its p-value is uniform, and the w-test rejects about α0 of the observations.
// Binomial limits at 4σ; a wrong dof (n instead of n − u: rate 4.2 % instead of 10 %) or the
// wrong tail would fail.
TEST(Statistics, MonteCarloRejectionRatesUnderTheModel) {
  const Index n = 10;
  const MatrixXd A = line_design(n);
  const MatrixXd S = ar1_covariance(n, 0.6);
  const MatrixXd L = Eigen::LLT<MatrixXd>(S).matrixL();
  const VectorXd x_true = (VectorXd(2) << 3.0, -0.2).finished();
  std::mt19937_64 rng(4242);
  std::normal_distribution<double> N(0.0, 1.0);
  const int runs = 500;
  const double alpha = 0.10;
  const double alpha0 = 0.05;
  int rejected = 0, w_rejected = 0, w_tested = 0;
  double p_sum = 0.0;
  for (int k = 0; k < runs; ++k) {
    VectorXd z(n);
    for (Index i = 0; i < n; ++i) z(i) = N(rng);
    const LeastSquaresResult r = solve_linear(A, A * x_true + L * z, S);
    const auto g = global_test(r, alpha);
    rejected += g.rejected ? 1 : 0;
    p_sum += g.p_value;
    const auto s = data_snooping(r, alpha0);
    w_rejected += static_cast<int>(s.rejected.size());
    w_tested += s.tested;
  }
  const double sd = std::sqrt(runs * alpha * (1.0 - alpha));
  EXPECT_NEAR(rejected, runs * alpha, 4.0 * sd);
  EXPECT_NEAR(p_sum / runs, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / runs));
  ASSERT_EQ(w_tested, runs * n);
  // The w_i of one run are correlated; 4σ of the independent case, doubled, stays lenient
  // but rejects a rate of 2·α0.
  const double w_sd = std::sqrt(w_tested * alpha0 * (1.0 - alpha0));
  EXPECT_NEAR(w_rejected, w_tested * alpha0, 8.0 * w_sd);
}

TEST(Statistics, ChiSquaredGate) {
  // χ²(2): limit −2·ln α.
  const double limit = -2.0 * std::log(0.01);
  EXPECT_TRUE(chi_squared_gate(0.0, 2, 0.01));
  EXPECT_TRUE(chi_squared_gate(limit * (1.0 - 1e-12), 2, 0.01));
  EXPECT_FALSE(chi_squared_gate(limit * (1.0 + 1e-12), 2, 0.01));
  EXPECT_THROW(static_cast<void>(chi_squared_gate(-1.0, 2, 0.01)), InputError);
  EXPECT_THROW(static_cast<void>(chi_squared_gate(1.0, 0, 0.01)), InputError);
  EXPECT_THROW(static_cast<void>(chi_squared_gate(1.0, 2, 1.0)), InputError);
}

// ---------------------------------------------------------------------------------------------
// w-test / data snooping.

// Twelve independent observations of a line with noise; a 9σ blunder in observation 5 is
// found (largest |w|, negative because v = A·x̂ − l), and it alone is rejected; without it
// none is.
TEST(Statistics, DataSnoopingFindsPlantedBlunder) {
  const Index n = 12;
  const MatrixXd A = line_design(n);
  const double sigma = 0.01;
  std::mt19937_64 rng(99);
  std::normal_distribution<double> N(0.0, sigma);
  VectorXd l(n);
  for (Index i = 0; i < n; ++i) l(i) = 5.0 + 0.01 * static_cast<double>(i) + N(rng);
  const VectorXd s = VectorXd::Constant(n, sigma);

  const LeastSquaresResult clean = solve_linear_diagonal(A, l, s);
  const auto c = data_snooping(clean, 0.001);
  EXPECT_NEAR(c.critical_value, 3.290526731491895, 1e-12);
  EXPECT_NEAR(c.alpha0, 0.001, 1e-15);
  EXPECT_TRUE(c.rejected.empty());
  EXPECT_EQ(c.tested, n);

  const double blunder = 9.0 * sigma;
  l(5) += blunder;
  const LeastSquaresResult r = solve_linear_diagonal(A, l, s);
  const auto b = data_snooping(r, 0.001);
  EXPECT_THAT(b.rejected, ElementsAre(5));
  EXPECT_EQ(b.largest_index, 5);
  EXPECT_LT(b.largest_w, 0.0);
  EXPECT_EQ(b.largest_w, r.w_statistics(5));
  // w is linear in l: the blunder shifts w_5 by exactly −∇·√r_5/σ_5 (≈ −8.6 here).
  EXPECT_NEAR(b.largest_w, clean.w_statistics(5) - blunder * std::sqrt(r.redundancy(5)) / sigma,
              1e-9);
  // The global test also notices it.
  EXPECT_TRUE(global_test(r, 0.01).rejected);
  EXPECT_FALSE(global_test(clean, 0.01).rejected);
}

TEST(Statistics, WTestWithCriticalValueSkipsUncontrolled) {
  const VectorXd w = (VectorXd(6) << 0.5, kNaN, -3.2, 3.1, kNaN, -0.1).finished();
  const auto r = w_test(w, 3.0);
  EXPECT_EQ(r.critical_value, 3.0);
  EXPECT_NEAR(r.alpha0, std::erfc(3.0 / std::sqrt(2.0)), 1e-17);  // 0.27 %
  EXPECT_THAT(r.rejected, ElementsAre(2, 3));
  EXPECT_EQ(r.tested, 4);
  EXPECT_EQ(r.largest_index, 2);
  EXPECT_EQ(r.largest_w, -3.2);
  // Ties keep the first; nothing tested gives no largest.
  const auto t = w_test((VectorXd(3) << 1.0, -1.0, 1.0).finished(), 3.0);
  EXPECT_EQ(t.largest_index, 0);
  EXPECT_TRUE(t.rejected.empty());
  const auto none = w_test((VectorXd(2) << kNaN, kNaN).finished(), 3.0);
  EXPECT_EQ(none.tested, 0);
  EXPECT_EQ(none.largest_index, -1);
  EXPECT_EQ(none.largest_w, 0.0);

  // In an adjustment, the observation that alone determines a parameter is not controlled.
  MatrixXd A(4, 2);
  A << 1, 0, 1, 0, 1, 0, 0, 1;
  const VectorXd l = (VectorXd(4) << 1.0, 1.2, 0.8, 5.0).finished();
  const LeastSquaresResult a = solve_linear_diagonal(A, l, VectorXd::Ones(4));
  ASSERT_TRUE(std::isnan(a.w_statistics(3)));
  const auto s = data_snooping(a, 0.05);
  EXPECT_EQ(s.tested, 3);
  EXPECT_NE(s.largest_index, 3);
}

TEST(Statistics, WTestErrors) {
  const VectorXd w = VectorXd::Zero(3);
  for (double k : {0.0, -1.0, kNaN, kInf})
    EXPECT_THROW(static_cast<void>(w_test(w, k)), InputError) << k;
  EXPECT_THAT([] { w_test((VectorXd(2) << 0.0, kInf).finished(), 3.0); },
              ThrowsMessage<InputError>(HasSubstr("observation 1")));
  LeastSquaresResult r;
  r.w_statistics = w;
  for (double a : {0.0, 1.0, 3.0, kNaN})
    EXPECT_THROW(static_cast<void>(data_snooping(r, a)), InputError) << a;
}

}  // namespace
