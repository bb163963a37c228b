// Gauss–Newton / Levenberg–Marquardt against noise-free closed forms, the optimality
// condition Jᵀ·Σ⁻¹·v = 0, and the dense cofactor formula at the solution.
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adjust_test_support.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/adjust/nonlinear.hpp"
#include "meridian/core/error.hpp"

namespace {

using meridian_test::message_of;

using meridian::InputError;
using meridian::NumericalError;
using meridian::adjust::NonlinearModel;
using meridian::adjust::NonlinearOptions;
using meridian::adjust::NonlinearResult;
using meridian::adjust::solve_linear;
using meridian::adjust::solve_nonlinear;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using ::testing::HasSubstr;

// y = a·exp(−b·t), t = 0, 0.5, …, 6.
VectorXd times() { return VectorXd::LinSpaced(13, 0.0, 6.0); }

NonlinearModel decay_model(bool analytic) {
  const VectorXd t = times();
  NonlinearModel m;
  m.predict = [t](const VectorXd& x) -> VectorXd {
    return x(0) * (-x(1) * t.array()).exp();
  };
  if (analytic) {
    m.jacobian = [t](const VectorXd& x) -> MatrixXd {
      MatrixXd J(t.size(), 2);
      const Eigen::ArrayXd e = (-x(1) * t.array()).exp();
      J.col(0) = e.matrix();
      J.col(1) = (-x(0) * t.array() * e).matrix();
      return J;
    };
  }
  return m;
}

// Analytic Jacobian of the decay model (for the dense checks).
MatrixXd decay_jacobian(const VectorXd& x) { return decay_model(true).jacobian(x); }

// AR(1) covariance with ρ and σ.
MatrixXd ar1(Index n, double sigma, double rho) {
  MatrixXd S(n, n);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j)
      S(i, j) = sigma * sigma * std::pow(rho, std::abs(static_cast<double>(i - j)));
  return S;
}

class Decay : public ::testing::TestWithParam<bool> {};

