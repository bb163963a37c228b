#pragma once
/// \file instrument.hpp
/// Gyro-theodolite instrument constants and the equilibrium equations that
/// turn an oscillation centre into the circle reading of gyro north N_G
/// (gyro-theodolite spec §1).
///
/// Conventions: scale readings in divisions (div), positive to the east;
/// circle readings and angles in radians, increasing clockwise; the spin
/// axis azimuth as a circle reading is N′ + τ·a.

#include <optional>

#include "meridian/core/uncertain.hpp"
#include "meridian/gyro/defaults.hpp"

namespace meridian::gyro {

/// A value with its standard deviation (core/uncertain.hpp).
using meridian::Uncertain;

/// Constants of one instrument at the station latitude.
struct Instrument {
  double scale_value_rad = 0.0;          ///< τ, radians per division (> 0)
  double sigma_scale_value_rad = 0.0;    ///< σ(τ)
  Uncertain torsion_ratio;               ///< λ = D_B/D_K at the station latitude (dimensionless, ≥ 0)
  /// Calibrated transit factor c (radians per division per second). When
  /// set, the transit method uses ΔN = c·B·Δt instead of the computed
  /// (1+λ)·τ·π/(2T_B).
  std::optional<Uncertain> transit_factor_rad_per_div_s;
  double sigma_time_s = kDefaultSigmaTime_s;          ///< stopwatch timing σ (s)
  double sigma_reading_div = kDefaultSigmaReading_div;  ///< scale reading σ (div)
};

/// Tape zero position α_p (div) with its σ; absent means "not observed"
/// and no zero-position correction is applied.
using ZeroPosition = std::optional<Uncertain>;

/// Circle reading of gyro north from a determination.
struct NorthReading {
  double north_rad = 0.0;               ///< N_G, normalised to [0, 2π)
  double sigma_rad = 0.0;               ///< σ(N_G) from all propagated sources
  double delta_n_rad = 0.0;             ///< N_G − N′ (non-tracking) or N_G − M (tracking), signed
  double zero_correction_rad = 0.0;     ///< −λ·τ·α_p (0 when α_p unknown)
  double sigma_zero_correction_rad = 0.0;
};

/// Non-tracking equilibrium: N_G = N′ + (1+λ)·τ·β − λ·τ·α_p, with σ
/// propagated from σ(β), σ(λ), σ(τ) and σ(α_p) (independent).
/// `clamp_rad` is N′, `beta_div` the equilibrium scale reading β.
NorthReading north_from_nontracking(double clamp_rad, Uncertain beta_div, const Instrument& inst,
                                    const ZeroPosition& zero = std::nullopt);

/// Non-tracking with a calibrated transit factor: ΔN = c·B·Δt is given
/// directly (radians, with σ); N_G = N′ + ΔN − λ·τ·α_p.
NorthReading north_from_delta(double clamp_rad, Uncertain delta_n_rad, const Instrument& inst,
                              const ZeroPosition& zero = std::nullopt);

/// Tracking equilibrium: N_G = M − λ·τ·α_p (M = centre of the tracked
/// oscillation as a circle reading, radians, with σ).
NorthReading north_from_tracking(Uncertain centre_rad, const Instrument& inst,
                                 const ZeroPosition& zero = std::nullopt);

}  // namespace meridian::gyro
