// Grid files of `gravity grid` (issue 14): NetCDF read back with the netCDF C API and with
// Debian's ncdump (netcdf-bin; the test fails, not skips, when ncdump is missing), CSV, atomic
// output, and the errors raised before any work.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <netcdf.h>
#include <unistd.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/gravity_grid_files.hpp"

namespace gtest_grid_files {

using namespace meridian;
using namespace meridian::gravity;
using namespace meridian::io;
namespace fs = std::filesystem;

struct TempDir {
  fs::path p = fs::temp_directory_path() / ("meridian_grid_files_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(p); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(p, ec);
  }
};

GridSpec small_spec(GridRegistration reg) {
  GridSpec s;
  s.west_deg = 10, s.east_deg = 20, s.south_deg = 30, s.north_deg = 35;
  s.lon_spacing_deg = s.lat_spacing_deg = 2.5;
  s.registration = reg;
  s.height_m = 150;
  s.quantities = {GridQuantity::Xi, GridQuantity::Geoid, GridQuantity::Anomaly};
  s.validate();
  return s;
}

// Library values (rad, m, m/s²) that identify the node and quantity.
double node_si_value(std::size_t k, std::size_t j, std::size_t i) {
  const double x = static_cast<double>(j * 100 + i) + 0.125;
  if (k == 0) return x * units::kArcsecond;  // xi: x arc-seconds
  if (k == 1) return -x;                     // geoid: −x m
  return x * 1e-5;                           // anomaly: x mGal
}
double file_value(std::size_t k, std::size_t j, std::size_t i) {
  const double x = static_cast<double>(j * 100 + i) + 0.125;
  return k == 1 ? -x : x;
}

void write_all(GridFileWriter& w, const GridSpec& s) {
  const std::size_t cols = s.columns(), nq = s.quantities.size();
  std::vector<double> data(cols * nq);
  for (std::size_t j = 0; j < s.rows(); ++j) {
    for (std::size_t k = 0; k < nq; ++k)
      for (std::size_t i = 0; i < cols; ++i) data[k * cols + i] = node_si_value(k, j, i);
    w.write_row(GridRow{j, s.lat_deg(j), cols, data});
  }
}

GridFileMetadata meta() {
  GridFileMetadata m;
  m.model_name = "synth";
  m.model_file = "synth.gfc";
  m.max_degree = 60;
  m.tide_system = "tide_free";
  m.path = GridPath::Parallel;
  m.history = "meridian gravity grid --test";
  return m;
}

std::string run(const std::string& cmd) {
  std::string out;
  FILE* pipe = ::popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return "popen failed";
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  const int status = ::pclose(pipe);
  if (status != 0) out += "\n[exit status " + std::to_string(status) + "]";
  return out;
}

bool have_ncdump() { return std::system("command -v ncdump > /dev/null 2>&1") == 0; }

std::string text_attribute(int ncid, int var, const char* name) {
  std::size_t len = 0;
  if (nc_inq_attlen(ncid, var, name, &len) != NC_NOERR) return "<missing>";
  std::string s(len, '\0');
  nc_get_att_text(ncid, var, name, s.data());
  return s;
}

TEST(GridFiles, NetCdfReadBackWithTheCApi) {
  TempDir dir;
  const fs::path path = dir.p / "g.nc";
  for (GridRegistration reg : {GridRegistration::Gridline, GridRegistration::Pixel}) {
    const GridSpec s = small_spec(reg);
    {
      auto w = open_grid_file(path, s, meta());
      write_all(*w, s);
      w->commit();
    }
    int nc = 0;
    ASSERT_EQ(nc_open(path.c_str(), NC_NOWRITE, &nc), NC_NOERR);
    int lat_dim = 0, lon_dim = 0;
    std::size_t rows = 0, cols = 0;
    ASSERT_EQ(nc_inq_dimid(nc, "lat", &lat_dim), NC_NOERR);
    ASSERT_EQ(nc_inq_dimid(nc, "lon", &lon_dim), NC_NOERR);
    nc_inq_dimlen(nc, lat_dim, &rows);
    nc_inq_dimlen(nc, lon_dim, &cols);
    EXPECT_EQ(rows, s.rows());
    EXPECT_EQ(cols, s.columns());
    int lat_var = 0, lon_var = 0;
    nc_inq_varid(nc, "lat", &lat_var);
    nc_inq_varid(nc, "lon", &lon_var);
    std::vector<double> lat(rows), lon(cols);
    nc_get_var_double(nc, lat_var, lat.data());
    nc_get_var_double(nc, lon_var, lon.data());
    for (std::size_t j = 0; j < rows; ++j) EXPECT_EQ(lat[j], s.lat_deg(j));
    for (std::size_t i = 0; i < cols; ++i) EXPECT_EQ(lon[i], s.lon_deg(i));
    EXPECT_EQ(text_attribute(nc, lat_var, "units"), "degrees_north");
    EXPECT_EQ(text_attribute(nc, lon_var, "units"), "degrees_east");
    int node_offset = -1;
    nc_get_att_int(nc, NC_GLOBAL, "node_offset", &node_offset);
    EXPECT_EQ(node_offset, reg == GridRegistration::Pixel ? 1 : 0);
    EXPECT_EQ(text_attribute(nc, NC_GLOBAL, "model"), "synth");
    EXPECT_EQ(text_attribute(nc, NC_GLOBAL, "synthesis_path"), "parallel");
    EXPECT_EQ(text_attribute(nc, NC_GLOBAL, "tide_system"), "tide_free");
    EXPECT_NE(text_attribute(nc, NC_GLOBAL, "Conventions").find("CF-1.8"), std::string::npos);
    int degree = 0;
    nc_get_att_int(nc, NC_GLOBAL, "max_degree", &degree);
    EXPECT_EQ(degree, 60);
    const char* names[] = {"xi", "geoid", "anomaly"};
    const char* unit[] = {"arcsec", "m", "mGal"};
    for (std::size_t k = 0; k < 3; ++k) {
      int var = 0;
      ASSERT_EQ(nc_inq_varid(nc, names[k], &var), NC_NOERR) << names[k];
      EXPECT_EQ(text_attribute(nc, var, "units"), unit[k]);
      EXPECT_NE(text_attribute(nc, var, "long_name").find("positive"), std::string::npos);
      int ndims = 0, dims[2] = {-1, -1};
      nc_inq_varndims(nc, var, &ndims);
      nc_inq_vardimid(nc, var, dims);
      EXPECT_EQ(ndims, 2);
      EXPECT_EQ(dims[0], lat_dim);  // (lat, lon): rows south to north
      EXPECT_EQ(dims[1], lon_dim);
      std::vector<double> v(rows * cols);
      nc_get_var_double(nc, var, v.data());
      double max_err = 0;
      for (std::size_t j = 0; j < rows; ++j)
        for (std::size_t i = 0; i < cols; ++i)
          max_err = std::max(max_err, std::abs(v[j * cols + i] - file_value(k, j, i)));
      EXPECT_LE(max_err, 1e-11) << names[k];
    }
    nc_close(nc);
  }
}

TEST(GridFiles, NetCdfReadBackWithNcdump) {
  ASSERT_TRUE(have_ncdump()) << "ncdump (Debian netcdf-bin, scripts/setup.sh) is required";
  TempDir dir;
  const fs::path path = dir.p / "g.nc";
  const GridSpec s = small_spec(GridRegistration::Gridline);
  auto w = open_grid_file(path, s, meta());
  write_all(*w, s);
  w->commit();
  const std::string h = run("ncdump -h " + path.string());
  for (const char* want : {"lat = 3 ;", "lon = 5 ;", "double lat(lat) ;", "double lon(lon) ;",
                           "double xi(lat, lon) ;", "double geoid(lat, lon) ;", "double anomaly(lat, lon) ;",
                           "xi:units = \"arcsec\" ;", "geoid:units = \"m\" ;", "anomaly:units = \"mGal\" ;",
                           "lat:units = \"degrees_north\" ;", "lon:units = \"degrees_east\" ;",
                           ":node_offset = 0 ;", ":max_degree = 60 ;", ":model = \"synth\" ;"})
    EXPECT_NE(h.find(want), std::string::npos) << want << "\n" << h;
  const std::string lon = run("ncdump -v lon " + path.string());
  EXPECT_NE(lon.find("lon = 10, 12.5, 15, 17.5, 20 ;"), std::string::npos) << lon;
  const std::string lat = run("ncdump -v lat " + path.string());
  EXPECT_NE(lat.find("lat = 30, 32.5, 35 ;"), std::string::npos) << lat;
  // ncdump prints 17 significant digits by default with -p; check a few values of geoid.
  const std::string geoid = run("ncdump -p 9,17 -v geoid " + path.string());
  EXPECT_NE(geoid.find("-0.125, -1.125, -2.125, -3.125, -4.125,"), std::string::npos) << geoid;
  EXPECT_NE(geoid.find("-200.125, -201.125, -202.125, -203.125, -204.125 ;"), std::string::npos) << geoid;
}

TEST(GridFiles, CsvLayout) {
  TempDir dir;
  const fs::path path = dir.p / "g.csv";
  const GridSpec s = small_spec(GridRegistration::Gridline);
  auto w = open_grid_file(path, s, meta());
  write_all(*w, s);
  w->commit();
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "lon_deg,lat_deg,xi_arcsec,geoid_m,anomaly_mGal");
  std::getline(in, line);
  EXPECT_EQ(line, "10.0000000000,30.0000000000,0.125000000,-0.125000000,0.125000000");
  int lines = 1;
  std::string last;
  while (std::getline(in, line)) ++lines, last = line;
  EXPECT_EQ(lines, 15);
  EXPECT_EQ(last, "20.0000000000,35.0000000000,204.125000000,-204.125000000,204.125000000");
}

