// Readers and writers of gyro files: the issue's schema, JSON as is, errors
// naming file, line and field, and write → read round trips.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/io/gyro_files.hpp"
#include "meridian/io/source_map.hpp"
#include "meridian/io/gyro_jobs.hpp"
#include "meridian/io/gyro_simulate.hpp"
#include "meridian/io/gyro_writers.hpp"
#include "meridian/io/gravity_egm.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/synthetic.hpp"

using namespace meridian;
using meridian::AngleUnit;
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

// Text fields go on into JSON and HTML: bytes that are not UTF-8 (a name
// saved as Latin-1) are an input error at the field's line, not an internal
// error when the JSON is written (issue 16).
TEST(GyroFiles, TextThatIsNotUtf8IsNamedWithFileAndLine) {
  TempDir d;
  std::string s = kIssueExample;
  s.replace(s.find("instrument:\n"), 12, "instrument:\n  name: \"K\xF6ln\"\n");
  expect_error([&] { io::read_gyro_reduce_file(d.write("latin1.yaml", s)); },
               {"latin1.yaml:2:", "instrument.name", "not UTF-8", "0xF6", "K\\xF6ln"});
  // The same name in UTF-8 is read as it is.
  std::string u = kIssueExample;
  u.replace(u.find("instrument:\n"), 12, "instrument:\n  name: \"K\xC3\xB6ln\"\n");
  EXPECT_NO_THROW(io::read_gyro_reduce_file(d.write("utf8.yaml", u)));
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

TEST(GyroFiles, SourceMapUsesInnermostRecordedField) {
  io::SourceMap book;
  book.add_document("c.yaml", io::FieldLines{{"line.determinations", 40}, {"line.determinations[1]", 52}});
  InputError e("bad", {"", std::nullopt, "line.determinations[1].crossings[0].times_s"});
  book.locate(e);
  EXPECT_STREQ(e.what(), "c.yaml:52: line.determinations[1].crossings[0].times_s: bad");
  InputError e2("bad", {"", std::nullopt, "line.determinations[10]"});
  book.locate(e2);
  EXPECT_STREQ(e2.what(), "c.yaml:40: line.determinations[10]: bad");
}

TEST(GyroFiles, CampaignGravityModelBesideTheFile) {
  TempDir d;
  auto truth = gyro::example_campaign_truth();
  truth.give_eta = false;  // so the model is used
  const auto sim = gyro::simulate_campaign(truth, 5);
  io::write_egm_files(gravity::make_synthetic_model({30, 2, 1e-5}), d.write("m.txt", "").parent_path() / "m");
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

// --- Field-crew habits: angle_unit, stopwatch times, errors at the wrong value's line.

namespace {
// The issue's example booked in `unit`: clamp and target reading `clamp`, the
// tracking run's reversals `reversals` (lines: clamp 10, target 11, reversals 21).
std::string reduce_file_in(const std::string& unit, const std::string& clamp,
                           const std::string& reversals) {
  std::string s = "angle_unit: " + unit + "\n" + kIssueExample;
  const std::string c = "clamp_reading: \"0 00 00\"\n";
  s.replace(s.find(c), c.size(), "clamp_reading: " + clamp + "\n    target_reading: " + clamp + "\n");
  const std::string r = "[\"359 41 12\", \"0 44 50\", \"359 42 04\"]";
  s.replace(s.find(r), r.size(), reversals);
  return s;
}

// Line of the first error thrown by `f`, and its text.
template <class F>
std::pair<int, std::string> error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return {e.context().line.value_or(-1), e.what()};
  }
  return {0, "no error"};
}
}  // namespace

