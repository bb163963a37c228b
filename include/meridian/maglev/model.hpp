#pragma once
/// \file model.hpp
/// The measurement model (M1) of a magnetically suspended gyro and its
/// solutions (maglev-gyro spec §1):
///
///   I_k = K·ω_e·cos φ·sin α_k + b + e_k,   k = 1, 2,   sin α_2 = −sin α_1   (M1)
///
/// α_k the azimuth of the spin axis equilibrium at position k, east of north
/// (clockwise, radians); K the scale (A·s/rad: current per unit of the
/// horizontal earth rate component ω_e·cos φ·sin α); b the constant bias (A);
/// A = K·ω_e·cos φ the directive amplitude (A); ω_e = units::kEarthRotationRate_rad_s.
///
/// Two positions: α_1 = asin((Ī_1 − Ī_2)/(2A)), b̂ = (Ī_1 + Ī_2)/2, gyro north
/// as a circle reading N_G = r_1 − α_1 (r_1 the circle reading of the spin
/// axis at position 1). A positive α_1 (I_1 > I_2 with K > 0) means the spin
/// axis points east of north, so north reads less than r_1.
/// σ (means independent, K independent of them):
///   σ²(α_1) = (σ²(Ī_1) + σ²(Ī_2))/(2A·cos α_1)² + (tan α_1·σ(K)/K)²,
///   σ(N_G) = hypot(σ(r_1), σ(α_1)), σ(b̂) = ½·hypot(σ(Ī_1), σ(Ī_2)).
///
/// Coarse seeking: positions at circle offsets θ_j clockwise from position 1
/// (θ = π is the fine-seeking position 2): I_j = A·sin(α_1 + θ_j) + b.
/// One position with b assumed: α_1 = asin((Ī − b)/A) − θ (|α_1 + θ| ≤ 90°
/// taken: the spin axis within a quarter turn of north); three or more
/// offsets: the linear least squares (adjust::solve_linear_diagonal) for
/// s = A·sin α_1, c = A·cos α_1 and b, α_1 = atan2(s, c) over the full circle,
/// and A estimated too.
///
/// Errors: InputError for a non-positive A or K, non-finite values, negative
/// σ, too few or degenerate positions; NumericalError (field "alpha1") when
/// |(Ī_1 − Ī_2)/(2A)| > 1 — the means or the constants are inconsistent.

#include <optional>
#include <vector>

#include "meridian/core/uncertain.hpp"

namespace meridian::maglev {

/// A = K·ω_e·cos φ (A), with σ from σ(K). Throws InputError for K ≤ 0 or
/// |φ| ≥ 90°.
Uncertain directive_amplitude(Uncertain scale_A_s_per_rad, double latitude_rad);

/// The two-position solution.
struct TwoPositionSolution {
  Uncertain alpha1_rad;  ///< α_1, in (−π/2, π/2)
  Uncertain north_rad;   ///< N_G = r_1 − α_1 (circle reading of north, [0, 2π))
  Uncertain bias_A;      ///< b̂
  double ratio = 0.0;    ///< (Ī_1 − Ī_2)/(2A), |ratio| ≤ 1
};

/// α_1, N_G, b̂ from the two position means (A, σ in A), the scale K
/// (A·s/rad) and the circle reading r_1. Throws as in the file comment.
TwoPositionSolution two_position(Uncertain mean1_A, Uncertain mean2_A, Uncertain scale_A_s_per_rad,
                                 double latitude_rad, Uncertain circle_reading1_rad);

/// The same for correlated levels (e.g. the levels of a joint drift fit, drift.hpp):
/// `covariance_A2` = Cov(Ī_1, Ī_2), so σ²(Ī_1 − Ī_2) = σ_1² + σ_2² − 2c enters α_1 and
/// σ²(Ī_1 + Ī_2) = σ_1² + σ_2² + 2c enters b̂. Throws as two_position (and InputError when the
/// covariance exceeds σ_1·σ_2).
TwoPositionSolution two_position(Uncertain mean1_A, Uncertain mean2_A, double covariance_A2,
                                 Uncertain scale_A_s_per_rad, double latitude_rad,
                                 Uncertain circle_reading1_rad);

/// One coarse-seeking position: its offset θ from position 1 and its mean.
struct CoarsePosition {
  double offset_rad = 0.0;  ///< θ_j, clockwise from position 1
  Uncertain mean_A;         ///< Ī_j with σ (> 0)
};

struct CoarseSolution {
  Uncertain alpha1_rad;                  ///< α_1 of position 1
  Uncertain north_rad;                   ///< N_G = r_1 − α_1
  std::optional<Uncertain> amplitude_A;  ///< A estimated (three or more offsets)
  Uncertain bias_A;                      ///< b (the assumed one for a single position)
};

/// Coarse north seeking (see the file comment). `assumed_bias_A` is needed
/// for a single position and ignored with three or more; two positions must
/// be π apart (two_position is used). Throws as in the file comment.
CoarseSolution coarse_seek(const std::vector<CoarsePosition>& positions,
                           Uncertain scale_A_s_per_rad, double latitude_rad,
                           Uncertain circle_reading1_rad,
                           std::optional<Uncertain> assumed_bias_A = std::nullopt);

}  // namespace meridian::maglev
