#pragma once
/// \file campaign.hpp
/// A complete station campaign (spec §7): instrument, calibration on a
/// known line before and after, determinations on the unknown line, and the
/// azimuth chain down to the grid azimuth, with tolerance checks.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/gyro/azimuth_chain.hpp"
#include "meridian/gyro/calibration.hpp"
#include "meridian/gyro/determination.hpp"
#include "meridian/gyro/instrument_spec.hpp"

namespace meridian::gravity {
class GravityField;
}

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

/// η from a global gravity model for points whose η is not given (spec §6,
/// step 3). The model's plumb-line direction at the point is used: η =
/// (Λ − λ)·cos φ of the model's gravity vector (gravity::FieldValues::eta_astro_rad).
struct DeflectionModel {
  std::shared_ptr<const gravity::GravityField> field;
  std::string source;                        ///< name or path as given (for notes and writers)
  std::string description;                   ///< e.g. "EGM2008 (degree 2190)"
  double sigma_eta_rad = 1.5 * units::kArcsecond;  ///< commission error assumed for η
};

/// The known line's azimuth and its kind.
struct KnownAzimuth {
  enum class Kind { Astronomic, Geodetic, Grid } kind = Kind::Astronomic;
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
  double zero_position_div = 0.5;
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
  std::optional<DeflectionModel> deflection_model;
};

/// A point resolved in both coordinate systems.
struct PointResult {
  std::string name;
  double lat_rad = 0, lon_rad = 0;
  geodesy::GridPoint grid;
};

/// A pass/fail check for the report.
struct Check {
  std::string name;
  double value = 0.0;       ///< in `unit`
  double tolerance = 0.0;   ///< in `unit`
  std::string unit;         ///< "arcsec" or "div"
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

/// Process a campaign. Errors carry field paths such as
/// "line.determinations[1].crossings[0].times_s" (the reader adds file/line).
/// `progress`, when given, is told about each determination reduced.
CampaignResult process_campaign(const CampaignInput& in, Progress* progress = nullptr);

}  // namespace meridian::gyro
