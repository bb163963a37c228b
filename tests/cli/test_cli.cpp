// Runs the meridian binary as a user would: outputs, the --json contract,
// exit codes and messages for bad input, atomic output, determinism.

#include <sys/wait.h>

#include <algorithm>
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

TEST_F(Cli, SimulateRefusesOptionsItsModeDoesNotUse) {
  // A trial found --tracking-reversals 20 ignored by --mode campaign, yet in the header.
  for (const auto& [cmd, option] :
       {std::pair{"gyro simulate --mode campaign --tracking-reversals 20", "--tracking-reversals"},
        std::pair{"gyro simulate --mode campaign --rho1 0.9", "--rho1"},
        std::pair{"gyro simulate --mode tracking --reversals 9", "--reversals"},
        std::pair{"gyro simulate --mode non-tracking --kappa 0.1", "--kappa"}}) {
    const CmdResult r = run(cmd);
    EXPECT_EQ(r.code, 1) << cmd;
    EXPECT_NE(r.err.find(std::string(option) + ": not used by --mode"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << cmd;
  }
  EXPECT_EQ(run("gyro simulate --mode campaign --seed 3 --sigma-time-s 0.2").code, 0);
  EXPECT_EQ(run("gyro simulate --mode tracking --tracking-reversals 9 --kappa 0.1").code, 0);
}

TEST_F(Cli, AReportThatCannotBeWrittenLeavesNoOutput) {
  // All outputs or none: a report in a missing directory used to leave -o written (trial).
  const auto f = write("obs.yaml", kScenario);
  const auto out = dir_ / "result.json";
  const CmdResult r = run("gyro reduce " + f.string() + " --json -o " + out.string() +
                          " --report " + (dir_ / "no" / "such" / "r.html").string());
  EXPECT_NE(r.code, 0) << r.err;  // 4 (I/O); without HTML reports the --report refusal
  EXPECT_FALSE(std::filesystem::exists(out));
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
  // the deflection-of-the-vertical part: a simulated line, its summary with truth
  EXPECT_NE(d.out.find("dynamic deflection of the vertical"), std::string::npos) << d.out;
  const auto dov = nlohmann::json::parse(slurp(dir_ / "demo" / "dov-demo.json"));
  EXPECT_EQ(dov["epochs"], 1801);
  EXPECT_LT(dov["rms_arcsec"]["smoothed"]["xi"].get<double>(),
            dov["rms_arcsec"]["model"]["xi"].get<double>());
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
  if (c.code != 0 && c.err.find("without HTML reports") != std::string::npos) GTEST_SKIP() << c.err;
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

// --- Field-crew habits and messages (issue 15, items 7 and 8).

TEST_F(Cli, StopwatchTimesAndAngleUnitsGiveTheSameResult) {
  // The scenario booked with m:ss.s times, and its tracking run in gon and in ddd.mmss.
  std::string mss = kScenario;
  auto replace = [](std::string& s, const std::string& from, const std::string& to) {
    ASSERT_NE(s.find(from), std::string::npos) << from;
    s.replace(s.find(from), from.size(), to);
  };
  // 269.066 s = 4:29.066, 490.934 s = 8:10.934, 440 s = 7:20.
  replace(mss, "[50.934, 269.066, 490.934]", "[\"0:50.934\", \"4:29.066\", \"8:10.934\"]");
  replace(mss, "period_s: 440.0", "period_s: \"7:20.0\"");
  const CmdResult a = run("gyro reduce " + write("s.yaml", kScenario).string() + " --json");
  const CmdResult b = run("gyro reduce " + write("mss.yaml", mss).string() + " --json");
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  for (int i = 0; i < 3; ++i)
    EXPECT_EQ(ja["determinations"][i]["north_reading_deg"], jb["determinations"][i]["north_reading_deg"]);
  // 359°41'12" = 399.651851852 gon: 0.9 * 399.651851852 = 359.686666667°. 0°44'50" = 0.830246914 gon, …
  std::string gon = "angle_unit: gon\n" + std::string(kScenario);
  replace(gon, "clamp_reading: \"0 00 00\"", "clamp_reading: 0");
  replace(gon, "clamp_reading: \"0 00 00\"", "clamp_reading: 0");
  replace(gon, "[\"359 41 12\", \"0 44 50\", \"359 42 04\", \"0 43 58\"]",
          "[399.6518518519, 0.8302469136, 399.6679012346, 0.8141975309]");
  std::string ddd = "angle_unit: ddd.mmss\n" + std::string(kScenario);
  replace(ddd, "clamp_reading: \"0 00 00\"", "clamp_reading: 0.0000");
  replace(ddd, "clamp_reading: \"0 00 00\"", "clamp_reading: 0.0000");
  replace(ddd, "[\"359 41 12\", \"0 44 50\", \"359 42 04\", \"0 43 58\"]",
          "[359.4112, 0.4450, 359.4204, 0.4358]");
  for (const auto& [name, text] : {std::pair{"gon.yaml", gon}, std::pair{"ddd.yaml", ddd}}) {
    const CmdResult c = run("gyro reduce " + write(name, text).string() + " --json");
    ASSERT_EQ(c.code, 0) << c.err;
    const auto jc = nlohmann::json::parse(c.out);
    EXPECT_NEAR(jc["determinations"][2]["north_reading_deg"].get<double>(),
                ja["determinations"][2]["north_reading_deg"].get<double>(), 1e-9) << name;
  }
  // A DDD.MMSS value with 99 seconds is refused at its line.
  replace(ddd, "359.4204", "359.4299");
  const CmdResult bad = run("gyro reduce " + write("bad.yaml", ddd).string());
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("bad.yaml:26: determinations[2].reversals[2]: cannot read angle \"359.4299\" as "
                         "ddd.mmss"), std::string::npos) << bad.err;
  // Seconds of a stopwatch time above 59: at the line, naming the element.
  replace(mss, "\"4:29.066\"", "\"4:69.066\"");
  const CmdResult t = run("gyro reduce " + write("t.yaml", mss).string());
  EXPECT_EQ(t.code, 1);
  EXPECT_NE(t.err.find("t.yaml:13: determinations[0].crossings[1].times_s[1]: cannot read time \"4:69.066\": "
                       "seconds must be below 60"), std::string::npos) << t.err;
}

TEST_F(Cli, TabIndentationIsNamed) {
  std::string tabbed = kScenario;
  tabbed.replace(tabbed.find("  torsion_ratio"), 2, "\t");
  const CmdResult r = run("gyro reduce " + write("tab.yaml", tabbed).string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("tab.yaml:3: tabs are not allowed for indentation (line 3)"), std::string::npos) << r.err;
}

TEST_F(Cli, ErrorAtTheLineOfTheWrongValue) {
  // The 4th reversal reading of a block list, bad as text and as a reversal sequence.
  std::string block = kScenario;
  const std::string flow = "[\"359 41 12\", \"0 44 50\", \"359 42 04\", \"0 43 58\"]";
  block.replace(block.find(flow), flow.size(),
                "\n      - \"359 41 12\"\n      - \"0 44 50\"\n      - \"359 42 04\"\n      - \"0 73 58\"");
  const CmdResult r = run("gyro reduce " + write("b.yaml", block).string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("b.yaml:29: determinations[2].reversals[3]: cannot read angle \"0 73 58\""),
            std::string::npos) << r.err;
  // A non-tracking reversal reading that does not alternate, 4th of a flow list over two lines:
  // found while processing, located at its element's line.
  std::string nt = kScenario;
  nt.replace(nt.find("reversals_div: [8.88, -9.12]"), 28, "reversals_div: [8.88, -9.12,\n                    8.7,\n                    8.9]");
  const CmdResult p = run("gyro reduce " + write("nt.yaml", nt).string());
  EXPECT_EQ(p.code, 1);
  EXPECT_NE(p.err.find("nt.yaml:17: determinations[0].reversals_div[3]: reversal readings must alternate"),
            std::string::npos) << p.err;
}

TEST_F(Cli, UnknownCommandOrOptionSuggestsTheNearest) {
  // `meridian ARGS` is a usage error (exit 2) whose message contains `expect`.
  auto usage_error = [&](const std::string& args, const std::string& expect) {
    const CmdResult r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(expect), std::string::npos) << args << "\n" << r.err;
  };
  usage_error("gyro campain x.yaml", "meridian gyro: unknown command \"campain\"; did you mean `campaign`?");
  usage_error("gyr reduce x.yaml", "did you mean `gyro`?");
  usage_error("gyro campaign --strcit x.yaml",
              "meridian gyro campaign: unknown option \"--strcit\"; did you mean `--strict`?");
  // An option's value is not mistaken for a word: --clamp takes "-0 12 00".
  usage_error("gyro simulate --clamp \"-0 12 00\" --seeed 3", "unknown option \"--seeed\"; did you mean `--seed`?");
  // Nothing near: the commands are listed.
  usage_error("gyro frobnicate x", "unknown command \"frobnicate\" (commands: reduce, campaign, template");
  // Other command-line errors keep CLI11's message.
  usage_error("gyro reduce", "FILE is required");
}

TEST_F(Cli, StrictListsTheFailedChecksAndWritesNoFile) {
  const CmdResult s = run("gyro template -o " + (dir_ / "t.yaml").string());
  ASSERT_EQ(s.code, 0) << s.err;
  std::string job = slurp(dir_ / "t.yaml");
  // Limits the job cannot meet: 1" between the two line runs, 0.05 div of zero-position drift.
  // (the template's tolerances block is commented out: its limits are the class's)
  const auto set = [&](const std::string& from, const std::string& to) {
    const auto at = job.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    job.replace(at, from.size(), to);
  };
  set("# tolerances:", "tolerances:");
  set("# determination_difference_arcsec: 40", "determination_difference_arcsec: 1");
  set("# zero_position_div: 0.5", "zero_position_div: 0.05");
  const auto f = write("strict.yaml", job);
  const auto out = dir_ / "out.txt", html = dir_ / "out.html";
  const CmdResult r = run("gyro campaign " + f.string() + " --strict -o " + out.string() + " --report " + html.string());
  if (r.err.find("without HTML reports") != std::string::npos) GTEST_SKIP() << r.err;
  EXPECT_EQ(r.code, 1);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(html));
  EXPECT_TRUE(r.out.empty());
  // One line per failed check (as many as the text report marks FAIL), then the summary.
  const CmdResult text = run("gyro campaign " + f.string());
  ASSERT_EQ(text.code, 0);
  auto count = [](const std::string& hay, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = hay.find(what); p != std::string::npos; p = hay.find(what, p + 1)) ++n;
    return n;
  };
  const std::size_t fails = count(text.out, "[FAIL]");
  ASSERT_GE(fails, 2u);
  EXPECT_EQ(count(r.err, "check failed: "), fails) << r.err;
  EXPECT_NE(r.err.find("check failed: any two runs on the line, gyro azimuths:"), std::string::npos) << r.err;
  // Each names where it was booked: the file, the line of the key and the field.
  const std::size_t determinations_line = static_cast<std::size_t>(
      std::count(job.begin(), job.begin() + static_cast<std::ptrdiff_t>(job.find("  determinations:")), '\n') + 1);
  // (the key's line, or the line its list starts on)
  const auto at = [&](std::size_t line) {
    return r.err.find("strict.yaml:" + std::to_string(line) +
                      ": line.determinations: check failed: any two runs on the line") != std::string::npos;
  };
  EXPECT_TRUE(at(determinations_line) || at(determinations_line + 1)) << r.err;
  EXPECT_NE(r.err.find("(limit 1.0 arcsec)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("checks failed; no output file written"), std::string::npos) << r.err;
  // Without -o the result still goes to stdout, for the crew to see.
  const CmdResult shown = run("gyro campaign " + f.string() + " --strict");
  EXPECT_EQ(shown.code, 1);
  EXPECT_EQ(shown.out, text.out);
}

TEST_F(Cli, TemplateIsAFieldBookThatRuns) {
  const CmdResult c = run("gyro template");
  ASSERT_EQ(c.code, 0) << c.err;
  const auto f = write("job.yaml", c.out);
  const auto out = dir_ / "job.txt";
  const CmdResult r = run("gyro campaign " + f.string() + " --strict -o " + out.string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(slurp(out).find("GRID AZIMUTH"), std::string::npos);
  // Gyro minus traverse: T against atan2(dy, dx) of the template's P1 and P2, recomputed here.
  const auto j = nlohmann::json::parse(run("gyro campaign " + f.string() + " --json").out);
  const double coord_deg = std::atan2(428000.330 - 428105.330, 3963200.752 - 3963321.552) * 180.0 / M_PI + 360.0;
  EXPECT_NEAR(j["grid_azimuth_from_coordinates_deg"].get<double>(), coord_deg, 1e-9);
  const double d = (j["grid_azimuth"]["deg"].get<double>() - coord_deg) * 3600.0;
  EXPECT_NEAR(j["gyro_minus_traverse_arcsec"].get<double>(), d, 1e-6);
  EXPECT_TRUE(j["accuracy_class_booked"].get<bool>());
  // Not a copy of an example: no example file is the template.
  for (const auto& e : fs::directory_iterator(MERIDIAN_EXAMPLES_DIR))
    EXPECT_NE(slurp(e.path()), c.out) << e.path();
  const CmdResult k = run("gyro template --kind reduce -o " + (dir_ / "r.yaml").string());
  ASSERT_EQ(k.code, 0) << k.err;
  const CmdResult rr = run("gyro reduce " + (dir_ / "r.yaml").string() + " --json");
  ASSERT_EQ(rr.code, 0) << rr.err;
  EXPECT_EQ(nlohmann::json::parse(rr.out)["determinations"].size(), 2u);
  const CmdResult bad = run("gyro template --kind campain");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("--kind: unknown kind \"campain\""), std::string::npos) << bad.err;
}

// The real job and its field mistakes (../shared/cases/gyro-field, optional
// data beside the repository): the clean book passes --strict, each mistake
// fails it or is an error naming the run.
TEST_F(Cli, FieldBookCasesPassOrFailTheRegulations) {
  const fs::path dir = fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "cases" / "gyro-field";
  if (!fs::exists(dir / "fieldbook.yaml")) GTEST_SKIP() << dir << " not present (optional data)";
  for (const char* good : {"fieldbook.yaml", "crew-mistakes-2/job.yaml"}) {
    const CmdResult clean = run("gyro campaign --strict " + (dir / good).string());
    EXPECT_EQ(clean.code, 0) << good << "\n" << clean.err << clean.out;
    EXPECT_EQ(clean.out.find("[FAIL]"), std::string::npos) << good;
  }
  struct Case {
    const char* file;
    int code;
    const char* says;
  } cases[] = {
      {"fb_Espread.yaml", 1, "check failed: any two runs on the known line, instrument constants (largest: "},
      {"fb_badrev_sig.yaml", 1, "check failed: tracking readings scatter as stated, line.determinations[0]"},
      {"03b_no_zero_at_all.yaml", 1, "check failed: zero position observed, line.determinations[0]"},
      {"04b_mdotss_numbers.yaml", 1, "line.determinations[1].crossings[0].times_s: the passages imply a period"},
      {"crew-mistakes-2/m4a.yaml", 1, "check failed: zero position observed before and after, line.determinations[1]"},
      {"crew-mistakes-2/m2a.yaml", 1,
       "known_line.before[0].target_rounds[0]: check failed: target rounds agree, known_line.before[0] (J3-GPS07 "
       "测前1 (逆转点法) 08:10): target_rounds[0] is 180 deg from the others, face left and face right swapped?"},
      {"crew-mistakes-2/m2c.yaml", 1,
       "line.determinations[1].target_rounds[0]: check failed: target rounds agree, line.determinations[1]"},
      {"crew-mistakes-2/m7e.yaml", 1,
       "m7e.yaml:66: instrument.accuracy_class_arcsec: check failed: accuracy class booked against the instrument's "
       "name (JT15 陀螺经纬仪 is a 15\" instrument): 25.0 arcsec"},
      {"crew-mistakes-2/m7f.yaml", 1,
       "instrument: check failed: accuracy class booked (not booked: the 15\" limits of the class of its name"},
      {"crew-mistakes-2/m9a.yaml", 1,
       "m9a.yaml:93: known_line.before[0].reversals: check failed: tracking readings scatter as stated, "
       "known_line.before[0]"},
      {"crew-mistakes-2/m5a.yaml", 1,
       "m5a.yaml:87: known_line.azimuth.value: check failed: known line: the given grid azimuth against its "
       "coordinates, to their rounding: 10.0 arcsec"},
      {"crew-mistakes-2/m6c.yaml", 1, "line.to: check failed: the line Ⅱ4->Ⅱ3: gyro grid azimuth against the azimuth "
                                      "of its coordinates (180 deg apart: from and to swapped?"},
  };
  for (const Case& c : cases) {
    const CmdResult r = run("gyro campaign --strict -o out.txt " + (dir / c.file).string());
    EXPECT_EQ(r.code, c.code) << c.file << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.file << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.txt")) << c.file;
  }
}

// A face reading booked 1' wrong the same way in both rounds of a run (helper trial, issue 36):
// the rounds agree with each other, but their 2C is 60" from the instrument's; and a wrong period_s.
TEST_F(Cli, TheSameFaceSlipInEveryRoundAndAWrongPeriodFail) {
  const fs::path job = fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "cases" / "gyro-field" / "crew-mistakes-2" / "job.yaml";
  if (!fs::exists(job)) GTEST_SKIP() << job << " not present (optional data)";
  std::ifstream in(job);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* r : {"right: \"346 07 33\"}", "right: \"346 07 30\"}"}) {
    const auto at = text.find(r);
    ASSERT_NE(at, std::string::npos) << r;
    text.replace(at + 12, 2, "08");  // 346 07 → 346 08
  }
  std::ofstream(dir_ / "slip.yaml") << text;
  const CmdResult r = run("gyro campaign --strict -o out.txt slip.yaml");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("slip.yaml:200: line.determinations[1].target_rounds[0]: check failed: target rounds agree"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the same face reading booked wrong in each round?"), std::string::npos) << r.err;
  // The tracking period T_A (7:46.4) booked for T_B (7:08.4) on the line's transit run: the passages
  // give 428.5 s, and the booked period would scale its ΔN by 428.4/466.4.
  std::ifstream in2(job);
  std::string t2((std::istreambuf_iterator<char>(in2)), std::istreambuf_iterator<char>());
  const auto at = t2.find("period_s: \"7:08.4\"", t2.find("\nline:"));
  ASSERT_NE(at, std::string::npos);
  t2.replace(at + 13, 4, "46.4");
  std::ofstream(dir_ / "period.yaml") << t2;
  const CmdResult p = run("gyro campaign --strict -o out.txt period.yaml");
  EXPECT_EQ(p.code, 1) << p.err;
  EXPECT_NE(p.err.find("period.yaml:179: line.determinations[0].period_s: check failed: booked period agrees with the "
                       "transit times"),
            std::string::npos)
      << p.err;
  EXPECT_NE(p.err.find("passages 428.5 s, booked 466.4 s"), std::string::npos) << p.err;
}

TEST_F(Cli, IndependentOrientationsOfOneLine) {
  ASSERT_EQ(run("gyro simulate --mode campaign --seed 21 -o a.yaml").code, 0);
  ASSERT_EQ(run("gyro simulate --mode campaign --seed 22 -o b.yaml").code, 0);
  const CmdResult r = run("gyro orientations a.yaml b.yaml --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["grid_azimuths"].size(), 2u);
  EXPECT_TRUE(j["all_checks_pass"].get<bool>());
  // Each grid azimuth is the one `gyro campaign` gives for that file.
  const auto a = nlohmann::json::parse(run("gyro campaign a.yaml --json").out);
  EXPECT_DOUBLE_EQ(j["grid_azimuths"][0]["deg"].get<double>(), a["grid_azimuth"]["deg"].get<double>());
  // The σ of the mean from the stated covariance, in closed form: sqrt(max(own, empirical)² + shared²)
  // with shared² = C12 for two that share the same contributions (ΣΣC/4 minus the own parts).
  const auto& m = j["mean_grid_azimuth"];
  const double c12 = j["covariance_arcsec2"][0][1].get<double>();
  EXPECT_GT(c12, 0.0);
  EXPECT_EQ(j["shared_sources"].size(), 3u);
  const double prop = std::sqrt(j["covariance_arcsec2"][0][0].get<double>() + j["covariance_arcsec2"][1][1].get<double>() +
                                2 * c12) / 2;
  EXPECT_NEAR(m["sigma_propagated_arcsec"].get<double>(), prop, 1e-9);
  const double own = m["sigma_own_arcsec"].get<double>(), emp = m["sigma_empirical_arcsec"].get<double>();
  EXPECT_NEAR(m["sigma_shared_arcsec"].get<double>(), std::sqrt(c12), 1e-9);
  EXPECT_NEAR(m["sigma_arcsec"].get<double>(), std::sqrt(std::pow(std::max(own, emp), 2) + c12), 1e-9);
  EXPECT_NE(run("gyro orientations a.yaml").code, 0);  // one file: a command-line error
}

TEST_F(Cli, DirectoryAndClampMistakesAreNamed) {
  fs::create_directories(dir_ / "a_dir");
  const CmdResult d = run("gyro campaign a_dir");
  EXPECT_EQ(d.code, 4) << d.err;
  EXPECT_NE(d.err.find("is a directory"), std::string::npos) << d.err;
  // More clamps than determinations would drop some silently.
  const CmdResult c = run("gyro simulate --clamp \"0 12 00,359 48 00\"");
  EXPECT_EQ(c.code, 1);
  EXPECT_NE(c.err.find("--clamp: 2 clamp readings for 1 determination(s)"), std::string::npos) << c.err;
  const CmdResult bad = run("gyro simulate --clamp \"0 72 00\"");
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("--clamp"), std::string::npos) << bad.err;
}

// Issue 35: a write error on standard output (a full disk behind `>`, /dev/full, a closed
// descriptor) exits 4 naming standard output; it exited 0 with the output lost or cut.
TEST_F(Cli, AFullOrClosedStandardOutputExitsFour) {
  const std::string ex = MERIDIAN_EXAMPLES_DIR;
  ASSERT_EQ(run("gravity synth-model --degree 6 --seed 1 --out m").code, 0);
  write("pts.csv", "lat,lon,h\n10,20,0\n-45,3,100\n");
  ASSERT_EQ(run("gyro simulate --mode campaign --seed 3 -o o3.yaml").code, 0);
  ASSERT_EQ(run("gyro simulate --mode campaign --seed 4 -o o4.yaml").code, 0);
  for (const std::string& args : std::vector<std::string>{"gyro template", "gyro simulate --mode campaign", "gyro campaign " + ex + "/campaign.yaml -q",
        "gyro campaign " + ex + "/campaign.yaml -q --json", "gyro orientations o3.yaml o4.yaml -q",
        "gravity point --model m.egm 10 20", "gravity points --model m.egm --input pts.csv",
        "nav process " + ex + "/nav-scenario-c/nav.yaml", "dov simulate --hours 0.01 --out -", "--version",
        "gyro campaign --help"}) {
    for (const char* sink : {"> /dev/full", ">&-"}) {
      const CmdResult r = shell(std::string(MERIDIAN_EXE) + " " + args + " " + sink);
      EXPECT_EQ(r.code, 4) << args << " " << sink << ": " << r.err;
      EXPECT_NE(r.err.find("standard output"), std::string::npos) << args << " " << sink << ": " << r.err;
      EXPECT_EQ(r.err.find("internal error"), std::string::npos) << args << ": " << r.err;
    }
    // The same command to a working standard output: 0.
    EXPECT_EQ(shell(std::string(MERIDIAN_EXE) + " " + args + " > /dev/null").code, 0) << args;
  }
}

// Issue 35: -o or --report naming the input was written over it (gyro reduce, gravity points,
// maglev denoise); now refused before any work, the input untouched.
TEST_F(Cli, AnOutputNamingAnInputIsRefused) {
  const std::string ex = MERIDIAN_EXAMPLES_DIR;
  ASSERT_EQ(run("gravity synth-model --degree 6 --seed 1 --out m").code, 0);
  write("p.csv", "lat,lon,h\n10,20,0\n");
  write("b.yaml", slurp(ex + "/tracking.yaml"));
  write("c.yaml", slurp(ex + "/campaign.yaml"));
  write("d.csv", slurp(ex + "/maglev-disturbed.csv"));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"gyro reduce b.yaml -o ./b.yaml", "b.yaml"},
      {"gyro reduce b.yaml --report b.yaml", "b.yaml"},
      {"gyro campaign c.yaml -q -o c.yaml", "c.yaml"},
      {"gyro stochastic b.yaml -o b.yaml", "b.yaml"},
      {"gyro orientations c.yaml c.yaml -o c.yaml", "c.yaml"},
      {"gravity points --model m.egm --input p.csv -o p.csv", "p.csv"},
      {"gravity points --model m.egm --input p.csv -o m.egm", "m.egm"},
      {"maglev denoise d.csv -o d.csv", "d.csv"}};
  for (const auto& [args, file] : cases) {
    const std::string before = slurp(dir_ / file);
    const CmdResult r = run(args);
    EXPECT_EQ(r.code, 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find("would overwrite the input " + file), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(slurp(dir_ / file), before) << args;
  }
}

