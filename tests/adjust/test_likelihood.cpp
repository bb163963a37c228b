// GLS log-likelihoods and the REML Fisher information against dense textbook formulas
// (explicit inverses and determinants, allowed here as the independent reference).
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/adjust/likelihood.hpp"
#include "meridian/core/error.hpp"

#include "adjust_test_support.hpp"

namespace {

using meridian_test::random_spd;

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using meridian::InputError;
using meridian::adjust::CovarianceFactor;
using meridian::adjust::gls_log_likelihood;
using meridian::adjust::reml_fisher_information;

constexpr double kLog2Pi = 1.8378770664093454836;

using meridian_test::random_matrix;

struct DenseLikelihood {
  double ml, reml;
};

// The textbook formulas with explicit inverses (Harville 1977).
DenseLikelihood dense_likelihood(const MatrixXd& A, const VectorXd& l, const MatrixXd& D) {
  const MatrixXd P = D.inverse();
  const MatrixXd N = A.transpose() * P * A;
  const VectorXd x = N.inverse() * A.transpose() * P * l;
  const VectorXd v = A * x - l;
  const double vtpv = v.dot(P * v);
  const double n = static_cast<double>(A.rows()), u = static_cast<double>(A.cols());
  const double ldd = std::log(D.determinant());
  return {-0.5 * (n * kLog2Pi + ldd + vtpv),
          -0.5 * ((n - u) * kLog2Pi + ldd + std::log(N.determinant()) -
                  std::log((A.transpose() * A).determinant()) + vtpv)};
}

TEST(Likelihood, MatchesDenseFormulas) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const Index n = 6 + trial, u = 2 + trial % 2;
    const MatrixXd A = random_matrix(n, u, rng);
    const VectorXd l = random_matrix(n, 1, rng);
    const MatrixXd D = random_spd(n, rng);
    const auto g = gls_log_likelihood(A, l, CovarianceFactor(D));
    const DenseLikelihood d = dense_likelihood(A, l, D);
    EXPECT_NEAR(g.ml, d.ml, 1e-10 * std::fabs(d.ml)) << trial;
    EXPECT_NEAR(g.reml, d.reml, 1e-10 * std::fabs(d.reml)) << trial;
    EXPECT_EQ(g.observations, n);
    EXPECT_EQ(g.parameters, u);
  }
}

TEST(Likelihood, DiagonalCovarianceClosedForm) {
  // l = c + noise, D = σ²·I: ln L = −n/2·ln(2πσ²) − Σ(l − l̄)²/(2σ²).
  const VectorXd l = (VectorXd(4) << 1.0, 2.0, 4.0, 5.0).finished();
  const MatrixXd A = MatrixXd::Ones(4, 1);
  const double s2 = 2.5;
  const auto g =
      gls_log_likelihood(A, l, CovarianceFactor::diagonal(VectorXd::Constant(4, std::sqrt(s2))));
  const double ss = 4.0 + 1.0 + 1.0 + 4.0;  // mean 3
  EXPECT_NEAR(g.ml, -2.0 * std::log(2.0 * M_PI * s2) - ss / (2.0 * s2), 1e-12);
  // REML: (n − 1) contrasts; ln det(AᵀD⁻¹A) − ln det(AᵀA) = ln(n/σ²) − ln n = −ln σ².
  EXPECT_NEAR(
      g.reml,
      -1.5 * std::log(2.0 * M_PI) - 0.5 * (4.0 * std::log(s2) - std::log(s2)) - ss / (2.0 * s2),
      1e-12);
}

TEST(Likelihood, RemlDoesNotDependOnTheParametrisation) {
  std::mt19937_64 rng(11);
  const MatrixXd A = random_matrix(9, 3, rng);
  const VectorXd l = random_matrix(9, 1, rng);
  const MatrixXd D = random_spd(9, rng);
  MatrixXd T = random_matrix(3, 3, rng);
  T.diagonal().array() += 3.0;
  const auto g1 = gls_log_likelihood(A, l, CovarianceFactor(D));
  const auto g2 = gls_log_likelihood(A * T, l, CovarianceFactor(D));
  EXPECT_NEAR(g1.reml, g2.reml, 1e-10 * std::fabs(g1.reml));
  EXPECT_NEAR(g1.ml, g2.ml, 1e-10 * std::fabs(g1.ml));
}

TEST(Likelihood, UnitChangeShiftsByTheDegreesOfFreedom) {
  // l in a unit s times smaller: ML + n·ln s, REML + (n − u)·ln s (header).
  std::mt19937_64 rng(3);
  const MatrixXd A = random_matrix(8, 2, rng);
  const VectorXd l = random_matrix(8, 1, rng);
  const MatrixXd D = random_spd(8, rng);
  const double s = 0.01;
  const auto g1 = gls_log_likelihood(A, l, CovarianceFactor(D));
  const auto g2 = gls_log_likelihood(A, l / s, CovarianceFactor(D / (s * s)));
  EXPECT_NEAR(g2.ml - g1.ml, -8.0 * std::log(1.0 / s), 1e-9);
  EXPECT_NEAR(g2.reml - g1.reml, -6.0 * std::log(1.0 / s), 1e-9);
}

TEST(Likelihood, FisherInformationMatchesDenseTraces) {
  std::mt19937_64 rng(5);
  const Index n = 10;
  const MatrixXd A = random_matrix(n, 3, rng);
  const MatrixXd D = random_spd(n, rng);
  const std::vector<MatrixXd> dd{random_spd(n, rng), MatrixXd::Identity(n, n), random_spd(n, rng)};
  const MatrixXd info = reml_fisher_information(A, CovarianceFactor(D), dd);
  const MatrixXd P = D.inverse();
  const MatrixXd Pb = P - P * A * (A.transpose() * P * A).inverse() * A.transpose() * P;
  for (Index a = 0; a < 3; ++a)
    for (Index b = 0; b < 3; ++b) {
      const double ref = 0.5 * (Pb * dd[a] * Pb * dd[b]).trace();
      EXPECT_NEAR(info(a, b), ref, 1e-10 * std::fabs(ref)) << a << b;
    }
}

TEST(Likelihood, BadInput) {
  const MatrixXd A = MatrixXd::Ones(3, 1);
  EXPECT_THROW(gls_log_likelihood(A, VectorXd::Ones(2), CovarianceFactor(MatrixXd::Identity(3, 3))),
               InputError);
  EXPECT_THROW(gls_log_likelihood(MatrixXd::Ones(1, 1), VectorXd::Ones(1),
                                  CovarianceFactor(MatrixXd::Identity(1, 1))),
               InputError);  // no redundancy
  EXPECT_THROW(reml_fisher_information(A, CovarianceFactor(MatrixXd::Identity(3, 3)),
                                       {MatrixXd::Identity(2, 2)}),
               InputError);
}

}  // namespace
