#pragma once
/// \file gravity_grid_files.hpp
/// Files of `meridian gravity grid` (issue 14): NetCDF grids (CF-1.8 and
/// COARDS, readable by GMT and QGIS/GDAL) and CSV for small grids, both
/// written atomically (a temporary file beside the target, fsync, rename):
/// on any error, or without commit(), the target is untouched. The layout
/// is documented in docs/file-formats.md, "Gravity grids".
///
/// Units in files (converted here from the library's SI and radians):
/// ξ, η in arc-seconds; N in metres; Δg and the disturbance vector
/// δg_east, δg_north, δg_up in mGal (1 mGal = 1e-5 m/s²). Signs: see
/// GridQuantity (gravity/grid_spec.hpp); each NetCDF variable states its
/// sign convention in its long_name.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <span>
#include <string_view>
#include <vector>

#include "meridian/gravity/grid_spec.hpp"
#include "meridian/gravity/grid_synthesis.hpp"

namespace meridian::io {

/// How one quantity is stored in a file.
struct GridQuantityFormat {
  std::string_view name;       ///< variable / column name: xi, eta, geoid, anomaly, dg_east, dg_north, dg_up
  std::string_view units;      ///< "arcsec", "m" or "mGal"
  double per_si = 1;           ///< file value = library value (rad, m, m/s²) × per_si
  std::string_view long_name;  ///< definition and sign convention, one line (ASCII)
};
GridQuantityFormat grid_quantity_format(gravity::GridQuantity q) noexcept;

enum class GridFileFormat { NetCdf, Csv, Gtx };
/// From the extension: .nc, .grd, .cdf → NetCdf; .csv → Csv; .gtx → Gtx. InputError
/// (field "--output") otherwise.
GridFileFormat grid_file_format_for(const std::filesystem::path& path);
/// "netcdf", "csv" or "gtx" (the `format` of `gravity grid --json`).
std::string_view to_string(GridFileFormat f) noexcept;
/// "NetCDF", "CSV" or "GTX" (the text summary of `gravity grid`).
std::string_view display_name(GridFileFormat f) noexcept;

/// CSV is meant for small grids: more nodes than this are refused (InputError, field "--output").
inline constexpr std::uint64_t kMaxCsvGridNodes = 1'000'000;

/// What a grid file says about where its numbers come from (NetCDF global attributes).
struct GridFileMetadata {
  std::string model_name;   ///< as the model file states it
  std::string model_file;   ///< path it was read from
  int max_degree = 0;       ///< degree evaluated
  std::string tide_system;  ///< as stated by the model file; empty: "not stated"
  gravity::GridPath path = gravity::GridPath::Parallel;  ///< synthesis path used (Fft or Parallel)
  std::string history;      ///< the command line, or empty
  /// Empty: every node at GridSpec::height_m (global attribute height_m). Otherwise where the
  /// per-node heights came from (global attribute height_source; height_m is not written).
  std::string height_source;
  /// The geodetic datum of the nodes' latitudes and longitudes: the model's reference (normal)
  /// ellipsoid, written as the CF grid mapping `crs` (semi-major axis a in metres, inverse
  /// flattening 1/f) with its WKT. Defaults: WGS84.
  double ellipsoid_a_m = 6378137.0;
  double ellipsoid_flattening = 1 / 298.257223563;
};

/// The number of longitude columns a grid file of this format stores for `spec`: its columns,
/// less the repeated column at W + 360° of a global gridline grid in a .gtx (readers wrap).
std::size_t stored_grid_columns(const std::filesystem::path& path, const gravity::GridSpec& spec);

/// The CF `crs_wkt` (WKT1, as GDAL reads and writes it) of geographic coordinates on an
/// ellipsoid: "WGS 84" (EPSG 4326) or "GRS 1980" when a and f are those ellipsoids' (f to 1e-12
/// relative), otherwise an ellipsoid named by its numbers.
std::string geographic_crs_wkt(double a_m, double flattening);

/// Receives the rows of a synthesis and writes them; commit() makes the file appear.
class GridFileWriter {
 public:
  virtual ~GridFileWriter() = default;
  /// One parallel (rows arrive from south to north, as synthesize_grid gives them).
  /// Throws IoError when the write fails, InputError when the row does not fit the spec.
  virtual void write_row(const gravity::GridRow& row) = 0;
  /// Close, flush to disk and rename into place. Throws IoError; also when rows are missing.
  virtual void commit() = 0;
};

/// The checks open_grid_file makes before it creates anything, for a caller
/// that wants them before loading a model: the extension (InputError, field
/// "--output"), a CSV of more than kMaxCsvGridNodes nodes (InputError), a .gtx
/// for anything but the geoid alone (InputError, field "--quantities"), a
/// directory that does not exist or cannot be written (IoError naming the path).
void check_grid_output(const std::filesystem::path& path, const gravity::GridSpec& spec);

/// Open a grid file for `spec` (validated by the caller): the temporary file
/// is created and, for NetCDF, the dimensions, the coordinate variables lon
/// and lat and the attributes are written now, so an unwritable path fails
/// here (IoError naming it) before any synthesis. Throws InputError for an
/// unknown extension or a CSV of more than kMaxCsvGridNodes nodes.
///
/// NetCDF (netCDF-4 classic model, double precision): dimensions lat (rows,
/// south to north) and lon (columns, west to east); coordinate variables
/// lat (degrees_north), lon (degrees_east); one variable per quantity,
/// (lat, lon), in the units above, each with `grid_mapping = "crs"`; GMT's node_offset (0
/// gridline, 1 pixel). The coordinate variables hold the nodes (a pixel grid's cell centres);
/// their `actual_range` is the nodes' range for gridline registration and the cells' outer
/// edges (the region) for pixel registration, as GMT writes it — GDAL and QGIS take a
/// node_offset = 1 grid's extent from it. A CF grid mapping variable `crs`
/// (latitude_longitude, the model's ellipsoid, `crs_wkt`) says the datum.
/// CSV: `lon_deg,lat_deg,<name>_<unit>…` (e.g. xi_arcsec), one line per node, rows
/// from south to north, 10 decimals for coordinates and 9 for values.
/// GTX (NOAA VDatum, read by PROJ and GDAL; geoid heights only): a 40-byte big-endian header
/// (first node's latitude and longitude, latitude and longitude spacing, all float64 degrees;
/// rows and columns, int32), then rows × columns float32 big-endian heights in metres, rows
/// from south to north, each from west to east. The header gives node coordinates, so both
/// registrations are stored as their nodes (a pixel grid's cell centres); a global gridline
/// grid is stored without its repeated last column (E = W + 360°: readers wrap longitudes).
/// float32 rounds a 100 m height to about 4 µm; a height beyond float32's range is a
/// NumericalError naming the node.
std::unique_ptr<GridFileWriter> open_grid_file(const std::filesystem::path& path, const gravity::GridSpec& spec,
                                               const GridFileMetadata& metadata);

/// A NetCDF grid of ellipsoidal heights (metres) at exactly the nodes of a GridSpec, read one
/// parallel at a time (GridSpec::node_heights; `gravity grid --height-grid FILE.nc[?VAR]`).
/// `path` may name the variable after a '?' (GMT's convention); otherwise the file must hold
/// exactly one two-dimensional variable. The variable's dimensions are (lat, lon) with
/// one-dimensional coordinate variables of the same names (also latitude/longitude, y/x);
/// rows may run south to north or north to south. Every node's coordinates must equal the
/// spec's (to 1e-9°; longitudes modulo 360°), a `units` attribute, when present, must be
/// metres, and every value must be finite and not the _FillValue.
class GridHeightFile {
 public:
  /// Opens and checks the file against `spec` (validated by the caller). Throws IoError
  /// (cannot open or read, naming the file) or InputError (field "--height-grid": another
  /// shape, other coordinates, units not metres, no or several candidate variables).
  GridHeightFile(const std::string& path, const gravity::GridSpec& spec);
  ~GridHeightFile();
  GridHeightFile(const GridHeightFile&) = delete;
  GridHeightFile& operator=(const GridHeightFile&) = delete;

  /// Row `row` (0 = southernmost) into heights_m (columns() values). Throws IoError on a read
  /// failure, InputError naming the node for a missing value. Not thread-safe.
  void read_row(std::size_t row, std::span<double> heights_m) const;
  /// A GridHeightSource that reads from this file (which must outlive it).
  gravity::GridHeightSource source() const;
  const std::string& variable() const noexcept { return variable_; }

 private:
  std::string file_, variable_;
  int ncid_ = -1, var_ = -1;
  bool south_first_ = true, has_fill_ = false;
  double fill_ = 0;
  std::size_t rows_ = 0, columns_ = 0;
  std::vector<double> lat_deg_, lon_deg_;  // of the spec's nodes, for messages
};

}  // namespace meridian::io
