#pragma once
/// \file data_snooping.hpp
/// Iterated data snooping (Baarda 1968) with the variance factor estimated from the other
/// observations: locate outlying observations one at a time, each removed by the mean-shift
/// model before the next test.
///
/// Test of observation i (outlier in i alone) in the adjustment l + v = A·x, Σ_ll = σ0²·Q:
/// Baarda's w_i = (P·v)_i / sqrt((P·Q_vv·P)_ii), P = Q⁻¹ (LeastSquaresResult::w_statistics, σ0 = 1).
/// When σ0 is not known (the booked σ may be optimistic, the readings correlated) the factor is
/// estimated without observation i: with Ω = vᵀPv and dof = n − u, the adjustment with
/// observation i replaced by an extra unknown (mean-shift model, equivalent to deleting it for
/// independent observations) has Ω_(i) = Ω − w_i² (Teunissen, Testing theory, 2006, §4), so
///     σ̂_(i)² = (Ω − w_i²)/(dof − 1),   t_i = w_i / σ̂_(i) ~ t(dof − 1) under H0,
/// the externally studentised residual (Pope's τ-test with the tested observation left out;
/// Koch, Parameter estimation, §4.4). The largest |t_i| is rejected when it exceeds
/// t_{1−α0/2}(dof − 1); that observation gets its own unknown (a column e_i of A: its residual
/// becomes 0, the others are adjusted as without it), and the test is repeated.
///
/// Sources: Baarda (1968) A testing procedure for use in geodetic networks; Pope (1976) The
/// statistics of residuals and the detection of outliers; Teunissen (2006).

#include <vector>

#include <Eigen/Dense>

#include "meridian/adjust/least_squares.hpp"

namespace meridian::adjust {

/// One located outlier.
struct SnoopedOutlier {
  int index = -1;          ///< observation (0-based row of A and l)
  double w = 0.0;          ///< Baarda's w at σ0 = 1 (dimensionless, signed as v_i)
  double t = 0.0;          ///< t_i = w_i/σ̂_(i) (dimensionless, signed as v_i)
  double critical = 0.0;   ///< t_{1−α0/2}(dof − 1) of that pass
  int dof = 0;             ///< dof of that pass (before the observation got its unknown)
  /// Estimated error of the observation: the mean-shift unknown ∇̂_i (units of l; l_i − ∇̂_i
  /// is consistent with the others). Positive when l_i is too large.
  double error = 0.0;
  double sigma_error = 0.0;  ///< its σ, a-posteriori (σ̂0 of the final adjustment)
};

struct SnoopingOptions {
  double alpha0 = 1e-3;  ///< two-sided significance per observation, 0 < α0 < 1
  int max_outliers = 3;  ///< ≥ 0; also stopped when dof would fall below 2
};

struct SnoopingResult {
  std::vector<SnoopedOutlier> outliers;  ///< in the order located
  /// The adjustment with every located outlier given its own unknown (the first A.cols()
  /// entries of x are the original parameters; then one ∇ per outlier, in the order located).
  /// Without outliers it is the plain adjustment.
  LeastSquaresResult final_fit;
  /// The largest |t| of the last pass (not rejected) and its observation (−1: none tested).
  double last_largest_t = 0.0;
  int last_largest_index = -1;
};

/// Iterated data snooping as above. A, l, Q as for solve_linear (Q the cofactor of the
/// observations: the test does not use its scale). Observations whose w is not defined (not
/// controlled) are not tested. Throws InputError as solve_linear, or unless 0 < α0 < 1 and
/// max_outliers ≥ 0; NumericalError as solve_linear.
SnoopingResult iterated_data_snooping(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                      const CovarianceFactor& Q, const SnoopingOptions& options = {});

}  // namespace meridian::adjust
