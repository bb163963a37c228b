#pragma once
/// \file laplace.hpp
/// The Laplace equation linking astronomic and geodetic azimuths.

namespace meridian::geodesy {

/// Laplace correction to be added to an astronomic azimuth A to obtain the
/// geodetic azimuth α: α = A + laplace_correction(η, φ) = A − η·tan φ
/// (radians). η is the prime-vertical deflection component (η = (Λ − λ)·cos φ,
/// astronomic minus geodetic), φ the geodetic latitude. Zenith-distance
/// terms are neglected (horizontal sightings).
double laplace_correction_rad(double eta_rad, double lat_rad);

}  // namespace meridian::geodesy
