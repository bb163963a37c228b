#pragma once
/// \file gyro_stochastic.hpp
/// `meridian gyro stochastic FILE`: the reversal-point series of a field book (as for
/// `gyro reduce`) — each tracking determination's circle readings and each zero-position run's
/// scale readings — each analysed under the competing stochastic models
/// (gyro::analyse_stochastic).
///
/// Units at this edge: tracking readings are converted from radians to arc-seconds relative
/// to `reference_rad` (the first reading rounded down to a whole degree; readings unwrapped
/// across 0°/360°), zero-position readings stay in divisions. The north reading is
/// reference + M, normalised to [0°, 360°).

#include <filesystem>
#include <string>

#include "meridian/core/progress.hpp"
#include "meridian/gyro/stochastic_book.hpp"

namespace meridian::io {

/// A field book and the analysis of its series.
struct StochasticJob {
  std::string file;
  bool campaign = false;  ///< the file is a campaign file (`campaign:` at the top level)
  gyro::StochasticBookResult result;
};

/// Read a reduce field book, or a campaign file (recognised by its top-level `campaign:`;
/// series from known_line.before, known_line.after and line.determinations), and analyse
/// every series of at least 6 readings. The booked σ of one reading (tracking:
/// sigma_reading_arcsec of the determination; zero position: the instrument's
/// sigma_reading_div) goes with each series for the booking check. Throws the reader's
/// ParseError/InputError (file, line, field) and, for a series that cannot be analysed, its
/// InputError/NumericalError with the file and the series' field ("determinations[2].reversals").
/// A file without any series of at least 6 readings is an InputError that says how many series
/// it has and the longest (a standard programme of 5 reversals per run is below the minimum).
StochasticJob run_stochastic_file(const std::filesystem::path& path, Progress* progress = nullptr);

}  // namespace meridian::io
