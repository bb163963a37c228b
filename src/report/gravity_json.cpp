#include "meridian/report/gravity_json.hpp"

#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

using nlohmann::json;

// A text the file may not state: null then.
json stated(const std::string& s) { return s.empty() ? json(nullptr) : json(s); }

}  // namespace

nlohmann::json gravity_point_to_json(const gravity::PointResult& r) {
  const gravity::FieldValues& v = r.values;
  const gravity::ModelInfo& m = r.model;
  return {{"model", m.name},
          {"model_file", m.source_file},
          {"max_degree", m.max_degree},
          {"file_max_degree", m.file_max_degree},
          {"model_description", stated(m.description)},
          {"gm_m3_s2", m.gm_m3_s2},
          {"reference_radius_m", m.radius_m},
          {"tide_system", stated(m.tide_system)},
          {"normalization", stated(m.normalization)},
          {"warnings", gravity::model_warnings(m)},
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
  const bool have = r.fallback.has_value();
  json j = {{"grid", r.grid_file},
            {"grid_format", r.grid.format},
            {"grid_metadata", r.grid.metadata},
            {"model", r.grid.model ? json(*r.grid.model) : json(nullptr)},
            {"max_degree", nullptr},
            {"gm_m3_s2", nullptr},
            {"reference_radius_m", nullptr},
            {"tide_system", nullptr},
            {"normalization", nullptr},
            {"interpolation", gravity::to_string(r.interpolation)},
            {"interpolation_used", gravity::to_string(r.interpolation_used)},
            {"latitude_deg", units::rad_to_deg(r.lat_rad)},
            {"longitude_deg", units::rad_to_deg(r.lon_rad)},
            {"geoid_m", r.geoid_m},
            {"fallback_available", have},
            {"fallback_xi_arcsec", have ? json(units::rad_to_arcsec(r.fallback->xi_rad)) : json(nullptr)},
            {"fallback_eta_arcsec", have ? json(units::rad_to_arcsec(r.fallback->eta_rad)) : json(nullptr)},
            {"fallback_method", gravity::GridDeflection{}.method},
            {"fallback_unavailable_reason", have ? json(nullptr) : json(r.fallback_unavailable)},
            {"notes", r.notes},
            {"warnings", r.grid.warnings}};
  return j;
}

nlohmann::json gravity_grid_to_json(const gravity::GridRunResult& r) {
  const gravity::GridSpec& spec = r.spec;
  const bool per_node = !r.height_grid.empty();
  json q = json::array();
  for (const gravity::GridFileQuantity& x : r.quantities)
    q.push_back({{"name", x.name}, {"units", x.units}, {"long_name", x.long_name}});
  return {{"output", r.output},
          {"format", r.format},
          {"model", r.model.name},
          {"model_file", r.model.source_file},
          {"max_degree", r.model.max_degree},
          {"region_deg", {spec.west_deg, spec.east_deg, spec.south_deg, spec.north_deg}},
          {"lon_spacing_deg", spec.lon_spacing_deg},
          {"lat_spacing_deg", spec.lat_spacing_deg},
          {"registration", std::string(gravity::to_string(spec.registration))},
          {"height_m", per_node ? json(nullptr) : json(spec.height_m)},
          {"height_grid", per_node ? json(r.height_grid) : json(nullptr)},
          {"rows", r.synthesis.rows},
          {"columns", r.synthesis.columns},
          {"stored_columns", r.stored_columns},
          {"nodes", spec.nodes()},
          {"quantities", q},
          {"path_used", std::string(gravity::to_string(r.synthesis.path_used))},
          {"fft_length", r.synthesis.fft_length},
          {"threads", r.synthesis.threads},
          {"elapsed_s", r.elapsed_s}};
}

}  // namespace meridian::report
