#pragma once
/// \file likelihood.hpp
/// The Gaussian log-likelihood of a Gauss–Markov model l + v = A·x with a full observation
/// covariance D = Σ_ll, in its ordinary (ML) and restricted (REML) forms, and the REML Fisher
/// information of parameters of D — what variance-component estimation and the comparison of
/// stochastic models (AIC, BIC, likelihood-ratio tests) are built on.
///
/// Every quantity is computed from the Cholesky factor D = L·Lᵀ (CovarianceFactor) and a QR
/// factorisation of the whitened design L⁻¹·A; no inverse of D is formed.
///
/// Units: the likelihoods are densities of l, so they change with the unit of l: expressing l
/// in a unit s times smaller adds n·ln s (ML) or (n − u)·ln s (REML). Compare likelihoods only
/// for the same observations in the same unit.
///
/// Sources: Harville (1977) Maximum likelihood approaches to variance component estimation
/// and to related problems, JASA 72:320–338 (REML, its Fisher information); Koch (1999)
/// Parameter estimation and hypothesis testing in linear models, 2nd ed., §3.4;
/// Teunissen & Amiri-Simkooei (2008) Least-squares variance component estimation, J Geod
/// 82:65–82 (the information matrix N_kl = ½·tr(P̄·Q_k·P̄·Q_l)).

#include <vector>

#include <Eigen/Dense>

#include "meridian/adjust/least_squares.hpp"

namespace meridian::adjust {

/// The log-likelihoods of l ~ N(A·x, D) at the generalised least-squares estimate x̂.
struct GlsLikelihood {
  /// ln L = −½·[n·ln 2π + ln det D + vᵀD⁻¹v], maximised over x (at x̂).
  double ml = 0.0;
  /// ln L_R = −½·[(n − u)·ln 2π + ln det D + ln det(AᵀD⁻¹A) − ln det(AᵀA) + vᵀD⁻¹v]: the density
  /// of the n − u error contrasts (Harville 1977). The term ln det(AᵀA) makes it independent of
  /// how the parameters x are scaled or combined (A → A·T), so models with the same columns of
  /// A in other units compare equal.
  double reml = 0.0;
  double vtpv = 0.0;                ///< vᵀD⁻¹v (dimensionless)
  double log_det_covariance = 0.0;  ///< ln det D
  double log_det_normal = 0.0;      ///< ln det(AᵀD⁻¹A)
  double log_det_design = 0.0;      ///< ln det(AᵀA)
  int observations = 0;             ///< n
  int parameters = 0;               ///< u
};

/// The likelihoods of l (size n) under l + v = A·x (n×u, n > u ≥ 1, full column rank) with
/// covariance D (size n). Throws InputError on mismatched sizes or non-finite input,
/// NumericalError when A is rank deficient (as solve_linear).
GlsLikelihood gls_log_likelihood(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                 const CovarianceFactor& D);

/// REML Fisher information of parameters ψ_a of the covariance D(ψ):
/// I_ab = ½·tr(P̄·∂D/∂ψ_a·P̄·∂D/∂ψ_b) with P̄ = D⁻¹ − D⁻¹A(AᵀD⁻¹A)⁻¹AᵀD⁻¹ (Harville 1977). For
/// D = Σ θ_k·Q_k and ψ = θ it is the normal matrix of least-squares VCE, and its inverse the
/// covariance of the estimates θ̂ (Teunissen & Amiri-Simkooei 2008). `derivatives` holds the
/// n×n symmetric matrices ∂D/∂ψ_a; the result is symmetric, positive semi-definite, in the
/// units of 1/ψ_a·1/ψ_b. Throws InputError on mismatched sizes, NumericalError when A is rank
/// deficient.
Eigen::MatrixXd reml_fisher_information(const Eigen::MatrixXd& A, const CovarianceFactor& D,
                                        const std::vector<Eigen::MatrixXd>& derivatives);

}  // namespace meridian::adjust
