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
