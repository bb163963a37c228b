#pragma once
/// \file azimuth_chain.hpp
/// The one azimuth chain astronomic ↔ geodetic ↔ grid of a line at its
/// station (gyro-theodolite spec §6, steps 3–4), forward and inverse, with σ.
///
///   α = A − η·tan φ − (ξ·sin α − η·cos α)·cot z    Laplace equation, geodesy/laplace.hpp
///   T = α − γ + δ                                  grid azimuth of the chord, geodesy/grid.hpp
///
/// A astronomic azimuth (from the plumb line, e.g. a gyro azimuth plus the
/// instrument constant), α geodetic azimuth (of the geodesic, from the
/// ellipsoid normal), T grid azimuth of the straight chord on the projection
/// plane; ξ = Φ − φ and η = (Λ − λ)·cos φ the deflection components,
/// astronomic minus geodetic (sign convention: geodesy/frames.hpp); φ the
/// geodetic latitude of the station; z the zenith distance of the sight from
/// the station to the target; γ the meridian convergence at the station
/// (bearing of grid north clockwise from true north, grid.hpp); δ the
/// arc-to-chord correction of the line (geodesy::arc_to_chord, so that
/// T_chord = α − γ + δ).
///
/// What is applied: without η, nothing (α = A). With η, the term −η·tan φ.
/// With η, ξ and z, also the zenith-distance term −(ξ·sin α − η·cos α)·cot z;
/// without z (a horizontal sight, z = 90°) or without ξ it is omitted, and
/// AzimuthSteps says so. ξ without η is an error.
///
/// The zenith-distance term uses α, the geodetic azimuth, as the equation is
/// written. The inverse chains have α; the forward chain solves
/// α = A − η·tan φ − (ξ·sin α − η·cos α)·cot z for α by fixed-point
/// iteration from α₀ = A − η·tan φ (a contraction: |∂/∂α| ≤ θ·|cot z| ≤ 0.08
/// within the guards, θ = √(ξ² + η²); a few iterations reach 1e-16 rad), so
/// that forward and inverse are exact inverses of each other. Using A in
/// the term instead would differ by O(θ²·cot z·(tan φ + cot z)), below the
/// accuracy of the first-order equation itself (laplace.hpp).
///
/// Signs (worked examples in the tests): η > 0 at φ = 45° N gives α = A − η;
/// ξ > 0 on a sight due east 20° upwards (z = 70°) gives α = A − ξ·cot 70°;
/// γ > 0 east of the central meridian in the northern hemisphere gives T < α.
///
/// Units: radians; azimuths clockwise from north, every output normalised to
/// [0, 2π) by wrap_positive_rad. σ: the given kind keeps its σ; the Laplace
/// step adds, in quadrature, the deflection's part to the kinds on the other
/// side of it (errors of ξ, η and the given azimuth independent): tan φ·σ(η)
/// without the zenith-distance term; with it, (tan φ − cos α·cot z)·σ(η)
/// and sin α·cot z·σ(ξ) — η enters both terms, so its two parts add
/// linearly. z (and the α inside the term) are taken as exact: an error
/// σ(z) changes the term by θ·σ(z)/sin²z, second order. γ and δ are exact.
///
/// Floating-point order (kept so that the gyro outputs stay byte-identical
/// when ξ and z are not given): the forward chain wraps each step
/// (α = wrap(A − η·tan φ), T = wrap(α − γ + δ) evaluated as (α − γ) + δ); the
/// inverse chains wrap only their outputs (from grid: α = (T + γ) − δ,
/// A = α + η·tan φ; from geodetic: A = α + η·tan φ, T = (α − γ) + δ). With
/// the zenith-distance term c_z: α = wrap((A + c_η) + c_z) and
/// A = (α − c_η) − c_z, c_η = −η·tan φ.
///
/// Errors: InputError for a non-finite azimuth, σ, γ or δ, a negative σ;
/// when η is given, from laplace_correction_rad (non-finite η or
/// |η| > 0.01 rad, |φ| ≥ 90°); ξ given without η, non-finite ξ or
/// |ξ| > 0.01 rad; a zenith distance (whenever given) outside
/// [kMinZenithDistance_rad, π − kMinZenithDistance_rad] (10°…170°).
/// NumericalError if the forward iteration does not converge (not expected
/// within the guards).

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
  /// ξ at the station (astro − geodetic, radians, |ξ| ≤ 0.01); needs η. Used
  /// only by the zenith-distance term (with zenith_distance_rad).
  std::optional<Uncertain> xi_rad{};
  /// Zenith distance z of the sight from the station to the target (radians,
  /// 10° ≤ z ≤ 170°, z < 90° upwards; geodetic or astronomic, the same to
  /// first order); none: a horizontal sight, the zenith-distance term omitted.
  std::optional<double> zenith_distance_rad{};
};

/// One line's azimuth of every kind, with σ (radians, azimuths in [0, 2π)).
struct AzimuthSteps {
  Uncertain astronomic_rad;             ///< A
  Uncertain geodetic_rad;               ///< α = A − η·tan φ
  Uncertain grid_rad;                   ///< T = α − γ + δ
  double laplace_correction_rad = 0.0;  ///< −η·tan φ (0 when not applied)
  bool laplace_applied = false;
  /// −(ξ·sin α − η·cos α)·cot z (0 when not applied): α = A + laplace + this.
  double zenith_correction_rad = 0.0;
  bool zenith_term_applied = false;  ///< ξ, η and z were all given
  double convergence_rad = 0.0;      ///< γ
  double arc_to_chord_rad = 0.0;     ///< δ (0 when not applied)
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
