#pragma once
/// \file markov_covariance.hpp
/// Covariance matrices of reversal-point readings whose errors follow a first- or second-order
/// Markov (autoregressive) process (gyro-stochastic spec §2, §3).
///
/// Markov-1: ε_i = Δ_i + ρ·ε_{i−1}, ε_0 = X_0. Unrolled ε = C·Δ + B·X_0 with C lower-triangular
/// Toeplitz, C_ij = ρ^{i−j} (i ≥ j), and B = (ρ, ρ², …, ρⁿ)ᵀ (n×1).
///
/// Markov-2: ε_i = Δ_i + ρ_1·ε_{i−1} + ρ_2·ε_{i−2}, ε_0 = X_1, ε_{−1} = X_2. C_ii = 1,
/// C_21 = ρ_1, C_ij = ρ_1·C_{i−1,j} + ρ_2·C_{i−2,j} (C_kj = 0 for k < j); B = (b_1 b_2) (n×2)
/// with b_{1,1} = ρ_1, b_{1,2} = ρ_1² + ρ_2, b_{1,i} = ρ_1·b_{1,i−1} + ρ_2·b_{1,i−2} and
/// b_{2,i} = ρ_2·C_{i,1}.
///
/// Both: D(L) = σ_1²·Q_1 + σ_2²·Q_2, Q_1 = C·Cᵀ (noise Δ, D(Δ_i) = σ_1²), Q_2 = B·Bᵀ (initial
/// states, D(X) = σ_2²). Dimensionless matrices; σ in the unit of the readings. Indices in the
/// formulas are 1-based (as in the spec); the matrices are 0-based.
///
/// Stationarity: |ρ| < 1 (Markov-1); the AR(2) triangle ρ_1 + ρ_2 < 1, ρ_2 − ρ_1 < 1,
/// |ρ_2| < 1 (Markov-2). Outside it the process is non-stationary and the builders throw.
///
/// Source: the spec; Box, Jenkins & Reinsel, Time series analysis, §3.2 (AR(2) stationarity).

#include <Eigen/Dense>

namespace meridian::gyro {

/// The factors of a Markov error model: ε = C·Δ + B·X.
struct MarkovFactors {
  Eigen::MatrixXd C;  ///< n×n, unit lower-triangular
  Eigen::MatrixXd B;  ///< n×1 (Markov-1) or n×2 (Markov-2)

  /// Q_1 = C·Cᵀ (n×n).
  Eigen::MatrixXd q1() const { return C * C.transpose(); }
  /// Q_2 = B·Bᵀ (n×n, rank ≤ 2).
  Eigen::MatrixXd q2() const { return B * B.transpose(); }
  /// D(L) = σ_1²·Q_1 + σ_2²·Q_2 (variances in the readings' unit squared, each ≥ 0 and
  /// finite, else InputError).
  Eigen::MatrixXd covariance(double sigma1_sq, double sigma2_sq) const;
};

/// True when (ρ_1, ρ_2) lies strictly inside the AR(2) stationarity triangle.
bool ar2_stationary(double rho1, double rho2);

/// Markov-1 factors for n ≥ 1 readings. Throws InputError when n < 1, ρ is not finite or
/// |ρ| ≥ 1 (non-stationary).
MarkovFactors markov1_factors(int n, double rho);

/// Markov-2 factors for n ≥ 1 readings. Throws InputError when n < 1, a ρ is not finite, or
/// (ρ_1, ρ_2) is outside the stationarity triangle (the message names the violated bound).
MarkovFactors markov2_factors(int n, double rho1, double rho2);

}  // namespace meridian::gyro
