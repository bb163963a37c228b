#pragma once
/// \file rts_smoother.hpp
/// Rauch–Tung–Striebel fixed-interval smoother over a whole line, streaming: it reads the
/// forward records (smoother_storage.hpp) last epoch first and hands each smoothed estimate to
/// the caller, so memory stays flat however long the line.
///
/// Equations (Rauch, Tung & Striebel, AIAA J. 3(8), 1965; Bar-Shalom et al. 2001 §8.6), for
/// k = K−2 … 0, starting from x̂ˢ_{K−1} = x̂_{K−1}, Pˢ_{K−1} = P_{K−1}:
///   C_k = P_k·Φ_{k+1}ᵀ·(P⁻_{k+1})⁻¹   (by a Cholesky solve with P⁻_{k+1}; no inverse),
///   x̂ˢ_k = x̂_k + C_k·(x̂ˢ_{k+1} − x̂⁻_{k+1}),
///   Pˢ_k = P_k + C_k·(Pˢ_{k+1} − P⁻_{k+1})·C_kᵀ, then Pˢ ← ½(Pˢ + Pˢᵀ) (fixed N: only the
///   upper triangle of the symmetric product is computed and mirrored, small_matrix.hpp).
/// For an extended filter the stored Φ is the Jacobian and x̂⁻ = f(x̂): the extended RTS smoother.
///
/// Errors: NumericalError naming the epoch when P⁻_{k+1} is not positive definite ("epoch
/// k+1") or Pˢ_k loses its positive finite diagonal ("epoch k"); IoError from the storage.

#include <cstdint>
#include <type_traits>
#include <vector>

#include <Eigen/Dense>

#include "meridian/filter/detail/checks.hpp"
#include "meridian/filter/detail/small_matrix.hpp"
#include "meridian/filter/estimate.hpp"
#include "meridian/filter/smoother_storage.hpp"

namespace meridian::filter {

/// Smooth the line in `storage`, calling sink(k, const Estimate<N>& smoothed) for
/// k = size()−1 down to 0 (reverse time order). The storage can be read again afterwards.
template <int N, typename Sink>
void rts_smooth(SmootherStorage<N>& storage, Sink&& sink) {
  auto reader = storage.read_reverse();
  // est[ns] is the smoothed estimate of epoch k+1; the filtered estimate of epoch k is read
  // into est[1 − ns] and turned into the smoothed one in place (no copies).
  Estimate<N> est[2];
  Estimate<N> pred[2];  // predicted estimates of epochs k+1 and k, alternating
  int nx = 0;           // pred[nx] is epoch k+1
  int ns = 0;
  if (!reader.next(pred[nx], est[ns])) return;
  Matrix<N, N> phi = reader.transition();  // Φ_{k+1}, copied only when it changes
  std::uint64_t phi_index = reader.transition_index();
  // Fixed N: the exact nonzeros of Φ, skipped in P_k·Φᵀ (small_matrix.hpp).
  typename detail::TransitionPatternFor<N>::type pattern{};
  if constexpr (N != Eigen::Dynamic) pattern.assign(phi);
  sink(reader.index(), static_cast<const Estimate<N>&>(est[ns]));
  Matrix<N, N> c;
  Matrix<N, N> d;
  Matrix<N, N> t;
  Vector<N> dx;
  while (reader.next(pred[1 - nx], est[1 - ns])) {
    const Eigen::Index k = reader.index();
    const Estimate<N>& next_pred = pred[nx];
    const Estimate<N>& next_smoothed = est[ns];
    Estimate<N>& s = est[1 - ns];  // filtered estimate of epoch k, then smoothed
    const Matrix<N, N>& filtered_p = s.P;
    if (const Matrix<N, N>* pphit = reader.filtered_times_next_transition())
      c = *pphit;  // compact records: the reader formed P_k·Φ_{k+1}ᵀ for P⁻_{k+1}
    else if constexpr (N != Eigen::Dynamic)
      detail::mul_abt_sparse(filtered_p, phi, pattern, c);  // P_k·Φ_{k+1}ᵀ
    else
      c.noalias() = filtered_p * phi.transpose();
    if (!detail::cholesky_right_solve_in_place(next_pred.P, c)) [[unlikely]]  // C_k
      detail::throw_not_positive_definite("predicted covariance P⁻", k + 1, next_pred.P);
    dx = next_smoothed.x - next_pred.x;
    s.x.noalias() += detail::product(c, dx);  // x̂_k + C_k·(x̂ˢ_{k+1} − x̂⁻_{k+1})
    t = next_smoothed.P - next_pred.P;
    if constexpr (N != Eigen::Dynamic) {
      // C·T·Cᵀ is symmetric: D = C·T, then the upper triangle of P_k + D·Cᵀ, mirrored.
      detail::mul_ab(c, t, d);
      detail::add_abt_symmetric(d, c, s.P);
    } else {
      d.noalias() = t * c.transpose();  // (Pˢ_{k+1} − P⁻_{k+1})·C_kᵀ
      s.P.noalias() += c * d;
      s.P = (0.5 * (s.P + s.P.transpose())).eval();
    }
    detail::check_covariance_diagonal(s.P, "smoothed covariance", k);
    if (!detail::all_finite(s.x)) [[unlikely]]
      detail::throw_numerical(k, "smoothed state is not finite");
    sink(k, static_cast<const Estimate<N>&>(s));
    nx = 1 - nx;
    ns = 1 - ns;
    if (reader.transition_index() != phi_index) {
      phi = reader.transition();
      phi_index = reader.transition_index();
      if constexpr (N != Eigen::Dynamic) pattern.assign(phi);
    }
  }
}

/// The smoothed estimates of the whole line in time order (index = epoch), for short lines.
template <int N>
std::vector<Estimate<N>> rts_smooth(SmootherStorage<N>& storage) {
  std::vector<Estimate<N>> out(static_cast<std::size_t>(storage.size()));
  rts_smooth(storage,
             [&](Eigen::Index k, const Estimate<N>& e) { out[static_cast<std::size_t>(k)] = e; });
  return out;
}

}  // namespace meridian::filter