// Issue 35: a disk that fills during the write (an LD_PRELOAD shim fails every write under
// full/ with ENOSPC; the free-space checks still pass). Every command exits 4 naming the file
// and leaves nothing in full/ — no output, no temporary file; NetCDF crashed in libhdf5's exit
// handler (exit 139) before.
TEST_F(Cli, AFullDiskDuringTheWriteExitsFourAndLeavesNothing) {
  const std::string ex = MERIDIAN_EXAMPLES_DIR;
  ASSERT_EQ(run("gravity synth-model --degree 6 --seed 1 --out m").code, 0);
  write("p.csv", "lat,lon,h\n10,20,0\n-45,3,100\n");
  fs::create_directories(dir_ / "full");
  const std::vector<std::string> cases = {
      "gravity grid --model m.egm -R g -I 10 -o full/g.nc -q",
      "gravity grid --model m.egm -R g -I 10 --quantities geoid -o full/g.gtx -q",
      "gravity grid --model m.egm -R g -I 10 -o full/g.csv -q",
      "gravity points --model m.egm --input p.csv -o full/p.csv -q",
      "gyro campaign " + ex + "/campaign.yaml -q -o full/c.txt",
      "gyro template -o full/t.yaml",
      "nav process " + ex + "/nav-scenario-c/nav.yaml -o full/track.csv",
      "dov simulate --hours 0.01 --out full/line.csv"};
  const std::string preload = std::string("LD_PRELOAD=") + MERIDIAN_WRITE_FAULT +
                              " ASAN_OPTIONS=verify_asan_link_order=0:detect_leaks=0 MERIDIAN_FAULT_PATH=/full/ ";
  for (const std::string& args : cases) {
    const CmdResult r = shell(preload + MERIDIAN_EXE + " " + args);
    EXPECT_EQ(r.code, 4) << args << ": " << r.err;
    EXPECT_NE(r.err.find("full/"), std::string::npos) << args << ": " << r.err;
    // libhdf5 reports its own words ("NetCDF: HDF error", "Permission denied" for a failed create).
    if (args.find(".nc") == std::string::npos) {
      EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << args << ": " << r.err;
    }
    for (const auto& left : fs::directory_iterator(dir_ / "full")) ADD_FAILURE() << args << " left " << left.path();
    fs::remove_all(dir_ / "full");
    fs::create_directories(dir_ / "full");
    // The shim only fails writes under full/: the same command elsewhere succeeds.
  }
  std::string ok = cases[0];
  ok.replace(ok.find("full/"), 5, "");
  EXPECT_EQ(shell(preload + MERIDIAN_EXE + " " + ok).code, 0) << ok;
}

