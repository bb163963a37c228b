// The deflection-of-the-vertical binary line reader (io/dov_binary.hpp): it returns exactly
// the number of samples its header announces, every value finite, the latitude within ±90°,
// the truth one per sample when the header says so; anything else is a meridian::Error.
#include <cmath>
#include <sstream>
#include <vector>

#include "fuzz_support.hpp"
#include "meridian/io/dov_binary.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  expect_value_or_error([&] {
    meridian::io::DovBinaryReader r(in, "line.bin");
    // A count beyond what the input can hold ends as "truncated": never allocate for it.
    std::vector<meridian::dov::Sample> samples;
    std::vector<meridian::dov::Truth> truth;
    std::size_t got = 0;
    while (const std::size_t n = r.next(samples, &truth, 64)) {
      got += n;
      if (samples.size() > 64 * 1024) {
        samples.clear();  // the harness keeps memory bounded as the workflow does
        truth.clear();
      }
      for (const auto& s : samples) {
        for (double v : {s.time_s, s.lat_rad, s.lon_rad, s.height_m, s.speed_m_s})
          check_finite(v, "a sample value is not finite");
        if (std::abs(s.lat_rad) > 1.5707963267948966 + 1e-12) finding("latitude beyond 90 deg");
        if (!s.lgu_body_to_nav.allFinite() || !s.ins_body_to_nav.allFinite())
          finding("attitude matrix not finite");
        if (r.has_model()) {
          check_finite(s.model_eta_rad, "model eta not finite");
          check_finite(s.model_xi_rad, "model xi not finite");
        }
      }
      if (r.has_truth() ? truth.size() != samples.size() : !truth.empty())
        finding("truth not one per sample");
      samples.clear();
      truth.clear();
    }
    if (got != r.count()) finding("sample count differs from the header's");
  });
  return 0;
}
