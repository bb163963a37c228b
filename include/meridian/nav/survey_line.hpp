#pragma once
/// \file survey_line.hpp
/// A survey line as observed (shared/spec/navigation.md §7; docs/navigation.md, "Geographic
/// input and the plane"): positions in a plane or geographic, true DR speeds and headings or
/// velocity components, LOP values as ground lengths or LORAN time differences, the map
/// projection as data, and the source (file, line) of every record. `to_plane` turns it into
/// the nav::Input of the methods; `process` runs them and returns a self-describing Result
/// (the projection, the reader's notes and the source of every rejected observation).
///
///   reader (io/nav_files.hpp) → SurveyLine → process(line) → Result → writers (report/nav_*.hpp)
///
/// The plane (x = north, y = east, m): the line's projection, else a local transverse Mercator
/// on WGS 84 whose central meridian is the first geographic position's longitude rounded to
/// 0.1° when any position is geographic, else the coordinates as given (no projection).
/// Positions go through geodesy::TransverseMercatorGrid::forward; a true DR velocity (heading α
/// clockwise from true north, or v_north, v_east) becomes a grid velocity by the rotation
/// T = α − γ and the point scale k, both evaluated along the dead-reckoned track from the initial
/// position; a fix's σ north, σ east is rotated by −γ and scaled by k; LOP values (ground
/// lengths) become grid lengths with the line scale factor of each ship–station distance
/// (Simpson's rule, the ship at its dead-reckoned position at the LOP's time). Without a
/// projection headings are taken as grid azimuths and LOP values as plane lengths, as given.
/// Time differences τ become range differences L = c·τ with the chain's propagation speed c.
///
/// Errors: InputError with the field paths of this struct, which a runner's io::SourceMap turns
/// into the file, line and column of the record: "stations[k].position", "fixes[k].position",
/// "truth[k].position" (the projection cannot take it), "dr[k].heading_rad" (speed and heading)
/// or "dr[k].v_north_m_s" (velocity components: the dead-reckoned position leaves the
/// projection), "lops[k]" (likewise at a LOP), "initial" (the initial position, or no fix near the
/// first DR epoch to give it), "projection" (plane and geographic positions without one); then
/// those of nav::process (navigation.hpp) with the same indices.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/nav/navigation.hpp"
#include "meridian/nav/observations.hpp"

namespace meridian::nav {

/// LORAN-C propagation speed over sea water (m/s), the default of LineChain: the conversion
/// L = c·τ of a time difference τ.
inline constexpr double kLoranPropagationSpeed_m_s = 299691162.0;
/// Default σ of a DR speed (m/s) and heading (degrees) and of each velocity component (m/s)
/// when the line gives none (a note says so).
inline constexpr double kDefaultSigmaSpeed_m_s = 0.05;
inline constexpr double kDefaultSigmaHeading_deg = 0.2;
/// Without an initial position, the fix nearest the first DR epoch and at most this far from it
/// in time (s) gives it.
inline constexpr double kInitialFixWindow_s = 5.0;

/// Where a record was read: file and 1-based line (empty file: made by a program).
struct SourceLine {
  std::string file;
  int line = 0;
};

/// A position as written: plane (x north, y east, m) or geographic (radians).
struct Position {
  bool geographic = false;
  double x_north_m = 0.0, y_east_m = 0.0;
  double lat_rad = 0.0, lon_rad = 0.0;
};

/// What a DR record gives.
enum class DrKind {
  SpeedHeading,  ///< speed over ground (m/s, ≥ 0) and heading (rad, true; grid without projection)
  Velocity,      ///< velocity components v_north, v_east (m/s, true; grid without projection)
};

/// One DR record (the velocity of the interval that ends at time_s).
struct DrRecord {
  double time_s = 0.0;
  double speed_m_s = 0.0, heading_rad = 0.0;    ///< DrKind::SpeedHeading
  double v_north_m_s = 0.0, v_east_m_s = 0.0;   ///< DrKind::Velocity
  SourceLine source;
};

struct StationRecord {
  std::string name;
  Position position;
  SourceLine source;
};

/// A chain with the propagation speed of its time differences.
struct LineChain {
  Chain chain;
  double propagation_speed_m_s = kLoranPropagationSpeed_m_s;  ///< > 0
};

/// Kind of a LOP as observed.
enum class LopKind { Range, RangeDifference, TimeDifference };

struct LopRecord {
  double time_s = 0.0;
  LopKind kind = LopKind::Range;
  std::size_t station = 0;   ///< index into SurveyLine::stations
  std::size_t station2 = 0;  ///< the second station of a difference
  std::size_t chain = Lop::kNoChain;  ///< index into SurveyLine::chains, or Lop::kNoChain
  double value_m = 0.0;              ///< a range or range difference on the ground (m)
  double time_difference_us = 0.0;   ///< LopKind::TimeDifference: τ (µs, as LORAN-C states it)
  double sigma_m = 0.0;
  SourceLine source;
};

struct FixRecord {
  double time_s = 0.0;
  Position position;
  double sigma_north_m = 0.0, sigma_east_m = 0.0;  ///< on the ground (geographic) or the plane
  SourceLine source;
};

struct TruthRecord {
  double time_s = 0.0;
  Position position;
  SourceLine source;
};

/// The line as observed. Indices of dr, lops, fixes and truth are those of the nav::Input that
/// to_plane makes (truth in time order).
struct SurveyLine {
  DrKind dr_kind = DrKind::SpeedHeading;
  std::vector<DrRecord> dr;  ///< at least 2
  std::vector<StationRecord> stations;
  std::vector<LineChain> chains;
  std::vector<LopRecord> lops;
  std::vector<FixRecord> fixes;
  std::vector<TruthRecord> truth;
  std::optional<geodesy::GridDefinition> projection;  ///< absent: see the file comment
  /// Absent: the fix nearest the first DR epoch within kInitialFixWindow_s (Input::initial_fix).
  std::optional<Position> initial;
  std::optional<double> initial_sigma_m;  ///< absent: InitialPosition's default (a note says so)
  SourceLine initial_source;              ///< where `initial` was given (its file names it)
  /// σ of DR speed (m/s) and heading (rad) samples, of DR velocity components (m/s); absent:
  /// the defaults above (a note says so).
  std::optional<double> sigma_speed_m_s, sigma_heading_rad, sigma_velocity_m_s;
  Options options;
  /// What the reader did (defaults, samples skipped) and dropped (lines not read): appended to
  /// Result::notes and Result::warnings.
  std::vector<std::string> notes, warnings;
};

/// The line in the plane of the methods.
struct PlaneLine {
  Input input;
  std::optional<geodesy::GridDefinition> projection;  ///< the plane's, when it has one
  std::vector<std::string> notes;  ///< the plane, defaults used, conversions made
};

/// The line in its plane (file comment).
PlaneLine to_plane(const SurveyLine& line);

/// to_plane, then process(Input): the Result with its projection, the notes of the reader and
/// of to_plane after those of the methods, the reader's warnings, and the source
/// ("lops.csv:14") of every rejected and skipped observation.
Result process(const SurveyLine& line, Progress* progress = nullptr);

}  // namespace meridian::nav
