#pragma once
/// \file track.hpp
/// Along-track evaluation: a densely sampled survey line (millions of
/// samples) is evaluated at a subset of its points and linearly
/// interpolated in along-track distance elsewhere, refining adaptively until
/// the interpolation error, checked against the model at the midpoint of
/// every interval, is below the tolerance.
///
/// Error statement: for linear interpolation over an interval of length Δ,
/// e(s) = −½ f″(ζ)(s − s0)(s1 − s), largest (Δ²/8 |f″|) at the midpoint. The
/// refinement stops only when the *measured* error at every interval's
/// midpoint is ≤ tolerance, so the error anywhere is ≤ tolerance as long as
/// f″ varies little within an interval (true once Δ is well below the
/// shortest half-wavelength πR/N of the model, e.g. 9 km for N = 2190; the
/// initial spacing is 0.05 R/N and intervals never span more than that).

#include <cstddef>
#include <span>
#include <vector>

#include "meridian/core/units.hpp"
#include "meridian/gravity/gravity_field.hpp"

namespace meridian::gravity {

struct TrackOptions {
  double tolerance_rad = 1e-4 * units::kArcsecond;  ///< for ξ, η (and the astronomic variant), rad
  double tolerance_geoid_m = 1e-5;                  ///< for N, metres
  /// Largest node spacing along the track (m); 0 = 0.05 R/N (R = 6371 km).
  double max_node_spacing_m = 0;
};

struct TrackResult {
  std::vector<FieldValues> values;         ///< one per track point
  std::size_t model_evaluations = 0;       ///< points evaluated with the full model (nodes and checks)
  double max_checked_error_rad = 0;        ///< largest |interpolated − model| of ξ, η at accepted midpoints
  double max_checked_error_geoid_m = 0;    ///< same for N
};

/// Evaluate `what` along `track` (consecutive points of one line; spacing
/// and heights may vary). All points are validated first as in
/// GravityField::evaluate. Nodes are evaluated in vectorised, threaded
/// batches. Throws InputError for non-positive tolerances.
TrackResult evaluate_track(const GravityField& field, std::span<const GeodeticPoint> track,
                           Quantities what = Quantities::All, const TrackOptions& options = {});

}  // namespace meridian::gravity
