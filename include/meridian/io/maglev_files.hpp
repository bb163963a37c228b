#pragma once
/// \file maglev_files.hpp
/// Readers and writers of maglev gyro files (docs/maglev-gyro.md, "File
/// formats"), on io::RecordReader (delimited text: comma, semicolon or
/// whitespace, `#` comments, an optional header line).
///
/// * Series: columns `time` (s) and `current` (A), taken by name when the
///   header has them (`time [s]`, `current [A]`), else the first two columns;
///   a third column `position` (1 or 2) puts both positions in one file.
///   Time strictly increasing within a position; every value a finite number.
/// * Calibration table: `azimuth` (its header unit [deg], [dms], [gon], [rad] or
///   [mrad]; without one DMS or decimal degrees), `mean1` (A, or [mA], [uA]),
///   `sigma1`, `mean2`, `sigma2` (the same), in this order or by these
///   header names. Every column's header unit is applied; one not understood
///   is an InputError at the header line naming the column (issue 30: [gon]
///   was read as degrees).
///
/// Errors name the file, line and field (`pos1.csv:17: time: time does not
/// increase`): ParseError for unreadable values, InputError for a missing
/// position, a position other than 1 or 2, too few columns, empty series;
/// IoError when a file cannot be opened.
///
/// The runners that read these files and call the maglev module are in
/// maglev_jobs.hpp.

#include <istream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/reduce.hpp"
#include "meridian/maglev/simulator.hpp"

namespace meridian::io {

/// A series with the 1-based file line of every sample (for errors found later).
struct MaglevSeriesFile {
  std::string file;
  maglev::PositionSeries series;
  std::vector<int> lines;
};

/// One position's series from a stream (`source` names it in errors). A
/// `position` column, when present, must hold `position` everywhere (1 or 2);
/// position 0 accepts only files without that column.
MaglevSeriesFile read_maglev_series(std::istream& in, const std::string& source, int position = 0);
/// From a file ("-" is stdin). Throws IoError when it cannot be opened.
MaglevSeriesFile read_maglev_series_file(const std::string& path, int position = 0);

/// Both positions from one file with a `position` column. Throws InputError
/// naming the file when a position has no samples.
std::pair<MaglevSeriesFile, MaglevSeriesFile> read_maglev_two_positions(const std::string& path);

/// A calibration table (see the file comment); latitude etc. are left at
/// their defaults for the caller to fill.
maglev::CalibrationInput read_maglev_calibration_table(const std::string& path);

/// `time,current` CSV with a header, 17 significant digits (the simulator's output and
/// `maglev denoise`'s). `header_comment` lines are written first with "# " before each.
std::string maglev_series_csv(const maglev::PositionSeries& s,
                              const std::string& header_comment = {});
/// Same with a `position` column, the samples of both positions in time order.
std::string maglev_two_position_csv(const maglev::PositionSeries& p1,
                                    const maglev::PositionSeries& p2,
                                    const std::string& header_comment = {});
/// A calibration table (azimuth in decimal degrees).
std::string maglev_calibration_csv(const maglev::CalibrationInput& in,
                                   const std::string& header_comment = {});
/// The header comment of a simulated determination's files: "made by: `made_by`" and a line
/// with the truth (α_1, φ and r_1 in degrees, K in A·s/rad, b in A).
std::string maglev_truth_comment(const std::string& made_by, const maglev::TwoPositionTruth& truth);

/// Instrument constants from a YAML or JSON file (io::Node): `scale_A_s_per_rad`
/// (K, > 0), `scale_sigma_A_s_per_rad`, `latitude` (DMS or degrees),
/// `circle_reading1` (r_1), `constant_deviation_A` and
/// `constant_deviation_sigma_A` (the prior bias). A stored calibration (the
/// JSON of `maglev calibrate --json`, `kind: maglev-calibration`) is read the
/// same way: its K and I*. Every key is optional; errors name file:line:key.
/// The same struct holds the values a front end gives beside the files
/// (io::MaglevReduceSetup::given, maglev_jobs.hpp).
struct MaglevConstants {
  std::optional<Uncertain> scale_A_s_per_rad;
  std::optional<double> latitude_rad;
  std::optional<double> circle_reading1_rad;
  std::optional<Uncertain> constant_deviation_A;
};
MaglevConstants read_maglev_constants(const std::string& path);

}  // namespace meridian::io