// Issue 35: Ctrl-C or a kill during a run left the atomic writer's hidden temporary file
// (.out.csv.tmp.*) behind. gravity points reads its rows from a FIFO that stays open, so the
// run is certainly in progress, its temporary file written, when the signal comes.
TEST_F(Cli, AnInterruptedRunLeavesNoTemporaryFile) {
  ASSERT_EQ(run("gravity synth-model --degree 6 --seed 1 --out m").code, 0);
  std::string rows = "lat,lon,h\n";
  for (int i = 0; i < 3000; ++i) rows += std::to_string(-60 + i % 120) + "," + std::to_string(i % 360) + ",0\n";
  write("rows.csv", rows);
  for (const auto& [signal, status] : {std::pair{"INT", 130}, std::pair{"TERM", 143}, std::pair{"HUP", 129}}) {
    const std::string script =
        // set -m: a background job of a shell without job control has SIGINT ignored, and an
        // ignored signal stays ignored (nohup).
        std::string("set -m; rm -f in; mkfifo in; ") + MERIDIAN_EXE +
        " gravity points --model m.egm --input in -o out.csv -q 2> err & pid=$!; exec 3> in; cat rows.csv >&3; "
        "for i in $(seq 200); do ls -a | grep -q '^\\.out\\.csv\\.tmp' && break; sleep 0.05; done; "
        "ls -a | grep -c '^\\.out\\.csv\\.tmp' > during; kill -" + signal + " $pid; "
        // A run that ignores the signal is killed after 10 s (status 137), not waited for forever.
        "for i in $(seq 200); do kill -0 $pid 2> /dev/null || break; sleep 0.05; done; kill -9 $pid 2> /dev/null; "
        "wait $pid; echo $?; exec 3>&-";
    write("interrupt.sh", script);
    const CmdResult r = shell("bash interrupt.sh");  // bash: set -m works in a script
    EXPECT_EQ(slurp(dir_ / "during"), "1\n") << signal << ": the run had no temporary file to remove";
    EXPECT_EQ(r.out, std::to_string(status) + "\n") << signal << ": " << r.err;
    for (const auto& e : fs::directory_iterator(dir_))
      EXPECT_EQ(e.path().filename().string().find(".out.csv.tmp"), std::string::npos) << signal << " left " << e.path();
    EXPECT_FALSE(fs::exists(dir_ / "out.csv")) << signal;
  }
}

