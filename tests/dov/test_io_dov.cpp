// io_dov: the line CSV round trip (write → read gives the same doubles and the same result),
// errors naming file:line:column, the configuration and the runner's error location.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "dov_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/io/gravity_egm.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/io/gravity_model_lookup.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/io/dov_files.hpp"
#include "meridian/io/dov_jobs.hpp"
#include "meridian/io/dov_writers.hpp"

namespace {

using namespace meridian;
using meridian_test::kAs;
using meridian_test::write;

std::filesystem::path temp_dir(const std::string& name) {
  return meridian_test::temp_dir("io_dov_" + name);
}

dov::Input small_line() {
  dov::SimulationOptions so;
  so.duration_s = 120.0;  // these cases run under ASan + UBSan too
  so.seed = 8;
  return dov::simulate(so);
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
    // a latitude beyond 90° (found by fuzz_dov_line): the reader names it, line and column
    dov::Input in = small_line();
    in.samples[2].lat_rad = 1.0;  // then made 91° in the text below
    std::string bad = io::dov_line_csv(in);
    const std::string written = fmt::format("{:.17g}", 1.0 / units::kDegree);
    ASSERT_NE(bad.find(written), std::string::npos);
    bad.replace(bad.find(written), written.size(), "91");
    std::istringstream s(bad);
    try {
      io::read_dov_line(s, "line.csv");
      FAIL();
    } catch (const InputError& e) {
      EXPECT_EQ(e.context().line, 5) << e.what();  // the comment, the header, samples 0 and 1
      EXPECT_EQ(e.context().field, "lat_deg") << e.what();
    }
  }
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
  // the transport rate: off by default, on with its baseline, a baseline alone is an error
  EXPECT_FALSE(c.options.transport_rate);
  write(dir / "tr.yaml", "line: line.csv\ntransport_rate: true\ntransport_rate_baseline_s: 30\n");
  const io::DovConfig tr = io::read_dov_config((dir / "tr.yaml").string());
  EXPECT_TRUE(tr.options.transport_rate);
  EXPECT_DOUBLE_EQ(tr.options.transport_rate_baseline_s, 30.0);
  EXPECT_FALSE(io::run_dov(tr).notes.empty());
  // booleans: YAML 1.2's true/True/TRUE and 1.1's yes/no; anything else names what is allowed
  for (const char* yes : {"True", "TRUE", "yes"}) {
    write(dir / "b.yaml", std::string("line: line.csv\ntransport_rate: ") + yes + "\n");
    EXPECT_TRUE(io::read_dov_config((dir / "b.yaml").string()).options.transport_rate) << yes;
  }
  write(dir / "b.yaml", "line: line.csv\ntransport_rate: 1\n");
  try {
    io::read_dov_config((dir / "b.yaml").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected true or false (or yes, no), got \"1\""),
              std::string::npos)
        << e.what();
  }
  // a key without a value is an error at the key's line, never the default (trial finding)
  for (const char* empty : {"zeta:\n", "zeta: ~\n", "zeta: null\n", "initial:\n"}) {
    write(dir / "e.yaml", std::string("line: line.csv\nsigma_model_arcsec: 3\n") + empty);
    try {
      io::read_dov_config((dir / "e.yaml").string());
      FAIL() << empty;
    } catch (const InputError& e) {
      EXPECT_EQ(e.context().line, 3) << e.what();
      EXPECT_NE(std::string(e.what()).find("has no value"), std::string::npos) << e.what();
    }
  }
  write(dir / "bad3.yaml", "line: line.csv\ntransport_rate_baseline_s: 30\n");
  try {
    io::read_dov_config((dir / "bad3.yaml").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().line, 2) << e.what();
  }
  std::filesystem::remove_all(dir);
}

// The line CSV without its model columns (as a user brings a line and names a model).
std::string without_model_columns(const std::string& csv) {
  std::istringstream in(csv);
  std::string out, row;
  int eta = -1, xi = -1;
  while (std::getline(in, row)) {
    if (row.empty() || row[0] == '#') {
      out += row + "\n";
      continue;
    }
    std::vector<std::string> f;
    std::stringstream ss(row);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    if (eta < 0)
      for (int i = 0; i < static_cast<int>(f.size()); ++i) {
        if (f[static_cast<std::size_t>(i)] == "model_eta_arcsec") eta = i;
        if (f[static_cast<std::size_t>(i)] == "model_xi_arcsec") xi = i;
      }
    std::string kept;
    for (int i = 0; i < static_cast<int>(f.size()); ++i)
      if (i != eta && i != xi) kept += (kept.empty() ? "" : ",") + f[static_cast<std::size_t>(i)];
    out += kept + "\n";
  }
  return out;
}

