// io_gravity: the lat,lon[,h] point reader, the CSV writer and the
// streaming runner of `gravity points`, checked against points written out
// by hand and the model evaluated one point at a time.

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/io/gravity_csv.hpp"
#include "meridian/io/gravity_jobs.hpp"
#include "meridian/io/gravity_points.hpp"

using namespace meridian;
namespace fs = std::filesystem;

namespace {

std::vector<gravity::GeodeticPoint> read_points(const std::string& text, std::size_t chunk = 1000) {
  std::istringstream in(text);
  io::GravityPointReader r(in, "p.csv");
  std::vector<gravity::GeodeticPoint> all, part;
  while (r.next(part, chunk)) all.insert(all.end(), part.begin(), part.end());
  return all;
}

std::string points_error_of(const std::string& text) {
  try {
    read_points(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(GravityPointReader, ReadsRowsWithHeaderCommentsDmsAndHeights) {
  const auto p = read_points(
      "# line 7\nlat,lon,h\n37.84,112.56,850\n\n-89.9 , -179 ,0 # pole\n10, 20\n45 30 "
      "00,-120,100\n");
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NEAR(p[0].lat_rad, 37.84 * units::kDegree, 1e-15);
  EXPECT_NEAR(p[0].lon_rad, 112.56 * units::kDegree, 1e-15);
  EXPECT_EQ(p[0].height_m, 850.0);
  EXPECT_NEAR(p[1].lat_rad, -89.9 * units::kDegree, 1e-15);
  EXPECT_EQ(p[2].height_m, 0.0);  // no height: 0
  EXPECT_NEAR(p[3].lat_rad, 45.5 * units::kDegree, 1e-15);
  // Whitespace-separated, CRLF, units in the header.
  const auto w = read_points("lat [deg] lon [deg] h [m]\r\n1.5 2.5 3\r\n-1 -2\r\n");
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NEAR(w[1].lon_rad, -2 * units::kDegree, 1e-15);
  EXPECT_EQ(w[0].height_m, 3.0);
}

TEST(GravityPointReader, ErrorsNameTheLineAndTheField) {
  // The messages of `gravity points` before the record reader (docs/gravity-field.md).
  EXPECT_EQ(points_error_of("lat,lon\n37.84,abc\n"),
            "p.csv:2: longitude: cannot read angle \"abc\": unexpected \"abc\"");
  EXPECT_EQ(points_error_of("37.84,12,5,6\n"),
            "p.csv:1: expected lat,lon[,h] (2 or 3 fields), got 4");
  EXPECT_EQ(points_error_of("37.84,12,5x\n"), "p.csv:1: h: height \"5x\" is not a number");
  EXPECT_EQ(points_error_of("97.84,12\n"),
            "p.csv:1: latitude: latitude 97.84 deg is outside [-90, 90]");
  EXPECT_EQ(points_error_of("1,2\n\n# c\n3\n"),
            "p.csv:4: expected lat,lon[,h] (2 or 3 fields), got 1");
  EXPECT_EQ(points_error_of("1,600\n"),
            "p.csv:1: longitude: longitude 600 deg is outside [-540, 540]");
  EXPECT_NE(points_error_of("1,2,-20000\n").find("p.csv:1: h: height -20000 m is outside"),
            std::string::npos);
}

TEST(GravityPointReader, SamePointsWhateverTheChunkSize) {
  std::string text = "lat,lon,h\n";
  for (int i = 0; i < 250; ++i)
    text +=
        std::to_string(i * 0.1) + "," + std::to_string(i * 0.2) + "," + std::to_string(i) + "\n";
  const auto a = read_points(text, 1000), b = read_points(text, 7);
  ASSERT_EQ(a.size(), 250u);
  ASSERT_EQ(b.size(), 250u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].lat_rad, b[i].lat_rad);
    EXPECT_EQ(a[i].height_m, static_cast<double>(i));
  }
}

TEST(GravityCsv, RowsHaveTheDocumentedColumnsAndDecimals) {
  EXPECT_EQ(io::gravity_points_csv_header(), "lat_deg,lon_deg,h_m,xi_arcsec,eta_arcsec,geoid_m\n");
  gravity::FieldValues v{};
  v.xi_rad = 1.5 * units::kArcsecond;
  v.eta_rad = -0.25 * units::kArcsecond;
  v.geoid_m = 20.125;
  const std::vector<gravity::GeodeticPoint> p{
      {37.84 * units::kDegree, -179.0 * units::kDegree, 850.5}};
  std::string out = "x";
  io::append_gravity_points_csv(out, p, std::vector<gravity::FieldValues>{v});
  EXPECT_EQ(out, "x37.8400000000,-179.0000000000,850.5000,1.500000000,-0.250000000,20.125000000\n");
  EXPECT_THROW(io::append_gravity_points_csv(out, p, {}), InputError);
}

class RecordingProgress : public Progress {
 public:
  void update(std::size_t done, std::size_t total, std::string_view what) override {
    last_done = done;
    last_total = total;
    last_what = std::string(what);
    ++calls;
  }
  void finish() override {}
  std::size_t last_done = 0, last_total = 0;
  std::string last_what;
  int calls = 0;
};

TEST(GravityJobs, StreamsEveryChunkAndSummarisesEveryPoint) {
  const fs::path dir =
      fs::temp_directory_path() / ("meridian_io_gravity_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // More points than one chunk, so the loop runs more than once.
  const int n = 20000;
  {
    std::ofstream f(dir / "pts.csv");
    f << "lat,lon,h\n";
    for (int i = 0; i < n; ++i)
      f << -60 + i * 0.006 << "," << -170 + i * 0.017 << "," << (i % 100) * 10 << "\n";
  }
  gravity::SyntheticModelOptions o;
  o.max_degree = 12;
  o.seed = 3;
  const io::LoadedModel model = io::prepare_model(gravity::make_synthetic_model(o));
  const gravity::GravityField& field = model.field;
  io::PointsInput input((dir / "pts.csv").string());
  EXPECT_EQ(input.size_bytes(), fs::file_size(dir / "pts.csv"));
  std::string csv;
  int writes = 0;
  RecordingProgress progress;
  const gravity::PointsResult result = io::run_gravity_points(
      input, field, model.info, gravity::PointsOptions{},
      [&](std::string_view t) {
        csv += t;
        ++writes;
      },
      &progress, 100);
  const gravity::PointsSummary& summary = result.summary;
  EXPECT_EQ(result.input, (dir / "pts.csv").string());
  EXPECT_EQ(result.model.max_degree, 12);
  EXPECT_EQ(summary.count(), static_cast<std::uint64_t>(n));
  EXPECT_EQ(writes, 1 + (n + 16383) / 16384);  // the header, then one write per chunk
  EXPECT_EQ(progress.last_done, progress.last_total);
  EXPECT_EQ(progress.last_what, "points (bytes of input)");
  EXPECT_LE(summary.sample().points().size(), 100u);
  // Every row: the model at that point, one point at a time.
  std::istringstream rows(csv);
  std::string line;
  std::getline(rows, line);
  EXPECT_EQ(line + "\n", io::gravity_points_csv_header());
  int i = 0;
  double sum_n = 0;
  while (std::getline(rows, line)) {
    double lat, lon, h, xi, eta, geoid;
    char c;
    std::istringstream(line) >> lat >> c >> lon >> c >> h >> c >> xi >> c >> eta >> c >> geoid;
    if (i % 499 == 0) {
      const auto v =
          field.evaluate(gravity::GeodeticPoint{lat * units::kDegree, lon * units::kDegree, h});
      EXPECT_NEAR(xi, v.xi_rad / units::kArcsecond, 1e-8) << line;
      EXPECT_NEAR(eta, v.eta_rad / units::kArcsecond, 1e-8) << line;
      EXPECT_NEAR(geoid, v.geoid_m, 1e-8) << line;
    }
    sum_n += geoid;
    ++i;
  }
  EXPECT_EQ(i, n);
  EXPECT_NEAR(summary.geoid_m().mean(), sum_n / n, 1e-8);
  EXPECT_THROW(io::PointsInput((dir / "missing.csv").string()), IoError);
  fs::remove_all(dir);
}

}  // namespace
