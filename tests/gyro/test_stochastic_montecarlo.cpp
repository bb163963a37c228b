// Monte Carlo validation of the stochastic models (gyro-stochastic spec §6): series simulated
// with known Markov-1 errors, many replications. Label `montecarlo`.
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/adjust/variance_components.hpp"
#include "meridian/core/error.hpp"
#include "meridian/gyro/markov_covariance.hpp"
#include "meridian/gyro/stochastic.hpp"

namespace {

using Eigen::VectorXd;
using namespace meridian::gyro;

// ε_i = Δ_i + ρ·ε_{i−1}, ε_0 = X_0, run as a recursion (not through C and B).
std::vector<double> series(int n, double rho, double s1, double s2, std::mt19937_64& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  double e = s2 * N(rng);
  const VectorXd y = reversal_design(n) * Eigen::Vector3d(754.0, 4800.0, 3.0);
  std::vector<double> r(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    e = s1 * N(rng) + rho * e;
    r[static_cast<std::size_t>(i)] = y(i) + e;
  }
  return r;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double sd(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

TEST(StochasticMonteCarlo, MlRhoAndReportedSigmaOfNorth) {
  const int n = 30, runs = 300;
  const double rho = 0.6, s1 = 2.0, s2 = 5.0;
  std::mt19937_64 rng(2026);
  const Eigen::MatrixXd D_true = markov1_factors(n, rho).covariance(s1 * s1, s2 * s2);
  // m_gls, var_gls: the ML fits a user would use (not marked degenerate); the others over all
  // runs.
  std::vector<double> rho_hat, rho_sd, m_gls, m_ols, sd_gls, var_gls, m_true, sd_true;
  int degenerate = 0;
  for (int k = 0; k < runs; ++k) {
    StochasticInput in;
    in.kind = SeriesKind::Scale;  // fitted as given
    in.readings = series(n, rho, s1, s2, rng);
    in.options.covariance_functions = false;
    in.options.markov2 = false;
    const auto res = analyse_stochastic(in);
    const ModelFit& ml = res.fit(StochasticModel::Markov1Ml);
    rho_hat.push_back(ml.rho[0]);
    if (std::isfinite(ml.rho_sigma[0])) rho_sd.push_back(ml.rho_sigma[0]);
    if (ml.degenerate) {
      ++degenerate;
    } else {
      m_gls.push_back(ml.north.value);
      sd_gls.push_back(ml.north.sigma);
      var_gls.push_back(ml.north.sigma * ml.north.sigma);
    }
    m_ols.push_back(res.fit(StochasticModel::WhiteNoise).north.value);
    const GlsFit t = reversal_gls(in.readings, D_true);
    m_true.push_back(t.y(0));
    sd_true.push_back(std::sqrt(t.covariance(0, 0)));
  }
  const double bias = mean(rho_hat) - rho;
  std::printf("ML rho: mean %.4f (bias %.4f), scatter %.4f, mean reported sigma %.4f\n",
              mean(rho_hat), bias, sd(rho_hat), mean(rho_sd));
  const double rms_gls = std::sqrt(mean(var_gls));
  std::printf(
      "north: GLS (ML rho, %zu non-degenerate of %d) scatter %.4f, rms reported m %.4f "
      "(ratio %.3f; mean reported m %.4f); GLS (true D) scatter %.4f, reported m %.4f; OLS "
      "scatter %.4f\n",
      m_gls.size(), runs, sd(m_gls), rms_gls, rms_gls / sd(m_gls), mean(sd_gls), sd(m_true),
      mean(sd_true), sd(m_ols));
  // Unbiased to within its standard error: the bias is below the σ of one estimate.
  EXPECT_LT(std::fabs(bias), mean(rho_sd));
  // The GLS with the Markov-1 covariance: its reported m_αN matches the empirical scatter
  // within 10 % and it scatters less than OLS.
  EXPECT_NEAR(mean(sd_true) / sd(m_true), 1.0, 0.10);
  // GLS is the best linear estimator: its σ is below the true σ of OLS under D (sandwich).
  const Eigen::MatrixXd G = reversal_design(n);
  const Eigen::Matrix3d Ni = (G.transpose() * G).inverse();
  const double sd_ols_true = std::sqrt((Ni * G.transpose() * D_true * G * Ni)(0, 0));
  std::printf("true sigma of the OLS north under D: %.4f\n", sd_ols_true);
  EXPECT_LE(mean(sd_true), sd_ols_true);
  // With ρ and the components estimated from the same 30 readings (EGLS, plug-in σ): the spec's
  // criterion, reported m_αN within 10 % of the empirical scatter, as the rms of the reported
  // σ (the σ a user would read, i.e. of the fits not marked degenerate) against the scatter of
  // those estimates. With 300 runs the scatter itself is uncertain by about 4 %.
  EXPECT_LE(degenerate, runs / 20);
  EXPECT_NEAR(rms_gls / sd(m_gls), 1.0, 0.10);
}

// The C-type models' m of M against the empirical scatter (user trial, finding 7: with the
// amplitude ĉ = Σvv/n their σ were √((n−3)/n) too small, 0.65 for n = 7). White-noise
// readings: the true covariance is σ²·I, so the rms reported m must not fall short of the
// empirical scatter of M̂ (a function fitted with some correlation is allowed to be
// conservative). 200 runs: the sd of the ratio is ~5 %.
TEST(StochasticMonteCarlo, CovarianceFunctionSigmaOfNorth) {
  for (const int n : {7, 20}) {
    const int runs = 200;
    std::mt19937_64 rng(77 + n);
    std::vector<std::vector<double>> m_hat(4), m_rep2(4);
    const StochasticModel models[4] = {StochasticModel::WhiteNoise, StochasticModel::Exponential,
                                       StochasticModel::Gaussian, StochasticModel::DampedCosine};
    for (int k = 0; k < runs; ++k) {
      StochasticInput in;
      in.kind = SeriesKind::Scale;  // fitted as given
      in.readings = series(n, 0.0, 5.0, 0.0, rng);
      in.options.markov2 = false;
      const auto res = analyse_stochastic(in);
      for (int j = 0; j < 4; ++j) {
        // The damped cosine needs n ≥ 10 (5 lags) and is left out below.
        if (models[j] == StochasticModel::DampedCosine && n < 10) {
          EXPECT_THROW(res.fit(models[j]), meridian::InputError);
          continue;
        }
        const auto& f = res.fit(models[j]);
        m_hat[static_cast<std::size_t>(j)].push_back(f.north.value);
        m_rep2[static_cast<std::size_t>(j)].push_back(f.north.sigma * f.north.sigma);
      }
    }
    for (int j = 0; j < 4; ++j) {
      if (m_hat[static_cast<std::size_t>(j)].empty()) continue;
      const double emp = sd(m_hat[static_cast<std::size_t>(j)]);
      const double rep = std::sqrt(mean(m_rep2[static_cast<std::size_t>(j)]));
      std::printf("n = %d %s: empirical sd of M %.3f, rms reported m %.3f, ratio %.3f\n", n,
                  to_string(models[j]).c_str(), emp, rep, rep / emp);
      EXPECT_GT(rep / emp, 0.85) << n << " " << to_string(models[j]);
      EXPECT_LT(rep / emp, 1.35) << n << " " << to_string(models[j]);
    }
  }
}

TEST(StochasticMonteCarlo, VceRecoversTheComponents) {
  const int n = 30, runs = 300;
  const double rho = 0.6, s1 = 2.0, s2 = 5.0;
  std::mt19937_64 rng(77);
  const MarkovFactors f = markov1_factors(n, rho);
  const std::vector<meridian::adjust::VarianceComponent> comps{{"sigma1^2", f.C},
                                                               {"sigma2^2", f.B}};
  int within1 = 0, within2 = 0, both = 0, both2 = 0, within1_2 = 0, within2_2 = 0;
  for (int k = 0; k < runs; ++k) {
    const auto r = series(n, rho, s1, s2, rng);
    const VectorXd l = Eigen::Map<const VectorXd>(r.data(), n);
    const auto v = meridian::adjust::estimate_variance_components(reversal_design(n), l, comps);
    const double h1 = std::sqrt(v.components(0)), h2 = std::sqrt(v.components(1));
    const double e1 = v.sigma(0) / (2.0 * h1);
    const double e2 =
        v.clipped[1] ? std::sqrt(std::sqrt(v.covariance(1, 1))) : v.sigma(1) / (2.0 * h2);
    const bool w1 = std::fabs(h1 - s1) <= e1;
    const bool w2 = std::isfinite(e2) && std::fabs(h2 - s2) <= e2;
    within1 += w1;
    within2 += w2;
    both += w1 && w2;
    within1_2 += std::fabs(h1 - s1) <= 2.0 * e1;
    within2_2 += std::isfinite(e2) && std::fabs(h2 - s2) <= 2.0 * e2;
    both2 +=
        (std::fabs(h1 - s1) <= 2.0 * e1) && std::isfinite(e2) && std::fabs(h2 - s2) <= 2.0 * e2;
  }
  std::printf(
      "VCE within 1 sigma: sigma1 %d, sigma2 %d, both %d; within 2 sigma: sigma1 %d, "
      "sigma2 %d, both %d; of %d\n",
      within1, within2, both, within1_2, within2_2, both2, runs);
  // A calibrated σ covers the truth in 68 % of runs at 1σ (binomial 3σ band for 300 runs:
  // 60 %–76 %), so the spec's "≥ 90 % within σ" is checked at 2σ (95 % expected) for σ1.
  // σ2 is NOT checked: one series holds a single realisation of the initial state X_0, so
  // σ2² is not consistently estimable from it and its normal-theory σ does not cover
  // (measured coverage printed above; docs/gyro-stochastic.md).
  EXPECT_GE(within1, 0.60 * runs);
  EXPECT_LE(within1, 0.76 * runs);
  EXPECT_GE(within1_2, 0.9 * runs);
}

}  // namespace
