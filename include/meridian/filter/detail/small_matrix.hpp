#pragma once
/// \file small_matrix.hpp
/// Internal: the dense kernels of the hot loops for small fixed sizes. Eigen sends a product
/// whose dimensions sum to 20 or more (8×8 times 8×8) to its blocked GEMM, which packs the
/// operands on every call; at these sizes a coefficient-based (lazy) product is several times
/// faster. Likewise its triangular solves with a matrix right-hand side take the general
/// blocked path. Dynamic sizes keep Eigen's defaults (large states gain from blocking).

#include <cmath>

#include <Eigen/Dense>

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
  for (int j = 0; j < C; ++j) {
    Eigen::Matrix<double, R, 1> s = A.col(0) * B(0, j);
    for (int k = 1; k < K; ++k) s += A.col(k) * B(k, j);
    out.col(j) = s;
  }
}

/// C = A·Bᵀ for fixed sizes (C must not alias A or B).
template <int R, int K, int C>
inline void mul_abt(const Eigen::Matrix<double, R, K>& A, const Eigen::Matrix<double, C, K>& B,
                    Eigen::Matrix<double, R, C>& out) {
  static_assert(R != Eigen::Dynamic && K != Eigen::Dynamic && C != Eigen::Dynamic);
  for (int j = 0; j < C; ++j) {
    Eigen::Matrix<double, R, 1> s = A.col(0) * B(j, 0);
    for (int k = 1; k < K; ++k) s += A.col(k) * B(j, k);
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
    for (int k = 0; k < K; ++k) s += A.col(k).template head<rows>() * B(J, k);
    out.col(J).template head<rows>() = s;
    add_abt_upper_columns<N, K, J + 1>(A, B, out);
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
    for (int j = 0; j < N; ++j) {
      double d = A(j, j);
      for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
      if (!(d > 0.0 && std::isfinite(d))) return false;
      d = std::sqrt(d);
      L(j, j) = d;
      inv_diag(j) = 1.0 / d;
      for (int i = j + 1; i < N; ++i) {
        double s = A(i, j);
        for (int k = 0; k < j; ++k) s -= L(i, k) * L(j, k);
        L(i, j) = s * inv_diag(j);
      }
    }
    for (int j = 0; j < N; ++j) {  // Y·Lᵀ = B: column j of B is Σ_{k≤j} L(j,k)·Y.col(k)
      for (int k = 0; k < j; ++k) B.col(j) -= L(j, k) * B.col(k);
      B.col(j) *= inv_diag(j);
    }
    for (int j = N - 1; j >= 0; --j) {  // X·L = Y: column j of Y is Σ_{k≥j} L(k,j)·X.col(k)
      for (int k = j + 1; k < N; ++k) B.col(j) -= L(k, j) * B.col(k);
      B.col(j) *= inv_diag(j);
    }
    return true;
  }
}

}  // namespace meridian::filter::detail
