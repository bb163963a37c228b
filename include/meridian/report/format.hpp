#pragma once
/// \file format.hpp
/// How angles and σ are printed in every workflow's reports (text, HTML):
/// directions in DMS, σ and corrections in arc-seconds, "n/a" for what
/// cannot be stated.

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"

namespace meridian::report::fmtx {

/// Direction in [0°, 360°) as D°M'S" with `decimals` digits of seconds.
inline std::string dir(double rad, int decimals = 1) {
  return format_direction_dms(Angle::radians(rad), {decimals, true, false});
}
/// Signed angle as D°M'S".
inline std::string dms(double rad, int decimals = 2) {
  return format_dms(Angle::radians(rad), {decimals, true, true});
}
/// σ in arc-seconds, "n/a" when not finite.
inline std::string sig(double rad, int decimals = 1) {
  return std::isfinite(rad) ? fmt::format("{:.{}f}\"", rad / units::kArcsecond, decimals)
                            : std::string("n/a");
}
/// Signed arc-seconds.
inline std::string sec(double rad, int decimals = 2) {
  return fmt::format("{:+.{}f}\"", rad / units::kArcsecond, decimals);
}
/// A plain number, "n/a" when not finite.
inline std::string num(double v, int decimals) {
  return std::isfinite(v) ? fmt::format("{:.{}f}", v, decimals) : std::string("n/a");
}

}  // namespace meridian::report::fmtx
