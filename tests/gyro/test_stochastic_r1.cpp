// The GLS of the non-linear reversal-point model (R1), r_i = M + (−1)^i·A·e^{−iκ}
// (gyro::reversal_gls_nonlinear), against references computed in this file: an unweighted
// Gauss–Newton on the normal equations (Σ = σ²I) and a Gauss–Newton on the explicitly whitened
// system (Eigen LLT of Σ, dense Householder QR) for a general Σ; noise-free series recover the
// truth; bad input raises.
#include <cmath>
#include <limits>
#include <tuple>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/gyro/markov_covariance.hpp"
#include "meridian/gyro/stochastic.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using meridian::InputError;
using meridian::NumericalError;
using namespace meridian::gyro;
using ::testing::HasSubstr;

// (R1) and its Jacobian, written out again here (i = 1 … n, (−1)^i = +1 for even i).
VectorXd r1t_predict(const Eigen::Vector3d& y, Index n) {
  VectorXd f(n);
  for (Index k = 0; k < n; ++k) {
    const double i = static_cast<double>(k + 1);
    f(k) = y(0) + std::pow(-1.0, i) * y(1) * std::exp(-i * y(2));
  }
  return f;
}

MatrixXd r1t_jacobian(const Eigen::Vector3d& y, Index n) {
  MatrixXd J(n, 3);
  for (Index k = 0; k < n; ++k) {
    const double i = static_cast<double>(k + 1);
    const double s = std::pow(-1.0, i);
    J(k, 0) = 1.0;
    J(k, 1) = s * std::exp(-i * y(2));
    J(k, 2) = -s * i * y(1) * std::exp(-i * y(2));
  }
  return J;
}

struct R1Reference {
  Eigen::Vector3d y;
  Eigen::Matrix3d cov;
};

// Unweighted Gauss–Newton on the normal equations JᵀJ·δ = Jᵀ(l − f), D_Ŷ = σ²·(JᵀJ)⁻¹.
R1Reference r1t_unweighted_gauss_newton(const VectorXd& l, double sigma, Eigen::Vector3d y) {
  const Index n = l.size();
  for (int it = 0; it < 200; ++it) {
    const MatrixXd J = r1t_jacobian(y, n);
    const Eigen::Matrix3d N = J.transpose() * J;
    const Eigen::Vector3d d = N.ldlt().solve(J.transpose() * (l - r1t_predict(y, n)));
    y += d;
    if (d.cwiseAbs().maxCoeff() < 1e-15 * (1.0 + y.cwiseAbs().maxCoeff())) break;
  }
  const MatrixXd J = r1t_jacobian(y, n);
  const Eigen::Matrix3d N = J.transpose() * J;
  return {y, sigma * sigma * N.inverse()};
}

// Gauss–Newton on the explicitly whitened system: Σ = L·Lᵀ (Eigen LLT), L⁻¹J and L⁻¹(l − f) by
// triangular solves, the step by a dense Householder QR; D_Ŷ = (RᵀR)⁻¹ of the whitened Jacobian.
R1Reference r1t_whitened_gauss_newton(const VectorXd& l, const MatrixXd& Sigma, Eigen::Vector3d y) {
  const Index n = l.size();
  const Eigen::LLT<MatrixXd> llt(Sigma);
  EXPECT_EQ(llt.info(), Eigen::Success);
  const auto L = llt.matrixL();
  for (int it = 0; it < 200; ++it) {
    const MatrixXd Jw = L.solve(r1t_jacobian(y, n));
    const VectorXd rw = L.solve(VectorXd(l - r1t_predict(y, n)));
    const Eigen::Vector3d d = Jw.householderQr().solve(rw);
    y += d;
    if (d.cwiseAbs().maxCoeff() < 1e-15 * (1.0 + y.cwiseAbs().maxCoeff())) break;
  }
  const MatrixXd Jw = L.solve(r1t_jacobian(y, n));
  const Eigen::HouseholderQR<MatrixXd> qr(Jw);
  const Eigen::Matrix3d R = qr.matrixQR().topRows(3).triangularView<Eigen::Upper>();
  const Eigen::Matrix3d Rinv = R.inverse();
  return {y, Rinv * Rinv.transpose()};
}

