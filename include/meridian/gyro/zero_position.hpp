#pragma once
/// \file zero_position.hpp
/// Tape zero position α_p from motor-off free oscillations observed before
/// and after a gyro run (spec §2).

#include <optional>
#include <string>
#include <vector>

#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/reversal.hpp"

namespace meridian::gyro {

/// One motor-off run: reversal readings on the scale (div), optionally timed.
struct ZeroPositionRun {
  std::vector<double> reversals_div;
  std::vector<double> times_s;   ///< empty, or one time per reversal (s), increasing
};

/// The centre of one run, its amplitude and (with times) the free period T_F.
struct ZeroPositionEstimate {
  ReversalResult fit;                     ///< centre = α_p (div)
  double amplitude_div = 0.0;             ///< half the mean peak-to-peak swing
  std::optional<Uncertain> free_period_s; ///< T_F = 2 × mean half-period, from the times
};

/// Before/after summary.
struct ZeroPositionSummary {
  std::optional<ZeroPositionEstimate> before;
  std::optional<ZeroPositionEstimate> after;
  Uncertain mean_div;                   ///< α_p used for the correction (mean of the runs given)
  std::optional<double> difference_div; ///< after − before, when both exist
  double tolerance_div = kDefaultZeroPositionTolerance_div;
  bool within_tolerance = true;
  std::vector<std::string> warnings;
};

/// Estimate one run with `method` (Schuler or a least-squares method).
/// `sigma_reading_div` is the a-priori reading σ (σ policy: ReversalResult). Throws InputError for a
/// bad sequence or bad times.
ZeroPositionEstimate estimate_zero_position(const ZeroPositionRun& run, ReversalMethod method,
                                            double sigma_reading_div);

/// Combine before/after runs (either may be absent, not both). The mean's σ
/// is the σ of the mean of the runs' centres, widened to half their
/// difference when that is larger (the drift is then the dominant error).
/// A difference above `tolerance_div` is a warning, and so is a run whose
/// readings scatter more than `sigma_reading_div` (the global test of
/// estimate_centre; that run then carries the larger a-posteriori σ).
ZeroPositionSummary summarise_zero_position(const std::optional<ZeroPositionRun>& before,
                                            const std::optional<ZeroPositionRun>& after,
                                            ReversalMethod method, double sigma_reading_div,
                                            double tolerance_div = kDefaultZeroPositionTolerance_div);

}  // namespace meridian::gyro
