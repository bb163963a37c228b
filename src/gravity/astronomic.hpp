#pragma once
// Private: astronomic latitude/longitude offsets of the plumb line.

#include <cmath>
#include <numbers>

#include "meridian/gravity/normal_gravity.hpp"

namespace meridian::gravity::detail {

/// ξ_a = Φ − φ and η_a = (Λ − λ) cos φ for g = γ + ∇T, with ∇T given in the
/// local geocentric frame (east, north along ψ, radial) at a point whose
/// geocentric latitude has sine t and cosine u.
inline void astronomic_deflection(const EcefPosition& gamma, double east, double north, double up, double t, double u,
                                  double lat_rad, double lon_rad, double& xi, double& eta) {
  const double cl = std::cos(lon_rad), sl = std::sin(lon_rad);
  // n = −g, the upward plumb line, in ECEF.
  const double nx = -(gamma.x_m - sl * east - t * cl * north + u * cl * up);
  const double ny = -(gamma.y_m + cl * east - t * sl * north + u * sl * up);
  const double nz = -(gamma.z_m + u * north + t * up);
  const double xp = cl * nx + sl * ny, yp = -sl * nx + cl * ny;  // in the meridian plane of λ; east
  const double phi_a = std::atan2(nz, std::hypot(xp, yp));
  xi = phi_a - lat_rad;
  eta = std::atan2(yp, xp) * (std::abs(lat_rad) == std::numbers::pi / 2 ? 0.0 : std::cos(lat_rad));
}

}  // namespace meridian::gravity::detail
