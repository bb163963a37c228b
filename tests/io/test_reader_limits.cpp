// Reader hardening (issue 35): model constants within Meridian's terrestrial ranges, repeated
// header keys refused, bounded lines (1 MiB), paths that are no file, non-physical truth rows
// and maglev currents: each error names the file, the line and the field.

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/io/gravity_egm.hpp"
#include "meridian/io/gravity_geoid_grid.hpp"
#include "meridian/io/gravity_icgem.hpp"
#include "meridian/io/gyro_files.hpp"
#include "meridian/io/gyro_writers.hpp"
#include "meridian/io/maglev_files.hpp"
#include "meridian/io/nav_files.hpp"
#include "meridian/io/nmea.hpp"
#include "meridian/io/record_reader.hpp"

using namespace meridian;
namespace fs = std::filesystem;

namespace {

class IoReaderLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("meridian_limits_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  // `text` with the line starting with `key` replaced by `line` (all of them).
  static std::string with_line(const std::string& text, const std::string& key, const std::string& line) {
    std::istringstream in(text);
    std::string out, l;
    while (std::getline(in, l)) out += (l.rfind(key, 0) == 0 ? line : l) + "\n";
    return out;
  }
  fs::path dir_;
};

// The error `f` throws, of class E, contains `what`.
template <class E>
void expect_error(const std::function<void()>& f, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error, expected: " << what;
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception: " << e.what() << " (expected: " << what << ")";
  }
}

const gravity::GravityModelData& small_model() {
  static const gravity::GravityModelData m = gravity::make_synthetic_model({4, 1, 1e-5});
  return m;
}

}  // namespace

TEST_F(IoReaderLimits, IcgemModelConstantsOutsideTheTerrestrialRanges) {
  const std::string gfc = io::format_icgem(small_model());
  const auto good = write("m.gfc", gfc);
  EXPECT_NO_THROW(io::read_icgem_file(good));
  const auto gm = write("gm.gfc", with_line(gfc, "earth_gravity_constant", "earth_gravity_constant 1e308"));
  expect_error<ParseError>([&] { io::read_icgem_file(gm); },
                           "gm.gfc:6: earth_gravity_constant: earth_gravity_constant = 1e+308 m^3/s^2 is not the GM "
                           "of a terrestrial model (Meridian accepts 3.5e+14 to 4.5e+14 m^3/s^2");
  const auto km = write("km.gfc", with_line(gfc, "radius", "radius 6378.137"));
  expect_error<ParseError>([&] { io::read_icgem_file(km); },
                           "km.gfc:7: radius: radius = 6378.137 is a radius in kilometres: the file must give metres "
                           "(6378137 m)");
  const auto one = write("one.gfc", with_line(gfc, "radius", "radius 1"));
  expect_error<ParseError>([&] { io::read_icgem_file(one); }, "one.gfc:7: radius: radius = 1 m is not the radius");
}

TEST_F(IoReaderLimits, IcgemRepeatedHeaderKeyNamesBothLines) {
  const std::string gfc = io::format_icgem(small_model());
  const auto twice = write("twice.gfc", with_line(gfc, "radius", "radius 6378137\nradius 6378000"));
  expect_error<ParseError>([&] { io::read_icgem_file(twice); },
                           "twice.gfc:8: radius: radius is given twice in the header, on lines 7 and 8");
  const auto deg = write("deg.gfc", with_line(gfc, "max_degree", "max_degree 4\nMAX_DEGREE 4"));
  expect_error<ParseError>([&] { io::read_icgem_file(deg); }, "max_degree is given twice in the header, on lines 8 and 9");
}

TEST_F(IoReaderLimits, EgmModelConstantsOutsideTheTerrestrialRanges) {
  io::write_egm_files(small_model(), dir_ / "m");
  const std::string egm = slurp(dir_ / "m.egm"), cof = slurp(dir_ / "m.egm.cof");
  EXPECT_NO_THROW(io::read_egm_file(dir_ / "m.egm"));
  auto variant = [&](const std::string& name, const std::string& key, const std::string& line) {
    write(name + ".egm.cof", cof);
    return write(name + ".egm", with_line(egm, key, line));
  };
  const auto r1 = variant("r1", "ReferenceRadius", "ReferenceRadius 1");
  expect_error<ParseError>([&] { io::read_egm_file(r1); },
                           "r1.egm:8: ReferenceRadius: ReferenceRadius = 1 m is not the radius of a terrestrial model "
                           "(Meridian accepts 6e+06 to 6.6e+06 m");
  const auto km = variant("km", "ModelRadius", "ModelRadius 6378.137");
  expect_error<ParseError>([&] { io::read_egm_file(km); }, "km.egm:5: ModelRadius: ModelRadius = 6378.137 is a radius in kilometres");
  const auto gm = variant("gm", "ReferenceMass", "ReferenceMass 1e308");
  expect_error<ParseError>([&] { io::read_egm_file(gm); }, "gm.egm:9: ReferenceMass: ReferenceMass = 1e+308 m^3/s^2 is not the GM");
  const auto mm = variant("mm", "ModelMass", "ModelMass 4.9e12");  // the Moon's
  expect_error<ParseError>([&] { io::read_egm_file(mm); }, "mm.egm:6: ModelMass: ModelMass = 4900000000000 m^3/s^2");
  const auto f = variant("f", "Flattening", "Flattening 0.3");
  expect_error<ParseError>([&] { io::read_egm_file(f); },
                           "f.egm:10: Flattening: Flattening = 0.3 is not the flattening of a terrestrial model "
                           "(Meridian accepts 0 to 0.01");
  const auto nf = variant("nf", "Flattening", "Flattening -0.001");
  expect_error<ParseError>([&] { io::read_egm_file(nf); }, "nf.egm:10: Flattening:");
}

