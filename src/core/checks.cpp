#include "meridian/core/checks.hpp"

#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian {

void require_finite(double v, std::string_view what, std::string_view field) {
  if (!std::isfinite(v))
    throw InputError(fmt::format("{} is not finite ({})", what, v), {"", std::nullopt, std::string(field)});
}

void require_finite(std::span<const double> values, std::string_view what, std::string_view field) {
  if (values.empty()) throw InputError(fmt::format("{} is empty", what), {"", std::nullopt, std::string(field)});
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw InputError(fmt::format("{} sample {} is not finite ({})", what, i, values[i]),
                       {"", std::nullopt, std::string(field)});
}

}  // namespace meridian
