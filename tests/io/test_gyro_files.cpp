// Readers and writers of gyro files: the issue's schema, JSON as is, errors
// naming file, line and field, and write → read round trips.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/io/gyro_files.hpp"
#include "meridian/io/gyro_jobs.hpp"
#include "meridian/io/gyro_writers.hpp"
#include "meridian/gravity/egm_format.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/synthetic.hpp"

using namespace meridian;
namespace fs = std::filesystem;

namespace {
constexpr double kArcsec = units::kArcsecond;

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("meridian_io_" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    std::ofstream(p) << text;
    return p;
  }

 private:
  fs::path path_;
};

const char* kIssueExample = R"(instrument:
  scale_value_arcsec: 600        # tau
  torsion_ratio: 0.30            # lambda
station:
  latitude_deg: 34.2
determinations:
  - mode: non-tracking
    method: transit
    clamp_reading: "0 00 00"
    period_s: 440.0
    zero_position_div: 0.0
    crossings:
      - level_div: 0
        times_s: [50.934, 269.066, 490.934]
        first_direction: east
    reversals_div: [8.88, -9.12]
  - mode: tracking
    method: schuler
    reversals: ["359 41 12", "0 44 50", "359 42 04"]
)";

// Expect an InputError whose message contains every fragment.
template <class F>
void expect_error(F&& f, std::initializer_list<std::string> fragments) {
  try {
    f();
    ADD_FAILURE() << "no error thrown";
  } catch (const InputError& e) {
    for (const auto& s : fragments) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(GyroFiles, ReadsTheIssueSchema) {
  TempDir d;
  const auto f = io::read_gyro_reduce_file(d.write("obs.yaml", kIssueExample));
  EXPECT_NEAR(f.input.instrument.scale_value_rad / kArcsec, 600.0, 1e-9);
  EXPECT_NEAR(f.input.instrument.torsion_ratio->value, 0.30, 1e-15);
  EXPECT_NEAR(f.input.latitude_rad / units::kDegree, 34.2, 1e-12);
  ASSERT_EQ(f.input.determinations.size(), 2u);
  const auto& n = f.input.determinations[0];
  EXPECT_EQ(n.mode, gyro::Mode::NonTracking);
  ASSERT_TRUE(n.method);
  EXPECT_EQ(gyro::to_string(*n.method), "transit");
  ASSERT_EQ(n.nontracking.crossings.size(), 1u);
  EXPECT_EQ(n.nontracking.crossings[0].first_direction, +1);
  EXPECT_DOUBLE_EQ(n.nontracking.crossings[0].times_s[1], 269.066);
  EXPECT_NEAR(n.nontracking.period_s->value, 440.0, 0);
  EXPECT_TRUE(n.zero_position.has_value());
  const auto& t = f.input.determinations[1];
  EXPECT_EQ(t.mode, gyro::Mode::Tracking);
  EXPECT_NEAR(t.tracking.reversals_rad[1] / units::kDegree, 44 / 60.0 + 50 / 3600.0, 1e-12);
  EXPECT_EQ(f.lines.at("determinations[1]"), 17);
}

TEST(GyroFiles, ReadsJsonAsIs) {
  TempDir d;
  const char* json = R"({
	"instrument": {"scale_value_arcsec": 600, "torsion_ratio": 0.3},
	"station": {"latitude_deg": "34 12 00"},
	"determinations": [
		{"mode": "tracking", "method": "all", "reversals": [359.6866, 0.7472, 359.7011]}
	]
})";
  const auto f = io::read_gyro_reduce_file(d.write("obs.json", json));
  EXPECT_NEAR(f.input.latitude_rad / units::kDegree, 34.2, 1e-12);
  EXPECT_FALSE(f.input.determinations[0].method);  // "all"
  EXPECT_NEAR(f.input.determinations[0].tracking.reversals_rad[0] / units::kDegree, 359.6866, 1e-12);
}