// Issue 35: a sigma of 1e200 in a job overflowed when squared and the error named a line of the
// data file (dr.csv:4: ... covariance; line.csv:4: initial covariance P0 ...). Now the job's
// own line and key are named.
TEST_F(Cli, AnAbsurdNumberInAJobIsNamedAtItsOwnLine) {
  const std::string ex = MERIDIAN_EXAMPLES_DIR;
  for (const char* f : {"dr.csv", "stations.csv", "lops.csv", "truth.csv"})
    write(f, slurp(ex + "/nav-scenario-c/" + f));
  std::string nav = slurp(ex + "/nav-scenario-c/nav.yaml");
  for (const std::string key : {"sigma_speed_m_s", "bias_sigma_m_s"}) {
    std::string t = nav;
    const auto at = t.find("\n" + key + ":");
    ASSERT_NE(at, std::string::npos) << key;
    const auto end = t.find('\n', at + 1);
    t.replace(at + 1, end - at - 1, key + ": 1e200");
    write("n.yaml", t);
    const CmdResult r = run("nav process n.yaml -q");
    EXPECT_EQ(r.code, 1) << key << ": " << r.err;
    EXPECT_NE(r.err.find("n.yaml:"), std::string::npos) << key << ": " << r.err;
    EXPECT_NE(r.err.find(key + ": 1e200 is beyond any value Meridian reads"), std::string::npos) << key << ": " << r.err;
    EXPECT_EQ(r.err.find("dr.csv"), std::string::npos) << key << ": " << r.err;
  }
  ASSERT_EQ(run("dov simulate --hours 0.02 --out line.csv --config dov.yaml").code, 0);
  std::string dov = slurp(dir_ / "dov.yaml");
  const auto at = dov.find("sigma_model_arcsec: 3");
  ASSERT_NE(at, std::string::npos) << dov;
  dov.replace(at, std::string("sigma_model_arcsec: 3").size(), "sigma_model_arcsec: 1e200");
  write("dov.yaml", dov);
  const CmdResult r = run("dov process dov.yaml -q");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("dov.yaml:3: sigma_model_arcsec: 1e200 is beyond"), std::string::npos) << r.err;
}

