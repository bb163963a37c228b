#pragma once
// Test helpers of the adjust tests: random matrices, the message of an expected exception.
#include <limits>
#include <random>
#include <string>

#include <Eigen/Dense>

namespace meridian_test {

inline Eigen::MatrixXd random_matrix(Eigen::Index r, Eigen::Index c, std::mt19937_64& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::MatrixXd m(r, c);
  for (Eigen::Index i = 0; i < r; ++i)
    for (Eigen::Index j = 0; j < c; ++j) m(i, j) = N(rng);
  return m;
}

/// Random symmetric positive definite matrix with correlations: B·Bᵀ + ½I, B uniform in [−1, 1].
inline Eigen::MatrixXd random_spd(Eigen::Index n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::MatrixXd B(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) B(i, j) = U(rng);
  return B * B.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
}

/// Message of the exception thrown by f, or "" when none of type E is thrown.
template <typename E, typename F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace meridian_test