TEST(GyroFiles, ErrorsNameFileLineAndField) {
  TempDir d;
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = kIssueExample;
    const auto pos = s.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    s.replace(pos, from.size(), to);
    return d.write("bad.yaml", s);
  };
  expect_error([&] { io::read_gyro_reduce_file(with("  scale_value_arcsec: 600", "  scale_value_mrad: 2.9")); },
               {"bad.yaml:", "instrument.scale_value_mrad", "unknown field"});
  expect_error([&] { io::read_gyro_reduce_file(with("[50.934, 269.066, 490.934]", "[50.934, 269.066, 269.0]")); },
               {"bad.yaml:14:", "determinations[0].crossings[0].times_s", "must increase"});
  expect_error([&] { io::read_gyro_reduce_file(with("\"359 41 12\"", "\"359 71 12\"")); },
               {"bad.yaml:19:", "determinations[1].reversals[0]", "minutes"});
  expect_error([&] { io::read_gyro_reduce_file(with("latitude_deg: 34.2", "latitude_deg: 80")); },
               {"bad.yaml:5:", "station.latitude_deg", "limit"});
  expect_error([&] { io::read_gyro_reduce_file(with("period_s: 440.0", "period_s: nan")); },
               {"bad.yaml:10:", "determinations[0].period_s", "finite"});
  expect_error([&] { io::read_gyro_reduce_file(with("first_direction: east", "first_direction: up")); },
               {"determinations[0].crossings[0].first_direction", "east or west"});
  expect_error([&] { io::read_gyro_reduce_file(with("    method: transit\n", "    method: transits\n")); },
               {"bad.yaml:8:", "determinations[0].method", "transits"});
  expect_error([&] { io::read_gyro_reduce_file(with("  torsion_ratio: 0.30            # lambda\n", "")); },
               {"instrument.torsion_ratio", "lambda"});
  expect_error([&] { io::read_gyro_reduce_file(with("station:\n  latitude_deg: 34.2\n", "")); },
               {"bad.yaml:", "station", "missing"});
  // Truncated file: YAML syntax error with a line.
  std::string truncated = kIssueExample;
  truncated = truncated.substr(0, truncated.find("\"359 42 04\""));
  expect_error([&] { io::read_gyro_reduce_file(d.write("trunc.yaml", truncated)); }, {"trunc.yaml:", "syntax"});
  expect_error([&] { io::read_gyro_reduce_file(d.write("empty.yaml", "\n\n")); }, {"empty.yaml", "empty"});
  EXPECT_THROW(io::read_gyro_reduce_file(d.write("none.yaml", "x").parent_path() / "missing.yaml"), IoError);
}

TEST(GyroFiles, CampaignWriteReadRoundTrip) {
  TempDir d;
  const auto sim = gyro::simulate_campaign(gyro::example_campaign_truth(), 5);
  const auto path = d.write("c.yaml", io::campaign_file_yaml(sim.input, "round trip\n"));
  const auto f = io::read_campaign_file(path);
  const auto& a = sim.input;
  const auto& b = f.campaign;
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.grid.zone, b.grid.zone);
  EXPECT_EQ(a.grid.ellipsoid.name, b.grid.ellipsoid.name);
  ASSERT_EQ(a.line.determinations.size(), b.line.determinations.size());
  ASSERT_TRUE(b.known_line);
  EXPECT_EQ(a.known_line->before.size(), b.known_line->before.size());
  for (std::size_t i = 0; i < a.line.determinations.size(); ++i) {
    const auto& x = a.line.determinations[i];
    const auto& y = b.line.determinations[i];
    EXPECT_EQ(x.mode, y.mode);
    EXPECT_NEAR(x.target_reading_rad->value, y.target_reading_rad->value, 1e-4 * kArcsec);
    EXPECT_NEAR(x.clamp_reading_rad, y.clamp_reading_rad, 1e-4 * kArcsec);
    ASSERT_EQ(x.nontracking.crossings.size(), y.nontracking.crossings.size());
    for (std::size_t c = 0; c < x.nontracking.crossings.size(); ++c)
      EXPECT_EQ(x.nontracking.crossings[c].times_s, y.nontracking.crossings[c].times_s);
    EXPECT_EQ(x.zero_before->reversals_div, y.zero_before->reversals_div);
    for (std::size_t r = 0; r < x.tracking.reversals_rad.size(); ++r)
      EXPECT_NEAR(x.tracking.reversals_rad[r], y.tracking.reversals_rad[r], 1e-4 * kArcsec);
  }
  EXPECT_NEAR(a.known_line->azimuth.value_rad.value, b.known_line->azimuth.value_rad.value, 1e-4 * kArcsec);
  EXPECT_NEAR(a.line.from.eta_rad->value, b.line.from.eta_rad->value, 1e-15);
}

