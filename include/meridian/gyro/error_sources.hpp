#pragma once
/// \file error_sources.hpp
/// The parts of a campaign's σ of the grid azimuth T that another
/// orientation of the same line may share: the known line's azimuth as given
/// (both orientations calibrate on it), ξ and η at the known station and at
/// the line's station (the same model, or the same booked values, at the same
/// points), and an instrument constant booked rather than calibrated. The
/// rest of σ(T) — the gyro runs on both lines — is each orientation's own.
///
/// Two orientations share a source when it is of the same kind, at the same
/// points (within kSamePointTolerance_m, orientations.hpp), from the same
/// source (text) and with the same value; the covariance of their T is then
/// Σ c₁·c₂ over the shared sources (first-order propagation,
/// cov(T₁, T₂) = Σ_k ∂T₁/∂x_k · ∂T₂/∂x_k · σ_k²), and the σ of the mean
/// of n orientations is sqrt(ΣᵢΣⱼ C_ij)/n (docs/gyro-theodolite.md, "Two
/// orientations").
///
/// Signs (worked from the chain, spec §4): T = α − γ + δ, α = A − η·tan φ + c_z,
/// A = A_G + E, E = A_known − A_G,known, A_known = α_known + η_k·tan φ_k − c_z,k,
/// with c_z = −(ξ·sin α − η·cos α)·cot z. Hence ∂T/∂α_known = +1,
/// ∂T/∂η_k = tan φ_k − cos α_k·cot z_k, ∂T/∂ξ_k = sin α_k·cot z_k,
/// ∂T/∂η = −tan φ + cos α·cot z, ∂T/∂ξ = −sin α·cot z (the cot z terms where
/// the zenith-distance term is applied), ∂T/∂E = +1 for a booked E.
/// Example: φ = 36°, η = 5″ ± 1″ at the station, no zenith term: c = −tan 36°·1″ = −0.727″.

#include <optional>
#include <string>

namespace meridian::gyro {

/// One error source of T and its contribution to σ(T).
struct ErrorSource {
  enum class Kind { KnownAzimuth, Eta, Xi, InstrumentConstant };
  Kind kind = Kind::KnownAzimuth;
  /// Where the value came from, compared as text: "known_line.azimuth (grid)",
  /// "given in the file", "<the deflection model's description>", "instrument_constant".
  std::string source;
  /// The point the source belongs to (the known station for KnownAzimuth; NaN-free,
  /// radians); `to_*` the known line's far end, when its coordinates are given.
  double lat_rad = 0, lon_rad = 0;
  std::optional<double> to_lat_rad, to_lon_rad;
  double value_rad = 0;         ///< the value taken (azimuth, η, ξ or E), radians
  double contribution_rad = 0;  ///< ∂T/∂x · σ_x (radians, signed as above)
  std::string point;            ///< the point's name, for the reports (not compared)
};

/// "known line azimuth", "eta", "xi", "instrument constant"
std::string to_string(ErrorSource::Kind kind);

}  // namespace meridian::gyro
