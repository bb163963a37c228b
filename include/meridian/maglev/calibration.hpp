#pragma once
/// \file calibration.hpp
/// Multi-angle calibration of a maglev gyro (maglev-gyro spec §2): the
/// instrument is set up at several known azimuths α_j (radians) and both
/// positions measured. The exact model of a misaligned instrument is
///
///   Ī_1 = k_1·sin(α − α*) + I*,   Ī_2 = k_2·sin(α − α*) + I*      (issue 30)
///
/// — both positions' curves cross at the instrument constant α* (the spin
/// axis' misalignment with the set-up mark, the best set-up azimuth: −δ for an
/// axis δ east of the mark) at the constant deviation I*. The four parameters
/// (k_1, k_2, α*, I*) are adjusted jointly by non-linear least squares
/// (adjust::solve_nonlinear, Gauss–Newton from the linear solution below),
/// weights from the σ of the means; their covariance is the inverse normal
/// matrix scaled by the a-posteriori variance factor σ̂0² (dof 2n − 4), and the
/// global model test of that fit says whether the scatter agrees with the σ.
///
/// The straight lines of the small-angle approximation Ī_k = k_k·sin α + c_k
/// (the old model: α* biased by ~1 % of itself and K several σ low for a
/// misalignment of 0.5° and set-ups over ±10°) are still fitted: they give the
/// starting point, and their intersection is reported for comparison
/// (linear_best_azimuth_rad, linear_scale_A_s_per_rad).
///
/// * Trend deviation: k_1 + k_2 (ideally 0: slopes ±K·ω_e·cos φ); tested
///   against 0 (two-sided Student t, dof 2n − 4, at α); with a nominal K also
///   each slope against ±K·ω_e·cos φ, and K̂ against the nominal K for a unit
///   slip (a ratio beyond 10^±1.5: the currents are 10³ off, e.g. values in A
///   under an [mA] header) — a loud warning and unit_slip_suspected.
/// * K from the slopes: K̂ = (k_1 − k_2)/(2·ω_e·cos φ).
/// * Mean line: (Ī_1 + Ī_2)/2 = k_m·sin(α − α*) + c_m (α* from the fit, a-priori σ);
///   k_m tested against 0; a significant slope means the constant deviation is
///   not constant: a calibration defect (reported as such).
/// * position1, position2 are the exact curves per position: slope k_k, intercept
///   c_k = I* − k_k·sin α* (the curve at α = 0), residuals of the joint fit, and
///   the position's share of the model test (its vᵀPv over n − 2).
///
/// Units: α in radians, currents in A, slopes in A (per unit of sin α), K in A·s/rad.
/// The runner io::run_maglev_calibrate_file reads a table and calls calibrate();
/// the Result carries the table and latitude its writers show.
/// Errors: InputError for fewer than 3 set-ups, non-finite values, σ ≤ 0,
/// fewer than 2 distinct azimuths, both positions' means identical at every set-up
/// (one column given twice); NumericalError for parallel lines (k_1 = k_2: no
/// intersection), |sin α*| ≥ 1, or a fit that does not converge.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/uncertain.hpp"

namespace meridian::maglev {

struct CalibrationSetup {
  double azimuth_rad = 0.0;  ///< α_j, the known set-up azimuth of position 1's spin axis
  Uncertain mean1_A;         ///< Ī_1 with σ (> 0)
  Uncertain mean2_A;         ///< Ī_2 with σ (> 0)
};

struct CalibrationInput {
  std::string source;  ///< what the table is, for reports (its file); may be empty
  std::vector<CalibrationSetup> setups;
  double latitude_rad = 0.0;
  double alpha = 0.05;                              ///< significance level of the tests
  std::optional<double> nominal_scale_A_s_per_rad;  ///< K to compare the slopes with
};

struct LineFit {
  Uncertain slope_A_per_rad;
  Uncertain intercept_A;
  double covariance = 0.0;          ///< cov(slope, intercept), A²/rad
  std::vector<double> residuals_A;  ///< v = fit − observed, per set-up
  adjust::GlobalTestResult global_test;
};

struct CalibrationResult {
  // What was fitted (CalibrationInput), for the writers.
  std::string source;                      ///< CalibrationInput::source
  std::vector<CalibrationSetup> setups;    ///< the table, in its order (residuals follow it)
  double latitude_rad = 0.0;

  LineFit position1, position2, mean_line;
  Uncertain trend_deviation_A_per_rad;  ///< k_1 + k_2
  double trend_z = 0.0;
  bool trend_significant = false;
  Uncertain best_azimuth_rad;      ///< α*, the instrument constant (exact model)
  Uncertain constant_deviation_A;  ///< I* (exact model)
  Uncertain scale_A_s_per_rad;     ///< K̂ from the slopes (exact model)
  double mean_slope_z = 0.0;
  bool mean_line_constant = true;  ///< k_m not significant
  std::vector<std::string> notes, warnings;

  // The exact model's adjustment (issue 30).
  adjust::GlobalTestResult fit_test{};  ///< global test of the joint fit, dof 2n − 4
  int iterations{};                     ///< Gauss–Newton steps from the linear solution
  /// Covariance of (k_1, k_2, α*, I*) = σ̂0²·N⁻¹ (A, A, rad, A), row-major.
  std::array<std::array<double, 4>, 4> covariance{};
  Uncertain linear_best_azimuth_rad{};   ///< α* of the straight lines (k·sin α + c), for comparison
  Uncertain linear_scale_A_s_per_rad{};  ///< K of the straight lines, for comparison
  std::optional<double> scale_ratio_to_nominal{};  ///< K̂ / nominal K, when a nominal K is given
  bool unit_slip_suspected{};  ///< K̂ 10^±1.5 or more off the nominal K (see the file comment)
};

/// Fit and analyse (see the file comment).
CalibrationResult calibrate(const CalibrationInput& in);

}  // namespace meridian::maglev
