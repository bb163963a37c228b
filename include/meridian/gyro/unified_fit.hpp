#pragma once
/// \file unified_fit.hpp
/// Unified least-squares fit of the non-tracking oscillation model (N1)
/// a(t) = β + B·e^{−k(t−t0)}·sin(2π(t − t0)/T_B) to all crossing times and
/// reversal readings at once (gyro-theodolite spec §4.6).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "meridian/adjust/nonlinear.hpp"
#include "meridian/gyro/nontracking.hpp"

namespace meridian::gyro {

struct UnifiedFitOptions {
  bool estimate_damping = false;   ///< include k (1/s) as a parameter
  /// Use the given period_s as a (weighted) observation of T_B when present;
  /// otherwise T_B is free.
  bool use_known_period = true;
  /// Fill UnifiedFitResult::simple_methods (the comparison table); switch off
  /// for Monte Carlo loops that only need the fit.
  bool compare_simple_methods = true;
};

/// One observation of the fit with its residual.
struct UnifiedFitResidual {
  enum class Kind { CrossingTime, ReversalReading } kind = Kind::CrossingTime;
  /// Crossing time: index into crossings; reversal reading: 0.
  int group = 0;
  /// Crossing time: index into crossings[group].times_s; reversal reading:
  /// index into reversals_div.
  int index = 0;
  double observed = 0.0;    ///< s or div
  double residual = 0.0;    ///< v = fitted − observed (s or div)
  double standardized = 0.0;
  double redundancy = 0.0;
};

/// The period observation (when period_s entered the fit with σ > 0).
struct UnifiedFitPeriodResidual {
  double observed = 0.0;    ///< s
  double residual = 0.0;    ///< fitted − observed (s)
  double standardized = 0.0;
  double redundancy = 0.0;
};

struct UnifiedFitResult {
  Uncertain beta_div;
  Uncertain amplitude_div;     ///< B at t0
  Uncertain t0_s;
  Uncertain period_s;          ///< T_B
  Uncertain damping_per_s;     ///< k (0, σ 0 when not estimated)
  Eigen::MatrixXd covariance;  ///< a-priori covariance of (β, B, t0, T_B[, k])
  double sigma0 = 0.0;         ///< a-posteriori σ̂0 (NaN when dof = 0)
  int dof = 0;
  int iterations = 0;
  std::vector<UnifiedFitResidual> residuals;
  std::optional<UnifiedFitPeriodResidual> period_residual;
  /// E.g. σ̂0 failing the χ² test, a large standardised residual, a simple
  /// method that could not be computed for the comparison table.
  std::vector<std::string> warnings;
  std::vector<std::string> assumptions;   ///< e.g. "k = 0 (damping neglected)"
  /// Every applicable simple method on the same data, for the comparison table.
  std::vector<BetaResult> simple_methods;
  /// A BetaResult view of this fit (method = LeastSquares).
  BetaResult as_beta_result() const;
};

/// Whether fit_nontracking can run with these options: at least one
/// crossing time; β and B separable (two consecutive passages of two levels,
/// or of one level and a reversal reading, or two reversal readings); a
/// start value for T_B (period_s, three passages of one level,
/// or two timed reversals); σ_t > 0 (and σ_a > 0 with reversals); as many
/// observations as parameters; reversal times when damping is estimated
/// from reversal readings.
bool unified_fit_applicable(const NonTrackingObservations& obs,
                            const UnifiedFitOptions& options = {});

/// Parameters (β, B, t0, T_B[, k]). Observation equations: every crossing
/// time as a function of the parameters on a fixed phase branch (eastward
/// passage θ = asin((a−β)/B) + 2πm, westward θ = π − asin((a−β)/B) + 2πm,
/// t = t0 + T_B·θ/(2π); with damping the root of (N1) near that time, by
/// Newton), σ = σ_t; every reversal reading a_r = β ± B·e^{−k(t_r − t0)},
/// σ = σ_a (sides alternate; t_r from reversal_times_s, needed only with
/// damping); period_s as an observation of T_B when use_known_period and
/// σ > 0, T_B held fixed when σ = 0. Start values from the simple methods;
/// Levenberg–Marquardt (adjust::solve_nonlinear) with analytic Jacobian.
/// Reported σ and covariance are a priori (from the given σ); σ̂0 separately.
/// Throws InputError when there are fewer observations than parameters (or
/// as unified_fit_applicable says), and NumericalError when the fit does not
/// converge, is singular, or leaves a timed level out of reach.
UnifiedFitResult fit_nontracking(const NonTrackingObservations& obs, const Instrument& inst,
                                 const UnifiedFitOptions& options = {});

}  // namespace meridian::gyro