TEST(GyroFiles, AngleUnitAppliesToCircleAnglesOnly) {
  TempDir d;
  // 359°41'12" = 359.686667° = 399.651852 gon = 359.4112 in ddd.mmss; 0°44'50" likewise.
  const double r0 = 359.0 + 41.0 / 60 + 12.0 / 3600, r1 = 44.0 / 60 + 50.0 / 3600;
  const double clamp = 0.5 + 30.0 / 3600;  // 0°30'30"
  struct Case {
    const char* unit;
    const char* clamp;
    const char* reversals;
    AngleUnit expect;
    double tol_deg;
  } cases[] = {
      {"dms", "\"0 30 30\"", "[\"359 41 12\", \"0 44 50\", \"359 42 04\"]", AngleUnit::Dms, 1e-12},
      {"deg", "0.508333333333", "[359.686666666667, \"0.747222222222°\", 359.701111111111]",
       AngleUnit::Degrees, 1e-11},
      {"gon", "0.564814814815", "[399.651851851852, \"0.830246913580 gon\", 399.668024691358]",
       AngleUnit::Gon, 1e-11},
      {"ddd.mmss", "0.3030", "[359.4112, \"0.4450\", 359.4204]", AngleUnit::DddMmss, 1e-12},
  };
  for (const auto& c : cases) {
    const auto f =
        io::read_gyro_reduce_file(d.write("u.yaml", reduce_file_in(c.unit, c.clamp, c.reversals)));
    EXPECT_EQ(f.input.angle_unit, c.expect) << c.unit;
    const auto& n = f.input.determinations[0];
    EXPECT_NEAR(n.clamp_reading_rad / units::kDegree, clamp, c.tol_deg) << c.unit;
    EXPECT_NEAR(n.target_reading_rad->value / units::kDegree, clamp, c.tol_deg) << c.unit;
    const auto& r = f.input.determinations[1].tracking.reversals_rad;
    EXPECT_NEAR(r[0] / units::kDegree, r0, c.tol_deg) << c.unit;
    EXPECT_NEAR(r[1] / units::kDegree, r1, c.tol_deg) << c.unit;
    // latitude_deg says degrees in its name: 34.2 stays 34.2° in a gon or ddd.mmss book.
    EXPECT_NEAR(f.input.latitude_rad / units::kDegree, 34.2, 1e-12) << c.unit;
  }
}

TEST(GyroFiles, AngleUnitIsNeverGuessedAndErrorsNameTheLine) {
  TempDir d;
  // DMS text in a gon book is refused, not reinterpreted.
  auto [line, what] = error_of([&] {
    io::read_gyro_reduce_file(
        d.write("g.yaml", reduce_file_in("gon", "\"0 30 30\"", "[1, 2, 1.5]")));
  });
  EXPECT_EQ(line, 10) << what;
  EXPECT_NE(what.find("determinations[0].clamp_reading"), std::string::npos) << what;
  EXPECT_NE(what.find("angle_unit is gon"), std::string::npos) << what;
  // 123.4599 is no ddd.mmss angle (99 seconds); the 4th reversal on its own line.
  std::tie(line, what) = error_of([&] {
    io::read_gyro_reduce_file(
        d.write("m.yaml", reduce_file_in("ddd.mmss", "0.3030",
                                         "\n      - 359.4112\n      - 0.4450\n"
                                         "      - 359.4204\n      - 123.4599")));
  });
  EXPECT_EQ(line, 25) << what;
  EXPECT_NE(what.find("determinations[1].reversals[3]: cannot read angle \"123.4599\" as ddd.mmss"),
            std::string::npos)
      << what;
  EXPECT_NE(what.find("seconds 99 must be below 60"), std::string::npos) << what;
  std::tie(line, what) = error_of([&] {
    io::read_gyro_reduce_file(d.write("x.yaml", reduce_file_in("grads", "1", "[1, 2, 1.5]")));
  });
  EXPECT_EQ(line, 1);
  EXPECT_NE(
      what.find("angle_unit: unknown angle unit \"grads\" (expected dms, deg, gon or ddd.mmss)"),
      std::string::npos)
      << what;
}