// The InputError of running the configuration at `config`; a test failure (and an empty error)
// when it runs or throws anything else.
InputError run_error(const std::filesystem::path& config) {
  try {
    io::run_dov(io::read_dov_config(config.string()));
    ADD_FAILURE() << config << " ran without an InputError";
  } catch (const InputError& e) {
    return e;
  }
  return InputError("");
}

TEST(DovFiles, ColumnsTheLineDoesNotUseAreWarnedAbout) {
  const auto dir = temp_dir("extra");
  const std::string csv = io::dov_line_csv(small_line());
  // The same line with two more columns: a status flag and a misspelt truth column.
  std::string extra;
  bool header = true;
  std::size_t start = 0;
  while (start < csv.size()) {
    const std::size_t end = csv.find('\n', start);
    std::string line = csv.substr(start, end - start);
    if (!line.empty() && line[0] != '#') {
      line += header ? ",status,truth_eta_arcsecs" : ",0,1.5";
      header = false;
    }
    extra += line + "\n";
    start = end == std::string::npos ? csv.size() : end + 1;
  }
  write(dir / "clean.csv", csv);
  write(dir / "extra.csv", extra);
  write(dir / "clean.yaml", "line: clean.csv\n");
  write(dir / "extra.yaml", "line: extra.csv\n");
  const dov::Result a = io::run_dov(io::read_dov_config((dir / "clean.yaml").string()));
  const dov::Result b = io::run_dov(io::read_dov_config((dir / "extra.yaml").string()));
  for (const auto& w : a.warnings) EXPECT_EQ(w.find("not used"), std::string::npos) << w;
  const auto it = std::find_if(b.warnings.begin(), b.warnings.end(), [](const std::string& w) {
    return w.find("not used") != std::string::npos;
  });
  ASSERT_NE(it, b.warnings.end());
  EXPECT_NE(it->find("extra.csv"), std::string::npos) << *it;
  EXPECT_NE(it->find("status, truth_eta_arcsecs are not used"), std::string::npos) << *it;
  // The columns change nothing else.
  ASSERT_EQ(a.epochs.size(), b.epochs.size());
  EXPECT_EQ(a.epochs.back().smoothed.eta_rad, b.epochs.back().smoothed.eta_rad);
  EXPECT_EQ(b.warnings.size(), a.warnings.size() + 1);
}

// A synthetic gravity model to `degree`, written as the EGM files of `stem` (stem.egm, …).
void write_synthetic_model(const std::filesystem::path& stem, int degree) {
  gravity::SyntheticModelOptions mo;
  mo.max_degree = degree;
  mo.seed = 5;
  io::write_egm_files(gravity::make_synthetic_model(mo), stem);
}

TEST(DovFiles, GravityModelGivesTheModelValues) {
  const auto dir = temp_dir("gravity");
  write_synthetic_model(dir / "syn", 180);
  const dov::Input in = small_line();
  write(dir / "line.csv", without_model_columns(io::dov_line_csv(in)));
  write(dir / "dov.yaml", "line: line.csv\ngravity_model: {model: syn.egm, max_degree: 120}\n");
  const io::DovConfig c = io::read_dov_config((dir / "dov.yaml").string());
  ASSERT_TRUE(c.gravity_model.has_value());
  EXPECT_EQ(c.gravity_model->max_degree, 120);
  const dov::Result r = io::run_dov(c);
  ASSERT_EQ(r.epochs.size(), in.samples.size());
  // η_G, ξ_G are the astronomic deflection of the truncated model at each sample (not ξ for η)
  const gravity::GravityField field(
      io::load_model((dir / "syn.egm").string(), gravity::Truncation{120, -1}));
  double largest_arcsec = 0.0, max_diff_arcsec = 0.0;
  for (std::size_t k = 0; k < in.samples.size(); k += 10) {
    const dov::Sample& s = in.samples[k];
    const auto v = field.evaluate({s.lat_rad, s.lon_rad, s.height_m}, gravity::Quantities::Deflection);
    largest_arcsec = std::max({largest_arcsec, std::abs(v.eta_astro_rad) / kAs, std::abs(v.xi_astro_rad) / kAs});
    max_diff_arcsec = std::max({max_diff_arcsec, std::abs(r.epochs[k].model_eta_rad - v.eta_astro_rad) / kAs,
                                std::abs(r.epochs[k].model_xi_rad - v.xi_astro_rad) / kAs});
  }
  EXPECT_GT(largest_arcsec, 0.1);        // a model that deflects, so a swap would show
  EXPECT_LT(max_diff_arcsec, 2e-4);      // the track tolerance, 1e-4″
  bool noted = false;
  for (const auto& n : r.notes) noted = noted || n.find("degree 120") != std::string::npos;
  EXPECT_TRUE(noted);
  // exactly one source of model values: columns and a model, or neither, are errors
  write(dir / "both.csv", io::dov_line_csv(in));
  write(dir / "both.yaml", "line: both.csv\nzeta: 0.05\ngravity_model: {model: syn.egm}\n");
  const InputError both = run_error(dir / "both.yaml");
  EXPECT_EQ(std::filesystem::path(both.context().file), dir / "both.yaml");
  EXPECT_EQ(both.context().line, 3) << both.what();
  EXPECT_NE(std::string(both.what()).find("one source"), std::string::npos) << both.what();
  write(dir / "none.yaml", "line: line.csv\n");
  const InputError none = run_error(dir / "none.yaml");
  EXPECT_EQ(std::filesystem::path(none.context().file), dir / "line.csv") << none.what();
  EXPECT_NE(std::string(none.what()).find("no gravity_model"), std::string::npos) << none.what();
  // a model that is not found: the configuration's line of the key
  write(dir / "missing.yaml", "line: line.csv\ngravity_model:\n  model: no-such-model-xyz\n");
  const InputError missing = run_error(dir / "missing.yaml");
  EXPECT_EQ(std::filesystem::path(missing.context().file), dir / "missing.yaml") << missing.what();
  EXPECT_EQ(missing.context().line, 3) << missing.what();
  std::filesystem::remove_all(dir);
}

