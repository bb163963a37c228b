// GeographicLib .egm metadata + .egm.cof coefficients (io/gravity_egm.hpp).
// One input holds both files: the text, the separator kSplit, the binary.
#include <string_view>

#include "meridian/io/gravity_egm.hpp"
#include "model_check.hpp"

namespace {
constexpr std::string_view kSplit = "\n@@COF@@\n";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace meridian_fuzz;
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const auto at = in.find(kSplit);
  const std::string_view meta = in.substr(0, at);
  const std::string_view cof =
      at == std::string_view::npos ? std::string_view() : in.substr(at + kSplit.size());
  const auto p = write("model.egm", meta);
  write("model.egm.cof", cof);
  expect_value_or_error([&] { check_model(meridian::io::read_egm_file(p)); });
  expect_value_or_error([&] { check_model(meridian::io::read_egm_file(p, {2, 1})); });
  return 0;
}
