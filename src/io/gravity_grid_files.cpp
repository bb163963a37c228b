#include "meridian/io/gravity_grid_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <netcdf.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/core/version.hpp"
#include "gravity_text.hpp"

namespace meridian::io {
namespace {

using gravity::GridQuantity;
using gravity::GridRow;
using gravity::GridSpec;

void check_row(const GridSpec& spec, const GridRow& row, std::size_t expected_row, const std::filesystem::path& p) {
  if (row.row != expected_row || row.columns != spec.columns() ||
      row.data.size() != spec.columns() * spec.quantities.size())
    throw InputError(fmt::format("grid row {} ({} columns) does not fit the grid (row {} of {} expected, {} columns)",
                                 row.row, row.columns, expected_row, spec.rows(), spec.columns()),
                     {p.string(), std::nullopt, {}});
}

// ---- NetCDF ----

class NetCdfGridWriter final : public GridFileWriter {
 public:
  NetCdfGridWriter(std::filesystem::path path, const GridSpec& spec, const GridFileMetadata& meta)
      : path_(std::move(path)), spec_(spec) {
    namespace fs = std::filesystem;
    const fs::path dir = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
    // Room for the whole file first: libhdf5 cannot close a file whose writes failed and
    // crashed at exit on a full disk (issue 35). The data are doubles, chunked, uncompressed.
    struct statvfs fsinfo {};
    if (::statvfs(dir.c_str(), &fsinfo) == 0) {
      const double need = static_cast<double>(spec.rows()) * static_cast<double>(spec.columns()) *
                              static_cast<double>(spec.quantities.size()) * 8.0 +
                          static_cast<double>(spec.rows() + spec.columns()) * 8.0 + 65536.0;
      const double free_bytes = static_cast<double>(fsinfo.f_bavail) * static_cast<double>(fsinfo.f_frsize);
      if (free_bytes < need)
        throw IoError(fmt::format("the NetCDF grid needs about {:.1f} MB and {} has {:.1f} MB free", need / 1e6,
                                  dir.string(), free_bytes / 1e6),
                      {path_.string(), std::nullopt, {}});
    }
    tmp_ = (dir / ("." + path_.filename().string() + ".tmp.XXXXXX")).string();
    const int fd = ::mkstemp(tmp_.data());
    if (fd < 0)
      throw IoError(fmt::format("cannot create a temporary file in {}: {}", dir.string(), std::strerror(errno)),
                    {path_.string(), std::nullopt, {}});
    ::close(fd);
    created_ = true;
    guard_.reset(tmp_);
    // A constructor that throws runs no destructor: clean up here (a failed create or define
    // left the temporary file behind; issue 35, the full-disk shim of the CLI tests).
    try {
      check(nc_create(tmp_.c_str(), NC_CLOBBER | NC_NETCDF4 | NC_CLASSIC_MODEL, &ncid_), "cannot create");
      open_ = true;
      define(meta);
    } catch (...) {
      if (open_) nc_abort(ncid_);
      ::unlink(tmp_.c_str());
      throw;
    }
  }

  ~NetCdfGridWriter() override {
    if (open_) nc_abort(ncid_);
    if (created_) ::unlink(tmp_.c_str());
  }

  void write_row(const GridRow& row) override {
    check_row(spec_, row, rows_written_, path_);
    const std::size_t cols = spec_.columns();
    buffer_.resize(cols);
    for (std::size_t k = 0; k < spec_.quantities.size(); ++k) {
      const double f = grid_quantity_format(spec_.quantities[k]).per_si;
      const std::span<const double> v = row.values(k);
      for (std::size_t i = 0; i < cols; ++i) {
        buffer_[i] = v[i] * f;
        lo_[k] = std::min(lo_[k], buffer_[i]);
        hi_[k] = std::max(hi_[k], buffer_[i]);
      }
      const std::size_t start[2] = {row.row, 0}, count[2] = {1, cols};
      check(nc_put_vara_double(ncid_, vars_[k], start, count, buffer_.data()), "cannot write");
    }
    ++rows_written_;
  }

