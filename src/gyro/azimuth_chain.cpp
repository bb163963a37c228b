#include "meridian/gyro/azimuth_chain.hpp"

#include <cmath>

#include "meridian/core/angle.hpp"
#include "meridian/geodesy/azimuth_chain.hpp"

namespace meridian::gyro {

AzimuthChainResult azimuth_chain(const AzimuthChainInput& in) {
  AzimuthChainResult r;
  const double ag = wrap_positive_rad(in.gyro_azimuth_rad.value);
  const double sag = in.gyro_azimuth_rad.sigma;
  r.gyro_azimuth_rad = {ag, sag};
  // A = A_G + E; the rest of the chain is geodesy's.
  const Uncertain a{wrap_positive_rad(ag + in.instrument_constant_rad.value),
                    std::hypot(sag, in.instrument_constant_rad.sigma)};
  const geodesy::AzimuthSteps s =
      geodesy::azimuth_from_astronomic(a, {in.latitude_rad, in.eta_rad, in.convergence_rad,
                                           in.arc_to_chord_rad, in.xi_rad, in.zenith_distance_rad});
  r.astronomic_azimuth_rad = s.astronomic_rad;
  r.geodetic_azimuth_rad = s.geodetic_rad;
  r.grid_azimuth_rad = s.grid_rad;
  r.laplace_correction_rad = s.laplace_correction_rad;
  r.zenith_correction_rad = s.zenith_correction_rad;
  r.zenith_distance_rad = in.zenith_distance_rad;
  r.zenith_term_applied = s.zenith_term_applied;
  r.convergence_rad = s.convergence_rad;
  r.arc_to_chord_rad = s.arc_to_chord_rad;
  r.laplace_applied = s.laplace_applied;
  r.arc_to_chord_applied = s.arc_to_chord_applied;
  if (!s.laplace_applied)
    r.notes.push_back(
        "Laplace correction not applied (eta unknown): geodetic azimuth taken equal to the "
        "astronomic one. If E was calibrated on a geodetic or grid known line nearby, the "
        "deflection is absorbed into E.");
  if (!s.arc_to_chord_applied)
    r.notes.push_back("arc-to-chord correction not applied (target coordinates not given)");
  return r;
}

}  // namespace meridian::gyro
