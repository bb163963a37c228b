#pragma once
/// \file defaults.hpp
/// The values Meridian assumes when a field book or a command line states
/// none: the one home of each default, referenced by the instrument, the
/// observations, the readers, the simulators and the CLI. They are typical
/// of tape-suspended gyro-theodolites of the 15″–25″ class (gyro-theodolite
/// spec §3, §5) and are always shown in reports where they were used.

#include "meridian/core/units.hpp"

namespace meridian::gyro {

/// Stopwatch timing σ of one crossing or reversal time (s).
inline constexpr double kDefaultSigmaTime_s = 0.1;
/// Reading σ of the eyepiece scale (div).
inline constexpr double kDefaultSigmaReading_div = 0.05;
/// Largest accepted difference of the zero position α_p after − before (div).
inline constexpr double kDefaultZeroPositionTolerance_div = 0.5;
/// Nominal accuracy class of the instrument (arcsec); sets default tolerances.
inline constexpr double kDefaultAccuracyClass_arcsec = 15.0;
/// Commission error assumed for η taken from a global gravity model (rad).
inline constexpr double kDefaultModelEtaSigma_rad = 1.5 * units::kArcsecond;
/// Commission error assumed for ξ taken from a global gravity model (rad);
/// global models determine both components about equally well.
inline constexpr double kDefaultModelXiSigma_rad = 1.5 * units::kArcsecond;

}  // namespace meridian::gyro