std::vector<double> r1t_series(const Eigen::Vector3d& truth, int n, const MatrixXd& Sigma,
                               std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  VectorXd z(n);
  for (int i = 0; i < n; ++i) z(i) = N(rng);
  const VectorXd e = Sigma.llt().matrixL() * z;
  const VectorXd l = r1t_predict(truth, n) + e;
  return {l.data(), l.data() + n};
}

double r1t_rel(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(b), 1e-300); }

TEST(ReversalGlsR1, WhiteNoiseIsUnweightedNonlinearLeastSquares) {
  // Σ = σ²I: the GLS of (R1) is the unweighted non-linear least squares; its D_Ŷ = σ²(JᵀJ)⁻¹.
  for (const auto& [truth, n, sigma] :
       {std::tuple{Eigen::Vector3d(754.0, 4800.0, 0.02), 15, 5.0},
        std::tuple{Eigen::Vector3d(-31.0, -2600.0, 0.05), 9, 3.0},
        std::tuple{Eigen::Vector3d(0.35, 11.5, 0.04), 12, 0.05}}) {
    const MatrixXd Sigma = sigma * sigma * MatrixXd::Identity(n, n);
    const auto r = r1t_series(truth, n, Sigma, 7 + static_cast<std::uint64_t>(n));
    const R1GlsFit g = reversal_gls_nonlinear(r, Sigma);
    // The reference starts at the truth, not at the (R2) start the code uses.
    const R1Reference ref =
        r1t_unweighted_gauss_newton(Eigen::Map<const VectorXd>(r.data(), n), sigma, truth);
    SCOPED_TRACE(n);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(r1t_rel(g.y(k), ref.y(k)), 1e-9) << k;
      EXPECT_LT(r1t_rel(g.covariance(k, k), ref.cov(k, k)), 1e-9) << k;
    }
    EXPECT_DOUBLE_EQ(g.centre.value, g.y(0));
    EXPECT_DOUBLE_EQ(g.centre.sigma, std::sqrt(g.covariance(0, 0)));
    EXPECT_DOUBLE_EQ(g.decay.sigma, std::sqrt(g.covariance(2, 2)));
    EXPECT_TRUE(g.converged);
    EXPECT_GE(g.iterations, 1);
    // Residuals v = f(Ŷ) − l.
    const VectorXd l = Eigen::Map<const VectorXd>(r.data(), n);
    EXPECT_LT((g.residuals - (r1t_predict(ref.y, n) - l)).cwiseAbs().maxCoeff(), 1e-8 * sigma);
  }
}

TEST(ReversalGlsR1, GeneralCovarianceIsOlsOfTheWhitenedSystem) {
  const Eigen::Vector3d truth(754.0, 4800.0, 0.01);
  const int n = 20;
  const MatrixXd D2 = markov2_factors(n, 0.5, 0.3).covariance(4.0, 25.0);
  const MatrixXd D1 = markov1_factors(n, 0.7).covariance(9.0, 16.0);
  // A covariance that is none of the builders': exponential correlation plus a varying diagonal.
  MatrixXd D3(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) D3(i, j) = 6.0 * std::exp(-std::abs(i - j) / 2.5);
  for (int i = 0; i < n; ++i) D3(i, i) += 1.0 + 0.2 * i;
  std::uint64_t seed = 21;
  for (const MatrixXd* D : std::vector<const MatrixXd*>{&D1, &D2, &D3}) {
    const auto r = r1t_series(truth, n, *D, seed++);
    const R1GlsFit g = reversal_gls_nonlinear(r, *D);
    const R1Reference ref =
        r1t_whitened_gauss_newton(Eigen::Map<const VectorXd>(r.data(), n), *D, truth);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(r1t_rel(g.y(k), ref.y(k)), 1e-9) << k;
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(g.covariance(k, j), ref.cov(k, j),
                    1e-9 * std::sqrt(ref.cov(k, k) * ref.cov(j, j)))
            << k << "," << j;
    }
    // The weighting matters: the unweighted fit differs (else this test could not fail).
    const R1Reference ols = r1t_unweighted_gauss_newton(Eigen::Map<const VectorXd>(r.data(), n),
                                                        1.0, truth);
    EXPECT_GT(std::fabs(ols.y(0) - g.y(0)), 1e-6);
  }
}

