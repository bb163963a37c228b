#pragma once
/// \file azimuth_chain.hpp
/// The one azimuth chain astronomic ↔ geodetic ↔ grid of a line at its
/// station (gyro-theodolite spec §6, steps 3–4), forward and inverse, with σ.
///
///   α = A − η·tan φ          Laplace equation (horizontal sight), geodesy/laplace.hpp
///   T = α − γ + δ            grid azimuth of the chord, geodesy/grid.hpp
///
/// A astronomic azimuth (from the plumb line, e.g. a gyro azimuth plus the
/// instrument constant), α geodetic azimuth (of the geodesic, from the
/// ellipsoid normal), T grid azimuth of the straight chord on the projection
/// plane; η = (Λ − λ)·cos φ the prime-vertical deflection, astronomic minus
/// geodetic (sign convention: geodesy/frames.hpp); φ the geodetic latitude of
/// the station; γ the meridian convergence at the station (bearing of grid
/// north clockwise from true north, grid.hpp); δ the arc-to-chord correction
/// of the line (geodesy::arc_to_chord, so that T_chord = α − γ + δ).
///
/// Signs (worked examples in the tests): η > 0 at φ = 45° N gives α = A − η;
/// γ > 0 east of the central meridian in the northern hemisphere gives T < α.
///
/// Units: radians; azimuths clockwise from north, every output normalised to
/// [0, 2π) by wrap_positive_rad. σ: the given kind keeps its σ; the Laplace
/// step adds tan φ·σ(η) in quadrature (η's error independent of the given
/// azimuth's) to the kinds on the other side of it; γ and δ are taken as
/// exact. The zenith-distance term of the Laplace equation is neglected
/// (horizontal sights, see laplace.hpp).
///
/// Floating-point order (kept so that the gyro outputs stay byte-identical):
/// the forward chain wraps each step (α = wrap(A − η·tan φ), T = wrap(α − γ
/// + δ) evaluated as (α − γ) + δ); the inverse chains wrap only their
/// outputs (from grid: α = (T + γ) − δ, A = α + η·tan φ; from geodetic:
/// A = α + η·tan φ, T = (α − γ) + δ).
///
/// Errors: InputError for a non-finite azimuth, σ, γ or δ, a negative σ,
/// and — when η is given — from laplace_correction_rad: non-finite η or
/// |η| > 0.01 rad, |φ| ≥ 90°.

#include <optional>
#include <string>

#include "meridian/core/uncertain.hpp"

namespace meridian::geodesy {

/// The three kinds of azimuth of a line.
enum class AzimuthKind { Astronomic, Geodetic, Grid };

/// "astronomic", "geodetic", "grid".
std::string to_string(AzimuthKind kind);

/// The reductions of one line at its station.
struct AzimuthReduction {
  /// Geodetic latitude φ of the station (radians; |φ| < π/2 when η is given).
  double latitude_rad = 0.0;
  /// η at the station (astro − geodetic, radians, |η| ≤ 0.01); none: Laplace not applied, α = A.
  std::optional<Uncertain> eta_rad;
  /// Meridian convergence γ at the station (grid north from true north, clockwise; radians).
  double convergence_rad = 0.0;
  /// δ of the line (geodesy::arc_to_chord, radians); none: not applied.
  std::optional<double> arc_to_chord_rad;
};

/// One line's azimuth of every kind, with σ (radians, azimuths in [0, 2π)).
struct AzimuthSteps {
  Uncertain astronomic_rad;             ///< A
  Uncertain geodetic_rad;               ///< α = A − η·tan φ
  Uncertain grid_rad;                   ///< T = α − γ + δ
  double laplace_correction_rad = 0.0;  ///< −η·tan φ (0 when not applied)
  bool laplace_applied = false;
  double convergence_rad = 0.0;   ///< γ
  double arc_to_chord_rad = 0.0;  ///< δ (0 when not applied)
  bool arc_to_chord_applied = false;
};

/// Forward: from the astronomic azimuth A (any value; radians, σ ≥ 0).
/// Throws InputError as in the file comment.
AzimuthSteps azimuth_from_astronomic(Uncertain astronomic_rad, const AzimuthReduction& r);

/// Any kind to every kind: `value_rad` is an azimuth of kind `kind` (any
/// value, radians, σ ≥ 0). Astronomic is azimuth_from_astronomic; Geodetic
/// and Grid run the inverse chain (e.g. a known line given in grid or
/// geodetic azimuth, reduced to the astronomic azimuth a gyro observes).
/// Throws InputError as in the file comment.
AzimuthSteps azimuth_steps(AzimuthKind kind, Uncertain value_rad, const AzimuthReduction& r);

}  // namespace meridian::geodesy