TEST_F(IoReaderLimits, EgmRepeatedKeyNamesBothLines) {
  io::write_egm_files(small_model(), dir_ / "m");
  const std::string egm = slurp(dir_ / "m.egm");
  write("t.egm.cof", slurp(dir_ / "m.egm.cof"));
  const auto t = write("t.egm", with_line(egm, "ModelMass", "ModelMass 398600441500000\nModelMass 398600441800000"));
  expect_error<ParseError>([&] { io::read_egm_file(t); }, "t.egm:7: ModelMass: ModelMass is given twice, on lines 6 and 7");
}

TEST_F(IoReaderLimits, PgmRepeatedOffsetOrScaleNamesBothLines) {
  const std::string raster = "4 3\n65535\n" + std::string(24, '\0');
  const auto ok = write("ok.pgm", "P5\n# Offset 0\n# Scale 0.001\n" + raster);
  EXPECT_NO_THROW(io::read_geoid_grid(ok));
  const auto o = write("o.pgm", "P5\n# Offset 0\n# Scale 0.001\n# Offset 5\n" + raster);
  expect_error<ParseError>([&] { io::read_geoid_grid(o); },
                           "o.pgm:4: Offset: # Offset is given twice in the header, on lines 2 and 4");
  const auto s = write("s.pgm", "P5\n# Scale 0.001\n# Offset 0\n# Scale 0.002\n" + raster);
  expect_error<ParseError>([&] { io::read_geoid_grid(s); }, "s.pgm:4: Scale: # Scale is given twice in the header, on lines 2 and 4");
}

TEST_F(IoReaderLimits, PathsThatAreNoFileAreRefusedAsIoErrors) {
  fs::create_directories(dir_ / "grid.gtx");
  fs::create_directories(dir_ / "plain");
  expect_error<IoError>([&] { io::read_geoid_grid(dir_ / "grid.gtx"); }, "grid.gtx: is a directory, not a file that can be read");
  expect_error<IoError>([&] { io::read_geoid_grid(dir_ / "plain"); }, "plain: is a directory");
  expect_error<IoError>([&] { io::read_icgem_file("/dev/zero"); }, "/dev/zero: is a character device, not a file that can be read");
  expect_error<IoError>([&] { io::read_egm_file("/dev/zero"); }, "/dev/zero: is a character device");
  expect_error<IoError>([&] { io::read_geoid_grid("/dev/zero.gtx"); }, "cannot open");  // no such file: the old message
  expect_error<IoError>([&] { io::nmea::read_file("/dev/zero", {}); }, "/dev/zero: is a character device");
  expect_error<IoError>([&] { io::read_nav_truth_file("/dev/zero"); }, "/dev/zero: is a character device");
  expect_error<IoError>([&] { io::read_maglev_series_file("/dev/zero"); }, "/dev/zero: is a character device");
  expect_error<IoError>([&] { io::read_maglev_series_file(dir_.string()); }, "is a directory");
}

TEST_F(IoReaderLimits, RecordReaderLinesAreBoundedAndReadExactlyAcrossItsBuffer) {
  // Lines around the reader's 16 KiB buffer and at the 1 MiB limit come back whole.
  std::string text = "a\n";
  const std::size_t lengths[] = {16382, 16383, 16384, 16385, 40000, std::size_t{1} << 20, 0, 7};
  for (std::size_t n : lengths) text += std::string(n, 'x') + "\n";
  text += "last-without-line-end";
  for (const bool crlf : {false, true}) {
    std::string t = text;
    if (crlf)
      for (std::size_t p = t.find('\n'); p != std::string::npos; p = t.find('\n', p + 2)) t.insert(p, "\r");
    std::istringstream in(t);
    io::RecordReader rr(in, "lines.txt", {io::Delimiter::Comma, io::HeaderMode::Absent});
    io::RecordChunk chunk;
    std::vector<std::size_t> got;
    while (rr.next(chunk, 3))
      for (std::size_t i = 0; i < chunk.size(); ++i) got.push_back(chunk[i].field(0).size());
    const std::vector<std::size_t> want = {1, 16382, 16383, 16384, 16385, 40000, std::size_t{1} << 20, 7, 21};
    EXPECT_EQ(got, want);
    EXPECT_EQ(rr.lines_read(), 10);
    EXPECT_EQ(rr.bytes_read(), t.size());
  }
  {
    std::istringstream in(std::string((std::size_t{1} << 20) + 1, 'x'));
    io::RecordReader rr(in, "one.csv");
    io::RecordChunk chunk;
    expect_error<ParseError>([&] { rr.next(chunk, 10); }, "one.csv:1: line 1 is longer than 1 MiB: not a text file?");
  }
  {
    std::istringstream in("time,current\n1,2\n" + std::string(3 << 20, '\0'));
    io::RecordReader rr(in, "zero.csv");
    io::RecordChunk chunk;
    expect_error<ParseError>([&] { while (rr.next(chunk, 1)) {} }, "zero.csv:3: line 3 is longer than 1 MiB");
  }
}

