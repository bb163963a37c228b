#pragma once
/// \file checks.hpp
/// The one home of the argument checks every module makes on plain numbers, so that a
/// non-finite value gets the same message wherever it is found.

#include <span>
#include <string_view>

namespace meridian {

/// Throws InputError "<what> is not finite (<v>)" with field `field` (empty: none) unless `v` is
/// finite. Example: require_finite(speed, "speed", "dr[3].speed_m_s").
void require_finite(double v, std::string_view what, std::string_view field = {});

/// Throws InputError "<what> is empty" for an empty span, and "<what> sample <i> is not finite
/// (<v>)" for the first non-finite element (i 0-based), with field `field`.
void require_finite(std::span<const double> values, std::string_view what, std::string_view field = {});

}  // namespace meridian