  void commit() override {
    if (!open_) throw IoError("committed twice", {path_.string(), std::nullopt, {}});
    if (rows_written_ != spec_.rows())
      throw IoError(fmt::format("only {} of {} rows were written", rows_written_, spec_.rows()),
                    {path_.string(), std::nullopt, {}});
    check(nc_redef(ncid_), "cannot write attributes to");
    for (std::size_t k = 0; k < vars_.size(); ++k) {
      const double range[2] = {lo_[k], hi_[k]};
      check(nc_put_att_double(ncid_, vars_[k], "actual_range", NC_DOUBLE, 2, range), "cannot write attributes to");
    }
    check(nc_enddef(ncid_), "cannot write attributes to");
    open_ = false;
    check(nc_close(ncid_), "cannot close");
    const int fd = ::open(tmp_.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) {
      const int err = errno;
      if (fd >= 0) ::close(fd);
      fail("cannot flush to disk", err);
    }
    // mkstemp creates 0600; give the result ordinary permissions (umask applies).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, static_cast<mode_t>(0666 & ~mask));
    ::close(fd);
    if (::rename(tmp_.c_str(), path_.c_str()) != 0) fail("cannot rename the temporary file into place", errno);
    created_ = false;
    guard_.release();
  }

 private:
  [[noreturn]] void fail(const char* what, int err) const {
    throw IoError(fmt::format("{}: {}", what, std::strerror(err)), {path_.string(), std::nullopt, {}});
  }
  void check(int status, const char* what) const {
    if (status != NC_NOERR)
      throw IoError(fmt::format("{} NetCDF file: {}", what, nc_strerror(status)), {path_.string(), std::nullopt, {}});
  }
  void text(int var, const char* name, std::string_view value) {
    check(nc_put_att_text(ncid_, var, name, value.size(), value.data()), "cannot write attributes to");
  }

