// The deflection-of-the-vertical line CSV reader (io/dov_files.hpp): every sample it returns
// has finite values, a latitude within ±90°, finite attitude matrices and, when the file has
// the model columns, finite model values; the file line of each sample increases.
#include <cmath>
#include <sstream>

#include "fuzz_support.hpp"
#include "meridian/io/dov_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  expect_value_or_error([&] {
    const meridian::io::DovLine line = meridian::io::read_dov_line(in, "line.csv");
    if (line.lines.size() != line.samples.size()) finding("one file line per sample");
    if (!line.truth.empty() && line.truth.size() != line.samples.size())
      finding("truth for some samples only");
    for (std::size_t k = 0; k < line.samples.size(); ++k) {
      const auto& s = line.samples[k];
      for (double v : {s.time_s, s.lat_rad, s.lon_rad, s.height_m, s.speed_m_s})
        check_finite(v, "a sample value is not finite");
      if (std::abs(s.lat_rad) > 1.5707963267948966 + 1e-12) finding("latitude beyond 90 deg");
      if (!s.lgu_body_to_nav.allFinite() || !s.ins_body_to_nav.allFinite())
        finding("attitude matrix not finite");
      if (line.has_model_values) {
        check_finite(s.model_eta_rad, "model eta not finite");
        check_finite(s.model_xi_rad, "model xi not finite");
      }
      if (k > 0 && line.lines[k] <= line.lines[k - 1]) finding("sample lines do not increase");
    }
  });
  return 0;
}
