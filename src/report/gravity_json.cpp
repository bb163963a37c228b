#include "meridian/report/gravity_json.hpp"

#include "meridian/core/units.hpp"

namespace meridian::report {

nlohmann::json gravity_point_to_json(const gravity::PointResult& r) {
  const gravity::FieldValues& v = r.values;
  return {{"model", r.model.name},
          {"model_file", r.model.source_file},
          {"max_degree", r.model.max_degree},
          {"latitude_deg", units::rad_to_deg(r.point.lat_rad)},
          {"longitude_deg", units::rad_to_deg(r.point.lon_rad)},
          {"height_m", r.point.height_m},
          {"xi_arcsec", units::rad_to_arcsec(v.xi_rad)},
          {"eta_arcsec", units::rad_to_arcsec(v.eta_rad)},
          {"geoid_m", v.geoid_m},
          {"gravity_anomaly_mgal", v.anomaly_m_s2 * 1e5},
          {"xi_astro_arcsec", units::rad_to_arcsec(v.xi_astro_rad)},
          {"eta_astro_arcsec", units::rad_to_arcsec(v.eta_astro_rad)},
          {"disturbing_potential_m2_s2", v.disturbing_potential_m2_s2}};
}

nlohmann::json geoid_grid_to_json(const gravity::GridPointResult& r) {
  return {{"grid", r.grid_file},
          {"interpolation", gravity::to_string(r.interpolation)},
          {"latitude_deg", units::rad_to_deg(r.lat_rad)},
          {"longitude_deg", units::rad_to_deg(r.lon_rad)},
          {"geoid_m", r.geoid_m},
          {"fallback_xi_arcsec", units::rad_to_arcsec(r.fallback.xi_rad)},
          {"fallback_eta_arcsec", units::rad_to_arcsec(r.fallback.eta_rad)},
          {"fallback_method", r.fallback.method}};
}

}  // namespace meridian::report
