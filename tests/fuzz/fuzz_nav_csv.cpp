// The navigation CSV readers (io/nav_files.hpp): the first byte chooses the reader (DR,
// stations, LOPs, fixes, truth), the rest is the file. Whatever they return has finite values,
// σ > 0, speeds ≥ 0, latitudes within ±90°, strictly increasing DR times, one file line per
// record and increasing lines.
#include <cmath>
#include <sstream>

#include "fuzz_support.hpp"
#include "meridian/io/nav_files.hpp"

namespace {

using namespace meridian_fuzz;

void check_position(const meridian::io::NavPosition& p) {
  if (p.geographic) {
    check_finite(p.lat_rad, "latitude not finite");
    check_finite(p.lon_rad, "longitude not finite");
    if (std::abs(p.lat_rad) > 1.5707963267948966 + 1e-12) finding("latitude beyond 90 deg");
  } else {
    check_finite(p.x_north_m, "x not finite");
    check_finite(p.y_east_m, "y not finite");
  }
}

template <typename File>
void check_lines(const File& f) {
  if (f.lines.size() != f.records.size()) finding("one file line per record");
  for (std::size_t k = 1; k < f.lines.size(); ++k)
    if (f.lines[k] <= f.lines[k - 1]) finding("record lines do not increase");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace io = meridian::io;
  if (size == 0) return 0;
  const int which = data[0] % 5;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data + 1), size - 1));
  expect_value_or_error([&] {
    switch (which) {
      case 0: {
        const io::NavDrFile f = io::read_nav_dr(in, "dr.csv");
        check_lines(f);
        for (std::size_t k = 0; k < f.records.size(); ++k) {
          const auto& r = f.records[k];
          for (double v : {r.time_s, r.a, r.b}) check_finite(v, "a DR value is not finite");
          if (f.speed_heading && r.a < 0.0) finding("negative speed");
          if (k > 0 && !(r.time_s > f.records[k - 1].time_s)) finding("DR times do not increase");
        }
        break;
      }
      case 1: {
        const io::NavStationsFile f = io::read_nav_stations(in, "stations.csv");
        if (f.names.size() != f.positions.size() || f.lines.size() != f.names.size())
          finding("stations: names, positions and lines differ in number");
        for (const auto& p : f.positions) check_position(p);
        for (std::size_t i = 0; i < f.names.size(); ++i)
          for (std::size_t j = 0; j < i; ++j)
            if (f.names[i] == f.names[j]) finding("duplicate station name");
        break;
      }
      case 2: {
        const io::NavLopsFile f = io::read_nav_lops(in, "lops.csv");
        check_lines(f);
        for (const auto& r : f.records) {
          check_finite(r.time_s, "LOP time not finite");
          check_finite(r.value, "LOP value not finite");
          if (!(r.sigma_m > 0.0) || !std::isfinite(r.sigma_m)) finding("LOP sigma not > 0");
          if (r.station.empty()) finding("LOP without a station");
        }
        break;
      }
      case 3: {
        const io::NavFixesFile f = io::read_nav_fixes(in, "fixes.csv");
        check_lines(f);
        for (const auto& r : f.records) {
          check_finite(r.time_s, "fix time not finite");
          check_position(r.position);
          if (!(r.sigma_north_m > 0.0 && r.sigma_east_m > 0.0) || !std::isfinite(r.sigma_north_m) ||
              !std::isfinite(r.sigma_east_m))
            finding("fix sigma not > 0");
        }
        break;
      }
      default: {
        const io::NavTruthFile f = io::read_nav_truth(in, "truth.csv");
        check_lines(f);
        for (const auto& r : f.records) {
          check_finite(r.time_s, "truth time not finite");
          check_position(r.position);
        }
      }
    }
  });
  return 0;
}