TEST(ReversalGlsR1, NoiseFreeSeriesRecoverTheTruth) {
  const int n = 30;
  const MatrixXd D = markov1_factors(n, 0.6).covariance(4.0, 25.0);
  for (const Eigen::Vector3d& truth :
       {Eigen::Vector3d(754.0, 4800.0, 0.002), Eigen::Vector3d(754.0, -4800.0, 0.03),
        Eigen::Vector3d(-0.4, 12.0, 0.08), Eigen::Vector3d(100.0, 300.0, -0.01)}) {
    const VectorXd l = r1t_predict(truth, n);
    const std::vector<double> r(l.data(), l.data() + n);
    for (const MatrixXd& Sigma : {MatrixXd(MatrixXd::Identity(n, n)), D}) {
      const R1GlsFit g = reversal_gls_nonlinear(r, Sigma);
      EXPECT_NEAR(g.y(0), truth(0), 1e-9 * std::fabs(truth(1)));
      EXPECT_NEAR(g.y(1), truth(1), 1e-9 * std::fabs(truth(1)));
      EXPECT_NEAR(g.y(2), truth(2), 1e-9);
      EXPECT_LT(g.residuals.cwiseAbs().maxCoeff(), 1e-8 * std::fabs(truth(1)));
    }
  }
  // (R2) is biased on a long decaying series; (R1) is not: the GLS of (R1) is the better centre.
  const Eigen::Vector3d truth(754.0, 4800.0, 0.02);
  const VectorXd l = r1t_predict(truth, n);
  const std::vector<double> r(l.data(), l.data() + n);
  const GlsFit r2 = reversal_gls(r, D);
  const R1GlsFit r1 = reversal_gls_nonlinear(r, D);
  EXPECT_GT(std::fabs(r2.y(0) - truth(0)), 1.0);
  EXPECT_LT(std::fabs(r1.y(0) - truth(0)), 1e-9 * truth(1));
}

TEST(ReversalGlsR1, BadInputRaises) {
  const int n = 8;
  const Eigen::Vector3d truth(754.0, 4800.0, 0.02);
  const VectorXd l = r1t_predict(truth, n);
  std::vector<double> r(l.data(), l.data() + n);
  const MatrixXd I = MatrixXd::Identity(n, n);
  // Too few readings.
  EXPECT_THROW(reversal_gls_nonlinear({1.0, 9.0, 2.0}, MatrixXd::Identity(3, 3)), InputError);
  // Covariance of the wrong size.
  EXPECT_THROW(reversal_gls_nonlinear(r, MatrixXd::Identity(n - 1, n - 1)), InputError);
  // A reading not finite: named.
  auto bad = r;
  bad[2] = std::nan("");
  try {
    reversal_gls_nonlinear(bad, I);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "readings[2]");
    EXPECT_THAT(e.message(), HasSubstr("reading 3 is not finite"));
  }
  // Covariance not finite.
  MatrixXd Dnan = I;
  Dnan(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(reversal_gls_nonlinear(r, Dnan), InputError);
  // Covariance not positive definite.
  MatrixXd Dneg = I;
  Dneg(3, 3) = -1.0;
  EXPECT_THROW(reversal_gls_nonlinear(r, Dneg), NumericalError);
  // No oscillation: the amplitude is zero and κ is not determined.
  try {
    reversal_gls_nonlinear(std::vector<double>(n, 5.0), I);
    ADD_FAILURE() << "no error";
  } catch (const NumericalError& e) {
    EXPECT_THAT(e.message(), HasSubstr("(R1) GLS"));
  }
  // Not converged within one step from the (R2) start of a strongly decaying series.
  const VectorXd l2 = r1t_predict(Eigen::Vector3d(754.0, 4800.0, 0.3), n);
  R1GlsOptions one;
  one.max_iterations = 1;
  try {
    reversal_gls_nonlinear(std::vector<double>(l2.data(), l2.data() + n), I, one);
    ADD_FAILURE() << "no error";
  } catch (const NumericalError& e) {
    EXPECT_THAT(e.message(), HasSubstr("(R1) GLS"));
  }
  R1GlsOptions zero;
  zero.max_iterations = 0;
  EXPECT_THROW(reversal_gls_nonlinear(r, I, zero), InputError);
}

