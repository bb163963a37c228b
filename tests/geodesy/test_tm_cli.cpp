// Cross-check against GeographicLib's own command-line tool
// TransverseMercatorProj (Debian package geographiclib-tools). Its input is
// generated and its output read at test time; nothing is hard-coded.
//
// The tool prints easting, northing (no false origin), convergence γ in
// degrees and scale k; with -r it reads easting, northing and prints
// latitude, longitude, γ and k. It is run twice: with -s (Krüger series,
// the algorithm of GeographicLib::TransverseMercator, so agreement is at
// the print precision) and without (exact, Lee's elliptic-function
// formulation, an independent algorithm). Tolerances: 1 mm in position,
// 0.001″ in γ, 1e-9 in k. Built as test_geodesy_reference (CTest label
// `reference`); it fails when the tool is missing.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/units.hpp"
#include "meridian/geodesy/grid.hpp"

namespace mg = meridian::geodesy;
namespace mu = meridian::units;

namespace {

constexpr const char* kTool = "TransverseMercatorProj";
constexpr double kTolPosition_m = 1e-3;
constexpr double kTolGamma_arcsec = 1e-3;
constexpr double kTolScale = 1e-9;

struct Case {
  mg::GridDefinition def;
  double lat_deg;
  double lon_deg;
};

struct Row {
  double a, b, gamma_deg, k;  // forward: E', N'; reverse: lat, lon
};

std::string find_on_path(const std::string& exe) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return {};
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/" + exe;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

// Fixed notation only: the tool's DMS parser would read an exponent's 'e'
// as the hemisphere designator "east".
std::string fixed(double v, int decimals) { return fmt::format("{:.{}f}", v, decimals); }

// Runs the tool on `lines` ("a b" pairs) for grid `d`; `series` selects -s.
std::vector<Row> run_tool(const std::string& exe, const mg::GridDefinition& d, bool reverse,
                          bool series, const std::vector<std::string>& lines) {
  std::string input;
  for (const std::string& l : lines) input += (input.empty() ? "" : ";") + l;
  const std::string cmd = fmt::format(
      "'{}' {} {} -l {} -k {} -e {} {} -p 9 --input-string \"{}\" 2>&1", exe,
      series ? "-s" : "-t", reverse ? "-r" : "", fixed(d.central_meridian_rad / mu::kDegree, 15),
      fixed(d.scale_factor, 15), fixed(d.ellipsoid.a_m, 6), fixed(d.ellipsoid.f, 20), input);
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "popen failed for: " << cmd;
    return {};
  }
  std::string out;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
  const int status = ::pclose(pipe);
  EXPECT_EQ(status, 0) << cmd << "\n" << out;
  std::vector<Row> rows;
  std::stringstream ss(out);
  std::string line;
  while (std::getline(ss, line)) {
    std::stringstream ls(line);
    Row r{};
    if (!(ls >> r.a >> r.b >> r.gamma_deg >> r.k)) {
      ADD_FAILURE() << "unparsable line from " << kTool << ": " << line << "\ncommand: " << cmd;
      continue;
    }
    rows.push_back(r);
  }
  EXPECT_EQ(rows.size(), lines.size()) << cmd << "\n" << out;
  return rows;
}

std::vector<Case> cases() {
  mg::GridDefinition custom;
  custom.system = mg::ZoneSystem::Custom;
  custom.central_meridian_rad = mu::deg_to_rad(123.5);
  custom.scale_factor = 0.9999;
  custom.false_easting_m = 300000;
  custom.false_northing_m = -2000000;
  custom.ellipsoid = mg::krassovsky1940();
  mg::GridDefinition wide = custom;
  wide.ellipsoid = mg::wgs84();
  wide.central_meridian_rad = mu::deg_to_rad(-60);
  return {
      {mg::utm(50, true), 39.9042, 116.4074},                       // Beijing, UTM 50N
      {mg::utm(50, true), 45.5, 119.9},                             // near the east edge
      {mg::utm(56, false), -33.8688, 151.2093},                     // Sydney, UTM 56S, west of CM
      {mg::utm(56, false), -12.5, 155.7},                           // UTM 56S, east of CM
      {mg::utm(33, false), -25.7, 12.1},                            // UTM 33S
      {mg::utm(32, true, mg::grs80()), 52.0, 10.2},                 // GRS80
      {mg::utm(1, true), 64.8, -179.9},                             // zone 1, CM 177W
      {mg::gauss_kruger_3(38, mg::cgcs2000(), true), 30.5928, 114.3055},  // Wuhan, 3° CGCS2000
      {mg::gauss_kruger_3(38, mg::cgcs2000(), true), 31.2, 112.55},       // west edge
      {mg::gauss_kruger_3(39, mg::cgcs2000()), 39.9042, 116.4074},
      {mg::gauss_kruger_3(120, mg::wgs84()), 51.4779, -0.0015},     // CM 360°
      {mg::gauss_kruger_6(20, mg::krassovsky1940(), true), 40.0, 119.8},  // Beijing 1954
      {mg::gauss_kruger_6(19, mg::iag75()), 34.2658, 108.9541},    // Xi'an 1980
      {mg::gauss_kruger_6(21, mg::iag75(), true), 47.0, 120.2},
      {custom, 60.0, 140.0},                                        // 16.5° from CM
      {custom, -5.0, 123.5},                                        // on the CM, south
      {wide, 10.0, -20.0},                                          // 40° from CM
  };
}

