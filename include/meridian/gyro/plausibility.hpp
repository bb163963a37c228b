#pragma once
/// \file plausibility.hpp
/// Observations no tape-suspended gyro-theodolite can produce are errors,
/// not warnings: they come from booking mistakes (stopwatch times booked as
/// m.ss numbers, a wrong sign or unit), and every result computed from them
/// would be wrong. The bounds are generous so that no real run is refused:
///
/// * the period implied by the crossings of one graduation (t_{k+2} − t_k
///   is one period T_B) must agree with the stated period_s within
///   kPeriodAgreement (25 %), or, without a stated period, lie within
///   [kMinPlausiblePeriod_s, kMaxPlausiblePeriod_s] (T_A ≈ 7–10 min, spec §1;
///   T_B < T_A);
/// * non-tracking scale readings lie within ±kMaxScaleReading_div (eyepiece
///   scales span about ±10–15 div).

#include "meridian/gyro/nontracking.hpp"

namespace meridian::gyro {

inline constexpr double kPeriodAgreement = 0.25;
inline constexpr double kMinPlausiblePeriod_s = 100.0;
inline constexpr double kMaxPlausiblePeriod_s = 1800.0;
inline constexpr double kMaxScaleReading_div = 30.0;

/// Throw InputError naming the field (`crossings[i].times_s`,
/// `reversals_div[i]`) when the observations break the bounds above.
void check_plausible(const NonTrackingObservations& obs);

}  // namespace meridian::gyro
