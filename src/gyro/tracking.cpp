#include "meridian/gyro/tracking.hpp"

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"

namespace meridian::gyro {

TrackingResult reduce_tracking(ReversalMethod method, const TrackingObservations& obs,
                               const Instrument& inst, const ZeroPosition& zero) {
  TrackingResult out;
  const std::vector<double> r = unwrap_circle_readings(obs.reversals_rad);
  try {
    out.fit = estimate_centre(method, r, obs.sigma_reading_rad);
  } catch (InputError& e) {
    e.add_context("", std::nullopt, "reversals");
    throw;
  }
  out.fit.centre.value = wrap_positive_rad(out.fit.centre.value);
  out.north = north_from_tracking(out.fit.centre, inst, zero);
  return out;
}

}  // namespace meridian::gyro