// Issue 35, one unit rule: a bracketed unit is applied or refused naming the column, never
// ignored (DR `speed [kn]`, `heading [rad]` and points `h [km]` were read as if unmarked).
TEST_F(Cli, BracketedUnitsAreAppliedOrRefusedNeverIgnored) {
  const std::string ex = MERIDIAN_EXAMPLES_DIR;
  ASSERT_EQ(run("gravity synth-model --degree 6 --seed 1 --out m").code, 0);
  write("km.csv", "lat [deg],lon [deg],h [km]\n10,20,1.5\n");
  write("m.csv", "lat,lon,h [m]\n10,20,1500\n");
  write("ft.csv", "lat,lon,h [ft]\n10,20,1500\n");
  const CmdResult km = run("gravity points --model m.egm --input km.csv -q");
  const CmdResult m = run("gravity points --model m.egm --input m.csv -q");
  ASSERT_EQ(km.code, 0) << km.err;
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(km.out, m.out);
  EXPECT_NE(km.out.find(",1500.0000,"), std::string::npos) << km.out;
  const CmdResult ft = run("gravity points --model m.egm --input ft.csv -q");
  EXPECT_EQ(ft.code, 1);
  EXPECT_NE(ft.err.find("ft.csv:1: h: column h [ft]: heights in [m] or [km]"), std::string::npos) << ft.err;
  for (const char* f : {"stations.csv", "lops.csv", "truth.csv", "nav.yaml"}) write(f, slurp(ex + "/nav-scenario-c/" + f));
  const std::string dr = slurp(ex + "/nav-scenario-c/dr.csv");
  const std::string header = "time_s,speed_m_s,heading_deg";
  ASSERT_NE(dr.find(header), std::string::npos);
  for (const auto& [marked, refused] : {std::pair{"time_s [s],speed_m_s [m/s],heading_deg [deg]", ""},
                                        std::pair{"time_s,speed_m_s [kn],heading_deg", "column speed_m_s [kn]"},
                                        std::pair{"time_s,speed_m_s,heading_deg [rad]", "column heading_deg [rad]"}}) {
    std::string t = dr;
    t.replace(t.find(header), header.size(), marked);
    write("dr.csv", t);
    const CmdResult r = run("nav process nav.yaml -q");
    if (std::string(refused).empty()) {
      EXPECT_EQ(r.code, 0) << marked << ": " << r.err;
    } else {
      EXPECT_EQ(r.code, 1) << marked;
      EXPECT_NE(r.err.find(std::string("dr.csv:3: ") ), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(refused), std::string::npos) << r.err;
    }
  }
}
