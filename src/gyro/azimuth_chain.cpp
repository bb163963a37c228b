#include "meridian/gyro/azimuth_chain.hpp"

#include <cmath>

#include "meridian/core/angle.hpp"

namespace meridian::gyro {

AzimuthChainResult azimuth_chain(const AzimuthChainInput& in) {
  AzimuthChainResult r;
  const double ag = wrap_positive_rad(in.gyro_azimuth_rad.value);
  const double sag = in.gyro_azimuth_rad.sigma;
  r.gyro_azimuth_rad = {ag, sag};
  const double a = wrap_positive_rad(ag + in.instrument_constant_rad.value);
  const double sa = std::hypot(sag, in.instrument_constant_rad.sigma);
  r.astronomic_azimuth_rad = {a, sa};
  double alpha = a, salpha = sa;
  if (in.eta_rad) {
    const double t = std::tan(in.latitude_rad);
    r.laplace_correction_rad = -in.eta_rad->value * t;
    alpha = wrap_positive_rad(a + r.laplace_correction_rad);
    salpha = std::hypot(sa, t * in.eta_rad->sigma);
    r.laplace_applied = true;
  } else {
    r.notes.push_back(
        "Laplace correction not applied (eta unknown): geodetic azimuth taken equal to the "
        "astronomic one. If E was calibrated on a geodetic or grid known line nearby, the "
        "deflection is absorbed into E.");
  }
  r.geodetic_azimuth_rad = {alpha, salpha};
  r.convergence_rad = in.convergence_rad;
  double t = alpha - in.convergence_rad;
  if (in.arc_to_chord_rad) {
    r.arc_to_chord_rad = *in.arc_to_chord_rad;
    t += *in.arc_to_chord_rad;
    r.arc_to_chord_applied = true;
  } else {
    r.notes.push_back("arc-to-chord correction not applied (target coordinates not given)");
  }
  r.grid_azimuth_rad = {wrap_positive_rad(t), salpha};
  return r;
}

}  // namespace meridian::gyro