TEST(GyroFiles, LocateErrorUsesInnermostRecordedField) {
  io::FieldLines lines{{"line.determinations", 40}, {"line.determinations[1]", 52}};
  InputError e("bad", {"", std::nullopt, "line.determinations[1].crossings[0].times_s"});
  io::locate_error(e, "c.yaml", lines);
  EXPECT_STREQ(e.what(), "c.yaml:52: line.determinations[1].crossings[0].times_s: bad");
  InputError e2("bad", {"", std::nullopt, "line.determinations[10]"});
  io::locate_error(e2, "c.yaml", lines);
  EXPECT_STREQ(e2.what(), "c.yaml:40: line.determinations[10]: bad");
}

TEST(GyroFiles, CampaignGravityModelBesideTheFile) {
  TempDir d;
  auto truth = gyro::example_campaign_truth();
  truth.give_eta = false;  // so the model is used
  const auto sim = gyro::simulate_campaign(truth, 5);
  gravity::write_egm_files(gravity::make_synthetic_model({30, 2, 1e-5}), d.write("m.txt", "").parent_path() / "m");
  std::string yaml = io::campaign_file_yaml(sim.input);
  const auto good = d.write("c.yaml", yaml + "gravity_model: {model: m.egm, eta_sigma_arcsec: 2}\n");
  // The reader names the model; it does not load it.
  const auto f = io::read_campaign_file(good);
  ASSERT_TRUE(f.campaign.gravity_model);
  EXPECT_EQ(f.campaign.gravity_model->source, "m.egm");
  EXPECT_EQ(f.campaign.gravity_model->lookup, (good.parent_path() / "m.egm").string());
  EXPECT_NEAR(f.campaign.gravity_model->sigma_eta_rad / kArcsec, 2.0, 1e-12);
  ASSERT_TRUE(f.campaign.line.from.height_m);
  EXPECT_NEAR(*f.campaign.line.from.height_m, 341.7, 1e-9);
  // Loaded once, shared between files.
  io::DeflectionModels models;
  const gyro::DeflectionModel& m = models.get(*f.campaign.gravity_model);
  EXPECT_NE(m.description.find("degree 30"), std::string::npos);
  EXPECT_NEAR(m.sigma_eta_rad / kArcsec, 2.0, 1e-12);
  EXPECT_NEAR(m.sigma_xi_rad / kArcsec, 1.5, 1e-12);  // the default
  EXPECT_EQ(&models.get(*f.campaign.gravity_model), &m);
  const auto job = io::run_campaign_file(good, &models);
  int noted = 0;
  for (const auto& n : job.result.notes)
    noted += n.find("from the gravity model " + m.description) != std::string::npos &&
             n.find("xi = ") != std::string::npos && n.find("eta = ") != std::string::npos;
  EXPECT_EQ(noted, 2);  // at the known station and at the station
  EXPECT_TRUE(job.result.chain.laplace_applied);
  // ξ is the model's plumb line, as η: the same as evaluating the model here.
  const auto& st = job.result.station;
  const gravity::GravityField field(gravity::make_synthetic_model({30, 2, 1e-5}));
  const auto v = field.evaluate(gravity::GeodeticPoint{st.lat_rad, st.lon_rad, 341.7});
  EXPECT_NEAR(m.deflection(st.lat_rad, st.lon_rad, 341.7).xi_rad, v.xi_astro_rad, 1e-15);
  EXPECT_NEAR(m.deflection(st.lat_rad, st.lon_rad, 341.7).eta_rad, v.eta_astro_rad, 1e-15);
  // Both components known and the heights of C and D given: the term is applied.
  EXPECT_TRUE(job.result.chain.zenith_term_applied);
  const auto xs =
      io::read_campaign_file(d.write("xs.yaml", yaml + "gravity_model: {model: m.egm, xi_sigma_arcsec: 2.5}\n"));
  EXPECT_NEAR(xs.campaign.gravity_model->sigma_xi_rad / kArcsec, 2.5, 1e-12);
  EXPECT_NEAR(xs.campaign.gravity_model->sigma_eta_rad / kArcsec, 1.5, 1e-12);
  // A model that cannot be found is reported at its line when the job runs.
  expect_error([&] { io::run_campaign_file(d.write("bad.yaml", yaml + "gravity_model: {model: nowhere.gfc}\n")); },
               {"bad.yaml:", "gravity_model.model", "not found"});
}

