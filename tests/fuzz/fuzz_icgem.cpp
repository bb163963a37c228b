// ICGEM .gfc reader (io/gravity_icgem.hpp), whole and truncated on load; a
// model it accepts is evaluated at one point.
#include "meridian/io/gravity_icgem.hpp"
#include "model_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  const auto p = write("model.gfc", {reinterpret_cast<const char*>(data), size});
  expect_value_or_error([&] { check_model(meridian::io::read_icgem_file(p)); });
  expect_value_or_error([&] { check_model(meridian::io::read_icgem_file(p, {2, 1})); });
  return 0;
}