TEST_F(IoReaderLimits, NmeaEndsOnALineLongerThanOneMebibyte) {
  std::istringstream in("$GPGGA,1\n" + std::string(3 << 20, '\0'));
  expect_error<ParseError>([&] { io::nmea::read(in, "<stdin>", {}, {}); },
                           "<stdin>:2: line 2 is longer than 1 MiB: not a text file?");
  // Long lines below the limit stay a counted problem, not an error.
  std::istringstream ok("$GPGGA,1\n" + std::string(100000, 'x') + "\n");
  const auto s = io::nmea::read(ok, "<stdin>", {}, {});
  EXPECT_EQ(s.lines, 2);
  EXPECT_GE(s.malformed, 1);
  ASSERT_FALSE(s.malformed_lines.empty());
  EXPECT_EQ(s.malformed_lines.back().first, 2);
}

TEST_F(IoReaderLimits, LongLinesInModelFilesAreRefused) {
  const std::string gfc = io::format_icgem(small_model());
  const auto l = write("l.gfc", gfc.substr(0, gfc.find('\n') + 1) + std::string((1 << 20) + 1, 'y') + "\n");
  expect_error<ParseError>([&] { io::read_icgem_file(l); }, "l.gfc:2: line 2 is longer than 1 MiB");
  io::write_egm_files(small_model(), dir_ / "m");
  write("e.egm.cof", slurp(dir_ / "m.egm.cof"));
  const auto e = write("e.egm", "EGMF-1\n" + std::string((1 << 20) + 1, 'y'));
  expect_error<ParseError>([&] { io::read_egm_file(e); }, "e.egm:2: line 2 is longer than 1 MiB");
}

TEST_F(IoReaderLimits, CampaignMaxDegreeMustNotBeNegative) {
  auto truth = gyro::example_campaign_truth();
  const auto sim = gyro::simulate_campaign(truth, 5);
  const std::string yaml = io::campaign_file_yaml(sim.input);
  const auto ok = write("ok.yaml", yaml + "gravity_model: {model: m.egm, max_degree: 0}\n");
  EXPECT_NO_THROW(io::read_campaign_file(ok));
  const auto bad = write("c.yaml", yaml + "gravity_model: {model: m.egm, max_degree: -5}\n");
  expect_error<InputError>([&] { io::read_campaign_file(bad); }, "max_degree must be >= 0");
  expect_error<InputError>([&] { io::read_campaign_file(bad); }, "c.yaml:");
}

TEST_F(IoReaderLimits, NavTruthOfNoShipIsRefusedAtItsLine) {
  std::istringstream plane("time_s,x_m,y_m\n0,0,0\n10,1e308,5\n");
  expect_error<InputError>([&] { io::read_nav_truth(plane, "truth.csv"); },
                           "truth.csv:3: x_m: true coordinate 1e+308 m is beyond ±1e+08 m: not a position");
  std::istringstream east("time_s,x_m,y_m\n0,0,-2e8\n");
  expect_error<InputError>([&] { io::read_nav_truth(east, "truth.csv"); }, "truth.csv:2: y_m:");
  std::istringstream geo("time_s,lat_deg,lon_deg\n0,10,20\n5,10,1e308\n");
  expect_error<InputError>([&] { io::read_nav_truth(geo, "geo.csv"); }, "geo.csv:3: lon_deg: true longitude");
  std::istringstream fine("time_s,x_m,y_m\n0,0,0\n10,99999999,-5\n");
  EXPECT_EQ(io::read_nav_truth(fine, "truth.csv").records.size(), 2u);
}

TEST_F(IoReaderLimits, MaglevCurrentBeyondAnyGyroNamesFileAndLine) {
  std::istringstream in("time [s],current [A]\n0,0.01\n1,4e9\n");
  expect_error<InputError>([&] { io::read_maglev_series(in, "d-1.csv"); },
                           "d-1.csv:3: current: current 4e+09 A is beyond ±1000 A: not a gyro's current");
  std::istringstream ma("time [s],current [mA]\n0,10\n1,-4e9\n");
  expect_error<InputError>([&] { io::read_maglev_series(ma, "ma.csv"); }, "ma.csv:3: current: current -4e+06 A");
  std::istringstream ok("time [s],current [A]\n0,0.01\n1,999\n");
  EXPECT_EQ(io::read_maglev_series(ok, "ok.csv").series.current_A.size(), 2u);
}