TEST(GyroFiles, CampaignXiAndZenithAngles) {
  TempDir d;
  auto truth = gyro::example_campaign_truth();
  truth.xi_station_rad = -6.0 * kArcsec;
  truth.xi_known_rad = 5.0 * kArcsec;
  auto sim = gyro::simulate_campaign(truth, 5);
  sim.input.line.zenith_angle_rad = (110 * 3600 + 12 * 60 + 5.5) * kArcsec;
  sim.input.known_line->zenith_angle_rad = (88 * 3600 + 1 * 60 + 2) * kArcsec;
  const std::string yaml = io::campaign_file_yaml(sim.input);
  const auto f = io::read_campaign_file(d.write("c.yaml", yaml));
  const auto& a = sim.input;
  const auto& b = f.campaign;
  ASSERT_TRUE(b.line.from.xi_rad);
  EXPECT_NEAR(b.line.from.xi_rad->value / kArcsec, -6.0, 1e-12);
  EXPECT_NEAR(b.line.from.xi_rad->sigma, a.line.from.xi_rad->sigma, 1e-15);
  ASSERT_TRUE(b.known_line->from.xi_rad);
  EXPECT_NEAR(b.known_line->from.xi_rad->value / kArcsec, 5.0, 1e-12);
  ASSERT_TRUE(b.line.zenith_angle_rad);
  EXPECT_NEAR(*b.line.zenith_angle_rad / kArcsec, 110 * 3600 + 12 * 60 + 5.5, 1e-4);
  ASSERT_TRUE(b.known_line->zenith_angle_rad);
  EXPECT_NEAR(*b.known_line->zenith_angle_rad / kArcsec, 88 * 3600 + 1 * 60 + 2, 1e-4);
  EXPECT_FALSE(b.line.to->xi_rad);
  // Written back the same.
  EXPECT_EQ(io::campaign_file_yaml(b), yaml);

  // As a surveyor writes it: zenith_angle in DMS or degrees beside from/to.
  auto with = [&](const std::string& from, const std::string& to) {
    const auto pos = yaml.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return d.write("bad.yaml", std::string(yaml).replace(pos, from.size(), to));
  };
  const auto deg = io::read_campaign_file(with("  zenith_angle: \"110 12 05.5000\"", "  zenith_angle: 95.5"));
  EXPECT_NEAR(*deg.campaign.line.zenith_angle_rad / units::kDegree, 95.5, 1e-12);
  expect_error([&] { io::read_campaign_file(with("  zenith_angle: \"110 12 05.5000\"", "  zenith_angle: 5")); },
               {"bad.yaml:", "line.zenith_angle", "no usable azimuth"});
  expect_error([&] { io::read_campaign_file(with("  zenith_angle: \"110 12 05.5000\"", "  zenith_angle: 179.9")); },
               {"bad.yaml:", "line.zenith_angle"});
  expect_error([&] { io::read_campaign_file(with("    xi_arcsec: -6\n", "    xi_arcsec: -3000\n")); },
               {"bad.yaml:", "line.from.xi_arcsec", "0.01 rad"});
  expect_error([&] { io::read_campaign_file(with("    xi_arcsec: -6\n", "")); },
               {"bad.yaml:", "line.from", "xi_sigma_arcsec given without xi_arcsec"});
  // The job applies the term for both lines and names the booked angles.
  const auto job = io::run_campaign_file(d.write("c2.yaml", yaml));
  EXPECT_TRUE(job.result.chain.zenith_term_applied);
  int booked = 0;
  for (const auto& n : job.result.notes) booked += n.find("booked (zenith_angle)") != std::string::npos;
  EXPECT_EQ(booked, 2);
}
