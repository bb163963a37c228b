// Geoid grids: .pgm against GeographicLib's Geoid on the same file,
// .gtx against closed-form surfaces, and damaged files.

#include <GeographicLib/Geoid.hpp>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include "gravity_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/io/gravity_geoid_grid.hpp"
#include "test_units.hpp"

namespace {

using namespace gtest_gravity;
using gtest_gravity::kDeg;
using meridian::gravity::GridInterpolation;

template <class T>
void put_be(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof b);
  if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + sizeof b);
  out.append(b, sizeof b);
}

double surface(double lat_deg, double lon_deg) {
  return 5 + 10 * std::sin(2 * lat_deg * kDeg) * std::cos(3 * lon_deg * kDeg) + 3 * std::cos(lat_deg * kDeg);
}

// A 1° GeographicLib-style PGM of `surface`.
std::string write_pgm(const std::string& name) {
  const int w = 360, h = 181;
  const double offset = -108, scale = 0.003;
  std::string s = "P5\n# Description synthetic\n# Offset " + std::to_string(offset) + "\n# Scale 0.003\n" +
                  std::to_string(w) + " " + std::to_string(h) + "\n65535\n";
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      put_be<std::uint16_t>(s, static_cast<std::uint16_t>(std::lround((surface(90.0 - r, c) - offset) / scale)));
  std::ofstream(scratch_dir() / (name + ".pgm"), std::ios::binary) << s;
  return name;
}

double quad(double lat_deg, double lon_deg) {
  return 1 + 0.3 * lat_deg + 0.2 * lon_deg + 0.01 * lat_deg * lat_deg - 0.02 * lat_deg * lon_deg + 0.005 * lon_deg * lon_deg;
}

// A .gtx of rows × cols nodes from (lat0, lon0) with the heights `value(r, c)`.
template <class F>
std::string gtx_of(int rows, int cols, double lat0, double lon0, double step, F value) {
  std::string s;
  put_be(s, lat0);
  put_be(s, lon0);
  put_be(s, step);
  put_be(s, step);
  put_be<std::int32_t>(s, rows);
  put_be<std::int32_t>(s, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) put_be(s, static_cast<float>(value(r, c)));
  return s;
}

std::string gtx_bytes(int rows, int cols, double lat0, double lon0, double step) {
  // Heights within the physical range (|N| <= 150 m).
  return gtx_of(rows, cols, lat0, lon0, step,
                [&](int r, int c) { return quad(lat0 + r * step, lon0 + c * step) - 100; });
}

TEST(GeoidGrid, PgmBilinearMatchesGeographicLibGeoid) {
  const std::string name = write_pgm("synthgeoid");
  const GeographicLib::Geoid gl(name, scratch_dir().string(), false);
  const auto g = meridian::io::read_geoid_grid(scratch_dir() / (name + ".pgm"));
  EXPECT_TRUE(g.wraps_longitude);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> lat(-90, 90), lon(-180, 360);
  for (int i = 0; i < 200; ++i) {
    const double la = lat(rng), lo = lon(rng);
    EXPECT_NEAR(meridian::gravity::grid_geoid_height_m(g, la * kDeg, lo * kDeg, GridInterpolation::Bilinear), gl(la, lo),
                1e-9)
        << la << " " << lo;
    // Bicubic is closer to the smooth surface than bilinear on average, and
    // both are within the 1° grid's interpolation error.
    EXPECT_NEAR(meridian::gravity::grid_geoid_height_m(g, la * kDeg, lo * kDeg), surface(la, lo), 0.01) << la << " " << lo;
  }
}

