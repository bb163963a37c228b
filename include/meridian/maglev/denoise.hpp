#pragma once
/// \file denoise.hpp
/// Wavelet denoising of one series (maglev-gyro spec §3 step 5): a p-level
/// DWT (wavelet.hpp), the detail coefficients thresholded, the series
/// reconstructed from the approximation at level p (kept unchanged) and the
/// thresholded details.
///
/// Noise level (Donoho & Johnstone 1994, Ideal spatial adaptation by wavelet
/// shrinkage, Biometrika 81(3)): σ = median(|d_1|)/0.6745 from the finest
/// detail coefficients d_1 (the median of an even count is the mean of the
/// two middle values, as numpy.median).
/// Rules:
///  * universal: λ = σ·sqrt(2·ln n), n the length of the series, the same λ
///    on every detail level;
///  * sure: per level j with n_j coefficients, λ_j minimises Stein's unbiased
///    risk estimate SURE(t) = n_j − 2·#{|d_i/σ| ≤ t} + Σ min((d_i/σ)², t²)
///    over t ∈ {0, |d_i/σ|} (Donoho & Johnstone 1995, Adapting to unknown
///    smoothness via wavelet shrinkage, JASA 90(432)), limited to the
///    universal threshold of the level σ·sqrt(2·ln n_j); λ_j = |d_i| of the
///    coefficient at the minimum (exactly, not σ·t rounded).
/// Thresholding (pywt.threshold): soft d → sign(d)·max(|d| − λ, 0); hard
/// d → d when |d| ≥ λ, else 0. Ties: a SURE threshold always equals one
/// |d_i|; hard thresholding keeps that coefficient (|d| ≥ λ), soft makes it 0.
/// With the universal rule the result equals pywt.wavedec → pywt.threshold
/// on every detail array → pywt.waverec, trimmed to n (tests compare 1e-10).
///
/// Units: those of the samples. Errors: InputError from wavedec (empty,
/// non-finite, level not possible for n and the wavelet). σ = 0 (more than
/// half of d_1 exactly zero) gives λ = 0: the series is returned as
/// reconstructed, unchanged to rounding.
///
/// `maglev denoise` is denoise_series(): a whole position series, validated
/// (series.hpp), its level kDefaultLevel lowered to what a short series allows
/// unless one is asked.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meridian/maglev/series.hpp"
#include "meridian/maglev/wavelet.hpp"

namespace meridian::maglev {

enum class ThresholdKind { Soft, Hard };
enum class ThresholdRule { Universal, Sure };

std::string to_string(ThresholdKind kind);  ///< "soft", "hard"
std::string to_string(ThresholdRule rule);  ///< "universal", "sure"
/// Inverses of to_string; throw InputError naming the accepted values.
ThresholdKind threshold_kind_from_string(std::string_view text);
ThresholdRule threshold_rule_from_string(std::string_view text);

/// Defaults of the spec: db4, soft, universal, symmetric extension.
struct DenoiseOptions {
  int wavelet_order = 4;  ///< dbN, 2 ≤ N ≤ 10
  int level = 4;          ///< p ≥ 1, ≤ max_level(n)
  ExtensionMode mode = ExtensionMode::Symmetric;
  ThresholdKind kind = ThresholdKind::Soft;
  ThresholdRule rule = ThresholdRule::Universal;
};

/// The decomposition level `maglev denoise` and `maglev reduce` use when none is asked.
inline constexpr int kDefaultLevel = 6;

/// kDefaultLevel lowered to the deepest level a series of n samples allows with `wavelet`
/// (max_level), and at least 1 (denoise() then refuses a series too short for any level).
int default_level(std::size_t n, const Wavelet& wavelet);

struct DenoiseResult {
  DenoiseOptions options;           ///< the options used (the level actually used)
  std::vector<double> values;       ///< the denoised series, same length as the input
  double noise_sigma = 0.0;         ///< σ = median(|d_1|)/0.6745 (units of the samples)
  std::vector<double> thresholds;   ///< λ per detail level, [0] = level 1 (finest) … [p−1]
  std::vector<std::size_t> zeroed;  ///< coefficients set to 0 per level, same order
  std::vector<std::size_t> coefficients;  ///< coefficients per level, same order
};

/// The threshold functions (pywt.threshold): λ ≥ 0.
double soft_threshold(double d, double lambda) noexcept;
double hard_threshold(double d, double lambda) noexcept;

/// The median of |v| (numpy.median); throws InputError for an empty v.
double median_abs(std::span<const double> v);

/// SURE threshold t ≥ 0 (in units of σ) for the normalised coefficients x = d/σ,
/// limited to sqrt(2·ln x.size()). Throws InputError for an empty x.
double sure_threshold(std::span<const double> x);

/// Denoise `x` (see the file comment). Throws as the file comment says.
DenoiseResult denoise(std::span<const double> x, const DenoiseOptions& options);

/// A whole series denoised (`maglev denoise`): its times as given, its currents denoised.
struct SeriesDenoising {
  PositionSeries series;    ///< time_s as given; current_A the denoised values
  DenoiseResult denoising;  ///< σ, λ per level, the options used (values as series.current_A)
};

/// Validate `s` (validate_series, field "series": "series.current_A") and denoise its currents;
/// `options.level` 0 means default_level(n): the default, lowered for a short series (an asked
/// level is taken as asked and refused when too deep). Throws InputError.
SeriesDenoising denoise_series(const PositionSeries& s, DenoiseOptions options);

}  // namespace meridian::maglev
