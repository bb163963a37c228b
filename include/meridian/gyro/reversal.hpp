#pragma once
/// \file reversal.hpp
/// Reversal-point (turning-point) estimators of the centre of a slowly
/// decaying oscillation (gyro-theodolite spec §3). Used for tracking-mode
/// circle readings (radians) and for motor-off zero-position scale readings
/// (divisions): the estimators are unit-agnostic, the caller states the unit.
///
/// Model (R1): r_i = M + (−1)^i·A·e^{−iκ}, i = 1…n, κ = decay per half
/// period. Linearised (R2): r_i = M + (−1)^i·A′ + (−1)^{i+1}·(2i − 1)·c.

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meridian/adjust/statistics.hpp"
#include "meridian/gyro/instrument.hpp"

namespace meridian::gyro {

enum class ReversalMethod {
  TwoPoint,      ///< M = (r1 + r2)/2 (no damping; later readings unused)
  Schuler,       ///< M = (r1 + 2r2 + r3)/4; for n > 3 the mean of the n−2 Schuler means
  LinearLsq,     ///< equal-weight least squares of (R2) in (M, A′, c)
  NonlinearLsq,  ///< Gauss–Newton/LM of (R1) in (M, A, κ), started from LinearLsq
};

/// "two-point", "schuler", "lsq-linear", "lsq".
std::string to_string(ReversalMethod m);
/// Inverse of to_string; throws InputError listing the accepted names.
ReversalMethod reversal_method_from_string(const std::string& name);

/// Significance level of the global test of σ̂0 against a stated reading σ.
inline constexpr double kReadingSigmaTestAlpha = 0.01;

/// Result of one estimator. All values in the unit of the readings.
///
/// Which σ the centre carries (estimate_centre):
/// * reading σ stated, dof > 0: the a-priori σ_r·sqrt(q_MM), unless the global
///   test of σ̂0 against σ_r rejects (then the larger a-posteriori
///   σ̂0·sqrt(q_MM), sigma_is_aposteriori = true);
/// * no reading σ stated, dof > 0: the a-posteriori σ̂0·sqrt(q_MM);
/// * dof = 0: σ_r·sqrt(q_MM) when stated, else NaN.
struct ReversalResult {
  ReversalMethod method = ReversalMethod::Schuler;
  /// Centre M. sigma is NaN when it cannot be stated (no a-priori reading σ
  /// and no redundancy).
  Uncertain centre;
  std::optional<Uncertain> amplitude;   ///< A (R1) or A′ (R2)
  std::optional<Uncertain> damping;     ///< κ per half period (R1) or c (R2)
  double cofactor_centre = 0.0;         ///< q_MM: σ_M = σ·sqrt(q_MM) for reading σ
  int dof = 0;                          ///< redundancy n − u of the fit (0 for closed forms)
  double sigma0 = 0.0;                  ///< a-posteriori σ of one reading (NaN when dof = 0)
  /// The stated a-priori σ of one reading (> 0), NaN when none was stated.
  double sigma_reading = std::numeric_limits<double>::quiet_NaN();
  bool sigma_is_aposteriori = false;    ///< centre.sigma from σ̂0 (true) or the a-priori σ (false)
  /// centre (and amplitude, damping, residuals) from the generalised least squares under a
  /// stochastic model of correlated readings (campaign option stochastic_model,
  /// stochastic_determination.hpp), σ = sqrt(D_Ŷ(0,0)); cofactor_centre, dof, sigma0 and
  /// reading_sigma_test then remain those of the white-noise fit (the check of the booked σ).
  bool sigma_from_gls = false;
  /// Global test of σ̂0 against the stated reading σ: T = dof·σ̂0²/σ_r² against
  /// χ²_{1−α}(dof), α = kReadingSigmaTestAlpha (adjust::global_test). Present
  /// when a reading σ is stated and dof > 0. `rejected`: the readings scatter
  /// more than stated, and centre.sigma is the a-posteriori σ.
  std::optional<adjust::GlobalTestResult> reading_sigma_test;
  std::vector<double> residuals;        ///< v = fitted − observed, one per reading used
  /// Successive Schuler means (r_i + 2r_{i+1} + r_{i+2})/4, i = 1 … n−2, for
  /// every method but TwoPoint: a hand check of the readings whatever the
  /// estimator.
  std::vector<double> partial_means;
  /// max − min of partial_means (unit of the readings), when there are at
  /// least two (n ≥ 4); a reading booked wrong shows as a large spread.
  std::optional<double> partial_means_spread;
  std::vector<std::string> notes;
};

/// The warning for a rejected reading_sigma_test, e.g. "the reversal readings
/// scatter more than stated: sigma0 = 65.6" against the stated 5.0" (2 degrees
/// of freedom; global test T = 344.01 > 9.21 at alpha = 1 %); the larger,
/// a-posteriori sigma is used". σ are divided by `unit` (units::kArcsecond for
/// circle readings in radians, 1 for divisions), printed with `decimals`
/// decimals and followed by `unit_symbol` (e.g. "\"" or " div"). Empty when
/// there was no test or it passed.
std::string reading_sigma_warning(const ReversalResult& r, double unit,
                                  std::string_view unit_symbol, int decimals);

/// Check that `readings` can be a reversal sequence: n ≥ min_count, all
/// finite, successive differences non-zero and alternating in sign.
/// Throws InputError naming the offending reading (field "[3]", message "reading 4 does not
/// alternate…").
void check_reversal_sequence(std::span<const double> readings, int min_count);

/// Estimate the centre. `sigma_reading` is the a-priori σ of one reading in
/// the readings' unit (NaN or ≤ 0 if not stated). The σ of M follows the
/// policy of ReversalResult: a-priori (sigma_reading·sqrt(q_MM)) when stated
/// and not rejected by the global test, else a-posteriori (σ̂0·sqrt(q_MM))
/// where dof > 0. For the Schuler mean with n > 3, σ̂0 comes from the
/// linearised fit (R2) and q_MM = Σw² of its weights.
/// Minimum readings: 2 (TwoPoint), 3 (Schuler, LinearLsq, NonlinearLsq).
ReversalResult estimate_centre(ReversalMethod method, std::span<const double> readings,
                               double sigma_reading);

/// Circle readings near 0°/360° (e.g. 359°41′, 0°44′) made continuous:
/// each reading is moved by a multiple of 2π to lie within π of the first.
std::vector<double> unwrap_circle_readings(std::span<const double> readings_rad);

}  // namespace meridian::gyro
