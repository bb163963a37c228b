#include "meridian/geodesy/sight.hpp"

#include <cmath>

#include <fmt/format.h>
#include <GeographicLib/Geocentric.hpp>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/frames.hpp"

namespace meridian::geodesy {
namespace {

void require_position(const GeodeticPosition& p, const char* what) {
  if (!std::isfinite(p.lat_rad) || !std::isfinite(p.lon_rad) || !std::isfinite(p.height_m))
    throw InputError(fmt::format("{} of the sight is not finite ({}, {}, {})", what, p.lat_rad,
                                 p.lon_rad, p.height_m));
  if (std::abs(p.lat_rad) > units::kPi / 2)
    throw InputError(fmt::format("latitude of the {} of the sight {} deg is beyond +-90 deg", what,
                                 units::rad_to_deg(p.lat_rad)));
}

Eigen::Vector3d ecef(const GeographicLib::Geocentric& g, const GeodeticPosition& p) {
  Eigen::Vector3d x;
  g.Forward(units::rad_to_deg(p.lat_rad), units::rad_to_deg(p.lon_rad), p.height_m, x.x(), x.y(),
            x.z());
  return x;
}

}  // namespace

double sight_zenith_distance_rad(const GeodeticPosition& from, const GeodeticPosition& to,
                                 const Ellipsoid& ellipsoid) {
  require_position(from, "station");
  require_position(to, "target");
  if (!std::isfinite(ellipsoid.a_m) || ellipsoid.a_m <= 0 || !std::isfinite(ellipsoid.f) ||
      ellipsoid.f < 0 || ellipsoid.f >= 1)
    throw InputError(fmt::format("invalid ellipsoid {}: a = {} m, f = {}", ellipsoid.name,
                                 ellipsoid.a_m, ellipsoid.f));
  const GeographicLib::Geocentric g(ellipsoid.a_m, ellipsoid.f);
  const Eigen::Vector3d d =
      rotation_ecef_to_enu(from.lat_rad, from.lon_rad) * (ecef(g, to) - ecef(g, from));
  if (d.norm() < 1e-3)
    throw InputError("the station and the target of the sight coincide: no zenith distance");
  return std::atan2(std::hypot(d.x(), d.y()), d.z());
}

}  // namespace meridian::geodesy
