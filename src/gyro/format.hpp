#pragma once
// Private to the gyro module (not installed): number formatting shared by its messages.

#include <string>

#include <fmt/format.h>

namespace meridian::gyro::detail {

/// x with 6 significant digits, for error messages and notes.
inline std::string num(double x) { return fmt::format("{:.6g}", x); }

}  // namespace meridian::gyro::detail
