#pragma once
/// \file nonlinear.hpp
/// Non-linear least squares l + v = f(x) with a full observation covariance,
/// by Gauss–Newton with Levenberg–Marquardt damping. The statistics of the
/// final iterate (cofactor matrix, residuals, redundancy, standardised
/// residuals, σ̂0) are those of the linearised problem at the solution.

#include <functional>

#include <Eigen/Dense>

#include "meridian/adjust/least_squares.hpp"

namespace meridian::adjust {

/// The model: predicted observations f(x) and, optionally, the Jacobian
/// ∂f/∂x (n×u). Without a Jacobian, central differences are used with a step
/// relative to |x_j| (see NonlinearOptions::difference_step).
struct NonlinearModel {
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> predict;
  std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> jacobian;  ///< may be empty
};

struct NonlinearOptions {
  int max_iterations = 100;
  /// Converged when every |Δx_j| ≤ step_tolerance·(|x_j| + step_scale_j),
  /// step_scale_j = 1 unless given in `step_scale`.
  double step_tolerance = 1e-12;
  Eigen::VectorXd step_scale;        ///< optional, size u
  bool levenberg_marquardt = true;   ///< false: plain Gauss–Newton steps
  double initial_damping = 1e-3;     ///< LM λ relative to diag(N)
  double difference_step = 1e-7;     ///< relative step for numerical Jacobians
};

struct NonlinearResult : LeastSquaresResult {
  int iterations = 0;
  bool converged = false;  ///< always true when returned (non-convergence throws)
};

/// Solve from the starting point x0. Throws NumericalError when the
/// iteration does not converge within max_iterations (the message gives the
/// last step and vᵀPv), when the normal matrix is singular, or when f returns
/// non-finite values at the start; InputError on size mismatch.
NonlinearResult solve_nonlinear(const NonlinearModel& model, const Eigen::VectorXd& l,
                                const Eigen::MatrixXd& sigma_ll, const Eigen::VectorXd& x0,
                                const NonlinearOptions& options = {});

}  // namespace meridian::adjust
