#pragma once
/// \file kalman_filter.hpp
/// Linear and extended Kalman filter: predict with Φ and Q_d, update in Joseph form with a
/// symmetric P, a whole observation vector at once or one scalar at a time, each update
/// reporting its innovation, NIS and χ² gate decision (innovation.hpp).
///
/// Equations as implemented (docs/filter.md; Bar-Shalom, Li & Kirubarajan 2001 ch. 5;
/// Grewal & Andrews, Kalman filtering, 4th ed., 2015, ch. 4 for the Joseph form):
///   predict   x̂⁻ = Φ·x̂  (extended: x̂⁻ = f(x̂) given by the caller, Φ = ∂f/∂x),
///             P⁻ = Φ·P·Φᵀ + Q_d;
///   update    ν = z − H·x̂⁻ (extended: z − h(x̂⁻) given by the caller), S = H·P⁻·Hᵀ + R,
///             NIS = νᵀS⁻¹ν, gate: reject when NIS > χ²_{1−α}(m) (state unchanged),
///             K = P⁻·Hᵀ·S⁻¹ (S by Cholesky, never inverted), x̂ = x̂⁻ + K·ν,
///             P = (I − K·H)·P⁻·(I − K·H)ᵀ + K·R·Kᵀ (Joseph), then P ← ½(P + Pᵀ).
/// The Joseph products use the rank-m structure of K·H: (I − KH)·P⁻ = P⁻ − K·(P⁻Hᵀ)ᵀ and
/// B·(I − KH)ᵀ = B − (B·Hᵀ)·Kᵀ, O(N²m) instead of O(N³), the same products as the textbook
/// form. For fixed sizes the last two terms are one product, B + (K·R − B·Hᵀ)·Kᵀ, of which only
/// the upper triangle is computed and mirrored (the result is symmetric); likewise Φ·P·Φᵀ.
///
/// Epochs: the filter starts at epoch 0 with the initial estimate; each predict moves to the
/// next epoch; updates belong to the current epoch. Every error names the epoch
/// (ErrorContext::field "epoch 1234"). Functions give the strong guarantee: after an exception
/// the filter is as it was before the call.
///
/// Errors: InputError for a non-finite or mis-shaped input, an asymmetric Q_d or R (beyond
/// 1e-9 of its largest entry), a negative variance; NumericalError when S is not positive
/// definite, NIS is not finite, or P loses its positive finite diagonal.

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Dense>

#include "meridian/filter/detail/checks.hpp"
#include "meridian/filter/detail/small_matrix.hpp"
#include "meridian/filter/discretisation.hpp"
#include "meridian/filter/estimate.hpp"
#include "meridian/filter/innovation.hpp"

namespace meridian::filter {

/// Innovations of a sequential update: one scalar observation at a time (R diagonal).
template <int M>
struct SequentialInnovations {
  Eigen::Index epoch = 0;  ///< epoch of the update
  Vector<M> nu;            ///< ν_i = z_i − h_iᵀ·x̂ (x̂ after the scalars before i)
  Vector<M> s;             ///< S_i = h_iᵀ·P·h_i + r_i
  Vector<M> nis;           ///< ν_i²/S_i
  Eigen::Matrix<bool, M, 1> accepted;  ///< false: scalar i failed the gate and was skipped
  double gate_limit = 0.0;             ///< χ²_{1−α}(1); +∞ without a gate
  /// Number of scalars rejected by the gate.
  Eigen::Index rejected() const { return accepted.size() - accepted.count(); }
};

/// A kernel for the predicted covariance Φ·P·Φᵀ + Q_d specialised to a transition structure
/// known at compile time (fixed N): fits(Φ) is true when every nonzero of Φ lies in the
/// structure, predict computes out = Φ·P·Φᵀ + q (P exactly symmetric, q = ½(Q_d + Q_dᵀ); and
/// P·Φᵀ into p_phit unless it is null) — bit for bit what the generic kernel gives, up to the
/// sign of a zero, in about half the instructions. structured_transition_kernel<N, rows>()
/// makes one from the structure's rows (detail::StructuredTransition).
template <int N>
struct TransitionKernel {
  bool (*fits)(const Matrix<N, N>& phi);
  void (*predict)(const Matrix<N, N>& phi, const Matrix<N, N>& P, const Matrix<N, N>& q,
                  Matrix<N, N>& out, Matrix<N, N>* p_phit);
};

/// The kernel of a structure whose row j may be nonzero in the columns of the set bits of
/// rows[j]. Define it as a constant (`static constexpr`) and pass its address to
/// KalmanFilter::set_transition_kernel.
template <int N, std::array<std::uint32_t, N> rows>
constexpr TransitionKernel<N> structured_transition_kernel() {
  return {&detail::StructuredTransition<N, rows>::fits,
          &detail::StructuredTransition<N, rows>::predict};
}

/// Kalman filter of an N-state (N fixed, or Eigen::Dynamic). A value type: copy it to branch.
template <int N>
class KalmanFilter {
 public:
  /// Start at epoch 0 from `initial` (finite, symmetric within 1e-9 relative, positive
  /// definite: else InputError naming epoch 0). `gate` applies to every update.
  explicit KalmanFilter(Estimate<N> initial, InnovationGate gate = InnovationGate());

