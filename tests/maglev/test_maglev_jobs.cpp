// The maglev runners (io/maglev_jobs.hpp): which constants win, what the Result carries for its
// writers, where errors are located; the simulator's settings of `maglev simulate`.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/io/maglev_files.hpp"
#include "meridian/io/maglev_jobs.hpp"
#include "meridian/maglev/simulator.hpp"

using namespace meridian;
namespace fs = std::filesystem;

namespace {

class MaglevJobs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("meridian_maglev_jobs_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    // A clean determination, 600 samples per position at 20 Hz.
    maglev::TwoPositionTruth t;
    t.alpha1_rad = 0.02;
    t.latitude_rad = 35 * units::kDegree;
    maglev::NoiseSpec n;
    n.samples = 600;
    n.rate_hz = 20;
    const auto in = maglev::simulate_determination(t, n, n, 3);
    write("p1.csv", io::maglev_series_csv(in.position1));
    write("p2.csv", io::maglev_series_csv(in.position2));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static io::MaglevReduceSetup given(double scale, double latitude_deg) {
    io::MaglevReduceSetup s;
    s.given.scale_A_s_per_rad = Uncertain{scale, 0.0};
    s.given.latitude_rad = latitude_deg * units::kDegree;
    return s;
  }
  fs::path dir_;
};

}  // namespace

TEST_F(MaglevJobs, GivenValuesWinOverTheCalibrationWhichWinsOverTheConstantsFile) {
  io::MaglevReduceSetup s;
  s.constants_file = write("k.yaml",
                           "scale_A_s_per_rad: 8000\nlatitude: 35\ncircle_reading1: 12\n"
                           "constant_deviation_A: 1e-4\n");
  auto in = io::maglev_reduce_input(s);
  EXPECT_EQ(in.scale_A_s_per_rad.value, 8000.0);
  EXPECT_DOUBLE_EQ(in.latitude_rad, 35 * units::kDegree);
  EXPECT_DOUBLE_EQ(in.circle_reading1_rad.value, 12 * units::kDegree);
  ASSERT_TRUE(in.options.prior_bias_A);
  EXPECT_EQ(in.options.prior_bias_A->value, 1e-4);
  // A stored calibration: its K and I*, not its other keys.
  s.calibration_file = write("cal.json",
                             R"({"kind": "maglev-calibration", "scale_A_s_per_rad": 7990,
                                 "scale_sigma_A_s_per_rad": 4, "constant_deviation_A": 2e-5,
                                 "constant_deviation_sigma_A": 1e-7})");
  in = io::maglev_reduce_input(s);
  EXPECT_EQ(in.scale_A_s_per_rad.value, 7990.0);
  EXPECT_EQ(in.scale_A_s_per_rad.sigma, 4.0);
  EXPECT_EQ(in.options.prior_bias_A->value, 2e-5);
  EXPECT_DOUBLE_EQ(in.latitude_rad, 35 * units::kDegree);
  s.given.scale_A_s_per_rad = Uncertain{7980, 1};
  s.given.constant_deviation_A = Uncertain{3e-5, 0};
  s.given.latitude_rad = 0.5;
  s.reading1_sigma_rad = 1e-5;
  s.options.prior_bias_A = Uncertain{9, 9};  // replaced by the constants' prior bias
  in = io::maglev_reduce_input(s);
  EXPECT_EQ(in.scale_A_s_per_rad.value, 7980.0);
  EXPECT_EQ(in.options.prior_bias_A->value, 3e-5);
  EXPECT_EQ(in.latitude_rad, 0.5);
  EXPECT_EQ(in.circle_reading1_rad.sigma, 1e-5);
}

