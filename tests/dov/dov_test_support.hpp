#pragma once
// Test helpers of the dov tests.
#include "meridian/core/units.hpp"

namespace meridian_test {

inline constexpr double kAs = meridian::units::kArcsecond;  ///< radians per arc-second

}  // namespace meridian_test