  /// Move to the next epoch with x̂⁻ = Φ·x̂, P⁻ = Φ·P·Φᵀ + Q_d.
  void predict(const Matrix<N, N>& phi, const Matrix<N, N>& q);
  /// predict(model.phi, model.q).
  void predict(const DiscreteModel<N>& model) { predict(model.phi, model.q); }
  /// Extended: move to the next epoch with x̂⁻ = x_predicted = f(x̂) computed by the caller,
  /// Φ = ∂f/∂x at x̂, P⁻ = Φ·P·Φᵀ + Q_d.
  void predict_extended(const Vector<N>& x_predicted, const Matrix<N, N>& phi,
                        const Matrix<N, N>& q);

  /// Linear update with z = H·x + v, v ~ N(0, R): z (m), H (m×N), R (m×m symmetric). The
  /// observation size m is H's compile-time row count (Eigen::Dynamic for a MatrixXd); any
  /// Eigen expression is accepted. A gate rejection leaves the state unchanged and is
  /// reported in the result.
  template <typename Z, typename H, typename R>
  Innovation<H::RowsAtCompileTime> update(const Eigen::MatrixBase<Z>& z,
                                          const Eigen::MatrixBase<H>& h,
                                          const Eigen::MatrixBase<R>& r) {
    constexpr int M = H::RowsAtCompileTime;
    return update_linear<M>(z.derived(), h.derived(), r.derived());
  }
  /// Extended update with the innovation ν = z − h(x̂⁻) computed by the caller and the
  /// Jacobian H = ∂h/∂x at x̂⁻.
  template <typename V, typename H, typename R>
  Innovation<H::RowsAtCompileTime> update_extended(const Eigen::MatrixBase<V>& nu,
                                                   const Eigen::MatrixBase<H>& h,
                                                   const Eigen::MatrixBase<R>& r) {
    constexpr int M = H::RowsAtCompileTime;
    return update_nonlinear<M>(nu.derived(), h.derived(), r.derived());
  }
  /// Linear update one scalar at a time with independent observation errors of variances
  /// r (m, each ≥ 0): row i of H and z_i use the estimate after scalars 0…i−1. Each scalar is
  /// gated alone (1 degree of freedom). Equals update() with R = diag(r) when nothing is
  /// rejected.
  template <typename Z, typename H, typename R>
  SequentialInnovations<H::RowsAtCompileTime> update_sequential(const Eigen::MatrixBase<Z>& z,
                                                                const Eigen::MatrixBase<H>& h,
                                                                const Eigen::MatrixBase<R>& r) {
    constexpr int M = H::RowsAtCompileTime;
    return update_scalars<M>(z.derived(), h.derived(), r.derived());
  }

  /// The current estimate (after the updates applied so far at this epoch).
  const Estimate<N>& estimate() const { return estimate_; }
  /// The predicted estimate of this epoch (before its updates); the initial one at epoch 0.
  const Estimate<N>& predicted() const { return predicted_; }
  /// Φ that led to this epoch (identity at epoch 0).
  const Matrix<N, N>& transition() const { return phi_; }
  /// Q_d of the predict that led to this epoch as the filter used it (zero at epoch 0): for
  /// fixed N ½(Q_d + Q_dᵀ), for dynamic sizes Q_d as given. With transition() and the filtered
  /// covariance P of the epoch before, predicted_covariance() reproduces predicted().P bit for
  /// bit (SmootherStorage's compact records rely on it).
  const Matrix<N, N>& process_noise() const {
    if constexpr (N != Eigen::Dynamic)
      return q_sym_;
    else
      return q_last_;
  }

