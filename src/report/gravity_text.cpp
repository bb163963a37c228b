#include "meridian/report/gravity_text.hpp"

#include <fmt/format.h>

#include "meridian/core/units.hpp"

namespace meridian::report {

std::string gravity_point_text(const gravity::PointResult& r) {
  return fmt::format(
      "model {} (degree {}, {})\npoint lat {:.9f} deg, lon {:.9f} deg, h {:.3f} m\n"
      "xi_arcsec  {:.9f}\neta_arcsec {:.9f}\ngeoid_m    {:.9f}\n",
      r.model.name, r.model.max_degree, r.model.source_file, units::rad_to_deg(r.point.lat_rad),
      units::rad_to_deg(r.point.lon_rad), r.point.height_m, units::rad_to_arcsec(r.values.xi_rad),
      units::rad_to_arcsec(r.values.eta_rad), r.values.geoid_m);
}

std::string geoid_grid_text(const gravity::GridPointResult& r) {
  return fmt::format(
      "grid {} ({})\ngeoid_m    {:.6f}\nxi_arcsec  {:.3f}  [{}]\neta_arcsec {:.3f}  [{}]\n",
      r.grid_file, gravity::to_string(r.interpolation), r.geoid_m,
      units::rad_to_arcsec(r.fallback.xi_rad), r.fallback.method,
      units::rad_to_arcsec(r.fallback.eta_rad), r.fallback.method);
}

}  // namespace meridian::report
