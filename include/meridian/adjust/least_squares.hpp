#pragma once
/// \file least_squares.hpp
/// Linear least squares (Gauss–Markov model) with a full observation
/// covariance, solved by Cholesky whitening and a QR factorisation — never
/// by an explicit inverse of the observation covariance.
///
/// Model: l + v = A·x, D(l) = Σ_ll = σ0²·Q_ll with the a-priori σ0 = 1, i.e.
/// Σ_ll is given in the observations' own units squared.
/// Sign convention of residuals: v = A·x̂ − l (corrections to the
/// observations, as in GNU Gama and most geodetic texts).

#include <Eigen/Dense>

namespace meridian::adjust {

/// Result of a least-squares adjustment. Units follow the columns of A
/// (parameters) and the rows of l (observations).
struct LeastSquaresResult {
  Eigen::VectorXd x;                  ///< estimated parameters x̂
  Eigen::MatrixXd cofactor;           ///< Q_xx = (Aᵀ Σ_ll⁻¹ A)⁻¹: a-priori covariance of x̂
  Eigen::MatrixXd covariance_aposteriori;  ///< σ̂0²·Q_xx (equals cofactor when dof = 0)
  Eigen::VectorXd residuals;          ///< v = A·x̂ − l
  Eigen::VectorXd redundancy;         ///< r_i = (Q_vv·Σ_ll⁻¹)_ii, sum = dof
  Eigen::VectorXd standardized_residuals;  ///< w_i = v_i / sqrt((Q_vv)_ii), a-priori σ0 = 1; NaN where (Q_vv)_ii ≈ 0
  double vtpv = 0.0;                  ///< vᵀ Σ_ll⁻¹ v
  int dof = 0;                        ///< degrees of freedom n − u
  double sigma0 = 0.0;                ///< a-posteriori σ̂0 = sqrt(vᵀPv / dof); NaN when dof = 0

  /// A-priori standard deviation of parameter i: sqrt(Q_xx(i,i)).
  double sigma_apriori(int i) const;
  /// A-posteriori standard deviation of parameter i: σ̂0·sqrt(Q_xx(i,i)); NaN when dof = 0.
  double sigma_aposteriori(int i) const;
};

/// Solve l + v = A·x with observation covariance Σ_ll (n×n, symmetric positive
/// definite). Requires n ≥ u = A.cols() ≥ 1.
/// Throws InputError on mismatched sizes or non-finite input, NumericalError
/// when Σ_ll is not positive definite or A is rank deficient (singular normal
/// matrix; the message names the parameter column that is dependent).
LeastSquaresResult solve_linear(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                const Eigen::MatrixXd& sigma_ll);

/// As above with independent observations of standard deviations `sigma`
/// (each > 0).
LeastSquaresResult solve_linear_diagonal(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                         const Eigen::VectorXd& sigma);

}  // namespace meridian::adjust
