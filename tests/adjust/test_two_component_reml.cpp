// The closed-form profile of a two-component restricted likelihood against its independent
// references: the likelihood evaluated densely at the same θ (gls_log_likelihood, Cholesky of
// the assembled D), iterated variance-component estimation on both routes, and a brute-force
// search of the likelihood around the reported maximum; both boundaries of the quadrant.
#include <cmath>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/adjust/likelihood.hpp"
#include "meridian/adjust/two_component_reml.hpp"
#include "meridian/adjust/variance_components.hpp"
#include "meridian/core/error.hpp"

#include "adjust_test_support.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using meridian::InputError;
using meridian::NumericalError;
using meridian::adjust::assemble_covariance;
using meridian::adjust::CovarianceFactor;
using meridian::adjust::estimate_variance_components;
using meridian::adjust::gls_log_likelihood;
using meridian::adjust::maximise_two_component_reml;
using meridian::adjust::VarianceComponent;
using meridian::adjust::VceMethod;
using meridian::adjust::VceOptions;
using ::testing::HasSubstr;

using meridian_test::random_matrix;

// A Markov-like pair: Q_1 = C·Cᵀ (C unit lower-triangular, full rank), Q_2 = B·Bᵀ of rank 2.
struct Problem {
  MatrixXd A;
  VectorXd l;
  VarianceComponent first, second;
};

Problem markov_like(int n, std::uint64_t seed, double theta1, double theta2) {
  std::mt19937_64 rng(seed);
  Problem p;
  p.A = random_matrix(n, 3, rng);
  MatrixXd C = MatrixXd::Identity(n, n);
  for (int i = 1; i < n; ++i)
    for (int j = 0; j < i; ++j) C(i, j) = std::pow(0.6, i - j);
  const MatrixXd B = random_matrix(n, 2, rng);
  p.first = {"sigma1^2", C};
  p.second = {"sigma2^2", B};
  p.l = p.A * VectorXd::Constant(3, 10.0) + std::sqrt(theta1) * C * random_matrix(n, 1, rng) +
        std::sqrt(theta2) * B * random_matrix(2, 1, rng);
  return p;
}

double reml_dense(const Problem& p, double t1, double t2) {
  const MatrixXd D = assemble_covariance({p.first, p.second}, Eigen::Vector2d(t1, t2));
  return gls_log_likelihood(p.A, p.l, CovarianceFactor(D)).reml;
}

TEST(TwoComponentReml, LikelihoodEqualsTheDenseEvaluationAndTheVceOnBothRoutes) {
  int interior = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const Problem p = markov_like(20, seed, 4.0, 25.0);
    const auto m = maximise_two_component_reml(p.A, p.l, p.first, p.second);
    SCOPED_TRACE(testing::Message() << "seed " << seed << " theta " << m.components.transpose());
    EXPECT_EQ(m.residual_dimension, 17);
    // Independent evaluation at the same θ: dense D, Cholesky, QR of the whitened design.
    EXPECT_NEAR(m.reml, reml_dense(p, m.components(0), m.components(1)), 1e-10 * std::fabs(m.reml));
    if (m.at_zero[0] || m.at_zero[1]) continue;
    ++interior;
    for (VceMethod method : {VceMethod::LsVce, VceMethod::Helmert}) {
      VceOptions o;
      o.method = method;
      o.initial = Eigen::Vector2d(1.0, 1.0);
      const auto v = estimate_variance_components(p.A, p.l, {p.first, p.second}, o);
      ASSERT_FALSE(v.clipped[0] || v.clipped[1]);
      EXPECT_NEAR(v.components(0), m.components(0), 1e-8 * m.components.maxCoeff());
      EXPECT_NEAR(v.components(1), m.components(1), 1e-8 * m.components.maxCoeff());
      EXPECT_NEAR(v.likelihood.reml, m.reml, 1e-12 * std::fabs(m.reml));
    }
  }
  EXPECT_GE(interior, 6);  // the comparison with the VCE must have been made
}

TEST(TwoComponentReml, NoNeighbourOnABruteForceGridIsHigher) {
  const Problem p = markov_like(15, 77, 9.0, 4.0);
  const auto m = maximise_two_component_reml(p.A, p.l, p.first, p.second);
  ASSERT_FALSE(m.at_zero[0] || m.at_zero[1]);
  for (double f1 : {0.5, 0.9, 0.99, 0.999, 1.0, 1.001, 1.01, 1.1, 2.0})
    for (double f2 : {0.0, 0.5, 0.9, 0.99, 0.999, 1.0, 1.001, 1.01, 1.1, 2.0})
      EXPECT_LE(reml_dense(p, f1 * m.components(0), f2 * m.components(1)),
                m.reml + 1e-12 * std::fabs(m.reml))
          << f1 << " " << f2;
}

