#pragma once
/// \file maglev_jobs.hpp
/// Running the maglev gyro workflows from files to results (docs/maglev-gyro.md):
/// read the files (maglev_files.hpp), assemble the Input from the files and
/// the values given beside them, call the maglev module, and give every error
/// the file, line and column of what it concerns (io::SourceMap). Shared by
/// `meridian maglev reduce | denoise | calibrate` and the Python package.
///
///     io::MaglevReduceSetup setup;                       // constants, options
///     setup.given.latitude_rad = 35 * units::kDegree;
///     setup.given.scale_A_s_per_rad = Uncertain{8000, 0};
///     maglev::ReduceResult r = io::run_maglev_reduce_files({"pos1.csv", "pos2.csv"}, setup);
///
/// An error about a sample (`position1.time_s[17]`) names the sample's file,
/// line and column (`pos1.csv:19: time: …`); one about a whole series
/// (`position2.current_A`) its file and column; one about a position's
/// processing (`position1.segment_length`) its file with the field kept.
/// Errors keep their class (ParseError, InputError, NumericalError, IoError).

#include <optional>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/reduce.hpp"
#include "meridian/io/maglev_files.hpp"

namespace meridian::io {

/// What a front end calls the values a reduction may lack, for the errors that ask for them
/// ("the scale K is needed: --scale, --config or --calibration").
struct MaglevArgumentNames {
  std::string scale = "scale_A_s_per_rad";
  std::string latitude = "latitude";
  std::string constants_file = "config";
  std::string calibration_file = "calibration";
};

/// What a reduction is given beside its series.
struct MaglevReduceSetup {
  /// Instrument constants (read_maglev_constants, YAML or JSON); empty: none.
  std::string constants_file;
  /// A stored calibration (`maglev calibrate --json`): its K and I* (the prior bias b₀) win over
  /// the constants file's; empty: none.
  std::string calibration_file;
  /// Values given directly (command-line options, keyword arguments): each wins over the files'.
  MaglevConstants given;
  double reading1_sigma_rad = 0.0;  ///< σ of r_1 (r_1 itself: 0 unless a file or `given` has it)
  std::optional<maglev::ChainSetup> chain;
  /// The processing options; their prior_bias_A is replaced by the constants' prior bias.
  maglev::ReduceOptions options;
  MaglevArgumentNames names;
};

/// The ReduceInput of `setup` without its series: the constants file's values, then the
/// calibration's K and I*, then `given`. Throws the readers' errors (file:line:key), and
/// InputError (field names.scale / names.latitude) when K or φ is given by none of them.
maglev::ReduceInput maglev_reduce_input(const MaglevReduceSetup& setup);

/// `maglev reduce FILE [FILE2]`: one file with a position column, or one file per position
/// ("-": standard input); the constants (maglev_reduce_input) are read first. The Result's source
/// names the files as given ("a.csv, b.csv"). Errors as the file comment says.
maglev::ReduceResult run_maglev_reduce_files(const std::vector<std::string>& files,
                                             const MaglevReduceSetup& setup,
                                             Progress* progress = nullptr);

/// The same for series given as arrays: errors keep their field paths ("position1.time_s[3]").
maglev::ReduceResult run_maglev_reduce(const MaglevReduceSetup& setup,
                                       maglev::PositionSeries position1,
                                       maglev::PositionSeries position2,
                                       Progress* progress = nullptr);

/// `maglev denoise FILE`: the series of FILE (time, current; "-": standard input) denoised by
/// maglev::denoise_series (`options.level` 0: the default, lowered for a short series). Errors
/// name the file.
maglev::SeriesDenoising run_maglev_denoise_file(const std::string& path,
                                                const maglev::DenoiseOptions& options);

/// `maglev calibrate TABLE`: the table read (read_maglev_calibration_table) and fitted at the
/// latitude, significance level and nominal K given. The Result's source is `path`. Errors name
/// the file.
maglev::CalibrationResult run_maglev_calibrate_file(
    const std::string& path, double latitude_rad, double alpha = 0.05,
    std::optional<double> nominal_scale_A_s_per_rad = std::nullopt);

}  // namespace meridian::io
