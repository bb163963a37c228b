#pragma once
/// \file reversal.hpp
/// Reversal-point (turning-point) estimators of the centre of a slowly
/// decaying oscillation (gyro-theodolite spec §3). Used for tracking-mode
/// circle readings (radians) and for motor-off zero-position scale readings
/// (divisions): the estimators are unit-agnostic, the caller states the unit.
///
/// Model (R1): r_i = M + (−1)^i·A·e^{−iκ}, i = 1…n, κ = decay per half
/// period. Linearised (R2): r_i = M + (−1)^i·A′ + (−1)^{i+1}·(2i − 1)·c.

#include <optional>
#include <span>
#include <string>
#include <vector>

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

/// Result of one estimator. All values in the unit of the readings.
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
  bool sigma_is_aposteriori = false;    ///< centre.sigma from σ̂0 (true) or the a-priori σ (false)
  std::vector<double> residuals;        ///< v = fitted − observed, one per reading used
  std::vector<double> partial_means;    ///< successive Schuler means (Schuler, n > 3)
  std::vector<std::string> notes;
};

/// Check that `readings` can be a reversal sequence: n ≥ min_count, all
/// finite, successive differences non-zero and alternating in sign.
/// Throws InputError naming the offending reading ("reading 4 (…) does not
/// alternate…").
void check_reversal_sequence(std::span<const double> readings, int min_count);

/// Estimate the centre. `sigma_reading` is the a-priori σ of one reading in
/// the readings' unit (NaN if unknown). The σ of M is a-priori
/// (sigma_reading·sqrt(q_MM)) when sigma_reading is known and the fit has no
/// redundancy, otherwise a-posteriori (σ̂0·sqrt(q_MM)) where dof > 0. For
/// the Schuler mean with n > 3, σ̂0 comes from the linearised fit (R2).
/// Minimum readings: 2 (TwoPoint), 3 (Schuler, LinearLsq, NonlinearLsq).
ReversalResult estimate_centre(ReversalMethod method, std::span<const double> readings,
                               double sigma_reading);

/// Circle readings near 0°/360° (e.g. 359°41′, 0°44′) made continuous:
/// each reading is moved by a multiple of 2π to lie within π of the first.
std::vector<double> unwrap_circle_readings(std::span<const double> readings_rad);

}  // namespace meridian::gyro