TEST(GyroFiles, StopwatchTimesAsMinutesAndSeconds) {
  TempDir d;
  std::string text = kIssueExample;
  auto replace = [&](const std::string& from, const std::string& to) {
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
  };
  // 50.934 s = 0:50.934; 269.066 s = 4:29.066; 490.934 s = 8:10.934; 440 s = 7:20.
  replace("[50.934, 269.066, 490.934]", "[\"0:50.934\", 4:29.066, \"8'10.934\\\"\"]");
  replace("period_s: 440.0", "period_s: \"7:20\"");
  replace("reversals_div: [8.88, -9.12]",
          "reversals_div: [8.88, -9.12]\n    reversal_times_s: [\"2:40\", \"0:06:20.5\"]\n"
          "    zero_position_sigma_div: 0.01");
  const auto f = io::read_gyro_reduce_file(d.write("t.yaml", text));
  const auto& o = f.input.determinations[0].nontracking;
  EXPECT_EQ(o.crossings[0].times_s, (std::vector<double>{50.934, 269.066, 490.934}));
  EXPECT_DOUBLE_EQ(o.period_s->value, 440.0);
  EXPECT_EQ(o.reversal_times_s, (std::vector<double>{160.0, 380.5}));
  // Seconds >= 60, a sign or garbage: a ParseError at the line, naming the element.
  for (const char* bad : {"4:69.066", "-4:29.066", "4:29.0.66", "four"}) {
    std::string b = text;
    b.replace(b.find("4:29.066"), 8, bad);
    try {
      io::read_gyro_reduce_file(d.write("b.yaml", b));
      ADD_FAILURE() << bad;
    } catch (const ParseError& e) {
      EXPECT_EQ(e.context().line, 14) << e.what();
      EXPECT_EQ(e.context().field, "determinations[0].crossings[0].times_s[1]") << e.what();
      EXPECT_NE(std::string(e.what()).find(std::string("cannot read time \"") + bad),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(GyroFiles, ErrorsAtTheLineOfTheWrongElement) {
  TempDir d;
  std::string text = kIssueExample;
  // A block sequence of times: the time out of order is reported at its own line (16).
  text.replace(text.find("[50.934, 269.066, 490.934]"), 26,
               "\n          - 50.934\n          - 269.066\n          - 269.0");
  auto [line, what] = error_of([&] { io::read_gyro_reduce_file(d.write("b.yaml", text)); });
  EXPECT_EQ(line, 17) << what;
  EXPECT_NE(what.find("determinations[0].crossings[0].times_s[2]: times must increase"),
            std::string::npos)
      << what;

  // Lines of every element are recorded, in block and flow sequences, so a
  // processing error naming an element is located at it.
  const char* tracking = R"(instrument: {scale_value_arcsec: 600, torsion_ratio: 0.3}
station: {latitude_deg: 34.2}
determinations:
  - mode: tracking
    reversals:
      - "359 41 12"
      - "0 44 50"
      - "359 42 04"
      - "359 40 00"
    zero_position:
      before: {reversals_div: [4.2, -3.7,
                               3.9, -3.5]}
)";
  const auto f = io::read_gyro_reduce_file(d.write("t.yaml", tracking));
  io::SourceMap book;
  book.add_document(f.file, f.lines);
  for (const auto& [field, expect] : std::vector<std::pair<std::string, int>>{
           {"determinations[0].reversals[3]", 9},
           {"determinations[0].reversals[0]", 6},
           {"determinations[0].zero_position.before.reversals_div[3]", 12},
           {"determinations[0].zero_position.before.reversals_div[1]", 11}}) {
    InputError e("bad", {"", std::nullopt, field});
    book.locate(e);
    EXPECT_EQ(e.context().line, expect) << field;
  }
  // And end to end: a non-tracking reversal that does not alternate, 4th of a block list.
  std::string nt = kIssueExample;
  nt.replace(nt.find("reversals_div: [8.88, -9.12]"), 28,
             "reversals_div:\n      - 8.88\n      - -9.12\n      - 8.7\n      - 8.9");
  std::tie(line, what) = error_of([&] { io::run_reduce_file(d.write("nt.yaml", nt)); });
  EXPECT_EQ(line, 20) << what;
  EXPECT_NE(what.find("determinations[0].reversals_div[3]"), std::string::npos) << what;
}

TEST(GyroFiles, TabIndentationIsNamed) {
  TempDir d;
  auto [line, what] = error_of([&] {
    io::read_gyro_reduce_file(
        d.write("tab.yaml", "instrument:\n  scale_value_arcsec: 600\n\ttorsion_ratio: 0.3\n"));
  });
  EXPECT_EQ(line, 3);
  EXPECT_NE(what.find("tab.yaml:3: tabs are not allowed for indentation (line 3)"),
            std::string::npos)
      << what;
  std::tie(line, what) = error_of([&] {
    io::read_gyro_reduce_file(d.write("tab2.yaml", "instrument:\n\tscale_value_arcsec: 600\n"));
  });
  EXPECT_NE(what.find("tab2.yaml:2: tabs are not allowed for indentation (line 2)"),
            std::string::npos)
      << what;
  // A tab elsewhere is no indentation: a comment after a value, a blank line.
  const auto f =
      io::read_gyro_reduce_file(d.write("ok.yaml", std::string(kIssueExample) + "\t\n# end\t\n"));
  EXPECT_EQ(f.input.determinations.size(), 2u);
  // A syntax error in a JSON file indented with tabs is a syntax error.
  std::tie(line, what) = error_of([&] {
    io::read_gyro_reduce_file(
        d.write("bad.json", "{\n\t\"instrument\": {\"scale_value_arcsec\": 600,,}\n}\n"));
  });
  EXPECT_EQ(what.find("tabs"), std::string::npos) << what;
}

TEST(GyroFiles, WritersKeepTheBooksAngleUnit) {
  TempDir d;
  const auto sim = gyro::simulate_campaign(gyro::example_campaign_truth(), 7);
  for (AngleUnit unit : {AngleUnit::Dms, AngleUnit::Degrees, AngleUnit::Gon, AngleUnit::DddMmss}) {
    gyro::CampaignInput a = sim.input;
    a.angle_unit = unit;
    const std::string yaml = io::campaign_file_yaml(a);
    EXPECT_EQ(yaml.find("angle_unit:") != std::string::npos, unit != AngleUnit::Dms);
    const auto b = io::read_campaign_file(d.write("c.yaml", yaml)).campaign;
    EXPECT_EQ(b.angle_unit, unit);
    EXPECT_NEAR(a.known_line->azimuth.value_rad.value, b.known_line->azimuth.value_rad.value,
                1e-4 * kArcsec);
    for (std::size_t i = 0; i < a.line.determinations.size(); ++i) {
      const auto& x = a.line.determinations[i];
      const auto& y = b.line.determinations[i];
      EXPECT_NEAR(x.target_reading_rad->value, y.target_reading_rad->value, 1e-4 * kArcsec);
      EXPECT_NEAR(x.clamp_reading_rad, y.clamp_reading_rad, 1e-4 * kArcsec);
      for (std::size_t r = 0; r < x.tracking.reversals_rad.size(); ++r)
        EXPECT_NEAR(x.tracking.reversals_rad[r], y.tracking.reversals_rad[r], 1e-4 * kArcsec);
    }
    // A signed instrument constant instead of the known line.
    a.known_line.reset();
    a.instrument_constant_rad = gyro::Uncertain{-25.4 * kArcsec, 5 * kArcsec};
    const auto c = io::read_campaign_file(d.write("e.yaml", io::campaign_file_yaml(a))).campaign;
    EXPECT_NEAR(c.instrument_constant_rad->value / kArcsec, -25.4, 1e-4);
    // And a reduce file.
    gyro::ReduceInput r;
    r.instrument = a.instrument;
    r.latitude_rad = 0.6;
    r.determinations = a.line.determinations;
    r.angle_unit = unit;
    const auto rr = io::read_gyro_reduce_file(d.write("r.yaml", io::reduce_file_yaml(r))).input;
    EXPECT_EQ(rr.angle_unit, unit);
    EXPECT_NEAR(rr.determinations[0].clamp_reading_rad, r.determinations[0].clamp_reading_rad,
                1e-4 * kArcsec);
  }
}

TEST(GyroFiles, TemplatesReadBack) {
  TempDir d;
  const std::string text = io::campaign_template_yaml();
  const auto c = io::read_campaign_file(d.write("t.yaml", text)).campaign;
  // The regulations' 3-2-3 programme, both modes, motor-off runs everywhere.
  ASSERT_TRUE(c.known_line);
  EXPECT_EQ(c.known_line->before.size(), 3u);
  EXPECT_EQ(c.line.determinations.size(), 2u);
  EXPECT_EQ(c.known_line->after.size(), 3u);
  int tracking = 0, nontracking = 0;
  for (const auto* list : {&c.known_line->before, &c.line.determinations, &c.known_line->after})
    for (const auto& x : *list) {
      (x.mode == gyro::Mode::Tracking ? tracking : nontracking) += 1;
      EXPECT_TRUE(x.zero_before && x.zero_after) << x.label;
      EXPECT_TRUE(x.target_reading_rad || !x.target_rounds.empty()) << x.label;
    }
  EXPECT_EQ(c.line.determinations[0].target_rounds.size(), 2u);  // rounds face left/right, before and after
  EXPECT_FALSE(c.record.observer.empty());
  EXPECT_EQ(tracking, 5);
  EXPECT_EQ(nontracking, 3);
  // Its stopwatch times are booked as m:ss.s: "0:34.8" = 34.8 s, "7:04.0" = 424 s.
  const auto& transit = c.known_line->before[1].nontracking;
  EXPECT_DOUBLE_EQ(transit.crossings[0].times_s[0], 34.8);
  EXPECT_DOUBLE_EQ(transit.crossings[0].times_s[1], 251.6);
  EXPECT_DOUBLE_EQ(transit.period_s->value, 424.0);
  EXPECT_EQ(c.angle_unit, AngleUnit::Dms);
  for (const char* mention :
       {"angle_unit", "ddd.mmss", "gon", "m:ss.s", "三、二、三", "first_direction"})
    EXPECT_NE(text.find(mention), std::string::npos) << mention;
  const auto r = io::read_gyro_reduce_file(d.write("r.yaml", io::reduce_template_yaml())).input;
  ASSERT_EQ(r.determinations.size(), 2u);
  EXPECT_EQ(r.determinations[0].mode, gyro::Mode::Tracking);
  EXPECT_EQ(r.determinations[1].mode, gyro::Mode::NonTracking);
  EXPECT_EQ(r.determinations[1].nontracking.crossings.size(), 3u);
  EXPECT_DOUBLE_EQ(r.determinations[1].nontracking.crossings[2].times_s[2], 493.0);  // "8:13.0"
}

TEST(GyroFiles, TolerancesAndRecordSheetRoundTrip) {
  TempDir d;
  auto sim = gyro::simulate_campaign(gyro::example_campaign_truth(), 5);
  sim.input.tolerances.determination_difference_rad = 25 * kArcsec;
  sim.input.tolerances.zero_position_limit_div = 0.4;
  sim.input.tolerances.orientation_mean_sigma_rad = 8 * kArcsec;
  sim.input.record.observer = "王工";
  sim.input.record.date = "2026-11-28";
  sim.input.instrument.serial = "0713";
  const std::string yaml = io::campaign_file_yaml(sim.input);
  const auto back = io::read_campaign_file(d.write("t.yaml", yaml)).campaign;
  EXPECT_NEAR(*back.tolerances.determination_difference_rad / kArcsec, 25, 1e-12);
  EXPECT_NEAR(*back.tolerances.zero_position_limit_div, 0.4, 1e-15);
  EXPECT_NEAR(*back.tolerances.orientation_mean_sigma_rad / kArcsec, 8, 1e-12);
  EXPECT_FALSE(back.tolerances.instrument_constant_max_rad);
  EXPECT_EQ(back.record.observer, "王工");
  EXPECT_EQ(back.record.date, "2026-11-28");
  EXPECT_EQ(back.instrument.serial, "0713");
  EXPECT_EQ(io::campaign_file_yaml(back), yaml);
}

TEST(GyroFiles, StochasticRunnerLocatesTheSeries) {
  // A book whose third determination's reversals fit (R2) exactly: the error is at the line of
  // its `reversals:` key (22), with the series' field.
  std::string book = kIssueExample;
  book += R"(  - mode: tracking
    label: flat
    reversals: ["0 00 10", "0 00 20", "0 00 10", "0 00 20", "0 00 10", "0 00 20", "0 00 10"]
)";
  TempDir d;
  const fs::path p = d.write("flat.yaml", book);
  try {
    io::run_stochastic_file(p);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().file, p.string());
    EXPECT_EQ(e.context().line, 22) << e.what();
    EXPECT_EQ(e.context().field, "determinations[2].reversals");
  }
  // No series of 6 readings: at the determinations (the line of their first element, 7).
  try {
    io::run_stochastic_file(d.write("short.yaml", kIssueExample));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().line, 7) << e.what();
    EXPECT_EQ(e.context().field, "determinations");
  }
}

