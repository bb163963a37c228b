#include "meridian/core/unicode.hpp"

#include <cstdlib>
#include <memory>

#include <fmt/format.h>
#include <utf8proc.h>

#include "meridian/core/error.hpp"

namespace meridian {

std::string nfkc(std::string_view text) {
  utf8proc_uint8_t* out = nullptr;
  const auto options = static_cast<utf8proc_option_t>(UTF8PROC_STABLE | UTF8PROC_COMPOSE | UTF8PROC_COMPAT);
  const utf8proc_ssize_t n = utf8proc_map(reinterpret_cast<const utf8proc_uint8_t*>(text.data()),
                                          static_cast<utf8proc_ssize_t>(text.size()), &out, options);
  const std::unique_ptr<utf8proc_uint8_t, decltype(&std::free)> owned(out, &std::free);
  if (n < 0) throw InputError(fmt::format("text is not valid UTF-8 ({})", utf8proc_errmsg(n)));
  return std::string(reinterpret_cast<const char*>(out), static_cast<std::size_t>(n));
}

bool same_name_nfkc(std::string_view a, std::string_view b) {
  return a == b || nfkc(a) == nfkc(b);
}

}  // namespace meridian
