#pragma once
/// \file series.hpp
/// One position's rotor-current series (maglev-gyro spec §1): the samples a
/// reduction, the denoising of `maglev denoise` and the simulator work on.
///
/// Units: time in s, current in A. A series is valid when it has at least one
/// sample, as many times as currents, every value finite, time strictly
/// increasing, and some variation (a mean with a σ needs noise).

#include <string>
#include <vector>

namespace meridian::maglev {

/// One position's rotor-current series.
struct PositionSeries {
  std::vector<double> time_s;     ///< strictly increasing
  std::vector<double> current_A;  ///< same length, finite
};

/// Validate one series (see the file comment); `field` prefixes the error
/// field ("position1" → "position1.current_A", "position1.time_s[17]").
/// Throws InputError.
void validate_series(const PositionSeries& s, const std::string& field);

}  // namespace meridian::maglev