TEST(GridFiles, AtomicAndErrorsBeforeWork) {
  TempDir dir;
  const GridSpec s = small_spec(GridRegistration::Gridline);
  for (const char* name : {"keep.nc", "keep.csv"}) {
    const fs::path path = dir.p / name;
    { std::ofstream(path) << "old"; }
    {
      auto w = open_grid_file(path, s, meta());
      w->write_row(GridRow{0, s.lat_deg(0), s.columns(), std::vector<double>(s.columns() * 3, 0.0)});
      EXPECT_THROW(w->commit(), IoError);  // rows missing
    }  // destroyed without commit: the old file stays, no temporary file is left
    std::ifstream in(path);
    std::string content;
    std::getline(in, content);
    EXPECT_EQ(content, "old") << name;
  }
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir.p)) ++files, (void)e;
  EXPECT_EQ(files, 2u);
  EXPECT_THROW(open_grid_file(dir.p / "no-such-dir" / "g.nc", s, meta()), IoError);
  EXPECT_THROW(open_grid_file(dir.p / "g.txt", s, meta()), InputError);
  GridSpec big = s;
  big.west_deg = 0, big.east_deg = 360, big.south_deg = -90, big.north_deg = 90;
  big.lon_spacing_deg = big.lat_spacing_deg = 0.1;  // 6.5 million nodes
  EXPECT_THROW(open_grid_file(dir.p / "big.csv", big, meta()), InputError);
  auto w = open_grid_file(dir.p / "rows.nc", s, meta());
  EXPECT_THROW(w->write_row(GridRow{1, s.lat_deg(1), s.columns(), std::vector<double>(s.columns() * 3, 0.0)}),
               InputError);  // out of order
  EXPECT_EQ(io::grid_quantity_format(GridQuantity::DisturbanceUp).units, "mGal");
}

}  // namespace gtest_grid_files

