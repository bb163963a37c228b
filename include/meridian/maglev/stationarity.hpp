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
///    when s is part of the reference (N kept samples), + otherwise. σ²_LR is
///    the long-run variance of the kept samples taken as one series about
///    their common mean (series_statistics.hpp, Geyer; segment means are not
///    removed, which would hide the low-frequency variance), so
///    autocorrelation widens the test. Two-sided Student t test at the
///    segment level with ν = n/(2K) degrees of freedom (K lags summed: the
///    estimated σ²_LR of a flat-top lag window, Priestley 1981 §6.2.3);
///    pass 1 uses robust batch means instead, σ²_LR = median(m_s·(x̄_s − μ)²)/
///    0.4549 with ν = 0.37·S.
///  * autocovariance: the vector u_s = (log(γ_s,0/γ_0), γ_s,k/γ_s,0 − γ_k/γ_0,
///    k = 1…M) — variance and autocorrelations, closer to normal than the
///    autocovariances of a short correlated segment — against its covariance
///    from Bartlett's formula m·Cov(γ̂_k, γ̂_l) = Σ_j γ_j·γ_{j+l−k} +
///    γ_{j+l}·γ_{j−k} (Bartlett 1946; Priestley 1981, §5.3) through the delta
///    method, with γ the autocovariance of the kept samples about their
///    common mean; Q_s = u_sᵀ·C⁻¹·u_s (the full matrix: the lags of a
///    correlated series are strongly correlated, and a sum treating them as
///    independent rejected clean segments ~4× too often) against χ²(M+1)
///    (adjust::chi_squared_upper_probability). The spec names lags 1…M; lag 0
///    (the variance) is added because a burst of oscillation shows first in
///    the variance.
///  * correlation_time_samples = σ²_LR/γ_0 of the kept samples: when it is
///    more than L/10 the segment statistics are far from normal and clean
///    segments are still rejected more often than α (reduce.hpp warns).
///
/// Significance: by default α is the family-wise level of a position
/// (Bonferroni, α/(2S) per segment and test, S segments, two tests): the
/// spec's per-segment α would reject α·S clean segments by chance, the most
/// deviating ones, and the kept mean would be biased by the selection.
/// Monte Carlo (tests/maglev/test_montecarlo.cpp): 2–4.5 % of clean
/// positions lose a segment for AR(1) φ = 0.8 and 0.95; 14–20 % at φ = 0.98
/// (correlation time a quarter of a segment; about 1 % of the samples).
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
  double alpha = 0.05;  ///< significance level (per position when family_wise, else per segment and test)
  /// Bonferroni: each segment and test at α/(2S) (S segments), so a clean series of any length
  /// loses a segment by chance with probability ≤ α. Without it, about α·S clean
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
  double segment_alpha = 0.0;      ///< level of each segment's tests (α/(2S) when family-wise)
  double reference_mean = 0.0;     ///< μ of the kept segments
  double long_run_variance = 0.0;  ///< σ²_LR used in the last pass's mean tests
  /// σ²_LR/γ_0 of the kept samples: the integrated correlation time in samples (1: white).
  double correlation_time_samples = 1.0;
  std::vector<double> reference_autocovariance;  ///< γ_0 … γ_J, mean over the kept segments
  int passes = 0;
  std::size_t kept_samples = 0;
  /// Indices of the rejected segments, ascending.
  std::vector<std::size_t> rejected() const;
};

/// Segment x and test every segment (see the file comment).
StationarityResult test_stationarity(std::span<const double> x, const StationarityOptions& options);

}  // namespace meridian::maglev
