#pragma once
/// \file geoid_grid.hpp
/// Geoid height grids (the nodes of a PROJ/NOAA `.gtx` or GeographicLib `.pgm`
/// file, read by io/gravity_geoid_grid.hpp), with bilinear or bicubic
/// interpolation. Deflections from differencing a grid are a labelled fallback
/// only (see grid_deflection_fallback).

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace meridian::gravity {

/// A regular latitude/longitude grid of geoid heights (metres). Node (r, c)
/// lies at latitude first_lat_rad + r·dlat_rad, longitude
/// first_lon_rad + c·dlon_rad (dlat may be negative: rows north to south;
/// dlon is positive).
class GeoidGrid {
 public:
  /// GTX's no-data value (NOAA VDatum, PROJ).
  static constexpr float kGtxNoData = -88.8888f;
  /// Nodes with |value| above this hold no data. The Earth's geoid lies
  /// within about −107 m (south of India) and +86 m (New Guinea) in EGM2008;
  /// 150 m leaves room for any model or datum while catching fill values
  /// such as 9999 or −32768 that are not flagged as GTX no-data.
  static constexpr double kMaxGeoidHeight_m = 150.0;

  std::string source_file;
  std::string format;            ///< "gtx" or "pgm"
  double first_lat_rad = 0, first_lon_rad = 0, dlat_rad = 0, dlon_rad = 0;
  int rows = 0, cols = 0;
  /// Covers all longitudes: cols·Δλ reaches 360° with or without a repeated
  /// first column (360°/Δλ a whole number); column indices are then taken
  /// modulo lon_period_cols.
  bool wraps_longitude = false;
  int lon_period_cols = 0;  ///< columns per 360° when wraps_longitude
  /// `.pgm` header comments `# Key value` as read (Description, DateTime,
  /// Vertical_Datum, …; Offset and Scale included); empty for `.gtx`, whose
  /// header holds only the geometry.
  std::map<std::string, std::string> metadata;

  /// The value stored at node (r, c) in metres (0 ≤ r < rows, 0 ≤ c < cols),
  /// no-data values included.
  double stored_m(int r, int c) const noexcept {
    const std::size_t k = static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c);
    if (!u16_.empty()) return offset_m_ + scale_m_ * u16_[k];
    return static_cast<double>(f32_[k]);
  }
  /// Height at node (r, c) in metres; nullopt where the node holds no data:
  /// kGtxNoData, a value that is not finite, or |value| > kMaxGeoidHeight_m.
  std::optional<double> node_m(int r, int c) const noexcept;

  /// Set wraps_longitude and lon_period_cols from `cols` and the longitude step as the file
  /// states it, `dlon_deg` (degrees): the grid wraps when cols·Δλ reaches 360° (with or
  /// without a repeated first column) and 360°/Δλ is a whole number (to 1e-9 relative).
  /// Readers call it once the geometry is set.
  void set_longitude_period(double dlon_deg) noexcept;

  // Storage (readers fill one of them).
  std::vector<float> f32_;          ///< gtx: float32 heights, −88.8888 = no data
  std::vector<std::uint16_t> u16_;  ///< pgm: raw pixels, height = offset + scale · pixel
  double offset_m_ = 0, scale_m_ = 1;
};

enum class GridInterpolation { Bilinear, Bicubic };

/// "bilinear" or "bicubic", as the CLI option and the JSON output name them.
const char* to_string(GridInterpolation interpolation) noexcept;

/// An interpolated geoid height and how it was obtained.
struct GridHeight {
  double geoid_m = 0;
  GridInterpolation used = GridInterpolation::Bicubic;  ///< may be Bilinear where Bicubic was asked (see note)
  std::string note;  ///< why the interpolation used differs from the one asked; empty when it does not
};

