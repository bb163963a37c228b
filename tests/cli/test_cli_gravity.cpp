// Runs `meridian gravity ...` as a user would, on synthetic models written by
// the CLI (the cross-check with GeographicLib's Gravity tool is in
// test_cli_reference.cpp).

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace fs = std::filesystem;

namespace {

using meridian_test::CmdResult;
class GravityCli : public meridian_test::CliTest {};

TEST_F(GravityCli, SynthModelWritesThreeFilesDeterministically) {
  ASSERT_EQ(run("gravity synth-model --degree 30 --seed 9 --out a").code, 0);
  ASSERT_EQ(run("gravity synth-model --degree 30 --seed 9 --out b").code, 0);
  for (const char* ext : {".gfc", ".egm.cof"}) {
    ASSERT_TRUE(fs::exists(dir_ / (std::string("a") + ext)));
    EXPECT_EQ(slurp(dir_ / (std::string("a") + ext)), slurp(dir_ / (std::string("b") + ext))) << ext;
  }
  EXPECT_TRUE(fs::exists(dir_ / "a.egm"));
  EXPECT_NE(run("gravity synth-model --degree 3000 --out c").code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "c.gfc"));
}

TEST_F(GravityCli, PointsCsvStdinToStdoutAndAtomicFile) {
  ASSERT_EQ(run("gravity synth-model --degree 20 --seed 1 --out m").code, 0);
  const std::string csv = "lat,lon,h\n10,20,0\n-89.9,0,5000\n45 30 00,-120,100\n";
  const CmdResult r = run("gravity points --model m.egm", csv);
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(r.out);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "lat_deg,lon_deg,h_m,xi_arcsec,eta_arcsec,geoid_m");
  EXPECT_EQ(lines[3].rfind("45.5000000000,-120.0000000000,100.0000,", 0), 0u) << lines[3];
  // Same numbers as `gravity point`.
  const auto j = nlohmann::json::parse(run("gravity point --model m.egm 10 20 --json").out);
  double lat, lon, h, xi, eta, n;
  char c;
  std::istringstream(lines[1]) >> lat >> c >> lon >> c >> h >> c >> xi >> c >> eta >> c >> n;
  EXPECT_NEAR(xi, j["xi_arcsec"].get<double>(), 1e-8);
  EXPECT_NEAR(n, j["geoid_m"].get<double>(), 1e-8);
  std::ofstream(dir_ / "in.csv") << csv;
  ASSERT_EQ(run("gravity points --model m.egm --input in.csv --output out.csv").code, 0);
  EXPECT_EQ(slurp(dir_ / "out.csv"), r.out);
}

TEST_F(GravityCli, BadInputGivesExitCodeAndNamesTheLine) {
  ASSERT_EQ(run("gravity synth-model --degree 10 --out m").code, 0);
  std::ofstream(dir_ / "bad.csv") << "10,20\n95,0\n";
  CmdResult r = run("gravity points --model m.egm --input bad.csv --output out.csv");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.csv:2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.csv"));
  r = run("gravity point --model m.egm 0 0 50000000");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("height"), std::string::npos) << r.err;
  r = run("gravity point --model no_such_model_name 0 0");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("not found"), std::string::npos) << r.err;
  std::ofstream(dir_ / "broken.gfc") << "end_of_head\n";
  r = run("gravity point --model broken.gfc 0 0");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("broken.gfc"), std::string::npos) << r.err;
}

TEST_F(GravityCli, ModelFoundByNameThroughGeographicLibEnvironment) {
  ASSERT_EQ(run("gravity synth-model --degree 10 --out mymodel").code, 0);
  const CmdResult r = run("gravity point --model mymodel 1 2");  // not a file name: looked up
  EXPECT_EQ(r.code, 1);
  const CmdResult ok = shell("GEOGRAPHICLIB_GRAVITY_PATH=" + dir_.string() + " " + MERIDIAN_EXE + " gravity point --model mymodel 1 2");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("xi_arcsec"), std::string::npos);
}

}  // namespace

