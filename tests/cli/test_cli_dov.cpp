// Runs `meridian dov ...` as a user would: simulate a line with its configuration, process it
// (JSON summary, profile CSV), and the errors for bad input (exit codes, file:line:column).

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

using meridian_test::CmdResult;
class DovCli : public meridian_test::CliTest {};

}  // namespace

TEST_F(DovCli, SimulateAndProcessAHalfHourLine) {
  const CmdResult s = run(
      "dov simulate --hours 0.5 --seed 3 --phi-e-arcsec 1.5 --phi-n-arcsec -2 --phi-u-arcsec 4 "
      "--out line.csv --config dov.yaml");
  ASSERT_EQ(s.code, 0) << s.err;
  const CmdResult r = run("dov process dov.yaml --json -q -o profile.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["epochs"], 1801);
  // the JSON contract of issue 10: rms_arcsec.{model,filtered,smoothed}.{eta,xi} with truth
  const double model = j["rms_arcsec"]["model"]["xi"].get<double>();
  const double filtered = j["rms_arcsec"]["filtered"]["xi"].get<double>();
  const double smoothed = j["rms_arcsec"]["smoothed"]["xi"].get<double>();
  // (the accuracy itself is the scenario tests' business, tests/dov/test_scenarios.cpp)
  EXPECT_GT(model, 1.0);
  EXPECT_LT(filtered, model);
  EXPECT_LT(smoothed, filtered);
  EXPECT_GT(j["mean_sigma_arcsec"]["smoothed"]["eta"].get<double>(), 0.0);
  EXPECT_TRUE(j["nis"]["mean"].get<double>() > 1.5 && j["nis"]["mean"].get<double>() < 2.5);
  EXPECT_TRUE(j["eps_u_deg_per_h"].contains("sigma"));
  EXPECT_EQ(j["discretisation"], "exact");
  // the profile: a header and one line per epoch
  const std::string profile = slurp(dir_ / "profile.csv");
  std::size_t lines = 0;
  for (char c : profile) lines += c == '\n';
  EXPECT_EQ(lines, 1802u);
  EXPECT_EQ(profile.rfind("time_s,lat_deg,lon_deg,model_eta_arcsec,", 0), 0u);
  // positions and truth in the profile are the line's own, row for row (10 digits)
  {
    const auto table = [](const std::string& text) {
      std::vector<std::vector<std::string>> rows;
      std::istringstream in(text);
      for (std::string l; std::getline(in, l);) {
        if (l.empty() || l[0] == '#') continue;
        std::vector<std::string> f;
        std::istringstream ls(l);
        for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
        rows.push_back(f);
      }
      return rows;
    };
    const auto line = table(slurp(dir_ / "line.csv"));
    const auto prof = table(profile);
    ASSERT_EQ(line.size(), prof.size());
    const auto col = [](const std::vector<std::string>& header, const std::string& name) {
      const auto it = std::find(header.begin(), header.end(), name);
      EXPECT_NE(it, header.end()) << name;
      return static_cast<std::size_t>(it - header.begin());
    };
    for (const char* name : {"lat_deg", "lon_deg", "truth_eta_arcsec", "truth_xi_arcsec"}) {
      const std::size_t a = col(line[0], name), b = col(prof[0], name);
      for (std::size_t k = 1; k < line.size(); k += 97)
        EXPECT_NEAR(std::stod(line[k][a]), std::stod(prof[k][b]), 1e-8) << name << " row " << k;
    }
  }
  // the profile never replaces its input (a user trial lost the line this way)
  const std::string line_before = slurp(dir_ / "line.csv");
  for (const char* target : {"line.csv", "dov.yaml"}) {
    const CmdResult o = run(std::string("dov process dov.yaml -q -o ") + target);
    EXPECT_NE(o.code, 0) << target;
    EXPECT_NE(o.err.find("would overwrite the input"), std::string::npos) << o.err;
  }
  EXPECT_EQ(slurp(dir_ / "line.csv"), line_before);
  // the text summary
  const CmdResult t = run("dov process dov.yaml -q");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("smoothed"), std::string::npos) << t.out;
  // the settings the result depends on are echoed (a trial finding)
  EXPECT_NE(t.out.find("sigma_model 3\", zeta 0.05, correlation length 10000 m; r: east 0.5\", "
                       "north 0.5\"; discretisation exact, extraction exact"),
            std::string::npos)
      << t.out;
}

