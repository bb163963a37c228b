#pragma once
/// \file small_matrix.hpp
/// Internal: the dense kernels of the hot loops for small fixed sizes. Eigen sends a product
/// whose dimensions sum to 20 or more (8×8 times 8×8) to its blocked GEMM, which packs the
/// operands on every call; at these sizes a coefficient-based (lazy) product is several times
/// faster. Likewise its triangular solves with a matrix right-hand side take the general
/// blocked path. Dynamic sizes keep Eigen's defaults (large states gain from blocking).

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include <Eigen/Dense>

// Full unrolling of the fixed-size loops below (GCC and Clang; both accept the GCC spelling).
// GCC's own heuristics leave the triangular loops of the Cholesky kernels rolled, with their
// index arithmetic and branches in the hot path.
#if defined(__GNUC__)
#define MERIDIAN_UNROLL _Pragma("GCC unroll 16")
#else
#define MERIDIAN_UNROLL
#endif

namespace meridian::filter::detail {

/// True when every dimension of a and b is known at compile time.
template <typename A, typename B>
inline constexpr bool kFixedProduct = (A::RowsAtCompileTime != Eigen::Dynamic) &&
                                      (A::ColsAtCompileTime != Eigen::Dynamic) &&
                                      (B::ColsAtCompileTime != Eigen::Dynamic);

/// a·b: coefficient-based for fixed sizes, Eigen's default product otherwise. Assign it with
/// .noalias() (the result must not alias an operand).
template <typename A, typename B>
auto product(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  if constexpr (kFixedProduct<A, B>)
    return a.derived().lazyProduct(b.derived());
  else
    return a.derived() * b.derived();
}

/// C = A·B for fixed sizes (C must not alias A or B): column j of C is Σ_k A.col(k)·B(k, j),
/// whole columns of A as packets. About 20 % faster than Eigen's lazy product at 8×8.
template <int R, int K, int C>
inline void mul_ab(const Eigen::Matrix<double, R, K>& A, const Eigen::Matrix<double, K, C>& B,
                   Eigen::Matrix<double, R, C>& out) {
  static_assert(R != Eigen::Dynamic && K != Eigen::Dynamic && C != Eigen::Dynamic);
  MERIDIAN_UNROLL
  for (int j = 0; j < C; ++j) {
    Eigen::Matrix<double, R, 1> s = A.col(0) * B(0, j);
    MERIDIAN_UNROLL
    for (int k = 1; k < K; ++k) s += A.col(k) * B(k, j);
    out.col(j) = s;
  }
}

/// C = A·Bᵀ for fixed sizes (C must not alias A or B).
template <int R, int K, int C>
inline void mul_abt(const Eigen::Matrix<double, R, K>& A, const Eigen::Matrix<double, C, K>& B,
                    Eigen::Matrix<double, R, C>& out) {
  static_assert(R != Eigen::Dynamic && K != Eigen::Dynamic && C != Eigen::Dynamic);
  MERIDIAN_UNROLL
  for (int j = 0; j < C; ++j) {
    Eigen::Matrix<double, R, 1> s = A.col(0) * B(j, 0);
    MERIDIAN_UNROLL
    for (int k = 1; k < K; ++k) s += A.col(k) * B(j, k);
    out.col(j) = s;
  }
}

/// True when a and b (of the same size) hold the same bits: the cheap test, one memcmp, that a
/// model's Φ or Q_d is the one already checked at the last epoch (an element-wise == is a chain
/// of scalar compares and branches).
template <typename A>
inline bool same_bits(const Eigen::PlainObjectBase<A>& a, const Eigen::PlainObjectBase<A>& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(typename A::Scalar) * static_cast<std::size_t>(a.size())) == 0;
}

