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

namespace {

using namespace gtest_gravity;
using meridian::gravity::GridInterpolation;
constexpr double kDeg = meridian::units::kDegree;

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

std::string gtx_bytes(int rows, int cols, double lat0, double lon0, double step) {
  std::string s;
  put_be(s, lat0);
  put_be(s, lon0);
  put_be(s, step);
  put_be(s, step);
  put_be<std::int32_t>(s, rows);
  put_be<std::int32_t>(s, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) put_be(s, static_cast<float>(quad(lat0 + r * step, lon0 + c * step) - 1000));
  return s;
}

TEST(GeoidGrid, PgmBilinearMatchesGeographicLibGeoid) {
  const std::string name = write_pgm("synthgeoid");
  const GeographicLib::Geoid gl(name, scratch_dir().string(), false);
  const auto g = meridian::gravity::read_geoid_grid(scratch_dir() / (name + ".pgm"));
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
  const auto g = meridian::gravity::read_geoid_grid(p);
  EXPECT_FALSE(g.wraps_longitude);
  for (double la = 30.6; la < 39.5; la += 1.37)
    for (double lo = 100.6; lo < 114.5; lo += 2.11) {
      const double h = meridian::gravity::grid_geoid_height_m(g, la * kDeg, lo * kDeg);
      EXPECT_NEAR(h, quad(la, lo) - 1000, 2e-4) << la << " " << lo;  // float32 storage
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
      (void)meridian::gravity::read_geoid_grid(p);
      ADD_FAILURE() << frag;
    } catch (const meridian::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(frag), std::string::npos) << e.what();
    }
  };
  expect("short.gtx", good.substr(0, good.size() - 3), "a 5 x 5 grid needs");
  expect("hdr.gtx", good.substr(0, 20), "too short");
  expect("bad.pgm", "P2\n", "not a binary PGM");
  expect("odd.pgm", "P5\n# Offset 0\n# Scale 1\n3 3\n65535\n", "bad raster size");
  std::string nodata = good;
  const float nd = -88.8888f;
  std::string be;
  put_be(be, nd);
  nodata.replace(40 + 4 * 12, 4, be);  // centre node
  const fs::path p = scratch_dir() / "nodata.gtx";
  std::ofstream(p, std::ios::binary) << nodata;
  const auto g = meridian::gravity::read_geoid_grid(p);
  EXPECT_THROW(meridian::gravity::grid_geoid_height_m(g, 2.1 * kDeg, 2.1 * kDeg), meridian::InputError);
  EXPECT_NO_THROW(meridian::gravity::grid_geoid_height_m(g, 0.5 * kDeg, 3.5 * kDeg, GridInterpolation::Bilinear));
}

}  // namespace
