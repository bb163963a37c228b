// Runs the meridian binary as a user would: outputs, the --json contract,
// exit codes and messages for bad input, atomic output, determinism.

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace fs = std::filesystem;

namespace {

using meridian_test::CmdResult;
class Cli : public meridian_test::CliTest {};

// Spec §8 scenario 2 (times to the printed ms) with every method.
const char* kScenario = R"(instrument:
  scale_value_arcsec: 600
  torsion_ratio: 0.30
station:
  latitude_deg: 34.2
determinations:
  - mode: non-tracking
    method: all
    clamp_reading: "0 00 00"
    period_s: 440.0
    crossings:
      - {level_div: -2, times_s: [35.263, 284.737, 475.263], first_direction: east}
      - {level_div: 0, times_s: [50.934, 269.066, 490.934], first_direction: east}
      - {level_div: 2, times_s: [66.652, 253.348, 506.652], first_direction: east}
    reversals_div: [8.88, -9.12]
  - mode: non-tracking
    method: direct
    clamp_reading: "0 00 00"
    period_s: 440.0
    crossings:
      - {level_div: -2, times_s: [35.263, 284.737, 475.263], first_direction: east}
      - {level_div: 2, times_s: [66.652, 253.348, 506.652], first_direction: east}
  - mode: tracking
    method: all
    reversals: ["359 41 12", "0 44 50", "359 42 04", "0 43 58"]
)";

}  // namespace

