#pragma once
/// \file consistency.hpp
/// Filter consistency for simulations: the normalised estimation error squared (NEES), the
/// normalised innovation squared (NIS, innovation.hpp) and their χ² acceptance intervals, and a
/// Monte Carlo helper that averages them over independent replications.
///
/// Bar-Shalom, Li & Kirubarajan (2001) §5.4: for a correct model
///   NEES_k = (x_k − x̂_k)ᵀ·P_k⁻¹·(x_k − x̂_k) ~ χ²(n),   NIS_k ~ χ²(m);
/// the average of R independent values, R·ε̄ ~ χ²(R·n), so the two-sided interval at
/// confidence c is [χ²_{(1−c)/2}(R·n)/R, χ²_{(1+c)/2}(R·n)/R] (quantiles from
/// adjust/statistics.hpp). Per epoch, the R replications are independent: that interval is
/// exact. Averaged over epochs too (R·K values), it is exact for NIS (the innovations of a
/// correct filter are white) and only indicative for NEES (errors are correlated in time).

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "meridian/filter/detail/checks.hpp"
#include "meridian/filter/estimate.hpp"

namespace meridian::filter {

/// NEES of an estimate against the true state: eᵀ·P⁻¹·e, e = x_true − x̂ (Cholesky solve).
/// Throws NumericalError naming the epoch when P is not positive definite.
template <int N>
double nees(const Vector<N>& x_true, const Estimate<N>& estimate, Eigen::Index epoch = 0) {
  const Eigen::LLT<Matrix<N, N>> llt(estimate.P);
  if (llt.info() != Eigen::Success) [[unlikely]]
    detail::throw_not_positive_definite("covariance P of the NEES", epoch, estimate.P);
  const Vector<N> e = x_true - estimate.x;
  return e.dot(llt.solve(e));
}

/// Two-sided interval [lower, upper] of a χ²-distributed statistic's average.
struct ChiSquaredInterval {
  double lower = 0.0;
  double upper = 0.0;
  bool contains(double v) const { return v >= lower && v <= upper; }
};

/// Interval at confidence c (0 < c < 1, e.g. 0.95) of the average of `samples` ≥ 1 independent
/// χ²(dof) values. Throws InputError for arguments out of range.
ChiSquaredInterval average_interval(double dof, std::int64_t samples, double confidence);

/// One replication of a simulation: NEES and NIS per epoch (the same epochs in every run).
struct ConsistencyRun {
  std::vector<double> nees;  ///< NEES_k, k = 0…K−1
  std::vector<double> nis;   ///< NIS_k, k = 0…K'−1 (may be empty)
};

/// Averages of one statistic over the replications.
struct ConsistencySeries {
  double dof = 0.0;                     ///< n (NEES) or m (NIS) of each value
  std::vector<double> average;          ///< ensemble average per epoch, over the R runs
  ChiSquaredInterval epoch_interval;    ///< interval of one epoch's average (R samples; exact)
  double fraction_inside = 0.0;         ///< share of epochs whose average is inside it
  double overall_average = 0.0;         ///< average over all runs and epochs
  ChiSquaredInterval overall_interval;  ///< its interval (R·K samples; see the file comment)
  bool overall_inside() const { return overall_interval.contains(overall_average); }
};

/// The summary of a Monte Carlo consistency check.
struct MonteCarloConsistency {
  int runs = 0;
  double confidence = 0.0;
  ConsistencySeries nees;
  ConsistencySeries nis;  ///< empty averages when the runs have no NIS
};

/// Summarise replications: state dimension n, innovation dimension m, confidence c.
/// Throws InputError when there are no runs, the runs differ in their number of epochs, a
/// value is negative or not finite, or n, m < 1, or c is not in (0, 1).
MonteCarloConsistency summarise_consistency(const std::vector<ConsistencyRun>& runs,
                                            double state_dof, double innovation_dof,
                                            double confidence = 0.95);

/// Run `runs` replications, replicate(r) → ConsistencyRun for r = 0…runs−1 (each with its own
/// random stream seeded from r, so the check is reproducible), and summarise them.
template <typename Replicate>
MonteCarloConsistency monte_carlo_consistency(int runs, Replicate&& replicate, double state_dof,
                                              double innovation_dof, double confidence = 0.95) {
  std::vector<ConsistencyRun> all;
  all.reserve(static_cast<std::size_t>(runs > 0 ? runs : 0));
  for (int r = 0; r < runs; ++r) all.push_back(replicate(r));
  return summarise_consistency(all, state_dof, innovation_dof, confidence);
}

}  // namespace meridian::filter