// A sample the model cannot be evaluated at (a height beyond its range) is named by its own
// line, not by the first sample of the block the model values are computed for; a line too short
// to smooth is named by the line file, not the configuration; Result::origin names the three.
TEST(DovFiles, ErrorsOfTheModelPointsAndTheWholeLineNameTheLineFile) {
  const auto dir = temp_dir("places");
  write_synthetic_model(dir / "syn", 24);
  dov::Input in = small_line();
  in.samples[50].height_m = 2.0e7;  // gravity::kMaxHeight_m is 1e7
  write(dir / "line.csv", without_model_columns(io::dov_line_csv(in)));
  write(dir / "dov.yaml", "line: line.csv\ngravity_model: {model: syn.egm}\n");
  const InputError high = run_error(dir / "dov.yaml");
  EXPECT_EQ(std::filesystem::path(high.context().file), dir / "line.csv") << high.what();
  EXPECT_EQ(high.context().line, 53) << high.what();  // comment, header, samples 0 … 50
  EXPECT_EQ(high.context().field, "lat_deg, lon_deg, height_m") << high.what();
  EXPECT_NE(std::string(high.what()).find("height"), std::string::npos) << high.what();

  const std::string csv = io::dov_line_csv(small_line());
  const std::size_t first_sample = csv.find('\n', csv.find('\n') + 1) + 1;
  write(dir / "short.csv", csv.substr(0, csv.find('\n', first_sample) + 1));  // one sample
  write(dir / "short.yaml", "line: short.csv\n");
  const InputError short_line = run_error(dir / "short.yaml");
  EXPECT_EQ(std::filesystem::path(short_line.context().file), dir / "short.csv") << short_line.what();
  EXPECT_FALSE(short_line.context().line.has_value());
  EXPECT_NE(std::string(short_line.what()).find("at least 2 samples, has 1"), std::string::npos)
      << short_line.what();

  write(dir / "good.csv", without_model_columns(io::dov_line_csv(small_line())));
  write(dir / "good.yaml", "line: good.csv\ngravity_model: {model: syn.egm, max_degree: 12}\n");
  const dov::Result r = io::run_dov_stream(io::read_dov_config((dir / "good.yaml").string()), {});
  EXPECT_EQ(std::filesystem::path(r.origin.input), dir / "good.yaml");
  EXPECT_EQ(std::filesystem::path(r.origin.line), dir / "good.csv");
  EXPECT_EQ(r.origin.model, "syn.egm (to degree 12)");
  EXPECT_TRUE(r.epochs.empty());  // no epochs kept unless asked
  std::filesystem::remove_all(dir);
}

