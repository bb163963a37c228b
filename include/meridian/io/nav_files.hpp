#pragma once
/// \file nav_files.hpp
/// Files of the marine navigation workflow (docs/file-formats.md, "Navigation files";
/// shared/spec/navigation.md §7): the CSV readers and writers of dead reckoning, stations,
/// lines of position, satellite fixes and truth, the NMEA 0183 adapter, the YAML/JSON
/// configuration and the runner that reads them, turns geographic input into the job's plane,
/// calls nav::process and names the file and line of an error.
///
/// CSV (record_reader.hpp: comma, semicolon or whitespace, `#` comments, CRLF): a header line
/// names the columns (any order, ASCII case ignored); one record per line:
///
///   DR        time_s, speed_m_s, heading_deg        (σ from the configuration), or
///             time_s, v_north_m_s, v_east_m_s       (σ from the configuration)
///             strictly increasing times
///   stations  name, x_m, y_m  or  name, lat_deg, lon_deg        (names unique)
///   LOPs      time_s, type, station, station2, value, sigma_m [, chain]
///             type range | range_difference (value in m) | time_difference (value in µs,
///             L = c·τ with the chain's propagation speed c, default 299 691 162 m/s);
///             station2 empty for a range
///   fixes     time_s, x_m, y_m  or  time_s, lat_deg, lon_deg, with sigma_m or both
///             sigma_x_m, sigma_y_m (σ north, σ east)
///   truth     time_s, x_m, y_m  or  time_s, lat_deg, lon_deg
///
/// Angles: decimal degrees or DMS (core/dms.hpp). Errors: ParseError/InputError naming the
/// file, the line and the column ("lops.csv:17: value: \"x\" is not a number"), InputError
/// naming the header line for a missing column, IoError when a file cannot be opened. An
/// exact duplicate LOP or fix (every value equal) is an InputError naming both lines.
///
/// Geographic input and the plane: the reader keeps positions, headings and LOP values as
/// written (nav::SurveyLine); nav::to_plane (nav/survey_line.hpp) puts them in the job's plane.
///
/// The runner (read_nav_job, run_nav): the configuration's files → nav::SurveyLine with an
/// io::SourceMap of where each of its fields was read → nav::process, whose errors leave with
/// the file, line and column of the element they name.

#include <cstddef>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/io/document.hpp"
#include "meridian/io/source_map.hpp"
#include "meridian/nav/navigation.hpp"
#include "meridian/nav/simulator.hpp"
#include "meridian/nav/survey_line.hpp"

