// Variance-component estimation against closed forms (one component; separable groups), the
// REML score equations evaluated with dense explicit inverses, the second computational route
// (Helmert's equations through the normal matrix) and a Monte Carlo of the reported σ.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/adjust/variance_components.hpp"
#include "meridian/core/error.hpp"

#include "adjust_test_support.hpp"

namespace {

using meridian_test::message_of;

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using meridian::InputError;
using meridian::NumericalError;
using meridian::adjust::assemble_covariance;
using meridian::adjust::CovarianceFactor;
using meridian::adjust::estimate_variance_components;
using meridian::adjust::reml_fisher_information;
using meridian::adjust::VarianceComponent;
using meridian::adjust::VceMethod;
using meridian::adjust::VceOptions;
using ::testing::HasSubstr;

using meridian_test::random_matrix;

TEST(VarianceComponents, OneComponentIsTheAposterioriVariance) {
  // D = θ·I: the REML estimate is σ̂0² = vᵀv/(n − u) of ordinary least squares, in one step.
  std::mt19937_64 rng(1);
  const MatrixXd A = random_matrix(12, 3, rng);
  const VectorXd l = random_matrix(12, 1, rng) * 4.0;
  const MatrixXd H = A * (A.transpose() * A).inverse() * A.transpose();
  const VectorXd v = (MatrixXd::Identity(12, 12) - H) * l;
  const double s2 = v.squaredNorm() / 9.0;
  for (VceMethod m : {VceMethod::LsVce, VceMethod::Helmert}) {
    VceOptions o;
    o.method = m;
    const auto r = estimate_variance_components(A, l, {{"s^2", MatrixXd::Identity(12, 12)}}, o);
    EXPECT_NEAR(r.components(0), s2, 1e-12 * s2);
    // σ(θ̂) = θ·sqrt(2/(n − u)) for one component (χ² with n − u degrees of freedom).
    EXPECT_NEAR(r.sigma(0), s2 * std::sqrt(2.0 / 9.0), 1e-10 * s2);
    EXPECT_NEAR(r.adjustment.sigma0, 1.0, 1e-10);
    EXPECT_FALSE(r.clipped[0]);
  }
}

TEST(VarianceComponents, SeparableGroupsAreEachGroupsVariance) {
  // Two groups of observations, each with its own mean and variance: block-diagonal Q_k
  // (Helmert's original setting) with a design that does not couple them, so each θ̂_k is the
  // group's sample variance about its mean, Σ(l − l̄)²/(n_k − 1).
  const VectorXd l = (VectorXd(9) << 1.0, 3.0, 2.0, 6.0, 10.0, 0.0, 20.0, -4.0, 8.0).finished();
  MatrixXd A = MatrixXd::Zero(9, 2);
  A.block(0, 0, 4, 1).setOnes();
  A.block(4, 1, 5, 1).setOnes();
  MatrixXd f1 = MatrixXd::Zero(9, 4), f2 = MatrixXd::Zero(9, 5);
  f1.topRows(4).setIdentity();
  f2.bottomRows(5).setIdentity();
  const auto r = estimate_variance_components(A, l, {{"group 1", f1}, {"group 2", f2}});
  // Group 1: mean 3, Σ(l − 3)² = 4 + 0 + 1 + 9 = 14 → 14/3. Group 2: mean 6.8,
  // Σ = 10.24 + 46.24 + 174.24 + 116.64 + 1.44 = 348.8 → 87.2.
  EXPECT_NEAR(r.components(0), 14.0 / 3.0, 1e-10);
  EXPECT_NEAR(r.components(1), 87.2, 1e-9);
  // Independent groups: σ²(θ̂_k) = 2θ_k²/(n_k − 1).
  EXPECT_NEAR(r.sigma(0), 14.0 / 3.0 * std::sqrt(2.0 / 3.0), 1e-9);
  EXPECT_NEAR(r.sigma(1), 87.2 * std::sqrt(2.0 / 4.0), 1e-8);
  EXPECT_NEAR(r.covariance(0, 1), 0.0, 1e-9);
}

// A correlated model: white noise plus a random-walk-like signal (Q2 = C·Cᵀ, C lower ones).
struct Correlated {
  MatrixXd A;
  VectorXd l;
  std::vector<VarianceComponent> comps;
};

Correlated correlated_case(std::uint64_t seed, double s1, double s2, Index n = 24) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  Correlated c;
  c.A.resize(n, 2);
  MatrixXd ft = MatrixXd::Zero(n, n);
  for (Index i = 0; i < n; ++i) {
    c.A(i, 0) = 1.0;
    c.A(i, 1) = (i % 2 == 0) ? 1.0 : -1.0;
    for (Index j = 0; j <= i; ++j) ft(i, j) = std::pow(0.7, static_cast<double>(i - j));
  }
  c.comps = {{"white", MatrixXd::Identity(n, n)}, {"markov", ft}};
  VectorXd e(n);
  for (Index i = 0; i < n; ++i) e(i) = N(rng);
  VectorXd d(n);
  for (Index i = 0; i < n; ++i) d(i) = N(rng);
  c.l = c.A * VectorXd::Constant(2, 3.0) + s1 * e + s2 * ft * d;
  return c;
}