// A line CSV with the matrices replaced by heading, pitch, roll: the angles of each matrix are
// taken here from the written-out form of dov/euler.hpp (θ = asin C₃₂, ψ = atan2(C₁₂, C₂₂),
// φ = atan2(−C₃₁, C₃₃)), so reading them back must give the same matrices and results.
TEST(DovFiles, EulerAngleColumnsGiveTheSameMatricesAndResults) {
  const auto dir = temp_dir("euler");
  const dov::Input in = small_line();
  const std::string csv = io::dov_line_csv(in);
  std::istringstream lines(csv);
  std::string out, l;
  bool header = true;
  while (std::getline(lines, l)) {
    if (l.empty() || l[0] == '#') continue;
    std::vector<std::string> f;
    std::istringstream ls(l);
    for (std::string c; std::getline(ls, c, ',');) f.push_back(c);
    // fields: 5 position/time, 9 lgu, 9 ins, then the rest
    std::string row = fmt::format("{},{},{},{},{}", f[0], f[1], f[2], f[3], f[4]);
    for (int a = 0; a < 2; ++a) {
      if (header) {
        const char* p = a == 0 ? "lgu" : "ins";
        row += fmt::format(",{0}_heading_deg,{0}_pitch_deg,{0}_roll_deg", p);
        continue;
      }
      const auto c = [&](int i, int j) { return std::stod(f[5 + 9 * a + 3 * (i - 1) + (j - 1)]); };
      const double deg = units::kDegree;
      // fixed notation: angle columns take decimal degrees or DMS, not exponents (core/dms.hpp)
      row += fmt::format(",{:.15f},{:.15f},{:.15f}", std::atan2(c(1, 2), c(2, 2)) / deg,
                         std::asin(c(3, 2)) / deg, std::atan2(-c(3, 1), c(3, 3)) / deg);
    }
    for (std::size_t i = 23; i < f.size(); ++i) row += "," + f[i];
    out += row + "\n";
    header = false;
  }
  std::istringstream euler_in(out);
  const io::DovLine euler = io::read_dov_line(euler_in, "euler.csv");
  ASSERT_EQ(euler.samples.size(), in.samples.size());
  for (std::size_t k = 0; k < in.samples.size(); k += 7) {
    EXPECT_LT((euler.samples[k].lgu_body_to_nav - in.samples[k].lgu_body_to_nav).cwiseAbs().maxCoeff(),
              1e-15);
    EXPECT_LT((euler.samples[k].ins_body_to_nav - in.samples[k].ins_body_to_nav).cwiseAbs().maxCoeff(),
              1e-15);
  }
  write(dir / "matrix.csv", csv);
  write(dir / "euler.csv", out);
  write(dir / "matrix.yaml", "line: matrix.csv\n");
  write(dir / "euler.yaml", "line: euler.csv\n");
  const dov::Result a = io::run_dov(io::read_dov_config((dir / "matrix.yaml").string()));
  const dov::Result b = io::run_dov(io::read_dov_config((dir / "euler.yaml").string()));
  for (std::size_t k = 0; k < a.epochs.size(); k += 11)
    EXPECT_NEAR(a.epochs[k].smoothed.xi_rad / kAs, b.epochs[k].smoothed.xi_rad / kAs, 1e-6);
  // an Euler line's attitude error names its angle columns
  std::string bad = out;
  const std::size_t line4 = [&] {
    std::size_t pos = 0;
    for (int i = 0; i < 4; ++i) pos = bad.find('\n', pos) + 1;  // header + 3 samples
    return pos;
  }();
  std::size_t at = line4;
  for (int comma = 0; comma < 8; ++comma) at = bad.find(',', at) + 1;  // ins_heading_deg
  bad.replace(at, bad.find(',', at) - at, "45");  // 45° off: beyond the 1° limit
  write(dir / "euler.csv", bad);
  try {
    io::run_dov(io::read_dov_config((dir / "euler.yaml").string()));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().line, 5) << e.what();
    EXPECT_EQ(e.context().field,
              "lgu_heading_deg, lgu_pitch_deg, lgu_roll_deg, ins_heading_deg, ins_pitch_deg, "
              "ins_roll_deg")
        << e.what();
  }
  // both forms of one attitude, or an incomplete set of angles: errors at the header
  std::string both = csv;
  both.replace(both.find("lgu_11"), 6, "lgu_heading_deg,lgu_pitch_deg,lgu_roll_deg,lgu_11");
  std::istringstream both_in(both);
  EXPECT_THROW(io::read_dov_line(both_in, "both.csv"), InputError);
  std::string partial = out;
  partial.replace(partial.find("ins_roll_deg"), 12, "ins_rol_deg");
  std::istringstream partial_in(partial);
  EXPECT_THROW(io::read_dov_line(partial_in, "partial.csv"), InputError);
  std::filesystem::remove_all(dir);
}

}  // namespace
