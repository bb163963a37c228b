#pragma once
/// \file gravity_text.hpp
/// Plain-text reports of the gravity commands for the terminal: ξ, η in
/// arc-seconds (astronomic minus geodetic, docs/gravity-field.md), N in
/// metres.

#include <string>

#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/points.hpp"

namespace meridian::report {

/// The model as its file states it, two lines: "model NAME (degree USED,
/// FILE)" and "model GM … m^3/s^2, reference radius … m, tide system …,
/// normalisation …" ("not stated" where the file does not say), then a
/// "warning: " line for each gravity::model_warnings.
std::string model_text(const gravity::ModelInfo& model);

/// `meridian gravity point`: model_text's lines, the point (degrees, 9
/// decimals; h in m, 3), xi_arcsec, eta_arcsec, geoid_m (9 decimals), then
/// the model's warnings.
std::string gravity_point_text(const gravity::PointResult& r);

/// `meridian gravity geoid-grid`: the grid file and interpolation, the model
/// as far as the grid states it, geoid_m (6 decimals) and the fallback ξ, η
/// (arc-seconds, 3 decimals) labelled with their method, or "unavailable"
/// with the reason; then notes (interpolation used) and warnings.
std::string geoid_grid_text(const gravity::GridPointResult& r);

}  // namespace meridian::report