TEST(GyroFiles, SimulateSettingsAreReadIntoWhatToSimulate) {
  io::SimulateSettings s;
  s.mode = "tracking";
  s.tau_arcsec = 300.0;
  s.latitude_deg = 45.0;
  s.centre = "1 00 00";
  s.sigma_tracking_arcsec = 6.0;
  s.noise = "markov1";
  s.sigma_initial_arcsec = 4.0;
  s.command_line = "meridian gyro simulate --mode tracking";
  const io::SimulationInput in = io::read_simulate_settings(s);
  const auto& st = std::get<gyro::StationSimulation>(in.what);
  EXPECT_EQ(st.mode, gyro::Mode::Tracking);
  EXPECT_NEAR(st.scale_value_rad, 300.0 * kArcsec, 1e-18);
  EXPECT_NEAR(st.latitude_rad, M_PI / 4.0, 1e-15);
  EXPECT_NEAR(st.centre_rad, 3600.0 * kArcsec, 1e-15);
  EXPECT_NEAR(st.sigma_tracking_rad, 6.0 * kArcsec, 1e-18);
  EXPECT_NEAR(st.sigma_initial_tracking_rad, 4.0 * kArcsec, 1e-18);
  EXPECT_EQ(st.noise, gyro::NoiseModel::Markov1);
  const std::string yaml = io::simulated_book_yaml(io::run_simulation(in));
  EXPECT_EQ(yaml.rfind("# Simulated by: meridian gyro simulate --mode tracking\n", 0), 0u) << yaml.substr(0, 80);
  // Campaign mode: the example's truth with the given white σ.
  io::SimulateSettings c;
  c.mode = "campaign";
  c.sim.sigma_time_s = 0.2;
  const auto truth = std::get<gyro::CampaignTruth>(io::read_simulate_settings(c).what);
  EXPECT_EQ(truth.sigma_time_s, 0.2);
  EXPECT_EQ(truth.name, gyro::example_campaign_truth().name);
  // Errors name the option.
  const auto field_of = [](const io::SimulateSettings& bad) {
    try {
      io::read_simulate_settings(bad);
    } catch (const InputError& e) {
      return e.context().field;
    }
    return std::string("no error");
  };
  io::SimulateSettings b;
  b.clamps = {"0", "1"};
  EXPECT_EQ(field_of(b), "--clamp");  // more clamps than determinations
  b = {};
  b.mode = "tracking";
  b.given = {"levels"};
  EXPECT_EQ(field_of(b), "--levels");
  b = {};
  b.mode = "campaign";
  b.noise = "markov2";
  EXPECT_EQ(field_of(b), "--noise");
  b = {};
  b.sigma_initial_arcsec = 1.0;  // non-tracking
  EXPECT_EQ(field_of(b), "--sigma-initial-arcsec");
  b = {};
  b.mode = "other";
  EXPECT_EQ(field_of(b), "--mode");
}

