#pragma once
/// \file dov_files.hpp
/// Readers of the dynamic deflection-of-the-vertical workflow (docs/deflection.md, "Files"):
/// the line CSV (and, by content, the binary line of dov_binary.hpp) and the YAML/JSON
/// configuration. Their writers are dov_writers.hpp, the runners that read both, load the
/// gravity model and call dov::process_stream dov_jobs.hpp.
///
/// Line CSV (record_reader.hpp: comma, semicolon or whitespace, `#` comments, CRLF): a header
/// line naming the columns (any order; ASCII case ignored), one sample per line:
///
///   time_s                     time (s), strictly increasing
///   lat_deg, lon_deg           geodetic latitude, longitude: decimal degrees or DMS
///   height_m                   ellipsoidal height (m)
///   speed_m_s                  speed over ground (m/s)
///   lgu_11 … lgu_33            C_b^n of LGU/GNSS, element (row, column), 1-based, E-N-U rows
///   ins_11 … ins_33            C_b^{n′} of INS/GNSS, likewise
///   or, for either attitude instead of its matrix (never both):
///   lgu_heading_deg, lgu_pitch_deg, lgu_roll_deg   (and ins_…) Euler angles, DMS or decimal
///                              degrees, by the convention of dov/euler.hpp: ENU, body
///                              right-forward-up, C_b^n = R_z(−ψ)·R_x(θ)·R_y(φ)
///   model_eta_arcsec, model_xi_arcsec   η_G, ξ_G of the global model (″)
///   truth_eta_arcsec, truth_xi_arcsec   optional (simulations): the true η, ξ (″), both or none
///
/// Frames and signs: attitude_difference.hpp and geodesy/frames.hpp. The compact binary format
/// is dov_binary.hpp (read_dov_line_file tells them by content); it holds matrices only.
/// read_dov_line* read the whole line into memory (about 300 bytes per sample); DovLineReader
/// reads it a chunk at a time. Errors: ParseError/InputError with the source, the line and the
/// column ("line.csv:17: lgu_23: \"x\" is not a number"), InputError naming the header line for
/// a missing column, IoError when the file cannot be opened.

#include <cstdint>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "meridian/core/error.hpp"
#include "meridian/dov/deflection.hpp"
#include "meridian/io/document.hpp"

namespace meridian::io {

/// A line file: its samples, the truth (empty, or one per sample) and the 1-based file line of
/// each sample.
struct DovLine {
  std::string source;
  std::vector<dov::Sample> samples;
  std::vector<dov::Truth> truth;
  std::vector<int> lines;
  /// false when the file has no model_eta_arcsec, model_xi_arcsec columns (the model values
  /// are then NaN until a gravity model fills them: dov_jobs.hpp).
  bool has_model_values = true;
  /// true: read from the binary format (dov_binary.hpp); `lines` is then empty and errors
  /// name "sample k" instead of a file line.
  bool binary = false;
  /// Whole-file reads (read_dov_line, read_dov_line_file): DovLineReader::ignored_columns().
  std::vector<std::string> ignored_columns;
};

/// Reads a line a chunk of samples at a time, so a long line never has to be in memory: a
/// binary line (dov_binary.hpp) or a CSV, told apart by content (the binary magic). Move-only.
/// Errors as the file comment (CSV) or dov_binary.hpp (binary).
class DovLineReader {
 public:
  /// Opens `path` and reads its header now. IoError when it cannot be opened.
  explicit DovLineReader(const std::string& path);
  /// A line CSV from `in` (which must outlive the reader); `source` names it in errors.
  DovLineReader(std::istream& in, const std::string& source);
  ~DovLineReader();
  DovLineReader(DovLineReader&&) noexcept;