/// The exact nonzeros of each row of a fixed-size R×C matrix B: row j has count[j] nonzero
/// entries, in the columns cols[j][0 … count[j] − 1] (ascending). Taken from B's values (an
/// entry is skipped only when it is exactly ±0; a NaN is kept), so a product with B that skips
/// the other entries gives the dense product's result: each skipped term is an exact ±0 that
/// would only have been added (the filter checks every covariance for finiteness, so no
/// 0·∞ is lost). The deflection model's Φ (an attitude block and two 2×2 Gauss–Markov blocks,
/// whatever the order of the states) has 21 nonzeros of 64; its H 4 of 16.
template <int R, int C>
struct RowPattern {
  static_assert(R != Eigen::Dynamic && C != Eigen::Dynamic && C <= 255);
  std::uint8_t count[R];
  std::uint8_t cols[R][C];

  RowPattern() = default;
  explicit RowPattern(const Eigen::Matrix<double, R, C>& b) { assign(b); }
  void assign(const Eigen::Matrix<double, R, C>& b) {
    for (int j = 0; j < R; ++j) {
      int n = 0;
      for (int k = 0; k < C; ++k)
        if (b(j, k) != 0.0) cols[j][n++] = static_cast<std::uint8_t>(k);
      count[j] = static_cast<std::uint8_t>(n);
    }
  }
};

/// C = A·Bᵀ for fixed sizes skipping the exact zeros of B (pattern of B's rows); C must not
/// alias A or B. Column j of C is Σ over the nonzeros B(j, k) of A.col(k)·B(j, k), in the
/// order of mul_abt, so for a finite A the result equals mul_abt's (up to the sign of a zero).
template <int R, int K, int C>
inline void mul_abt_sparse(const Eigen::Matrix<double, R, K>& A,
                           const Eigen::Matrix<double, C, K>& B, const RowPattern<C, K>& pattern,
                           Eigen::Matrix<double, R, C>& out) {
  for (int j = 0; j < C; ++j) {
    const int n = pattern.count[j];
    if (n == 0) {
      out.col(j).setZero();
      continue;
    }
    const std::uint8_t* cols = pattern.cols[j];
    Eigen::Matrix<double, R, 1> s = A.col(cols[0]) * B(j, cols[0]);
    for (int i = 1; i < n; ++i) s += A.col(cols[i]) * B(j, cols[i]);
    out.col(j) = s;
  }
}

namespace sym {
// Column J of the upper triangle of out += A·Bᵀ: rows 0…J rounded up to an even count (whole
// SSE2 packets; the extra entry below the diagonal is overwritten by the mirror).
template <int N, int K, int J>
inline void add_abt_upper_columns(const Eigen::Matrix<double, N, K>& A,
                                  const Eigen::Matrix<double, N, K>& B,
                                  Eigen::Matrix<double, N, N>& out) {
  if constexpr (J < N) {
    constexpr int rows = (J + 2) / 2 * 2 < N ? (J + 2) / 2 * 2 : N;
    Eigen::Matrix<double, rows, 1> s = out.col(J).template head<rows>();
    MERIDIAN_UNROLL
    for (int k = 0; k < K; ++k) s += A.col(k).template head<rows>() * B(J, k);
    out.col(J).template head<rows>() = s;
    add_abt_upper_columns<N, K, J + 1>(A, B, out);
  }
}
// As add_abt_upper_columns, skipping the exact zeros of B's rows.
template <int N, int K, int J>
inline void add_abt_upper_columns_sparse(const Eigen::Matrix<double, N, K>& A,
                                         const Eigen::Matrix<double, N, K>& B,
                                         const RowPattern<N, K>& pattern,
                                         Eigen::Matrix<double, N, N>& out) {
  if constexpr (J < N) {
    constexpr int rows = (J + 2) / 2 * 2 < N ? (J + 2) / 2 * 2 : N;
    Eigen::Matrix<double, rows, 1> s = out.col(J).template head<rows>();
    const std::uint8_t* cols = pattern.cols[J];
    for (int i = 0; i < pattern.count[J]; ++i)
      s += A.col(cols[i]).template head<rows>() * B(J, cols[i]);
    out.col(J).template head<rows>() = s;
    add_abt_upper_columns_sparse<N, K, J + 1>(A, B, pattern, out);
  }
}
}  // namespace sym

