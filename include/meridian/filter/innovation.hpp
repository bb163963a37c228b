#pragma once
/// \file innovation.hpp
/// The innovation of an update, its normalised square (NIS) and the χ² gate that rejects an
/// observation instead of absorbing it.
///
/// For an observation z = h(x) + v, v ~ N(0, R), and the prior (x̂⁻, P⁻):
///   ν = z − h(x̂⁻) (linear: z − H·x̂⁻), S = H·P⁻·Hᵀ + R,
///   NIS = νᵀ·S⁻¹·ν ~ χ²(m), m = dim z, when the model holds
/// (Bar-Shalom, Li & Kirubarajan, Estimation with applications to tracking and navigation,
/// Wiley 2001, §5.4). The gate accepts when NIS ≤ χ²_{1−α}(m); the quantile comes from
/// adjust/statistics.hpp (Boost.Math), computed once per m.

#include <array>

#include "meridian/filter/estimate.hpp"

namespace meridian::filter {

/// The innovation of one update (a vector observation, or one scalar of a sequential update).
template <int M>
struct Innovation {
  Eigen::Index epoch = 0;   ///< epoch of the update (0-based)
  Vector<M> nu;             ///< innovation ν = z − h(x̂⁻) (observation units)
  Matrix<M, M> S;           ///< its covariance S = H·P⁻·Hᵀ + R (symmetric positive definite)
  double nis = 0.0;         ///< νᵀ·S⁻¹·ν (dimensionless, ≥ 0)
  double gate_limit = 0.0;  ///< χ²_{1−α}(m) of the gate; +∞ when no gate was applied
  bool accepted = true;     ///< false: NIS > gate_limit, the state was left unchanged
  /// Degrees of freedom m = dim ν.
  Eigen::Index dof() const { return nu.size(); }
};

/// A χ² gate at significance α: accepts an innovation when NIS ≤ χ²_{1−α}(m). The limits for
/// m = 1…16 are computed at construction (Boost.Math through adjust); larger m on each call.
/// Immutable after construction.
class InnovationGate {
 public:
  /// No gate: every innovation is accepted (limit +∞).
  InnovationGate();
  /// Gate at significance α (probability of rejecting a correct observation), 0 < α < 1,
  /// e.g. 0.01. Throws InputError otherwise.
  explicit InnovationGate(double alpha);

  /// True when the gate rejects anything (constructed with α).
  bool enabled() const { return alpha_ > 0.0; }
  /// α; 0 when disabled.
  double alpha() const { return alpha_; }
  /// χ²_{1−α}(dof) for dof ≥ 1; +∞ when disabled. Throws InputError for dof < 1.
  double limit(Eigen::Index dof) const;

 private:
  static constexpr int kCached = 16;
  double alpha_ = 0.0;
  std::array<double, kCached + 1> limits_{};  // limits_[m], m = 1…kCached
};

}  // namespace meridian::filter