  const std::string& source() const;
  /// The column(s) a dov::Sample member came from, for errors: "lat_rad" → "lat_deg",
  /// "ins_body_to_nav" → "ins_11…ins_33" or "ins_heading_deg, ins_pitch_deg, ins_roll_deg";
  /// a binary line's record field names.
  std::string column_of(const std::string& member) const;
  bool binary() const;
  bool has_model_values() const;
  bool has_truth() const;
  /// CSV header columns the line does not use, as written (empty for the binary format): a
  /// misspelt optional column (model_eta_arcsec, truth_eta_arcsec, …) is not read, and the
  /// runners (dov_jobs.hpp) warn about each.
  std::vector<std::string> ignored_columns() const;
  /// The number of samples when the format states it up front (binary), else nullopt.
  std::optional<std::uint64_t> count() const;
  /// Replace the contents of `chunk` by the next up to `max` (≥ 1) samples (with their truth
  /// and, for a CSV, file lines); false when none are left.
  bool next(DovLine& chunk, std::size_t max);

 private:
  struct Impl;
  void start_csv(std::istream& in, const std::string& source);
  std::unique_ptr<Impl> impl_;
};

/// Read a line CSV from `in`; `source` names it in errors. Throws as the file comment says.
DovLine read_dov_line(std::istream& in, const std::string& source);
/// Read the line at `path`, binary when it starts with the binary format's magic ("MRDN-DOV"),
/// else CSV. IoError when it cannot be opened.
DovLine read_dov_line_file(const std::string& path);


/// The line file's column of a scalar dov::Sample member, as the files and the Python package's
/// arrays name it: "lat_rad" → "lat_deg", "lon_rad" → "lon_deg", "model_eta_rad" →
/// "model_eta_arcsec", "model_xi_rad" → "model_xi_arcsec"; any other member as given (time_s,
/// height_m, speed_m_s are their own columns).
std::string dov_line_column(const std::string& member);

/// The global gravity model a configuration names (`gravity_model: {model: …, max_degree: …}`).
struct DovGravityModel {
  std::string source;   ///< name or path as written (e.g. "egm2008", "models/x.gfc")
  std::string lookup;   ///< the path beside the configuration when such a file exists, else source
  int max_degree = -1;  ///< truncate on load; −1: the model's full degree
};

/// A configuration: the line file and the options (spec defaults where a key is absent).
///
///   line: survey.csv                # relative to the configuration's directory
///   zeta: 0.05
///   sigma_model_arcsec: 3           # σ of the global model's error
///   correlation_length_m: 10000     # λ in ω₀ = 2πV/λ
///   stationary_speed_m_s: 0.1       # or speed_sigma_m_s: 0.03 (threshold 4σ; not both)
///   stationary_sigma_factor: 4      # only with speed_sigma_m_s
///   stationary_min_duration_s: 5    # hysteresis of stops and starts
///   sigma_obs_arcsec: 0.5           # or sigma_obs_east_arcsec, sigma_obs_north_arcsec
///   initial: {phi_e_arcsec: 2, phi_n_arcsec: 2, phi_u_arcsec: 5, eps_u_deg_per_h: 0.003,
///             delta_arcsec: 3, x_arcsec_s: 955}   # the last two default to the model's
///   discretisation: exact           # or published_first_order
///   extraction: exact               # or skew_symmetric
///   max_step_s: 60
///   gate_alpha: 0                   # χ² gate significance; 0: none
///   statistics_start_s: 0
///   whiteness_alpha: 0.05           # Ljung–Box test of the normalised innovations
///   gravity_model: {model: egm2008, max_degree: 360}   # instead of the model columns
///
/// Unknown keys are errors (typos). Errors carry the file, line and key.
struct DovConfig {
  std::string file;       ///< the configuration's path
  std::string line_path;  ///< resolved against the configuration's directory
  dov::Options options;
  /// The global model that gives η_G, ξ_G at every sample (as in gyro campaign files: a file
  /// beside the configuration, a path, or a name looked up where GeographicLib keeps its
  /// models, io/gravity_model_lookup.hpp); absent: the line's model columns.
  std::optional<DovGravityModel> gravity_model;
  FieldLines lines;  ///< lines of the configuration's keys
};

/// Read a configuration (YAML or JSON). Throws ParseError/InputError with file, line and key,
/// IoError when the file cannot be read.
DovConfig read_dov_config(const std::string& path);

}  // namespace meridian::io
