#pragma once
/// \file laplace.hpp
/// The Laplace equation linking astronomic and geodetic azimuths, to first
/// order in the deflection of the vertical:
///
///     A − α = η·tan φ + (ξ·sin α − η·cos α)·cot z
///
/// A astronomic azimuth (from the plumb line, e.g. a gyro azimuth plus the
/// instrument constant), α geodetic azimuth (from the ellipsoid normal),
/// ξ = Φ − φ and η = (Λ − λ)·cos φ the deflection components, astronomic
/// minus geodetic (sign convention: geodesy/frames.hpp), φ the geodetic
/// latitude of the station and z the zenith distance of the sight from the
/// station to the target. The first term rotates the meridian (astronomic
/// north lies in the plane of the plumb line and the rotation axis); the
/// second tilts the horizon and vanishes for a horizontal sight (z = 90°).
/// Sources: Hofmann-Wellenhof & Moritz, Physical Geodesy, 2nd ed. (2006)
/// §2.19; the first-order derivation from the two local frames is in
/// docs/geodesy.md, and the tests compare the equation with the exact
/// rotation between the frames.
///
/// The equation is first order: terms of order θ²·(tan φ + cot z)·cot z,
/// θ = √(ξ² + η²), are neglected (see docs/geodesy.md for the residual
/// against the exact frames). To that order z may be the geodetic zenith
/// distance (from the heights) or the astronomic one (a booked zenith angle),
/// and α or A may stand in the second term (they differ by O(θ)).

#include "meridian/core/units.hpp"

namespace meridian::geodesy {

/// Smallest accepted zenith distance of a sight (radians, 10°); the largest
/// is π minus it. cot z grows without bound towards the zenith and the nadir,
/// where a sight has no azimuth; within 80° of the horizon |cot z| ≤ 5.7,
/// the term stays first order (its neglected part ≤ θ²·cot²z, 0.016″ for
/// θ = 10″) and a pointing's horizontal-direction error, σ/sin z, at most
/// 5.8 times the pointing σ.
inline constexpr double kMinZenithDistance_rad = 10.0 * units::kDegree;

/// Laplace correction to be added to an astronomic azimuth A to obtain the
/// geodetic azimuth α of a horizontal sight: α = A + laplace_correction(η, φ)
/// = A − η·tan φ (radians). η is the prime-vertical deflection component
/// (η = (Λ − λ)·cos φ, astronomic minus geodetic), φ the geodetic latitude.
/// The zenith-distance term is laplace_zenith_correction_rad.
///
/// eta_rad: radians, positive when the astronomic longitude exceeds the
/// geodetic one (sign convention: geodesy/frames.hpp); |η| ≤ 0.01 rad
/// (kMaxDeflection_rad ≈ 34′, far above the largest deflections on Earth,
/// about 1′; larger values are almost surely a unit error).
/// lat_rad: radians, north positive, |φ| < π/2. Example: η = +5″ at
/// φ = 45° N gives −5″. Throws InputError for non-finite values or values
/// out of range.
double laplace_correction_rad(double eta_rad, double lat_rad);

/// The zenith-distance term of the Laplace equation, as a correction to be
/// added to A (radians): −(ξ·sin α − η·cos α)·cot z, so that
/// α = A + laplace_correction_rad(η, φ) + laplace_zenith_correction_rad(ξ, η, α, z).
///
/// xi_rad, eta_rad: the deflection components (radians, astronomic minus
/// geodetic, |ξ|, |η| ≤ kMaxDeflection_rad). azimuth_rad: the geodetic
/// azimuth α of the sight (radians, any value; A may be used instead, see
/// the file comment). zenith_distance_rad: z of the sight (radians,
/// kMinZenithDistance_rad ≤ z ≤ π − kMinZenithDistance_rad; z < 90° looks
/// up). Example: ξ = +5″, η = 0, α = 90°, z = 70° (a sight 20° upwards to the
/// east) gives −5″·cot 70° = −1.820″; the same sight downwards (z = 110°)
/// gives +1.820″. Throws InputError for non-finite values or values out of
/// range.
double laplace_zenith_correction_rad(double xi_rad, double eta_rad, double azimuth_rad,
                                     double zenith_distance_rad);

/// Throws InputError unless zenith_distance_rad is finite and within
/// [kMinZenithDistance_rad, π − kMinZenithDistance_rad] (the message says
/// that a vertical sight has no azimuth).
void check_zenith_distance(double zenith_distance_rad);

}  // namespace meridian::geodesy