  /// The exact nonzeros of a Φ, as the fixed-size kernels skip them (small_matrix.hpp); an
  /// empty stand-in for dynamic sizes.
  using TransitionPattern = typename detail::TransitionPatternFor<N>::type;
  static TransitionPattern pattern_of(const Matrix<N, N>& phi);
  /// out = Φ·P·Φᵀ + Q exactly as predict() computes P⁻ (the same operations in the same order):
  /// P the filtered covariance of the epoch before (exactly symmetric), q as process_noise()
  /// returns it, `pattern` = pattern_of(phi). No checks; out must not alias an operand.
  /// Fixed N: `p_phit`, when given, receives the intermediate P·Φᵀ (the RTS gain's numerator).
  static void predicted_covariance(const Matrix<N, N>& phi, const TransitionPattern& pattern,
                                   const Matrix<N, N>& P, const Matrix<N, N>& q,
                                   Matrix<N, N>& out, Matrix<N, N>* p_phit = nullptr);
  /// Use `kernel` (fixed N, ignored for dynamic sizes; must outlive the filter and its copies)
  /// for P⁻ whenever Φ fits its structure, the generic sparse kernel otherwise; nullptr: always
  /// the generic one. The results are the same either way (TransitionKernel);
  /// SmootherStorage::append(filter) takes the kernel over for the P⁻ it recomputes.
  void set_transition_kernel(const TransitionKernel<N>* kernel) {
    if constexpr (N != Eigen::Dynamic) {  // dynamic sizes: ignored
      kernel_ = kernel;
      phi_fits_kernel_ = kernel_ != nullptr && kernel_->fits(phi_);
    } else {
      (void)kernel;
    }
  }
  /// The kernel set by set_transition_kernel (nullptr: none).
  const TransitionKernel<N>* transition_kernel() const { return kernel_; }
  /// Current epoch, 0-based.
  Eigen::Index epoch() const { return epoch_; }
  /// Number of states.
  Eigen::Index size() const { return estimate_.x.size(); }
  const InnovationGate& gate() const { return gate_; }

 private:
  // True when phi is phi_ bit for bit (fixed N; always false for dynamic sizes): the Φ of the
  // last epoch, already checked.
  bool same_transition(const Matrix<N, N>& phi) const {
    if constexpr (N != Eigen::Dynamic)
      return detail::same_bits(phi, phi_);
    else
      return false;
  }
  void check_transition(const Matrix<N, N>& phi, Eigen::Index next, bool known) const {
    detail::check_shape(phi.rows(), phi.cols(), size(), size(), "transition Φ", next);
    if (!known) detail::check_finite(phi, "transition Φ", next);
  }
  void commit_prediction(const Vector<N>& x, const Matrix<N, N>& phi, const Matrix<N, N>& q,
                         bool known_phi);
  template <int M>
  Innovation<M> update_linear(const Vector<M>& z, const Matrix<M, N>& H, const Matrix<M, M>& R);
  template <int M>
  Innovation<M> update_nonlinear(const Vector<M>& nu, const Matrix<M, N>& H, const Matrix<M, M>& R);
  template <int M>
  SequentialInnovations<M> update_scalars(const Vector<M>& z, const Matrix<M, N>& H,
                                          const Vector<M>& r);
  template <int M>
  Innovation<M> apply_update(const Vector<M>& nu, const Matrix<M, N>& H, const Matrix<M, M>& R);

  static constexpr int kCache = N == Eigen::Dynamic ? 0 : N;  // size of the fixed-N caches
  using PhiPattern = TransitionPattern;