namespace {

std::string text_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(DocumentTree, ACampaignThroughTreeJsonIsTheSameCampaign) {
  // The browser field book hands the readers a tree made by another parser (document.hpp,
  // load_tree_json): the example campaign through yaml-cpp's tree written as tree JSON must read
  // and reduce to exactly what the file gives.
  using meridian::io::Node;
  const std::filesystem::path book = std::filesystem::path(MERIDIAN_SOURCE_DIR) / "examples" / "campaign.yaml";
  const Node from_file = Node::load_file(book);
  const Node from_tree = Node::load_tree_json(meridian::io::to_tree_json(from_file.tree()), book.string());
  const auto a = meridian::io::read_campaign_document(from_file);
  const auto b = meridian::io::read_campaign_document(from_tree);
  EXPECT_EQ(a.lines, b.lines);
  const meridian::gyro::CampaignResult ra = meridian::gyro::process(a.campaign);
  const meridian::gyro::CampaignResult rb = meridian::gyro::process(b.campaign);
  EXPECT_EQ(ra.chain.grid_azimuth_rad.value, rb.chain.grid_azimuth_rad.value);
  EXPECT_EQ(ra.chain.grid_azimuth_rad.sigma, rb.chain.grid_azimuth_rad.sigma);
  ASSERT_EQ(ra.checks.size(), rb.checks.size());
  for (std::size_t i = 0; i < ra.checks.size(); ++i) EXPECT_EQ(ra.checks[i].value, rb.checks[i].value);
}

TEST(DocumentTree, ErrorsNameTheSamePlaceEitherWay) {
  using meridian::io::Node;
  // A bad value, a key without a value, an unknown field, a duplicate: file, line and field as from yaml-cpp.
  std::string text = text_of(std::filesystem::path(MERIDIAN_SOURCE_DIR) / "examples" / "campaign.yaml");
  const auto at = text.find("latitude_deg");
  ASSERT_NE(at, std::string::npos);
  for (const std::string& bad : {std::string("latitude_dog"), std::string("latitude_deg:\n  x")}) {
    std::string t = text;
    t.replace(at, std::string("latitude_deg").size(), bad);
    std::string from_yaml, from_tree;
    try {
      (void)meridian::io::read_campaign_document(Node::load_text(t, "book.yaml"));
    } catch (const meridian::Error& e) {
      from_yaml = e.what();
    }
    try {
      const Node n = Node::load_text(t, "book.yaml");
      (void)meridian::io::read_campaign_document(Node::load_tree_json(meridian::io::to_tree_json(n.tree()), "book.yaml"));
    } catch (const meridian::Error& e) {
      from_tree = e.what();
    } catch (...) {
      from_tree = "?";
    }
    EXPECT_FALSE(from_yaml.empty()) << bad;
    EXPECT_EQ(from_yaml, from_tree) << bad;
  }
  // Not a tree: named as such, never a crash.
  for (const char* j : {"", "[]", "{\"kind\": \"map\"}", "{\"kind\": \"scalar\", \"line\": 1}",
                        "{\"kind\": \"map\", \"members\": [{\"key\": 1, \"value\": {}}]}",
                        "{\"kind\": \"sequence\", \"elements\": [], \"line\": -3}", "{\"kind\": \"tree\"}"})
    EXPECT_THROW((void)Node::load_tree_json(j, "t.json"), meridian::ParseError) << j;
  // A top level that is not a map is the readers' own message.
  EXPECT_THROW((void)Node::load_tree_json("{\"kind\": \"scalar\", \"scalar\": \"x\", \"line\": 1}", "t.json"),
               meridian::InputError);
  // Nesting beyond the limit is an error, not a stack overflow.
  std::string deep;
  for (int i = 0; i < 300; ++i) deep += "{\"kind\": \"sequence\", \"elements\": [";
  deep += "{\"kind\": \"null\"}";
  for (int i = 0; i < 300; ++i) deep += "]}";
  EXPECT_THROW((void)Node::load_tree_json(deep, "t.json"), meridian::ParseError);
  EXPECT_THROW((void)Node::load_text(std::string(300, '[') + std::string(300, ']'), "t.yaml"), meridian::ParseError);
}

TEST(GyroFiles, ADirectionBeyondAFullCircleIsRefusedNotWrapped) {
  // Helper trial (issue 36): a known azimuth booked 399 47 00 in a degrees book read as 39 47 00.
  using meridian::io::Node;
  const std::string text = text_of(std::filesystem::path(MERIDIAN_SOURCE_DIR) / "examples" / "campaign.yaml");
  const std::string az = "value: \"28 21 04.1081\"";
  ASSERT_NE(text.find(az), std::string::npos);
  std::string t = text;
  t.replace(t.find(az), az.size(), "value: \"399 47 00\"");
  std::string what;
  try {
    (void)meridian::io::read_campaign_document(Node::load_text(t, "book.yaml"));
  } catch (const meridian::Error& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("known_line.azimuth.value"), std::string::npos) << what;
  EXPECT_NE(what.find("less than a full circle (360 deg)"), std::string::npos) << what;
  EXPECT_NE(what.find("a gon value in a book whose angle_unit is not gon?"), std::string::npos) << what;
  // A circle reading of 360 00 00 is 0; one of 400 20 00 is refused (and is no gon value either).
  for (const auto& [reading, refused] : {std::pair{"360 00 00", false}, std::pair{"400 20 00", true}}) {
    t = text;
    const std::string first = "target_reading: \"117 56 54.8129\"";
    ASSERT_NE(t.find(first), std::string::npos);
    t.replace(t.find(first), first.size(), std::string("target_reading: \"") + reading + "\"");
    what.clear();
    try {
      const auto c = meridian::io::read_campaign_document(Node::load_text(t, "book.yaml")).campaign;
      EXPECT_EQ(c.known_line->before[0].target_reading_rad->value, 0.0);
    } catch (const meridian::Error& e) {
      what = e.what();
    }
    EXPECT_EQ(!what.empty(), refused) << reading << ": " << what;
    if (refused) {
      EXPECT_NE(what.find("book.yaml:48"), std::string::npos) << what;
      EXPECT_NE(what.find("target_reading"), std::string::npos) << what;
      EXPECT_EQ(what.find("gon value"), std::string::npos) << what;
    }
  }
}

TEST(GyroFiles, APointFarOutsideItsZoneIsWarnedOf) {
  // Helper trial (issue 36): coordinates of another zone were accepted, caught only by gyro - traverse.
  using meridian::io::Node;
  const std::string text = text_of(std::filesystem::path(MERIDIAN_SOURCE_DIR) / "examples" / "campaign.yaml");
  auto warnings_of = [](const std::string& t) {
    const auto r = meridian::gyro::process(meridian::io::read_campaign_document(Node::load_text(t, "b.yaml")).campaign);
    std::string all;
    for (const auto& w : r.warnings) all += w + "\n";
    return all;
  };
  EXPECT_EQ(warnings_of(text).find("half width"), std::string::npos) << warnings_of(text);
  // 300 km farther west: 3.4 deg from 114 E at 37.8 N, beyond GK3's 1.5 deg half width.
  std::string t = text;
  const std::string y = "y_m: 372430.12";
  ASSERT_NE(t.find(y), std::string::npos);
  t.replace(t.find(y), y.size(), "y_m: 72430.12");
  const std::string w = warnings_of(t);
  EXPECT_NE(w.find("known_line.from: 4."), std::string::npos) << w;
  EXPECT_NE(w.find("from the central meridian 114.0 deg of zone 38, beyond the zone's half width 1.5 deg"),
            std::string::npos)
      << w;
}
