#pragma once
/// \file gravity_html.hpp
/// The HTML report document of `meridian gravity points --report`: built
/// from the run's result (gravity::PointsResult: its summary and thinned
/// sample), so a run of any length streams. Render with render_html().

#include <string>

#include "meridian/gravity/points.hpp"
#include "meridian/report/html.hpp"

namespace meridian::report {

/// Sections (HTML ids):
/// * `summary`: the number of points, a table of the minimum, maximum,
///   mean, RMS and standard deviation of ξ, η (arc-seconds) and N (metres),
///   and the extent of the points;
/// * `maps`: three Vega-Lite point maps (longitude, latitude) of the
///   thinned sample, coloured by ξ, by η and by N, each captioned with how
///   many of how many points it draws — none when the input had no points;
/// * `definitions`: what ξ, η and N are and their signs (astronomic minus
///   geodetic), the evaluation (full model, or along-track interpolation
///   and its tolerance).
/// The header names the input, the model (name, file, degree) and the options.
Document gravity_points_document(const gravity::PointsResult& result);

}  // namespace meridian::report
