#pragma once
/// \file dov_jobs.hpp
/// The runners of the deflection-of-the-vertical workflow (docs/deflection.md): read the line a
/// block at a time (dov_files.hpp, CSV or binary by content), load the gravity model a
/// configuration names, call dov::process_stream and give an error the file, line and column
/// it came from (io::SourceMap); the runner of a line given as columns (the Python package);
/// and `dov convert`.
///
/// Errors (all runners): about a sample ("samples[k].member", the filter's "epoch k") the line
/// file's name, the sample's line and the CSV column ("line.csv:17: ins_11…ins_33: …"), for a
/// binary line "line.bin: sample k: member"; about the line as a whole ("samples": too short)
/// the line file; about options and the gravity model the configuration's file, line and key.
/// The class of an error is kept (ParseError, InputError, NumericalError, IoError).

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/dov/deflection.hpp"
#include "meridian/dov/streaming.hpp"
#include "meridian/io/dov_columns.hpp"
#include "meridian/io/dov_files.hpp"

namespace meridian::io {

/// Read config.line_path, run dov::process_stream with config.options, handing the epochs to
/// `outputs`, and return the Result. Result::origin names the configuration, the line file and
/// the gravity model ("egm96 (to degree 360)"); the line's notes and warnings follow the
/// workflow's: the model that gave η_G, ξ_G, the line's columns that were not read.
///
/// With config.gravity_model, η_G, ξ_G of every sample are the astronomic deflection of the
/// model's plumb line at the sample's position, ξ = Φ − φ, η = (Λ − λ)·cos φ (the gyro
/// runner's quantity; gravity/gravity_field.hpp, xi_astro_rad and eta_astro_rad), evaluated
/// along the line by gravity::evaluate_track within 1e-4″, 65 536 samples at a time. Exactly
/// one source of model values: a line with model columns and a configuration that names a
/// model (an error at the gravity_model key), or neither (an error naming the line file), is
/// an InputError. Memory stays flat for a line of any length (dov/streaming.hpp).
dov::Result run_dov_stream(const DovConfig& config, const dov::EpochOutputs& outputs,
                           Progress* progress = nullptr);

/// run_dov_stream keeping every epoch in Result::epochs (a short line).
dov::Result run_dov(const DovConfig& config, Progress* progress = nullptr);

/// A line given as columns (the Python package's arrays) with the options of the configuration
/// at `options_file` (its `line:` is not read); every epoch kept. Errors: dov_input's; a
/// configuration that names a gravity model is an InputError at its file (the columns carry
/// η_G, ξ_G); an error about a sample names the column and element, without a file
/// ("lat_deg[3]", "lgu_body_to_nav[3]", "truth_eta_arcsec[3]"; others keep their field).
dov::Result run_dov_columns(const DovLineColumns& line, const std::string& options_file,
                            Progress* progress = nullptr);

/// What `dov convert` converted.
struct DovConversion {
  std::string input, output;  ///< as given ("-": standard output)
  std::uint64_t samples = 0;
  bool model_values = false;  ///< the line has η_G, ξ_G (model columns)
  bool truth = false;         ///< the line has truth columns
  std::vector<std::string> ignored_columns;  ///< columns of the input CSV not converted
};

/// `dov convert IN OUT`: the line at `input` (CSV or binary, by content) to the binary format,
/// or — `output` ending in .csv (any case) or "-" — to a line CSV (dov_writers.hpp; "-":
/// written to `standard_output`), a block of 65 536 samples at a time. A file is written
/// atomically: to a temporary beside it, renamed into place when complete (the binary header's
/// count is written last). Errors: the reader's (dov_files.hpp); IoError when the output cannot
/// be written.
DovConversion convert_dov_line(const std::string& input, const std::string& output,
                               std::ostream& standard_output);

/// What `dov convert` says on standard error: a warning line about the columns not converted
/// (neither output has room for them) and the summary line, "OUT: 361 samples, model values,
/// truth" ("stdout" for "-").
std::string dov_conversion_text(const DovConversion& conversion);

}  // namespace meridian::io
