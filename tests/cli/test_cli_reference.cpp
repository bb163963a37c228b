// `meridian gravity point` against GeographicLib's own command-line tool
// Gravity (Debian geographiclib-tools, installed by scripts/setup.sh) on the
// same model file. CTest label `reference`: fails when the tool is missing.

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

using meridian_test::CmdResult;
class GravityCli : public meridian_test::CliTest {};

}  // namespace

TEST_F(GravityCli, PointJsonMatchesGeographicLibGravityTool) {
  ASSERT_EQ(run("gravity synth-model --degree 60 --seed 3 --out m").code, 0);
  const CmdResult r = run("gravity point --model m.egm -33.5 151.25 120 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"xi_arcsec", "eta_arcsec", "geoid_m"}) EXPECT_TRUE(j.contains(k)) << k;
  // The .gfc copy is the same model.
  const auto g = nlohmann::json::parse(run("gravity point --model m.gfc --json -- -33.5 151.25 120").out);
  EXPECT_NEAR(g["xi_arcsec"].get<double>(), j["xi_arcsec"].get<double>(), 1e-9);
  ASSERT_EQ(std::system("command -v Gravity > /dev/null 2>&1"), 0)
      << "GeographicLib's Gravity tool is needed (Debian geographiclib-tools; scripts/setup.sh installs it)";
  // Gravity -A prints Dg01 (mGal), xi, eta (arcsec); -H prints N (m).
  const CmdResult a = shell("echo '-33.5 151.25 120' | Gravity -n m -d . -A -p 9");
  const CmdResult h = shell("echo '-33.5 151.25' | Gravity -n m -d . -H -p 9");
  ASSERT_EQ(a.code, 0) << a.err;
  double dg, xi, eta, n;
  std::istringstream(a.out) >> dg >> xi >> eta;
  std::istringstream(h.out) >> n;
  EXPECT_NEAR(j["xi_arcsec"].get<double>(), xi, 1e-6);
  EXPECT_NEAR(j["eta_arcsec"].get<double>(), eta, 1e-6);
  EXPECT_NEAR(j["geoid_m"].get<double>(), n, 1e-6);
}


// `meridian gravity geoid-grid` on ../shared/cases/geoid-grids/west-180.gtx
// (a global grid from -180 deg without a repeated column) against
// GeographicLib's GeoidEval -l (bilinear) on the same nodes written here as a
// GeographicLib .pgm (rows from 90 N, columns from 0 E; the nodes are whole
// centimetres, so offset -30 m and scale 1 mm hold them exactly). Skipped
// when the case file is absent; fails when GeoidEval is missing.
TEST_F(GravityCli, GeoidGridMatchesGeoidEvalOnAGlobalGridFromMinus180) {
  namespace fs = std::filesystem;
  const fs::path gtx = fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "cases" / "geoid-grids" / "west-180.gtx";
  if (!fs::exists(gtx)) GTEST_SKIP() << gtx << " not present";
  std::ifstream in(gtx, std::ios::binary);
  const std::string d((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(d.size(), 40u + 4u * 19u * 36u);
  auto be32 = [&](std::size_t at) {
    std::uint32_t u = 0;
    for (int k = 0; k < 4; ++k) u = (u << 8) | static_cast<unsigned char>(d[at + static_cast<std::size_t>(k)]);
    return u;
  };
  auto node = [&](int r, int c) {  // gtx: row 0 at -90, column 0 at -180
    const std::uint32_t u = be32(40 + 4 * static_cast<std::size_t>(r * 36 + c));
    float f;
    std::memcpy(&f, &u, 4);
    return static_cast<double>(f);
  };
  std::string pgm = "P5\n# Description west-180.gtx as pgm\n# Offset -30\n# Scale 0.001\n36 19\n65535\n";
  for (int r = 0; r < 19; ++r)
    for (int c = 0; c < 36; ++c) {
      const long v = std::lround((node(18 - r, (c + 18) % 36) + 30) / 0.001);
      pgm += static_cast<char>((v >> 8) & 0xFF);
      pgm += static_cast<char>(v & 0xFF);
    }
  std::ofstream(dir_ / "w180.pgm", std::ios::binary) << pgm;
  ASSERT_EQ(std::system("command -v GeoidEval > /dev/null 2>&1"), 0)
      << "GeographicLib's GeoidEval tool is needed (Debian geographiclib-tools; scripts/setup.sh installs it)";
  for (const auto& [lat, lon] : std::vector<std::pair<double, double>>{
           {9.9959, 175.3}, {-45.2, 179.99}, {60.5, -179.5}, {0.1, -0.1}, {89.5, 123.4}, {-33.3, 185.0}}) {
    const std::string where = std::to_string(lat) + " " + std::to_string(lon);
    const CmdResult gl = shell("echo '" + where + "' | GeoidEval -n w180 -d . -l");
    ASSERT_EQ(gl.code, 0) << gl.err;
    double n_gl = 0;
    std::istringstream(gl.out) >> n_gl;
    const CmdResult r = run("gravity geoid-grid --grid " + gtx.string() + " --interpolation bilinear --json -- " + where);
    ASSERT_EQ(r.code, 0) << r.err;
    // GeoidEval prints 4 decimals; the nodes differ from their float32 copies by < 1e-6 m.
    EXPECT_NEAR(nlohmann::json::parse(r.out)["geoid_m"].get<double>(), n_gl, 6e-5) << where;
  }
  const CmdResult gl = shell("echo '9.9959 175.3' | GeoidEval -n w180 -d . -l");
  EXPECT_EQ(gl.out.rfind("-15.7158", 0), 0u) << gl.out;  // the issue's -15.715771 m
}