TEST(GeoidGrid, GtxBicubicReproducesQuadraticsAndFallbackSlopes) {
  const fs::path p = scratch_dir() / "quad.gtx";
  std::ofstream(p, std::ios::binary) << gtx_bytes(41, 61, 30, 100, 0.25);
  const auto g = meridian::io::read_geoid_grid(p);
  EXPECT_FALSE(g.wraps_longitude);
  for (double la = 30.6; la < 39.5; la += 1.37)
    for (double lo = 100.6; lo < 114.5; lo += 2.11) {
      const double h = meridian::gravity::grid_geoid_height_m(g, la * kDeg, lo * kDeg);
      EXPECT_NEAR(h, quad(la, lo) - 100, 2e-5) << la << " " << lo;  // float32 storage
      const auto d = meridian::gravity::grid_deflection_fallback(g, la * kDeg, lo * kDeg);
      const double e2 = (2 - 1 / 298.257223563) / 298.257223563, s = std::sin(la * kDeg), w = std::sqrt(1 - e2 * s * s);
      const double mr = 6378137.0 * (1 - e2) / (w * w * w), nr = 6378137.0 / w;
      const double dlat = 0.3 + 0.02 * la - 0.02 * lo, dlon = 0.2 - 0.02 * la + 0.01 * lo;  // per degree
      EXPECT_NEAR(d.xi_rad, -dlat / kDeg / mr, 1e-3 * std::abs(dlat / kDeg / mr) + 1e-9);
      EXPECT_NEAR(d.eta_rad, -dlon / kDeg / (nr * std::cos(la * kDeg)), 1e-3 * std::abs(dlon / kDeg / nr) + 1e-9);
      EXPECT_NE(std::string(d.method).find("fallback"), std::string::npos);
    }
  EXPECT_THROW(meridian::gravity::grid_geoid_height_m(g, 45 * kDeg, 105 * kDeg), meridian::InputError);
}

TEST(GeoidGrid, RejectsDamagedFilesAndNoData) {
  const std::string good = gtx_bytes(5, 5, 0, 0, 1);
  auto expect = [&](const std::string& name, const std::string& bytes, const std::string& frag) {
    const fs::path p = scratch_dir() / name;
    std::ofstream(p, std::ios::binary) << bytes;
    try {
      (void)meridian::io::read_geoid_grid(p);
      ADD_FAILURE() << frag;
    } catch (const meridian::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(frag), std::string::npos) << e.what();
    }
  };
  expect("short.gtx", good.substr(0, good.size() - 3), "a 5 x 5 grid needs");
  expect("hdr.gtx", good.substr(0, 20), "too short");
  // One parallel (`gravity grid` writes it; PROJ reads it) is no surface to interpolate.
  expect("row.gtx", gtx_bytes(1, 5, 10, 0, 1), "a 1 x 5 .gtx grid (a single parallel) cannot be interpolated");
  expect("col.gtx", gtx_bytes(5, 1, 10, 0, 1), "a 5 x 1 .gtx grid (a single meridian) cannot be interpolated");
  expect("bad.pgm", "P2\n", "not a binary PGM");
  expect("odd.pgm", "P5\n# Offset 0\n# Scale 1\n3 3\n65535\n", "bad raster size");
  std::string nodata = good;
  const float nd = -88.8888f;
  std::string be;
  put_be(be, nd);
  nodata.replace(40 + 4 * 12, 4, be);  // centre node
  const fs::path p = scratch_dir() / "nodata.gtx";
  std::ofstream(p, std::ios::binary) << nodata;
  const auto g = meridian::io::read_geoid_grid(p);
  EXPECT_THROW(meridian::gravity::grid_geoid_height_m(g, 2.1 * kDeg, 2.1 * kDeg), meridian::InputError);
  EXPECT_NO_THROW(meridian::gravity::grid_geoid_height_m(g, 0.5 * kDeg, 3.5 * kDeg, GridInterpolation::Bilinear));
}

}  // namespace

// ---------------------------------------------------------------------------
// Conventions of grids that circulate (issue 16): a global grid from −180°
// without a repeated column, regional grids across the antimeridian, tiles
// with no-data nodes. Each grid is generated here from a formula; the files
// of ../shared/cases/geoid-grids are checked too when present.

