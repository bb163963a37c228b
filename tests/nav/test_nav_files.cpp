// Files of the navigation workflow (io/nav_files.hpp): every CSV reader's good and bad cases
// (messages name the file, line and column), the writers' round trip, the configuration's
// defaults and errors, the job reader (plane, projection, initial position, names), the true →
// grid velocity against GeographicLib's Geodesic and two grid forward() calls, and the NMEA
// adapter on a log written here (heading interpolated across 359° → 1°, thinning, truth,
// midnight).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include <GeographicLib/Geodesic.hpp>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/geodesy/grid.hpp"
#include "meridian/io/nav_files.hpp"
#include "meridian/io/source_map.hpp"
#include "meridian/nav/survey_line.hpp"

namespace {

namespace io = meridian::io;
namespace nav = meridian::nav;
namespace fs = std::filesystem;
using meridian::InputError;
using meridian::ParseError;

// A job read (io::read_nav_job) and put in its plane (nav::to_plane) as nav::process sees it,
// errors located as the runner locates them.
struct PlaneJob {
  io::NavJob job;
  nav::Input input;
  std::optional<meridian::geodesy::GridDefinition> projection;
  std::vector<std::string> notes;  ///< the reader's, then the plane's
};
PlaneJob plane_job(const io::NavConfig& c) {
  PlaneJob r;
  r.job = io::read_nav_job(c);
  nav::PlaneLine p = io::located(r.job.sources, [&] { return nav::to_plane(r.job.line); });
  r.input = std::move(p.input);
  r.projection = p.projection;
  r.notes = r.job.line.notes;
  r.notes.insert(r.notes.end(), p.notes.begin(), p.notes.end());
  return r;
}
constexpr double kDeg = std::numbers::pi / 180.0;

// The message of what `fn` throws as E ("" when it throws nothing).
template <class E = meridian::Error, class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

template <class R>
R read_text(R (*reader)(std::istream&, const std::string&), const std::string& text, const std::string& name) {
  std::istringstream in(text);
  return reader(in, name);
}

/// A scratch directory per test, removed afterwards.
class NavFilesDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("meridian_navfiles_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

// "$" + body + "*HH", the checksum computed here.
std::string nmea_line(const std::string& body) {
  unsigned x = 0;
  for (char c : body) x ^= static_cast<unsigned char>(c);
  const char* d = "0123456789ABCDEF";
  return "$" + body + "*" + d[x >> 4] + d[x & 15] + "\n";
}

}  // namespace

// --- DR -------------------------------------------------------------------------------------

TEST(NavDrReader, SpeedHeadingAnyOrderCaseCommentsDms) {
  const auto f = read_text(io::read_nav_dr,
                           "# a comment\n"
                           "Heading_Deg, TIME_S, speed_m_s\n"
                           "30, 0, 5\n"
                           "30d30m, 5, 5.5   # DMS\n"
                           "\n"
                           "359.5, 10, 0\n",
                           "dr.csv");
  ASSERT_EQ(f.records.size(), 3u);
  EXPECT_TRUE(f.speed_heading);
  EXPECT_EQ(f.lines, (std::vector<int>{3, 4, 6}));
  EXPECT_DOUBLE_EQ(f.records[1].time_s, 5.0);
  EXPECT_DOUBLE_EQ(f.records[1].a, 5.5);
  EXPECT_NEAR(f.records[1].b, 30.5 * kDeg, 1e-15);
  EXPECT_NEAR(f.records[2].b, 359.5 * kDeg, 1e-15);
}

TEST(NavDrReader, VelocityComponents) {
  const auto f = read_text(io::read_nav_dr, "time_s;v_north_m_s;v_east_m_s\n1;2.5;-1\n2;3;4\n", "v.csv");
  ASSERT_EQ(f.records.size(), 2u);
  EXPECT_FALSE(f.speed_heading);
  EXPECT_DOUBLE_EQ(f.records[0].a, 2.5);
  EXPECT_DOUBLE_EQ(f.records[0].b, -1.0);
}

TEST(NavDrReader, ErrorsNameFileLineColumn) {
  const auto msg = [](const std::string& text) {
    return error_of<InputError>([&] { read_text(io::read_nav_dr, text, "dr.csv"); });
  };
  EXPECT_HAS(msg("time_s,speed_m_s,heading_deg\n0,5,30\n5,x,30\n"), "dr.csv:3: speed_m_s:");
  EXPECT_HAS(msg("time_s,speed_m_s,heading_deg\n0,5,30\n5,5,north\n"), "dr.csv:3: heading_deg:");
  EXPECT_HAS(msg("time_s,speed_m_s,heading_deg\n0,-5,30\n"), "dr.csv:2: speed_m_s: speed -5 m/s is negative");
  // not strictly increasing: names the line and the earlier one
  const std::string t = msg("time_s,speed_m_s,heading_deg\n0,5,30\n5,5,30\n5,5,30\n");
  EXPECT_HAS(t, "dr.csv:4: time_s:");
  EXPECT_HAS(t, "line 3");
  EXPECT_HAS(msg("time_s,speed_m_s,heading_deg\n0,5,30\n-1,5,30\n"), "dr.csv:3: time_s:");
  EXPECT_HAS(msg("time_s,speed_m_s\n0,5\n"), "dr.csv:1");                    // no heading_deg
  EXPECT_HAS(msg("time_s,speed_m_s\n0,5\n"), "heading_deg");
  EXPECT_HAS(msg("time_s,heading_deg\n0,5\n"), "speed_m_s, heading_deg or v_north_m_s");
  EXPECT_HAS(msg("time_s,speed_m_s,heading_deg,v_north_m_s,v_east_m_s\n0,1,2,3,4\n"), "not both");
  EXPECT_HAS(msg("0,5,30\n"), "header line");
  EXPECT_HAS(msg("time_s,speed_m_s,heading_deg\n0,5\n"), "dr.csv:2");        // short line
  // a value beyond the header's columns (was ignored); empty trailing fields are fine
  EXPECT_HAS(msg("time_s,speed_m_s,heading_deg\n0,5,30\n5,5,30,7\n"),
             "dr.csv:3: 4 fields, but the header (line 1) names 3 columns: \"7\" in field 4");
  EXPECT_EQ(msg("time_s,speed_m_s,heading_deg\n0,5,30,,\n5,5,30\n"), "");
  // DMS with spaces in a comma-separated field (docs/file-formats.md's example); no quoting
  EXPECT_NEAR(read_text(io::read_nav_dr, "time_s,speed_m_s,heading_deg\n5,5.01,60 06 30\n", "dr.csv").records[0].b,
              (60.0 + 6.0 / 60.0 + 30.0 / 3600.0) * kDeg, 1e-15);
  EXPECT_HAS(error_of<meridian::IoError>([] { io::read_nav_dr_file("/nonexistent/dr.csv"); }),
             "/nonexistent/dr.csv");
}

// --- stations ---------------------------------------------------------------------------------

TEST(NavStationsReader, PlaneAndGeographic) {
  const auto p = read_text(io::read_nav_stations, "name,x_m,y_m\nA,100,-200\nB,0.5,1e3\n", "s.csv");
  ASSERT_EQ(p.names.size(), 2u);
  EXPECT_EQ(p.names[1], "B");
  EXPECT_FALSE(p.positions[0].geographic);
  EXPECT_DOUBLE_EQ(p.positions[0].y_east_m, -200.0);
  const auto g = read_text(io::read_nav_stations, "lon_deg,name,lat_deg\n114:30:00,Hill,30d15m\n", "g.csv");
  ASSERT_EQ(g.names.size(), 1u);
  EXPECT_TRUE(g.positions[0].geographic);
  EXPECT_NEAR(g.positions[0].lat_rad, 30.25 * kDeg, 1e-15);
  EXPECT_NEAR(g.positions[0].lon_rad, 114.5 * kDeg, 1e-15);
}

TEST(NavStationsReader, Errors) {
  const auto msg = [](const std::string& text) {
    return error_of<InputError>([&] { read_text(io::read_nav_stations, text, "s.csv"); });
  };
  const std::string dup = msg("name,x_m,y_m\nA,0,0\nB,1,1\nA,2,2\n");
  EXPECT_HAS(dup, "s.csv:4: name:");
  EXPECT_HAS(dup, "line 2");
  EXPECT_HAS(msg("name,x_m,y_m,lat_deg,lon_deg\nA,0,0,1,1\n"), "not both");
  EXPECT_HAS(msg("name,lat_deg,lon_deg\nA,91,0\n"), "s.csv:2: lat_deg:");
  EXPECT_HAS(msg("name,x_m,y_m\n,0,0\n"), "s.csv:2: name:");
  EXPECT_HAS(msg("name,x_m\nA,0\n"), "y_m");
}

// --- LOPs -------------------------------------------------------------------------------------

TEST(NavLopsReader, TypesStationsChains) {
  const auto f = read_text(io::read_nav_lops,
                           "time_s,type,station,station2,value,sigma_m,chain\n"
                           "5,range,A,,1234.5,50,\n"
                           "10,RANGE_DIFFERENCE,A,B,-300,20,X\n"
                           "15,time_difference,B,A,12.5,30,X\n",
                           "lops.csv");
  ASSERT_EQ(f.records.size(), 3u);
  EXPECT_EQ(f.records[0].kind, io::NavLopKind::Range);
  EXPECT_TRUE(f.records[0].chain.empty());
  EXPECT_EQ(f.records[1].kind, io::NavLopKind::RangeDifference);
  EXPECT_EQ(f.records[1].station2, "B");
  EXPECT_EQ(f.records[2].kind, io::NavLopKind::TimeDifference);
  EXPECT_DOUBLE_EQ(f.records[2].value, 12.5);  // µs, converted by the job reader
  EXPECT_EQ(f.records[2].chain, "X");
  EXPECT_EQ(f.lines, (std::vector<int>{2, 3, 4}));
  // no chain and no station2 columns: ranges only
  const auto r = read_text(io::read_nav_lops, "time_s,type,station,value,sigma_m\n1,range,A,10,5\n", "r.csv");
  EXPECT_EQ(r.records.size(), 1u);
}

TEST(NavLopsReader, ErrorsNameFileLineColumn) {
  const std::string h = "time_s,type,station,station2,value,sigma_m\n";
  const auto msg = [&](const std::string& body) {
    return error_of<InputError>([&] { read_text(io::read_nav_lops, h + body, "lops.csv"); });
  };
  EXPECT_HAS(msg("5,range,A,,1,50\n5,bearing,A,,1,50\n"), "lops.csv:3: type: \"bearing\" is not a LOP type");
  EXPECT_HAS(msg("5,range,A,B,1,50\n"), "lops.csv:2: station2: a range has one station");
  EXPECT_HAS(msg("5,range_difference,A,,1,50\n"), "lops.csv:2: station2:");
  EXPECT_HAS(msg("5,range_difference,A,A,1,50\n"), "lops.csv:2: station2:");
  EXPECT_HAS(msg("5,range,A,,1,0\n"), "lops.csv:2: sigma_m: sigma_m must be > 0");
  EXPECT_HAS(msg("5,range,A,,1x,50\n"), "lops.csv:2: value:");
  EXPECT_HAS(msg("5,range,,,1,50\n"), "lops.csv:2: station:");
  // an exact duplicate names both lines
  const std::string d = msg("5,range,A,,1,50\n6,range,A,,1,50\n# comment\n5,range,A,,1,50\n");
  EXPECT_HAS(d, "lops.csv:5:");
  EXPECT_HAS(d, "lines 2 and 5");
  // the same time with another value is not a duplicate
  EXPECT_EQ(msg("5,range,A,,1,50\n5,range,A,,2,50\n"), "");
  EXPECT_HAS(error_of<InputError>([] {
               read_text(io::read_nav_lops, "time_s,type,station,value\n1,range,A,10\n", "l.csv");
             }),
             "sigma_m");
}

// --- fixes and truth ---------------------------------------------------------------------------

TEST(NavFixesReader, SigmaForms) {
  const auto a = read_text(io::read_nav_fixes, "time_s,x_m,y_m,sigma_m\n20,1,2,10\n10,3,4,5\n", "f.csv");
  ASSERT_EQ(a.records.size(), 2u);  // any time order
  EXPECT_DOUBLE_EQ(a.records[0].sigma_north_m, 10.0);
  EXPECT_DOUBLE_EQ(a.records[0].sigma_east_m, 10.0);
  const auto b = read_text(io::read_nav_fixes, "time_s,lat_deg,lon_deg,sigma_x_m,sigma_y_m\n1,30,114,3,4\n", "g.csv");
  EXPECT_TRUE(b.records[0].position.geographic);
  EXPECT_DOUBLE_EQ(b.records[0].sigma_north_m, 3.0);
  EXPECT_DOUBLE_EQ(b.records[0].sigma_east_m, 4.0);
}

TEST(NavFixesReader, Errors) {
  const auto msg = [](const std::string& text) {
    return error_of<InputError>([&] { read_text(io::read_nav_fixes, text, "f.csv"); });
  };
  EXPECT_HAS(msg("time_s,x_m,y_m\n1,2,3\n"), "f.csv:1");
  EXPECT_HAS(msg("time_s,x_m,y_m\n1,2,3\n"), "sigma_m or both sigma_x_m and sigma_y_m");
  EXPECT_HAS(msg("time_s,x_m,y_m,sigma_m,sigma_x_m\n1,2,3,4,5\n"), "not both");
  EXPECT_HAS(msg("time_s,x_m,y_m,sigma_m\n1,2,3,-4\n"), "f.csv:2: sigma_m:");
  const std::string d = msg("time_s,x_m,y_m,sigma_m\n1,2,3,4\n2,2,3,4\n1,2,3,4\n");
  EXPECT_HAS(d, "f.csv:4:");
  EXPECT_HAS(d, "lines 2 and 4");
}

TEST(NavTruthReader, GoodAndDuplicateTime) {
  const auto t = read_text(io::read_nav_truth, "time_s,x_m,y_m\n5,1,2\n0,3,4\n", "t.csv");
  ASSERT_EQ(t.records.size(), 2u);
  const std::string d = error_of<InputError>(
      [] { read_text(io::read_nav_truth, "time_s,x_m,y_m\n5,1,2\n5,3,4\n", "t.csv"); });
  EXPECT_HAS(d, "t.csv:3: time_s:");
  EXPECT_HAS(d, "line 2");
}

// --- writers ----------------------------------------------------------------------------------

TEST(NavWriters, RoundTripSeventeenDigits) {
  nav::Input in;
  for (int k = 0; k < 3; ++k)
    in.dr.push_back(nav::dr_from_speed_heading(5.0 * k, 5.0 + 0.1 * k, (60.0 + 150.0 * k) * kDeg, 0.02, 0.001));
  in.stations = {{"A", 1000.0 / 3.0, -2000.0 / 7.0}, {"B", 0.1, 0.2}};
  nav::Lop l;
  l.time_s = 5.0, l.station = 1, l.value_m = 1234.5678901234567, l.sigma_m = 50.0;
  in.lops.push_back(l);
  l.type = nav::LopType::RangeDifference, l.station = 0, l.station2 = 1, l.value_m = -1.0 / 3.0;
  in.lops.push_back(l);
  nav::Fix f;
  f.time_s = 10.0, f.x_north_m = 1.0 / 3.0, f.y_east_m = 2.0 / 3.0;
  f.covariance << 4.0, 0.0, 0.0, 9.0;
  in.fixes.push_back(f);
  in.truth = {{0.0, 1.0 / 7.0, 2.0 / 7.0}};

  const auto dr = read_text(io::read_nav_dr, io::nav_dr_csv(in.dr, "Simulated: x\ny"), "dr.csv");
  ASSERT_EQ(dr.records.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(dr.records[k].time_s, in.dr[k].time_s);
    EXPECT_NEAR(dr.records[k].a * std::cos(dr.records[k].b), in.dr[k].v_north_m_s, 1e-14);
    EXPECT_NEAR(dr.records[k].a * std::sin(dr.records[k].b), in.dr[k].v_east_m_s, 1e-14);
  }
  const auto st = read_text(io::read_nav_stations, io::nav_stations_csv(in.stations), "s.csv");
  EXPECT_EQ(st.positions[0].x_north_m, in.stations[0].x_north_m);
  EXPECT_EQ(st.positions[0].y_east_m, in.stations[0].y_east_m);
  const auto lo = read_text(io::read_nav_lops, io::nav_lops_csv(in), "l.csv");
  ASSERT_EQ(lo.records.size(), 2u);
  EXPECT_EQ(lo.records[0].station, "B");
  EXPECT_EQ(lo.records[0].value, in.lops[0].value_m);
  EXPECT_EQ(lo.records[1].kind, io::NavLopKind::RangeDifference);
  EXPECT_EQ(lo.records[1].station2, "B");
  EXPECT_EQ(lo.records[1].value, in.lops[1].value_m);
  const auto fx = read_text(io::read_nav_fixes, io::nav_fixes_csv(in.fixes), "f.csv");
  EXPECT_EQ(fx.records[0].position.x_north_m, f.x_north_m);
  EXPECT_EQ(fx.records[0].sigma_east_m, 3.0);
  const auto tr = read_text(io::read_nav_truth, io::nav_truth_csv(in.truth), "t.csv");
  EXPECT_EQ(tr.records[0].position.y_east_m, in.truth[0].y_east_m);
  // the settings comment is one line
  const std::string csv = io::nav_dr_csv(in.dr, "Simulated: x\ny");
  EXPECT_HAS(csv, "# Simulated: x y\n");
}

// What `nav simulate` writes reads back as the same Input: a line built here (the simulator's
// shape: plane coordinates, no projection, σ of speed and heading per file, the initial
// position off the truth as in scenario D).
TEST_F(NavFilesDir, SimulationFilesReadBackAsTheSameInput) {
  nav::SimulationOptions so;
  so.sigma_speed_m_s = 0.02, so.sigma_heading_rad = 0.001;
  nav::SimulatedLine line;
  nav::Input& in = line.input;
  for (int k = 0; k <= 10; ++k) {
    const double speed = 5.0 + 0.5 + 0.1 * std::sin(std::numbers::pi * k / 6.0);
    in.dr.push_back(nav::dr_from_speed_heading(5.0 * k, speed, 60.0 * kDeg, so.sigma_speed_m_s, so.sigma_heading_rad));
    in.truth.push_back({5.0 * k, 2.5 * k, 4.33 * k});
  }
  in.stations = {{"S1", 5000.0, -3000.0}, {"S2", -4000.0, 2000.0}, {"S3", 8000.0, 9000.0}};
  for (int k = 1; k <= 10; ++k) {
    nav::Lop l;
    l.time_s = 5.0 * k, l.station = static_cast<std::size_t>(k % 3), l.value_m = 5000.0 + 17.0 * k + 1.0 / 3.0;
    l.sigma_m = 50.0;
    in.lops.push_back(l);
  }
  nav::Fix f;
  f.time_s = 25.0, f.x_north_m = 12.5, f.y_east_m = 21.65;
  f.covariance = Eigen::Matrix2d::Identity() * 100.0;
  in.fixes.push_back(f);
  in.initial = {100.0, 0.0, 100.0};
  in.options.threshold_m = 100.0;
  line.settings = "Simulated: scenario D, seed 7";
  write("dr.csv", io::nav_dr_csv(in.dr, line.settings));
  write("stations.csv", io::nav_stations_csv(in.stations, line.settings));
  write("lops.csv", io::nav_lops_csv(in, line.settings));
  write("truth.csv", io::nav_truth_csv(in.truth, line.settings));
  write("fixes.csv", io::nav_fixes_csv(in.fixes, line.settings));
  const std::string yaml = io::nav_simulation_config(line, so);
  EXPECT_HAS(yaml, "# Simulated: scenario D, seed 7\n");
  nav::SimulatedLine bare = line;
  bare.settings = "scenario D, seed 7";
  EXPECT_HAS(io::nav_simulation_config(bare, so), "# Simulated: scenario D, seed 7\n");
  const PlaneJob r = plane_job(io::read_nav_config(write("nav.yaml", yaml)));
  EXPECT_FALSE(r.projection);
  ASSERT_EQ(r.input.dr.size(), in.dr.size());
  for (std::size_t k = 0; k < in.dr.size(); ++k) {
    EXPECT_EQ(r.input.dr[k].time_s, in.dr[k].time_s);
    EXPECT_NEAR(r.input.dr[k].v_north_m_s, in.dr[k].v_north_m_s, 1e-14);
    EXPECT_NEAR(r.input.dr[k].v_east_m_s, in.dr[k].v_east_m_s, 1e-14);
    EXPECT_NEAR((r.input.dr[k].covariance - in.dr[k].covariance).norm(), 0.0, 1e-18);
  }
  ASSERT_EQ(r.input.stations.size(), 3u);
  EXPECT_EQ(r.input.stations[2].name, "S3");
  EXPECT_EQ(r.input.stations[2].y_east_m, 9000.0);
  ASSERT_EQ(r.input.lops.size(), in.lops.size());
  for (std::size_t k = 0; k < in.lops.size(); ++k) {
    EXPECT_EQ(r.input.lops[k].station, in.lops[k].station);
    EXPECT_EQ(r.input.lops[k].value_m, in.lops[k].value_m);
    EXPECT_EQ(r.input.lops[k].time_s, in.lops[k].time_s);
  }
  ASSERT_EQ(r.input.fixes.size(), 1u);
  EXPECT_EQ(r.input.fixes[0].covariance, f.covariance);
  EXPECT_EQ(r.input.truth.size(), in.truth.size());
  EXPECT_EQ(r.input.truth[3].y_east_m, in.truth[3].y_east_m);
  EXPECT_EQ(r.input.initial.x_north_m, 100.0);  // the bad start, not the first fix
  EXPECT_EQ(r.input.initial.sigma_m, 100.0);
  EXPECT_EQ(r.input.options.threshold_m, in.options.threshold_m);
  EXPECT_EQ(r.input.options.bias_correlation_time_s, in.options.bias_correlation_time_s);
  for (const auto& n : r.notes) EXPECT_EQ(n.find("default"), std::string::npos) << n;  // every σ stated
}

// --- configuration ----------------------------------------------------------------------------

TEST_F(NavFilesDir, ConfigDefaultsAndEveryOption) {
  const std::string p = write("nav.yaml", "dr: dr.csv\n");
  const io::NavConfig c = io::read_nav_config(p);
  EXPECT_EQ(c.dr_path, (dir_ / "dr.csv").string());
  EXPECT_FALSE(c.initial);
  EXPECT_FALSE(c.projection);
  EXPECT_FALSE(c.sigma_speed_m_s);
  const nav::Options d;
  EXPECT_EQ(c.options.threshold_m, d.threshold_m);
  EXPECT_EQ(c.options.rejection, nav::Rejection::Threshold);

  const std::string q = write("all.yaml",
                              "dr: sub/dr.csv\nstations: s.csv\nlops: l.csv\nfixes: f.csv\ntruth: t.csv\n"
                              "initial: {lat: 30d, lon: \"114:30\", sigma_m: 20}\n"
                              "projection: {type: utm, zone: 50, north: true}\n"
                              "sigma_speed_m_s: 0.1\nsigma_heading_deg: 0.5\nsigma_velocity_m_s: 0.2\n"
                              "chains:\n  - {name: X, estimate_offset: true, sigma_offset_prior_m: 500,\n"
                              "     propagation_speed_m_s: 299700000}\n"
                              "rejection: w-test\nthreshold_m: 150\nalpha: 0.01\nsegment_s: 120\n"
                              "backward_window_s: 30\nfix_tolerance_m: 100\nmax_reduction_s: 3\n"
                              "max_dr_gap_s: 20\nbias_model: gauss-markov\nbias_sigma_m_s: 0.5\n"
                              "bias_random_walk_m_s_per_sqrt_s: 0.001\nbias_correlation_time_s: 300\n"
                              "statistics_bin_s: 30\nbias_start_s: 90\nsequential_sigma_velocity_m_s: 0.25\n"
                              "warn_gap_s: 120\n");
  const io::NavConfig a = io::read_nav_config(q);
  EXPECT_EQ(a.dr_path, (dir_ / "sub" / "dr.csv").string());
  ASSERT_TRUE(a.initial);
  EXPECT_TRUE(a.initial->geographic);
  EXPECT_NEAR(a.initial->lon_rad, 114.5 * kDeg, 1e-15);
  EXPECT_EQ(*a.initial_sigma_m, 20.0);
  ASSERT_TRUE(a.projection);
  EXPECT_EQ(a.projection->definition.zone, 50);
  EXPECT_NEAR(*a.sigma_heading_rad, 0.5 * kDeg, 1e-15);
  ASSERT_EQ(a.chains.size(), 1u);
  EXPECT_TRUE(a.chains[0].chain.estimate_offset);
  EXPECT_FALSE(a.chains[0].chain.estimate_scale);
  EXPECT_EQ(a.chains[0].chain.sigma_offset_prior_m, 500.0);
  EXPECT_EQ(a.chains[0].propagation_speed_m_s, 299700000.0);
  const nav::Options& o = a.options;
  EXPECT_EQ(o.rejection, nav::Rejection::WTest);
  EXPECT_EQ(o.threshold_m, 150.0);
  EXPECT_EQ(o.alpha, 0.01);
  EXPECT_EQ(o.segment_s, 120.0);
  EXPECT_EQ(o.backward_window_s, 30.0);
  EXPECT_EQ(o.fix_tolerance_m, 100.0);
  EXPECT_EQ(o.max_reduction_s, 3.0);
  EXPECT_EQ(o.max_dr_gap_s, 20.0);
  EXPECT_EQ(o.bias_model, nav::BiasModel::GaussMarkov);
  EXPECT_EQ(o.bias_sigma_m_s, 0.5);
  EXPECT_EQ(o.bias_random_walk_m_s_per_sqrt_s, 0.001);
  EXPECT_EQ(o.bias_correlation_time_s, 300.0);
  EXPECT_EQ(o.statistics_bin_s, 30.0);
  EXPECT_EQ(o.bias_start_s, 90.0);
  EXPECT_EQ(o.sequential_sigma_velocity_m_s, 0.25);
  EXPECT_EQ(o.warn_gap_s, 120.0);
  // JSON too
  const io::NavConfig j = io::read_nav_config(write("nav.json", "{\"dr\": \"dr.csv\", \"threshold_m\": 80}"));
  EXPECT_EQ(j.options.threshold_m, 80.0);
}

TEST_F(NavFilesDir, ConfigErrorsNameFileLineKey) {
  const auto msg = [&](const std::string& text) {
    const std::string p = write("bad.yaml", text);
    return error_of<InputError>([&] { io::read_nav_config(p); });
  };
  EXPECT_HAS(msg("dr: dr.csv\nthreshhold_m: 5\n"), "bad.yaml:2");
  EXPECT_HAS(msg("dr: dr.csv\nthreshhold_m: 5\n"), "threshhold_m");
  EXPECT_HAS(msg("dr: dr.csv\nrejection: chi2\n"), "bad.yaml:2: rejection: \"chi2\" is not a rejection");
  EXPECT_HAS(msg("dr: dr.csv\nbias_model: white\n"), "bad.yaml:2: bias_model:");
  EXPECT_HAS(msg("dr: dr.csv\nalpha: 1.5\n"), "bad.yaml:2: alpha:");
  EXPECT_HAS(msg("dr: dr.csv\nthreshold_m: -1\n"), "bad.yaml:2: threshold_m:");
  EXPECT_HAS(msg("stations: s.csv\n"), "dr:");
  EXPECT_HAS(msg("dr: d.csv\nnmea: {heading: h.nmea}\n"), "bad.yaml:2: nmea: give dr: or nmea:");
  EXPECT_HAS(msg("dr: d.csv\nlops: l.csv\n"), "needs stations:");
  EXPECT_HAS(msg("dr: d.csv\ninitial: {x_m: 1, lat: 2}\n"), "bad.yaml:2: initial:");
  EXPECT_HAS(msg("dr: d.csv\ninitial: {x_m: 1}\n"), "y_m");
  EXPECT_HAS(msg("dr: d.csv\ninitial: {x_m: 1, y_m: 2, sigma_m: 0}\n"), "initial.sigma_m");
  EXPECT_HAS(msg("dr: d.csv\nprojection: {type: utm, zone: 61}\n"), "bad.yaml:2");
  EXPECT_HAS(msg("dr: d.csv\nprojection: {type: lambert}\n"), "is not a projection type");
  EXPECT_HAS(msg("dr: d.csv\nprojection: {type: utm, zone: 31, central_meridian: 3}\n"), "central_meridian");
  EXPECT_HAS(msg("dr: d.csv\nchains: [{name: X}, {name: X}]\n"), "already defined");
  EXPECT_HAS(msg("dr: d.csv\nchains: [{name: X, scale: true}]\n"), "scale");
  EXPECT_HAS(msg("nmea: {heading: h.nmea, speed_sentence: rmc}\n"), "is not a speed sentence");
  EXPECT_HAS(msg("nmea: {heading: h.nmea, positions: none, fix_interval_s: 120}\n"), "needs positions");
  EXPECT_HAS(msg("nmea: {heading: h.nmea}\nfixes: f.csv\n"), "positions: none");
}

TEST_F(NavFilesDir, SigmaKeysOfTheOtherDrKindAreErrors) {
  // Before, these were accepted and silently had no effect.
  write("sh.csv", "time_s,speed_m_s,heading_deg\n0,5,90\n5,5,90\n");
  write("v.csv", "time_s,v_north_m_s,v_east_m_s\n0,0,5\n5,0,5\n");
  const auto msg = [&](const std::string& text) {
    const std::string p = write("k.yaml", text);
    return error_of<InputError>([&] { plane_job(io::read_nav_config(p)); });
  };
  const std::string a = msg("dr: sh.csv\ninitial: {x_m: 0, y_m: 0}\nsigma_velocity_m_s: 0.1\n");
  EXPECT_HAS(a, "k.yaml:3: sigma_velocity_m_s: sigma_velocity_m_s does not apply here");
  EXPECT_HAS(a, "set sigma_speed_m_s and sigma_heading_deg");
  const std::string b = msg("dr: v.csv\ninitial: {x_m: 0, y_m: 0}\nsigma_speed_m_s: 0.1\n");
  EXPECT_HAS(b, "k.yaml:3: sigma_speed_m_s:");
  EXPECT_HAS(b, "set sigma_velocity_m_s");
  EXPECT_HAS(msg("dr: v.csv\ninitial: {x_m: 0, y_m: 0}\nsigma_heading_deg: 1\n"), "k.yaml:3: sigma_heading_deg:");
  EXPECT_EQ(msg("dr: v.csv\ninitial: {x_m: 0, y_m: 0}\nsigma_velocity_m_s: 0.1\n"), "");
}

// --- the job: plane, projection, names, initial position ----------------------------------------

TEST_F(NavFilesDir, PlaneJobResolvesNamesAndTimeDifferences) {
  write("dr.csv", "time_s,speed_m_s,heading_deg\n0,5,90\n5,5,90\n10,5,90\n");
  write("s.csv", "name,x_m,y_m\nA,1000,0\nB,0,1000\n");
  write("l.csv",
        "time_s,type,station,station2,value,sigma_m,chain\n"
        "5,range,A,,1000,50,\n"
        "10,time_difference,A,B,1,30,X\n"
        "10,time_difference,B,A,2,30,\n");
  const std::string p = write("nav.yaml",
                              "dr: dr.csv\nstations: s.csv\nlops: l.csv\ninitial: {x_m: 10, y_m: 20}\n"
                              "sigma_speed_m_s: 0.1\nsigma_heading_deg: 1\n"
                              "chains: [{name: X, propagation_speed_m_s: 3e8}]\n");
  const PlaneJob r = plane_job(io::read_nav_config(p));
  EXPECT_FALSE(r.projection);
  ASSERT_EQ(r.input.dr.size(), 3u);
  EXPECT_NEAR(r.input.dr[1].v_north_m_s, 0.0, 1e-15);
  EXPECT_NEAR(r.input.dr[1].v_east_m_s, 5.0, 1e-15);
  // σ: J diag(σv², σα²) Jᵀ at α = 90°: var north = (v σα)², var east = σv²
  EXPECT_NEAR(r.input.dr[1].covariance(0, 0), std::pow(5.0 * kDeg, 2), 1e-15);
  EXPECT_NEAR(r.input.dr[1].covariance(1, 1), 0.01, 1e-15);
  EXPECT_EQ(r.input.initial.x_north_m, 10.0);
  EXPECT_EQ(r.input.initial.sigma_m, nav::InitialPosition{}.sigma_m);
  ASSERT_EQ(r.input.lops.size(), 3u);
  EXPECT_EQ(r.input.lops[0].station, 0u);
  EXPECT_EQ(r.input.lops[0].chain, nav::Lop::kNoChain);
  EXPECT_EQ(r.input.lops[1].type, nav::LopType::RangeDifference);
  EXPECT_EQ(r.input.lops[1].station2, 1u);
  EXPECT_EQ(r.input.lops[1].chain, 0u);
  EXPECT_DOUBLE_EQ(r.input.lops[1].value_m, 300.0);              // 1 µs at 3e8 m/s
  EXPECT_DOUBLE_EQ(r.input.lops[2].value_m, 2e-6 * 299691162.0);  // the LORAN-C default
  EXPECT_EQ(r.input.lops[2].station, 1u);
  ASSERT_EQ(r.job.line.lops.size(), 3u);
  EXPECT_EQ(r.job.line.lops[2].source.line, 4);
  bool noted = false;
  for (const auto& n : r.notes) noted |= n.find("299691162") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST_F(NavFilesDir, JobErrorsNameTheLine) {
  write("dr.csv", "time_s,speed_m_s,heading_deg\n0,5,90\n5,5,90\n");
  write("s.csv", "name,x_m,y_m\nA,1000,0\n");
  const auto msg = [&](const std::string& lops, const std::string& extra = "") {
    write("l.csv", "time_s,type,station,station2,value,sigma_m,chain\n" + lops);
    const std::string p = write("nav.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\n" + extra);
    return error_of<InputError>([&] { plane_job(io::read_nav_config(p)); });
  };
  const std::string init = "initial: {x_m: 0, y_m: 0}\n";
  EXPECT_HAS(msg("5,range,A,,1,1,\n5,range,Z,,1,1,\n", init), "l.csv:3: station: unknown station \"Z\"");
  EXPECT_HAS(msg("5,range,A,,1,1,Q\n", init), "l.csv:2: chain: chain \"Q\" is not in the configuration");
  // no initial: and no fix: says to give initial
  const std::string i = msg("5,range,A,,1,1,\n");
  EXPECT_HAS(i, "nav.yaml");
  EXPECT_HAS(i, "give initial:");
  // a single DR sample
  write("dr1.csv", "time_s,speed_m_s,heading_deg\n0,5,90\n");
  const std::string p = write("one.yaml", "dr: dr1.csv\n" + init);
  EXPECT_HAS(error_of<InputError>([&] { plane_job(io::read_nav_config(p)); }), "at least 2");
}

TEST_F(NavFilesDir, InitialFromTheFirstFixAndMixedCoordinates) {
  write("dr.csv", "time_s,speed_m_s,heading_deg\n100,5,90\n105,5,90\n");
  write("f.csv", "time_s,x_m,y_m,sigma_x_m,sigma_y_m\n500,9,9,1,1\n103,50,60,3,4\n");
  const PlaneJob r = plane_job(io::read_nav_config(write("nav.yaml", "dr: dr.csv\nfixes: f.csv\n")));
  // the fix of line 3 (nav::process moves it by the DR to t = 100 s and does not use it again)
  ASSERT_TRUE(r.input.initial_fix.has_value());
  EXPECT_EQ(*r.input.initial_fix, 1u);
  EXPECT_EQ(r.job.line.fixes[1].source.line, 3);
  // a fix 6 s after the first epoch is too late
  write("f2.csv", "time_s,x_m,y_m,sigma_m\n106,1,1,1\n");
  const std::string late = error_of<InputError>(
      [&] { plane_job(io::read_nav_config(write("late.yaml", "dr: dr.csv\nfixes: f2.csv\n"))); });
  EXPECT_HAS(late, "give initial:");
  // plane fixes with a geographic initial position and no projection
  const std::string mixed = error_of<InputError>([&] {
    plane_job(io::read_nav_config(write("mix.yaml", "dr: dr.csv\nfixes: f.csv\ninitial: {lat: 30, lon: 114}\n")));
  });
  EXPECT_HAS(mixed, "give a projection");
  EXPECT_HAS(mixed, "f.csv");
}

TEST_F(NavFilesDir, DefaultProjectionAtTheFirstGeographicLongitude) {
  write("dr.csv", "time_s,speed_m_s,heading_deg\n0,5,0\n5,5,0\n");
  write("s.csv", "name,lat_deg,lon_deg\nA,45.1,7.6649\nB,45.2,7.7\n");
  write("l.csv", "time_s,type,station,station2,value,sigma_m\n5,range,A,,100,5\n");
  const PlaneJob r = plane_job(io::read_nav_config(
      write("nav.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\ninitial: {lat: 45, lon: 7.7, sigma_m: 10}\n")));
  ASSERT_TRUE(r.projection);
  // the initial position is the first geographic point: 7.7° (already on 0.1°)
  EXPECT_NEAR(r.projection->central_meridian_rad, 7.7 * kDeg, 1e-15);
  EXPECT_EQ(r.projection->scale_factor, 1.0);
  EXPECT_EQ(r.projection->false_easting_m, 0.0);
  EXPECT_EQ(r.projection->false_northing_m, 0.0);
  const auto ll = meridian::geodesy::TransverseMercatorGrid(*r.projection)
                      .reverse(r.input.stations[0].x_north_m, r.input.stations[0].y_east_m);
  EXPECT_NEAR(ll.lat_rad, 45.1 * kDeg, 1e-12);
  EXPECT_NEAR(ll.lon_rad, 7.6649 * kDeg, 1e-12);
  EXPECT_NEAR(r.input.initial.y_east_m, 0.0, 1e-6);  // on the central meridian
  bool noted = false;
  for (const auto& n : r.notes) noted |= n.find("central meridian 7.7") != std::string::npos;
  EXPECT_TRUE(noted);
  // without initial: the first station sets it: 7.6649 → 7.7
  write("f.csv", "time_s,lat_deg,lon_deg,sigma_m\n0,45,7.63,5\n");
  const PlaneJob s = plane_job(
      io::read_nav_config(write("n2.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\nfixes: f.csv\n")));
  EXPECT_NEAR(s.projection->central_meridian_rad, 7.7 * kDeg, 1e-15);
  write("s3.csv", "name,lat_deg,lon_deg\nA,45.1,7.64\n");
  const PlaneJob t = plane_job(
      io::read_nav_config(write("n3.yaml", "dr: dr.csv\nstations: s3.csv\nlops: l.csv\nfixes: f.csv\n")));
  EXPECT_NEAR(t.projection->central_meridian_rad, 7.6 * kDeg, 1e-15);
}

// The true → grid velocity: a ship at 45° N, 2.5° east of the central meridian of a transverse
// Mercator, steaming 5 m/s on a true heading of 30°. Independent value: GeographicLib's
// Geodesic moves the point 2.5 m back and forth along the true azimuth; two grid forward()
// calls give the grid displacement over that 5 m, whose bearing and length are the grid
// velocity (central: the chord's arc-to-chord and the change of k along it, 1e-8 over a 5 m
// one-sided step here, cancel to second order).
TEST_F(NavFilesDir, TrueHeadingBecomesGridAzimuthWithConvergenceAndScale) {
  const double lat0 = 45.0, lon0 = 9.5, alpha = 30.0, v = 5.0;
  write("dr.csv", "time_s,speed_m_s,heading_deg\n0,5,30\n1,5,30\n");
  write("vel.csv", "time_s,v_north_m_s,v_east_m_s\n0,4.330127018922193,2.5\n1,4.330127018922193,2.5\n");
  const std::string proj = "projection: {type: transverse-mercator, central_meridian: 7, scale_factor: 0.9996, "
                           "false_easting_m: 500000}\n";
  const PlaneJob r = plane_job(io::read_nav_config(
      write("nav.yaml", "dr: dr.csv\n" + proj + "initial: {lat: 45, lon: 9.5}\nsigma_heading_deg: 0\n")));
  const PlaneJob c = plane_job(
      io::read_nav_config(write("vel.yaml", "dr: vel.csv\n" + proj + "initial: {lat: 45, lon: 9.5}\n")));

  meridian::geodesy::GridDefinition g;
  g.system = meridian::geodesy::ZoneSystem::Custom;
  g.central_meridian_rad = 7.0 * kDeg, g.scale_factor = 0.9996, g.false_easting_m = 500000.0, g.false_northing_m = 0;
  const meridian::geodesy::TransverseMercatorGrid grid(g);
  const GeographicLib::Geodesic geod(g.ellipsoid.a_m, g.ellipsoid.f);
  double lat1 = 0, lon1 = 0, lat2 = 0, lon2 = 0;
  geod.Direct(lat0, lon0, alpha, -v / 2, lat1, lon1);
  geod.Direct(lat0, lon0, alpha, v / 2, lat2, lon2);
  const auto p0 = grid.forward(lat0 * kDeg, lon0 * kDeg);
  const auto p1 = grid.forward(lat1 * kDeg, lon1 * kDeg);
  const auto p2 = grid.forward(lat2 * kDeg, lon2 * kDeg);
  const double dx = p2.x_north_m - p1.x_north_m, dy = p2.y_east_m - p1.y_east_m;
  // the convergence here is well away from 0: the test discriminates the sign
  EXPECT_GT(p0.convergence_rad, 1.5 * kDeg);
  for (const PlaneJob* run : {&r, &c}) {
    const nav::DrSample& s = run->input.dr[0];
    EXPECT_NEAR(std::atan2(s.v_east_m_s, s.v_north_m_s), std::atan2(dy, dx), 1e-8);
    EXPECT_NEAR(std::hypot(s.v_north_m_s, s.v_east_m_s), std::hypot(dx, dy), 1e-8);
  }
  // and T = α − γ with the scale k, as grid.hpp states
  EXPECT_NEAR(std::atan2(dy, dx), alpha * kDeg - p0.convergence_rad, 1e-8);
  EXPECT_NEAR(std::hypot(dx, dy) / v, p0.scale, 1e-8);
}

// A range measured on the ground is a grid length times the line scale factor. Independent
// value: GeographicLib's Geodesic gives the ground distances from the ship (the initial
// position, a LOP at t = 0) to stations 60 km and 90 km away in UTM zone 32, 2.5° east of its
// central meridian (k − 1 ≈ −4e-4 … +3e-4); the reduced values must equal the lengths of the
// grid chords between the projected points.
TEST_F(NavFilesDir, GroundRangesBecomeGridLengths) {
  const double lat0 = 45.0, lon0 = 11.5;
  const GeographicLib::Geodesic& geod = GeographicLib::Geodesic::WGS84();
  double la = 0, lo = 0, lb = 0, lob = 0;
  geod.Direct(lat0, lon0, 70.0, 60000.0, la, lo);
  geod.Direct(lat0, lon0, 200.0, 90000.0, lb, lob);
  double sa = 0, sb = 0;
  geod.Inverse(lat0, lon0, la, lo, sa);
  geod.Inverse(lat0, lon0, lb, lob, sb);
  char st[256], lp[512];
  std::snprintf(st, sizeof st, "name,lat_deg,lon_deg\nA,%.15f,%.15f\nB,%.15f,%.15f\n", la, lo, lb, lob);
  std::snprintf(lp, sizeof lp,
                "time_s,type,station,station2,value,sigma_m\n0,range,A,,%.10f,50\n0,range_difference,A,B,%.10f,20\n",
                sa, sa - sb);
  write("s.csv", st);
  write("l.csv", lp);
  write("dr.csv", "time_s,speed_m_s,heading_deg\n0,5,0\n5,5,0\n");
  const PlaneJob r = plane_job(io::read_nav_config(write(
      "nav.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\ninitial: {lat: 45, lon: 11.5, sigma_m: 10}\n"
                  "projection: {type: utm, zone: 32}\n")));
  const auto grid_length = [&](std::size_t i) {
    return std::hypot(r.input.stations[i].x_north_m - r.input.initial.x_north_m,
                      r.input.stations[i].y_east_m - r.input.initial.y_east_m);
  };
  EXPECT_GT(std::abs(grid_length(0) - sa), 10.0);  // the reduction matters here
  EXPECT_NEAR(r.input.lops[0].value_m, grid_length(0), 1e-3);
  EXPECT_NEAR(r.input.lops[1].value_m, grid_length(0) - grid_length(1), 1e-3);
  EXPECT_NEAR(r.input.lops[0].sigma_m, 50.0, 0.05);
  // a plane job without a projection keeps its values
  write("sp.csv", "name,x_m,y_m\nA,60000,0\nB,0,90000\n");
  const PlaneJob p = plane_job(io::read_nav_config(
      write("p.yaml", "dr: dr.csv\nstations: sp.csv\nlops: l.csv\ninitial: {x_m: 0, y_m: 0}\n")));
  EXPECT_EQ(p.input.lops[0].value_m, std::stod(std::string(lp).substr(std::string(lp).find("0,range,A,,") + 11)));
}

TEST_F(NavFilesDir, GeographicFixCovarianceTurnsIntoTheGrid) {
  write("dr.csv", "time_s,speed_m_s,heading_deg\n0,5,0\n5,5,0\n");
  write("f.csv", "time_s,lat_deg,lon_deg,sigma_x_m,sigma_y_m\n0,45,9.5,1,10\n");
  const PlaneJob r = plane_job(io::read_nav_config(write(
      "nav.yaml", "dr: dr.csv\nfixes: f.csv\nprojection: {type: transverse-mercator, central_meridian: 7}\n")));
  const auto& cov = r.input.fixes[0].covariance;
  const meridian::geodesy::GridDefinition& g = *r.projection;
  const auto p = meridian::geodesy::TransverseMercatorGrid(g).forward(45 * kDeg, 9.5 * kDeg);
  // the long axis (σ 10 m east, azimuth 90°) has grid azimuth 90° − γ
  const double angle = 0.5 * std::atan2(2 * cov(0, 1), cov(0, 0) - cov(1, 1));  // of the major axis from x
  EXPECT_NEAR(std::abs(std::remainder(angle - (90 * kDeg - p.convergence_rad), std::numbers::pi)), 0.0, 1e-9);
  EXPECT_NEAR(cov.trace(), p.scale * p.scale * 101.0, 1e-9);
  // the initial position from this fix (at the first epoch: not moved): its whole grid
  // covariance is dead reckoning's at epoch 0 (it was reduced to the larger σ before)
  ASSERT_TRUE(r.input.initial_fix.has_value());
  const nav::Result res = nav::process(r.input);
  EXPECT_TRUE(res.find(nav::Method::DeadReckoning)->track[0].covariance.isApprox(cov, 1e-12));
}

// --- NMEA --------------------------------------------------------------------------------------

std::string fmt_hms(int h, int m, int s) {
  char b[16];
  std::snprintf(b, sizeof b, "%02d%02d%02d", h, m, s);
  return b;
}

// A log on 2014-08-01 from 23:59:50 to 00:00:10 of the next day, no logger stamps: ZDA dates
// it; GGA every second; HDT alternating across north; VTG speed 10 kn after each GGA (its time
// is the GGA's). One VTG sits in an HDT gap of 4 s (skipped and counted).
std::string midnight_log() {
  std::string s = "# hand-made\n" + nmea_line("GPZDA,235950.00,01,08,2014,00,00");
  for (int k = 0; k <= 20; ++k) {
    const int sec = (50 + k) % 60, min = k < 10 ? 59 : 0, hour = k < 10 ? 23 : 0;
    const std::string hms = fmt_hms(hour, min, sec);
    s += nmea_line("GPGGA," + hms + ".00,4500.0000,N,00930.0000,E,1,08,0.9,10.0,M,45.0,M,,");
    if (k == 11) s += nmea_line("GPZDA," + hms + ".00,02,08,2014,00,00");
    if (!(k >= 13 && k <= 17)) s += nmea_line(k % 2 ? "HEHDT,1.0,T" : "HEHDT,359.0,T");
    s += nmea_line("GPVTG,0.0,T,,M,10.0,N,18.52,K");
  }
  return s;
}

TEST_F(NavFilesDir, NmeaMidnightThinningTruthAndSkippedSpeed) {
  const std::string log = write("ship.nmea", midnight_log());
  io::NavNmeaConfig c;
  c.heading_path = c.speed_path = c.positions_path = log;
  c.fix_interval_s = 5.0;
  const io::NavNmeaData d = io::read_nav_nmea(c);
  EXPECT_TRUE(d.dated);
  EXPECT_EQ(d.origin_unix_s, 16283.0 * 86400.0);  // 2014-08-01 (days_from_civil)
  ASSERT_EQ(d.dr.records.size(), 20u);           // 21 VTG, one in the HDT gap
  EXPECT_DOUBLE_EQ(d.dr.records.front().time_s, 86390.0);
  EXPECT_DOUBLE_EQ(d.dr.records.back().time_s, 86410.0);  // over midnight, increasing
  for (std::size_t k = 1; k < d.dr.records.size(); ++k)
    EXPECT_GT(d.dr.records[k].time_s, d.dr.records[k - 1].time_s);
  EXPECT_NEAR(d.dr.records[0].a, 10.0 * 1852.0 / 3600.0, 1e-12);
  EXPECT_NEAR(d.dr.records[0].b, 359.0 * kDeg, 1e-12);
  EXPECT_NEAR(d.dr.records[1].b, 1.0 * kDeg, 1e-12);
  // thinning: fixes at 0, 5, 10, 15, 20 s after the first GGA; the other 16 are the truth
  ASSERT_EQ(d.fixes.records.size(), 5u);
  EXPECT_DOUBLE_EQ(d.fixes.records[2].time_s, 86400.0);
  EXPECT_EQ(d.fixes.records[0].sigma_north_m, io::kNavDefaultSigmaFix_m);
  EXPECT_EQ(d.truth.records.size(), 16u);
  EXPECT_DOUBLE_EQ(d.truth.records[0].time_s, 86391.0);
  EXPECT_NEAR(d.fixes.records[0].position.lat_rad, 45.0 * kDeg, 1e-15);
  bool gap = false, sigma = false;
  for (const auto& n : d.notes) {
    gap |= n.find("VTG speed samples with no HDT within 2 s: 1 skipped") != std::string::npos;
    sigma |= n.find("sigma 5 m per coordinate (default") != std::string::npos;
  }
  EXPECT_TRUE(gap);
  EXPECT_TRUE(sigma);
  // the whole job: default projection at 9.5°, initial position from the first fix
  const std::string p = write("nav.yaml", "nmea: {heading: ship.nmea, fix_interval_s: 5}\n");
  const PlaneJob r = plane_job(io::read_nav_config(p));
  ASSERT_TRUE(r.projection);
  EXPECT_NEAR(r.projection->central_meridian_rad, 9.5 * kDeg, 1e-15);
  EXPECT_EQ(r.input.dr.size(), 20u);
  EXPECT_EQ(r.input.fixes.size(), 5u);
  EXPECT_EQ(r.input.truth.size(), 16u);
  EXPECT_NEAR(r.input.initial.y_east_m, 0.0, 1e-6);
  EXPECT_EQ(r.input.initial_fix, std::optional<std::size_t>(0));
  EXPECT_EQ(r.job.line.dr[0].source.file, log);
}

// Heading and speed in two files with logger stamps: the heading interpolated circularly
// across north (359° → 1° gives 0° halfway), VBW's transverse speed turning the velocity.
TEST_F(NavFilesDir, NmeaHeadingInterpolatedAcrossNorthFromAnotherFile) {
  const std::string day = "2014-08-01T10:00:";
  write("gyro.nmea", day + "00.000000Z " + nmea_line("HEHDT,359.0,T") + day + "01.000000Z " +
                         nmea_line("HEHDT,1.0,T") + day + "02.000000Z " + nmea_line("HEHDT,3.0,T") +
                         day + "09.000000Z " + nmea_line("HEHDT,3.0,T"));
  write("log.nmea", day + "00.500000Z " + nmea_line("GPVTG,10.0,T,,M,,N,36.0,K") + day + "01.250000Z " +
                        nmea_line("GPVTG,10.0,T,,M,,N,36.0,K") + day + "05.500000Z " +
                        nmea_line("GPVTG,10.0,T,,M,,N,36.0,K") + day + "08.000000Z " +
                        nmea_line("GPVBW,,,V,5.0,1.0,A"));
  io::NavNmeaConfig c;
  c.heading_path = (dir_ / "gyro.nmea").string();
  c.speed_path = (dir_ / "log.nmea").string();
  const io::NavNmeaData d = io::read_nav_nmea(c);
  ASSERT_EQ(d.dr.records.size(), 2u);  // 05.5: no HDT within 2 s; VBW not the chosen sentence
  EXPECT_DOUBLE_EQ(d.dr.records[0].time_s, 36000.5);
  EXPECT_NEAR(std::remainder(d.dr.records[0].b, 2 * std::numbers::pi), 0.0, 1e-12);
  EXPECT_NEAR(d.dr.records[1].b, 1.5 * kDeg, 1e-12);
  EXPECT_NEAR(d.dr.records[0].a, 10.0, 1e-12);  // 36 km/h
  EXPECT_EQ(d.dr.lines[1], 2);
  c.speed_sentence = io::NavSpeedSentence::Vbw;
  const io::NavNmeaData v = io::read_nav_nmea(c);
  ASSERT_EQ(v.dr.records.size(), 1u);  // at 08.0 the HDT of 09.0 is within 2 s
  EXPECT_NEAR(v.dr.records[0].a, std::hypot(5.0, 1.0) * 1852.0 / 3600.0, 1e-12);  // knots
  EXPECT_NEAR(v.dr.records[0].b, 3.0 * kDeg + std::atan2(1.0, 5.0), 1e-12);
}

TEST_F(NavFilesDir, NmeaWithoutHeadingsOrSpeedsIsAnError) {
  write("log.nmea", nmea_line("GPZDA,100000.00,01,08,2014,00,00") + nmea_line("GPVTG,10.0,T,,M,,N,36.0,K"));
  io::NavNmeaConfig c;
  c.heading_path = c.speed_path = (dir_ / "log.nmea").string();
  EXPECT_HAS(error_of<InputError>([&] { io::read_nav_nmea(c); }), "no usable HDT");
  write("log.nmea", nmea_line("GPZDA,100000.00,01,08,2014,00,00") + nmea_line("HEHDT,1.0,T") +
                        nmea_line("GPVTG,10.0,T,,M,,N,36.0,K"));
  c.speed_sentence = io::NavSpeedSentence::Vbw;
  EXPECT_HAS(error_of<InputError>([&] { io::read_nav_nmea(c); }), "no usable VBW speed");
  EXPECT_HAS(error_of<InputError>([&] { io::read_nav_nmea(c); }), "the file has no VBW sentence");
  // logs that do not overlap in time: every speed sample is skipped, and the message says why
  write("gyro.nmea", "2014-08-01T10:00:00.000Z " + nmea_line("HEHDT,1.0,T"));
  write("gps.nmea", "2014-08-01T11:00:00.000Z " + nmea_line("GPVTG,10.0,T,,M,,N,36.0,K"));
  c.heading_path = (dir_ / "gyro.nmea").string();
  c.speed_path = (dir_ / "gps.nmea").string();
  c.speed_sentence = io::NavSpeedSentence::Vtg;
  EXPECT_HAS(error_of<InputError>([&] { io::read_nav_nmea(c); }),
             "1 skipped: VTG speed samples with no HDT within 2 s (first line 1)");
  // every VTG without a checksum: the message says so and names the option (it said "the
  // file has no VTG sentence")
  write("gyro.nmea", "2014-08-01T10:00:00.000Z " + nmea_line("HEHDT,1.0,T"));
  write("gps.nmea", "2014-08-01T10:00:00.000Z $GPVTG,10.0,T,,M,,N,36.0,K\n2014-08-01T10:00:01.000Z $GPVTG,10.0,T,,M,,N,36.0,K\n");
  const std::string nochk = error_of<InputError>([&] { io::read_nav_nmea(c); });
  EXPECT_HAS(nochk, "2 GPVTG sentences without a checksum, rejected (first lines 1, 2 of the file's 2 without one)");
  EXPECT_HAS(nochk, "accept_missing_checksum: true");
  EXPECT_EQ(nochk.find("has no VTG sentence"), std::string::npos) << nochk;
}

TEST_F(NavFilesDir, NmeaLinesDroppedByTheReaderAreWarnedAbout) {
  // The midnight log with a bad checksum (line 3), a line without one (line 4) and two joined
  // sentences (line 5) inserted: nav::process gets a warning with the counts and the first lines.
  std::string log = midnight_log();
  const std::size_t second = log.find('\n', log.find('\n') + 1) + 1;  // after line 2
  log.insert(second, "$HEHDT,1.0,T*00\n$HEHDT,1.0,T\n$HEHDT,1.0,$GPVTG,0.0,T*12\n");
  write("ship.nmea", log);
  const io::NavRun r = io::run_nav(io::read_nav_config(write("n.yaml", "nmea: {heading: ship.nmea}\n")));
  std::string all;
  for (const std::string& w : r.result.warnings) all += w + "\n";
  EXPECT_HAS(all, "ship.nmea: 3 lines not read: 1 with a bad checksum (line 3), 1 without a checksum (line 4; "
                  "accept_missing_checksum: true reads them), 1 malformed (line 5: ");
}

// Errors of nav::process about an element are given its file, line and column.
TEST_F(NavFilesDir, ProcessErrorsAreLocated) {
  write("dr.csv", "time_s,speed_m_s,heading_deg\n0,5,90\n5,5,90\n10,5,90\n");
  write("s.csv", "name,x_m,y_m\nA,1000,0\n");
  write("l.csv", "time_s,type,station,station2,value,sigma_m\n5,range,A,,1000,50\n\n10,range,A,,1000,50\n");
  const io::NavConfig c = io::read_nav_config(
      write("nav.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\ninitial: {x_m: 0, y_m: 0}\nthreshold_m: 50\n"));
  const io::NavJob job = io::read_nav_job(c);
  const auto located_as = [&](const std::string& field) {
    return error_of([&] { io::located(job.sources, [&] { throw InputError("bad", {"", std::nullopt, field}); }); });
  };
  EXPECT_EQ(located_as("lops[1].value_m"), (dir_ / "l.csv").string() + ":4: value: bad");
  EXPECT_EQ(located_as("dr[2].time_s"), (dir_ / "dr.csv").string() + ":4: time_s: bad");
  EXPECT_EQ(located_as("epoch 1"), (dir_ / "dr.csv").string() + ":3: bad");
  EXPECT_EQ(located_as("options.threshold_m"), (dir_ / "nav.yaml").string() + ":5: threshold_m: bad");
  EXPECT_EQ(located_as("initial.sigma_m"), (dir_ / "nav.yaml").string() + ":4: initial.sigma_m: bad");
  EXPECT_EQ(located_as("stations[0].x_north_m"), (dir_ / "s.csv").string() + ":2: x_m: bad");
  // the fix that gives the initial position: its line
  write("f.csv", "time_s,x_m,y_m,sigma_m\n1,0,0,5\n");
  const io::NavJob jf = io::read_nav_job(
      io::read_nav_config(write("nf.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\nfixes: f.csv\n")));
  EXPECT_EQ(error_of([&] {
              io::located(jf.sources, [&] { throw InputError("bad", {"", std::nullopt, "fixes[0].time_s"}); });
            }),
            (dir_ / "f.csv").string() + ":2: time_s: bad");
  // the class is kept
  EXPECT_THROW(
      io::located(job.sources, [&] { throw meridian::NumericalError("n", {"", std::nullopt, "epoch 1"}); }),
      meridian::NumericalError);
  // statistics bins beyond nav::kMaxStatisticsBins over the line (std::bad_alloc before)
  const std::string bins = error_of<InputError>([&] {
    io::run_nav(io::read_nav_config(write("b.yaml", "dr: dr.csv\ninitial: {x_m: 0, y_m: 0}\nstatistics_bin_s: 1e-9\n")));
  });
  EXPECT_HAS(bins, "b.yaml:3: statistics_bin_s:");
}

// A whole run on a small plane line. Needs nav::process (a placeholder that throws until the
// numerics land: this test fails only for that reason until then).
TEST_F(NavFilesDir, RunNavProcessesAPlaneLine) {
  std::string dr = "time_s,speed_m_s,heading_deg\n", lops = "time_s,type,station,station2,value,sigma_m\n";
  for (int k = 0; k <= 60; ++k) {
    dr += std::to_string(5 * k) + ",5,90\n";
    const double y = 25.0 * k;
    lops += std::to_string(5 * k) + ",range,A,," + std::to_string(std::hypot(1000.0, y)) + ",5\n";
    lops += std::to_string(5 * k) + ",range,B,," + std::to_string(std::hypot(1000.0, 2000.0 - y)) + ",5\n";
  }
  write("dr.csv", dr);
  write("l.csv", lops);
  write("s.csv", "name,x_m,y_m\nA,1000,0\nB,-1000,2000\n");
  const io::NavConfig c =
      io::read_nav_config(write("nav.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\ninitial: {x_m: 0, y_m: 0}\n"));
  const io::NavRun r = io::run_nav(c);
  EXPECT_EQ(r.result.epochs, 61u);
  EXPECT_NE(r.result.find(nav::Method::Rts), nullptr);
}

// The Result describes itself: the projection of its plane, the file and line of each
// rejected observation (the blunder of l.csv line 62: row 61, k = 30, station A).
TEST_F(NavFilesDir, RunNavResultCarriesItsProjectionAndSources) {
  const double x0 = 4983000.0, y0 = 500000.0;
  std::string dr = "time_s,speed_m_s,heading_deg\n", lops = "time_s,type,station,station2,value,sigma_m\n";
  for (int k = 0; k <= 60; ++k) {
    dr += std::to_string(5 * k) + ",5,90\n";
    const double y = 25.0 * k;
    lops += std::to_string(5 * k) + ",range,A,," + std::to_string(std::hypot(1000.0, y) + (k == 30 ? 500.0 : 0.0)) +
            ",5\n";
    lops += std::to_string(5 * k) + ",range,B,," + std::to_string(std::hypot(1000.0, 2000.0 - y)) + ",5\n";
  }
  write("dr.csv", dr);
  write("l.csv", lops);
  write("s.csv", "name,x_m,y_m\nA," + std::to_string(x0 + 1000.0) + "," + std::to_string(y0) + "\nB," +
                     std::to_string(x0 - 1000.0) + "," + std::to_string(y0 + 2000.0) + "\n");
  const io::NavRun r = io::run_nav(io::read_nav_config(write(
      "nav.yaml", "dr: dr.csv\nstations: s.csv\nlops: l.csv\nprojection: {type: utm, zone: 32}\ninitial: {x_m: " +
                      std::to_string(x0) + ", y_m: " + std::to_string(y0) + "}\n")));
  ASSERT_TRUE(r.result.projection);
  EXPECT_EQ(r.result.projection->zone, 32);
  bool blunder = false;
  for (const nav::RejectedObservation& o : r.result.rejected) {
    EXPECT_EQ(o.source, "l.csv:" + std::to_string(2 + o.index)) << o.reason;
    blunder |= o.index == 60;
  }
  EXPECT_TRUE(blunder);
  bool plane = false;
  for (const std::string& n : r.result.notes) plane |= n.rfind("plane: ", 0) == 0;
  EXPECT_TRUE(plane);
}

TEST_F(NavFilesDir, AnInitialFixBeforeTheFirstEpochIsMovedThereAndUsedOnce) {
  // The trial's j9 job: exact DR 5.5 m/s east from t = 0, exact fixes at t = −4 s (0, −22)
  // and t = 600 s (0, 3300), σ 1 m, no initial: → the fix moved to t = 0 is (0, 0), the truth:
  // every method exact, nothing rejected (before: DR 22 m off, the fix rejected by χ²).
  std::string dr = "time_s,speed_m_s,heading_deg\n", truth = "time_s,x_m,y_m\n";
  for (int k = 0; k <= 240; ++k) {
    dr += std::to_string(5 * k) + ",5.5,90\n";
    truth += std::to_string(5 * k) + ",0," + std::to_string(27.5 * k) + "\n";
  }
  write("dr.csv", dr);
  write("t.csv", truth);
  write("f.csv", "time_s,x_m,y_m,sigma_m\n-4,0,-22,1\n600,0,3300,1\n");
  const io::NavRun r = io::run_nav(io::read_nav_config(
      write("nav.yaml", "dr: dr.csv\nfixes: f.csv\ntruth: t.csv\nsigma_speed_m_s: 0.01\nsigma_heading_deg: 0.01\n")));
  EXPECT_TRUE(r.result.rejected.empty());
  for (const nav::MethodResult& m : r.result.methods) {
    ASSERT_TRUE(m.errors);
    EXPECT_LT(m.errors->rms_m, 1e-6) << nav::to_string(m.method);
  }
  bool noted = false;
  for (const std::string& n : r.result.notes)
    noted |= n.find("line 2 (t = -4.000 s, sigma 1 m) moved by the dead reckoning to the first DR epoch") !=
             std::string::npos;
  EXPECT_TRUE(noted);
}

// --- the real logs of ../shared/data/nmea (skipped when absent) ---------------------------------

namespace {
fs::path nmea_data() { return fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "data" / "nmea"; }
}  // namespace

// The real-data case: gyro HDT (5 Hz, logger stamps only) with the Seapath's VTG speed
// and GGA positions, one GGA every 120 s as a fix, the rest as truth. Counts by grep/awk:
// grep -c INVTG → 625 (no repeated logger stamp: awk '{print $1}' | sort | uniq -d → none);
// GGA at 00:00:00.16 … 00:10:24.16, 1 Hz, all quality 1 → fixes at 0.16, 120.16, …, 600.16
// (6) and 619 withheld.
TEST(NavNmeaRealLogs, GyroHeadingSeapathSpeedThinnedGga) {
  if (!fs::is_directory(nmea_data())) GTEST_SKIP() << nmea_data() << " is absent";
  io::NavNmeaConfig c;
  c.heading_path = (nmea_data() / "nbp1406-gyro.nmea").string();
  c.speed_path = c.positions_path = (nmea_data() / "nbp1406-seapath330.nmea").string();
  c.fix_interval_s = 120.0;
  const io::NavNmeaData d = io::read_nav_nmea(c);
  EXPECT_EQ(d.origin_unix_s, 16283.0 * 86400.0);  // 2014-08-01
  ASSERT_EQ(d.dr.records.size(), 625u);
  EXPECT_NEAR(d.dr.records[0].time_s, 0.402, 1e-6);            // the VTG's logger stamp
  EXPECT_NEAR(d.dr.records[0].a, 9.1 * 1852.0 / 3600.0, 1e-12);  // INVTG …,9.1,N,16.9,K
  EXPECT_NEAR(d.dr.records[0].b, 218.53 * kDeg, 1e-12);          // HDT 218.53 at 0.383 and 0.583
  ASSERT_EQ(d.fixes.records.size(), 6u);
  EXPECT_NEAR(d.fixes.records[1].time_s, 120.16, 1e-6);
  EXPECT_NEAR(d.fixes.records[5].time_s, 600.16, 1e-6);
  EXPECT_EQ(d.truth.records.size(), 619u);
  // latitude 22°00.110899' S
  EXPECT_NEAR(d.fixes.records[0].position.lat_rad, -(22.0 + 0.110899 / 60.0) * kDeg, 1e-12);
  // the whole job reads: initial position from the GGA of 0.16 s (0.24 s before the first DR)
  const PlaneJob r = [&] {
    io::NavConfig cfg;
    cfg.file = "nav.yaml";
    cfg.nmea = c;
    return plane_job(cfg);
  }();
  EXPECT_EQ(r.input.dr.size(), 625u);
  EXPECT_EQ(r.input.fixes.size(), 6u);
  ASSERT_TRUE(r.projection);
  EXPECT_NEAR(r.projection->central_meridian_rad, -17.9 * kDeg, 1e-15);  // 17°56.36' W → 17.9° W
  EXPECT_NEAR(r.input.initial.x_north_m, r.input.fixes[0].x_north_m, 0.0);
}

// GPS week rollover: the P-code receiver dates its ZDA 1994-12-16 while the logger says
// 2014-08-01; its first GGA, 23:59:59.226, is the day before. 1000 VTG and GGA (grep -c).
TEST(NavNmeaRealLogs, RolloverCorrectedAndMidnightStraddled) {
  if (!fs::is_directory(nmea_data())) GTEST_SKIP() << nmea_data() << " is absent";
  io::NavNmeaConfig c;
  c.heading_path = (nmea_data() / "nbp1406-gyro.nmea").string();
  c.speed_path = c.positions_path = (nmea_data() / "nbp1406-pcode-gps-rollover.nmea").string();
  const io::NavNmeaData d = io::read_nav_nmea(c);
  EXPECT_EQ(d.origin_unix_s, 16282.0 * 86400.0);  // 2014-07-31: the first GGA's day
  ASSERT_EQ(d.fixes.records.size(), 1000u);
  EXPECT_NEAR(d.fixes.records[0].time_s, 86399.226, 1e-6);
  EXPECT_NEAR(d.fixes.records[1].time_s, 86400.226, 1e-6);  // across midnight
  for (std::size_t k = 1; k < d.fixes.records.size(); ++k)
    EXPECT_GT(d.fixes.records[k].time_s, d.fixes.records[k - 1].time_s);
  EXPECT_EQ(d.dr.records.size(), 1000u);
  EXPECT_NEAR(d.dr.records[0].time_s, 86400.241, 1e-6);
  bool noted = false;
  for (const auto& n : d.notes) noted |= n.find("GPS week rollover") != std::string::npos;
  EXPECT_TRUE(noted);
  // The origin's note says what it is (it said "the first epoch's day": the DR starts on 1 August).
  bool origin = false;
  for (const auto& n : d.notes)
    origin |= n.find("NMEA times: seconds since 2014-07-31T00:00:00.000Z (00:00 UTC of the day of the earliest "
                     "sample: the GGA position of ") != std::string::npos &&
              n.find("line 2, 2014-07-31T23:59:59.226Z)") != std::string::npos;
  EXPECT_TRUE(origin);
}

// --- robustness: mutated files give meridian::Error or a result, nothing else -----------------

namespace {
std::string mutate(std::string s, std::mt19937& g) {
  static const char kBytes[] = ",;\n#-.e9 \t\"x\xff\x00";
  std::uniform_int_distribution<int> op(0, 3), byte(0, sizeof kBytes - 2);
  const int n = 1 + static_cast<int>(g() % 4);
  for (int k = 0; k < n && !s.empty(); ++k) {
    const std::size_t at = g() % s.size();
    switch (op(g)) {
      case 0: s[at] = kBytes[byte(g)]; break;
      case 1: s.insert(at, 1, kBytes[byte(g)]); break;
      case 2: s.erase(at, 1 + g() % 8); break;
      default: s.resize(at); break;
    }
  }
  return s;
}
}  // namespace

TEST(NavReadersRobustness, MutatedCsvGivesErrorsOnly) {
  const std::string good[] = {
      "time_s,speed_m_s,heading_deg\n0,5,30\n5,5.5,\"30 30\"\n10,5,359\n",
      "name,lat_deg,lon_deg\nA,45.1,7.6\nB,45d12m,7:42\n",
      "time_s,type,station,station2,value,sigma_m,chain\n5,range,A,,1234.5,50,\n10,time_difference,A,B,12.5,30,X\n",
      "time_s,x_m,y_m,sigma_x_m,sigma_y_m\n1,2,3,4,5\n2,3,4,5,6\n",
      "time_s,lat_deg,lon_deg\n0,45,7\n1,45.0001,7\n"};
  std::mt19937 g(20261202);
  int errors = 0, ok = 0;
  for (int round = 0; round < 3000; ++round) {
    const int which = round % 5;
    const std::string text = mutate(good[which], g);
    std::istringstream in(text);
    try {
      switch (which) {
        case 0: io::read_nav_dr(in, "m.csv"); break;
        case 1: io::read_nav_stations(in, "m.csv"); break;
        case 2: io::read_nav_lops(in, "m.csv"); break;
        case 3: io::read_nav_fixes(in, "m.csv"); break;
        default: io::read_nav_truth(in, "m.csv"); break;
      }
      ++ok;
    } catch (const meridian::Error& e) {
      ++errors;
      EXPECT_NE(std::string(e.what()).find("m.csv"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a meridian::Error: " << e.what() << "\n" << text;
    }
  }
  EXPECT_GT(errors, 100);
  EXPECT_GT(ok, 100);
}

TEST_F(NavFilesDir, MutatedNmeaAndConfigGiveErrorsOnly) {
  const std::string log = midnight_log();
  const std::string config = "nmea: {heading: ship.nmea, fix_interval_s: 5}\nthreshold_m: 100\n";
  std::mt19937 g(7);
  for (int round = 0; round < 300; ++round) {
    write("ship.nmea", round % 2 ? mutate(log, g) : log);
    const std::string p = write("nav.yaml", round % 2 ? config : mutate(config, g));
    try {
      plane_job(io::read_nav_config(p));
    } catch (const meridian::Error&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a meridian::Error: " << e.what();
    }
  }
}
