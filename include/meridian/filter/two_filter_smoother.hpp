#pragma once
/// \file two_filter_smoother.hpp
/// Two-filter (forward/backward) smoother: the forward Kalman filter's estimates
/// (smoother_storage.hpp) combined at every epoch with a backward information filter
/// (information_filter.hpp) run over the same observations in reverse — the
/// forward/backward combination of RTKLIB's post-processing (rtkcmn.c smoother():
/// xs = Qs·(Qf⁻¹·xf + Qb⁻¹·xb), Qs = (Qf⁻¹ + Qb⁻¹)⁻¹).
///
/// Two differences from RTKLIB, both so that the result equals the RTS smoother (and the batch
/// least-squares solution) on a linear Gaussian model:
/// * at epoch k the forward filtered estimate (observations 0…k and the prior) is combined
///   with the backward information from the observations k+1…K−1 only, so z_k is counted
///   once (RTKLIB combines two filtered solutions that both contain z_k);
/// * the backward filter starts from no information (Y = 0) rather than a re-initialised
///   covariance, and the combination is evaluated in information form, so a backward
///   information matrix that is still singular (early in the backward pass) is exact:
///     Pˢ = (I + P·Y)⁻¹·P = (P⁻¹ + Y)⁻¹,  x̂ˢ = x̂ + Pˢ·(y − Y·x̂)
///   (LU with partial pivoting of I + P·Y, whose eigenvalues are ≥ 1).
/// combine_independent() is RTKLIB's formula for two independent estimates in covariance form
/// (for combining a forward and a backward solution, or a fix with a dead-reckoned position).

#include <string>

#include <Eigen/Dense>

#include "meridian/filter/detail/checks.hpp"
#include "meridian/filter/estimate.hpp"
#include "meridian/filter/information_filter.hpp"
#include "meridian/filter/smoother_storage.hpp"

namespace meridian::filter {

/// Combine a forward estimate (x̂, P) of epoch `epoch` with backward information (Y, y) about
/// the same state from independent observations. Throws NumericalError naming the epoch when
/// I + P·Y is singular or the result is not finite or has a non-positive variance.
template <int N>
Estimate<N> combine_information(const Estimate<N>& forward, const Matrix<N, N>& Y,
                                const Vector<N>& y, Eigen::Index epoch) {
  const Eigen::Index n = forward.x.size();
  Matrix<N, N> a = Matrix<N, N>::Identity(n, n);
  a.noalias() += forward.P * Y;
  const Eigen::PartialPivLU<Matrix<N, N>> lu(a);
  if (!(std::abs(lu.determinant()) > 0.0)) [[unlikely]]
    detail::throw_numerical(epoch, "I + P·Y is singular in the two-filter combination");
  Estimate<N> s;
  s.P = lu.solve(forward.P);
  s.P = (0.5 * (s.P + s.P.transpose())).eval();
  Vector<N> r = y;
  r.noalias() -= Y * forward.x;
  s.x = forward.x;
  s.x.noalias() += s.P * r;
  detail::check_covariance_diagonal(s.P, "combined covariance", epoch);
  if (!s.x.allFinite()) [[unlikely]]
    detail::throw_numerical(epoch, "combined state is not finite");
  return s;
}

/// RTKLIB's minimum-variance combination of two independent estimates of the same state:
/// x̂ = Q·(Qa⁻¹·x̂a + Qb⁻¹·x̂b), Q = (Qa⁻¹ + Qb⁻¹)⁻¹, evaluated without inverses as
/// x̂ = x̂a + Qa·(Qa + Qb)⁻¹·(x̂b − x̂a), Q = Qa − Qa·(Qa + Qb)⁻¹·Qa (Cholesky of Qa + Qb).
/// Throws InputError naming the epoch for non-finite or mis-shaped inputs, NumericalError when
/// Qa + Qb is not positive definite or the result has a non-positive variance.
template <int N>
Estimate<N> combine_independent(const Estimate<N>& a, const Estimate<N>& b, Eigen::Index epoch) {
  const Eigen::Index n = a.x.size();
  detail::check_shape(b.P.rows(), b.x.rows(), n, n, "second estimate", epoch);
  detail::check_finite(a.x, "first estimate x", epoch);
  detail::check_finite(a.P, "first estimate P", epoch);
  detail::check_finite(b.x, "second estimate x", epoch);
  detail::check_finite(b.P, "second estimate P", epoch);
  const Matrix<N, N> sum = a.P + b.P;
  const Eigen::LLT<Matrix<N, N>> llt(sum);
  if (llt.info() != Eigen::Success) [[unlikely]]
    detail::throw_not_positive_definite("sum of the two covariances", epoch, sum);
  const Matrix<N, N> g = llt.solve(a.P);  // (Qa + Qb)⁻¹·Qa; its transpose is the gain
  Estimate<N> s;
  s.x = a.x;
  s.x.noalias() += g.transpose() * (b.x - a.x);
  s.P = a.P;
  s.P.noalias() -= a.P * g;
  s.P = (0.5 * (s.P + s.P.transpose())).eval();
  detail::check_covariance_diagonal(s.P, "combined covariance", epoch);
  return s;
}

/// The two-filter smoother over the line in `forward` (size() epochs, filtered by a
/// KalmanFilter and appended epoch by epoch). For k = K−1 down to 0 it
///   1. combines the forward estimate of epoch k with the backward information from the
///      observations after k and calls sink(k, const Estimate<N>& smoothed);
///   2. calls replay(k, BackwardInformationFilter<N>& backward), which must add epoch k's
///      observations (backward.update(z, H, R) — the same ones the forward filter used, leaving
///      out those its gate rejected) and then, for k > 0, move to epoch k−1 with the forward
///      step from k−1 to k (backward.predict(Φ_k, Q_k)).
/// Throws InputError naming the epoch when replay does not leave the backward filter at k−1;
/// the errors of combine_information(), the backward filter and the storage.
template <int N, typename Replay, typename Sink>
void two_filter_smooth(SmootherStorage<N>& forward, Replay&& replay, Sink&& sink) {
  const Eigen::Index K = forward.size();
  if (K == 0) return;
  BackwardInformationFilter<N> backward(K - 1, forward.state_size());
  auto reader = forward.read_reverse();
  EpochRecord<N> record;
  while (reader.next(record)) {
    const Eigen::Index k = reader.index();
    const Estimate<N> s = combine_information<N>(record.filtered, backward.information(),
                                                 backward.information_vector(), k);
    sink(k, s);
    replay(k, backward);
    if (k > 0 && backward.epoch() != k - 1)
      detail::throw_input(k,
                          "the replay of the two-filter smoother must predict the backward "
                          "filter to the previous epoch");
  }
}

}  // namespace meridian::filter
