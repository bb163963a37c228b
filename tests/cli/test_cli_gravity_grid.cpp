// `meridian gravity grid` (issue 14) as a user runs it: NetCDF and CSV outputs, the path
// chosen, values against `gravity point`, and the errors raised before any work.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace gtest_cli_grid {

namespace fs = std::filesystem;
using meridian_test::CmdResult;
class GravityGridCli : public meridian_test::CliTest {};

std::vector<std::vector<double>> csv_rows(const std::string& text, std::string* header = nullptr) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (header) *header = line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream f(line);
    std::string cell;
    while (std::getline(f, cell, ',')) v.push_back(std::stod(cell));
    rows.push_back(v);
  }
  return rows;
}

TEST_F(GravityGridCli, GlobalNetCdfUsesFftAndNcdumpShowsTheGrid) {
  ASSERT_EQ(run("gravity synth-model --degree 40 --seed 3 --out m").code, 0);
  const CmdResult r = run("gravity grid --model m.gfc --region g --spacing 30d --quantities xi,eta,geoid,anomaly "
                          "--height 0 -o out.nc --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["path_used"], "fft");
  EXPECT_EQ(j["fft_length"], 12);
  EXPECT_EQ(j["rows"], 7);
  EXPECT_EQ(j["columns"], 13);
  EXPECT_EQ(j["registration"], "gridline");
  EXPECT_EQ(j["format"], "netcdf");
  EXPECT_EQ(j["quantities"][3]["units"], "mGal");
  EXPECT_EQ(j["max_degree"], 40);
  const CmdResult h = shell("ncdump -h out.nc");
  ASSERT_EQ(h.code, 0) << "ncdump (netcdf-bin) is required: " << h.err;
  for (const char* want : {"lat = 7 ;", "lon = 13 ;", "double xi(lat, lon) ;", "double geoid(lat, lon) ;",
                           "xi:units = \"arcsec\" ;", "anomaly:units = \"mGal\" ;", ":synthesis_path = \"fft\" ;",
                           ":node_offset = 0 ;", ":max_degree = 40 ;"})
    EXPECT_NE(h.out.find(want), std::string::npos) << want << "\n" << h.out;
  const CmdResult lat = shell("ncdump -v lat out.nc");
  EXPECT_NE(lat.out.find("lat = -90, -60, -30, 0, 30, 60, 90 ;"), std::string::npos) << lat.out;
  // No temporary file is left beside the output.
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

TEST_F(GravityGridCli, CsvValuesEqualGravityPointAndBothPathsAgree) {
  ASSERT_EQ(run("gravity synth-model --degree 30 --seed 5 --out m").code, 0);
  const CmdResult fft = run("gravity grid --model m.gfc -R 0/360/-90/90 -I 45d --quantities xi,eta,geoid -o fft.csv -q");
  ASSERT_EQ(fft.code, 0) << fft.err;
  EXPECT_NE(fft.out.find("path fft"), std::string::npos) << fft.out;
  const CmdResult par = run("gravity grid --model m.gfc -R 0/360/-90/90 -I 45d --quantities xi,eta,geoid --path "
                            "parallel -o par.csv -q");
  ASSERT_EQ(par.code, 0) << par.err;
  EXPECT_NE(par.out.find("path parallel"), std::string::npos) << par.out;
  std::string header;
  const auto a = csv_rows(slurp(dir_ / "fft.csv"), &header), b = csv_rows(slurp(dir_ / "par.csv"));
  EXPECT_EQ(header, "lon_deg,lat_deg,xi_arcsec,eta_arcsec,geoid_m");
  ASSERT_EQ(a.size(), 9u * 5u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t c = 0; c < 5; ++c) EXPECT_NEAR(a[k][c], b[k][c], 2e-9) << k << "," << c;
  // Node (lon 90, lat 45) = row 3 (from −90), column 2.
  const auto& node = a[3 * 9 + 2];
  EXPECT_EQ(node[0], 90);
  EXPECT_EQ(node[1], 45);
  const auto p = nlohmann::json::parse(run("gravity point --model m.gfc 45 90 --json").out);
  EXPECT_NEAR(node[2], p["xi_arcsec"].get<double>(), 1e-8);
  EXPECT_NEAR(node[3], p["eta_arcsec"].get<double>(), 1e-8);
  EXPECT_NEAR(node[4], p["geoid_m"].get<double>(), 1e-8);
}

TEST_F(GravityGridCli, RegionalPixelGridUsesTheParallelPath) {
  ASSERT_EQ(run("gravity synth-model --degree 20 --seed 2 --out m").code, 0);
  const CmdResult r = run("gravity grid --model m.gfc --region -10/20/35/50 --spacing 5m/300s -r --quantities "
                          "dg_up,geoid --height 1000 -o reg.nc --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["path_used"], "parallel");
  EXPECT_EQ(j["registration"], "pixel");
  EXPECT_EQ(j["columns"], 360);
  EXPECT_EQ(j["rows"], 180);
  const CmdResult h = shell("ncdump -h reg.nc");
  EXPECT_NE(h.out.find(":node_offset = 1 ;"), std::string::npos) << h.out;
  EXPECT_NE(h.out.find(":height_m = 1000. ;"), std::string::npos) << h.out;
}

// Big-endian value at `p` (decoded here, independently of the writer and of read_gtx).
template <class T, class U>
T from_big_endian(const char* p) {
  U u = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) u = static_cast<U>((u << 8) | static_cast<unsigned char>(p[i]));
  T t;
  std::memcpy(&t, &u, sizeof t);
  return t;
}

std::string fmt_point(double lat, double lon) {
  std::ostringstream o;
  o << "gravity point --model m.gfc --json " << lat << " " << lon;
  return o.str();
}

TEST_F(GravityGridCli, GeoidAsGtxHasTheHeaderAndValuesOfGravityPoint) {
  ASSERT_EQ(run("gravity synth-model --degree 30 --seed 5 --out m").code, 0);
  const CmdResult r = run("gravity grid --model m.gfc -R -30/60/-45/45 -I 15d --quantities geoid -o n.gtx --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["format"], "gtx");
  const std::string d = slurp(dir_ / "n.gtx");
  ASSERT_EQ(d.size(), 40u + 4u * 7u * 7u);
  EXPECT_EQ((from_big_endian<double, std::uint64_t>(d.data())), -45.0);       // first node's latitude
  EXPECT_EQ((from_big_endian<double, std::uint64_t>(d.data() + 8)), -30.0);   // and longitude
  EXPECT_EQ((from_big_endian<double, std::uint64_t>(d.data() + 16)), 15.0);   // spacings
  EXPECT_EQ((from_big_endian<double, std::uint64_t>(d.data() + 24)), 15.0);
  EXPECT_EQ((from_big_endian<std::int32_t, std::uint32_t>(d.data() + 32)), 7);  // rows
  EXPECT_EQ((from_big_endian<std::int32_t, std::uint32_t>(d.data() + 36)), 7);  // columns
  // Node (lat 15, lon 45): row 4 from the south, column 5 from the west; float32 of N.
  const float got = from_big_endian<float, std::uint32_t>(d.data() + 40 + 4 * (4 * 7 + 5));
  const auto p = nlohmann::json::parse(run("gravity point --model m.gfc 15 45 --json").out);
  const double want = p["geoid_m"].get<double>();
  EXPECT_NE(want, 0.0);
  EXPECT_EQ(got, static_cast<float>(want));
  // PROJ (an independent reader of the format) applies the grid as a vertical shift: z + N.
  const CmdResult proj = shell("echo '45 15 0 0' | PROJ_NETWORK=OFF cct -d 7 +proj=vgridshift +grids=./n.gtx +multiplier=1");
  ASSERT_EQ(proj.code, 0) << "cct (Debian's proj-bin, installed by scripts/setup.sh) is required: " << proj.err;
  std::istringstream fields(proj.out);
  double lon = 0, lat = 0, z = 0;
  fields >> lon >> lat >> z;
  EXPECT_EQ(lon, 45.0) << proj.out;
  EXPECT_EQ(lat, 15.0) << proj.out;
  EXPECT_NEAR(z, want, 1e-5) << proj.out;  // float32 in the file, 7 decimals printed

  // A global gridline grid (0…360) is stored without its repeated column (PROJ misplaced every
  // value east of it when it was there): nodes east of 180° through PROJ equal gravity point.
  const CmdResult g = run("gravity grid --model m.gfc -R g -I 15d --quantities geoid -o g.gtx -q");
  ASSERT_EQ(g.code, 0) << g.err;
  const std::string gd = slurp(dir_ / "g.gtx");
  ASSERT_EQ(gd.size(), 40u + 4u * 13u * 24u);
  EXPECT_EQ((from_big_endian<std::int32_t, std::uint32_t>(gd.data() + 36)), 24);
  for (const char* node : {"195 30", "-15 -45", "345 60", "0 0"}) {
    const CmdResult at = shell(std::string("echo '") + node +
                               " 0 0' | PROJ_NETWORK=OFF cct -d 7 +proj=vgridshift +grids=./g.gtx +multiplier=1");
    ASSERT_EQ(at.code, 0) << at.err;
    std::istringstream in(at.out), where(node);
    double x = 0, y = 0, zz = 0, lo = 0, la = 0;
    in >> x >> y >> zz;
    where >> lo >> la;
    const auto pt = nlohmann::json::parse(run(fmt_point(la, lo)).out);
    EXPECT_NEAR(zz, pt["geoid_m"].get<double>(), 1e-5) << node << ": " << at.out;
  }
}

// GDAL (so QGIS) and GMT, independent readers, place both registrations where they are, with
// the grid's CRS: a pixel grid's extent is its region, a gridline grid's nodes are the centres
// of cells half a spacing beyond it (GDAL's raster view of point samples).
double gdal_number(const std::string& text, const std::string& key, int which) {
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return std::nan("");
  const std::size_t open = text.find('(', at);
  std::string inside = text.substr(open + 1, text.find(')', open) - open - 1);
  const std::size_t comma = inside.find(',');
  return std::stod(which == 0 ? inside.substr(0, comma) : inside.substr(comma + 1));
}

TEST_F(GravityGridCli, GdalAndGmtReadBothRegistrationsAndTheCrs) {
  ASSERT_EQ(run("gravity synth-model --degree 12 --seed 4 --out m").code, 0);
  struct Case {
    const char* args;
    double origin_lon, origin_lat, pixel_deg;
    const char* gmt_x;
    const char* gmt_y;
  };
  for (const Case& c : {Case{"-R g -I 30m -r", 0.0, 90.0, 0.5, "x_min: 0 x_max: 360", "y_min: -90 y_max: 90"},
                        Case{"-R d -I 1d -r", -180.0, 90.0, 1.0, "x_min: -180 x_max: 180", "y_min: -90 y_max: 90"},
                        Case{"-R -10/20/35/50 -I 15m -r", -10.0, 50.0, 0.25, "x_min: -10 x_max: 20",
                             "y_min: 35 y_max: 50"},
                        Case{"-R -10/20/35/50 -I 15m", -10.125, 50.125, 0.25, "x_min: -10 x_max: 20",
                             "y_min: 35 y_max: 50"}}) {
    SCOPED_TRACE(c.args);
    ASSERT_EQ(run(std::string("gravity grid --model m.gfc --quantities geoid,xi ") + c.args + " -o g.nc -q").code, 0);
    const CmdResult info = shell("gdalinfo NETCDF:g.nc:geoid");
    ASSERT_EQ(info.code, 0) << "gdalinfo (Debian's gdal-bin, installed by scripts/setup.sh) is required: "
                            << info.err;
    EXPECT_NEAR(gdal_number(info.out, "Origin =", 0), c.origin_lon, 1e-9) << info.out;
    EXPECT_NEAR(gdal_number(info.out, "Origin =", 1), c.origin_lat, 1e-9) << info.out;
    EXPECT_NEAR(gdal_number(info.out, "Pixel Size =", 0), c.pixel_deg, 1e-12) << info.out;
    EXPECT_NEAR(gdal_number(info.out, "Pixel Size =", 1), -c.pixel_deg, 1e-12) << info.out;
    EXPECT_NE(info.out.find("WGS 84"), std::string::npos) << "the CRS is not read:\n" << info.out;
    EXPECT_EQ(info.out.find("Coordinate System is `'"), std::string::npos) << info.out;
    const CmdResult g = shell("gmt grdinfo 'g.nc?geoid'");
    ASSERT_EQ(g.code, 0) << "gmt (Debian's gmt, installed by scripts/setup.sh) is required: " << g.err;
    EXPECT_NE(g.out.find(c.gmt_x), std::string::npos) << g.out;
    EXPECT_NE(g.out.find(c.gmt_y), std::string::npos) << g.out;
  }
  const CmdResult h = shell("ncdump -h g.nc");
  for (const char* want : {"int crs ;", "crs:grid_mapping_name = \"latitude_longitude\" ;",
                           "crs:semi_major_axis = 6378137. ;", "geoid:grid_mapping = \"crs\" ;",
                           "xi:grid_mapping = \"crs\" ;"})
    EXPECT_NE(h.out.find(want), std::string::npos) << want << "\n" << h.out;
}

TEST_F(GravityGridCli, AGlobalGtxSummarySaysTheColumnsItHolds) {
  ASSERT_EQ(run("gravity synth-model --degree 12 --seed 4 --out m").code, 0);
  const CmdResult r = run("gravity grid --model m.gfc -R g -I 15d --quantities geoid -o g.gtx -q");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("25 x 13 nodes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(24 x 13 stored"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(run("gravity grid --model m.gfc -R g -I 15d --quantities geoid -o g.gtx "
                                           "--json -q").out);
  EXPECT_EQ(j["columns"], 25);
  EXPECT_EQ(j["stored_columns"], 24);
  const std::string d = slurp(dir_ / "g.gtx");
  EXPECT_EQ((from_big_endian<std::int32_t, std::uint32_t>(d.data() + 36)), 24);
  const auto n = nlohmann::json::parse(run("gravity grid --model m.gfc -R g -I 15d --quantities geoid -o g.nc "
                                           "--json -q").out);
  EXPECT_EQ(n["stored_columns"], 25);
}

TEST_F(GravityGridCli, BadInputFailsBeforeAnyWork) {
  // The model does not exist: every error below must come before it is looked for.
  struct Case {
    const char* args;
    int code;
    const char* message;
  };
  const Case cases[] = {
      {"--region 30/10/0/10 --spacing 1 -o a.nc", 1, "W (30) must be less than E (10)"},
      {"--region 10/10/0/10 --spacing 1 -o a.nc", 1, "must be less than E"},
      {"--region 0/10/-95/10 --spacing 1 -o a.nc", 1, "must lie within [-90, 90]"},
      {"--region 0/10/0/10 --spacing 3 -o a.nc", 1, "not a whole multiple"},
      {"--region 0/1/0/1 --spacing 5d -o a.nc", 1, "gives no node"},
      {"--region g --spacing 0.05s -o a.nc", 1, "nodes, more than"},
      {"--region 0/10/0 --spacing 1 -o a.nc", 1, "cannot read region"},
      {"--region 0/10/0/10 --spacing 1q -o a.nc", 1, "cannot read spacing"},
      {"--region 0/10/0/10 --spacing 1 --quantities xi,zeta -o a.nc", 1, "unknown quantity \"zeta\""},
      {"--region 0/7/0/7 --spacing 0.7 --path fft -o a.nc", 1, "FFT path needs"},
      {"--region 0/10/0/10 --spacing 1 -o a.txt", 1, "from its extension"},
      {"--region g --spacing 5m -o big.csv", 1, "CSV grid is for small grids"},
      {"--region 0/10/0/10 --spacing 1 -o no/such/dir/a.nc", 4, "cannot write to the directory"},
      {"--region 0/10/0/10 --spacing 1 --quantities geoid,xi -o a.gtx", 1, "holds geoid heights only"},
  };
  for (const Case& c : cases) {
    const CmdResult r = run(std::string("gravity grid --model does-not-exist.gfc ") + c.args);
    EXPECT_EQ(r.code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.find("does-not-exist"), std::string::npos) << c.args << "\n" << r.err;
  }
  for (const auto& e : fs::directory_iterator(dir_)) {
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(name == "stdin" || name == "stdout" || name == "stderr") << name;
  }
  // Then the model: exit 4 (file), still no output.
  const CmdResult r = run("gravity grid --model does-not-exist.gfc --region 0/10/0/10 --spacing 1 -o a.nc");
  EXPECT_NE(r.code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "a.nc"));
}

}  // namespace gtest_cli_grid

namespace gtest_cli_grid {

TEST_F(GravityGridCli, PerNodeHeightsFromANetCdfGrid) {
  ASSERT_EQ(run("gravity synth-model --degree 24 --seed 7 --out m").code, 0);
  // A 5 x 3 height grid in CDL, turned into NetCDF by ncgen (netcdf-bin).
  write("h.cdl", "netcdf h {\ndimensions:\n lat = 3 ;\n lon = 5 ;\nvariables:\n double lat(lat) ;\n"
                 " double lon(lon) ;\n double elevation(lat, lon) ;\n  elevation:units = \"m\" ;\ndata:\n"
                 " lat = 40, 40.5, 41 ;\n lon = 0, 0.5, 1, 1.5, 2 ;\n"
                 " elevation = 0, 100, 200, 300, 400,\n  1000, 1100, 1200, 1300, 1400,\n"
                 "  2000, 2100, 2200, 2300, 2400 ;\n}\n");
  const CmdResult g = shell("ncgen -o h.nc h.cdl");
  ASSERT_EQ(g.code, 0) << "ncgen (netcdf-bin) is required: " << g.err;
  const CmdResult r = run("gravity grid --model m.gfc --region 0/2/40/41 --spacing 30m --height-grid h.nc "
                          "--quantities xi,eta,geoid -o out.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("heights per node from h.nc"), std::string::npos) << r.out;
  const auto rows = csv_rows(slurp(dir_ / "out.csv"));
  ASSERT_EQ(rows.size(), 15u);
  const auto& node = rows[1 * 5 + 3];  // lat 40.5, lon 1.5, h 1300 m
  EXPECT_EQ(node[0], 1.5);
  EXPECT_EQ(node[1], 40.5);
  const auto p = nlohmann::json::parse(run("gravity point --model m.gfc 40.5 1.5 1300 --json").out);
  EXPECT_NEAR(node[2], p["xi_arcsec"].get<double>(), 1e-8);
  EXPECT_NEAR(node[3], p["eta_arcsec"].get<double>(), 1e-8);
  EXPECT_NEAR(node[4], p["geoid_m"].get<double>(), 1e-8);
  // Another grid than the heights': refused before the model is loaded; --height and
  // --height-grid together: a usage error.
  const CmdResult bad = run("gravity grid --model nope.gfc --region 0/2/40/41 --spacing 15m --height-grid h.nc -o b.nc");
  EXPECT_EQ(bad.code, 1) << bad.err;
  EXPECT_NE(bad.err.find("the height grid has 5 x 3 nodes"), std::string::npos) << bad.err;
  EXPECT_EQ(run("gravity grid --model m.gfc --region 0/2/40/41 --spacing 30m --height 5 --height-grid h.nc -o c.nc").code,
            2);
  EXPECT_FALSE(fs::exists(dir_ / "b.nc"));
  EXPECT_FALSE(fs::exists(dir_ / "c.nc"));
}

}  // namespace gtest_cli_grid
