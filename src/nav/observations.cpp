#include "meridian/nav/observations.hpp"

#include <cmath>

#include "meridian/core/error.hpp"

namespace meridian::nav {

DrSample dr_from_speed_heading(double time_s, double speed_m_s, double heading_rad,
                               double sigma_speed_m_s, double sigma_heading_rad) {
  if (!std::isfinite(time_s)) throw InputError("time is not finite", {{}, {}, "time_s"});
  if (!std::isfinite(speed_m_s) || speed_m_s < 0.0)
    throw InputError("speed must be finite and >= 0", {{}, {}, "speed_m_s"});
  if (!std::isfinite(heading_rad)) throw InputError("heading is not finite", {{}, {}, "heading_rad"});
  if (!std::isfinite(sigma_speed_m_s) || sigma_speed_m_s < 0.0)
    throw InputError("σ of the speed must be finite and >= 0", {{}, {}, "sigma_speed_m_s"});
  if (!std::isfinite(sigma_heading_rad) || sigma_heading_rad < 0.0)
    throw InputError("σ of the heading must be finite and >= 0", {{}, {}, "sigma_heading_rad"});
  const double c = std::cos(heading_rad);
  const double s = std::sin(heading_rad);
  DrSample d;
  d.time_s = time_s;
  d.v_north_m_s = speed_m_s * c;
  d.v_east_m_s = speed_m_s * s;
  // J = [[cos α, −v sin α], [sin α, v cos α]] (rows v_N, v_E; columns v, α).
  Eigen::Matrix2d j;
  j << c, -speed_m_s * s, s, speed_m_s * c;
  const Eigen::Vector2d var(sigma_speed_m_s * sigma_speed_m_s, sigma_heading_rad * sigma_heading_rad);
  d.covariance = j * var.asDiagonal() * j.transpose();
  d.covariance = 0.5 * (d.covariance + d.covariance.transpose()).eval();
  return d;
}

}  // namespace meridian::nav
