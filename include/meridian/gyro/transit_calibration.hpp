#pragma once
/// \file transit_calibration.hpp
/// Empirical transit factor c from two transit determinations at clamp
/// positions on either side of north (spec §4.1):
/// N = N′₁ + c·B₁·Δt₁ = N′₂ + c·B₂·Δt₂ ⇒ c = (N′₂ − N′₁)/(B₁·Δt₁ − B₂·Δt₂).

#include <string>
#include <vector>

#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/reduce.hpp"

namespace meridian::gyro {

struct TransitFactorCalibration {
  Uncertain factor_rad_per_div_s;        ///< c (rad/(div·s)) with σ
  double computed_rad_per_div_s = 0.0;   ///< (1+λ)·τ·π/(2T_B) for comparison, when T_B is known (else 0)
  Uncertain amplitude1_div, amplitude2_div;   ///< B_i from the reversal readings
  Uncertain dt1_s, dt2_s;                     ///< Δt_i = −t1 + 2t2 − t3 of the level-0 transits
  double north_rad = 0.0;                     ///< N from the calibrated c (both give the same)
  std::vector<std::string> notes;
};

/// Each determination must be non-tracking with the transit method's inputs
/// (≥ 3 level-0 crossings, ≥ 2 reversal readings); B and the
/// direction-corrected Δt (with σ) come from the transit reduction. The
/// clamps must differ.
TransitFactorCalibration calibrate_transit_factor(const DeterminationInput& first,
                                                  const DeterminationInput& second,
                                                  const Instrument& inst);

/// The `gyro transit-factor` workflow: a reduce input holding exactly the
/// two determinations (clamped east and west of north) at one station; the
/// instrument is resolved at the station latitude. Throws InputError
/// (field "determinations") for any other number of determinations, and
/// the errors above with field paths "determinations[i]…".
TransitFactorCalibration calibrate_transit_factor(const ReduceInput& in);

}  // namespace meridian::gyro
