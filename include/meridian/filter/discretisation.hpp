#pragma once
/// \file discretisation.hpp
/// Discretisation of a continuous linear model ẋ = F·x + G·w, E[w(t)w(τ)ᵀ] = Q_c·δ(t − τ),
/// over a step Δt into x_k = Φ·x_{k−1} + w_k, E[w_k w_kᵀ] = Q_d.
///
/// * Van Loan (exact for F, G, Q_c constant over the step): with the 2N×2N matrix
///   A = [[−F, G·Q_c·Gᵀ], [0, Fᵀ]]·Δt and B = exp(A) = [[·, B12], [0, B22]],
///   Φ = B22ᵀ = exp(F·Δt) and Q_d = Φ·B12 = ∫₀^Δt exp(Fs)·G·Q_c·Gᵀ·exp(Fᵀs) ds
///   (C. F. Van Loan, Computing integrals involving the matrix exponential, IEEE Trans.
///   Automatic Control 23(3), 1978, 395–404). exp by Eigen's Padé scaling-and-squaring
///   (unsupported/Eigen/MatrixFunctions). Q_d is linear in Q_c, so Q_c is scaled to unit size
///   before the exponential and the result scaled back: the blocks of A then have comparable
///   size even when Q_c is 1e-13 (deflection of the vertical in rad²/s).
/// * FirstOrder: Φ ≈ I + F·Δt, Q_d ≈ G·Q_c·Gᵀ·Δt. Errors O(Δt²) in Φ and O(Δt²) in Q_d
///   (relative O(Δt)); an option for comparisons, not the default.
/// * FirstOrderDiscreteNoise: Φ ≈ I + F·Δt, Q_d = Γ·Q·Γᵀ with Γ = G·Δt, i.e. Q_d = Δt²·G·Q·Gᵀ,
///   where `q_c` then holds Q, the covariance of a noise sample held constant over the step
///   (not a spectral density). This is the form of the published INS/GNSS deflection method
///   (shared/spec/deflection.md §3: "Φ ≈ I + F·Δt and Q_d = Δt²·Q"); it equals FirstOrder
///   when Q = Q_c/Δt. Use it only to reproduce that method.
///
/// Units: F in 1/s (entries relate state derivatives to states), Δt in s, Q_c in (units of w)²·s
/// (power spectral density), Φ dimensionless per entry pair, Q_d in state units squared.
///
/// Not for the hot loop: each call allocates (dynamic 2N×2N exponential). A model whose
/// coefficients change slowly (latitude, speed) is re-discretised when they change.

#include <Eigen/Dense>

#include "meridian/filter/estimate.hpp"

namespace meridian::filter {

/// How a continuous model becomes a discrete one.
enum class Discretisation {
  VanLoan,                  ///< exact Φ = exp(FΔt), Q_d by Van Loan's method (default)
  FirstOrder,               ///< Φ ≈ I + FΔt, Q_d ≈ G·Q_c·Gᵀ·Δt
  FirstOrderDiscreteNoise,  ///< Φ ≈ I + FΔt, Q_d = Δt²·G·Q·Gᵀ (the published method's form)
};

/// Continuous linear model with N states and W noise inputs.
template <int N, int W>
struct ContinuousModel {
  Matrix<N, N> F;    ///< dynamics matrix, ẋ = F·x + G·w (1/s)
  Matrix<N, W> G;    ///< noise input matrix
  Matrix<W, W> q_c;  ///< spectral density of w (symmetric, ≥ 0); see Discretisation for its
                     ///< meaning under FirstOrderDiscreteNoise
};

/// Discrete model x_k = Φ·x_{k−1} + w_k, w_k ~ N(0, Q_d).
template <int N>
struct DiscreteModel {
  Matrix<N, N> phi;  ///< state transition Φ from t_{k−1} to t_k
  Matrix<N, N> q;    ///< covariance Q_d of the process noise over the step (symmetric)
};

/// The dynamic-size implementation behind discretise() (src/filter/discretisation.cpp).
/// Throws InputError when F is not square, G or q_c do not match it, q_c is not symmetric
/// (within 1e-12 of its largest entry) or has a negative diagonal, an entry is not finite, or
/// dt_s is not finite and > 0; NumericalError when the exponential is not finite (F·Δt too
/// large).
DiscreteModel<Eigen::Dynamic> discretise_dynamic(const Eigen::MatrixXd& F, const Eigen::MatrixXd& G,
                                                 const Eigen::MatrixXd& q_c, double dt_s,
                                                 Discretisation method);

/// Discretise `model` over dt_s seconds (> 0) with `method`. Q_d is symmetric. Throws as
/// discretise_dynamic.
template <int N, int W>
DiscreteModel<N> discretise(const ContinuousModel<N, W>& model, double dt_s,
                            Discretisation method = Discretisation::VanLoan) {
  DiscreteModel<Eigen::Dynamic> d = discretise_dynamic(model.F, model.G, model.q_c, dt_s, method);
  return DiscreteModel<N>{d.phi, d.q};
}

}  // namespace meridian::filter