TEST_F(DovCli, SimulateRecordsItsSettingsAndWritesBothFilesOrNeither) {
  ASSERT_EQ(run("dov simulate --hours 0.01 --seed 7 --phi-u-arcsec 4 --out line.csv").code, 0);
  const std::string csv = slurp(dir_ / "line.csv");
  const std::string second = csv.substr(csv.find('\n') + 1, csv.find('\n', csv.find('\n') + 1) - csv.find('\n') - 1);
  EXPECT_EQ(second.rfind("# Simulated: seed 7, ", 0), 0u) << second;
  EXPECT_NE(second.find("phi(0) E N U = 0 0 4\""), std::string::npos) << second;
  // a configuration that cannot be written: neither file is written
  const CmdResult r = run("dov simulate --hours 0.01 --out fresh.csv --config no/such/dir/dov.yaml");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("no/such/dir"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "fresh.csv"));
  // the same file for both, or the line on standard output with a configuration: refused
  EXPECT_NE(run("dov simulate --hours 0.01 --out same.yaml --config same.yaml").code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "same.yaml"));
  const CmdResult d = run("dov simulate --hours 0.01 --out - --config dov.yaml");
  EXPECT_NE(d.code, 0);
  EXPECT_NE(d.err.find("--config needs --out"), std::string::npos) << d.err;
}

TEST_F(DovCli, TransportRateFromSimulationToSummary) {
  // --transport-rate puts it in the truth, in the line's settings comment and in the
  // configuration, and the summary says the processing used it.
  ASSERT_EQ(run("dov simulate --hours 0.05 --speed-m-s 200 --transport-rate --out line.csv "
                "--config dov.yaml").code,
            0);
  EXPECT_NE(slurp(dir_ / "dov.yaml").find("transport_rate: true"), std::string::npos);
  EXPECT_NE(slurp(dir_ / "line.csv").find("attitude error with transport rate"), std::string::npos);
  const CmdResult text = run("dov process dov.yaml -q");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("transport rate from the track (10 s baselines, 18 closed)"),
            std::string::npos)
      << text.out;
  const CmdResult json = run("dov process dov.yaml -q --json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["transport_rate"]["baseline_s"], 10.0);
  EXPECT_EQ(j["transport_rate"]["updates"], 18);  // 1-Hz samples over 180 s: closed at 10, 20, …, 180 s
  // a baseline longer than the line: ω_en never set, and a warning says so
  write("long.yaml", "line: line.csv\ntransport_rate: true\ntransport_rate_baseline_s: 2000\n");
  const CmdResult longer = run("dov process long.yaml -q");
  ASSERT_EQ(longer.code, 0) << longer.err;
  EXPECT_NE(longer.out.find("no baseline of 2000 s closed"), std::string::npos) << longer.out;
  // without the flag: the spec's Earth-rate model, said as null
  ASSERT_EQ(run("dov simulate --hours 0.05 --out plain.csv --config plain.yaml").code, 0);
  EXPECT_EQ(slurp(dir_ / "plain.yaml").find("transport_rate"), std::string::npos);
  const CmdResult plain = run("dov process plain.yaml -q --json");
  EXPECT_TRUE(nlohmann::json::parse(plain.out)["transport_rate"].is_null()) << plain.out;
}

TEST_F(DovCli, AReportThatCannotBeWrittenLeavesNoProfile) {
  ASSERT_EQ(run("dov simulate --hours 0.02 --out line.csv --config dov.yaml").code, 0);
  const CmdResult r = run("dov process dov.yaml -q -o profile.csv --report no/such/r.html");
  EXPECT_NE(r.code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "profile.csv"));
}

TEST_F(DovCli, BadSampleNamesFileLineAndColumn) {
  ASSERT_EQ(run("dov simulate --hours 0.05 --out line.csv --config dov.yaml").code, 0);
  // line 4 is the first sample (two comments, header): make its lgu_11 unreadable
  std::string csv = slurp(dir_ / "line.csv");
  std::size_t pos = 0;
  for (int l = 0; l < 3; ++l) pos = csv.find('\n', pos) + 1;  // start of line 4
  for (int comma = 0; comma < 5; ++comma) pos = csv.find(',', pos) + 1;  // field 6: lgu_11
  csv.insert(pos, "q");
  write("line.csv", csv);
  const CmdResult r = run("dov process dov.yaml -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("line.csv:4: lgu_11"), std::string::npos) << r.err;
}

TEST_F(DovCli, NonOrthogonalMatrixAndConfigTypo) {
  ASSERT_EQ(run("dov simulate --hours 0.05 --out line.csv --config dov.yaml").code, 0);
  std::string csv = slurp(dir_ / "line.csv");
  // sample 4 (line 8): scale its ins_11 by replacing the field with 2
  std::size_t pos = 0;
  for (int l = 0; l < 7; ++l) pos = csv.find('\n', pos) + 1;
  for (int comma = 0; comma < 14; ++comma) pos = csv.find(',', pos) + 1;  // field 15: ins_11
  csv.replace(pos, csv.find(',', pos) - pos, "2");
  write("line.csv", csv);
  const CmdResult r = run("dov process dov.yaml -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("line.csv:8: ins_11…ins_33"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not orthogonal"), std::string::npos) << r.err;
  write("typo.yaml", "line: line.csv\nsigma_modle_arcsec: 3\n");
  const CmdResult t = run("dov process typo.yaml -q");
  EXPECT_EQ(t.code, 1);
  EXPECT_NE(t.err.find("typo.yaml:2"), std::string::npos) << t.err;
  EXPECT_FALSE(std::ifstream(dir_ / "profile.csv").good());
}