namespace {

TEST_F(GravityCli, TrackOptionInterpolatesWithinTolerance) {
  ASSERT_EQ(run("gravity synth-model --degree 90 --seed 2 --out m").code, 0);
  std::string csv;
  for (int i = 0; i < 400; ++i) csv += std::to_string(40 + i * 1e-4) + "," + std::to_string(10 + i * 1e-4) + ",0\n";
  const CmdResult exact = run("gravity points --model m.egm", csv);
  const CmdResult track = run("gravity points --model m.egm --track-tolerance-arcsec 0.0001", csv);
  ASSERT_EQ(track.code, 0) << track.err;
  std::istringstream a(exact.out), b(track.out);
  std::string la, lb;
  std::getline(a, la);
  std::getline(b, lb);
  double worst = 0;
  while (std::getline(a, la) && std::getline(b, lb)) {
    double x[6], y[6];
    char c;
    std::istringstream sa(la), sb(lb);
    for (int k = 0; k < 6; ++k) sa >> x[k] >> c, sb >> y[k] >> c;
    worst = std::max({worst, std::abs(x[3] - y[3]), std::abs(x[4] - y[4])});
  }
  EXPECT_LT(worst, 1.5e-4);
}

}  // namespace

namespace {

TEST_F(GravityCli, GeoidGridCommandLabelsTheFallbackDeflection) {
  // A 1° PGM with constant height 12.345 m (offset 0, scale 0.001).
  std::string s = "P5\n# Offset 0\n# Scale 0.001\n360 181\n65535\n";
  for (int i = 0; i < 360 * 181; ++i) s += std::string{static_cast<char>(12345 >> 8), static_cast<char>(12345 & 255)};
  std::ofstream(dir_ / "flat.pgm", std::ios::binary) << s;
  const CmdResult r = run("gravity geoid-grid --grid flat.pgm 12.5 -7.25 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["geoid_m"].get<double>(), 12.345, 1e-9);
  EXPECT_NEAR(j["fallback_xi_arcsec"].get<double>(), 0.0, 1e-9);
  EXPECT_NE(j["fallback_method"].get<std::string>().find("fallback"), std::string::npos);
  EXPECT_EQ(run("gravity geoid-grid --grid missing.gtx 0 0").code, 4);
}

}  // namespace

namespace {

// Files in the test directory whose name marks an unfinished atomic write.
int temporary_files(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) ++n;
  return n;
}

int occurrences(const std::string& s, const std::string& what) {
  int n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + what.size())) ++n;
  return n;
}

