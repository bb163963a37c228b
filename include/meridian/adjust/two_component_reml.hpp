#pragma once
/// \file two_component_reml.hpp
/// The maximum of the restricted likelihood of l + v = A·x with the two-component
/// stochastic model
///
///     D(l) = θ_1·Q_1 + θ_2·Q_2,   θ_1, θ_2 ≥ 0,
///
/// found without iterating variance-component estimation: both cofactor matrices are brought
/// to diagonal form on the residual space at once, after which the likelihood is a sum of
/// scalar terms and its maximum over θ is a one-dimensional search.
///
/// With K (n×r, r = n − u) an orthonormal basis of the residual space (Kᵀ·A = 0, from the QR
/// factorisation of A), S_k = Kᵀ·Q_k·K, the Cholesky factor S_1 = L·Lᵀ, the eigenvalues λ_j
/// and eigenvectors u_j of L⁻¹·S_2·L⁻ᵀ and z = Uᵀ·L⁻¹·Kᵀ·l:
///
///     ln L_R(θ) = −½·[r·ln 2π + 2·Σ ln L_ii + Σ_j ln(θ_1 + θ_2·λ_j) + Σ_j z_j²/(θ_1 + θ_2·λ_j)],
///
/// which is the restricted (REML) log-likelihood of adjust::gls_log_likelihood (Harville 1977;
/// the identity det(KᵀDK) = det D·det(AᵀD⁻¹A)/det(AᵀA) for orthonormal K, Harville 1974).
/// The scale s = θ_1 + θ_2 is profiled out in closed form; the ratio τ = θ_2/θ_1 is found on
/// a logarithmic grid wide enough to reach both boundaries and refined by golden section and
/// Newton's method in ln τ (the boundaries θ_2 = 0 and, when Q_2 is positive definite on the
/// residual space, θ_1 = 0 are examined exactly).
///
/// The result is the maximum over the whole quadrant θ ≥ 0 (the grid finds the global one
/// when the profile has several), where iterated VCE (estimate_variance_components) converges
/// to the local maximum nearest its start; at that maximum both give the same θ̂ and the
/// same likelihood to rounding. Cost: O(n²·u + r³) once, then O(r) per trial ratio — what a
/// search over further parameters of Q_1, Q_2 (the ρ of a Markov process) needs.
///
/// Sources: Harville (1974) Bayesian inference for variance components using only error
/// contrasts, Biometrika 61:383–385; Harville (1977) JASA 72:320–338; the simultaneous
/// diagonalisation as in Kang et al. (2008) Efficient control of population structure in model
/// organism association mapping (EMMA), Genetics 178:1709–1723.

#include <array>

#include <Eigen/Dense>

#include "meridian/adjust/variance_components.hpp"

namespace meridian::adjust {

struct TwoComponentReml {
  Eigen::Vector2d components;  ///< θ̂_1, θ̂_2 (units of l squared), ≥ 0
  /// θ̂_k is exactly 0: the maximum lies on that boundary of the quadrant.
  std::array<bool, 2> at_zero{false, false};
  double reml = 0.0;  ///< ln L_R at θ̂ (as GlsLikelihood::reml; density of the r contrasts)
  int residual_dimension = 0;  ///< r = n − u
};

/// The θ ≥ 0 maximising the restricted likelihood of l (size n) under l + v = A·x (n×u,
/// n > u + 1, full column rank) with D = θ_1·F_1·F_1ᵀ + θ_2·F_2·F_2ᵀ (the components' factors,
/// n rows each; their names are used in messages). Q_1 must be positive definite on the
/// residual space (Kᵀ·Q_1·K, see the file comment); Q_2 may be of low rank.
/// Throws InputError on mismatched sizes or non-finite input; NumericalError when A is rank
/// deficient, when Q_1 is singular on the residual space, or when l lies in the column space
/// of A (no residual: the likelihood has no maximum).
TwoComponentReml maximise_two_component_reml(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                             const VarianceComponent& first,
                                             const VarianceComponent& second);

}  // namespace meridian::adjust
