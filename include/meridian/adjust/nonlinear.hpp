#pragma once
/// \file nonlinear.hpp
/// Non-linear least squares l + v = f(x) with a full observation covariance,
/// by Gauss–Newton with Levenberg–Marquardt damping on the whitened problem
/// L⁻¹(f(x) − l), Σ_ll = L·Lᵀ. The statistics of the final iterate (cofactor
/// matrix, residuals, redundancy, standardised residuals, σ̂0) are those of the
/// linearised problem l − f(x_k) + v = J(x_k)·Δx at the last iterate x_k; the
/// returned x = x_k + Δx includes that final (below-tolerance) correction, so
/// residuals equal f(x̂) − l to second order in Δx. Sign convention as in
/// least_squares.hpp: v = f(x̂) − l.

#include <functional>

#include <Eigen/Dense>

#include "meridian/adjust/least_squares.hpp"

namespace meridian::adjust {

/// The model: predicted observations f(x) (size n, units of l) and, optionally,
/// the Jacobian ∂f/∂x (n×u). Without a Jacobian, central differences are used
/// with the step h_j = difference_step·(|x_j| + step_scale_j) (step_scale_j = 1
/// unless given), i.e. relative to |x_j| for |x_j| ≫ step_scale_j.
struct NonlinearModel {
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> predict;
  std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> jacobian;  ///< may be empty
};

struct NonlinearOptions {
  /// Maximum number of steps taken (accepted LM steps or GN steps; rejected LM trials,
  /// which only raise the damping, do not count); ≥ 1.
  int max_iterations = 100;
  /// Converged when every |Δx_j| ≤ step_tolerance·(|x_j| + step_scale_j),
  /// step_scale_j = 1 unless given in `step_scale`, where Δx is the undamped
  /// Gauss–Newton step from the current iterate (so a step made small only by LM
  /// damping does not count). Also converged when a damped step that is itself
  /// below this tolerance fails to reduce vᵀPv: the minimum is then reached to
  /// rounding level even though the Gauss–Newton step is not yet that small.
  double step_tolerance = 1e-12;
  Eigen::VectorXd step_scale;        ///< optional, size u, each > 0; units of x
  bool levenberg_marquardt = true;   ///< false: plain (undamped, unchecked) Gauss–Newton steps
  double initial_damping = 1e-3;     ///< LM λ relative to diag(N) (Marquardt scaling), > 0
  double difference_step = 1e-7;     ///< relative step for numerical Jacobians, > 0
  /// Rank test of the Jacobian, as LinearOptions::rank_tolerance. ≤ 0: automatic,
  /// i.e. the linear default with an analytic Jacobian and max(that, 1000·ε/difference_step)
  /// (2.2e-6 by default) with a numerical one, whose columns carry relative errors ≈ ε/h
  /// that would otherwise hide an exact dependency.
  double rank_tolerance = 0.0;
};

struct NonlinearResult : LeastSquaresResult {
  int iterations = 0;      ///< steps taken (0 when x0 already satisfies the convergence test)
  bool converged = false;  ///< always true when returned (non-convergence throws)
};

/// Solve from the starting point x0 (size u, n ≥ u ≥ 1). Throws NumericalError
/// when the iteration does not converge within max_iterations (the message gives
/// the last step and vᵀPv), when the normal matrix is singular, when f returns
/// non-finite values at the start (or after a plain Gauss–Newton step), or when the
/// Jacobian is not finite; InputError on size mismatch (including a model returning
/// the wrong number of values), non-finite input or invalid options.
NonlinearResult solve_nonlinear(const NonlinearModel& model, const Eigen::VectorXd& l,
                                const Eigen::MatrixXd& sigma_ll, const Eigen::VectorXd& x0,
                                const NonlinearOptions& options = {});

}  // namespace meridian::adjust