TEST_F(GravityCli, PointsReportIsWrittenAfterTheCsvAndHasTheMaps) {
  ASSERT_EQ(run("gravity synth-model --degree 30 --seed 4 --out m").code, 0);
  std::string csv = "lat [deg],lon [deg],h [m]\n";
  const int n = 300;
  for (int i = 0; i < n; ++i) csv += std::to_string(44 + i * 0.01) + "," + std::to_string(6 + i * 0.02) + ",100\n";
  write("pts.csv", csv);
  const CmdResult plain = run("gravity points --model m.gfc --input pts.csv -o plain.csv");
  ASSERT_EQ(plain.code, 0) << plain.err;
  const CmdResult r = run("gravity points --model m.gfc --input pts.csv -o out.csv --report r.html");
  if (r.code != 0 && r.err.find("without HTML reports") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  // The report does not change the CSV.
  EXPECT_EQ(slurp(dir_ / "out.csv"), slurp(dir_ / "plain.csv"));
  const std::string html = slurp(dir_ / "r.html");
  // One map per mapped quantity (xi, eta, N), each drawing every point of
  // this short run.
  const std::vector<std::string> mapped = {"xi (arcsec)", "eta (arcsec)", "N (m)"};
  EXPECT_EQ(occurrences(html, "data-vega-spec="), static_cast<int>(mapped.size()));
  for (const auto& m : mapped) EXPECT_NE(html.find(m), std::string::npos) << m;
  EXPECT_EQ(occurrences(html, "All " + std::to_string(n) + " points are drawn."), static_cast<int>(mapped.size()));
  for (const char* id : {"summary", "maps", "definitions"})
    EXPECT_NE(html.find(std::string("<section id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_NE(html.find("astronomic minus geodetic"), std::string::npos);
  EXPECT_EQ(temporary_files(dir_), 0);
  // From stdin to stdout, the same rows.
  const CmdResult piped = run("gravity points --model m.gfc --report piped.html", csv);
  ASSERT_EQ(piped.code, 0) << piped.err;
  EXPECT_EQ(piped.out, slurp(dir_ / "plain.csv"));
  EXPECT_NE(slurp(dir_ / "piped.html").find("&lt;stdin&gt;"), std::string::npos);
}

TEST_F(GravityCli, BadCsvLeavesNoReport) {
  ASSERT_EQ(run("gravity synth-model --degree 10 --seed 2 --out m").code, 0);
  write("bad.csv", "lat,lon\n10,20\n11,x\n");
  CmdResult r = run("gravity points --model m.egm --input bad.csv -o out.csv --report r.html");
  if (r.code != 0 && r.err.find("without HTML reports") != std::string::npos) GTEST_SKIP() << r.err;
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.csv:3: longitude"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
  EXPECT_FALSE(fs::exists(dir_ / "out.csv"));
  // A report from an earlier run is left as it was.
  write("r.html", "earlier report");
  r = run("gravity points --model m.egm --report r.html", "10,20\n95,0\n");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("<stdin>:2: latitude"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "r.html"), "earlier report");
  EXPECT_EQ(temporary_files(dir_), 0);
}

}  // namespace

namespace {

// Model metadata as the file states it (issue 16): the synthetic model's
// .gfc states its tide system and normalisation, its .egm (GeographicLib's
// format has no key for it) does not, and then a warning says so.
TEST_F(GravityCli, ModelMetadataAsStatedByTheFileAndAWarningWhenItIsNot) {
  ASSERT_EQ(run("gravity synth-model --degree 8 --seed 3 --out m").code, 0);
  const CmdResult g = run("gravity point --model m.gfc 60 25 --json");
  ASSERT_EQ(g.code, 0) << g.err;
  const auto j = nlohmann::json::parse(g.out);
  EXPECT_EQ(j["model"], "synth8s3");
  EXPECT_EQ(j["max_degree"], 8);
  EXPECT_EQ(j["file_max_degree"], 8);
  EXPECT_EQ(j["gm_m3_s2"].get<double>(), 3.986004415e14);  // the .gfc's earth_gravity_constant line
  EXPECT_NEAR(j["reference_radius_m"].get<double>(), 6378136.3, 1e-6);
  EXPECT_EQ(j["tide_system"], "tide_free");
  EXPECT_EQ(j["normalization"], "fully_normalized");
  EXPECT_TRUE(j["warnings"].empty());
  const CmdResult e = run("gravity point --model m.egm 60 25 --json --max-degree 5");
  ASSERT_EQ(e.code, 0) << e.err;
  const auto k = nlohmann::json::parse(e.out);
  EXPECT_EQ(k["max_degree"], 5);
  EXPECT_EQ(k["file_max_degree"], 8);
  EXPECT_TRUE(k["tide_system"].is_null());
  EXPECT_TRUE(k["normalization"].is_null());
  ASSERT_EQ(k["warnings"].size(), 1u);
  EXPECT_NE(k["warnings"][0].get<std::string>().find("does not state its tide system"), std::string::npos);
  const CmdResult t = run("gravity point --model m.gfc 60 25");
  EXPECT_NE(t.out.find("\nmodel GM 398600441500000 m^3/s^2, reference radius 6378136.3 m, tide system tide_free, "
                       "normalisation fully_normalized\n"),
            std::string::npos)
      << t.out;
  // Nothing above degree 0 kept: zeros, printed without a minus sign (trial finding).
  const CmdResult z = run("gravity point --model m.egm 60 25 --max-degree 0");
  ASSERT_EQ(z.code, 0) << z.err;
  EXPECT_NE(z.out.find("\nxi_arcsec  0.000000000\neta_arcsec 0.000000000\ngeoid_m    0.000000000\n"), std::string::npos)
      << z.out;
  const CmdResult te = run("gravity point --model m.egm 60 25");
  EXPECT_NE(te.out.find("tide system not stated, normalisation fully normalised (not stated; the format's default)\n"),
            std::string::npos)
      << te.out;
  EXPECT_NE(te.out.find("\nwarning: the model file does not state its tide system"), std::string::npos) << te.out;
  // gravity points: the CSV is unchanged, the model goes to stderr (warnings even with --quiet).
  const CmdResult p = run("gravity points --model m.egm -q", "60,25\n");
  ASSERT_EQ(p.code, 0) << p.err;
  EXPECT_EQ(p.out.rfind("lat_deg,lon_deg,h_m,xi_arcsec,eta_arcsec,geoid_m\n60.0000000000,25.0000000000,", 0), 0u);
  EXPECT_EQ(p.err.rfind("warning: the model file does not state its tide system", 0), 0u) << p.err;
  const CmdResult pg = run("gravity points --model m.gfc", "60,25\n");
  EXPECT_EQ(pg.err.rfind("model synth8s3 (degree 8, m.gfc)\nmodel GM", 0), 0u) << pg.err;
}

// The geoid-grid cases, run as a user would on the files of
// ../shared/cases/geoid-grids (skipped when absent; the unit tests build the
// same grids from their formulas).
class GeoidGridCasesCli : public GravityCli {
 protected:
  void SetUp() override {
    GravityCli::SetUp();
    cases_ = fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "cases" / "geoid-grids";
    if (!fs::exists(cases_ / "tile.gtx") || !fs::exists(cases_ / "west-180.gtx"))
      GTEST_SKIP() << cases_ << " not present";
  }
  CmdResult grid(const std::string& file, const std::string& args) {
    return run("gravity geoid-grid --grid " + (cases_ / file).string() + " " + args);
  }
  fs::path cases_;
};

TEST_F(GeoidGridCasesCli, GlobalGridFromMinus180WithoutRepeatedColumn) {
  // GeographicLib's GeoidEval -l on the same grid as .pgm: -15.715771 m.
  for (const char* lon : {"175.3", "-184.7", "535.3"}) {
    const CmdResult r = grid("west-180.gtx", std::string("--interpolation bilinear 9.9959 ") + lon);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("\ngeoid_m    -15.715771\n"), std::string::npos) << r.out;
  }
}

TEST_F(GeoidGridCasesCli, TileWithNoDataNodesGivesNOrNamesTheNode) {
  // 56.30 21.20 (bicubic asked; edge cell, bilinear used): N = 20.12 m on the
  // tile's plane, the deflection unavailable (its southern neighbour is outside).
  CmdResult r = grid("tile.gtx", "56.30 21.20 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["geoid_m"].get<double>(), 20 + 0.8 * 0.30 - 0.6 * 0.20, 1e-5);
  EXPECT_EQ(j["interpolation_used"], "bilinear");
  EXPECT_FALSE(j["fallback_available"].get<bool>());
  EXPECT_TRUE(j["fallback_xi_arcsec"].is_null());
  r = grid("tile.gtx", "56.30 21.20");
  EXPECT_NE(r.out.find("\ngeoid_m    20.120000\nxi_arcsec  unavailable"), std::string::npos) << r.out;
  // 56.70 21.90 bilinear: 20.02 m.
  r = grid("tile.gtx", "--interpolation bilinear 56.70 21.90 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["geoid_m"].get<double>(), 20 + 0.8 * 0.70 - 0.6 * 0.90, 1e-5);
  EXPECT_TRUE(j["fallback_available"].get<bool>());
  // 56.20 23.30: a corner holds 9999 (bilinear through it would be 3611.76 m): an input error naming the node.
  for (const char* interp : {"bilinear", "bicubic"}) {
    r = grid("tile.gtx", std::string("--interpolation ") + interp + " 56.20 23.30");
    EXPECT_EQ(r.code, 1) << interp;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find("node(0,5)"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("lat 56.000000 deg, lon 23.500000 deg, which holds 9999"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("3611"), std::string::npos) << r.err;
  }
  // A longitude outside the tile is named as the longitude.
  r = grid("tile.gtx", "56.5 30");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find(": lon: longitude 30.000000 deg is outside"), std::string::npos) << r.err;
}

}  // namespace
