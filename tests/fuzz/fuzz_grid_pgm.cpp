// Geoid grid reader, .pgm (io/gravity_geoid_grid.hpp), and interpolation on what it accepts.
#include "grid_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  const auto p = write("grid.pgm", {reinterpret_cast<const char*>(data), size});
  expect_value_or_error([&] { check_grid(meridian::io::read_geoid_grid(p)); });
  return 0;
}
