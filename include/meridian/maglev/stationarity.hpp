#pragma once
/// \file stationarity.hpp
/// Selection of the stable segments of one position's current series
/// (maglev-gyro spec §3 steps 1–4).
///
/// The series is split into consecutive segments of L samples (the last one
/// takes the remainder when it is shorter than L/2, else stands alone).
/// Each segment s (m_s samples, mean x̄_s, autocovariance γ_s,k about its own
/// mean, series_statistics.hpp) is tested against the reference — the
/// position's stable state:
///
///  * mean stationarity: z_s = (x̄_s − μ)/sqrt(σ²_LR·(1/m_s ∓ 1/N)), the −
///    when s is part of the reference (N kept samples), + otherwise; σ²_LR the
///    Geyer-truncated long-run variance of the reference autocovariance, so
///    autocorrelation widens the test. Two-sided normal test at α
///    (adjust::normal_two_sided_probability).
///  * autocovariance: Q_s = Σ_{k=0}^{M} (γ_s,k − γ_k)²/V_k with Bartlett's
///    variance of a sample autocovariance V_k = (1/m_s)·Σ_{|j|≤J}(γ_j² +
///    γ_{j+k}·γ_{j−k}) (Bartlett 1946; Priestley 1981, Spectral analysis and
///    time series, §5.3), compared with χ²(M+1) at α
///    (adjust::chi_squared_upper_probability). The spec names lags 1…M; lag 0
///    (the variance) is added because a burst of oscillation shows first in
///    the variance. The lags are treated as independent, an approximation:
///    for strongly correlated noise the test rejects somewhat more often than α.
///
/// Significance: by default α is the family-wise level of a position
/// (Bonferroni, α/S per segment and test): the spec's per-segment α would
/// reject α·S clean segments by chance, the most deviating ones, and the
/// kept mean would be biased by the selection (seen in simulations: 2σ).
///
/// The reference is the position's own stable state, found iteratively: it
/// starts from the median of the segment means and the lag-wise median of the
/// segment autocovariances (robust against a minority of disturbed segments,
/// where the plain overall mean of the spec is pulled by the disturbance) and
/// is then the mean and the length-weighted mean autocovariance of the
/// segments kept, until the kept set repeats (at most 20 passes).
///
/// Errors: InputError for a series shorter than two segments, a segment
/// length below 32, M < 1 or ≥ L/4, α outside (0, 1), non-finite samples;
/// NumericalError when no segment passes both tests.

#include <cstddef>
#include <span>
#include <vector>

namespace meridian::maglev {

struct StationarityOptions {
  /// L, samples per segment; 0: automatic, max(64, n/20) (about 20 segments).
  std::size_t segment_length = 0;
  double alpha = 0.05;  ///< significance level (per position when family_wise, else per segment)
  /// Bonferroni: each segment is tested at α/S (S segments), so a clean series of any length
  /// loses a segment by chance with probability ≤ α per test. Without it, about α·S clean
  /// segments are rejected, and always the most extreme ones, which biases the kept mean.
  bool family_wise = true;
  int autocovariance_lags = 10;  ///< M
};

struct SegmentTest {
  std::size_t begin = 0;          ///< first sample (0-based)
  std::size_t end = 0;            ///< one past the last sample
  double mean = 0.0;              ///< x̄_s (units of the series)
  double z_mean = 0.0;            ///< mean-stationarity statistic
  double p_mean = 0.0;            ///< its two-sided p-value
  double q_autocovariance = 0.0;  ///< Q_s
  double p_autocovariance = 0.0;  ///< P(χ²(M+1) > Q_s)
  bool mean_passed = false;
  bool autocovariance_passed = false;
  bool kept = false;  ///< both passed: a stable segment
};

struct StationarityResult {
  std::vector<SegmentTest> segments;
  std::size_t segment_length = 0;  ///< L used
  double segment_alpha = 0.0;      ///< level of each segment's tests (α/S when family-wise)
  double reference_mean = 0.0;     ///< μ of the kept segments
  double long_run_variance = 0.0;  ///< σ²_LR of the reference
  std::vector<double> reference_autocovariance;  ///< γ_0 … γ_J of the reference
  int passes = 0;
  std::size_t kept_samples = 0;
  /// Indices of the rejected segments, ascending.
  std::vector<std::size_t> rejected() const;
};

/// Segment x and test every segment (see the file comment).
StationarityResult test_stationarity(std::span<const double> x, const StationarityOptions& options);

}  // namespace meridian::maglev
