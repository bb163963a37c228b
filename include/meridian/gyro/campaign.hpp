#pragma once
/// \file campaign.hpp
/// A complete station campaign (spec §7): instrument, calibration on a
/// known line before and after, determinations on the unknown line, and the
/// azimuth chain down to the grid azimuth, with tolerance checks.

#include <optional>
#include <string>
#include <vector>

#include "meridian/core/dms.hpp"
#include "meridian/core/progress.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/azimuth_chain.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/gyro/azimuth_chain.hpp"
#include "meridian/gyro/calibration.hpp"
#include "meridian/gyro/deflection_model.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/error_sources.hpp"
#include "meridian/gyro/instrument_spec.hpp"
#include "meridian/gyro/regulations.hpp"

namespace meridian::gyro {

/// A survey point: geographic or grid coordinates (at least one).
struct PointInput {
  std::string name;
  std::optional<double> lat_rad, lon_rad;   ///< geodetic latitude/longitude (radians)
  std::optional<double> x_north_m, y_east_m; ///< grid coordinates on the campaign grid
  std::optional<Uncertain> eta_rad;          ///< η at this point (radians), if known
  /// Ellipsoidal height (m), used to evaluate ξ, η from a gravity model (0
  /// with a note when absent: they change by well under 0.1″ per 100 m) and,
  /// at both ends of a line, for the zenith distance of its sight.
  std::optional<double> height_m;
  /// ξ at this point (radians, astro − geodetic, north component), if known.
  std::optional<Uncertain> xi_rad{};
  /// Half the last booked digit of x and y (m; 0.0005 for coordinates booked to 1 mm), as
  /// the reader saw the text. Unset: inferred from the shortest text of the number (which
  /// drops trailing zeros, so never tighter than booked).
  std::optional<double> x_half_unit_m{}, y_half_unit_m{};
};

/// The known line's azimuth and its kind (converted to astronomic by the
/// geodesy azimuth chain).
struct KnownAzimuth {
  using Kind = geodesy::AzimuthKind;
  Kind kind = Kind::Astronomic;
  Uncertain value_rad;
};

struct KnownLineInput {
  PointInput from;                           ///< where the gyro stands
  std::optional<PointInput> to;              ///< the known target (for δ with a grid azimuth)
  KnownAzimuth azimuth;
  /// Booked zenith angle of the sight from → to (radians, 10°…170°); else
  /// from the heights of both points; else horizontal.
  std::optional<double> zenith_angle_rad;
  std::vector<DeterminationInput> before;    ///< each with a target reading
  std::vector<DeterminationInput> after;
};

struct LineInput {
  PointInput from;                           ///< station C
  std::optional<PointInput> to;              ///< target D (grid coordinates give δ)
  /// Booked zenith angle of the sight C → D (radians, 10°…170°); else from
  /// the heights of C and D; else horizontal.
  std::optional<double> zenith_angle_rad;
  std::vector<DeterminationInput> determinations;  ///< each with a target reading
};

/// The record sheet (记录表) of a job: who observed, booked, computed and
/// checked it, when and in what conditions, as booked (free text). Shown in
/// the reports; only the observers enter a check (the regulations want the
/// same observer above and below ground).
struct RecordSheet {
  std::string observer;      ///< of every run unless a run names its own
  std::string booker;
  std::string computed_by;
  std::string checked_by;
  std::string date;
  std::string weather;       ///< e.g. "surface overcast, wind 2 m/s; underground 1.2 m/s"
  std::string temperature;   ///< e.g. "surface 6 C, underground 24 C"
  std::string remarks;
  /// The language of the result sheet: "en" (or empty) English; "zh" Chinese labels with the
  /// English term beside each (坐标方位角 grid azimuth), as a mine files it.
  std::string language;
};

struct CampaignInput {
  std::string name;
  RecordSheet record;
  InstrumentSpec instrument;
  geodesy::GridDefinition grid;
  std::optional<KnownLineInput> known_line;
  /// E given directly (signed, radians) when there is no known line.
  std::optional<Uncertain> instrument_constant_rad;
  LineInput line;
  Tolerances tolerances;                     ///< overrides of the class limits (regulations.hpp)
  ReduceOptions options;
  /// A gravity model giving ξ, η at the points that do not state them; loaded
  /// by the caller (see deflection_model.hpp).
  std::optional<GravityModelRef> gravity_model;
  AngleUnit angle_unit = AngleUnit::Dms;  ///< the file's `angle_unit:`, as ReduceInput's
  /// The stochastic model of the reversal readings of every tracking determination (the file's
  /// `stochastic_model:`; stochastic_determination.hpp). A determination for which it cannot be
  /// used keeps white noise, with a warning. White (default): results as without the option.
  StochasticChoice stochastic_model = StochasticChoice::White;
  /// The campaign file it was read from, as named (for the reports; empty when
  /// the Input is built in code). Never opened by the library.
  std::string file;
};

/// A point resolved in both coordinate systems.
struct PointResult {
  std::string name;
  double lat_rad = 0, lon_rad = 0;
  geodesy::GridPoint grid;
};

/// Unit of a check's value and tolerance.
enum class CheckUnit { Arcsec, Div, Runs, Observers, Checks, Entries, Seconds };
/// "arcsec", "div", "runs", "observers", "checks", "entries" (a field booked: 1, or not: 0), "s"
std::string to_string(CheckUnit u);

/// A pass/fail check for the report: `value` against the limit `tolerance`
/// (at most, or at least for a minimum such as a number of runs).
struct Check {
  std::string name;
  double value = 0.0;       ///< in `unit`
  double tolerance = 0.0;   ///< the limit, in `unit`
  CheckUnit unit = CheckUnit::Arcsec;
  bool pass = true;
  bool minimum = false;     ///< true: the value must be at least the limit
  bool signed_value = false;  ///< the value has a sign; the check is |value| ≤ tolerance
  std::string source;       ///< where the limit comes from (regulations, class, the file, Meridian)
  /// The input field the check is about, as a field path of the Input
  /// ("line.determinations[1].target_rounds[0]"; empty: the job as a whole).
  /// The runner's io::SourceMap turns it into the file and line.
  std::string field;
};


struct CampaignResult {
  /// What was processed (a copy of the Input): the writers show its file, its
  /// observations, the record sheet and the angle unit.
  CampaignInput input;
  std::string name;
  PointResult station;                       ///< C
  std::optional<PointResult> target;         ///< D
  std::optional<PointResult> known_station;
  std::optional<PointResult> known_target;
  std::optional<KnownAzimuth> known_azimuth_given;  ///< the known line's azimuth as given, with its kind
  ResolvedInstrument instrument_station;     ///< constants at C
  std::optional<ResolvedInstrument> instrument_known;  ///< constants at the known station
  std::vector<DeterminationResult> known_before, known_after;
  std::vector<Uncertain> known_gyro_azimuths_before, known_gyro_azimuths_after;
  std::optional<Uncertain> known_astronomic_azimuth_rad;
  std::optional<InstrumentConstantResult> instrument_constant;
  Uncertain instrument_constant_used_rad;
  std::vector<DeterminationResult> determinations;
  std::vector<Uncertain> gyro_azimuths;      ///< A_G per determination of the unknown line
  AzimuthMean gyro_azimuth_mean;
  AzimuthChainResult chain;
  RegulationLimits limits;                   ///< the limits the checks used
  RecordSheet record;                        ///< as booked (for the reports)
  /// The campaign's stochastic_model (each determination's own request and what was used:
  /// DeterminationResult::stochastic).
  StochasticChoice stochastic_model = StochasticChoice::White;
  std::string instrument_name, instrument_serial;
  std::vector<Check> checks;
  /// One-run standard deviations (一次测定中误差, AzimuthMean::one_run_sigma)
  /// of the instrument constants on the known line and of the gyro azimuths
  /// on the line (radians), where there are two runs or more.
  std::optional<double> constant_one_run_sigma_rad;
  std::optional<double> line_one_run_sigma_rad;
  /// Grid azimuth of the known line from its end points' coordinates (chord,
  /// atan2(Δy, Δx)), when both are given.
  std::optional<double> known_grid_azimuth_from_coordinates_rad;
  /// Grid azimuth of the line C→D from its end points' coordinates (the
  /// traverse's 坐标方位角, geodesy::grid_azimuth), when both are given; the
  /// record sheet shows chain.grid_azimuth_rad minus it (gyro − traverse).
  std::optional<double> line_grid_azimuth_from_coordinates_rad;
  /// The parts of σ(chain.grid_azimuth_rad) that another orientation of the
  /// line may share (error_sources.hpp); their Σ c² ≤ σ(T)², the rest is this
  /// campaign's own.
  std::vector<ErrorSource> shared_error_sources;
  std::vector<std::string> notes;
  std::vector<std::string> warnings;
  bool all_checks_pass() const;
};

/// Resolve a point on the grid: grid coordinates are authoritative when
/// given (the geographic ones are then only checked; a difference above 1″
/// adds a warning), else the geographic ones are projected. Errors carry
/// `field` as their field path.
PointResult resolve_point(const PointInput& p, const geodesy::TransverseMercatorGrid& grid,
                          const std::string& field, std::vector<std::string>& warnings);

/// Process a campaign: the instrument constant from the known line (or as
/// given), every determination of the line, the tolerance checks and the
/// azimuth chain to the grid azimuth. Errors carry field paths such as
/// "line.determinations[1].crossings[0].times_s" (the runner's io::SourceMap adds
/// the file and line). `progress`, when given, is told about each determination
/// reduced. `deflection`, when given, supplies ξ and η at the points that do
/// not state them; it is required when the input names a gravity_model
/// (InputError otherwise).
CampaignResult process(const CampaignInput& in, Progress* progress = nullptr,
                       const DeflectionModel* deflection = nullptr);

}  // namespace meridian::gyro
