#pragma once
// Shared helpers of the gravity tests: temporary directories, synthetic
// model files written once per process, random points.

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "meridian/core/units.hpp"
#include "meridian/io/gravity_egm.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/io/gravity_icgem.hpp"
#include "meridian/gravity/synthetic.hpp"

namespace gtest_gravity {

namespace fs = std::filesystem;

/// A per-process scratch directory, removed at exit.
inline const fs::path& scratch_dir() {
  struct Dir {
    fs::path p;
    Dir() {
      p = fs::temp_directory_path() / ("meridian_gravity_test_" + std::to_string(::getpid()));
      fs::create_directories(p);
    }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  };
  static Dir d;
  return d.p;
}

/// Synthetic model of degree n (seed fixed), written as NAME.egm(.cof) and
/// NAME.gfc into scratch_dir() once. Returns the model name (= file stem).
inline std::string synthetic_files(int degree, std::uint64_t seed = 20260) {
  static std::map<std::pair<int, std::uint64_t>, std::string> done;
  const auto key = std::make_pair(degree, seed);
  if (auto it = done.find(key); it != done.end()) return it->second;
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = degree;
  o.seed = seed;
  const auto model = meridian::gravity::make_synthetic_model(o);
  const std::string name = "syn" + std::to_string(degree) + "_" + std::to_string(seed);
  meridian::io::write_egm_files(model, scratch_dir() / name);
  done[key] = name;
  return name;
}

struct TestPoint {
  double lat_deg, lon_deg, h_m;
};

/// Random points over the globe, plus polar caps (|φ| > 89°), the poles
/// themselves and the equator, heights in [−500 m, 10 km].
inline std::vector<TestPoint> test_points(int random_count, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> z(-1, 1), lon(-180, 180), h(-500, 10000), cap(89, 90);
  std::vector<TestPoint> pts = {{90, 0, 0}, {-90, 37, 1200}, {0, 0, 0}, {89.999, 123.4, -500}, {-89.5, -77, 10000},
                                {45, 180, 0}, {-30, -179.99, 250}};
  for (int i = 0; i < random_count; ++i) {
    const double lat = std::asin(z(g)) * 180 / meridian::units::kPi;
    pts.push_back({lat, lon(g), h(g)});
    if (i % 4 == 0) pts.push_back({(i % 8 == 0 ? 1 : -1) * cap(g), lon(g), h(g)});
  }
  return pts;
}

inline meridian::gravity::GeodeticPoint geodetic(const TestPoint& p) {
  return {p.lat_deg * meridian::units::kDegree, p.lon_deg * meridian::units::kDegree, p.h_m};
}

inline fs::path shared_gravity_dir() { return fs::path(MERIDIAN_SOURCE_DIR) / ".." / "shared" / "data" / "gravity"; }

}  // namespace gtest_gravity