TEST_F(MaglevJobs, MissingConstantsAreNamedAsTheFrontEndCallsThem) {
  io::MaglevReduceSetup s;
  s.constants_file = write("k.yaml", "latitude: 35\n");
  s.names = {"--scale", "--latitude", "--config", "--calibration"};
  try {
    io::maglev_reduce_input(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--scale: the scale K is needed: --scale, --config or --calibration");
  }
  s.constants_file = write("k.yaml", "scale_A_s_per_rad: 8000\n");
  try {
    io::maglev_reduce_input(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--latitude: the latitude is needed: --latitude or --config");
  }
}

TEST_F(MaglevJobs, TheResultCarriesWhatItsWritersShow) {
  io::MaglevReduceSetup s = given(8000, 35);
  s.options.denoising.level = 4;
  const auto r = io::run_maglev_reduce_files({path("p1.csv"), path("p2.csv")}, s);
  EXPECT_EQ(r.source, path("p1.csv") + ", " + path("p2.csv"));
  EXPECT_EQ(r.scale_A_s_per_rad.value, 8000.0);
  EXPECT_DOUBLE_EQ(r.latitude_rad, 35 * units::kDegree);
  EXPECT_EQ(r.options.denoising.level, 4);
  ASSERT_EQ(r.position1.series.time_s.size(), 600u);
  EXPECT_DOUBLE_EQ(r.position1.series.time_s[20], 1.0);  // 20 Hz
  EXPECT_EQ(r.position2.series.time_s[0], 0.0);
}

TEST_F(MaglevJobs, ErrorsAboutASeriesNameItsFileAndColumn) {
  std::string constant = "time,current\n";
  for (int i = 0; i < 600; ++i) constant += std::to_string(i) + ",0.01\n";
  write("const.csv", constant);
  try {
    io::run_maglev_reduce_files({path("p1.csv"), path("const.csv")}, given(8000, 35));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().file, path("const.csv"));
    EXPECT_FALSE(e.context().line);
    EXPECT_EQ(e.context().field, "current");
  }
  // One file for both positions: the position's processing keeps its field.
  write("both.csv", "time,current,position\n0,0.01,1\n1,0.02,1\n2,0.015,1\n0,0.01,2\n1,0.03,2\n");
  try {
    io::run_maglev_reduce_files({path("both.csv")}, given(8000, 35));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().file, path("both.csv"));
    EXPECT_EQ(e.context().field, "position1.segment_length");
  }
  // |(I1 − I2)/(2A)| > 1 concerns no file: a NumericalError naming alpha1.
  try {
    io::run_maglev_reduce_files({path("p1.csv"), path("p2.csv")}, given(1e-3, 35));
    FAIL();
  } catch (const NumericalError& e) {
    EXPECT_EQ(e.context().file, "");
    EXPECT_EQ(e.context().field, "alpha1");
  }
  // A reader's own error passes as it is (ParseError kept).
  write("bad.csv", "time,current\n0,0.01\n1,x\n");
  try {
    io::run_maglev_reduce_files({path("bad.csv"), path("p2.csv")}, given(8000, 35));
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_EQ(e.context().file, path("bad.csv"));
    EXPECT_EQ(e.context().line, 3);
  }
}

TEST_F(MaglevJobs, ArraysKeepTheirFieldPaths) {
  maglev::PositionSeries p1{{0, 1, 2, 3}, {1e-3, 2e-3, 1e-3, 2e-3}};
  maglev::PositionSeries p2{{0, 1, 0.5, 3}, {1e-3, 2e-3, 1e-3, 2e-3}};
  try {
    io::run_maglev_reduce(given(8000, 35), p1, p2);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().file, "");
    EXPECT_EQ(e.context().field, "position2.time_s[2]");
  }
}

TEST_F(MaglevJobs, DenoiseLowersTheDefaultLevelForAShortSeries) {
  maglev::NoiseSpec n;
  n.samples = 300;
  write("s.csv", io::maglev_series_csv(maglev::simulate_series(1e-3, n, 5)));
  maglev::DenoiseOptions o;
  o.level = 0;
  const auto r = io::run_maglev_denoise_file(path("s.csv"), o);
  // pywt.dwt_max_level(300, 8) = floor(log2(300/7)) = 5.
  EXPECT_EQ(r.denoising.options.level, 5);
  EXPECT_EQ(r.series.time_s.size(), 300u);
  EXPECT_EQ(r.series.current_A, r.denoising.values);
  o.level = 6;  // asked: refused
  EXPECT_THROW(io::run_maglev_denoise_file(path("s.csv"), o), InputError);
  write("c.csv", "time,current\n0,1\n1,1\n2,1\n");
  try {
    io::run_maglev_denoise_file(path("c.csv"), o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().file, path("c.csv"));
    EXPECT_EQ(e.context().field, "series.current_A");
  }
}

TEST_F(MaglevJobs, CalibrationCarriesItsTableAndNamesItsFile) {
  write("t.csv", "azimuth,mean1,sigma1,mean2,sigma2\n-1,-0.008,1e-7,0.008,1e-7\n"
                 "0,1e-5,1e-7,1e-5,1e-7\n1,0.008,1e-7,-0.008,1e-7\n");
  const auto r = io::run_maglev_calibrate_file(path("t.csv"), 35 * units::kDegree, 0.01);
  EXPECT_EQ(r.source, path("t.csv"));
  ASSERT_EQ(r.setups.size(), 3u);
  EXPECT_DOUBLE_EQ(r.setups[2].azimuth_rad, units::kDegree);
  EXPECT_EQ(r.setups[0].mean2_A.value, 0.008);
  EXPECT_DOUBLE_EQ(r.latitude_rad, 35 * units::kDegree);
  write("few.csv", "azimuth,mean1,sigma1,mean2,sigma2\n0,1,1,2,1\n1,1,1,2,1\n");
  try {
    io::run_maglev_calibrate_file(path("few.csv"), 0.6);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path("few.csv") + ": setups: 2 set-ups are too few (at least 3 azimuths)");
  }
}

