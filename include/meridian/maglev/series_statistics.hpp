#pragma once
/// \file series_statistics.hpp
/// Location estimates of one autocorrelated current series with honest σ
/// (maglev-gyro spec §3, "Precision"): the sample mean with σ from the
/// effective sample size, the median, the Huber mean, and the stability of
/// repeated determinations.
///
/// Autocovariance (biased estimator, the one whose sequence is positive
/// semi-definite): γ_k = (1/n)·Σ_{i<n−k} (x_i − x̄)(x_{i+k} − x̄).
/// Long-run variance σ²_LR = γ_0 + 2·Σ_{k≥1} γ_k, truncated by Geyer's
/// initial positive sequence (Geyer 1992, Practical Markov chain Monte Carlo,
/// Statistical Science 7(4)): pair sums Γ_m = γ_{2m} + γ_{2m+1} are added
/// while positive, σ²_LR = −γ_0 + 2·Σ_m Γ_m, at most kMaxLongRunLag lags.
/// Effective sample size n_eff = n·γ_0/σ²_LR, limited to [1, n] (the limit
/// n keeps the σ of a slightly anti-correlated series from being optimistic);
/// σ(x̄) = sqrt(γ_0/n_eff) = sqrt(σ²_LR/n) (when not limited).
///
/// Units: those of the samples (A for rotor currents; variances A²).
/// Errors: InputError for fewer than 2 samples or non-finite values.

#include <cstddef>
#include <span>
#include <vector>

#include "meridian/core/uncertain.hpp"

namespace meridian::maglev {

/// Longest lag the long-run variance sums (a series correlated longer than
/// this gets a note: its σ may be optimistic).
inline constexpr int kMaxLongRunLag = 1000;

/// γ_0 … γ_max_lag about `mean` (max_lag < x.size()). Throws InputError otherwise.
std::vector<double> autocovariance(std::span<const double> x, double mean, int max_lag);

/// Geyer-truncated long-run variance from an autocovariance sequence acov[0…L].
struct LongRunVariance {
  double gamma0 = 0.0;     ///< γ_0 (sample variance with 1/n)
  double long_run = 0.0;   ///< σ²_LR (≥ 0; γ_0 when the first pair sum is not positive)
  int lags = 0;            ///< last lag summed
  bool truncated = false;  ///< the sequence was still positive at the last lag available
};
LongRunVariance long_run_variance(std::span<const double> acov);

/// The mean of a series with σ from the effective sample size.
struct MeanEstimate {
  double mean = 0.0;
  double sigma = 0.0;     ///< σ of the mean
  double n_eff = 0.0;     ///< effective sample size, 1 ≤ n_eff ≤ n
  std::size_t n = 0;      ///< samples
  double variance = 0.0;  ///< sample variance γ_0 (1/n)
  int lags = 0;           ///< lags summed in σ²_LR
  bool lag_limit_reached = false;
};

/// Mean, σ(x̄) and n_eff of x (see the file comment). Throws InputError for
/// fewer than 2 samples or a non-finite value.
MeanEstimate mean_with_autocorrelation(std::span<const double> x);

/// The median of x (numpy.median: mean of the two middle values for even n).
/// Throws InputError for an empty x.
double median(std::span<const double> x);

/// Huber's M-estimate of location (Huber 1964; tuning k in units of the
/// scale s = 1.4826·MAD, default 1.345: 95 % efficiency under normality),
/// by iteratively reweighted means (to 1e-10·s, at most 100 iterations).
/// σ: the asymptotic variance s²·mean(ψ²)/mean(ψ')² / n, multiplied by
/// n/n_eff of the series for autocorrelation. With s = 0 (more than half the
/// samples equal) the median is returned with σ 0. Throws InputError for
/// fewer than 2 samples, non-finite values or k ≤ 0; NumericalError when the
/// iteration does not converge.
Uncertain huber_mean(std::span<const double> x, double n_eff, double k = 1.345);

/// Stability of repeated determinations (spec §3): m = sqrt(Σ v²/(n − 1)),
/// v_i = x_i − x̄ (units of x). Throws InputError for fewer than 2 values.
double stability(std::span<const double> values);

}  // namespace meridian::maglev
