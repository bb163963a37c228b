#pragma once
/// \file gravity_json.hpp
/// JSON views of the gravity commands (their `--json` output). The keys are
/// a stable contract for scripts (docs/gravity-field.md §5).

#include <nlohmann/json.hpp>

#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/grid_run.hpp"
#include "meridian/gravity/points.hpp"

namespace meridian::report {

/// `meridian gravity point --json`: model, model_file, max_degree,
/// latitude_deg, longitude_deg, height_m, xi_arcsec, eta_arcsec, geoid_m,
/// gravity_anomaly_mgal, xi_astro_arcsec, eta_astro_arcsec,
/// disturbing_potential_m2_s2.
nlohmann::json gravity_point_to_json(const gravity::PointResult& r);

/// `meridian gravity geoid-grid --json`: grid, interpolation, latitude_deg,
/// longitude_deg, geoid_m, fallback_xi_arcsec, fallback_eta_arcsec,
/// fallback_method.
nlohmann::json geoid_grid_to_json(const gravity::GridPointResult& r);

/// `meridian gravity grid --json`: output, format, model, model_file, max_degree,
/// region_deg [W, E, S, N], lon_spacing_deg, lat_spacing_deg, registration, height_m (null
/// with per-node heights), height_grid (null without), rows, columns, nodes, quantities
/// [{name, units, long_name}], path_used, fft_length, threads, elapsed_s.
nlohmann::json gravity_grid_to_json(const gravity::GridRunResult& r);

}  // namespace meridian::report
