// Runs `meridian maglev ...` as a user would: simulate, reduce, denoise,
// calibrate, and the errors for bad input (exit codes, file:line:field).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

using meridian_test::CmdResult;
class MaglevCli : public meridian_test::CliTest {
 protected:
  // Clean, realistic noise; 20 000 samples per position.
  const std::string sim_ =
      "maglev simulate --alpha1 1.1459 --white 1e-5 --ar1-phi 0.8 --ar1-sigma 2e-6 ";
};

std::size_t count_lines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace

TEST_F(MaglevCli, CleanDeterminationToATenthOfAnArcsecond) {
  ASSERT_EQ(run(sim_ + "--samples 20000 --seed 3 --out d").code, 0);
  // The spec's clean scenario (no drift): the two-position model without a drift term.
  const CmdResult r =
      run("maglev reduce d-1.csv d-2.csv --scale 8000 --latitude 35 --drift none --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["result"]["alpha1_arcsec"].get<double>(), 1.1459 * 3600, 0.1);
  EXPECT_NEAR(j["result"]["north_deg"].get<double>(), 360 - 1.1459, 0.1 / 3600);
  EXPECT_LT(j["result"]["alpha1_sigma_arcsec"].get<double>(), 0.05);
  EXPECT_EQ(j["position1"]["samples"], 20000);
  // The default fits a drift too: one block per position, so σ about doubles (still < 0.1″).
  const CmdResult d = run("maglev reduce d-1.csv d-2.csv --scale 8000 --latitude 35 --json -q");
  ASSERT_EQ(d.code, 0) << d.err;
  const auto jd = nlohmann::json::parse(d.out);
  const double s = jd["result"]["alpha1_sigma_arcsec"].get<double>();
  EXPECT_LT(s, 0.1);
  EXPECT_NEAR(jd["result"]["alpha1_arcsec"].get<double>(), 1.1459 * 3600, 3.0 * s);
  EXPECT_FALSE(jd["drift"]["significant"].get<bool>());
}

TEST_F(MaglevCli, InterferenceIsRejectedAndListed) {
  ASSERT_EQ(
      run(sim_ + "--samples 20000 --burst 1:63:103:2e-3:6e-4:0.5:8 --seed 11 --one-file --out d")
          .code,
      0);
  const CmdResult r = run("maglev reduce d.csv --scale 8000 --latitude 35 --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(std::abs(j["plain"]["alpha1_arcsec"].get<double>() - 1.1459 * 3600), 10.0);
  EXPECT_NEAR(j["result"]["alpha1_arcsec"].get<double>(), 1.1459 * 3600, 0.1);
  const auto rejected = j["position1"]["rejected_segments"];
  ASSERT_GE(rejected.size(), 4u);
  for (const auto& i : rejected) {
    if (!j["position1"]["segments"][i.get<std::size_t>()]["kept"].get<bool>()) continue;
    ADD_FAILURE() << "a rejected segment is marked kept";
  }
  // The text names the rejected segments too.
  const CmdResult t = run("maglev reduce d.csv --scale 8000 --latitude 35 -q");
  EXPECT_NE(t.out.find("rejected segment"), std::string::npos);
}

TEST_F(MaglevCli, DenoiseWritesTheSeriesAndRefusesTooDeepALevel) {
  ASSERT_EQ(run(sim_ + "--samples 1000 --seed 5 --out d").code, 0);
  CmdResult r = run("maglev denoise d-1.csv --wavelet db6 --level 4 --threshold hard -o out.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string out = slurp(dir_ / "out.csv");
  EXPECT_NE(out.find("time [s],current [A]"), std::string::npos);
  EXPECT_NE(out.find("db6 levels 4"), std::string::npos);
  // 1000 samples and the header line (+ 2 comment lines).
  EXPECT_EQ(count_lines(out), 1000u + 3u);
  r = run(
      "maglev denoise d-1.csv --wavelet db6 --level 7");  // max level for 1000 samples with db6: 6
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("level"), std::string::npos) << r.err;
  r = run("maglev denoise d-1.csv --wavelet db12");
  EXPECT_EQ(r.code, 2);  // an invalid option value is a bad command line
  EXPECT_NE(r.err.find("db2"), std::string::npos) << r.err;
}

// Invalid option values and missing required constants are command-line errors: exit 2
// (docs/cli.md), before any file is read.
TEST_F(MaglevCli, InvalidOptionValuesExitTwo) {
  ASSERT_EQ(run(sim_ + "--samples 1000 --seed 5 --out d").code, 0);
  for (const char* opts : {"--wavelet db1", "--wavelet haar", "--mode zero", "--rule minimax",
                           "--threshold medium", "--level 0"}) {
    const CmdResult r = run(std::string("maglev denoise d-1.csv ") + opts);
    EXPECT_EQ(r.code, 2) << opts << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << opts;
  }
  const std::string red = "maglev reduce d-1.csv d-2.csv -q ";
  for (const char* opts :
       {"--scale 8000 --latitude 35 --alpha 0", "--scale 8000 --latitude 35 --alpha 1",
        "--scale 8000 --latitude 35 --alpha x", "--scale 8000 --latitude 35 --lags 0",
        "--scale 8000 --latitude 35 --segment 10", "--scale 8000 --latitude 35 --mode zero",
        "--latitude 35", "--scale 8000"}) {
    const CmdResult r = run(red + opts);
    EXPECT_EQ(r.code, 2) << opts << ": " << r.err;
  }
  CmdResult r = run(red + "--latitude 35");
  EXPECT_NE(r.err.find("--scale"), std::string::npos) << r.err;
  r = run(red + "--scale 8000");
  EXPECT_NE(r.err.find("--latitude"), std::string::npos) << r.err;
  r = run("maglev calibrate nothing.csv --latitude 35 --alpha 1.5");
  EXPECT_EQ(r.code, 2) << r.err;
  // Valid values still run.
  EXPECT_EQ(run(red + "--scale 8000 --latitude 35 --alpha 0.01 --lags 5 --segment 0").code, 0);
}

TEST_F(MaglevCli, CalibrationRecoversTheLinesAndFeedsReduce) {
  ASSERT_EQ(run("maglev simulate --calibration-azimuths=-3,-2,-1,0,1,2,3 --slope-ratio1 1.01 "
                "--slope-ratio2 0.99 "
                "--best-azimuth 0.11459 --constant-deviation 1.75e-5 --samples 20000 --white 1e-5 "
                "--seed 4 --out c")
                .code,
            0);
  CmdResult r = run("maglev calibrate c-calibration.csv --latitude 35 --json -o cal.json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir_ / "cal.json"));
  EXPECT_NEAR(j["best_azimuth_arcsec"].get<double>(), 0.11459 * 3600,
              3 * j["best_azimuth_sigma_arcsec"].get<double>());
  EXPECT_NEAR(j["constant_deviation_A"].get<double>(), 1.75e-5,
              3 * j["constant_deviation_sigma_A"].get<double>());
  EXPECT_NEAR(j["scale_A_s_per_rad"].get<double>(), 8000,
              3 * j["scale_sigma_A_s_per_rad"].get<double>());
  EXPECT_TRUE(j["trend_significant"].get<bool>());
  // The stored calibration gives reduce its K and the prior bias of the symmetry check.
  ASSERT_EQ(run(sim_ + "--samples 20000 --seed 3 --bias 1.75e-5 --out d").code, 0);
  r = run("maglev reduce d-1.csv d-2.csv --calibration cal.json --latitude 35 --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto k = nlohmann::json::parse(r.out);
  EXPECT_NEAR(k["scale_A_s_per_rad"].get<double>(), j["scale_A_s_per_rad"].get<double>(), 1e-9);
  ASSERT_TRUE(k.contains("symmetry"));
  EXPECT_TRUE(k["symmetry"]["passed"].get<bool>()) << k["symmetry"].dump();
}

// The shipped examples come from one instrument: the disturbed determination's bias is the
// calibration's I* (trial finding 11: z = 1105 when b was 2e-4 A and I* 1.75e-5 A).
TEST_F(MaglevCli, ShippedExamplesPassTheSymmetryCheck) {
  const std::string ex = std::string(MERIDIAN_SOURCE_DIR) + "/examples/";
  CmdResult r = run("maglev calibrate " + ex + "maglev-calibration.csv --latitude 35 --json -o cal.json");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("maglev reduce " + ex + "maglev-disturbed.csv --calibration cal.json --latitude 35 --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto k = nlohmann::json::parse(r.out);
  EXPECT_TRUE(k["symmetry"]["passed"].get<bool>()) << k["symmetry"].dump();
  // Truth of the example: α1 = 1.1459°; the burst on position 1 is rejected.
  EXPECT_NEAR(k["result"]["alpha1_arcsec"].get<double>(), 1.1459 * 3600,
              3 * k["result"]["alpha1_sigma_arcsec"].get<double>());
  EXPECT_FALSE(k["position1"]["rejected_segments"].empty());
  // The calibration's slopes are printed in A/rad, as its warnings and JSON keys say.
  r = run("maglev calibrate " + ex + "maglev-calibration.csv --latitude 35");
  EXPECT_NE(r.out.find("k = 0.48"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(" A   c ="), std::string::npos) << r.out;
}

// Usability (trial finding 17): a short series is denoised at the deepest level it allows when
// --level is not given; a σ from a handful of samples is flagged.
TEST_F(MaglevCli, ShortSeriesAreHandledWithoutSurprises) {
  ASSERT_EQ(run(sim_ + "--samples 300 --seed 5 --out d").code, 0);
  CmdResult r = run("maglev denoise d-1.csv -o out.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  // pywt.dwt_max_level(300, 8) = floor(log2(300/7)) = 5.
  EXPECT_NE(slurp(dir_ / "out.csv").find("db4 levels 5"), std::string::npos);
  r = run("maglev denoise d-1.csv --level 6");  // asked explicitly: refused
  EXPECT_EQ(r.code, 1);
  write("s4.csv", "time,current\n0,1\n1,2\n2,1.5\n3,1.2\n");
  r = run("maglev denoise s4.csv");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("too few for any level"), std::string::npos) << r.err;
  ASSERT_EQ(run(sim_ + "--samples 2 --seed 5 --out n2").code, 0);
  r = run("maglev reduce n2-1.csv n2-2.csv --scale 8000 --latitude 35 --no-process");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("rests on 2 samples"), std::string::npos) << r.out;
  ASSERT_EQ(run(sim_ + "--samples 100 --seed 5 --out n100").code, 0);
  r = run("maglev reduce n100-1.csv n100-2.csv --scale 8000 --latitude 35");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no processing"), std::string::npos) << r.err;
}

TEST_F(MaglevCli, BadInputNamesFileLineAndField) {
  ASSERT_EQ(run(sim_ + "--samples 3000 --seed 1 --out d").code, 0);
  write("empty.csv", "time,current\n");
  CmdResult r = run("maglev reduce empty.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("empty.csv"), std::string::npos) << r.err;
  // Non-monotonic time: line 3 of the file.
  write("back.csv", "time,current\n0,0.01\n1,0.01\n0.5,0.02\n");
  r = run("maglev reduce back.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("back.csv:4: time"), std::string::npos) << r.err;
  // NaN sample.
  write("nan.csv", "time,current\n0,0.01\n1,nan\n");
  r = run("maglev reduce nan.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("nan.csv:3: current"), std::string::npos) << r.err;
  // Constant series.
  std::string constant = "time,current\n";
  for (int i = 0; i < 3000; ++i) constant += std::to_string(i) + ",0.01\n";
  write("const.csv", constant);
  r = run("maglev reduce const.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("const.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no variation in the series"), std::string::npos) << r.err;
  // denoise names the file, not an internal field.
  r = run("maglev denoise const.csv --level 2");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("const.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no variation in the series"), std::string::npos) << r.err;
  // A stray third value (no position column in the header): an error at file:line.
  std::string extra = "time [s],current [A]\n";
  for (int i = 0; i < 100; ++i)
    extra += std::to_string(i) + ",0.01" + std::to_string(i % 7) + (i == 88 ? ",3\n" : "\n");
  write("extra.csv", extra);
  r = run("maglev reduce extra.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("extra.csv:90"), std::string::npos) << r.err;
  r = run("maglev denoise extra.csv --level 2");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("extra.csv:90"), std::string::npos) << r.err;
  // Empty trailing fields are not values.
  std::string trailing = "time,current\n";
  for (int i = 0; i < 100; ++i) trailing += std::to_string(i) + ",0.01" + std::to_string(i % 7) + ",\n";
  write("trailing.csv", trailing);
  EXPECT_EQ(run("maglev denoise trailing.csv --level 2").code, 0);
  // A position missing from a one-file input.
  write("one.csv", "time,current,position\n0,0.01,1\n1,0.02,1\n");
  r = run("maglev reduce one.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("position 2 has no samples"), std::string::npos) << r.err;
  // Too short for two segments.
  write("short.csv", "time,current\n0,0.01\n1,0.02\n2,0.01\n");
  r = run("maglev reduce short.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("short.csv"), std::string::npos) << r.err;
  // |(I1 − I2)/(2Kω cos φ)| > 1: a numerical error, exit 3, no NaN.
  r = run("maglev reduce d-1.csv d-2.csv --scale 10 --latitude 35 --json -q");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("> 1"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  // Missing constants: a bad command line.
  r = run("maglev reduce d-1.csv d-2.csv --latitude 35 -q");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--scale"), std::string::npos) << r.err;
}

// Units in the header are applied, never ignored: the same series in ms and mA gives the
// same determination; a unit that is not understood is an error at the header line.
TEST_F(MaglevCli, HeaderUnitsAreAppliedOrRefused) {
  ASSERT_EQ(run(sim_ + "--samples 3000 --seed 2 --out d").code, 0);
  for (const char* pos : {"1", "2"}) {
    std::istringstream in(slurp(dir_ / (std::string("d-") + pos + ".csv")));
    std::string line, out = "# converted\ntime [ms],current [mA]\n";
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || line[0] == 't') continue;
      const auto comma = line.find(',');
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.17g,%.17g\n", std::stod(line.substr(0, comma)) * 1e3,
                    std::stod(line.substr(comma + 1)) * 1e3);
      out += buf;
    }
    write(std::string("m-") + pos + ".csv", out);
  }
  const CmdResult si = run("maglev reduce d-1.csv d-2.csv --scale 8000 --latitude 35 --json -q");
  const CmdResult milli = run("maglev reduce m-1.csv m-2.csv --scale 8000 --latitude 35 --json -q");
  ASSERT_EQ(si.code, 0) << si.err;
  ASSERT_EQ(milli.code, 0) << milli.err;
  const auto a = nlohmann::json::parse(si.out)["result"];
  const auto b = nlohmann::json::parse(milli.out)["result"];
  EXPECT_NEAR(b["alpha1_arcsec"].get<double>(), a["alpha1_arcsec"].get<double>(), 1e-6);
  EXPECT_NEAR(b["alpha1_sigma_arcsec"].get<double>(), a["alpha1_sigma_arcsec"].get<double>(), 1e-6);
  write("volt.csv", "# a comment\ntime [s],current [V]\n0,0.01\n1,0.02\n");
  const CmdResult r = run("maglev reduce volt.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("volt.csv:2: current"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[V]"), std::string::npos) << r.err;
}

// A burst on position 2 counts from that position's start and shows in its plain mean; a
// burst that touches no sample is an error rather than silently absent.
TEST_F(MaglevCli, SimulatedBurstsArePlacedInTheirPositionOrRefused) {
  const std::string base = sim_ + "--samples 3000 --rate-hz 20 --seed 4 ";
  ASSERT_EQ(run(base + "--out clean").code, 0);
  ASSERT_EQ(run(base + "--burst 2:10:40:2e-3:6e-4:0.5:8 --out hit").code, 0);
  const auto mean2 = [&](const std::string& prefix) {
    const CmdResult r =
        run("maglev reduce " + prefix + "-1.csv " + prefix + "-2.csv --scale 8000 --latitude 35 --json -q");
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out)["position2"]["mean_all_A"].get<double>();
  };
  // The burst's offset (0.6 mA at full envelope over 30 s of 150 s) moves the plain mean.
  EXPECT_GT(std::abs(mean2("hit") - mean2("clean")), 5e-5);
  const CmdResult r = run(base + "--burst 1:500:600:2e-3:6e-4:0.5:8 --out miss");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("outside the series"), std::string::npos) << r.err;
}

TEST_F(MaglevCli, HtmlReportsShowTheSeriesAndSegments) {
  ASSERT_EQ(run(sim_ + "--samples 4000 --rate-hz 20 --burst 1:63:103:2e-3:6e-4:0.5:8 --seed 2 --out d").code, 0);
  const CmdResult r = run("maglev reduce d-1.csv d-2.csv --scale 8000 --latitude 35 -q -o out.txt --report r.html");
  if (r.code != 0 && r.err.find("without HTML reports") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = slurp(dir_ / "r.html");
  EXPECT_NE(html.find("id=\"position1\""), std::string::npos);
  EXPECT_NE(html.find("REJECTED"), std::string::npos);
  EXPECT_NE(html.find("raw and cleaned series"), std::string::npos);
  // The report does not change the text result.
  ASSERT_EQ(run("maglev reduce d-1.csv d-2.csv --scale 8000 --latitude 35 -q -o plain.txt").code, 0);
  EXPECT_EQ(slurp(dir_ / "out.txt"), slurp(dir_ / "plain.txt"));
  // Bad input: no report is written.
  write("bad.csv", "time,current\n0,0.01\n0,0.02\n");
  const CmdResult bad = run("maglev reduce bad.csv d-2.csv --scale 8000 --latitude 35 -q --report bad.html");
  EXPECT_EQ(bad.code, 1);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.html"));
}

// The field case of issue 30 (../shared/cases/maglev-field/continuous-drift.csv: a drift of
// 2e-7 A/s continuing across both positions on one clock; truth α1 = 0°30′00″ with K 8000 at
// 35°): within 3σ of the truth, the drift found and reported. Before the drift model:
// 29′45.339″ ± 3.067″ with no word about a trend. Skipped only when ../shared is absent.
TEST_F(MaglevCli, ContinuousDriftCaseGivesItsTruth) {
  const std::filesystem::path shared = std::filesystem::path(MERIDIAN_SOURCE_DIR) / ".." / "shared";
  if (!std::filesystem::exists(shared)) GTEST_SKIP() << shared << " not present (optional data)";
  const std::string file = (shared / "cases" / "maglev-field" / "continuous-drift.csv").string();
  const CmdResult r = run("maglev reduce " + file + " --scale 8000 --latitude 35 --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double a = j["result"]["alpha1_arcsec"].get<double>();
  const double s = j["result"]["alpha1_sigma_arcsec"].get<double>();
  EXPECT_LT(std::abs(a - 1800.0), 3.0 * s) << a << " ± " << s;
  ASSERT_TRUE(j.contains("drift"));
  EXPECT_TRUE(j["drift"]["significant"].get<bool>());
  EXPECT_EQ(j["drift"]["sequence"], "1-2");
  // The segment tests see the series with the drift taken out: nothing rejected for the drift.
  EXPECT_TRUE(j["position1"]["rejected_segments"].empty());
  EXPECT_TRUE(j["position2"]["rejected_segments"].empty());
  EXPECT_NEAR(j["drift"]["rate_A_per_s"].get<double>(), 2e-7,
              3.0 * j["drift"]["rate_sigma_A_per_s"].get<double>());
  const CmdResult t = run("maglev reduce " + file + " --scale 8000 --latitude 35 -q");
  EXPECT_NE(t.out.find("drift (linear, common clock, blocks 1-2)"), std::string::npos) << t.out;
}

// `maglev simulate` puts the blocks of a sequence on one clock with the drift continuous; reduce
// finds the blocks, the drift, and a symmetric sequence barely pays for it.
TEST_F(MaglevCli, SimulatedSequencesShareOneClockAndTheDrift) {
  ASSERT_EQ(run(sim_ + "--samples 3000 --rate-hz 10 --drift 2e-7 --sequence 1,2,2,1 --pause 40 "
                       "--seed 5 --one-file --out s")
                .code,
            0);
  const CmdResult r = run("maglev reduce s.csv --scale 8000 --latitude 35 --json -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["drift"]["sequence"], "1-2-2-1");
  EXPECT_EQ(j["position1"]["samples"], 6000);
  EXPECT_NEAR(j["drift"]["rate_A_per_s"].get<double>(), 2e-7,
              4.0 * j["drift"]["rate_sigma_A_per_s"].get<double>());
  EXPECT_LT(j["drift"]["sigma_inflation"].get<double>(), 1.2);
  const double a = j["result"]["alpha1_arcsec"].get<double>();
  EXPECT_LT(std::abs(a - 1.1459 * 3600), 4.0 * j["result"]["alpha1_sigma_arcsec"].get<double>());
  // --drift none: the symmetric sequence cancels the linear drift by design.
  const CmdResult n = run("maglev reduce s.csv --scale 8000 --latitude 35 --drift none --json -q");
  ASSERT_EQ(n.code, 0) << n.err;
  const auto jn = nlohmann::json::parse(n.out);
  EXPECT_FALSE(jn.contains("drift"));
  EXPECT_LT(std::abs(jn["result"]["alpha1_arcsec"].get<double>() - 1.1459 * 3600),
            4.0 * jn["result"]["alpha1_sigma_arcsec"].get<double>());
  EXPECT_EQ(run("maglev reduce s.csv --scale 8000 --latitude 35 --drift cubic").code, 2);
  EXPECT_EQ(run(sim_ + "--sequence 1,3 --out bad").code, 1);
  EXPECT_EQ(run(sim_ + "--sequence 1,1 --out bad").code, 1);
}

// The settling case of issue 30 (../shared/cases/maglev-field/settling-1.csv, -2.csv: ∓3e-4 A
// decaying with τ 20 s after each rotation; truth α1 0.866272865°): the transient detected at
// both positions, cut and stated, α1 within 3σ (before: −4.1″ ± 0.6″ over 15 seeds with σ
// 2.5″). A cut given is taken as given. Skipped only when ../shared is absent.
TEST_F(MaglevCli, SettlingCaseIsDetectedCutAndStated) {
  const std::filesystem::path shared = std::filesystem::path(MERIDIAN_SOURCE_DIR) / ".." / "shared";
  if (!std::filesystem::exists(shared)) GTEST_SKIP() << shared << " not present (optional data)";
  const std::filesystem::path dir = shared / "cases" / "maglev-field";
  const std::string files =
      (dir / "settling-1.csv").string() + " " + (dir / "settling-2.csv").string();
  const std::string opts = " --scale 6000 --latitude 34.25 --reading1 23.111870399 --json -q";
  const CmdResult r = run("maglev reduce " + files + opts);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double a = j["result"]["alpha1_arcsec"].get<double>();
  const double s = j["result"]["alpha1_sigma_arcsec"].get<double>();
  EXPECT_LT(std::abs(a - 0.866272865 * 3600), 3.0 * s) << a << " ± " << s;
  ASSERT_EQ(j["settling"].size(), 2u);
  for (const auto& c : j["settling"]) {
    EXPECT_TRUE(c["detected"].get<bool>());
    EXPECT_GT(c["cut_s"].get<double>(), 20.0);
    EXPECT_NEAR(std::abs(c["amplitude_A"].get<double>()), 3e-4, 1e-4);
  }
  EXPECT_LT(j["settling"][0]["amplitude_A"].get<double>(), 0.0);  // −3e-4 at position 1
  const CmdResult g = run("maglev reduce " + files + opts + " --settling-cut 90");
  ASSERT_EQ(g.code, 0) << g.err;
  const auto jg = nlohmann::json::parse(g.out);
  ASSERT_EQ(jg["settling"].size(), 2u);
  EXPECT_FALSE(jg["settling"][0]["detected"].get<bool>());
  EXPECT_EQ(jg["settling"][0]["samples_cut"], 900);
  // The continuous-drift case has no transient: nothing cut.
  const CmdResult c = run("maglev reduce " + (dir / "continuous-drift.csv").string() +
                          " --scale 8000 --latitude 35 --json -q");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_TRUE(nlohmann::json::parse(c.out)["settling"].empty());
}