  void define(const GridFileMetadata& meta) {
    const std::size_t rows = spec_.rows(), cols = spec_.columns();
    int lat_dim = 0, lon_dim = 0, lat_var = 0, lon_var = 0;
    check(nc_def_dim(ncid_, "lat", rows, &lat_dim), "cannot define");
    check(nc_def_dim(ncid_, "lon", cols, &lon_dim), "cannot define");
    check(nc_def_var(ncid_, "lat", NC_DOUBLE, 1, &lat_dim, &lat_var), "cannot define");
    check(nc_def_var(ncid_, "lon", NC_DOUBLE, 1, &lon_dim, &lon_var), "cannot define");
    text(lat_var, "long_name", "latitude");
    text(lat_var, "standard_name", "latitude");
    text(lat_var, "units", "degrees_north");
    text(lon_var, "long_name", "longitude");
    text(lon_var, "standard_name", "longitude");
    text(lon_var, "units", "degrees_east");
    std::vector<double> lat(rows), lon(cols);
    for (std::size_t j = 0; j < rows; ++j) lat[j] = spec_.lat_deg(j);
    for (std::size_t i = 0; i < cols; ++i) lon[i] = spec_.lon_deg(i);
    // A pixel grid's range is its cells' outer edges (GMT's convention, which GDAL follows for
    // node_offset = 1: the nodes' range there gave a half-cell shift and a wrong pixel size).
    const bool pixel = spec_.registration == gravity::GridRegistration::Pixel;
    const double hy = pixel ? spec_.lat_spacing_deg / 2 : 0.0, hx = pixel ? spec_.lon_spacing_deg / 2 : 0.0;
    const double lat_range[2] = {lat.front() - hy, lat.back() + hy}, lon_range[2] = {lon.front() - hx, lon.back() + hx};
    check(nc_put_att_double(ncid_, lat_var, "actual_range", NC_DOUBLE, 2, lat_range), "cannot define");
    check(nc_put_att_double(ncid_, lon_var, "actual_range", NC_DOUBLE, 2, lon_range), "cannot define");
    const int dims[2] = {lat_dim, lon_dim};
    const std::size_t chunk[2] = {1, cols};
    for (GridQuantity q : spec_.quantities) {
      const GridQuantityFormat f = grid_quantity_format(q);
      int var = 0;
      check(nc_def_var(ncid_, std::string(f.name).c_str(), NC_DOUBLE, 2, dims, &var), "cannot define");
      check(nc_def_var_chunking(ncid_, var, NC_CHUNKED, chunk), "cannot define");
      text(var, "long_name", f.long_name);
      text(var, "units", f.units);
      text(var, "grid_mapping", "crs");
      vars_.push_back(var);
    }
    define_crs(meta);
    lo_.assign(vars_.size(), std::numeric_limits<double>::infinity());
    hi_.assign(vars_.size(), -std::numeric_limits<double>::infinity());
    text(NC_GLOBAL, "Conventions", "CF-1.8, COARDS");
    text(NC_GLOBAL, "title", fmt::format("{} synthesised from {} to degree {}", quantity_list(), meta.model_name,
                                         meta.max_degree));
    text(NC_GLOBAL, "source", fmt::format("Meridian {} (meridian gravity grid)", version()));
    if (!meta.history.empty()) text(NC_GLOBAL, "history", meta.history);
    text(NC_GLOBAL, "model", meta.model_name);
    text(NC_GLOBAL, "model_file", meta.model_file);
    check(nc_put_att_int(ncid_, NC_GLOBAL, "max_degree", NC_INT, 1, &meta.max_degree), "cannot define");
    text(NC_GLOBAL, "tide_system", meta.tide_system.empty() ? "not stated" : meta.tide_system);
    text(NC_GLOBAL, "registration", pixel ? "pixel (cell centres; GMT -r)" : "gridline (nodes on the region's edges)");
    const int node_offset = pixel ? 1 : 0;
    check(nc_put_att_int(ncid_, NC_GLOBAL, "node_offset", NC_INT, 1, &node_offset), "cannot define");
    text(NC_GLOBAL, "synthesis_path", gravity::to_string(meta.path));
    if (meta.height_source.empty())
      check(nc_put_att_double(ncid_, NC_GLOBAL, "height_m", NC_DOUBLE, 1, &spec_.height_m), "cannot define");
    else
      text(NC_GLOBAL, "height_source", "ellipsoidal height of each node (m) from " + meta.height_source);
    text(NC_GLOBAL, "comment",
         "Heights are ellipsoidal (height_m: the same at every node; height_source: per node); the geoid "
         "height N is evaluated on the ellipsoid (h = 0) whatever the height. xi, eta, dg_* are in the local geocentric (spherical) frame as "
         "GeographicLib's SphericalAnomaly; definitions: Meridian docs/gravity-field.md, Grids.");
    check(nc_enddef(ncid_), "cannot define");
    check(nc_put_var_double(ncid_, lat_var, lat.data()), "cannot write");
    check(nc_put_var_double(ncid_, lon_var, lon.data()), "cannot write");
  }

  // CF 1.8 §5.6: a scalar grid mapping variable that GDAL (so QGIS) and xarray read as the CRS.
  void define_crs(const GridFileMetadata& meta) {
    int crs = 0;
    check(nc_def_var(ncid_, "crs", NC_INT, 0, nullptr, &crs), "cannot define");
    text(crs, "grid_mapping_name", "latitude_longitude");
    const double a = meta.ellipsoid_a_m, inv_f = 1 / meta.ellipsoid_flattening, zero = 0;
    check(nc_put_att_double(ncid_, crs, "semi_major_axis", NC_DOUBLE, 1, &a), "cannot define");
    check(nc_put_att_double(ncid_, crs, "inverse_flattening", NC_DOUBLE, 1, &inv_f), "cannot define");
    check(nc_put_att_double(ncid_, crs, "longitude_of_prime_meridian", NC_DOUBLE, 1, &zero), "cannot define");
    const std::string wkt = geographic_crs_wkt(meta.ellipsoid_a_m, meta.ellipsoid_flattening);
    text(crs, "crs_wkt", wkt);
    text(crs, "spatial_ref", wkt);  // GDAL's own name for it (older GDAL reads only this)
  }

