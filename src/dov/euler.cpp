#include "meridian/dov/euler.hpp"

#include <cmath>

namespace meridian::dov {

Eigen::Matrix3d body_to_nav_from_euler(double heading_rad, double pitch_rad, double roll_rad) {
  const double cy = std::cos(heading_rad), sy = std::sin(heading_rad);
  const double cp = std::cos(pitch_rad), sp = std::sin(pitch_rad);
  const double cr = std::cos(roll_rad), sr = std::sin(roll_rad);
  Eigen::Matrix3d c;
  c << cy * cr + sy * sp * sr, sy * cp, cy * sr - sy * sp * cr,  //
      -sy * cr + cy * sp * sr, cy * cp, -sy * sr - cy * sp * cr,  //
      -cp * sr, sp, cp * cr;
  return c;
}

}  // namespace meridian::dov
