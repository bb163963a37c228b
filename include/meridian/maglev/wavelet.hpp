#pragma once
/// \file wavelet.hpp
/// The one-dimensional discrete wavelet transform with Daubechies wavelets
/// db2…db10: one level (dwt/idwt) and multilevel (wavedec/waverec), in the
/// conventions of PyWavelets 1.x (`pywt.dwt`, `idwt`, `wavedec`, `waverec`)
/// so that coefficients and reconstructions agree with it to rounding
/// (tests/maglev/test_wavelet_reference.cpp checks 1e-10 against Debian's
/// python3-pywt).
///
/// Filters (F = 2N taps for dbN): rec_lo = the Daubechies scaling filter h
/// (Σh = √2, Σh² = 1, N vanishing moments; coefficients as tabulated by
/// PyWavelets, Daubechies (1992) Ten lectures on wavelets, SIAM, Table 6.1);
/// dec_lo[k] = h[F−1−k], dec_hi[k] = (−1)^(k+1)·h[k], rec_hi[k] = dec_hi[F−1−k].
///
/// One level, input x of length n ≥ 1 (x_e: x extended by the mode):
///   cA[o] = Σ_{j<F} dec_lo[j]·x_e[i_o − j],  cD likewise with dec_hi,
///   symmetric:     i_o = 2o + 1, o = 0 … ⌊(n+F−1)/2⌋ − 1; x_e is the
///                  half-sample symmetric extension (… x1 x0 | x0 x1 … x_{n−1} | x_{n−1} x_{n−2}
///                  …);
///   periodization: i_o = F/2 + 2o, o = 0 … ⌈n/2⌉ − 1; x_e is x (with x_{n−1}
///                  repeated once when n is odd) extended periodically.
/// Inverse: symmetric keeps the samples F−2 … 2m−1 of the full convolution
/// y[t] = Σ_o cA[o]·rec_lo[t−2o] + cD[o]·rec_hi[t−2o] (m coefficients, 2m−F+2
/// samples); periodization is the adjoint (= inverse) of the periodic
/// forward transform (2m samples). waverec trims an approximation that is one
/// longer than the next detail level, as pywt.waverec does.
///
/// Units: whatever the samples carry (the transform is linear).
/// Errors: InputError for an unknown wavelet name, an empty or non-finite
/// input, a level < 1 or above max_level, mismatched coefficient lengths.

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace meridian::maglev {

/// How the signal is extended beyond its ends (PyWavelets' mode names).
enum class ExtensionMode { Symmetric, Periodization };

/// "symmetric", "periodization".
std::string to_string(ExtensionMode mode);
/// Inverse of to_string; throws InputError naming the accepted values.
ExtensionMode extension_mode_from_string(std::string_view text);

/// A Daubechies wavelet dbN, 2 ≤ N ≤ 10 (filter length F = 2N).
class Wavelet {
 public:
  /// Throws InputError unless 2 ≤ order ≤ 10.
  explicit Wavelet(int order);
  /// "db2" … "db10" (ASCII case ignored); throws InputError otherwise.
  static Wavelet from_name(std::string_view name);

  int order() const noexcept { return order_; }
  std::string name() const;  ///< "db4"
  std::size_t filter_length() const noexcept { return rec_lo_.size(); }
  const std::vector<double>& dec_lo() const noexcept { return dec_lo_; }
  const std::vector<double>& dec_hi() const noexcept { return dec_hi_; }
  const std::vector<double>& rec_lo() const noexcept { return rec_lo_; }
  const std::vector<double>& rec_hi() const noexcept { return rec_hi_; }

 private:
  int order_;
  std::vector<double> dec_lo_, dec_hi_, rec_lo_, rec_hi_;
};

/// Number of coefficients of one level for an input of n samples:
/// ⌊(n+F−1)/2⌋ (symmetric), ⌈n/2⌉ (periodization).
std::size_t dwt_coefficient_length(std::size_t n, std::size_t filter_length, ExtensionMode mode);

/// Deepest useful level for n samples: ⌊log2(n/(F−1))⌋, 0 when n < F−1
/// (pywt.dwt_max_level). wavedec accepts levels 1 … max_level.
int max_level(std::size_t n, const Wavelet& wavelet);

/// One level: approximation and detail coefficients.
struct DwtLevel {
  std::vector<double> approximation;  ///< cA
  std::vector<double> detail;         ///< cD
};

/// One level of the forward transform (pywt.dwt). Throws InputError for an
/// empty or non-finite input.
DwtLevel dwt(std::span<const double> x, const Wavelet& wavelet, ExtensionMode mode);

/// One level of the inverse transform (pywt.idwt) from cA and cD of equal
/// length m ≥ 1: 2m−F+2 samples (symmetric; needs 2m ≥ F−1) or 2m
/// (periodization). Throws InputError for unequal or too short inputs.
std::vector<double> idwt(std::span<const double> approximation, std::span<const double> detail,
                         const Wavelet& wavelet, ExtensionMode mode);

/// Multilevel coefficients, ordered as pywt.wavedec returns them:
/// [cA_p, cD_p, cD_{p−1}, …, cD_1] (coefficients[0] the approximation at
/// level p, coefficients[p] the finest details).
struct WaveletCoefficients {
  std::vector<std::vector<double>> coefficients;
  int level() const noexcept { return static_cast<int>(coefficients.size()) - 1; }
};

/// p-level decomposition (pywt.wavedec(x, wavelet, mode, level=p)). Throws
/// InputError for an empty or non-finite x, p < 1 or p > max_level(x.size()).
WaveletCoefficients wavedec(std::span<const double> x, const Wavelet& wavelet, ExtensionMode mode,
                            int level);

/// Reconstruction (pywt.waverec). The result has the length of the original
/// signal when it was even at every level (symmetric mode reconstructs
/// n rounded up to even at each level, as pywt does); callers trim to n.
/// Throws InputError for fewer than two coefficient arrays or lengths that
/// do not fit together.
std::vector<double> waverec(const WaveletCoefficients& c, const Wavelet& wavelet,
                            ExtensionMode mode);

/// The coefficients of one decomposition as views, in WaveletCoefficients' order: [0] = cA_p,
/// [k] = cD_{p−k+1} (k = 1 … p; [p] the finest details).
using CoefficientViews = std::vector<std::span<double>>;

/// wavedec(x, wavelet, mode, level), then `edit` changes the coefficients in place (it must not
/// change their number or lengths), then waverec trimmed to x.size() — the same arithmetic as the
/// three calls, bit for bit, but all levels live in one scratch array allocated once (huge pages
/// for long series, core/scratch_array.hpp) instead of two vectors per level: what denoise() of a
/// series of millions of samples runs. Throws what wavedec throws, and what `edit` throws.
std::vector<double> edit_coefficients(std::span<const double> x, const Wavelet& wavelet,
                                      ExtensionMode mode, int level,
                                      const std::function<void(const CoefficientViews&)>& edit);

}  // namespace meridian::maglev
