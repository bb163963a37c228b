#include "meridian/gyro/markov_covariance.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gyro {

using Eigen::Index;
using Eigen::MatrixXd;

namespace {

void check_n(int n) {
  if (n < 1)
    throw InputError(fmt::format("Markov covariance: needs at least 1 reading, got {}", n));
}

}  // namespace

MatrixXd MarkovFactors::covariance(double sigma1_sq, double sigma2_sq) const {
  if (!(std::isfinite(sigma1_sq) && sigma1_sq >= 0.0 && std::isfinite(sigma2_sq) &&
        sigma2_sq >= 0.0))
    throw InputError(
        fmt::format("Markov covariance: variance components must be finite and "
                    ">= 0, are {} and {}",
                    sigma1_sq, sigma2_sq));
  return sigma1_sq * q1() + sigma2_sq * q2();
}

bool ar2_stationary(double rho1, double rho2) {
  return std::isfinite(rho1) && std::isfinite(rho2) && rho1 + rho2 < 1.0 && rho2 - rho1 < 1.0 &&
         std::fabs(rho2) < 1.0;
}

MarkovFactors markov1_factors(int n, double rho) {
  check_n(n);
  if (!(std::isfinite(rho) && std::fabs(rho) < 1.0))
    throw InputError(
        fmt::format("Markov-1: rho = {} is outside the stationary region |rho| < 1", rho));
  const Index m = n;
  MarkovFactors f{MatrixXd::Zero(m, m), MatrixXd(m, 1)};
  double p = 1.0;  // ρ^k built by multiplication: the recursion, not pow()
  for (Index k = 0; k < m; ++k) {
    for (Index i = k; i < m; ++i) f.C(i, i - k) = p;
    p *= rho;
    f.B(k, 0) = p;  // ρ^{k+1}
  }
  return f;
}

MarkovFactors markov2_factors(int n, double rho1, double rho2) {
  check_n(n);
  if (!(std::isfinite(rho1) && std::isfinite(rho2)))
    throw InputError(fmt::format("Markov-2: rho1 = {}, rho2 = {} must be finite", rho1, rho2));
  if (!ar2_stationary(rho1, rho2)) {
    const char* bound = rho1 + rho2 >= 1.0   ? "rho1 + rho2 < 1"
                        : rho2 - rho1 >= 1.0 ? "rho2 - rho1 < 1"
                                             : "|rho2| < 1";
    throw InputError(
        fmt::format("Markov-2: (rho1, rho2) = ({}, {}) is outside the AR(2) "
                    "stationarity triangle ({} is violated): the process is "
                    "non-stationary",
                    rho1, rho2, bound));
  }
  const Index m = n;
  MarkovFactors f{MatrixXd::Zero(m, m), MatrixXd(m, 2)};
  for (Index j = 0; j < m; ++j) {
    f.C(j, j) = 1.0;
    if (j + 1 < m) f.C(j + 1, j) = rho1;
    for (Index i = j + 2; i < m; ++i) f.C(i, j) = rho1 * f.C(i - 1, j) + rho2 * f.C(i - 2, j);
  }
  for (Index i = 0; i < m; ++i) {
    if (i == 0)
      f.B(i, 0) = rho1;
    else if (i == 1)
      f.B(i, 0) = rho1 * rho1 + rho2;
    else
      f.B(i, 0) = rho1 * f.B(i - 1, 0) + rho2 * f.B(i - 2, 0);
    f.B(i, 1) = rho2 * f.C(i, 0);
  }
  return f;
}

}  // namespace meridian::gyro
