#pragma once
/// \file gravity_text.hpp
/// Plain-text reports of the gravity commands for the terminal: ξ, η in
/// arc-seconds (astronomic minus geodetic, docs/gravity-field.md), N in
/// metres.

#include <string>

#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/points.hpp"

namespace meridian::report {

/// `meridian gravity point`: the model (name, degree, file), the point
/// (degrees, 9 decimals; h in m, 3), xi_arcsec, eta_arcsec, geoid_m (9 decimals).
std::string gravity_point_text(const gravity::PointResult& r);

/// `meridian gravity geoid-grid`: the grid file and interpolation, geoid_m
/// (6 decimals) and the fallback ξ, η (arc-seconds, 3 decimals) labelled
/// with their method.
std::string geoid_grid_text(const gravity::GridPointResult& r);

}  // namespace meridian::report