TEST_F(Cli, ReduceJsonContract) {
  const auto f = write("obs.yaml", kScenario);
  const CmdResult r = run("gyro reduce " + f.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& d = j.at("determinations");
  ASSERT_EQ(d.size(), 3u);
  for (const auto& e : d) {
    for (const char* k : {"mode", "method", "north_reading_deg", "sigma_arcsec"}) EXPECT_TRUE(e.contains(k)) << k;
  }
  EXPECT_EQ(d[0].at("mode"), "non-tracking");
  EXPECT_EQ(d[0].at("method"), "all");
  EXPECT_TRUE(d[0].contains("beta_div"));
  EXPECT_TRUE(d[0].contains("delta_n_arcsec"));
  const auto& results = d[0].at("results");
  ASSERT_GE(results.size(), 6u);
  // Times rounded to 1 ms move ΔN by up to ~0.03": the spec's values to 0.05".
  for (const auto& m : results) {
    const double dn = m.at("delta_n_arcsec");
    const std::string name = m.at("method");
    const double expect = name == "time-difference" ? -95.193 : name == "transit" ? -93.603 : -93.600;
    EXPECT_NEAR(dn, expect, 0.05) << name;
    EXPECT_TRUE(m.at("sigma_arcsec").is_number()) << name;
    const double n = m.at("north_reading_deg");
    EXPECT_NEAR(n, 360.0 + dn / 3600.0, 1e-9) << name;  // N_G = N' + ΔN, normalised
  }
  EXPECT_EQ(d[1].at("method"), "direct");
  EXPECT_FALSE(d[1].contains("results"));
  EXPECT_EQ(d[2].at("mode"), "tracking");
  EXPECT_FALSE(d[2].contains("beta_div"));
  EXPECT_TRUE(d[2].at("sigma_arcsec").is_number());  // n = 4 gives redundancy
}

TEST_F(Cli, ReduceAcceptsJsonInputAsIs) {
  const auto f = write("obs.json",
                       R"({"instrument": {"scale_value_arcsec": 600, "torsion_ratio": 0.3},
                           "station": {"latitude_deg": 34.2},
                           "determinations": [{"mode": "tracking", "method": "two-point",
                                               "reversals": ["359 41 12", "0 44 50"]}]})");
  const CmdResult r = run("gyro reduce " + f.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double expect = ((-(18 * 60 + 48)) + (44 * 60 + 50)) / 2.0 / 3600.0;
  EXPECT_NEAR(j["determinations"][0]["north_reading_deg"].get<double>(), expect, 1e-9);
  EXPECT_TRUE(j["determinations"][0]["sigma_arcsec"].is_null());  // no redundancy, no a-priori σ
}

TEST_F(Cli, BadInputExitCodeMessageAndNoPartialOutput) {
  std::string bad = kScenario;
  const std::string good_readings = "[\"359 41 12\", \"0 44 50\", \"359 42 04\", \"0 43 58\"]";
  bad.replace(bad.find(good_readings), good_readings.size(), "[\"359 41 12\", \"0 44 50\", \"0 45 04\", \"0 43 58\"]");
  const auto f = write("bad.yaml", bad);
  const auto out = dir_ / "result.json";
  const CmdResult r = run("gyro reduce " + f.string() + " --json -o " + out.string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.yaml:25: determinations[2].reversals"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reading 3"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(r.out.empty());
  for (const auto& e : fs::directory_iterator(dir_))  // no temporary left behind either
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos);

  // A level the light mark never reaches (beyond the reversal readings).
  std::string unreachable = kScenario;
  unreachable.replace(unreachable.find("{level_div: 2,"), 14, "{level_div: 10,");
  const CmdResult u = run("gyro reduce " + write("far.yaml", unreachable).string());
  EXPECT_EQ(u.code, 1);
  EXPECT_NE(u.err.find("far.yaml:14: determinations[0].crossings[2].level_div"), std::string::npos) << u.err;
  EXPECT_NE(u.err.find("never reaches"), std::string::npos) << u.err;

  const CmdResult missing = run("gyro reduce " + (dir_ / "nope.yaml").string());
  EXPECT_EQ(missing.code, 4);
  EXPECT_NE(missing.err.find("nope.yaml"), std::string::npos);
  EXPECT_EQ(run("gyro reduce").code, 2);
  EXPECT_EQ(run("gyro frobnicate x").code, 2);
}

TEST_F(Cli, OutputFileWrittenAtomically) {
  const auto f = write("obs.yaml", kScenario);
  const auto out = dir_ / "result.json";
  const CmdResult r = run("gyro reduce " + f.string() + " --json -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto parsed = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(parsed["determinations"].size(), 3u);
}

TEST_F(Cli, SimulateIsDeterministicAndReducible) {
  const CmdResult a = run("gyro simulate --mode non-tracking --seed 42");
  const CmdResult b = run("gyro simulate --mode non-tracking --seed 42");
  const CmdResult c = run("gyro simulate --mode non-tracking --seed 43");
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_NE(a.out, c.out);
  const auto f = write("sim.yaml", a.out);
  const CmdResult r = run("gyro reduce " + f.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // Truth: ΔN = −93.6"; with 0.1 s / 0.05 div noise the LS result is within a few σ.
  const double dn = j["determinations"][0]["delta_n_arcsec"];
  const double sigma = j["determinations"][0]["sigma_arcsec"];
  EXPECT_LT(std::fabs(dn + 93.6), 4 * sigma);
  const CmdResult t = run("gyro simulate --mode tracking --seed 1 --sigma-tracking-arcsec 0");
  ASSERT_EQ(t.code, 0) << t.err;
  const CmdResult tr = run("gyro reduce " + write("t.yaml", t.out).string() + " --json");
  ASSERT_EQ(tr.code, 0) << tr.err;
  const double m = nlohmann::json::parse(tr.out)["determinations"][0]["north_reading_deg"];
  EXPECT_NEAR(m * 3600.0, 12 * 60 + 34, 0.01);  // spec §8.4: M = 0°12'34"
}

TEST_F(Cli, CampaignAndDemo) {
  const CmdResult s = run("gyro simulate --mode campaign --seed 9 -o " + (dir_ / "c.yaml").string());
  ASSERT_EQ(s.code, 0) << s.err;
  const CmdResult c = run("gyro campaign " + (dir_ / "c.yaml").string() + " --json");
  ASSERT_EQ(c.code, 0) << c.err;
  const auto j = nlohmann::json::parse(c.out);
  for (const char* k : {"grid_azimuth", "geodetic_azimuth", "astronomic_azimuth", "instrument_constant_arcsec",
                        "checks", "station"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_TRUE(j["grid_azimuth"]["sigma_arcsec"].is_number());
  const CmdResult d = run("demo --output-dir " + (dir_ / "demo").string());
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_NE(d.out.find("GRID AZIMUTH"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "demo" / "campaign.json"));
  EXPECT_TRUE(fs::exists(dir_ / "demo" / "campaign.txt"));
}

TEST_F(Cli, TransitFactorCalibration) {
  // Two clamps 12' east and west of a north at 0°00'00": simulate both, then calibrate.
  const CmdResult e = run("gyro simulate --mode non-tracking --levels 0 --clamp \"-0 12 00\" --beta-div 0.923077 --sigma-time-s 0 --sigma-reading-div 0");
  const CmdResult w = run("gyro simulate --mode non-tracking --levels 0 --clamp \"0 12 00\" --beta-div -0.923077 --sigma-time-s 0 --sigma-reading-div 0");
  ASSERT_EQ(e.code, 0) << e.err;
  ASSERT_EQ(w.code, 0) << w.err;
  // Join the two files' determinations.
  std::string both = e.out + w.out.substr(w.out.find("determinations:\n") + 16);
  const CmdResult r = run("gyro transit-factor " + write("tf.yaml", both).string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // c = (1+λ)τπ/(2T_B) to within the small-angle error (|β|/B ≈ 0.1: ~0.2 %).
  const double computed = 1.3 * 600 * M_PI / 880;
  EXPECT_NEAR(j["transit_factor_arcsec_per_div_s"].get<double>() / computed, 1.0, 0.005);
}

TEST_F(Cli, HtmlReportWrittenOnlyOnSuccess) {
  const CmdResult s = run("gyro simulate --mode campaign --seed 5 -o " + (dir_ / "c.yaml").string());
  ASSERT_EQ(s.code, 0) << s.err;
  const auto html = dir_ / "c.html";
  const CmdResult c = run("gyro campaign " + (dir_ / "c.yaml").string() + " --report " + html.string());
  ASSERT_EQ(c.code, 0) << c.err;
  const std::string page = slurp(html);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("data-vega-spec"), std::string::npos);
  EXPECT_NE(page.find("<section id=\"result\">"), std::string::npos);
  const auto f = write("obs.yaml", kScenario);
  const CmdResult r = run("gyro reduce " + f.string() + " --report " + (dir_ / "r.html").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(dir_ / "r.html").find("<section id=\"determination-3\">"), std::string::npos);
  // Bad input: no report file.
  std::string bad = kScenario;
  bad.replace(bad.find("period_s: 440.0"), 15, "period_s: -440");
  const CmdResult b = run("gyro reduce " + write("bad.yaml", bad).string() + " --report " + (dir_ / "b.html").string());
  EXPECT_EQ(b.code, 1);
  EXPECT_FALSE(fs::exists(dir_ / "b.html"));
}

TEST_F(Cli, ProgressBarOnlyOnATerminalAndNotWhenQuiet) {
  const std::string cmd = std::string("MERIDIAN_PROGRESS_DELAY_S=0 ") + MERIDIAN_EXE +
                          " gyro simulate --determinations 40 -o " + (dir_ / "s.yaml").string();
  // Not a terminal: nothing on stderr.
  const CmdResult plain = run("gyro simulate --determinations 40 -o " + (dir_ / "p.yaml").string());
  EXPECT_EQ(plain.err, "");
  // A pseudo-terminal (util-linux `script`): the bar is drawn and cleared.
  const auto log = dir_ / "tty.log";
  ASSERT_EQ(std::system(("script -qec '" + cmd + "' " + log.string() + " > /dev/null").c_str()), 0);
  const std::string tty = slurp(log);
  EXPECT_NE(tty.find("simulating ["), std::string::npos) << tty;
  EXPECT_NE(tty.find("\033[K"), std::string::npos);
  ASSERT_EQ(std::system(("script -qec '" + cmd + " --quiet' " + log.string() + " > /dev/null").c_str()), 0);
  EXPECT_EQ(slurp(log).find("simulating ["), std::string::npos);
}
