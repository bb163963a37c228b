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
///
/// Indices (parameters, observations) are 0-based everywhere, including in
/// error messages.

#include <Eigen/Dense>

namespace meridian::adjust {

/// Result of a least-squares adjustment. Units follow the columns of A
/// (parameters) and the rows of l (observations).
struct LeastSquaresResult {
  Eigen::VectorXd x;                  ///< estimated parameters x̂
  Eigen::MatrixXd cofactor;           ///< Q_xx = (Aᵀ Σ_ll⁻¹ A)⁻¹: a-priori covariance of x̂
  Eigen::MatrixXd covariance_aposteriori;  ///< σ̂0²·Q_xx (equals cofactor when dof = 0)
  Eigen::VectorXd residuals;          ///< v = A·x̂ − l
  /// r_i = (Q_vv·Σ_ll⁻¹)_ii with Q_vv = Σ_ll − A·Q_xx·Aᵀ; sum = dof. For independent
  /// observations r_i = 1 − h_ii ∈ [0, 1]; with correlations single values may leave [0, 1].
  Eigen::VectorXd redundancy;
  /// (Q_vv)_ii = Σ_ii − (A·Q_xx·Aᵀ)_ii: a-priori variance of the residual v_i (units of l_i
  /// squared), ≥ 0 up to rounding; σ_vi = sqrt((Q_vv)_ii).
  Eigen::VectorXd qvv_diagonal;
  /// w_i = v_i / sqrt((Q_vv)_ii) with the a-priori σ0 = 1 (dimensionless, ~N(0,1) under the
  /// model); NaN where (Q_vv)_ii ≤ 1e-12·Σ_ii, i.e. the observation is not controlled.
  Eigen::VectorXd standardized_residuals;
  /// Baarda's w-test statistic for an outlier in observation i alone (Baarda 1968;
  /// Teunissen, Testing theory, 2006): w_i = (P·v)_i / sqrt((P·Q_vv·P)_ii), P = Σ_ll⁻¹,
  /// dimensionless, ~N(0,1) under the model, same sign as v_i. Equals standardized_residuals
  /// (exactly) for a diagonal Σ_ll; with correlated observations v_i/σ_vi is not the w-test
  /// statistic and this is the one to test. NaN where (P·Q_vv·P)_ii ≤ 1e-12·(Σ_ll⁻¹)_ii, i.e.
  /// an outlier in observation i cannot be told from a change of the parameters.
  /// See adjust/statistics.hpp for the tests.
  Eigen::VectorXd w_statistics;
  double vtpv = 0.0;                  ///< vᵀ Σ_ll⁻¹ v
  int dof = 0;                        ///< degrees of freedom n − u
  double sigma0 = 0.0;                ///< a-posteriori σ̂0 = sqrt(vᵀPv / dof); NaN when dof = 0

  /// A-priori standard deviation of parameter i: sqrt(Q_xx(i,i)).
  /// Throws InputError when i is out of range.
  double sigma_apriori(int i) const;
  /// A-posteriori standard deviation of parameter i: σ̂0·sqrt(Q_xx(i,i)); NaN when dof = 0.
  /// Throws InputError when i is out of range.
  double sigma_aposteriori(int i) const;
};

/// Tuning of the linear solver; the defaults suit almost every problem.
struct LinearOptions {
  /// Rank test. Each column of the whitened design matrix L⁻¹·A (Σ_ll = L·Lᵀ) is first
  /// scaled to unit length, so the parameters' units do not matter; a parameter counts as
  /// undetermined when the part of its column that the other columns cannot explain
  /// (|R_kk| of a column-pivoted QR, the sine of the angle to their span) is below this value.
  /// ≤ 0 selects the automatic value 100·max(n, u)·ε (ε = 2.2e-16).
  double rank_tolerance = 0.0;
};

/// Cholesky factor Σ_ll = L·Lᵀ of an observation covariance, used to whiten
/// observations: L⁻¹·l has unit covariance. Diagonal covariances are stored as
/// the vector of standard deviations (no n×n storage).
class CovarianceFactor {
 public:
  /// Factor a full covariance (n×n, symmetric within 1e-10 of sqrt(Σ_ii·Σ_jj)).
  /// An exactly diagonal matrix takes the diagonal path.
  /// Throws InputError on a non-square, empty, non-finite or asymmetric matrix and
  /// NumericalError when Σ_ll is not (numerically) positive definite.
  explicit CovarianceFactor(const Eigen::MatrixXd& sigma_ll);
  /// Independent observations with standard deviations `sigma` (each finite and > 0,
  /// else InputError).
  static CovarianceFactor diagonal(const Eigen::VectorXd& sigma);

  int size() const { return static_cast<int>(variances_.size()); }
  bool is_diagonal() const { return lower_.size() == 0; }
  /// Σ_ii.
  const Eigen::VectorXd& variances() const { return variances_; }
  /// ln det Σ_ll = 2·Σ_i ln L_ii (for likelihoods; finite, as Σ_ll is positive definite).
  double log_determinant() const;

  /// m ← L⁻¹·m (m has size() rows).
  void whiten(Eigen::Ref<Eigen::MatrixXd> m) const;
  /// m ← L⁻ᵀ·m.
  void whiten_transposed(Eigen::Ref<Eigen::MatrixXd> m) const;
  /// m ← L·m (undo whiten).
  void colour(Eigen::Ref<Eigen::MatrixXd> m) const;

 private:
  CovarianceFactor() = default;
  Eigen::VectorXd variances_;
  Eigen::VectorXd sigma_;  // diagonal case: sqrt(Σ_ii)
  Eigen::MatrixXd lower_;  // full case: L (lower triangle); empty when diagonal
};

/// Solve l + v = A·x with observation covariance Σ_ll (n×n, symmetric positive
/// definite). Requires n ≥ u = A.cols() ≥ 1.
/// Throws InputError on mismatched sizes or non-finite input, NumericalError
/// when Σ_ll is not positive definite or A is rank deficient (singular normal
/// matrix; the message names the parameter column that is dependent, e.g.
/// "normal matrix is singular: parameter 2 is not determined by the observations …").
/// The rank test is scale-free (see LinearOptions), so columns in very different units
/// are fine.
LeastSquaresResult solve_linear(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                const Eigen::MatrixXd& sigma_ll);

/// As above with independent observations of standard deviations `sigma`
/// (each > 0 and finite, else InputError).
LeastSquaresResult solve_linear_diagonal(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                         const Eigen::VectorXd& sigma);

/// As above with an already factored covariance (to factor Σ_ll once for many
/// right-hand sides or iterations) and solver options.
LeastSquaresResult solve_linear(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                const CovarianceFactor& sigma_ll,
                                const LinearOptions& options = {});

}  // namespace meridian::adjust