/// out ← out + A·Bᵀ for a sum known to be symmetric (Φ·P·Φᵀ + Q, C·T·Cᵀ + P): only the upper
/// triangle is computed (about 60 % of the products at 8×8), then mirrored into the lower one,
/// so the result is exactly symmetric. Fixed sizes only; out must not alias A or B.
template <int N, int K>
inline void add_abt_symmetric(const Eigen::Matrix<double, N, K>& A,
                              const Eigen::Matrix<double, N, K>& B,
                              Eigen::Matrix<double, N, N>& out) {
  static_assert(N != Eigen::Dynamic && K != Eigen::Dynamic);
  sym::add_abt_upper_columns<N, K, 0>(A, B, out);
  for (int j = 0; j < N; ++j)
    for (int i = j + 1; i < N; ++i) out(i, j) = out(j, i);
}

/// add_abt_symmetric skipping the exact zeros of B (pattern of B's rows): the same result.
template <int N, int K>
inline void add_abt_symmetric_sparse(const Eigen::Matrix<double, N, K>& A,
                                     const Eigen::Matrix<double, N, K>& B,
                                     const RowPattern<N, K>& pattern,
                                     Eigen::Matrix<double, N, N>& out) {
  static_assert(N != Eigen::Dynamic && K != Eigen::Dynamic);
  sym::add_abt_upper_columns_sparse<N, K, 0>(A, B, pattern, out);
  for (int j = 0; j < N; ++j)
    for (int i = j + 1; i < N; ++i) out(i, j) = out(j, i);
}

/// Stand-in for a RowPattern where sizes are dynamic (no pattern is kept).
struct NoPattern {};

/// The pattern type of an N×N transition: RowPattern<N, N>, NoPattern for Eigen::Dynamic.
/// A specialisation, not std::conditional_t<N == Eigen::Dynamic, …>: Eigen::Dynamic is a
/// namespace-scope const (internal linkage), and GCC gives a member whose declared parameter
/// type names it internal linkage, so the explicit instantiation of KalmanFilter<Dynamic>
/// did not export KalmanFilter::predicted_covariance.
template <int N>
struct TransitionPatternFor {
  using type = RowPattern<N, N>;
};
template <>
struct TransitionPatternFor<Eigen::Dynamic> {
  using type = NoPattern;
};

/// out = Q + Φ·P·Φᵀ for fixed sizes, the predicted covariance of KalmanFilter::predict and of
/// the smoothers that recompute it: q_sym = ½(Q + Qᵀ), P exactly symmetric, `pattern` the
/// exact nonzeros of Φ. Φ·P is formed as (P·Φᵀ)ᵀ (the same terms in the same order, P being
/// symmetric) so that both products skip the zeros of Φ; only the upper triangle of
/// Q + (Φ·P)·Φᵀ is computed, then mirrored. out must not alias an operand.
/// p_phit receives P·Φᵀ (the RTS smoother's gain numerator, smoother_storage.hpp).
template <int N>
inline void predict_covariance(const Eigen::Matrix<double, N, N>& phi,
                               const Eigen::Matrix<double, N, N>& P,
                               const Eigen::Matrix<double, N, N>& q_sym,
                               const RowPattern<N, N>& pattern, Eigen::Matrix<double, N, N>& out,
                               Eigen::Matrix<double, N, N>& p_phit) {
  mul_abt_sparse(P, phi, pattern, p_phit);
  const Eigen::Matrix<double, N, N> phi_p = p_phit.transpose();
  out = q_sym;
  add_abt_symmetric_sparse(phi_p, phi, pattern, out);
}
template <int N>
inline void predict_covariance(const Eigen::Matrix<double, N, N>& phi,
                               const Eigen::Matrix<double, N, N>& P,
                               const Eigen::Matrix<double, N, N>& q_sym,
                               const RowPattern<N, N>& pattern, Eigen::Matrix<double, N, N>& out) {
  Eigen::Matrix<double, N, N> p_phit;
  predict_covariance(phi, P, q_sym, pattern, out, p_phit);
}