namespace gtest_grid_files {

// A height grid written with the netCDF C API: rows north to south (as many tools write them),
// `units`, an optional second variable and an optional fill value at one node.
void write_height_grid(const fs::path& path, const GridSpec& s, const char* units, bool second_variable,
                       bool fill_one, double lon_offset_deg = 0) {
  int nc = 0, lat_dim = 0, lon_dim = 0, lat_var = 0, lon_var = 0, z = 0, other = 0;
  ASSERT_EQ(nc_create(path.c_str(), NC_CLOBBER | NC_NETCDF4 | NC_CLASSIC_MODEL, &nc), NC_NOERR);
  nc_def_dim(nc, "lat", s.rows(), &lat_dim);
  nc_def_dim(nc, "lon", s.columns(), &lon_dim);
  nc_def_var(nc, "lat", NC_DOUBLE, 1, &lat_dim, &lat_var);
  nc_def_var(nc, "lon", NC_DOUBLE, 1, &lon_dim, &lon_var);
  const int dims[2] = {lat_dim, lon_dim};
  nc_def_var(nc, "z", NC_DOUBLE, 2, dims, &z);
  nc_put_att_text(nc, z, "units", std::strlen(units), units);
  const double fill = -9999;
  nc_put_att_double(nc, z, "_FillValue", NC_DOUBLE, 1, &fill);
  if (second_variable) nc_def_var(nc, "z2", NC_DOUBLE, 2, dims, &other);
  nc_enddef(nc);
  std::vector<double> lat(s.rows()), lon(s.columns()), h(s.rows() * s.columns());
  for (std::size_t j = 0; j < s.rows(); ++j) lat[j] = s.lat_deg(s.rows() - 1 - j);
  for (std::size_t i = 0; i < s.columns(); ++i) lon[i] = s.lon_deg(i) + lon_offset_deg;
  for (std::size_t r = 0; r < s.rows(); ++r)
    for (std::size_t i = 0; i < s.columns(); ++i)
      h[r * s.columns() + i] = 1000.0 * static_cast<double>(s.rows() - 1 - r) + static_cast<double>(i);
  if (fill_one) h[1] = fill;
  nc_put_var_double(nc, lat_var, lat.data());
  nc_put_var_double(nc, lon_var, lon.data());
  nc_put_var_double(nc, z, h.data());
  if (second_variable) nc_put_var_double(nc, other, h.data());
  nc_close(nc);
}

TEST(GridFiles, HeightGridIsReadRowByRowFromSouthToNorth) {
  TempDir dir;
  const GridSpec s = small_spec(GridRegistration::Gridline);
  const fs::path p = dir.p / "h.nc";
  write_height_grid(p, s, "m", false, false, 360.0);  // longitudes 370…380: the same meridians
  const io::GridHeightFile f(p.string(), s);
  EXPECT_EQ(f.variable(), "z");
  std::vector<double> h(s.columns());
  for (std::size_t j = 0; j < s.rows(); ++j) {
    f.source()(j, h);
    for (std::size_t i = 0; i < s.columns(); ++i) EXPECT_EQ(h[i], 1000.0 * static_cast<double>(j) + static_cast<double>(i));
  }
}

TEST(GridFiles, HeightGridErrors) {
  TempDir dir;
  const GridSpec s = small_spec(GridRegistration::Gridline);
  auto field_of = [&](const std::string& path, const GridSpec& spec) -> std::string {
    try {
      io::GridHeightFile f(path, spec);
      std::vector<double> h(spec.columns());
      for (std::size_t j = 0; j < spec.rows(); ++j) f.read_row(j, h);
      return "no error";
    } catch (const InputError& e) {
      return "InputError " + e.context().field + ": " + e.message();
    } catch (const IoError& e) {
      return "IoError " + e.context().file;
    }
  };
  const fs::path km = dir.p / "km.nc", two = dir.p / "two.nc", fill = dir.p / "fill.nc";
  write_height_grid(km, s, "km", false, false);
  write_height_grid(two, s, "m", true, false);
  write_height_grid(fill, s, "metres", false, true);
  EXPECT_NE(field_of(km.string(), s).find("must be in metres"), std::string::npos) << field_of(km.string(), s);
  EXPECT_NE(field_of(two.string(), s).find("2 two-dimensional variables"), std::string::npos);
  EXPECT_EQ(field_of(two.string() + "?z2", s), "no error");
  EXPECT_NE(field_of(two.string() + "?nope", s).find("no variable \"nope\""), std::string::npos);
  EXPECT_NE(field_of(fill.string(), s).find("no height at lat 35 deg, lon 12.5 deg"), std::string::npos)
      << field_of(fill.string(), s);
  GridSpec other = s;
  other.west_deg = 12.5, other.east_deg = 22.5;  // same shape, other meridians
  EXPECT_NE(field_of(two.string() + "?z", other).find("is not the grid's node longitude"), std::string::npos);
  other = s;
  other.registration = GridRegistration::Pixel;  // another shape
  EXPECT_NE(field_of(two.string() + "?z", other).find("4 x 2"), std::string::npos) << field_of(two.string() + "?z", other);
  EXPECT_EQ(field_of((dir.p / "missing.nc").string(), s), "IoError " + (dir.p / "missing.nc").string());
}

}  // namespace gtest_grid_files
