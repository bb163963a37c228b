#pragma once
/// \file stochastic_book.hpp
/// The result of `meridian gyro stochastic` for one field book: every reversal-point series
/// of the book (each tracking determination's circle readings, each zero-position run's scale
/// readings) with its model comparison (gyro::analyse_stochastic, stochastic.hpp). The reader
/// that splits a book into series is io::run_stochastic_file (io/gyro_stochastic.hpp); the
/// writers are in report/gyro_stochastic.hpp.

#include <string>
#include <vector>

#include "meridian/gyro/stochastic.hpp"

namespace meridian::gyro {

/// One series of a field book and its analysis.
struct StochasticSeries {
  /// Field path of the series, e.g. "determinations[0].reversals" or
  /// "determinations[1].zero_before", followed by the book's label in parentheses if any.
  std::string label;
  /// true: circle readings in arc-seconds relative to reference_rad; false: zero-position
  /// scale readings in divisions.
  bool tracking = true;
  /// Tracking: the readings are arc-seconds relative to this circle reading (radians; the
  /// first reading rounded down to a whole degree). 0 for zero-position runs.
  double reference_rad = 0.0;
  StochasticInput input;
  StochasticResult result;
};

/// Every series of one field book, in the book's order.
struct StochasticBookResult {
  std::vector<StochasticSeries> series;
};

}  // namespace meridian::gyro
