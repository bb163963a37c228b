#include "meridian/geodesy/laplace.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/frames.hpp"

namespace meridian::geodesy {
namespace {

void require_deflection(double v, const char* name) {
  if (!std::isfinite(v) || std::abs(v) > kMaxDeflection_rad)
    throw InputError(
        fmt::format("deflection component {} = {} rad ({}\") is not finite or exceeds 0.01 rad; "
                    "is it in radians?",
                    name, v, units::rad_to_arcsec(v)));
}

}  // namespace

double laplace_correction_rad(double eta_rad, double lat_rad) {
  require_deflection(eta_rad, "eta");
  // tan φ is unbounded at the poles, where an azimuth has no meaning anyway.
  if (!std::isfinite(lat_rad) || std::abs(lat_rad) >= units::kPi / 2)
    throw InputError(fmt::format("latitude {} rad ({} deg) must satisfy |lat| < 90 deg", lat_rad,
                                 units::rad_to_deg(lat_rad)));
  return -eta_rad * std::tan(lat_rad);
}

void check_zenith_distance(double zenith_distance_rad) {
  const double z = zenith_distance_rad;
  if (!std::isfinite(z) || z < kMinZenithDistance_rad || z > units::kPi - kMinZenithDistance_rad)
    throw InputError(fmt::format(
        "zenith distance {:.4f} deg of the sight must be within [{:g}, {:g}] deg: a sight "
        "near the zenith or the nadir has no usable azimuth (cot z unbounded)",
        units::rad_to_deg(z), units::rad_to_deg(kMinZenithDistance_rad),
        180.0 - units::rad_to_deg(kMinZenithDistance_rad)));
}

double laplace_zenith_correction_rad(double xi_rad, double eta_rad, double azimuth_rad,
                                     double zenith_distance_rad) {
  require_deflection(xi_rad, "xi");
  require_deflection(eta_rad, "eta");
  if (!std::isfinite(azimuth_rad))
    throw InputError(fmt::format("azimuth {} is not finite", azimuth_rad));
  check_zenith_distance(zenith_distance_rad);
  const double cot_z = std::cos(zenith_distance_rad) / std::sin(zenith_distance_rad);
  return -(xi_rad * std::sin(azimuth_rad) - eta_rad * std::cos(azimuth_rad)) * cot_z;
}

}  // namespace meridian::geodesy
