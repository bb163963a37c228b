#pragma once
/// \file sight.hpp
/// The zenith distance of a straight line of sight between two points given
/// by geodetic coordinates and ellipsoidal heights, for the zenith-distance
/// term of the Laplace equation (geodesy/laplace.hpp).
///
/// Rigorous: both points to ECEF (GeographicLib::Geocentric on the given
/// ellipsoid), the chord rotated into the geodetic ENU frame of the station
/// (rotation_ecef_to_enu, geodesy/frames.hpp), z = atan2(√(e² + n²), u).
/// This is the zenith distance from the ellipsoid normal of the straight
/// chord; the Earth's curvature is included, refraction is not (a
/// coefficient k = 0.13 bends a sight by k·s/(2R) ≈ 2″ per kilometre, which
/// changes the Laplace term by a factor 1 + O(1e-5)).
///
/// The surveyor's spherical formula z ≈ π/2 − atan(Δh/s) + s/(2R) (s the
/// horizontal distance, R a mean radius) neglects h/R in the distance and
/// cos²(elevation) on the curvature term: about 11″ off on a 1 km, 20° sight
/// at 860 m (tests; docs/geodesy.md) — still far below what matters for the
/// term, which an error δz changes by θ·δz/sin²z.
///
/// Heights: ellipsoidal heights h. Only the height difference matters to
/// first order; normal or orthometric heights (a mine datum) may be used
/// instead when the geoid changes by less than a few centimetres along the
/// line (slope error Δ(N)/s, e.g. 0.02 m / 100 m ≈ 41″ in z — still
/// negligible for the term).

#include "meridian/geodesy/ellipsoid.hpp"

namespace meridian::geodesy {

/// A point by geodetic latitude, longitude (radians, north/east positive)
/// and ellipsoidal height (metres).
struct GeodeticPosition {
  double lat_rad = 0.0;
  double lon_rad = 0.0;
  double height_m = 0.0;
};

/// Zenith distance (radians, in [0, π]; < π/2 when `to` is seen upwards) of
/// the straight sight from `from` to `to`, measured from the ellipsoid normal
/// at `from`, rigorously (file comment). Throws InputError for non-finite
/// input, |latitude| > π/2, an invalid ellipsoid (a ≤ 0, f outside [0, 1))
/// or coincident points (closer than 1 mm).
double sight_zenith_distance_rad(const GeodeticPosition& from, const GeodeticPosition& to,
                                 const Ellipsoid& ellipsoid);

}  // namespace meridian::geodesy