/// predict_covariance for a transition whose nonzeros lie in a structure known at compile time:
/// Rows[j] has bit k set where Φ(j, k) may be nonzero. The same terms in the same order as
/// predict_covariance with the RowPattern of Φ, fully unrolled instead of looping over each
/// row's nonzeros (about half the instructions for the deflection model): a term the structure
/// keeps where Φ holds an exact zero adds an exact ±0 (P is finite: the filter checks it), so
/// the result is the same bit for bit up to the sign of a zero. Q enters each upper column
/// directly instead of being copied into out first (the mirror writes the lower triangle).
template <int N, std::array<std::uint32_t, N> Rows>
struct StructuredTransition {
  static_assert(N != Eigen::Dynamic && N <= 32);
  using M = Eigen::Matrix<double, N, N>;

  /// True when every nonzero of phi (a NaN included) lies in the structure.
  static bool fits(const M& phi) {
    for (int k = 0; k < N; ++k)
      for (int j = 0; j < N; ++j)
        if (phi(j, k) != 0.0 && ((Rows[j] >> k) & 1u) == 0) return false;
    return true;
  }

  /// out = Q + Φ·P·Φᵀ as predict_covariance; p_phit (if not null) receives P·Φᵀ.
  static void predict(const M& phi, const M& P, const M& q_sym, M& out, M* p_phit) {
    M local;
    M& ppt = p_phit != nullptr ? *p_phit : local;
    each<N>([&]<int J>() { pphit_column<J>(P, phi, ppt); });
    const M phi_p = ppt.transpose();  // Φ·P, P being exactly symmetric
    each<N>([&]<int J>() { upper_column<J>(phi_p, phi, q_sym, out); });
    for (int j = 0; j < N; ++j)
      for (int i = j + 1; i < N; ++i) out(i, j) = out(j, i);
  }

 private:
  // f.template operator()<I>() for I = 0 … C − 1, unrolled.
  template <int C, typename F>
  static void each(F&& f) {
    [&]<int... I>(std::integer_sequence<int, I...>) {
      (f.template operator()<I>(), ...);
    }(std::make_integer_sequence<int, C>{});
  }
  // Column J of P·Φᵀ: Σ over the structure's k of row J, ascending, of P.col(k)·Φ(J, k).
  template <int J>
  static void pphit_column(const M& P, const M& phi, M& out) {
    constexpr std::uint32_t row = Rows[J];
    if constexpr (row == 0) {
      out.col(J).setZero();
    } else {
      constexpr int first = std::countr_zero(row);
      Eigen::Matrix<double, N, 1> s = P.col(first) * phi(J, first);
      each<N>([&]<int K>() {
        if constexpr (K > first && ((row >> K) & 1u) != 0) s += P.col(K) * phi(J, K);
      });
      out.col(J) = s;
    }
  }
  // Rows 0 … J (rounded up to an even count, as add_abt_upper_columns) of column J of
  // Q + (Φ·P)·Φᵀ.
  template <int J>
  static void upper_column(const M& phi_p, const M& phi, const M& q_sym, M& out) {
    constexpr std::uint32_t row = Rows[J];
    constexpr int rows = (J + 2) / 2 * 2 < N ? (J + 2) / 2 * 2 : N;
    Eigen::Matrix<double, rows, 1> s = q_sym.col(J).template head<rows>();
    each<N>([&]<int K>() {
      if constexpr (((row >> K) & 1u) != 0) s += phi_p.col(K).template head<rows>() * phi(J, K);
    });
    out.col(J).template head<rows>() = s;
  }
};

