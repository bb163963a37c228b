#pragma once
/// \file tracking.hpp
/// Tracking-mode determination: circle readings at the reversal points of
/// the tracked oscillation → centre M → N_G = M − λ·τ·α_p (spec §1, §3).

#include <limits>
#include <vector>

#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/reversal.hpp"

namespace meridian::gyro {

struct TrackingObservations {
  std::vector<double> reversals_rad;  ///< horizontal-circle readings at the reversals (radians)
  /// A-priori σ of one reversal reading (radians); NaN if unknown, in which
  /// case σ(N_G) needs redundancy (n > 3 for the least-squares methods).
  double sigma_reading_rad = std::numeric_limits<double>::quiet_NaN();
};

struct TrackingResult {
  ReversalResult fit;   ///< centre etc. in radians (centre normalised to [0, 2π))
  NorthReading north;   ///< N_G with σ, zero-position correction applied when α_p known
};

/// Reduce one tracking determination. Readings may straddle 0°/360°.
/// Throws InputError for a bad reversal sequence (naming the reading).
TrackingResult reduce_tracking(ReversalMethod method, const TrackingObservations& obs,
                               const Instrument& inst, const ZeroPosition& zero = std::nullopt);

}  // namespace meridian::gyro