  std::string quantity_list() const {
    std::string s;
    for (GridQuantity q : spec_.quantities) s += (s.empty() ? "" : ", ") + std::string(gravity::to_string(q));
    return s;
  }

  std::filesystem::path path_;
  GridSpec spec_;
  std::string tmp_;
  bool created_ = false, open_ = false;
  TemporaryFileGuard guard_;  // tmp_ removed on SIGINT/SIGTERM too
  int ncid_ = -1;
  std::vector<int> vars_;
  std::vector<double> buffer_, lo_, hi_;
  std::size_t rows_written_ = 0;
};

// ---- Formats written as a byte stream: a header, then each row's bytes in turn ----

// The row order check, the row count and the atomic file of CSV and GTX; a format supplies its
// header (written by its constructor) and encode_row.
class StreamGridWriter : public GridFileWriter {
 public:
  void write_row(const GridRow& row) final {
    check_row(spec_, row, rows_written_, path_);
    out_.write(encode_row(row));
    ++rows_written_;
  }

  void commit() final {
    if (rows_written_ != spec_.rows())
      throw IoError(fmt::format("only {} of {} rows were written", rows_written_, spec_.rows()),
                    {path_.string(), std::nullopt, {}});
    out_.commit();
  }

 protected:
  StreamGridWriter(const std::filesystem::path& path, const GridSpec& spec) : path_(path), spec_(spec), out_(path) {}
  // The bytes of one row (checked against the spec already). Throws as write_row.
  virtual std::string encode_row(const GridRow& row) const = 0;

  std::filesystem::path path_;
  GridSpec spec_;
  AtomicFileWriter out_;

 private:
  std::size_t rows_written_ = 0;
};

// ---- CSV ----

class CsvGridWriter final : public StreamGridWriter {
 public:
  CsvGridWriter(const std::filesystem::path& path, const GridSpec& spec) : StreamGridWriter(path, spec) {
    std::string header = "lon_deg,lat_deg";
    for (GridQuantity q : spec_.quantities) {
      const GridQuantityFormat f = grid_quantity_format(q);
      header += fmt::format(",{}_{}", f.name, f.units);
    }
    out_.write(header + "\n");
  }

 private:
  std::string encode_row(const GridRow& row) const override {
    std::string text;
    const std::size_t cols = spec_.columns();
    for (std::size_t i = 0; i < cols; ++i) {
      text += fmt::format("{:.10f},{:.10f}", spec_.lon_deg(i), row.lat_deg);
      for (std::size_t k = 0; k < spec_.quantities.size(); ++k)
        text += fmt::format(",{:.9f}", row.values(k)[i] * grid_quantity_format(spec_.quantities[k]).per_si);
      text += '\n';
    }
    return text;
  }
};

// ---- GTX (NOAA VDatum; PROJ and GDAL read it) ----

// Big-endian bytes of an IEEE value or a 32-bit integer.
template <class T>
void put_big_endian(std::string& out, T value) {
  static_assert(sizeof(T) == 4 || sizeof(T) == 8);
  using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  const U u = std::bit_cast<U>(value);
  for (int shift = 8 * static_cast<int>(sizeof(T)) - 8; shift >= 0; shift -= 8)
    out += static_cast<char>((u >> shift) & 0xFF);
}

class GtxGridWriter final : public StreamGridWriter {
 public:
  GtxGridWriter(const std::filesystem::path& path, const GridSpec& spec)
      : StreamGridWriter(path, spec),
        // A global gridline grid repeats its first column at W + 360°: GTX readers wrap the
        // longitude themselves (PROJ's own global grids have no repeated column) and PROJ 9.1
        // misplaces every value east of the repeat when it is there (trial finding), so it is
        // not written.
        columns_(stored_grid_columns(path, spec)) {
    // Header: first node's latitude and longitude, the two spacings (degrees, float64), rows and
    // columns (int32); then the values row by row from south to north.
    std::string header;
    put_big_endian(header, spec_.lat_deg(0));
    put_big_endian(header, spec_.lon_deg(0));
    put_big_endian(header, spec_.lat_spacing_deg);
    put_big_endian(header, spec_.lon_spacing_deg);
    put_big_endian(header, static_cast<std::int32_t>(spec_.rows()));
    put_big_endian(header, static_cast<std::int32_t>(columns_));
    out_.write(header);
  }