/// Solve A·X = B in place (B ← A⁻¹·B) for a symmetric positive definite A (only its lower
/// triangle is read) by Cholesky A = L·Lᵀ (Golub & Van Loan, Matrix computations, 4th ed.,
/// alg. 4.2.1). Returns false, B untouched, when A is not positive definite (a pivot that is
/// not > 0 or not finite). Fixed sizes: plain loops the compiler unrolls; dynamic: Eigen::LLT.
template <int N, int K>
bool cholesky_solve_in_place(const Eigen::Matrix<double, N, N>& A, Eigen::Matrix<double, N, K>& B) {
  if constexpr (N == Eigen::Dynamic || K == Eigen::Dynamic) {
    const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(A);
    if (llt.info() != Eigen::Success) return false;
    llt.solveInPlace(B);
    return true;
  } else {
    Eigen::Matrix<double, N, N> L;
    for (int j = 0; j < N; ++j) {
      double d = A(j, j);
      for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
      if (!(d > 0.0 && std::isfinite(d))) return false;
      d = std::sqrt(d);
      L(j, j) = d;
      const double inv = 1.0 / d;
      for (int i = j + 1; i < N; ++i) {
        double s = A(i, j);
        for (int k = 0; k < j; ++k) s -= L(i, k) * L(j, k);
        L(i, j) = s * inv;
      }
    }
    for (int c = 0; c < K; ++c) {
      // L·y = b, then Lᵀ·x = y, column by column.
      for (int i = 0; i < N; ++i) {
        double s = B(i, c);
        for (int k = 0; k < i; ++k) s -= L(i, k) * B(k, c);
        B(i, c) = s / L(i, i);
      }
      for (int i = N - 1; i >= 0; --i) {
        double s = B(i, c);
        for (int k = i + 1; k < N; ++k) s -= L(k, i) * B(k, c);
        B(i, c) = s / L(i, i);
      }
    }
    return true;
  }
}

/// Solve X·A = B in place (B ← B·A⁻¹) for a symmetric positive definite A, by Cholesky
/// A = L·Lᵀ: first Y·Lᵀ = B, then X·L = Y, column by column, so every step is an operation on
/// a whole contiguous column of B (vectorised for fixed sizes). Returns false, B untouched,
/// when A is not positive definite. Used for gains: K = (P⁻Hᵀ)·S⁻¹, C = (P·Φᵀ)·(P⁻)⁻¹.
template <int R, int N>
bool cholesky_right_solve_in_place(const Eigen::Matrix<double, N, N>& A,
                                   Eigen::Matrix<double, R, N>& B) {
  if constexpr (N == Eigen::Dynamic || R == Eigen::Dynamic) {
    const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(A);
    if (llt.info() != Eigen::Success) return false;
    // B·A⁻¹ = (A⁻¹·Bᵀ)ᵀ, A symmetric.
    Eigen::Matrix<double, N, R> bt = B.transpose();
    llt.solveInPlace(bt);
    B = bt.transpose();
    return true;
  } else {
    Eigen::Matrix<double, N, N> L;
    Eigen::Matrix<double, N, 1> inv_diag;
    MERIDIAN_UNROLL
    for (int j = 0; j < N; ++j) {
      double d = A(j, j);
      MERIDIAN_UNROLL
      for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
      if (!(d > 0.0 && std::isfinite(d))) return false;
      d = std::sqrt(d);
      L(j, j) = d;
      inv_diag(j) = 1.0 / d;
      MERIDIAN_UNROLL
      for (int i = j + 1; i < N; ++i) {
        double s = A(i, j);
        MERIDIAN_UNROLL
        for (int k = 0; k < j; ++k) s -= L(i, k) * L(j, k);
        L(i, j) = s * inv_diag(j);
      }
    }
    // Each column is accumulated in a local (registers), not re-stored after every term.
    MERIDIAN_UNROLL
    for (int j = 0; j < N; ++j) {  // Y·Lᵀ = B: column j of B is Σ_{k≤j} L(j,k)·Y.col(k)
      Eigen::Matrix<double, R, 1> c = B.col(j);
      MERIDIAN_UNROLL
      for (int k = 0; k < j; ++k) c -= L(j, k) * B.col(k);
      B.col(j) = c * inv_diag(j);
    }
    MERIDIAN_UNROLL
    for (int j = N - 1; j >= 0; --j) {  // X·L = Y: column j of Y is Σ_{k≥j} L(k,j)·X.col(k)
      Eigen::Matrix<double, R, 1> c = B.col(j);
      MERIDIAN_UNROLL
      for (int k = j + 1; k < N; ++k) c -= L(k, j) * B.col(k);
      B.col(j) = c * inv_diag(j);
    }
    return true;
  }
}

}  // namespace meridian::filter::detail
