#pragma once
/// \file calibration.hpp
/// Multi-angle calibration of a maglev gyro (maglev-gyro spec §2): the
/// instrument is set up at several known azimuths α_j (small, radians) and
/// both positions measured; straight lines are fitted (sin α ≈ α)
///
///   Ī_1 = k_1·α + c_1,   Ī_2 = k_2·α + c_2,   (Ī_1 + Ī_2)/2 = k_m·α + c_m
///
/// by weighted least squares (adjust::solve_linear_diagonal, weights from the
/// σ of the means; σ of the parameters a-priori, i.e. the means' σ are taken
/// as known, and the global model test says whether the scatter agrees).
///
/// * Trend deviation: k_1 + k_2 (ideally 0: slopes ±K·ω_e·cos φ); tested
///   against 0 (two-sided normal test at α); with a nominal K also each
///   slope against ±K·ω_e·cos φ.
/// * Intersection (best set-up azimuth α*, constant deviation I*):
///   sin α* = (c_2 − c_1)/(k_1 − k_2), I* = k_1·sin α* + c_1, σ by first-order
///   propagation (the two lines independent).
/// * K from the slopes: K̂ = (k_1 − k_2)/(2·ω_e·cos φ).
/// * Mean line: k_m tested against 0; a significant slope means the constant
///   deviation is not constant: a calibration defect (reported as such).
///
/// Units: α in radians, currents in A, slopes in A (per unit of sin α), K in A·s/rad.
/// The runner io::run_maglev_calibrate_file reads a table and calls calibrate();
/// the Result carries the table and latitude its writers show.
/// Errors: InputError for fewer than 3 set-ups, non-finite values, σ ≤ 0,
/// fewer than 2 distinct azimuths; NumericalError for parallel lines
/// (k_1 = k_2: no intersection) or |sin α*| ≥ 1.

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
  Uncertain best_azimuth_rad;      ///< α*
  Uncertain constant_deviation_A;  ///< I*
  Uncertain scale_A_s_per_rad;     ///< K̂ from the slopes
  double mean_slope_z = 0.0;
  bool mean_line_constant = true;  ///< k_m not significant
  std::vector<std::string> notes, warnings;
};

/// Fit and analyse (see the file comment).
CalibrationResult calibrate(const CalibrationInput& in);

}  // namespace meridian::maglev
