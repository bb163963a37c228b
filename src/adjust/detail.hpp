#pragma once
// Private to the adjust module (not installed): the input checks and the scale-free,
// rank-revealing QR shared by the linear solver (least_squares.cpp) and the
// Gauss–Newton steps of the non-linear solver (nonlinear.cpp).

#include <limits>

#include <Eigen/Dense>

namespace meridian::adjust::detail {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kLog2Pi = 1.8378770664093454836;  ///< ln 2π (likelihoods)

/// Index of the first non-finite entry of v, −1 when all are finite.
Eigen::Index first_non_finite(const Eigen::VectorXd& v);

/// Position of a matrix entry; row = col = −1 means none.
struct Cell {
  Eigen::Index row = -1;
  Eigen::Index col = -1;
  bool found() const { return row >= 0; }
};

/// First non-finite entry of m in column-major order.
Cell first_non_finite(const Eigen::MatrixXd& m);

/// Throw InputError "<name> has a non-finite value (x) at (i, j)" / "… at index i".
void check_finite(const Eigen::MatrixXd& m, const char* name);
void check_finite(const Eigen::VectorXd& v, const char* name);

/// Automatic rank tolerance for an n×u design: 100·max(n, u)·ε.
double default_rank_tolerance(Eigen::Index n, Eigen::Index u);

/// Column-pivoted QR of W·S⁻¹, S = diag(scale) the column norms of W, so the rank test
/// does not depend on the parameters' units. A zero column keeps scale 1 (and stays zero).
struct ScaledQr {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
  Eigen::VectorXd scale;
  Eigen::Index first_zero_column = -1;  ///< first column of W that is exactly zero, or −1

  /// Numerical rank: the first k with |R_kk| ≤ tol·|R_00| (u when there is none).
  Eigen::Index rank(double tol) const;
  /// Parameter (column of W) at pivot position k.
  Eigen::Index column_at(Eigen::Index k) const { return qr.colsPermutation().indices()(k); }
};

ScaledQr scaled_qr(Eigen::MatrixXd w);

/// scaled_qr of a whitened design that must have full column rank: throws NumericalError
/// naming the first undetermined parameter when a column is zero or |R_kk| ≤ tol·|R_00|.
ScaledQr full_rank_qr(Eigen::MatrixXd w, double tol);

/// The first u columns of Q of a ScaledQr (n×u, orthonormal): a basis of the column space.
Eigen::MatrixXd thin_q(const ScaledQr& s);

}  // namespace meridian::adjust::detail