TEST(ReversalGlsR1, RoutesOfTheComparisonAgree) {
  // Whitening against normal equations for the (R2) fits: the (R1) fits under the models'
  // covariances agree to 1e-9 as well (spec §5).
  const int n = 20;
  const MatrixXd Dtrue = markov1_factors(n, 0.6).covariance(4.0, 25.0);
  const auto r = r1t_series(Eigen::Vector3d(754.0, 4800.0, 0.005), n, Dtrue, 11);
  StochasticInput a, b;
  a.kind = b.kind = SeriesKind::Scale;  // fitted as given
  a.readings = b.readings = r;
  b.options.route = GlsRoute::NormalEquations;
  const auto ra = analyse_stochastic(a);
  const auto rb = analyse_stochastic(b);
  ASSERT_EQ(ra.models.size(), rb.models.size());
  for (std::size_t i = 0; i < ra.models.size(); ++i) {
    SCOPED_TRACE(to_string(ra.models[i].model));
    ASSERT_EQ(ra.models[i].r1.has_value(), rb.models[i].r1.has_value());
    if (!ra.models[i].r1) continue;
    const auto& x = *ra.models[i].r1;
    const auto& y = *rb.models[i].r1;
    EXPECT_LT(r1t_rel(x.centre.value, y.centre.value), 1e-9);
    EXPECT_LT(r1t_rel(x.centre.sigma, y.centre.sigma), 1e-9);
    EXPECT_LT(r1t_rel(x.decay.value, y.decay.value), 1e-9);
  }
}

TEST(ReversalGlsR1, EveryModelOfTheComparisonCarriesItsR1Fit) {
  // Each model's (R1) fit is the GLS of (R1) with that model's covariance, rebuilt here from the
  // reported parameters.
  const int n = 20;
  const MatrixXd Dtrue = markov1_factors(n, 0.6).covariance(4.0, 25.0);
  const auto r = r1t_series(Eigen::Vector3d(754.0, 4800.0, 0.005), n, Dtrue, 5);
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given
  in.readings = r;
  const auto res = analyse_stochastic(in);
  int checked = 0;
  for (const auto& f : res.models) {
    SCOPED_TRACE(to_string(f.model));
    ASSERT_TRUE(f.r1.has_value());
    MatrixXd D;
    const double s1 = f.sigma1.value * f.sigma1.value, s2 = f.sigma2.value * f.sigma2.value;
    if (f.model == StochasticModel::WhiteNoise)
      D = s1 * MatrixXd::Identity(n, n);
    else if (f.model == StochasticModel::Markov1Grid || f.model == StochasticModel::Markov1Ml)
      D = markov1_factors(n, f.rho[0]).covariance(s1, s2);
    else if (f.model == StochasticModel::Markov2Grid || f.model == StochasticModel::Markov2Ml)
      D = markov2_factors(n, f.rho[0], f.rho[1]).covariance(s1, s2);
    else
      continue;
    const R1Reference ref =
        r1t_whitened_gauss_newton(Eigen::Map<const VectorXd>(r.data(), n), D, f.r1->start);
    EXPECT_LT(r1t_rel(f.r1->centre.value, ref.y(0)), 1e-9);
    EXPECT_LT(r1t_rel(f.r1->centre.sigma, std::sqrt(ref.cov(0, 0))), 1e-9);
    EXPECT_LT(r1t_rel(f.r1->decay.value, ref.y(2)), 1e-9);
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

}  // namespace
