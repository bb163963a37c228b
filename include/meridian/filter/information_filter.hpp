#pragma once
/// \file information_filter.hpp
/// Backward information filter: the information about x_k carried by the observations after
/// epoch k, run from the last epoch towards the first, starting from no information at all
/// (Y = 0: no prior at the end of the line). The backward half of the two-filter smoother
/// (two_filter_smoother.hpp).
///
/// State: information matrix Y (N×N, symmetric, ≥ 0; may be singular) and information vector
/// y = Y·x̂ᵇ. Equations (Fraser & Potter, IEEE Trans. AC 14(4), 1969; Mayne, Automatica 4, 1966;
/// in the form of Simon, Optimal state estimation, Wiley 2006, §9.4.2, without Φ⁻¹ or Q⁻¹ so Φ
/// and Q may be singular):
///   update with z_k = H·x_k + v, v ~ N(0, R), R positive definite:
///     Y ← Y + Hᵀ·R⁻¹·H,  y ← y + Hᵀ·R⁻¹·z   (R by Cholesky, whitened);
///   predict from epoch k to k−1 through x_k = Φ_k·x_{k−1} + w, w ~ N(0, Q_k):
///     A = I + Y·Q_k (eigenvalues ≥ 1: well conditioned),
///     Y ← Φ_kᵀ·A⁻¹·Y·Φ_k,  y ← Φ_kᵀ·A⁻¹·y,   (A by LU with partial pivoting), Y ← ½(Y + Yᵀ).
/// (A⁻¹·Y = (Y⁻¹ + Q)⁻¹ where Y is invertible.)
///
/// Errors (naming the epoch): InputError for non-finite or mis-shaped inputs or an R that is
/// not positive definite; NumericalError when A is singular or a result is not finite.

#include <string>

#include <Eigen/Dense>

#include "meridian/filter/detail/checks.hpp"
#include "meridian/filter/estimate.hpp"

namespace meridian::filter {

/// Information from the future of an N-state line, run backwards (N fixed or Eigen::Dynamic).
template <int N>
class BackwardInformationFilter {
 public:
  /// No information about x at epoch `last_epoch` (the last epoch of the line), n states.
  BackwardInformationFilter(Eigen::Index last_epoch, Eigen::Index n = N)
      : Y_(Matrix<N, N>::Zero(n, n)), y_(Vector<N>::Zero(n)), epoch_(last_epoch) {
    if (n < 1) detail::throw_input(last_epoch, "the state is empty");
  }

  /// Add the observation z (m) = H·x + v of the current epoch, v ~ N(0, R), R (m×m)
  /// symmetric positive definite.
  template <typename Z, typename HD, typename RD>
  void update(const Eigen::MatrixBase<Z>& z, const Eigen::MatrixBase<HD>& h,
              const Eigen::MatrixBase<RD>& r) {
    constexpr int M = HD::RowsAtCompileTime;
    add_observation<M>(z.derived(), h.derived(), r.derived());
  }

  /// Move from the current epoch k to k−1 through x_k = Φ·x_{k−1} + w, w ~ N(0, Q): Φ and Q
  /// are those of the forward step from k−1 to k.
  void predict(const Matrix<N, N>& phi, const Matrix<N, N>& q) {
    detail::check_shape(phi.rows(), phi.cols(), size(), size(), "transition Φ", epoch_);
    detail::check_shape(q.rows(), q.cols(), size(), size(), "process noise Q_d", epoch_);
    detail::check_finite(phi, "transition Φ", epoch_);
    detail::check_finite(q, "process noise Q_d", epoch_);
    Matrix<N, N> a = Matrix<N, N>::Identity(size(), size());
    a.noalias() += Y_ * q;
    const Eigen::PartialPivLU<Matrix<N, N>> lu(a);
    if (!(std::abs(lu.determinant()) > 0.0)) [[unlikely]]
      detail::throw_numerical(epoch_, "I + Y·Q is singular in the backward prediction");
    const Matrix<N, N> ay = lu.solve(Y_);  // A⁻¹·Y
    const Vector<N> av = lu.solve(y_);     // A⁻¹·y
    const Matrix<N, N> t = ay * phi;
    Matrix<N, N> y_next;
    y_next.noalias() = phi.transpose() * t;
    y_next = (0.5 * (y_next + y_next.transpose())).eval();
    Vector<N> v_next;
    v_next.noalias() = phi.transpose() * av;
    if (!y_next.allFinite() || !v_next.allFinite()) [[unlikely]]
      detail::throw_numerical(epoch_ - 1, "backward information is not finite");
    Y_ = y_next;
    y_ = v_next;
    --epoch_;
  }

  /// Information matrix Y about x at epoch() (inverse units of the states squared).
  const Matrix<N, N>& information() const { return Y_; }
  /// Information vector y = Y·x̂ᵇ.
  const Vector<N>& information_vector() const { return y_; }
  /// The epoch the information refers to.
  Eigen::Index epoch() const { return epoch_; }
  Eigen::Index size() const { return y_.size(); }

 private:
  template <int M>
  void add_observation(const Vector<M>& z, const Matrix<M, N>& H, const Matrix<M, M>& R) {
    detail::check_shape(H.rows(), H.cols(), z.rows(), size(), "observation matrix H", epoch_);
    detail::check_shape(R.rows(), R.cols(), z.rows(), z.rows(), "observation covariance R", epoch_);
    detail::check_finite(z, "observation z", epoch_);
    detail::check_finite(H, "observation matrix H", epoch_);
    detail::check_finite(R, "observation covariance R", epoch_);
    const Eigen::LLT<Matrix<M, M>> llt(R);
    if (llt.info() != Eigen::Success) [[unlikely]]
      detail::throw_input(epoch_,
                          "observation covariance R is not positive definite (the "
                          "information filter needs R⁻¹)");
    const Matrix<M, N> hw = llt.matrixL().solve(H);  // L⁻¹·H
    const Vector<M> zw = llt.matrixL().solve(z);     // L⁻¹·z
    Y_.noalias() += hw.transpose() * hw;
    y_.noalias() += hw.transpose() * zw;
  }

  Matrix<N, N> Y_;
  Vector<N> y_;
  Eigen::Index epoch_;
};

}  // namespace meridian::filter