TEST_F(DovCli, HtmlReportShowsTheProfileAndTheNisCheck) {
  ASSERT_EQ(run("dov simulate --hours 0.25 --seed 4 --out line.csv --config dov.yaml").code, 0);
  const CmdResult r = run("dov process dov.yaml -q --json --report r.html");
  if (r.code != 0 && r.err.find("without HTML reports") != std::string::npos) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = slurp(dir_ / "r.html");
  for (const char* id : {"summary", "profile", "innovations", "notes"})
    EXPECT_NE(html.find(std::string("id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_NE(html.find("mean NIS"), std::string::npos);
  EXPECT_NE(html.find("smoothed ± σ"), std::string::npos);
  EXPECT_NE(html.find("\"truth\""), std::string::npos);  // the simulated truth is drawn
  // the same NIS as the JSON summary, to three decimals
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NE(html.find(fmt::format("{:.3f}", j["nis"]["mean"].get<double>())), std::string::npos);
  // the report never replaces an input, and a bad configuration writes none
  EXPECT_NE(run("dov process dov.yaml -q --report line.csv").code, 0);
  // profile and report on one path: refused (a trial lost the profile this way)
  const CmdResult same = run("dov process dov.yaml -q -o out.html --report out.html");
  EXPECT_NE(same.code, 0);
  EXPECT_NE(same.err.find("same file"), std::string::npos) << same.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.html"));
  write("typo.yaml", "line: line.csv\nzetta: 0.05\n");
  EXPECT_NE(run("dov process typo.yaml -q --report bad.html").code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.html"));
}

TEST_F(DovCli, BinaryLineConvertedOrSimulatedGivesTheSameProfile) {
  ASSERT_EQ(run("dov simulate --hours 0.05 --seed 5 --out line.csv --config csv.yaml").code, 0);
  const CmdResult c = run("dov convert line.csv line.bin");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_NE(c.err.find("181 samples, model values, truth"), std::string::npos) << c.err;
  EXPECT_EQ(slurp(dir_ / "line.bin").substr(0, 8), "MRDN-DOV");
  write("bin.yaml", "line: line.bin\n");
  const CmdResult a = run("dov process csv.yaml -q --json -o a.csv");
  const CmdResult b = run("dov process bin.yaml -q --json -o b.csv");
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  // the binary line holds what the CSV reader read: the same numbers, so the same profile
  EXPECT_EQ(slurp(dir_ / "a.csv"), slurp(dir_ / "b.csv"));
  EXPECT_EQ(a.out, b.out);
  // simulate --binary: the simulator's doubles; processed, close to the CSV's (17 digits)
  ASSERT_EQ(run("dov simulate --hours 0.05 --seed 5 --binary --out sim.bin").code, 0);
  write("sim.yaml", "line: sim.bin\n");
  const CmdResult s = run("dov process sim.yaml -q --json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_NEAR(nlohmann::json::parse(s.out)["rms_arcsec"]["smoothed"]["xi"].get<double>(),
              nlohmann::json::parse(a.out)["rms_arcsec"]["smoothed"]["xi"].get<double>(), 1e-9);
  // refused: the binary line to standard output, over its input
  EXPECT_NE(run("dov simulate --hours 0.01 --binary --out -").code, 0);
  // --binary without --out: dov-line.bin, not binary bytes in dov-line.csv (trial)
  ASSERT_EQ(run("dov simulate --hours 0.01 --binary").code, 0);
  EXPECT_EQ(slurp(dir_ / "dov-line.bin").substr(0, 8), "MRDN-DOV");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "dov-line.csv"));
  EXPECT_NE(run("dov convert line.csv line.csv").code, 0);
  EXPECT_EQ(slurp(dir_ / "line.csv").substr(0, 20), "# meridian dov line:");
  // a convert that fails (a bad CSV) leaves no output
  std::string bad = slurp(dir_ / "line.csv");
  bad.replace(bad.rfind("\n", bad.size() - 2) + 1, 3, "xyz");
  write("bad.csv", bad);
  const CmdResult f = run("dov convert bad.csv bad.bin");
  EXPECT_EQ(f.code, 1);
  EXPECT_NE(f.err.find("bad.csv:"), std::string::npos) << f.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "bad.bin"));
}

