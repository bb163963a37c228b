#pragma once
/// \file laplace.hpp
/// The Laplace equation linking astronomic and geodetic azimuths.

namespace meridian::geodesy {

/// Laplace correction to be added to an astronomic azimuth A to obtain the
/// geodetic azimuth α: α = A + laplace_correction(η, φ) = A − η·tan φ
/// (radians). η is the prime-vertical deflection component (η = (Λ − λ)·cos φ,
/// astronomic minus geodetic), φ the geodetic latitude. Zenith-distance
/// terms are neglected (horizontal sightings).
///
/// eta_rad: radians, positive when the astronomic longitude exceeds the
/// geodetic one (sign convention: geodesy/frames.hpp); |η| ≤ 0.01 rad
/// (kMaxDeflection_rad ≈ 34′, far above the largest deflections on Earth,
/// about 1′; larger values are almost surely a unit error).
/// lat_rad: radians, north positive, |φ| < π/2. Example: η = +5″ at
/// φ = 45° N gives −5″. Throws InputError for non-finite values or values
/// out of range.
double laplace_correction_rad(double eta_rad, double lat_rad);

}  // namespace meridian::geodesy
