#include "meridian/geodesy/laplace.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/frames.hpp"

namespace meridian::geodesy {

double laplace_correction_rad(double eta_rad, double lat_rad) {
  if (!std::isfinite(eta_rad) || std::abs(eta_rad) > kMaxDeflection_rad)
    throw InputError(fmt::format(
        "deflection component eta = {} rad ({}\") is not finite or exceeds 0.01 rad; "
        "is it in radians?",
        eta_rad, units::rad_to_arcsec(eta_rad)));
  // tan φ is unbounded at the poles, where an azimuth has no meaning anyway.
  if (!std::isfinite(lat_rad) || std::abs(lat_rad) >= units::kPi / 2)
    throw InputError(fmt::format("latitude {} rad ({} deg) must satisfy |lat| < 90 deg",
                                 lat_rad, units::rad_to_deg(lat_rad)));
  return -eta_rad * std::tan(lat_rad);
}

}  // namespace meridian::geodesy