TEST(VarianceComponents, ConvergedEstimatesSolveTheRemlScoreEquations) {
  // At the REML maximum q_k = vᵀPQ_kPv equals tr(P̄Q_k) (Harville 1977), evaluated here with
  // explicit dense inverses.
  // (Seed 5 of this design has its REML maximum on the boundary θ_markov = 0, checked on a
  // dense grid; seed 1000 has it inside.)
  const Correlated c = correlated_case(1000, 1.0, 2.0);
  const auto r = estimate_variance_components(c.A, c.l, c.comps);
  ASSERT_FALSE(r.clipped[0] || r.clipped[1]);
  const MatrixXd D = assemble_covariance(c.comps, r.components);
  const MatrixXd P = D.inverse();
  const MatrixXd Pb = P - P * c.A * (c.A.transpose() * P * c.A).inverse() * c.A.transpose() * P;
  for (std::size_t k = 0; k < 2; ++k) {
    const MatrixXd Q = c.comps[k].factor * c.comps[k].factor.transpose();
    const double q = c.l.dot(Pb * Q * Pb * c.l);
    const double t = (Pb * Q).trace();
    EXPECT_NEAR(q, t, 1e-8 * t) << k;
  }
  // The reported covariance is the inverse REML Fisher information.
  std::vector<MatrixXd> dd;
  for (const auto& comp : c.comps) dd.push_back(comp.factor * comp.factor.transpose());
  const MatrixXd info = reml_fisher_information(c.A, CovarianceFactor(D), dd);
  const MatrixXd prod = info * r.covariance;
  EXPECT_LT((prod - MatrixXd::Identity(2, 2)).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(VarianceComponents, HelmertAndLsVceRoutesAgree) {
  for (std::uint64_t seed : {5u, 6u, 7u}) {
    const Correlated c = correlated_case(seed, 1.0, 3.0);
    VceOptions a, b;
    a.method = VceMethod::LsVce;
    b.method = VceMethod::Helmert;
    const auto ra = estimate_variance_components(c.A, c.l, c.comps, a);
    const auto rb = estimate_variance_components(c.A, c.l, c.comps, b);
    for (Index k = 0; k < 2; ++k) {
      EXPECT_NEAR(ra.components(k), rb.components(k), 1e-9 * ra.components.maxCoeff()) << seed;
      ASSERT_EQ(ra.clipped[static_cast<std::size_t>(k)], rb.clipped[static_cast<std::size_t>(k)]);
      if (!ra.clipped[static_cast<std::size_t>(k)]) {
        EXPECT_NEAR(ra.sigma(static_cast<int>(k)), rb.sigma(static_cast<int>(k)),
                    1e-9 * ra.sigma(static_cast<int>(k)));
      }
    }
    EXPECT_NEAR(ra.adjustment.x(0), rb.adjustment.x(0), 1e-9 * std::fabs(ra.adjustment.x(0)));
    EXPECT_NEAR(ra.likelihood.reml, rb.likelihood.reml, 1e-9 * std::fabs(ra.likelihood.reml));
  }
}

TEST(VarianceComponents, FullCofactorAndItsFactorGiveTheSameEstimate) {
  const Correlated c = correlated_case(9, 1.0, 2.0);
  const MatrixXd q2 = c.comps[1].factor * c.comps[1].factor.transpose();
  const auto r1 = estimate_variance_components(c.A, c.l, c.comps);
  const auto r2 = estimate_variance_components(
      c.A, c.l, {c.comps[0], VarianceComponent::from_cofactor("markov", q2)});
  EXPECT_NEAR(r1.components(0), r2.components(0), 1e-9 * r1.components.maxCoeff());
  EXPECT_NEAR(r1.components(1), r2.components(1), 1e-9 * r1.components.maxCoeff());
}

TEST(VarianceComponents, NegativeComponentIsClippedAndSaid) {
  // Q2 touches only the first observation, which fits the model exactly: the data say the
  // component is smaller than nothing.
  const Index n = 8;
  MatrixXd A = MatrixXd::Ones(n, 1);
  VectorXd l(n);
  l << 5.0, 4.0, 6.0, 3.0, 7.0, 5.5, 4.5, 5.0;  // mean 5: the first residual is 0
  MatrixXd f2 = MatrixXd::Zero(n, 1);
  f2(0, 0) = 1.0;
  const auto r =
      estimate_variance_components(A, l, {{"white", MatrixXd::Identity(n, n)}, {"spike", f2}});
  EXPECT_TRUE(r.clipped[1]);
  EXPECT_EQ(r.components(1), 0.0);
  EXPECT_TRUE(std::isnan(r.sigma(1)));
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_THAT(r.notes[0], HasSubstr("spike estimated negative"));
  // With the spike gone the white component is the one-component estimate.
  EXPECT_NEAR(r.components(0), 10.5 / 7.0, 1e-9);  // Σ(l − 5)² = 10.5 over 7
}

TEST(VarianceComponents, NonConvergenceIsANumericalError) {
  const Correlated c = correlated_case(5, 1.5, 2.0);
  VceOptions o;
  o.max_iterations = 2;
  EXPECT_THAT(
      message_of<NumericalError>([&] { estimate_variance_components(c.A, c.l, c.comps, o); }),
      HasSubstr("did not converge in 2 iterations"));
}

TEST(VarianceComponents, BadInput) {
  const Correlated c = correlated_case(5, 1.5, 2.0);
  // Fewer degrees of freedom than components.
  EXPECT_THAT(message_of<InputError>([&] {
                estimate_variance_components(
                    c.A.topRows(3), c.l.head(3),
                    {{"a", MatrixXd::Identity(3, 3)}, {"b", MatrixXd::Identity(3, 3)}});
              }),
              HasSubstr("need at least 2 degrees of freedom"));
  EXPECT_THAT(message_of<InputError>([&] {
                estimate_variance_components(c.A, c.l, {{"zero", MatrixXd::Zero(24, 2)}});
              }),
              HasSubstr("zero"));
  VceOptions o;
  o.initial = VectorXd::Constant(2, -1.0);
  EXPECT_THROW(estimate_variance_components(c.A, c.l, c.comps, o), InputError);
  // Two identical components cannot be separated.
  EXPECT_THAT(
      message_of<NumericalError>([&] {
        estimate_variance_components(c.A, c.l, {c.comps[0], {"again", MatrixXd::Identity(24, 24)}});
      }),
      HasSubstr("cannot be separated"));
  // A semi-definite component alone gives a singular covariance.
  MatrixXd f = MatrixXd::Zero(24, 1);
  f(0, 0) = 1.0;
  EXPECT_THROW(estimate_variance_components(c.A, c.l, {{"rank one", f}}), NumericalError);
  EXPECT_THROW(VarianceComponent::from_cofactor("neg", -MatrixXd::Identity(3, 3)), InputError);
}

TEST(VarianceComponents, MonteCarloSigmaMatchesScatter) {
  // 200 replications of the correlated model: the mean of θ̂ is the truth (REML is unbiased
  // here to its standard error) and the mean reported σ(θ̂) matches the empirical scatter.
  // n = 60 and σ1 = σ2 keep the REML maximum inside (θ > 0) in most runs; with n = 24,
  // σ1 = 1 a third of the runs have it on the boundary (a dense grid of the REML agrees).
  const double s1 = 2.0, s2 = 2.0;
  const int runs = 200;
  std::vector<double> t1, t2, r1, r2;
  for (int i = 0; i < runs; ++i) {
    const Correlated c = correlated_case(1000 + static_cast<std::uint64_t>(i), s1, s2, 60);
    const auto r = estimate_variance_components(c.A, c.l, c.comps);
    if (r.clipped[0] || r.clipped[1]) continue;
    t1.push_back(r.components(0));
    t2.push_back(r.components(1));
    r1.push_back(r.sigma(0));
    r2.push_back(r.sigma(1));
  }
  ASSERT_GT(t1.size(), 180u);
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / static_cast<double>(v.size());
  };
  auto sd = [&](const std::vector<double>& v) {
    const double m = mean(v);
    double s = 0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
  };
  const double m = static_cast<double>(t1.size());
  EXPECT_NEAR(mean(t1), s1 * s1, 3.0 * sd(t1) / std::sqrt(m));
  EXPECT_NEAR(mean(t2), s2 * s2, 3.0 * sd(t2) / std::sqrt(m));
  EXPECT_NEAR(mean(r1) / sd(t1), 1.0, 0.2);
  EXPECT_NEAR(mean(r2) / sd(t2), 1.0, 0.2);
}

}  // namespace
