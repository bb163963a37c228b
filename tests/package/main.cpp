// Uses the installed library: DMS parsing and a tracking reduction; a small global grid by the
// FFT path (Meridian::gravity links FFTW privately) and the units of a grid file
// (Meridian::io_gravity links netCDF privately), so their link dependencies are checked too.
#include <cmath>
#include <cstdio>
#include <string>

#include "meridian/core/dms.hpp"
#include "meridian/gravity/grid_synthesis.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/gyro/tracking.hpp"
#include "meridian/io/gravity_grid_files.hpp"

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

  namespace mg = meridian::gravity;
  const mg::GravityField field(mg::make_synthetic_model({8, 1, 1e-5}));
  mg::GridSpec spec;
  meridian::gravity::parse_grid_region("g", spec);
  spec.lon_spacing_deg = spec.lat_spacing_deg = 30;
  spec.quantities = {mg::GridQuantity::Geoid};
  std::size_t nodes = 0;
  const auto r = mg::synthesize_grid(field, spec, [&](const mg::GridRow& row) { nodes += row.columns; });
  std::printf("consumer: %zu grid nodes by the %s path, geoid in %s\n", nodes,
              std::string(mg::to_string(r.path_used)).c_str(),
              std::string(meridian::io::grid_quantity_format(mg::GridQuantity::Geoid).units).c_str());
  return std::fabs(t.north.north_rad - expect) < 1e-9 && nodes == 13 * 7 && r.path_used == mg::GridPath::Fft ? 0 : 1;
}
