// Reader hardening (issue 35) as a user meets it: the exit code and message of `meridian` for
// absurd model constants, repeated header keys, a directory or a device given as a file,
// endless input (/dev/zero), a non-physical truth row and an absurd maglev current.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "cli_fixture.hpp"

namespace {

using meridian_test::CmdResult;
class ReadersCli : public meridian_test::CliTest {
 protected:
  // `text` with every line starting with `key` replaced by `line`.
  static std::string with_line(const std::string& text, const std::string& key, const std::string& line) {
    return std::regex_replace(text, std::regex("(^|\n)" + key + "[^\n]*"), "$1" + line);
  }
};

}  // namespace

TEST_F(ReadersCli, AbsurdModelConstantsExitOneNamingFileLineAndField) {
  ASSERT_EQ(run("gravity synth-model --degree 4 --seed 1 --out m").code, 0);
  const std::string gfc = slurp(dir_ / "m.gfc"), egm = slurp(dir_ / "m.egm");
  write("gm.gfc", with_line(gfc, "earth_gravity_constant", "earth_gravity_constant 1e308"));
  CmdResult r = run("gravity point --model gm.gfc 10 20");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("gm.gfc:6: earth_gravity_constant: earth_gravity_constant = 1e+308 m^3/s^2 is not the GM of a "
                       "terrestrial model"),
            std::string::npos)
      << r.err;
  write("km.gfc", with_line(gfc, "radius", "radius 6378.137"));
  r = run("gravity point --model km.gfc 10 20");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("km.gfc:7: radius: radius = 6378.137 is a radius in kilometres"), std::string::npos) << r.err;
  std::filesystem::copy_file(dir_ / "m.egm.cof", dir_ / "r1.egm.cof");
  write("r1.egm", with_line(egm, "ReferenceRadius", "ReferenceRadius 1"));
  r = run("gravity point --model r1.egm 10 20");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("r1.egm:8: ReferenceRadius: ReferenceRadius = 1 m is not the radius"), std::string::npos) << r.err;
  write("twice.gfc", with_line(gfc, "radius", "radius 6378137\nradius 6378000"));
  r = run("gravity point --model twice.gfc 10 20");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("twice.gfc:8: radius: radius is given twice in the header, on lines 7 and 8"), std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(ReadersCli, ADirectoryOrADeviceAsAGridOrModelExitsFour) {
  std::filesystem::create_directories(dir_ / "grid.gtx");
  std::filesystem::create_directories(dir_ / "tiles");
  CmdResult r = run("gravity geoid-grid --grid grid.gtx 10 20");
  EXPECT_EQ(r.code, 4);
  EXPECT_NE(r.err.find("grid.gtx: is a directory, not a file that can be read"), std::string::npos) << r.err;
  r = run("gravity geoid-grid --grid tiles 10 20");
  EXPECT_EQ(r.code, 4);
  EXPECT_NE(r.err.find("tiles: is a directory"), std::string::npos) << r.err;
  r = run("nav inspect /dev/zero");
  EXPECT_EQ(r.code, 4);
  EXPECT_NE(r.err.find("/dev/zero: is a character device, not a file that can be read"), std::string::npos) << r.err;
  r = run("maglev reduce /dev/zero /dev/zero --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 4);
  EXPECT_NE(r.err.find("/dev/zero: is a character device"), std::string::npos) << r.err;
}

TEST_F(ReadersCli, EndlessInputEndsQuicklyWithAnError) {
  const auto t0 = std::chrono::steady_clock::now();
  // stdin from /dev/zero: no line end ever comes (it used to spin until killed)
  CmdResult r = shell("timeout 60 " + std::string(MERIDIAN_EXE) + " nav inspect /dev/stdin < /dev/zero");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("/dev/stdin:1: line 1 is longer than 1 MiB: not a text file?"), std::string::npos) << r.err;
  r = shell("timeout 60 " + std::string(MERIDIAN_EXE) + " maglev reduce - --scale 8000 --latitude 35 -q < /dev/zero");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("line 1 is longer than 1 MiB"), std::string::npos) << r.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
}

TEST_F(ReadersCli, ANonPhysicalTruthRowOrMaglevCurrentNamesFileAndLine) {
  ASSERT_EQ(run("nav simulate --scenario C --seed 7 --out line --stations 2 --duration-s 600 --fixes-every-s 300").code, 0);
  std::string truth = slurp(dir_ / "line" / "truth.csv");
  const auto header = truth.find("time_s,x_m,y_m\n");
  ASSERT_NE(header, std::string::npos);
  // the first data row (line 4 of the file) becomes 0,1e308,0
  const auto row = header + std::string("time_s,x_m,y_m\n").size();
  truth.replace(row, truth.find('\n', row) - row, "0,1e308,0");
  write("line/truth.csv", truth);
  CmdResult r = run("nav process line/nav.yaml -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("line/truth.csv:4: x_m: true coordinate 1e+308 m is beyond"), std::string::npos) << r.err;

  write("d-1.csv", "time [s],current [A]\n0,0.01\n1,4e9\n2,0.01\n");
  write("d-2.csv", "time [s],current [A]\n0,-0.01\n1,-0.01\n2,-0.01\n");
  r = run("maglev reduce d-1.csv d-2.csv --scale 8000 --latitude 35 -q");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("d-1.csv:3: current: current 4e+09 A is beyond ±1000 A"), std::string::npos) << r.err;
}
