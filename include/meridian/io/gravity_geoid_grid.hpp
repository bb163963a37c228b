#pragma once
/// \file gravity_geoid_grid.hpp
/// Geoid height grid files: PROJ/NOAA `.gtx` (e.g. Debian proj-data's `egm96_15.gtx`) and
/// GeographicLib `.pgm` geoid files, read into gravity::GeoidGrid (plain data: the nodes'
/// geometry and stored values), which gravity/geoid_grid.hpp interpolates.

#include <filesystem>

#include "meridian/gravity/geoid_grid.hpp"

namespace meridian::io {

/// Read a `.gtx` (big-endian header: south latitude, west longitude, Δlat,
/// Δlon in degrees, rows, cols; then float32 heights, south row first) or a
/// GeographicLib `.pgm` (P5, 16-bit, `# Offset`, `# Scale`, rows from 90°N,
/// columns from 0°E over 360°), chosen by the extension (case-insensitive).
/// Errors (ParseError/IoError naming the file): bad header (a `.gtx` origin outside
/// [−90°, 90°] × [−360°, 360°], steps not in [1e-6°, 180°] and [1e-6°, 360°], fewer than 2
/// rows or columns, rows beyond the pole, columns spanning more than 360° plus one repeated
/// column), sizes, truncated or over-long data, `.pgm` header text that is not UTF-8;
/// InputError for another extension.
gravity::GeoidGrid read_geoid_grid(const std::filesystem::path& path);

}  // namespace meridian::io
