#pragma once
/// \file whiteness.hpp
/// The Ljung–Box portmanteau test of whiteness, accumulated one epoch at a time so that a
/// line of millions of epochs needs O(max_lag) memory: for a correct model the normalised
/// innovations of a Kalman filter are white (innovation.hpp), a time-correlated noise the
/// model does not have makes them autocorrelated.
///
/// For one series e_1 … e_n with mean ē and sample autocorrelations
///   ρ̂_k = Σ_{t=k+1}^{n} (e_t − ē)(e_{t−k} − ē) / Σ_{t=1}^{n} (e_t − ē)²,
///   Q = n(n + 2)·Σ_{k=1}^{h} ρ̂_k² / (n − k)  ~  χ²(h) for a white series
/// (Ljung & Box 1978, "On a measure of lack of fit in time series models", Biometrika 65(2),
/// 297–303). For m series that are independent of each other under the null hypothesis (the
/// components of S^{-1/2}·ν of a vector innovation), Q is the sum of their Q and has m·h
/// degrees of freedom. The test rejects when Q > χ²_{1−α}(m·h) (adjust/statistics.hpp,
/// Boost.Math).

#include <cstddef>
#include <vector>

namespace meridian::filter {

/// The outcome of a Ljung–Box test.
struct LjungBoxResult {
  std::size_t samples = 0;      ///< n, values in each series
  int lags = 0;                 ///< h; 0: too few samples, not tested (pass)
  double q = 0.0;               ///< Q, summed over the series
  double dof = 0.0;             ///< m·h
  double alpha = 0.0;           ///< significance level
  double critical_value = 0.0;  ///< χ²_{1−α}(m·h)
  double p_value = 1.0;         ///< P(χ²(m·h) > Q)
  bool pass = true;             ///< Q ≤ critical_value (or not tested)
};

/// The number of lags h = min(max_lag, ⌊n/5⌋) used by LjungBox::result by default.
int ljung_box_default_lags(std::size_t samples, int max_lag);

/// Streaming accumulator of the lag sums of `series` series up to lag `max_lag`.
class LjungBox {
 public:
  /// series ≥ 1, max_lag ≥ 1 (InputError otherwise).
  LjungBox(int series, int max_lag);
  /// One value of each series (values[0 … series−1]), the next epoch. Non-finite values throw
  /// InputError.
  void add(const double* values);
  std::size_t size() const { return n_; }
  int max_lag() const { return max_lag_; }
  /// The test at significance α (0 < α < 1) with h = lags lags (1 ≤ h ≤ max_lag, h < n);
  /// lags = 0 asks for ljung_box_default_lags(n, max_lag). A result with lags 0 (not tested,
  /// pass) when that gives 0.
  LjungBoxResult result(double alpha, int lags = 0) const;

 private:
  int m_, max_lag_;
  std::size_t n_ = 0;
  std::vector<double> sum_;        // Σ e, per series
  std::vector<double> lag_sum_;    // Σ_{t>k} e_t·e_{t−k}, [series][k], k = 0…max_lag
  std::vector<double> first_;      // the first max_lag values, [series][i]
  std::vector<double> last_;       // ring of the last max_lag values, [series][i]
};

}  // namespace meridian::filter
