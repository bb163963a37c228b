#pragma once
// Test helpers of the gravity tests: the angle units the expected values are written in.
#include "meridian/core/units.hpp"

namespace gtest_gravity {

inline constexpr double kDeg = meridian::units::kDegree;        ///< radians per degree
inline constexpr double kArcsec = meridian::units::kArcsecond;  ///< radians per arc-second

}  // namespace gtest_gravity