/// Interpolated geoid height at geodetic (lat_rad, lon_rad). The longitude
/// is reduced modulo 360° to the grid's longitudes first (a grid on
/// 230°–250° E takes −124.5°; one on 172°–190° E takes −179°). Bilinear uses
/// the 4 nodes around the point (GeographicLib's Geoid with cubic = false);
/// bicubic is Keys' cubic convolution (a = −1/2; exact for quadratics) on
/// the 4×4 nodes around it. Only nodes with a non-zero weight are needed.
/// Bicubic falls back to bilinear (GridHeight::used, note) where its 4×4
/// nodes are not all inside the grid, or where a needed one of them holds
/// no data but the 4 bilinear nodes do. Throws InputError with field "lat"
/// or "lon" for a coordinate that is not finite, a latitude outside ±90° or
/// outside the grid, a longitude outside a regional grid; and with field
/// "node(r,c)" naming the node, its position and value when a node the
/// interpolation needs holds no data (GeoidGrid::node_m) — never a height
/// computed from a no-data value.
GridHeight grid_geoid_height(const GeoidGrid& grid, double lat_rad, double lon_rad,
                             GridInterpolation interpolation = GridInterpolation::Bicubic);

/// grid_geoid_height(...).geoid_m.
double grid_geoid_height_m(const GeoidGrid& grid, double lat_rad, double lon_rad,
                           GridInterpolation interpolation = GridInterpolation::Bicubic);

/// FALLBACK ONLY — deflection from the grid's slope: ξ = −∂N/∂(north
/// distance), η = −∂N/∂(east distance), central differences of the
/// interpolated surface over one grid step on the ellipsoid (a_m, f).
/// Inaccurate (quantisation, interpolation slope discontinuities, the grid's
/// smoothing); prefer a spherical-harmonic model (GravityField). Throws as
/// grid_geoid_height for any of the four neighbours.
struct GridDeflection {
  double xi_rad = 0, eta_rad = 0;
  const char* method = "grid-gradient fallback (not a spherical-harmonic deflection)";
};
GridDeflection grid_deflection_fallback(const GeoidGrid& grid, double lat_rad, double lon_rad,
                                        double a_m = 6378137.0, double f = 1 / 298.257223563,
                                        GridInterpolation interpolation = GridInterpolation::Bicubic);

/// What a grid file says about the model its heights come from. A `.gtx`
/// says nothing; a GeographicLib `.pgm` names it in `# Description` at most.
/// None of the formats states the degree, GM, reference radius, tide system
/// or normalisation, so `warnings` always says so.
struct GridModelInfo {
  std::string format;                    ///< "gtx" or "pgm"
  std::optional<std::string> model;      ///< `.pgm` Description, when given
  std::map<std::string, std::string> metadata;  ///< GeoidGrid::metadata
  std::vector<std::string> warnings;     ///< what the file does not state
};
GridModelInfo grid_model_info(const GeoidGrid& grid);

/// `meridian gravity geoid-grid`: N and the labelled fallback deflection at one point.
struct GridPointResult {
  std::string grid_file;  ///< GeoidGrid::source_file
  GridModelInfo grid;
  GridInterpolation interpolation = GridInterpolation::Bicubic;       ///< asked for
  GridInterpolation interpolation_used = GridInterpolation::Bicubic;  ///< GridHeight::used
  double lat_rad = 0, lon_rad = 0;  ///< as given (the longitude not reduced)
  double geoid_m = 0;               ///< grid_geoid_height
  /// grid_deflection_fallback on the default ellipsoid with the same
  /// interpolation (FALLBACK ONLY); nullopt when a neighbour is unavailable.
  std::optional<GridDeflection> fallback;
  std::string fallback_unavailable;  ///< why fallback is nullopt
  std::vector<std::string> notes;    ///< GridHeight::note, when there is one
};

/// grid_geoid_height and grid_deflection_fallback at one point. Errors as
/// grid_geoid_height's for N; a failure of the deflection (a neighbour outside
/// the grid or without data) only leaves `fallback` empty, with the reason.
GridPointResult evaluate_grid_point(const GeoidGrid& grid, double lat_rad, double lon_rad,
                                    GridInterpolation interpolation = GridInterpolation::Bicubic);

}  // namespace meridian::gravity
