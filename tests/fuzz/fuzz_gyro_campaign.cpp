// Gyro field-book reader, `gyro campaign` files (io/gyro_files.hpp), YAML or JSON as is.
#include "fuzz_support.hpp"
#include "meridian/io/gyro_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  const auto p = write("book.yaml", {reinterpret_cast<const char*>(data), size});
  expect_value_or_error([&] { (void)meridian::io::read_campaign_file(p); });
  return 0;
}
