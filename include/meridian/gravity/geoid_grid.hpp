#pragma once
/// \file geoid_grid.hpp
/// Geoid height grids: PROJ/NOAA `.gtx` (e.g. Debian proj-data's
/// `egm96_15.gtx`) and GeographicLib `.pgm` geoid files, with bilinear or
/// bicubic interpolation. Deflections from differencing a grid are a
/// labelled fallback only (see grid_deflection_fallback).

#include <cstdint>
#include <limits>
#include <filesystem>
#include <string>
#include <vector>

namespace meridian::gravity {

/// A regular latitude/longitude grid of geoid heights (metres). Node (r, c)
/// lies at latitude first_lat_rad + r·dlat_rad, longitude
/// first_lon_rad + c·dlon_rad (dlat may be negative: rows north to south).
class GeoidGrid {
 public:
  std::string source_file;
  std::string format;            ///< "gtx" or "pgm"
  double first_lat_rad = 0, first_lon_rad = 0, dlat_rad = 0, dlon_rad = 0;
  int rows = 0, cols = 0;
  bool wraps_longitude = false;  ///< covers all longitudes (column index taken modulo the period)
  int lon_period_cols = 0;       ///< columns per 360° when wraps_longitude

  /// Height at node (r, c) in metres; NaN where the file has no data.
  double node_m(int r, int c) const noexcept {
    const std::size_t k = static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c);
    if (!u16_.empty()) return offset_m_ + scale_m_ * u16_[k];
    const float v = f32_[k];
    return v == -88.8888f ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(v);
  }

  // Storage (readers fill one of them).
  std::vector<float> f32_;          ///< gtx: float32 heights, −88.8888 = no data
  std::vector<std::uint16_t> u16_;  ///< pgm: raw pixels, height = offset + scale · pixel
  double offset_m_ = 0, scale_m_ = 1;
};

/// Read a `.gtx` (big-endian header: south latitude, west longitude, Δlat,
/// Δlon in degrees, rows, cols; then float32 heights, south row first) or a
/// GeographicLib `.pgm` (P5, 16-bit, `# Offset`, `# Scale`, rows from 90°N,
/// columns from 0°E over 360°). Errors (ParseError/IoError naming the file):
/// bad header, sizes, truncated data.
GeoidGrid read_geoid_grid(const std::filesystem::path& path);

enum class GridInterpolation { Bilinear, Bicubic };

/// "bilinear" or "bicubic", as the CLI option and the JSON output name them.
const char* to_string(GridInterpolation interpolation) noexcept;

/// Interpolated geoid height (m) at geodetic (lat_rad, lon_rad). Bicubic is
/// Keys' cubic convolution (a = −1/2; exact for quadratics) on the 4×4
/// nodes around the point, falling back to bilinear where those are not all
/// inside the grid. Throws InputError outside the grid or where a needed
/// node has no data.
double grid_geoid_height_m(const GeoidGrid& grid, double lat_rad, double lon_rad,
                           GridInterpolation interpolation = GridInterpolation::Bicubic);

/// FALLBACK ONLY — deflection from the grid's slope: ξ = −∂N/∂(north
/// distance), η = −∂N/∂(east distance), central differences of the
/// interpolated surface over one grid step on the ellipsoid (a_m, f).
/// Inaccurate (quantisation, interpolation slope discontinuities, the grid's
/// smoothing); prefer a spherical-harmonic model (GravityField).
struct GridDeflection {
  double xi_rad = 0, eta_rad = 0;
  const char* method = "grid-gradient fallback (not a spherical-harmonic deflection)";
};
GridDeflection grid_deflection_fallback(const GeoidGrid& grid, double lat_rad, double lon_rad,
                                        double a_m = 6378137.0, double f = 1 / 298.257223563);

/// `meridian gravity geoid-grid`: N and the labelled fallback deflection at one point.
struct GridPointResult {
  std::string grid_file;  ///< GeoidGrid::source_file
  GridInterpolation interpolation = GridInterpolation::Bicubic;
  double lat_rad = 0, lon_rad = 0;
  double geoid_m = 0;       ///< grid_geoid_height_m
  GridDeflection fallback;  ///< grid_deflection_fallback on the default ellipsoid (FALLBACK ONLY)
};

/// grid_geoid_height_m and grid_deflection_fallback at one point (errors as theirs).
GridPointResult evaluate_grid_point(const GeoidGrid& grid, double lat_rad, double lon_rad,
                                    GridInterpolation interpolation = GridInterpolation::Bicubic);

}  // namespace meridian::gravity
