// Uses the installed library: DMS parsing and a tracking reduction.
#include <cmath>
#include <cstdio>

#include "meridian/core/dms.hpp"
#include "meridian/gyro/tracking.hpp"

int main() {
  meridian::gyro::TrackingObservations obs;
  for (const char* r : {"359 41 12", "0 44 50", "359 42 04"})
    obs.reversals_rad.push_back(meridian::parse_angle(r).rad());
  meridian::gyro::Instrument inst;
  inst.scale_value_rad = meridian::Angle::arcseconds(600).rad();
  inst.torsion_ratio = {0.3, 0.0};
  const auto t = meridian::gyro::reduce_tracking(meridian::gyro::ReversalMethod::Schuler, obs, inst);
  const double expect = meridian::Angle::arcseconds(794.0).rad();  // (−1128 + 2·2690 − 1076)/4 "
  std::printf("consumer: N_G = %s\n", meridian::format_dms(meridian::Angle::radians(t.north.north_rad)).c_str());
  return std::fabs(t.north.north_rad - expect) < 1e-9 ? 0 : 1;
}
