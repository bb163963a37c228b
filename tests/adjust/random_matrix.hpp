#pragma once
// Test helper of the adjust tests: a matrix of independent standard normal deviates.
#include <random>

#include <Eigen/Dense>

namespace meridian_test {

inline Eigen::MatrixXd random_matrix(Eigen::Index r, Eigen::Index c, std::mt19937_64& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::MatrixXd m(r, c);
  for (Eigen::Index i = 0; i < r; ++i)
    for (Eigen::Index j = 0; j < c; ++j) m(i, j) = N(rng);
  return m;
}

}  // namespace meridian_test