TEST_F(DovCli, BinaryLineConvertsBackToTheSameCsv) {
  // CSV → binary → CSV gives the same rows (17 digits read back to the same doubles), and
  // the comment says where it came from; "-" writes it to standard output.
  ASSERT_EQ(run("dov simulate --hours 0.05 --seed 6 --out line.csv").code, 0);
  ASSERT_EQ(run("dov convert line.csv line.bin").code, 0);
  const CmdResult c = run("dov convert line.bin back.csv");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_NE(c.err.find("back.csv: 181 samples, model values, truth"), std::string::npos) << c.err;
  const auto rows = [](const std::string& text) {
    std::string out;
    std::size_t at = 0;
    while (at < text.size()) {
      const std::size_t end = text.find('\n', at);
      const std::string line = text.substr(at, end - at);
      if (line.rfind("#", 0) != 0) out += line + "\n";
      at = end == std::string::npos ? text.size() : end + 1;
    }
    return out;
  };
  const std::string original = slurp(dir_ / "line.csv"), back = slurp(dir_ / "back.csv");
  EXPECT_EQ(rows(back), rows(original));
  EXPECT_NE(back.find("# Converted from line.bin"), std::string::npos);
  const CmdResult out = run("dov convert line.bin -");
  ASSERT_EQ(out.code, 0) << out.err;
  EXPECT_EQ(rows(out.out), rows(original));
  // a line without model columns stays without them
  ASSERT_EQ(run("dov simulate --hours 0.01 --out full.csv").code, 0);
  std::string text = slurp(dir_ / "full.csv"), stripped;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    std::string line = text.substr(at, end - at);
    if (line.rfind("#", 0) != 0) {  // drop fields 24 and 25 (model_eta/xi_arcsec)
      std::size_t a = 0;
      for (int k = 0; k < 23; ++k) a = line.find(',', a) + 1;
      const std::size_t b = line.find(',', line.find(',', a) + 1);
      line.erase(a - 1, b == std::string::npos ? std::string::npos : b - a + 1);
    }
    stripped += line + "\n";
    at = end == std::string::npos ? text.size() : end + 1;
  }
  write("nomodel.csv", stripped);
  ASSERT_EQ(run("dov convert nomodel.csv nomodel.bin").code, 0);
  const CmdResult n = run("dov convert nomodel.bin nomodel-back.csv");
  ASSERT_EQ(n.code, 0) << n.err;
  EXPECT_NE(n.err.find("no model values"), std::string::npos) << n.err;
  EXPECT_EQ(rows(slurp(dir_ / "nomodel-back.csv")), rows(stripped));
  EXPECT_EQ(slurp(dir_ / "nomodel-back.csv").find("model_eta"), std::string::npos);
}

TEST_F(DovCli, SimulateOptionErrorsInTheOptionsTerms) {
  // user-trial findings: CLI11's range message, radians and internal member names
  const CmdResult r = run("dov simulate --rate-hz 0 --out x.csv");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--rate-hz must be > 0 (samples per second), is 0"), std::string::npos)
      << r.err;
  const CmdResult l = run("dov simulate --latitude 95 --hours 0.01 --out x.csv");
  EXPECT_EQ(l.code, 1);
  EXPECT_NE(l.err.find("--latitude must be strictly between -89° and 89°, is 95°"), std::string::npos) << l.err;
  const CmdResult t = run("dov simulate --latitude 79 --heading 0 --speed-m-s 50 --hours 100 --out x.csv");
  EXPECT_EQ(t.code, 1);
  EXPECT_NE(t.err.find("the track leaves ±89° of latitude within --hours 100"), std::string::npos)
      << t.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.csv"));
}

TEST_F(DovCli, TruncatedBinaryLineNamesTheSample) {
  ASSERT_EQ(run("dov simulate --hours 0.05 --seed 5 --binary --out line.bin").code, 0);
  const std::string full = slurp(dir_ / "line.bin");
  write("cut.bin", full.substr(0, 32 + 100 * 216 + 17));
  write("cut.yaml", "line: cut.bin\n");
  const CmdResult r = run("dov process cut.yaml -q -o profile.csv");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("cut.bin"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sample 100"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "profile.csv"));  // nothing half-written
  // a time reversal in a binary line: the workflow's error, with the sample index
  std::string rev = full;
  const double t = -5.0;
  std::memcpy(rev.data() + 32 + 60 * 216, &t, 8);  // time_s of sample 60 (little-endian host)
  write("rev.bin", rev);
  write("rev.yaml", "line: rev.bin\n");
  const CmdResult v = run("dov process rev.yaml -q");
  EXPECT_EQ(v.code, 1);
  EXPECT_NE(v.err.find("rev.bin: sample 60: time_s"), std::string::npos) << v.err;
}