double prefix_m(const mg::GridDefinition& d) { return d.zone_prefix ? d.zone * 1e6 : 0.0; }

struct MaxDiff {
  double position_m = 0, gamma_arcsec = 0, scale = 0;
  void print(const char* what) const {
    std::printf("[ geodesy  ] vs %s %s: max |d pos| %.3e m, |d gamma| %.3e\", |d k| %.3e\n",
                kTool, what, position_m, gamma_arcsec, scale);
  }
};

void compare(bool series) {
  const std::string exe = find_on_path(kTool);
  // A missing tool is a failure, not a skip: these are the reference checks.
  ASSERT_FALSE(exe.empty()) << "reference tool " << kTool << " not found on PATH; it comes with "
                            << "the Debian package geographiclib-tools, which scripts/setup.sh "
                            << "installs (apt-get install geographiclib-tools)";
  MaxDiff fwd, rev;
  for (const Case& c : cases()) {
    const mg::GridDefinition& d = c.def;
    SCOPED_TRACE(fmt::format("{} at {} {}", mg::describe(d), c.lat_deg, c.lon_deg));
    const mg::TransverseMercatorGrid g(d);
    const mg::GridPoint p = g.forward(mu::deg_to_rad(c.lat_deg), mu::deg_to_rad(c.lon_deg));

    const std::vector<Row> f =
        run_tool(exe, d, false, series, {fixed(c.lat_deg, 12) + " " + fixed(c.lon_deg, 12)});
    ASSERT_EQ(f.size(), 1u);
    const double de = p.y_east_m - (f[0].a + d.false_easting_m + prefix_m(d));
    const double dn = p.x_north_m - (f[0].b + d.false_northing_m);
    const double dg = mu::rad_to_arcsec(p.convergence_rad) - f[0].gamma_deg * 3600;
    EXPECT_NEAR(de, 0, kTolPosition_m);
    EXPECT_NEAR(dn, 0, kTolPosition_m);
    EXPECT_NEAR(dg, 0, kTolGamma_arcsec);
    EXPECT_NEAR(p.scale, f[0].k, kTolScale);
    fwd.position_m = std::max(fwd.position_m, std::hypot(de, dn));
    fwd.gamma_arcsec = std::max(fwd.gamma_arcsec, std::abs(dg));
    fwd.scale = std::max(fwd.scale, std::abs(p.scale - f[0].k));

    // Reverse at a grid point 1234.567 m north-east of the projected point.
    const double x = p.x_north_m + 1234.567;
    const double y = p.y_east_m + 1234.567;
    const mg::GeographicPoint q = g.reverse(x, y);
    const std::vector<Row> r =
        run_tool(exe, d, true, series,
                 {fixed(y - d.false_easting_m - prefix_m(d), 9) + " " +
                  fixed(x - d.false_northing_m, 9)});
    ASSERT_EQ(r.size(), 1u);
    const double dlat = q.lat_rad - mu::deg_to_rad(r[0].a);
    // Longitudes compared modulo 360° (the tool returns [-180°, 180°]).
    const double dlon = std::remainder(q.lon_rad - mu::deg_to_rad(r[0].b), 2 * mu::kPi);
    const double dpos = d.ellipsoid.a_m * std::hypot(dlat, dlon * std::cos(q.lat_rad));
    const double dgr = mu::rad_to_arcsec(q.convergence_rad) - r[0].gamma_deg * 3600;
    EXPECT_LT(dpos, kTolPosition_m);
    EXPECT_NEAR(dgr, 0, kTolGamma_arcsec);
    EXPECT_NEAR(q.scale, r[0].k, kTolScale);
    rev.position_m = std::max(rev.position_m, dpos);
    rev.gamma_arcsec = std::max(rev.gamma_arcsec, std::abs(dgr));
    rev.scale = std::max(rev.scale, std::abs(q.scale - r[0].k));
  }
  fwd.print(series ? "-s forward" : "(exact) forward");
  rev.print(series ? "-s -r reverse" : "(exact) -r reverse");
}

}  // namespace

TEST(GridVsTransverseMercatorProj, KruegerSeries) { compare(true); }
TEST(GridVsTransverseMercatorProj, ExactAlgorithm) { compare(false); }