 private:
  std::string encode_row(const GridRow& row) const override {
    std::string bytes;
    bytes.reserve(4 * columns_);
    const std::span<const double> n = row.values(0);  // geoid, metres
    for (std::size_t i = 0; i < columns_; ++i) {
      if (!(std::abs(n[i]) <= std::numeric_limits<float>::max()))
        throw NumericalError(fmt::format("the geoid height {} m at lat {} deg, lon {} deg does not fit the float32 "
                                         "of a .gtx file (damaged model?)",
                                         n[i], row.lat_deg, spec_.lon_deg(i)),
                             {path_.string(), std::nullopt, fmt::format("rows[{}]", row.row)});
      put_big_endian(bytes, static_cast<float>(n[i]));
    }
    return bytes;
  }

  std::size_t columns_;
};

// A NetCDF call's status: IoError "cannot read WHAT: …" naming the file unless it succeeded.
void nc_ok(int status, const char* what, const std::string& file) {
  if (status != NC_NOERR) throw IoError(fmt::format("cannot read {}: {}", what, nc_strerror(status)), {file, std::nullopt, {}});
}

// The height variable: `variable` when named (FILE?VAR), else the file's only two-dimensional
// one (its name into `variable`).
int height_variable(int ncid, std::string& variable, const ErrorContext& where) {
  int var = -1;
  if (variable.empty()) {
    int nvars = 0;
    nc_ok(nc_inq_nvars(ncid, &nvars), "the variables", where.file);
    std::vector<std::string> names;
    for (int v = 0; v < nvars; ++v) {
      int nd = 0;
      char name[NC_MAX_NAME + 1] = {};
      nc_ok(nc_inq_varndims(ncid, v, &nd), "the variables", where.file);
      nc_ok(nc_inq_varname(ncid, v, name), "the variables", where.file);
      if (nd == 2) names.emplace_back(name), var = v;
    }
    if (names.size() != 1)
      throw InputError(fmt::format("the height grid has {} two-dimensional variables; name one as FILE?VARIABLE",
                                   names.size()),
                       where);
    variable = names.front();
  } else if (nc_inq_varid(ncid, variable.c_str(), &var) != NC_NOERR) {
    throw InputError(fmt::format("the height grid has no variable \"{}\"", variable), where);
  }
  return var;
}

// The two dimensions of a height variable, with their coordinate variables' values.
struct HeightAxes {
  std::string name[2];
  std::size_t length[2] = {0, 0};
  std::vector<double> coordinates[2];
};

HeightAxes height_axes(int ncid, int var, const std::string& variable, const ErrorContext& where) {
  int nd = 0, dims[NC_MAX_VAR_DIMS] = {};
  nc_ok(nc_inq_varndims(ncid, var, &nd), "the variable", where.file);
  if (nd != 2) throw InputError(fmt::format("variable \"{}\" has {} dimensions, not 2", variable, nd), where);
  nc_ok(nc_inq_vardimid(ncid, var, dims), "the variable", where.file);
  HeightAxes axes;
  for (int k = 0; k < 2; ++k) {
    char name[NC_MAX_NAME + 1] = {};
    nc_ok(nc_inq_dim(ncid, dims[k], name, &axes.length[k]), "the dimensions", where.file);
    axes.name[k] = name;
    int cv = 0;
    if (nc_inq_varid(ncid, name, &cv) != NC_NOERR)
      throw InputError(fmt::format("dimension \"{}\" has no coordinate variable", axes.name[k]), where);
    axes.coordinates[k].resize(axes.length[k]);
    nc_ok(nc_get_var_double(ncid, cv, axes.coordinates[k].data()), "the coordinates", where.file);
  }
  return axes;
}

// The axes are (lat, lon) with exactly the spec's nodes (latitudes south to north or north to
// south, longitudes modulo 360°); returns whether the rows run south to north.
bool check_height_nodes(const HeightAxes& axes, const GridSpec& spec, const std::string& variable,
                        const ErrorContext& where) {
  const std::size_t rows = spec.rows(), columns = spec.columns();
  const std::string d0 = detail::lower(axes.name[0]), d1 = detail::lower(axes.name[1]);
  if (!(d0 == "lat" || d0 == "latitude" || d0 == "y") || !(d1 == "lon" || d1 == "longitude" || d1 == "x"))
    throw InputError(fmt::format("variable \"{}\" has dimensions ({}, {}); expected (lat, lon)", variable,
                                 axes.name[0], axes.name[1]),
                     where);
  if (axes.length[0] != rows || axes.length[1] != columns)
    throw InputError(fmt::format("the height grid has {} x {} nodes (lon x lat), the grid {} x {}", axes.length[1],
                                 axes.length[0], columns, rows),
                     where);
  const std::vector<double>& lats = axes.coordinates[0];
  const bool south_first = rows < 2 || lats.front() <= lats.back();
  for (std::size_t j = 0; j < rows; ++j) {
    const double lat = lats[south_first ? j : rows - 1 - j];
    if (!(std::abs(lat - spec.lat_deg(j)) <= 1e-9))
      throw InputError(fmt::format("the height grid's latitude {} is not the grid's node latitude {} (row {})", lat,
                                   spec.lat_deg(j), j),
                       where);
  }
  for (std::size_t i = 0; i < columns; ++i) {
    double d = axes.coordinates[1][i] - spec.lon_deg(i);
    d -= 360.0 * std::round(d / 360.0);
    if (!(std::abs(d) <= 1e-9))
      throw InputError(fmt::format("the height grid's longitude {} is not the grid's node longitude {} (column {})",
                                   axes.coordinates[1][i], spec.lon_deg(i), i),
                       where);
  }
  return south_first;
}

// A `units` attribute, when the variable has one, says metres.
void check_height_units(int ncid, int var, const std::string& variable, const ErrorContext& where) {
  std::size_t n = 0;
  if (nc_inq_attlen(ncid, var, "units", &n) != NC_NOERR) return;
  std::string units(n, '\0');
  nc_ok(nc_get_att_text(ncid, var, "units", units.data()), "the units", where.file);
  while (!units.empty() && (units.back() == '\0' || units.back() == ' ')) units.pop_back();
  const std::string u = detail::lower(units);
  if (u != "m" && u != "meter" && u != "meters" && u != "metre" && u != "metres")
    throw InputError(fmt::format("variable \"{}\" is in \"{}\"; heights must be in metres", variable, units), where);
}

}  // namespace

GridHeightFile::GridHeightFile(const std::string& path, const GridSpec& spec)
    : rows_(spec.rows()), columns_(spec.columns()) {
  const std::size_t q = path.rfind('?');
  file_ = q == std::string::npos ? path : path.substr(0, q);
  if (q != std::string::npos) variable_ = path.substr(q + 1);
  const ErrorContext where{file_, std::nullopt, "--height-grid"};
  if (const int st = nc_open(file_.c_str(), NC_NOWRITE, &ncid_); st != NC_NOERR)
    throw IoError(fmt::format("cannot open the height grid: {}", nc_strerror(st)), {file_, std::nullopt, {}});
  try {
    var_ = height_variable(ncid_, variable_, where);
    south_first_ = check_height_nodes(height_axes(ncid_, var_, variable_, where), spec, variable_, where);
    check_height_units(ncid_, var_, variable_, where);
    has_fill_ = nc_get_att_double(ncid_, var_, "_FillValue", &fill_) == NC_NOERR;
    for (std::size_t j = 0; j < rows_; ++j) lat_deg_.push_back(spec.lat_deg(j));
    for (std::size_t i = 0; i < columns_; ++i) lon_deg_.push_back(spec.lon_deg(i));
  } catch (...) {
    nc_close(ncid_);
    throw;
  }
}

GridHeightFile::~GridHeightFile() { nc_close(ncid_); }

void GridHeightFile::read_row(std::size_t row, std::span<double> heights_m) const {
  if (row >= rows_ || heights_m.size() != columns_)
    throw InputError(fmt::format("height row {} of {} values asked of a {} x {} grid", row, heights_m.size(), columns_,
                                 rows_),
                     {file_, std::nullopt, "--height-grid"});
  const std::size_t start[2] = {south_first_ ? row : rows_ - 1 - row, 0}, count[2] = {1, columns_};
  if (const int st = nc_get_vara_double(ncid_, var_, start, count, heights_m.data()); st != NC_NOERR)
    throw IoError(fmt::format("cannot read heights: {}", nc_strerror(st)), {file_, std::nullopt, {}});
  for (std::size_t i = 0; i < columns_; ++i)
    if (!std::isfinite(heights_m[i]) || (has_fill_ && heights_m[i] == fill_))
      throw InputError(fmt::format("no height at lat {} deg, lon {} deg (variable \"{}\")", lat_deg_[row],
                                   lon_deg_[i], variable_),
                       {file_, std::nullopt, "--height-grid"});
}

gravity::GridHeightSource GridHeightFile::source() const {
  return [this](std::size_t row, std::span<double> h) { read_row(row, h); };
}

GridQuantityFormat grid_quantity_format(GridQuantity q) noexcept {
  const double arcsec = 1.0 / units::kArcsecond, mgal = 1e5;
  switch (q) {
    case GridQuantity::Xi:
      return {"xi", "arcsec", arcsec,
              "deflection of the vertical, north-south component xi (positive: plumb line north of the ellipsoid "
              "normal, astronomic latitude greater than geodetic)"};
    case GridQuantity::Eta:
      return {"eta", "arcsec", arcsec,
              "deflection of the vertical, east-west component eta (positive: plumb line east of the ellipsoid "
              "normal, astronomic longitude greater than geodetic)"};
    case GridQuantity::Geoid:
      return {"geoid", "m", 1.0, "geoid height N above the reference ellipsoid (positive: geoid above the ellipsoid)"};
    case GridQuantity::Anomaly:
      return {"anomaly", "mGal", mgal,
              "spherical gravity anomaly Dg = -dT/dr - 2T/r (positive: gravity stronger than normal)"};
    case GridQuantity::DisturbanceEast:
      return {"dg_east", "mGal", mgal,
              "gravity disturbance vector grad T, east component (1/(r cos psi)) dT/dlambda, local geocentric "
              "frame (positive east)"};
    case GridQuantity::DisturbanceNorth:
      return {"dg_north", "mGal", mgal,
              "gravity disturbance vector grad T, north component (1/r) dT/dpsi, local geocentric frame "
              "(positive north)"};
    case GridQuantity::DisturbanceUp:
      return {"dg_up", "mGal", mgal,
              "gravity disturbance vector grad T, radial component dT/dr (positive up, away from the Earth's "
              "centre; the scalar gravity disturbance is -dg_up)"};
  }
  return {"?", "?", 1.0, "?"};
}

std::string_view to_string(GridFileFormat f) noexcept {
  switch (f) {
    case GridFileFormat::NetCdf: return "netcdf";
    case GridFileFormat::Csv: return "csv";
    case GridFileFormat::Gtx: return "gtx";
  }
  return "?";
}

std::string_view display_name(GridFileFormat f) noexcept {
  switch (f) {
    case GridFileFormat::NetCdf: return "NetCDF";
    case GridFileFormat::Csv: return "CSV";
    case GridFileFormat::Gtx: return "GTX";
  }
  return "?";
}

GridFileFormat grid_file_format_for(const std::filesystem::path& path) {
  const std::string ext = detail::lower(path.extension().string());
  if (ext == ".nc" || ext == ".grd" || ext == ".cdf") return GridFileFormat::NetCdf;
  if (ext == ".csv") return GridFileFormat::Csv;
  if (ext == ".gtx") return GridFileFormat::Gtx;
  throw InputError(fmt::format("cannot tell the format of \"{}\" from its extension: use .nc (NetCDF), .gtx "
                               "(geoid heights) or .csv",
                               path.string()),
                   {"", {}, "--output"});
}

std::size_t stored_grid_columns(const std::filesystem::path& path, const GridSpec& spec) {
  const bool repeated = spec.global_longitude() && spec.registration == gravity::GridRegistration::Gridline;
  return spec.columns() - (grid_file_format_for(path) == GridFileFormat::Gtx && repeated ? 1 : 0);
}

std::string geographic_crs_wkt(double a_m, double flattening) {
  const auto is = [&](double a, double inv_f) {
    return a_m == a && std::abs(flattening * inv_f - 1) <= 1e-12;
  };
  if (is(6378137.0, 298.257223563))
    return "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563,"
           "AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM[\"Greenwich\",0,"
           "AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],"
           "AXIS[\"Latitude\",NORTH],AXIS[\"Longitude\",EAST],AUTHORITY[\"EPSG\",\"4326\"]]";
  const std::string name = is(6378137.0, 298.257222101) ? "GRS 1980"
                           : fmt::format("ellipsoid a = {:.4f} m, 1/f = {:.9f}", a_m, 1 / flattening);
  return fmt::format("GEOGCS[\"{0} (the gravity model's reference ellipsoid)\",DATUM[\"{0}\",SPHEROID[\"{0}\","
                     "{1:.17g},{2:.17g}]],PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433],"
                     "AXIS[\"Latitude\",NORTH],AXIS[\"Longitude\",EAST]]",
                     name, a_m, 1 / flattening);
}

void check_grid_output(const std::filesystem::path& path, const GridSpec& spec) {
  const GridFileFormat format = grid_file_format_for(path);
  if (format == GridFileFormat::Gtx) {
    if (spec.quantities != std::vector<GridQuantity>{GridQuantity::Geoid})
      throw InputError("a .gtx file holds geoid heights only: use --quantities geoid, or write NetCDF (.nc)",
                       {"", {}, "--quantities"});
    if (spec.rows() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()) ||
        spec.columns() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
      throw InputError("too many rows or columns for the 32-bit sizes of a .gtx header", {"", {}, "--output"});
  }
  if (format == GridFileFormat::Csv && spec.nodes() > kMaxCsvGridNodes)
    throw InputError(fmt::format("a CSV grid is for small grids: {} nodes is more than {}; write NetCDF (.nc)",
                                 spec.nodes(), kMaxCsvGridNodes),
                     {"", {}, "--output"});
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (::access(dir.c_str(), W_OK) != 0)
    throw IoError(fmt::format("cannot write to the directory {}: {}", dir.string(), std::strerror(errno)),
                  {path.string(), std::nullopt, {}});
}

std::unique_ptr<GridFileWriter> open_grid_file(const std::filesystem::path& path, const GridSpec& spec,
                                               const GridFileMetadata& metadata) {
  check_grid_output(path, spec);
  switch (grid_file_format_for(path)) {
    case GridFileFormat::Csv: return std::make_unique<CsvGridWriter>(path, spec);
    case GridFileFormat::Gtx: return std::make_unique<GtxGridWriter>(path, spec);
    case GridFileFormat::NetCdf: break;
  }
  return std::make_unique<NetCdfGridWriter>(path, spec, metadata);
}

}  // namespace meridian::io
