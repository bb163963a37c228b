#pragma once
/// \file estimate.hpp
/// A Gaussian state estimate (x̂, P) and the matrix types of the filter module.
///
/// Sizes are template arguments: N = 8 gives Eigen fixed-size matrices (no heap allocation,
/// unrolled and vectorised products), N = Eigen::Dynamic gives run-time sizes. Every type and
/// function of meridian::filter is a template on the state size N (and the observation size M),
/// and both kinds are tested.
///
/// Conventions of the whole module (docs/filter.md):
/// * x is a column vector of N states in the units the model chooses (radians, metres,
///   rad/s, …); P = E[(x − x̂)(x − x̂)ᵀ] in the products of those units. P is kept exactly
///   symmetric (every step that changes it ends with P ← ½(P + Pᵀ), or for fixed sizes computes
///   only the upper triangle of the symmetric result and mirrors it).
/// * States are addressed by name, never by number: a model declares its indices once, e.g.
///   `struct DovState { static constexpr int phi_e = 0, …, size = 8; };` (docs/filter.md).
/// * Epochs are counted from 0 (the epoch of the initial estimate) and every numerical error
///   names its epoch in ErrorContext::field as "epoch 1234".

#include <cmath>

#include <Eigen/Dense>

namespace meridian::filter {

/// Column vector of R rows (R = Eigen::Dynamic for a run-time size).
template <int R>
using Vector = Eigen::Matrix<double, R, 1>;

/// R×C matrix, column-major (Eigen's default). For a 1×1 or R×1 shape Eigen needs the
/// column-major storage order, which is what this alias gives.
template <int R, int C>
using Matrix = Eigen::Matrix<double, R, C>;

/// A Gaussian estimate of an N-state: mean x̂ and covariance P (N×N, symmetric positive
/// definite). A plain value: the filter, the smoothers and the storage copy it.
template <int N>
struct Estimate {
  Vector<N> x;     ///< state estimate x̂ (model units)
  Matrix<N, N> P;  ///< covariance of x̂ (model units squared), symmetric positive definite

  /// Number of states (N, or the run-time size for N = Eigen::Dynamic).
  Eigen::Index size() const { return x.size(); }
  /// Standard deviation of state i: sqrt(P(i, i)) (model units).
  double sigma(Eigen::Index i) const { return std::sqrt(P(i, i)); }
};

}  // namespace meridian::filter