namespace {

namespace gg = meridian::gravity;

fs::path write_bytes(const std::string& name, const std::string& bytes) {
  const fs::path p = scratch_dir() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

// A smooth global surface on whole centimetres (so a .pgm with scale 0.001
// holds it exactly).
double cm_surface(double lat_deg, double lon_deg) {
  return std::round(100 * (-5 - 3 * std::sin(2 * lon_deg * kDeg) * std::cos(lat_deg * kDeg) +
                           8 * std::sin(lat_deg * kDeg) * std::cos(lon_deg * kDeg))) /
         100;
}

// The geometry of ../shared/cases/geoid-grids/west-180.gtx (PROJ's
// egm96_15.gtx convention): 19 × 36 nodes of 10°, columns from −180°, no
// repeated column at +180°.
std::string west180_bytes() {
  return gtx_of(19, 36, -90, -180, 10, [](int r, int c) { return cm_surface(-90 + 10 * r, -180 + 10 * c); });
}

// The same nodes as a GeographicLib .pgm (rows from 90° N, columns from 0° E)
// for GeographicLib::Geoid: read back from the .gtx's own float32 values.
std::string pgm_of_global_gtx(const gg::GeoidGrid& g, const std::string& name) {
  const int rows = g.rows, cols = g.lon_period_cols;
  std::string s = "P5\n# Description converted\n# Offset -30\n# Scale 0.001\n" + std::to_string(cols) + " " +
                  std::to_string(rows) + "\n65535\n";
  const int shift = static_cast<int>(std::lround(-g.first_lon_rad / g.dlon_rad));  // gtx column of 0° E
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double v = *g.node_m(rows - 1 - r, (c + shift) % cols);
      put_be<std::uint16_t>(s, static_cast<std::uint16_t>(std::lround((v + 30) / 0.001)));
    }
  std::ofstream(scratch_dir() / (name + ".pgm"), std::ios::binary) << s;
  return name;
}

// Bilinear interpolation written out from its definition (independent of the code under test).
double bilinear_by_hand(double v00, double v01, double v10, double v11, double y, double x) {
  return (1 - y) * (1 - x) * v00 + (1 - y) * x * v01 + y * (1 - x) * v10 + y * x * v11;
}

fs::path shared_case(const std::string& name) {
  return fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "cases" / "geoid-grids" / name;
}

TEST(GeoidGridCases, GlobalGridFromMinus180WithoutRepeatedColumnWraps) {
  const auto g = meridian::io::read_geoid_grid(write_bytes("w180.gtx", west180_bytes()));
  EXPECT_TRUE(g.wraps_longitude);
  EXPECT_EQ(g.lon_period_cols, 36);
  // In the last cell (170° E – 180°) and across it, in every spelling of the longitude.
  const double y = (9.9959 - 0) / 10, x = (175.3 - 170) / 10;
  const double expect = bilinear_by_hand(cm_surface(0, 170), cm_surface(0, 180), cm_surface(10, 170),
                                         cm_surface(10, 180), y, x);
  for (double lon : {175.3, 175.3 - 360, 175.3 + 360})
    EXPECT_NEAR(gg::grid_geoid_height_m(g, 9.9959 * kDeg, lon * kDeg, GridInterpolation::Bilinear), expect, 1e-6) << lon;
  const GeographicLib::Geoid gl(pgm_of_global_gtx(g, "w180conv"), scratch_dir().string(), false);
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> lat(-90, 90), lon(-180, 180), edge(170, 190);
  for (int i = 0; i < 300; ++i) {
    const double la = lat(rng), lo = i % 2 ? lon(rng) : edge(rng);
    EXPECT_NEAR(gg::grid_geoid_height_m(g, la * kDeg, lo * kDeg, GridInterpolation::Bilinear), gl(la, lo), 1e-6)
        << la << " " << lo;
    EXPECT_NO_THROW((void)gg::evaluate_grid_point(g, la * kDeg, lo * kDeg));
  }
  // The same grid with the repeated column at +180° is global too, with the same heights.
  const auto r = meridian::io::read_geoid_grid(write_bytes(
      "w180rep.gtx", gtx_of(19, 37, -90, -180, 10, [](int a, int c) { return cm_surface(-90 + 10 * a, -180 + 10 * c); })));
  EXPECT_TRUE(r.wraps_longitude);
  EXPECT_EQ(gg::grid_geoid_height_m(r, 9.9959 * kDeg, 175.3 * kDeg), gg::grid_geoid_height_m(g, 9.9959 * kDeg, 175.3 * kDeg));
}

TEST(GeoidGridCases, SharedWest180CaseWhenPresent) {
  const fs::path p = shared_case("west-180.gtx");
  if (!fs::exists(p)) GTEST_SKIP() << p << " not present (optional data; the generated grid is tested above)";
  const auto g = meridian::io::read_geoid_grid(p);
  // The value, computed with GeographicLib's GeoidEval -l on the grid as .pgm ...
  EXPECT_NEAR(gg::grid_geoid_height_m(g, 9.9959 * kDeg, 175.3 * kDeg, GridInterpolation::Bilinear), -15.715771, 1e-6);
  // ... and again here with GeographicLib::Geoid on the .pgm written from this file.
  const GeographicLib::Geoid gl(pgm_of_global_gtx(g, "w180shared"), scratch_dir().string(), false);
  EXPECT_NEAR(gl(9.9959, 175.3), -15.715771, 1e-6);
}

TEST(GeoidGridCases, RegionalLongitudesAreComparedModulo360) {
  auto plane = [](double lon0) {
    return [lon0](int r, int c) { return 10 + 0.1 * r + 0.05 * c + 0 * lon0; };
  };
  // 230°–250° E, 1° steps: −124.5° is 235.5° E.
  const auto a = meridian::io::read_geoid_grid(write_bytes("east230.gtx", gtx_of(11, 21, 40, 230, 1, plane(230))));
  EXPECT_FALSE(a.wraps_longitude);
  EXPECT_NEAR(gg::grid_geoid_height_m(a, 45.25 * kDeg, -124.5 * kDeg), 10 + 0.1 * 5.25 + 0.05 * 5.5, 1e-5);
  EXPECT_NEAR(gg::grid_geoid_height_m(a, 45.25 * kDeg, 235.5 * kDeg), 10 + 0.1 * 5.25 + 0.05 * 5.5, 1e-5);
  // 172°–190° E across the antimeridian: −179° is 181° E; 180° and −180° are the same column.
  const auto b = meridian::io::read_geoid_grid(write_bytes("anti.gtx", gtx_of(6, 19, -20, 172, 1, plane(172))));
  for (double lon : {-179.0, 181.0, 541.0})
    EXPECT_NEAR(gg::grid_geoid_height_m(b, -17.5 * kDeg, lon * kDeg), 10 + 0.1 * 2.5 + 0.05 * 9, 1e-5) << lon;
  EXPECT_NEAR(gg::grid_geoid_height_m(b, -17.5 * kDeg, -180 * kDeg), gg::grid_geoid_height_m(b, -17.5 * kDeg, 180 * kDeg),
              1e-12);
  EXPECT_NEAR(gg::grid_geoid_height_m(b, -17.5 * kDeg, (172 - 360) * kDeg), 10 + 0.25, 1e-5);  // the west edge
  // Outside: the field is the coordinate that is out.
  auto field_of = [&](double la, double lo) {
    try {
      (void)gg::grid_geoid_height_m(b, la * kDeg, lo * kDeg);
    } catch (const meridian::InputError& e) {
      return e.context().field + ": " + e.message();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field_of(-17.5, 200).rfind("lon: longitude 200.000000 deg is outside the grid's longitudes [172.000000, "
                                       "190.000000] deg",
                                       0),
            0u)
      << field_of(-17.5, 200);
  EXPECT_EQ(field_of(-17.5, -160).rfind("lon: ", 0), 0u) << field_of(-17.5, -160);
  EXPECT_EQ(field_of(-30, 180).rfind("lat: latitude -30.000000 deg is outside", 0), 0u) << field_of(-30, 180);
}

// ../shared/cases/geoid-grids/tile.gtx: 6 × 6 nodes of 0.5° from 56° N 21° E
// on the plane N = 20 + 0.8(φ − 56) − 0.6(λ − 21); (57.5, 22.5) holds the GTX
// no-data value, (56.0, 23.5) holds 9999.
double tile_plane(double lat, double lon) { return 20 + 0.8 * (lat - 56) - 0.6 * (lon - 21); }

std::string tile_bytes() {
  return gtx_of(6, 6, 56, 21, 0.5, [](int r, int c) {
    const double lat = 56 + 0.5 * r, lon = 21 + 0.5 * c;
    if (lat == 57.5 && lon == 22.5) return static_cast<double>(gg::GeoidGrid::kGtxNoData);
    if (lat == 56.0 && lon == 23.5) return 9999.0;
    return tile_plane(lat, lon);
  });
}

void check_tile(const gg::GeoidGrid& g) {
  // 56.30 21.20, bicubic asked: at the grid's south-west edge (bilinear, exact
  // on a plane), and the deflection's southern neighbour (55.8°) is outside
  // the grid: N is still given, the deflection reported unavailable.
  gg::GridPointResult r = gg::evaluate_grid_point(g, 56.30 * kDeg, 21.20 * kDeg);
  EXPECT_NEAR(r.geoid_m, 20.1200, 1e-5);
  EXPECT_NEAR(r.geoid_m, tile_plane(56.30, 21.20), 1e-5);
  EXPECT_EQ(r.interpolation_used, GridInterpolation::Bilinear);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("edge"), std::string::npos) << r.notes[0];
  EXPECT_FALSE(r.fallback.has_value());
  EXPECT_NE(r.fallback_unavailable.find("latitude 55.800000 deg is outside"), std::string::npos) << r.fallback_unavailable;
  // 56.70 21.90 bilinear: its four nodes are valid; so are the deflection's.
  r = gg::evaluate_grid_point(g, 56.70 * kDeg, 21.90 * kDeg, GridInterpolation::Bilinear);
  EXPECT_NEAR(r.geoid_m, 20.0200, 1e-5);
  EXPECT_TRUE(r.notes.empty());
  ASSERT_TRUE(r.fallback.has_value());
  // The plane's slope: ξ = −0.8 m/° over the meridian radius, η = +0.6 m/° over N cos φ.
  const double e2 = (2 - 1 / 298.257223563) / 298.257223563, s = std::sin(56.7 * kDeg), w = std::sqrt(1 - e2 * s * s);
  EXPECT_NEAR(r.fallback->xi_rad, -0.8 / kDeg / (6378137.0 * (1 - e2) / (w * w * w)), 1e-9);
  EXPECT_NEAR(r.fallback->eta_rad, 0.6 / kDeg / (6378137.0 / w * std::cos(56.7 * kDeg)), 1e-9);
  // The same point bicubic: its 4 × 4 nodes include (57.5, 22.5) with a
  // non-zero weight, so bilinear is used and the note names the node.
  const gg::GridHeight h = gg::grid_geoid_height(g, 56.70 * kDeg, 21.90 * kDeg);
  EXPECT_NEAR(h.geoid_m, 20.0200, 1e-5);
  EXPECT_EQ(h.used, GridInterpolation::Bilinear);
  EXPECT_NE(h.note.find("lat 57.500000 deg, lon 22.500000 deg, which holds -88.8888 (the GTX no-data value)"),
            std::string::npos)
      << h.note;
  // On a grid line the nodes beyond it have weight zero and are not needed:
  // 56.6 21.5 is bicubic although (57.5, 22.5) is in its 4 × 4 stencil.
  const gg::GridHeight on_line = gg::grid_geoid_height(g, 56.6 * kDeg, 21.5 * kDeg);
  EXPECT_EQ(on_line.used, GridInterpolation::Bicubic);
  EXPECT_NEAR(on_line.geoid_m, tile_plane(56.6, 21.5), 1e-5);
  // 56.20 23.30: a corner holds 9999 (plain bilinear would give 3611.76 m):
  // an error naming the node, with either interpolation.
  for (const auto interp : {GridInterpolation::Bilinear, GridInterpolation::Bicubic}) {
    try {
      (void)gg::grid_geoid_height_m(g, 56.20 * kDeg, 23.30 * kDeg, interp);
      ADD_FAILURE() << "no error";
    } catch (const meridian::InputError& e) {
      EXPECT_EQ(e.context().field, "node(0,5)");
      EXPECT_NE(e.message().find("lat 56.000000 deg, lon 23.500000 deg, which holds 9999"), std::string::npos)
          << e.what();
    }
  }
  // The no-data node itself is needed at 57.3 22.3 (bilinear).
  try {
    (void)gg::grid_geoid_height_m(g, 57.3 * kDeg, 22.3 * kDeg, GridInterpolation::Bilinear);
    ADD_FAILURE() << "no error";
  } catch (const meridian::InputError& e) {
    EXPECT_NE(e.message().find("-88.8888 (the GTX no-data value)"), std::string::npos) << e.what();
  }
}

TEST(GeoidGridCases, TileWithNoDataNodes) {
  const auto g = meridian::io::read_geoid_grid(write_bytes("tile.gtx", tile_bytes()));
  EXPECT_FALSE(g.node_m(3, 3).has_value());  // −88.8888
  EXPECT_FALSE(g.node_m(0, 5).has_value());  // 9999
  EXPECT_NEAR(*g.node_m(1, 1), tile_plane(56.5, 21.5), 1e-5);
  check_tile(g);
}

TEST(GeoidGridCases, SharedTileCaseWhenPresent) {
  const fs::path p = shared_case("tile.gtx");
  if (!fs::exists(p)) GTEST_SKIP() << p << " not present (optional data; the generated tile is tested above)";
  check_tile(meridian::io::read_geoid_grid(p));
}

TEST(GeoidGridCases, ImplausibleHeadersAreRejectedBeforeUse) {
  auto rejected = [](const std::string& name, const std::string& bytes) {
    const fs::path p = write_bytes(name, bytes);
    EXPECT_THROW((void)meridian::io::read_geoid_grid(p), meridian::ParseError) << name;
  };
  auto flat = [](int, int) { return 1.0; };
  rejected("wide.gtx", gtx_of(3, 40, 0, 0, 10, flat));        // 390° of columns
  rejected("pole.gtx", gtx_of(3, 3, 85, 0, 10, flat));        // rows beyond 90° N
  rejected("tinystep.gtx", gtx_of(2, 2, 0, 0, 0, flat));      // zero step
  rejected("nanorigin.gtx", gtx_of(2, 2, std::nan(""), 0, 1, flat));
  rejected("denormal.gtx", gtx_of(7, 12, -90, -180, 7.59e-321, flat));  // found by fuzz_grid_gtx: infinite slope
  // A header claiming 10^6 × 10^6 nodes in a file of 56 bytes: a size error, no allocation.
  std::string huge = gtx_of(2, 2, 0, 0, 1e-4, flat);
  std::string be;
  put_be<std::int32_t>(be, 1000000);
  huge.replace(32, 4, be);
  huge.replace(36, 4, be);
  rejected("huge.gtx", huge);
}

}  // namespace
