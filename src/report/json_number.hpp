#pragma once
// Private to the report module (not installed): a number for a JSON document.

#include <cmath>

#include <nlohmann/json.hpp>

namespace meridian::report::detail {

/// v as a JSON number, or null when v is not finite (JSON has no NaN or infinity).
inline nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

}  // namespace meridian::report::detail