TEST_P(Decay, NoiseFreeRecoveryFromFarAway) {
  const bool analytic = GetParam();
  const VectorXd x_true = (VectorXd(2) << 5.0, 0.7).finished();
  const NonlinearModel m = decay_model(analytic);
  const VectorXd l = m.predict(x_true);
  const VectorXd x0 = (VectorXd(2) << 0.5, 4.0).finished();  // 10× off in both
  const MatrixXd S = ar1(l.size(), 0.01, 0.5);
  const NonlinearResult r = solve_nonlinear(m, l, S, x0);
  EXPECT_TRUE(r.converged);
  EXPECT_GT(r.iterations, 3);
  EXPECT_NEAR(r.x(0), 5.0, 1e-10 * 5.0);
  EXPECT_NEAR(r.x(1), 0.7, 1e-10 * 0.7);
  EXPECT_EQ(r.dof, 11);
  EXPECT_LT(r.vtpv, 1e-16);
  // Cofactor at the solution: (Jᵀ Σ⁻¹ J)⁻¹ with the analytic Jacobian at the true values.
  const MatrixXd J = decay_jacobian(x_true);
  const MatrixXd Q = (J.transpose() * S.inverse() * J).inverse();
  for (Index j = 0; j < 2; ++j)
    for (Index k = 0; k < 2; ++k)
      EXPECT_NEAR(r.cofactor(j, k), Q(j, k), (analytic ? 1e-9 : 1e-6) * std::abs(Q(j, j)));
  EXPECT_NEAR(r.redundancy.sum(), 11.0, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(AnalyticAndNumerical, Decay, ::testing::Bool());

TEST(Nonlinear, NoisyDecaySatisfiesNormalEquations) {
  const VectorXd t = times();
  const NonlinearModel m = decay_model(true);
  std::mt19937_64 rng(4711);
  std::normal_distribution<double> N(0.0, 0.05);
  VectorXd l = m.predict((VectorXd(2) << 3.0, 0.4).finished());
  for (Index i = 0; i < l.size(); ++i) l(i) += N(rng);
  const MatrixXd S = ar1(l.size(), 0.05, 0.3);
  const NonlinearResult r = solve_nonlinear(m, l, S, (VectorXd(2) << 1.0, 2.0).finished());
  // Independent optimality check with the dense inverse: Jᵀ·Σ⁻¹·(f(x̂) − l) = 0.
  const MatrixXd P = S.inverse();
  const MatrixXd J = decay_jacobian(r.x);
  const VectorXd v = m.predict(r.x) - l;
  const VectorXd g = J.transpose() * P * v;
  const VectorXd gscale = (J.transpose() * P * J).diagonal().cwiseSqrt() * std::sqrt(v.dot(P * v));
  for (Index j = 0; j < 2; ++j) EXPECT_LT(std::abs(g(j)) / gscale(j), 1e-9) << j;
  EXPECT_NEAR(r.vtpv, v.dot(P * v), 1e-9 * r.vtpv);
  for (Index i = 0; i < l.size(); ++i) EXPECT_NEAR(r.residuals(i), v(i), 1e-10);
  EXPECT_NEAR(r.sigma0, std::sqrt(v.dot(P * v) / 11.0), 1e-9);
  const MatrixXd Q = (J.transpose() * P * J).inverse();
  EXPECT_NEAR(r.sigma_apriori(1), std::sqrt(Q(1, 1)), 1e-9 * std::sqrt(Q(1, 1)));
  EXPECT_NEAR(r.covariance_aposteriori(0, 1), r.sigma0 * r.sigma0 * Q(0, 1),
              1e-8 * std::abs(Q(0, 0)));
  // Redundancy and standardised residuals of the linearised problem at x̂.
  const MatrixXd qvv = S - J * Q * J.transpose();
  const VectorXd red = (qvv * P).diagonal();
  for (Index i = 0; i < l.size(); ++i) {
    EXPECT_NEAR(r.redundancy(i), red(i), 1e-9);
    EXPECT_NEAR(r.standardized_residuals(i), v(i) / std::sqrt(qvv(i, i)), 1e-7);
  }
}

// Distance resection: position from distances to four known points, start 2 km away.
TEST(Nonlinear, DistanceResection) {
  const MatrixXd P = (MatrixXd(4, 2) << 1000.0, 2000.0, 3500.0, 2100.0, 3300.0, 4800.0, 900.0,
                      4500.0).finished();
  const VectorXd x_true = (VectorXd(2) << 2234.5678, 3187.1234).finished();
  NonlinearModel m;
  m.predict = [P](const VectorXd& x) -> VectorXd {
    return (P.rowwise() - x.transpose()).rowwise().norm();
  };
  const VectorXd l = m.predict(x_true);
  NonlinearOptions opt;
  opt.step_scale = VectorXd::Constant(2, 1000.0);  // metres
  const auto r = solve_nonlinear(m, l, 1e-6 * MatrixXd::Identity(4, 4),
                                 (VectorXd(2) << 500.0, 6000.0).finished(), opt);
  EXPECT_NEAR(r.x(0), x_true(0), 1e-10 * 3000.0);
  EXPECT_NEAR(r.x(1), x_true(1), 1e-10 * 3000.0);
}

TEST(Nonlinear, LinearModelReproducesLinearSolver) {
  MatrixXd A(5, 2);
  A << 1, 0, 1, 1, 1, 2, 1, 3, 1, 4;
  const VectorXd l = (VectorXd(5) << 0.9, 3.1, 4.8, 7.2, 9.0).finished();
  const MatrixXd S = ar1(5, 0.2, 0.4);
  NonlinearModel m;
  m.predict = [A](const VectorXd& x) -> VectorXd { return A * x; };
  const auto r = solve_nonlinear(m, l, S, VectorXd::Zero(2));
  const auto lin = solve_linear(A, l, S);
  EXPECT_LT((r.x - lin.x).norm(), 1e-9);
  EXPECT_LT((r.cofactor - lin.cofactor).norm(), 1e-8);
  EXPECT_NEAR(r.vtpv, lin.vtpv, 1e-9);
  EXPECT_LT((r.redundancy - lin.redundancy).norm(), 1e-8);
}

// With λ = 1e14 the first steps are ~1e-14, below the step tolerance, only because of the
// damping: that must not count as convergence.
TEST(Nonlinear, HeavyDampingIsNotConvergence) {
  const NonlinearModel m = decay_model(true);
  NonlinearOptions opt;
  opt.initial_damping = 1e14;
  const auto r = solve_nonlinear(m, m.predict((VectorXd(2) << 5.0, 0.7).finished()),
                                 MatrixXd::Identity(13, 13), (VectorXd(2) << 0.5, 4.0).finished(),
                                 opt);
  EXPECT_NEAR(r.x(0), 5.0, 1e-10 * 5.0);
  EXPECT_NEAR(r.x(1), 0.7, 1e-10 * 0.7);
}

TEST(Nonlinear, StartAtSolutionTakesNoStep) {
  const NonlinearModel m = decay_model(true);
  const VectorXd x = (VectorXd(2) << 2.0, 0.5).finished();
  const auto r = solve_nonlinear(m, m.predict(x), MatrixXd::Identity(13, 13), x);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.x, x);
}

TEST(Nonlinear, NonConvergenceThrows) {
  const NonlinearModel m = decay_model(true);
  const VectorXd l = m.predict((VectorXd(2) << 5.0, 0.7).finished());
  NonlinearOptions opt;
  opt.max_iterations = 2;
  const std::string msg = message_of<NumericalError>([&] {
    solve_nonlinear(m, l, MatrixXd::Identity(13, 13), (VectorXd(2) << 0.5, 4.0).finished(), opt);
  });
  EXPECT_THAT(msg, HasSubstr("no convergence within 2 iterations"));
  EXPECT_THAT(msg, HasSubstr("the last step changed parameter"));
  EXPECT_THAT(msg, HasSubstr("vᵀPv = "));
}

// f = a·b·t determines only the product: singular whatever the Jacobian.
TEST(Nonlinear, ProductOfParametersIsSingular) {
  const VectorXd t = VectorXd::LinSpaced(6, 1.0, 6.0);
  for (const bool analytic : {false, true}) {
    NonlinearModel m;
    m.predict = [t](const VectorXd& x) -> VectorXd { return x(0) * x(1) * t; };
    if (analytic) {
      m.jacobian = [t](const VectorXd& x) -> MatrixXd {
        MatrixXd J(t.size(), 2);
        J.col(0) = x(1) * t;
        J.col(1) = x(0) * t;
        return J;
      };
    }
    const VectorXd l = 6.0 * t;
    const std::string msg = message_of<NumericalError>([&] {
      solve_nonlinear(m, l, MatrixXd::Identity(6, 6), (VectorXd(2) << 1.3, 2.9).finished());
    });
    EXPECT_THAT(msg, HasSubstr("normal matrix is singular")) << analytic;
  }
}

// From the far start of the Decay tests undamped Gauss–Newton overshoots into b ≫ 1, where the
// Jacobian is numerically rank deficient: Levenberg–Marquardt is needed there.
TEST(Nonlinear, PlainGaussNewtonFailsFromFarAway) {
  const NonlinearModel m = decay_model(true);
  NonlinearOptions opt;
  opt.levenberg_marquardt = false;
  EXPECT_THROW(solve_nonlinear(m, m.predict((VectorXd(2) << 5.0, 0.7).finished()),
                               MatrixXd::Identity(13, 13), (VectorXd(2) << 0.5, 4.0).finished(),
                               opt),
               NumericalError);
}

TEST(Nonlinear, PlainGaussNewtonFromNearbyStart) {
  const NonlinearModel m = decay_model(true);
  const VectorXd x_true = (VectorXd(2) << 5.0, 0.7).finished();
  NonlinearOptions opt;
  opt.levenberg_marquardt = false;
  const auto r = solve_nonlinear(m, m.predict(x_true), MatrixXd::Identity(13, 13),
                                 (VectorXd(2) << 4.8, 0.72).finished(), opt);
  EXPECT_NEAR(r.x(0), 5.0, 1e-10 * 5.0);
  EXPECT_NEAR(r.x(1), 0.7, 1e-10 * 0.7);
}

TEST(Nonlinear, InputAndModelErrors) {
  const NonlinearModel m = decay_model(true);
  const VectorXd l = m.predict((VectorXd(2) << 5.0, 0.7).finished());
  const MatrixXd S = MatrixXd::Identity(13, 13);
  const VectorXd x0 = (VectorXd(2) << 1.0, 1.0).finished();
  EXPECT_THROW(solve_nonlinear(m, l, MatrixXd::Identity(12, 12), x0), InputError);
  EXPECT_THROW(solve_nonlinear(m, l.head(12), S, x0), InputError);
  EXPECT_THROW(solve_nonlinear(m, l, S, (VectorXd(2) << 1.0, std::nan("")).finished()),
               InputError);
  EXPECT_THROW(solve_nonlinear(NonlinearModel{}, l, S, x0), InputError);
  NonlinearOptions bad;
  bad.step_scale = VectorXd::Ones(3);
  EXPECT_THROW(solve_nonlinear(m, l, S, x0, bad), InputError);
  bad = {};
  bad.max_iterations = 0;
  EXPECT_THROW(solve_nonlinear(m, l, S, x0, bad), InputError);

  NonlinearModel wrong = m;
  wrong.predict = [](const VectorXd&) -> VectorXd { return VectorXd::Ones(5); };
  EXPECT_THAT(message_of<InputError>([&] { solve_nonlinear(wrong, l, S, x0); }),
              HasSubstr("model returned 5 predicted observations, expected 13"));
  wrong = m;
  wrong.jacobian = [](const VectorXd&) -> MatrixXd { return MatrixXd::Ones(13, 3); };
  EXPECT_THROW(solve_nonlinear(wrong, l, S, x0), InputError);

  NonlinearModel nan_model;
  nan_model.predict = [](const VectorXd& x) -> VectorXd {
    return VectorXd::Constant(13, std::log(x(0) - 2.0));  // NaN for x0 < 2
  };
  EXPECT_THAT(message_of<NumericalError>([&] { solve_nonlinear(nan_model, l, S, x0); }),
              HasSubstr("not finite at the starting point"));
  EXPECT_THROW(solve_nonlinear(m, l, S, x0, [] {
                 NonlinearOptions o;
                 o.levenberg_marquardt = false;
                 o.max_iterations = 3;
                 return o;
               }()),
               NumericalError);
}

}  // namespace