TEST(MaglevSimulation, PositionTwoFollowsAfterThePauseAndBurstsCountFromTheirPosition) {
  maglev::DeterminationSimulation sim;
  sim.noise.samples = 500;
  sim.noise.rate_hz = 100;
  sim.noise.start_s = 10;
  sim.bursts = {{2, {3, 9, 1e-3, 0, 0.5, 4}}, {1, {1, 2, 1e-3, 0, 0.5, 4}}};
  const auto [s1, s2] = maglev::position_noise(sim);
  EXPECT_EQ(s1.start_s, 10.0);
  EXPECT_EQ(s2.start_s, 10.0 + 5.0 + 30.0);
  ASSERT_EQ(s1.bursts.size(), 1u);
  ASSERT_EQ(s2.bursts.size(), 1u);
  EXPECT_EQ(s1.bursts[0].begin_s, 11.0);
  EXPECT_EQ(s2.bursts[0].begin_s, 48.0);
  EXPECT_EQ(s2.bursts[0].end_s, 54.0);
  sim.bursts = {{3, {}}};
  EXPECT_THROW(maglev::position_noise(sim), InputError);
}

TEST(MaglevSimulation, CalibrationSlopesAreRatiosOfTheIdealAmplitude) {
  maglev::CalibrationSimulation sim;
  sim.scale_A_s_per_rad = 9000;
  sim.latitude_rad = 0.7;
  sim.slope_ratio1 = 1.01;
  sim.slope_ratio2 = 0.99;
  const double A = 9000 * 7.2921150e-5 * std::cos(0.7);  // K·ω_e·cos φ
  const auto t = maglev::calibration_truth(sim);
  EXPECT_NEAR(t.slope1_A, 1.01 * A, 1e-12);
  EXPECT_NEAR(t.slope2_A, -0.99 * A, 1e-12);
  EXPECT_EQ(t.latitude_rad, 0.7);
}

// The drift of a simulated determination continues on the common clock across the blocks of
// its sequence (issue 30: the drift restarting at each position cancelled and hid the bias);
// settling and steps are placed per block and position.
TEST(MaglevSimulation, DriftIsContinuousOnTheCommonClockAcrossBlocks) {
  maglev::DeterminationSimulation sim;
  sim.noise.samples = 100;
  sim.noise.rate_hz = 10;
  sim.noise.white_sigma_A = 1e-12;
  sim.noise.drift_A_per_s = 1e-5;
  sim.sequence = {1, 2, 2, 1};
  sim.pause_s = 20;
  sim.steps = {{2, {15, 3e-3}}};
  const double A = sim.truth.scale_A_s_per_rad * 7.2921150e-5 * std::cos(sim.truth.latitude_rad);
  const double m = A * std::sin(sim.truth.alpha1_rad);
  const maglev::ReduceInput in = maglev::simulate_determination(sim);
  ASSERT_EQ(in.position1.time_s.size(), 200u);
  ASSERT_EQ(in.position2.time_s.size(), 200u);
  // Blocks of 10 s, 20 s apart: position 2 at 30…39.9 s and 60…69.9 s, position 1 again at 90 s.
  EXPECT_DOUBLE_EQ(in.position2.time_s[0], 30.0);
  EXPECT_DOUBLE_EQ(in.position1.time_s[100], 90.0);
  EXPECT_NEAR(in.position1.current_A[100], m + sim.truth.bias_A + 1e-5 * 90.0, 1e-10);
  EXPECT_NEAR(in.position2.current_A[0], -m + sim.truth.bias_A + 1e-5 * 30.0, 1e-10);
  // The step 15 s after position 2's first block began (45 s): in its second block only.
  EXPECT_NEAR(in.position2.current_A[100], -m + sim.truth.bias_A + 1e-5 * 60.0 + 3e-3, 1e-10);
  EXPECT_NEAR(in.position2.current_A[99], -m + sim.truth.bias_A + 1e-5 * 39.9, 1e-10);
  // The old behaviour on request: every block's drift from its own start.
  sim.drift_restarts = true;
  sim.steps.clear();
  const maglev::ReduceInput r = maglev::simulate_determination(sim);
  EXPECT_NEAR(r.position2.current_A[0], -m + sim.truth.bias_A, 1e-10);
  // Settling: +A at position 1, −A at position 2, from each block's start.
  sim.drift_restarts = false;
  sim.noise.drift_A_per_s = 0;
  sim.noise.settling_A = 2e-4;
  sim.noise.settling_tau_s = 5;
  const maglev::ReduceInput s = maglev::simulate_determination(sim);
  EXPECT_NEAR(s.position1.current_A[100], m + sim.truth.bias_A + 2e-4, 1e-10);
  EXPECT_NEAR(s.position2.current_A[100] - (-m + sim.truth.bias_A), -2e-4, 1e-10);
  sim.sequence = {1, 1};
  EXPECT_THROW(maglev::simulate_determination(sim), InputError);
  sim.sequence = {1, 2};
  sim.steps = {{1, {1000, 1e-3}}};
  EXPECT_THROW(maglev::simulate_determination(sim), InputError);
}
