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
#include "meridian/gyro/instrument_spec.hpp"

namespace meridian::gyro {

/// A survey point: geographic or grid coordinates (at least one).
struct PointInput {
  std::string name;
  std::optional<double> lat_rad, lon_rad;   ///< geodetic latitude/longitude (radians)
  std::optional<double> x_north_m, y_east_m; ///< grid coordinates on the campaign grid
  std::optional<Uncertain> eta_rad;          ///< η at this point (radians), if known
  /// Ellipsoidal height (m), used to evaluate η from a gravity model; 0 with
  /// a note when absent (η changes by well under 0.1″ per 100 m).
  std::optional<double> height_m;
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
  std::vector<DeterminationInput> before;    ///< each with a target reading
  std::vector<DeterminationInput> after;
};

struct LineInput {
  PointInput from;                           ///< station C
  std::optional<PointInput> to;              ///< target D (grid coordinates give δ)
  std::vector<DeterminationInput> determinations;  ///< each with a target reading
};

struct Tolerances {
  std::optional<double> determination_difference_rad;  ///< default from the accuracy class
  std::optional<double> instrument_constant_difference_rad;  ///< default: same as above
  double zero_position_div = kDefaultZeroPositionTolerance_div;
};

struct CampaignInput {
  std::string name;
  InstrumentSpec instrument;
  geodesy::GridDefinition grid;
  std::optional<KnownLineInput> known_line;
  /// E given directly (signed, radians) when there is no known line.
  std::optional<Uncertain> instrument_constant_rad;
  LineInput line;
  Tolerances tolerances;
  ReduceOptions options;
  /// A gravity model giving η at the points whose η is not stated; loaded
  /// by the caller (see deflection_model.hpp).
  std::optional<GravityModelRef> gravity_model;
  AngleUnit angle_unit = AngleUnit::Dms;  ///< the file's `angle_unit:`, as ReduceInput's
};

/// A point resolved in both coordinate systems.
struct PointResult {
  std::string name;
  double lat_rad = 0, lon_rad = 0;
  geodesy::GridPoint grid;
};

/// Unit of a check's value and tolerance.
enum class CheckUnit { Arcsec, Div };
std::string to_string(CheckUnit u);  ///< "arcsec", "div"

/// A pass/fail check for the report.
struct Check {
  std::string name;
  double value = 0.0;       ///< in `unit`
  double tolerance = 0.0;   ///< in `unit`
  CheckUnit unit = CheckUnit::Arcsec;
  bool pass = true;
};

struct CampaignResult {
  std::string name;
  PointResult station;                       ///< C
  std::optional<PointResult> target;         ///< D
  std::optional<PointResult> known_station;
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
  std::vector<Check> checks;
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
/// "line.determinations[1].crossings[0].times_s" (io::locate_error adds the
/// file and line). `progress`, when given, is told about each determination
/// reduced. `deflection`, when given, supplies η at the points whose η is
/// not stated; it is required when the input names a gravity_model
/// (InputError otherwise).
CampaignResult process(const CampaignInput& in, Progress* progress = nullptr,
                       const DeflectionModel* deflection = nullptr);

}  // namespace meridian::gyro