namespace meridian::io {

/// Default σ of each coordinate of an NMEA GGA fix (m) (a note says so).
inline constexpr double kNavDefaultSigmaFix_m = 5.0;
/// A speed sample of an NMEA log with no HDT this close in time (s) is skipped.
inline constexpr double kNavHeadingGap_s = 2.0;

/// A position as written: plane (x north, y east, m) or geographic (radians).
using NavPosition = nav::Position;

// ---- raw file contents (before the plane and the names are resolved) -------------------------

struct NavDrFile {
  std::string source;
  bool speed_heading = true;  ///< columns speed_m_s, heading_deg; false: v_north_m_s, v_east_m_s
  struct Record {
    double time_s = 0.0;
    double a = 0.0;  ///< speed (m/s) or v_north (m/s)
    double b = 0.0;  ///< heading (rad, true or grid) or v_east (m/s)
  };
  std::vector<Record> records;
  std::vector<int> lines;
};

struct NavStationsFile {
  std::string source;
  std::vector<std::string> names;
  std::vector<NavPosition> positions;
  std::vector<int> lines;
};

/// Kind of a LOP record as written (`type` column).
using NavLopKind = nav::LopKind;

struct NavLopsFile {
  std::string source;
  struct Record {
    double time_s = 0.0;
    NavLopKind kind = NavLopKind::Range;
    std::string station, station2, chain;  ///< chain empty: none
    double value = 0.0;                    ///< m, or µs for a time difference
    double sigma_m = 0.0;
  };
  std::vector<Record> records;
  std::vector<int> lines;
};

struct NavFixesFile {
  std::string source;
  struct Record {
    double time_s = 0.0;
    NavPosition position;
    double sigma_north_m = 0.0, sigma_east_m = 0.0;
  };
  std::vector<Record> records;
  std::vector<int> lines;
};

struct NavTruthFile {
  std::string source;
  struct Record {
    double time_s = 0.0;
    NavPosition position;
  };
  std::vector<Record> records;
  std::vector<int> lines;
};

/// Readers of `in` (`source` names it in errors) and of a path (IoError when it cannot be
/// opened). They check the values of one record (finite, σ > 0, speed ≥ 0, |lat| ≤ 90°, known
/// type, DR times strictly increasing, no duplicate LOP or fix, unique station names); names
/// of stations and chains are resolved by the runner.
NavDrFile read_nav_dr(std::istream& in, const std::string& source);
NavDrFile read_nav_dr_file(const std::string& path);
NavStationsFile read_nav_stations(std::istream& in, const std::string& source);
NavStationsFile read_nav_stations_file(const std::string& path);
NavLopsFile read_nav_lops(std::istream& in, const std::string& source);
NavLopsFile read_nav_lops_file(const std::string& path);
NavFixesFile read_nav_fixes(std::istream& in, const std::string& source);
NavFixesFile read_nav_fixes_file(const std::string& path);
NavTruthFile read_nav_truth(std::istream& in, const std::string& source);
NavTruthFile read_nav_truth_file(const std::string& path);

// ---- writers (used by `nav simulate`); plane coordinates, 17 significant digits --------------

/// `settings`, when not empty, is written as a `# ` comment line before the header (the
/// simulator's settings); line ends inside it become spaces.
/// DR as time_s, speed_m_s, heading_deg (speed |v|, heading atan2(v_E, v_N) in [0°, 360°)).
std::string nav_dr_csv(const std::vector<nav::DrSample>& dr, const std::string& settings = {});
std::string nav_stations_csv(const std::vector<nav::Station>& stations,
                             const std::string& settings = {});
/// LOPs as time_s, type, station, station2, value, sigma_m, chain (names from `input`).
std::string nav_lops_csv(const nav::Input& input, const std::string& settings = {});
/// Fixes as time_s, x_m, y_m, sigma_x_m, sigma_y_m (the diagonal of the covariance).
std::string nav_fixes_csv(const std::vector<nav::Fix>& fixes, const std::string& settings = {});
std::string nav_truth_csv(const std::vector<nav::TruthPoint>& truth,
                          const std::string& settings = {});

// ---- configuration ---------------------------------------------------------------------------

/// `projection:` of a configuration.
struct NavProjectionConfig {
  geodesy::GridDefinition definition;
};

/// One entry of `chains:`.
using NavChainConfig = nav::LineChain;

/// Which NMEA sentence gives the speed.
enum class NavSpeedSentence { Vtg, Vbw };

/// The `nmea:` block.
struct NavNmeaConfig {
  std::string heading_path;    ///< HDT
  std::string speed_path;      ///< VTG or VBW; default the heading file
  std::string positions_path;  ///< GGA; default the speed file; empty with `positions: none`
  NavSpeedSentence speed_sentence = NavSpeedSentence::Vtg;
  /// Keep one GGA every this many seconds as a fix; the others become the truth. 0: every
  /// GGA is a fix, no truth.
  double fix_interval_s = 0.0;
  double sigma_fix_m = kNavDefaultSigmaFix_m;
  bool sigma_fix_given = false;
  bool accept_missing_checksum = false;
};

struct NavConfig {
  std::string file;  ///< the configuration's path
  /// Input files, resolved against the configuration's directory; empty when not given.
  std::string dr_path, stations_path, lops_path, fixes_path, truth_path;
  std::optional<NavNmeaConfig> nmea;
  std::optional<NavProjectionConfig> projection;
  /// `initial:`; absent: the first fix within nav::kInitialFixWindow_s of the first DR epoch.
  std::optional<NavPosition> initial;
  std::optional<double> initial_sigma_m;
  std::vector<NavChainConfig> chains;
  nav::Options options;
  /// σ of DR speed/heading samples and of DR velocity components; nullopt: the defaults above.
  std::optional<double> sigma_speed_m_s, sigma_heading_rad, sigma_velocity_m_s;
  FieldLines lines;  ///< lines of the configuration's keys
};

/// Read a configuration (YAML or JSON):
///
///   dr: dr.csv                 # files relative to the configuration's directory
///   stations: stations.csv
///   lops: lops.csv
///   fixes: fixes.csv           # optional
///   truth: truth.csv           # optional
///   nmea: {heading: gyro.nmea, speed: gps.nmea, positions: gps.nmea, speed_sentence: vtg,
///          fix_interval_s: 120, sigma_fix_m: 5, accept_missing_checksum: false}  # instead of dr
///   initial: {x_m: 0, y_m: 0, sigma_m: 100}     # or {lat: …, lon: …, sigma_m: …}
///   projection: {type: utm, zone: 31, north: true}
///               # or {type: transverse-mercator, central_meridian: 114, scale_factor: 1,
///               #     false_easting_m: 0, false_northing_m: 0}; ellipsoid: wgs84 (default),
///               # grs80, cgcs2000, …
///   sigma_speed_m_s: 0.05
///   sigma_heading_deg: 0.2
///   sigma_velocity_m_s: 0.05   # DR given as v_north_m_s, v_east_m_s
///   chains: [{name: X, estimate_scale: false, estimate_offset: true,
///             sigma_scale_prior: 1e-3, sigma_offset_prior_m: 1000,
///             propagation_speed_m_s: 299691162}]
///   rejection: threshold       # or w-test
///   threshold_m: 100, alpha: 0.001, segment_s: 60, backward_window_s: 60,
///   fix_tolerance_m: 200, max_reduction_s: 10, max_dr_gap_s: 60,
///   bias_model: random-walk    # or gauss-markov
///   bias_sigma_m_s: 1, bias_random_walk_m_s_per_sqrt_s: 0.005, bias_correlation_time_s: 600,
///   statistics_bin_s: 60
///
/// Unknown keys are errors (typos). Errors carry the file, line and key.
NavConfig read_nav_config(const std::string& path);

/// The configuration `nav simulate` writes beside its files dr.csv, stations.csv, lops.csv,
/// truth.csv and (with fixes) fixes.csv: the simulated line's initial position and options, the
/// simulation's σ of speed and heading, numbers in the shortest form that reads back the same;
/// the line's settings as a `# Simulated: …` comment.
std::string nav_simulation_config(const nav::SimulatedLine& line, const nav::SimulationOptions& options);

/// Write the files of a simulated line into the directory `dir` (created when missing), as
/// `nav simulate --out DIR` does: dr.csv, stations.csv, lops.csv, truth.csv, fixes.csv (with
/// fixes) and nav.yaml, each CSV starting `# Simulated: <settings>`. All or none: every file
/// is computed and its temporary written before any is renamed into place. Returns the names
/// written, in that order. IoError when the directory cannot be created or a file written.
std::vector<std::string> write_nav_simulation(const std::string& dir, const nav::SimulatedLine& line,
                                              const nav::SimulationOptions& options);

/// Positions, DR and truth of NMEA 0183 logs (the `nmea:` block), before the plane: DR samples
/// (speed over ground, true heading interpolated circularly from HDT) with the lines of the
/// speed file, GGA fixes (geographic) and the withheld GGA positions as truth. Times: seconds
/// since origin_unix_s, 00:00 UTC of the day of the first epoch.
struct NavNmeaData {
  NavDrFile dr;
  NavFixesFile fixes;
  NavTruthFile truth;
  double origin_unix_s = 0.0;
  bool dated = true;  ///< false: no dates or logger stamps, times of day (from day 0)
  std::vector<std::string> notes;
  /// Per file, the lines the NMEA reader dropped (bad or missing checksum, malformed) with
  /// their counts and first line numbers.
  std::vector<std::string> warnings;
};
NavNmeaData read_nav_nmea(const NavNmeaConfig& config);

/// Every file a configuration names (the configuration first, then dr, stations, lops, fixes,
/// truth and the NMEA logs; absent ones left out): what an output must not overwrite.
std::vector<std::string> nav_input_files(const NavConfig& config);

/// A job as read: the line as observed (nav/survey_line.hpp) and where each of its fields was
/// read, the one field → line table of this reader: rows "dr", "epoch", "stations", "lops",
/// "fixes", "truth" with their CSV column names (none for NMEA logs), and the configuration's
/// keys ("options.<key>" is the key <key>; any other field its innermost key, the document
/// itself as the fallback).
struct NavJob {
  nav::SurveyLine line;
  SourceMap sources;
};

/// Read everything the configuration names into a nav::SurveyLine: the CSV files or the NMEA
/// logs, station and chain names resolved, truth in time order, the configuration's initial
/// position, projection, σ and options. Errors: those of the readers; InputError naming the
/// LOP file's line for an unknown station or chain, the configuration's key for a σ of the
/// other kind of DR, the DR file for fewer than 2 samples.
NavJob read_nav_job(const NavConfig& config);

/// The runner's result: the job as read and its processed line (nav::process(SurveyLine): the
/// Result carries the projection, the notes and the sources of its observations).
struct NavRun {
  NavJob job;
  nav::Result result;
};

/// read_nav_job, then nav::process with the errors located (io::located): an error about an
/// element ("lops[12].value_m", "dr[5].time_s", "epoch 5") gets the file, line and column of
/// that element; about options, chains and the initial position the configuration's file,
/// line and key. The class of the error is kept.
NavRun run_nav(const NavConfig& config, Progress* progress = nullptr);

}  // namespace meridian::io
