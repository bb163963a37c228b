// The lat,lon[,h] point reader of `gravity points` (io/gravity_points.hpp):
// every point it returns is finite and within the ranges it documents.
#include <cmath>
#include <sstream>
#include <vector>

#include "fuzz_support.hpp"
#include "meridian/io/gravity_points.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  expect_value_or_error([&] {
    meridian::io::GravityPointReader reader(in, "points.csv");
    std::vector<meridian::gravity::GeodeticPoint> pts;
    while (reader.next(pts, 7))
      for (const auto& p : pts) {
        check_finite(p.lat_rad, "latitude not finite");
        check_finite(p.lon_rad, "longitude not finite");
        check_finite(p.height_m, "height not finite");
        if (std::abs(p.lat_rad) > 1.5707963267948966 + 1e-12) finding("latitude beyond 90 deg");
      }
  });
  return 0;
}