  Estimate<N> estimate_;
  Estimate<N> predicted_;
  Matrix<N, N> phi_;
  InnovationGate gate_;
  Eigen::Index epoch_ = 0;
  // Fixed N: the last Q_d that passed the input checks (when have_checked_q_) and ½(Q_d + Q_dᵀ)
  // of it.
  bool have_checked_q_ = false;
  Matrix<kCache, kCache> checked_q_ = decltype(checked_q_)::Zero();
  Matrix<kCache, kCache> q_sym_ = decltype(q_sym_)::Zero();
  // Fixed N: the exact nonzeros of phi_ (small_matrix.hpp), recomputed only when Φ changes.
  PhiPattern phi_pattern_{};
  // Fixed N: the structured kernel, if any, and whether phi_ fits it.
  const TransitionKernel<N>* kernel_ = nullptr;
  bool phi_fits_kernel_ = false;
  // Dynamic sizes: Q_d of the last predict (process_noise()).
  std::conditional_t<N == Eigen::Dynamic, Matrix<N, N>, detail::NoPattern> q_last_{};
};

namespace detail {

/// InputError naming the epoch unless m is symmetric within 1e-9 of its largest |entry| and
/// its diagonal is ≥ 0 (a covariance given by the caller: Q_d, R, P_0).
template <typename Derived>
inline void check_input_covariance(const Eigen::MatrixBase<Derived>& m, const char* name,
                                   Eigen::Index epoch) {
  check_finite(m, name, epoch);
  const double scale = m.cwiseAbs().maxCoeff();
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) [[unlikely]]
    throw_input(epoch, std::string(name) + " is not symmetric");
  if ((m.diagonal().array() < 0.0).any()) [[unlikely]]
    throw_input(epoch, std::string(name) + " has a negative variance on its diagonal");
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Implementation.

template <int N>
KalmanFilter<N>::KalmanFilter(Estimate<N> initial, InnovationGate gate)
    : estimate_(std::move(initial)), gate_(gate) {
  const Eigen::Index n = estimate_.x.size();
  if (n < 1) detail::throw_input(0, "the initial state is empty");
  detail::check_shape(estimate_.P.rows(), estimate_.P.cols(), n, n, "initial covariance P0", 0);
  detail::check_finite(estimate_.x, "initial state x0", 0);
  detail::check_input_covariance(estimate_.P, "initial covariance P0", 0);
  if (Eigen::LLT<Matrix<N, N>>(estimate_.P).info() != Eigen::Success)
    detail::throw_input(0, "initial covariance P0 is not positive definite");
  estimate_.P = (0.5 * (estimate_.P + estimate_.P.transpose())).eval();
  predicted_ = estimate_;
  phi_ = Matrix<N, N>::Identity(n, n);
  if constexpr (N != Eigen::Dynamic)
    phi_pattern_.assign(phi_);
  else
    q_last_ = Matrix<N, N>::Zero(n, n);
}

template <int N>
typename KalmanFilter<N>::TransitionPattern KalmanFilter<N>::pattern_of(const Matrix<N, N>& phi) {
  TransitionPattern pattern{};
  if constexpr (N != Eigen::Dynamic) pattern.assign(phi);
  return pattern;
}

template <int N>
void KalmanFilter<N>::predicted_covariance(const Matrix<N, N>& phi,
                                           const TransitionPattern& pattern,
                                           const Matrix<N, N>& P, const Matrix<N, N>& q,
                                           Matrix<N, N>& out, Matrix<N, N>* p_phit) {
  if constexpr (N != Eigen::Dynamic) {
    if (p_phit != nullptr)
      detail::predict_covariance(phi, P, q, pattern, out, *p_phit);
    else
      detail::predict_covariance(phi, P, q, pattern, out);
  } else {
    (void)pattern;
    (void)p_phit;
    Matrix<N, N> phi_p;
    phi_p.noalias() = phi * P;
    out = q;
    out.noalias() += phi_p * phi.transpose();
    out = (0.5 * (out + out.transpose())).eval();
  }
}

template <int N>
void KalmanFilter<N>::predict(const Matrix<N, N>& phi, const Matrix<N, N>& q) {
  const Eigen::Index next = epoch_ + 1;
  const bool known = same_transition(phi);  // a constant model's Φ is checked once
  check_transition(phi, next, known);
  Vector<N> x;
  x.noalias() = detail::product(phi, estimate_.x);
  commit_prediction(x, phi, q, known);
}

template <int N>
void KalmanFilter<N>::predict_extended(const Vector<N>& x_predicted, const Matrix<N, N>& phi,
                                       const Matrix<N, N>& q) {
  const Eigen::Index next = epoch_ + 1;
  detail::check_shape(x_predicted.rows(), 1, size(), 1, "predicted state f(x)", next);
  detail::check_shape(phi.rows(), phi.cols(), size(), size(), "transition Φ", next);
  detail::check_finite(x_predicted, "predicted state f(x)", next);
  const bool known = same_transition(phi);
  check_transition(phi, next, known);
  commit_prediction(x_predicted, phi, q, known);
}

template <int N>
void KalmanFilter<N>::commit_prediction(const Vector<N>& x, const Matrix<N, N>& phi,
                                        const Matrix<N, N>& q, bool known_phi) {
  const Eigen::Index next = epoch_ + 1;
  detail::check_shape(q.rows(), q.cols(), size(), size(), "process noise Q_d", next);
  if constexpr (N != Eigen::Dynamic) {
    // A constant model passes the same Q_d every epoch: check it once (the cache holds only a
    // Q_d that passed; compared bit for bit).
    if (!have_checked_q_ || !detail::same_bits(q, checked_q_)) {
      detail::check_input_covariance(q, "process noise Q_d", next);
      checked_q_ = q;
      q_sym_ = 0.5 * (q + q.transpose());
      have_checked_q_ = true;
    }
  } else {
    detail::check_input_covariance(q, "process noise Q_d", next);
  }
  Matrix<N, N>& p = predicted_.P;  // written only after the checks above
  if constexpr (N != Eigen::Dynamic) {
    // Φ·P, then only the upper triangle of Q + (Φ·P)·Φᵀ, mirrored (small_matrix.hpp), both
    // skipping the exact zeros of Φ. Φ·P = (P·Φᵀ)ᵀ for the exactly symmetric P, term for term.
    const bool new_phi = !known_phi;
    PhiPattern pattern;
    if (new_phi) pattern.assign(phi);
    const PhiPattern& pat = new_phi ? pattern : phi_pattern_;
    const bool fits = new_phi ? kernel_ != nullptr && kernel_->fits(phi) : phi_fits_kernel_;
    Matrix<N, N> p_new;
    if (fits)
      kernel_->predict(phi, estimate_.P, q_sym_, p_new, nullptr);
    else
      predicted_covariance(phi, pat, estimate_.P, q_sym_, p_new);
    detail::check_covariance_diagonal(p_new, "predicted covariance P⁻", next);
    p = p_new;
    if (new_phi) {
      phi_ = phi;
      phi_pattern_ = pattern;
      phi_fits_kernel_ = fits;
    }
  } else {
    Matrix<N, N> p_new;
    predicted_covariance(phi, detail::NoPattern{}, estimate_.P, q, p_new);
    detail::check_covariance_diagonal(p_new, "predicted covariance P⁻", next);
    p = std::move(p_new);
  }
  predicted_.x = x;
  estimate_.x = x;
  estimate_.P = p;
  if constexpr (N == Eigen::Dynamic) {
    phi_ = phi;
    q_last_ = q;
  }
  epoch_ = next;
}

template <int N>
template <int M>
Innovation<M> KalmanFilter<N>::update_linear(const Vector<M>& z, const Matrix<M, N>& H,
                                             const Matrix<M, M>& R) {
  detail::check_shape(H.rows(), H.cols(), z.rows(), size(), "observation matrix H", epoch_);
  detail::check_finite(z, "observation z", epoch_);
  detail::check_finite(H, "observation matrix H", epoch_);
  Vector<M> nu = z;
  nu.noalias() -= detail::product(H, estimate_.x);
  return apply_update<M>(nu, H, R);
}

template <int N>
template <int M>
Innovation<M> KalmanFilter<N>::update_nonlinear(const Vector<M>& nu, const Matrix<M, N>& H,
                                                const Matrix<M, M>& R) {
  detail::check_shape(H.rows(), H.cols(), nu.rows(), size(), "observation matrix H", epoch_);
  detail::check_finite(nu, "innovation ν", epoch_);
  detail::check_finite(H, "observation matrix H", epoch_);
  return apply_update<M>(nu, H, R);
}

template <int N>
template <int M>
Innovation<M> KalmanFilter<N>::apply_update(const Vector<M>& nu, const Matrix<M, N>& H,
                                            const Matrix<M, M>& R) {
  const Eigen::Index m = nu.rows();
  if (m < 1) detail::throw_input(epoch_, "the observation is empty");
  detail::check_shape(R.rows(), R.cols(), m, m, "observation covariance R", epoch_);
  detail::check_input_covariance(R, "observation covariance R", epoch_);

  Innovation<M> in;
  in.epoch = epoch_;
  in.nu = nu;
  const Matrix<N, N>& P = estimate_.P;
  constexpr bool fixed = N != Eigen::Dynamic && M != Eigen::Dynamic;
  using HPattern =
      std::conditional_t<fixed, detail::RowPattern<fixed ? M : 1, fixed ? N : 1>, detail::NoPattern>;
  HPattern h_pattern{};  // fixed sizes: the exact nonzeros of H, skipped in P⁻·Hᵀ and B·Hᵀ
  Matrix<N, M> U;        // P⁻·Hᵀ
  if constexpr (fixed) {
    h_pattern.assign(H);
    detail::mul_abt_sparse(P, H, h_pattern, U);
  } else
    U.noalias() = P * H.transpose();
  in.S = R;
  in.S.noalias() += H * U;
  in.S = (0.5 * (in.S + in.S.transpose())).eval();
  Vector<M> s_nu = nu;  // S⁻¹·ν
  if (!detail::cholesky_solve_in_place(in.S, s_nu)) [[unlikely]]
    detail::throw_not_positive_definite("innovation covariance S = H·P⁻·Hᵀ + R", epoch_, in.S);
  in.nis = nu.dot(s_nu);
  if (!std::isfinite(in.nis)) [[unlikely]]
    detail::throw_numerical(epoch_,
                            "normalised innovation squared is not finite (S is "
                            "numerically singular)");
  in.gate_limit = gate_.limit(m);
  if (!(in.nis <= in.gate_limit)) {
    in.accepted = false;
    return in;
  }

  Matrix<N, M> K = U;  // K = (P⁻Hᵀ)·S⁻¹ (S was factored above: positive definite)
  detail::cholesky_right_solve_in_place(in.S, K);
  Vector<N> x = estimate_.x;
  x.noalias() += detail::product(K, nu);
  Matrix<N, N> b = P;  // (I − KH)·P⁻
  if constexpr (fixed) {
    for (int j = 0; j < N; ++j) {
      Vector<N> c = b.col(j);
      for (int k = 0; k < M; ++k) c -= K.col(k) * U(j, k);
      b.col(j) = c;
    }
    Matrix<N, M> g;  // K·R − (I − KH)·P⁻·Hᵀ
    detail::mul_ab(K, R, g);
    Matrix<N, M> bht;
    detail::mul_abt_sparse(b, H, h_pattern, bht);
    g -= bht;
    // (I − KH)·P⁻·(I − KH)ᵀ + K·R·Kᵀ = b + g·Kᵀ, symmetric: upper triangle, mirrored.
    detail::add_abt_symmetric(g, K, b);
  } else {
    b.noalias() -= K * U.transpose();
    Matrix<N, M> bht;
    bht.noalias() = b * H.transpose();
    b.noalias() -= bht * K.transpose();  // (I − KH)·P⁻·(I − KH)ᵀ
    Matrix<N, M> kr;
    kr.noalias() = K * R;
    b.noalias() += kr * K.transpose();  // + K·R·Kᵀ
    b = (0.5 * (b + b.transpose())).eval();
  }
  detail::check_covariance_diagonal(b, "covariance P after the update", epoch_);
  if (!detail::all_finite(x)) [[unlikely]]
    detail::throw_numerical(epoch_, "state x̂ after the update is not finite");
  estimate_.x = x;
  estimate_.P = b;
  return in;
}

template <int N>
template <int M>
SequentialInnovations<M> KalmanFilter<N>::update_scalars(const Vector<M>& z, const Matrix<M, N>& H,
                                                         const Vector<M>& r) {
  detail::check_shape(H.rows(), H.cols(), z.rows(), size(), "observation matrix H", epoch_);
  detail::check_shape(r.rows(), 1, z.rows(), 1, "observation variances r", epoch_);
  detail::check_finite(z, "observation z", epoch_);
  detail::check_finite(H, "observation matrix H", epoch_);
  detail::check_finite(r, "observation variances r", epoch_);
  const Eigen::Index m = z.rows();
  SequentialInnovations<M> out;
  out.epoch = epoch_;
  out.nu.resize(m);
  out.s.resize(m);
  out.nis.resize(m);
  out.accepted.resize(m);
  out.gate_limit = gate_.limit(1);
  const KalmanFilter before = *this;  // strong guarantee across the scalars
  try {
    for (Eigen::Index i = 0; i < m; ++i) {
      const Matrix<1, N> h = H.row(i);
      Vector<1> nu;
      nu(0) = z(i) - (h * estimate_.x)(0);
      const Matrix<1, 1> ri = Matrix<1, 1>::Constant(r(i));
      const Innovation<1> in = apply_update<1>(nu, h, ri);
      out.nu(i) = in.nu(0);
      out.s(i) = in.S(0, 0);
      out.nis(i) = in.nis;
      out.accepted(i) = in.accepted;
    }
  } catch (...) {
    *this = before;
    throw;
  }
  return out;
}

// The dynamic-size filter is compiled once in src/filter/kalman_filter.cpp.
extern template class KalmanFilter<Eigen::Dynamic>;

}  // namespace meridian::filter
