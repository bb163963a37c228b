// ICGEM .gfc reader (gravity/icgem.hpp), whole and truncated on load; a
// model it accepts is evaluated at one point.
#include "meridian/gravity/icgem.hpp"
#include "model_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  const auto p = write("model.gfc", {reinterpret_cast<const char*>(data), size});
  expect_value_or_error([&] { check_model(meridian::gravity::read_icgem_file(p)); });
  expect_value_or_error([&] { check_model(meridian::gravity::read_icgem_file(p, {2, 1})); });
  return 0;
}