TEST(TwoComponentReml, SecondComponentAtZeroWhenTheDataHaveNoneOfIt) {
  // l has no component along the residual part of F_2 (Q_1 = I): θ_2 = 0 exactly and θ_1 the
  // a-posteriori variance of ordinary least squares; the VCE clips θ_2 to the same point.
  std::mt19937_64 rng(5);
  const int n = 14;
  const MatrixXd A = random_matrix(n, 3, rng);
  const MatrixXd proj =
      MatrixXd::Identity(n, n) - A * (A.transpose() * A).ldlt().solve(A.transpose());
  const VectorXd f = random_matrix(n, 1, rng);
  const VectorXd fr = proj * f;
  VectorXd l = random_matrix(n, 1, rng);
  l -= fr * (fr.dot(l) / fr.squaredNorm());
  const VarianceComponent c1{"s1", MatrixXd::Identity(n, n)}, c2{"s2", f};
  const auto m = maximise_two_component_reml(A, l, c1, c2);
  EXPECT_TRUE(m.at_zero[1]);
  EXPECT_FALSE(m.at_zero[0]);
  EXPECT_EQ(m.components(1), 0.0);
  EXPECT_NEAR(m.components(0), (proj * l).squaredNorm() / (n - 3), 1e-12);
  const auto v = estimate_variance_components(A, l, {c1, c2}, {});
  EXPECT_TRUE(v.clipped[1]);
  EXPECT_NEAR(v.components(0), m.components(0), 1e-9 * m.components(0));
  const Problem p{A, l, c1, c2};
  EXPECT_NEAR(m.reml, reml_dense(p, m.components(0), 0.0), 1e-12 * std::fabs(m.reml));
}

TEST(TwoComponentReml, FirstComponentAtZeroWhenTheDataFollowTheSecondExactly) {
  // Q_1 = I, Q_2 definite; residual coordinates z_j ∝ λ_j in Q_2's eigenbasis make the slope of
  // the likelihood in θ_1 at θ_1 = 0 negative (AM–HM): the maximum is on the boundary θ_1 = 0.
  std::mt19937_64 rng(9);
  const int n = 12;
  const MatrixXd A = random_matrix(n, 2, rng);
  const Eigen::HouseholderQR<MatrixXd> qr(A);
  const MatrixXd K = MatrixXd(qr.householderQ()).rightCols(n - 2);
  const MatrixXd W = random_matrix(n, n, rng) + 3.0 * MatrixXd::Identity(n, n);
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(K.transpose() * W * W.transpose() * K);
  const VectorXd lam = eig.eigenvalues();
  const VectorXd z = lam * std::sqrt((n - 2) / lam.sum());
  const VectorXd l = K * (eig.eigenvectors() * z) + A * Eigen::Vector2d(3.0, -1.0);
  const VarianceComponent c1{"s1", MatrixXd::Identity(n, n)}, c2{"s2", W};
  const auto m = maximise_two_component_reml(A, l, c1, c2);
  EXPECT_TRUE(m.at_zero[0]);
  EXPECT_EQ(m.components(0), 0.0);
  EXPECT_NEAR(m.components(1), 1.0, 1e-12);  // Σ z_j²/λ_j / r = 1 by construction
  const Problem p{A, l, c1, c2};
  EXPECT_NEAR(m.reml, reml_dense(p, 0.0, 1.0), 1e-12 * std::fabs(m.reml));
  const auto v = estimate_variance_components(A, l, {c1, c2}, {});
  EXPECT_TRUE(v.clipped[0]);
  EXPECT_NEAR(v.components(1), 1.0, 1e-9);
}

TEST(TwoComponentReml, BadInputIsReported) {
  const Problem p = markov_like(10, 3, 1.0, 1.0);
  EXPECT_THROW(maximise_two_component_reml(p.A, p.l.head(9), p.first, p.second), InputError);
  EXPECT_THROW(maximise_two_component_reml(p.A.leftCols(0), p.l, p.first, p.second), InputError);
  VarianceComponent bad = p.second;
  bad.factor(2, 1) = std::nan("");
  EXPECT_THROW(maximise_two_component_reml(p.A, p.l, p.first, bad), InputError);
  // Q_1 of rank 2: singular on the 7-dimensional residual space.
  try {
    maximise_two_component_reml(p.A, p.l, p.second, p.first);
    ADD_FAILURE() << "no error";
  } catch (const NumericalError& e) {
    EXPECT_THAT(e.what(), HasSubstr("sigma2^2 is singular on the residual space"));
  }
  // No residual at all.
  const VectorXd exact = p.A * Eigen::Vector3d(1.0, 2.0, 3.0);
  EXPECT_THROW(maximise_two_component_reml(p.A, exact, p.first, p.second), NumericalError);
  // Rank-deficient design.
  MatrixXd a2 = p.A;
  a2.col(2) = a2.col(1);
  EXPECT_THROW(maximise_two_component_reml(a2, p.l, p.first, p.second), NumericalError);
}

}  // namespace
