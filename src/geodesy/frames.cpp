#include "meridian/geodesy/frames.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/checks.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::geodesy {
namespace {

void require_latitude(double lat_rad, const char* what) {
  require_finite(lat_rad, what);
  if (std::abs(lat_rad) > units::kPi / 2)
    throw InputError(fmt::format("{} {} rad ({} deg) must satisfy |lat| <= 90 deg", what, lat_rad,
                                 units::rad_to_deg(lat_rad)));
}

void require_deflection(const Deflection& d) {
  for (const auto& [v, name] : {std::pair{d.xi_rad, "xi"}, std::pair{d.eta_rad, "eta"}}) {
    if (!std::isfinite(v) || std::abs(v) > kMaxDeflection_rad)
      throw InputError(
          fmt::format("deflection component {} = {} rad ({}\") is not finite or exceeds {} rad; "
                      "is it in radians?",
                      name, v, units::rad_to_arcsec(v), kMaxDeflection_rad));
  }
}

void require_vector(const Eigen::Vector3d& v) {
  if (!v.allFinite()) throw InputError("zenith direction vector is not finite");
  if (v.squaredNorm() == 0.0) throw InputError("zenith direction vector is zero");
}

// Unit "up" (ellipsoid normal at latitude lat) in ECEF.
Eigen::Vector3d up_ecef(double lat_rad, double lon_rad) {
  const double cp = std::cos(lat_rad), sp = std::sin(lat_rad);
  return {cp * std::cos(lon_rad), cp * std::sin(lon_rad), sp};
}

}  // namespace

Eigen::Matrix3d rotation_ecef_to_enu(double lat_rad, double lon_rad) {
  require_latitude(lat_rad, "latitude");
  require_finite(lon_rad, "longitude");
  const double sp = std::sin(lat_rad), cp = std::cos(lat_rad);
  const double sl = std::sin(lon_rad), cl = std::cos(lon_rad);
  Eigen::Matrix3d r;
  r << -sl, cl, 0.0,           // e
      -sp * cl, -sp * sl, cp,  // n
      cp * cl, cp * sl, sp;    // u
  return r;
}

Eigen::Matrix3d rotation_enu_to_ned() {
  Eigen::Matrix3d p;
  p << 0.0, 1.0, 0.0,  //
      1.0, 0.0, 0.0,   //
      0.0, 0.0, -1.0;
  return p;
}

Eigen::Matrix3d rotation_ned_to_enu() { return rotation_enu_to_ned(); }

Eigen::Matrix3d rotation_ecef_to_ned(double lat_rad, double lon_rad) {
  return rotation_enu_to_ned() * rotation_ecef_to_enu(lat_rad, lon_rad);
}

double geocentric_latitude_rad(double lat_rad, double height_m, const Ellipsoid& e) {
  require_latitude(lat_rad, "latitude");
  require_finite(height_m, "height");
  if (!std::isfinite(e.a_m) || e.a_m <= 0 || !std::isfinite(e.f) || e.f < 0 || e.f >= 1)
    throw InputError(fmt::format("invalid ellipsoid {}: a = {} m, f = {}", e.name, e.a_m, e.f));
  const double e2 = e.f * (2 - e.f);
  const double sp = std::sin(lat_rad), cp = std::cos(lat_rad);
  const double n = e.a_m / std::sqrt(1 - e2 * sp * sp);
  const double z = (n * (1 - e2) + height_m);  // times sin φ
  if (z <= 0)
    throw InputError(
        fmt::format("height {} m is at or below -N(1 - e^2) = {} m (the Earth's centre)", height_m,
                    -n * (1 - e2)));
  return std::atan2(z * sp, (n + height_m) * cp);
}

Eigen::Matrix3d rotation_geocentric_to_enu(double lat_rad, double geocentric_lat_rad) {
  require_latitude(lat_rad, "geodetic latitude");
  require_latitude(geocentric_lat_rad, "geocentric latitude");
  const double d = lat_rad - geocentric_lat_rad;
  const double c = std::cos(d), s = std::sin(d);
  Eigen::Matrix3d r;
  r << 1.0, 0.0, 0.0,  //
      0.0, c, -s,      //
      0.0, s, c;
  return r;
}

Deflection deflection_from_astronomic(double astro_lat_rad, double astro_lon_rad, double lat_rad,
                                      double lon_rad) {
  require_latitude(astro_lat_rad, "astronomic latitude");
  require_finite(astro_lon_rad, "astronomic longitude");
  require_latitude(lat_rad, "geodetic latitude");
  require_finite(lon_rad, "geodetic longitude");
  return {astro_lat_rad - lat_rad, wrap_signed_rad(astro_lon_rad - lon_rad) * std::cos(lat_rad)};
}

Eigen::Vector3d astronomic_zenith_enu(double astro_lat_rad, double astro_lon_rad, double lat_rad,
                                      double lon_rad) {
  require_latitude(astro_lat_rad, "astronomic latitude");
  require_finite(astro_lon_rad, "astronomic longitude");
  return rotation_ecef_to_enu(lat_rad, lon_rad) * up_ecef(astro_lat_rad, astro_lon_rad);
}

Eigen::Vector3d astronomic_zenith_enu(const Deflection& d, double lat_rad) {
  require_deflection(d);
  require_finite(lat_rad, "latitude");
  if (std::abs(lat_rad) >= units::kPi / 2)
    throw InputError(fmt::format(
        "latitude {} deg: the exact zenith from (xi, eta) needs |lat| < 90 deg (eta / cos lat)",
        units::rad_to_deg(lat_rad)));
  const double astro_lat = lat_rad + d.xi_rad;
  if (std::abs(astro_lat) > units::kPi / 2)
    throw InputError(fmt::format("astronomic latitude lat + xi = {} deg is beyond +-90 deg",
                                 units::rad_to_deg(astro_lat)));
  // Only Λ − λ matters: evaluate on the meridian λ = 0.
  return astronomic_zenith_enu(astro_lat, d.eta_rad / std::cos(lat_rad), lat_rad, 0.0);
}

Eigen::Vector3d astronomic_zenith_enu_first_order(const Deflection& d) {
  require_deflection(d);
  return Eigen::Vector3d(d.eta_rad, d.xi_rad, 1.0).normalized();
}

Deflection deflection_from_zenith_enu(const Eigen::Vector3d& zenith_enu, double lat_rad) {
  require_vector(zenith_enu);
  require_latitude(lat_rad, "latitude");
  // Back to ECEF on the meridian λ = 0; normalising is not needed for atan2.
  const Eigen::Vector3d x = rotation_ecef_to_enu(lat_rad, 0.0).transpose() * zenith_enu;
  const double astro_lat = std::atan2(x.z(), std::hypot(x.x(), x.y()));
  const double dlon = std::atan2(x.y(), x.x());
  return {astro_lat - lat_rad,
          std::abs(lat_rad) == units::kPi / 2 ? 0.0 : dlon * std::cos(lat_rad)};
}

Deflection deflection_from_zenith_enu_first_order(const Eigen::Vector3d& zenith_enu) {
  if (!zenith_enu.allFinite()) throw InputError("zenith direction vector is not finite");
  if (!(zenith_enu.z() > 0))
    throw InputError(
        fmt::format("zenith direction has up component {} <= 0 (at or below the "
                    "horizon)",
                    zenith_enu.z()));
  return {zenith_enu.y() / zenith_enu.z(), zenith_enu.x() / zenith_enu.z()};
}

}  // namespace meridian::geodesy
