#pragma once
/// \file gravity_text.hpp
/// Plain-text reports of the gravity commands for the terminal: ξ, η in
/// arc-seconds (astronomic minus geodetic, docs/gravity-field.md), N in
/// metres.

#include <string>

#include "meridian/gravity/geoid_grid.hpp"
#include "meridian/gravity/grid_run.hpp"
#include "meridian/gravity/points.hpp"
#include "meridian/gravity/synthetic.hpp"

namespace meridian::report {

/// The model as its file states it, two lines: "model NAME (degree USED,
/// FILE)" and "model GM … m^3/s^2, reference radius … m, tide system …,
/// normalisation …" ("not stated" where the file does not say), then a
/// "warning: " line for each gravity::model_warnings.
std::string model_text(const gravity::ModelInfo& model);

/// Only model_text's "warning: " lines (`gravity points -q`, `gravity grid -q`/`--json` on
/// stderr); empty when there is nothing to warn about.
std::string model_warnings_text(const gravity::ModelInfo& model);

/// `meridian gravity point`: model_text's lines, the point (degrees, 9
/// decimals; h in m, 3), xi_arcsec, eta_arcsec, geoid_m (9 decimals), then
/// the model's warnings.
std::string gravity_point_text(const gravity::PointResult& r);

/// `meridian gravity geoid-grid`: the grid file and interpolation, the model
/// as far as the grid states it, geoid_m (6 decimals) and the fallback ξ, η
/// (arc-seconds, 3 decimals) labelled with their method, or "unavailable"
/// with the reason; then notes (interpolation used) and warnings.
std::string geoid_grid_text(const gravity::GridPointResult& r);

/// `meridian gravity grid`: three lines — "wrote FILE (FORMAT): C x R nodes (lon x lat,
/// REGISTRATION registration), NAME [UNITS], …", where the heights came from, and the path
/// used (FFT length, or GravityCircle per parallel, or per-node points), the threads and the
/// wall time (s, 2 decimals).
std::string gravity_grid_text(const gravity::GridRunResult& r);

/// `meridian gravity synth-model`: "wrote PREFIX.gfc, PREFIX.egm, PREFIX.egm.cof (model NAME,
/// degree N, seed S)".
std::string synthetic_model_text(const gravity::SyntheticModelFiles& r);

}  // namespace meridian::report
