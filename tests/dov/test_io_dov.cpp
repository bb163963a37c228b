// io_dov: the line CSV round trip (write → read gives the same doubles and the same result),
// errors naming file:line:column, the configuration and the runner's error location.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "dov_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/io/dov_files.hpp"

namespace {

using namespace meridian;
using meridian_test::kAs;

dov::Input small_line() {
  dov::SimulationOptions so;
  so.duration_s = 120.0;  // these cases run under ASan + UBSan too
  so.seed = 8;
  return dov::simulate(so);
}

std::filesystem::path temp_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() /
                 ("meridian_test_io_dov_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

void write(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

TEST(DovFiles, LineRoundTrip) {
  const dov::Input in = small_line();
  const std::string csv = io::dov_line_csv(in);
  std::istringstream s(csv);
  const io::DovLine line = io::read_dov_line(s, "line.csv");
  ASSERT_EQ(line.samples.size(), in.samples.size());
  ASSERT_EQ(line.truth.size(), in.truth.size());
  EXPECT_EQ(line.lines.front(), 3);  // comment, header, first sample
  for (std::size_t k = 0; k < in.samples.size(); ++k) {
    const dov::Sample& a = in.samples[k];
    const dov::Sample& b = line.samples[k];
    EXPECT_EQ(a.time_s, b.time_s);
    EXPECT_NEAR(a.lat_rad, b.lat_rad, 1e-16);
    EXPECT_NEAR(a.lon_rad, b.lon_rad, 1e-15);
    EXPECT_EQ(a.lgu_body_to_nav, b.lgu_body_to_nav);
    EXPECT_EQ(a.ins_body_to_nav, b.ins_body_to_nav);
    EXPECT_NEAR(a.model_xi_rad, b.model_xi_rad, 1e-20);
    EXPECT_NEAR(a.model_eta_rad, b.model_eta_rad, 1e-20);
    EXPECT_NEAR(in.truth[k].xi_rad, line.truth[k].xi_rad, 1e-20);
  }
  dov::Input back;
  back.samples = line.samples;
  back.truth = line.truth;
  const dov::Result r1 = dov::process(in), r2 = dov::process(back);
  for (std::size_t k = 0; k < r1.epochs.size(); k += 29)
    EXPECT_NEAR(r1.epochs[k].smoothed.xi_rad / kAs, r2.epochs[k].smoothed.xi_rad / kAs, 1e-9);
}

TEST(DovFiles, LineErrorsNameLineAndColumn) {
  const std::string csv = io::dov_line_csv(small_line());
  {
    std::string bad = csv;
    const auto third = bad.find('\n', bad.find('\n', bad.find('\n') + 1) + 1);  // end of line 3
    bad.insert(third, "x");  // line 3's last field becomes "…x"
    std::istringstream s(bad);
    try {
      io::read_dov_line(s, "line.csv");
      FAIL();
    } catch (const ParseError& e) {
      EXPECT_EQ(e.context().file, "line.csv");
      EXPECT_EQ(e.context().line, 3);
      EXPECT_EQ(e.context().field, "truth_xi_arcsec");
    }
  }
  {
    std::string bad = csv;
    bad.replace(bad.find("lgu_23"), 6, "lgu_2x");
    std::istringstream s(bad);
    try {
      io::read_dov_line(s, "line.csv");
      FAIL();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("lgu_23"), std::string::npos) << e.what();
    }
  }
  {
    std::string bad = csv;
    bad.replace(bad.find(",truth_xi_arcsec"), 16, ",other");
    std::istringstream s(bad);
    EXPECT_THROW(io::read_dov_line(s, "line.csv"), InputError);
  }
}

TEST(DovFiles, ConfigAndRunner) {
  const auto dir = temp_dir("config");
  dov::Input in = small_line();
  // a non-orthogonal INS matrix at sample 10 (file line 13)
  in.samples[10].ins_body_to_nav *= 1.0 + 1e-5;
  write(dir / "line.csv", io::dov_line_csv(in));
  write(dir / "dov.yaml",
        "line: line.csv\n"
        "zeta: 0.07\n"
        "sigma_model_arcsec: 2.5\n"
        "sigma_obs_arcsec: 0.4\n"
        "initial:\n"
        "  phi_u_arcsec: 6\n"
        "  eps_u_deg_per_h: 0.01\n"
        "discretisation: published_first_order\n"
        "extraction: skew_symmetric\n"
        "statistics_start_s: 60\n");
  const io::DovConfig c = io::read_dov_config((dir / "dov.yaml").string());
  EXPECT_EQ(std::filesystem::path(c.line_path), dir / "line.csv");
  EXPECT_DOUBLE_EQ(c.options.model.zeta, 0.07);
  EXPECT_DOUBLE_EQ(c.options.model.sigma_model_rad, 2.5 * kAs);
  EXPECT_DOUBLE_EQ(c.options.sigma_obs_north_rad, 0.4 * kAs);
  EXPECT_DOUBLE_EQ(c.options.initial.phi_u_rad, 6.0 * kAs);
  EXPECT_DOUBLE_EQ(c.options.initial.phi_e_rad, 2.0 * kAs);  // default
  EXPECT_DOUBLE_EQ(c.options.initial.eps_u_rad_s, 0.01 * units::kDegree / 3600.0);
  EXPECT_EQ(c.options.discretisation, dov::DiscretisationMethod::PublishedFirstOrder);
  EXPECT_EQ(c.options.extraction, dov::Extraction::SkewSymmetric);
  EXPECT_DOUBLE_EQ(c.options.statistics_start_s, 60.0);
  try {
    io::run_dov(c);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::filesystem::path(e.context().file), dir / "line.csv");
    EXPECT_EQ(e.context().line, 13);
    EXPECT_EQ(e.context().field, "ins_11…ins_33");  // the CSV columns, not the Sample member
  }
  // a clean line runs
  write(dir / "line.csv", io::dov_line_csv(small_line()));
  const dov::Result r = io::run_dov(c);
  EXPECT_TRUE(r.summary.rms_smoothed.has_value());
  // a typo is an error at its line
  write(dir / "bad.yaml", "line: line.csv\nzeta: 0.05\nsigma_modl_arcsec: 3\n");
  try {
    io::read_dov_config((dir / "bad.yaml").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().line, 3) << e.what();
  }
  write(dir / "bad2.yaml", "line: line.csv\ndiscretisation: second_order\n");
  EXPECT_THROW(io::read_dov_config((dir / "bad2.yaml").string()), InputError);
  std::filesystem::remove_all(dir);
}

}  // namespace
