// Wavelet filters and transforms against closed forms: orthonormality, vanishing
// moments, perfect reconstruction, energy conservation (Parseval) of the orthogonal
// periodized transform; thresholds; errors. (PyWavelets itself: test_wavelet_reference.)

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/wavelet.hpp"

using namespace meridian;
using namespace meridian::maglev;

namespace {
std::vector<double> noise(std::size_t n, unsigned seed, double sigma = 1.0) {
  std::mt19937_64 g(seed);
  std::normal_distribution<double> d(0.0, sigma);
  std::vector<double> v(n);
  for (auto& x : v) x = d(g);
  return v;
}
}  // namespace

TEST(Wavelet, FiltersAreOrthonormalWithVanishingMoments) {
  for (int n = 2; n <= 10; ++n) {
    const Wavelet w(n);
    const auto& h = w.rec_lo();
    ASSERT_EQ(h.size(), static_cast<std::size_t>(2 * n));
    EXPECT_NEAR(std::accumulate(h.begin(), h.end(), 0.0), std::sqrt(2.0), 1e-14);
    // Σ h_k h_{k+2m} = δ_m (orthonormal shifts by two).
    for (std::size_t m = 0; 2 * m < h.size(); ++m) {
      double s = 0;
      for (std::size_t k = 0; k + 2 * m < h.size(); ++k) s += h[k] * h[k + 2 * m];
      EXPECT_NEAR(s, m == 0 ? 1.0 : 0.0, 1e-14) << "db" << n << " m=" << m;
    }
    // N vanishing moments of the wavelet: Σ k^p g_k = 0, p < N, g = dec_hi.
    const auto& g = w.dec_hi();
    for (int p = 0; p < n; ++p) {
      double s = 0, scale = 0;
      for (std::size_t k = 0; k < g.size(); ++k) {
        s += std::pow(static_cast<double>(k), p) * g[k];
        scale += std::pow(static_cast<double>(k), p) * std::abs(g[k]);
      }
      EXPECT_NEAR(s / scale, 0.0, 1e-9) << "db" << n << " moment " << p;
    }
  }
}

TEST(Wavelet, PerfectReconstructionEveryWaveletAndMode) {
  for (std::size_t len : {256u, 1000u, 777u}) {
    const auto x = noise(len, 7u + static_cast<unsigned>(len));
    for (int n = 2; n <= 10; ++n) {
      const Wavelet w(n);
      for (auto mode : {ExtensionMode::Symmetric, ExtensionMode::Periodization}) {
        const int top = max_level(len, w);
        ASSERT_GE(top, 1);
        const auto c = wavedec(x, w, mode, top);
        auto y = waverec(c, w, mode);
        ASSERT_GE(y.size(), len);
        for (std::size_t i = 0; i < len; ++i) ASSERT_NEAR(y[i], x[i], 1e-11) << n << " " << i;
      }
    }
  }
}

TEST(Wavelet, EditCoefficientsIsWavedecThenWaverecBitForBit) {
  // The one-scratch-array path of denoise() against the three public calls: the same
  // coefficients handed to `edit`, and the same reconstruction after an edit, to the last bit.
  for (int order : {2, 4, 7, 10}) {
    const Wavelet w(order);
    for (ExtensionMode mode : {ExtensionMode::Symmetric, ExtensionMode::Periodization}) {
      for (std::size_t n : {std::size_t{257}, std::size_t{1000}, std::size_t{4099}}) {
        const auto x = noise(n, static_cast<unsigned>(order * 10000 + n));
        const int level = std::min(4, max_level(n, w));
        WaveletCoefficients c = wavedec(x, w, mode, level);
        const auto v = edit_coefficients(x, w, mode, level, [&](const CoefficientViews& views) {
          ASSERT_EQ(views.size(), c.coefficients.size());
          for (std::size_t k = 0; k < views.size(); ++k) {
            ASSERT_EQ(views[k].size(), c.coefficients[k].size());
            EXPECT_TRUE(std::equal(views[k].begin(), views[k].end(), c.coefficients[k].begin()))
                << "db" << order << " n=" << n << " array " << k;
          }
          for (std::size_t k = 1; k < views.size(); ++k)  // an edit: halve every detail
            for (double& d : views[k]) d *= 0.5;
        });
        for (std::size_t k = 1; k < c.coefficients.size(); ++k)
          for (double& d : c.coefficients[k]) d *= 0.5;
        auto expected = waverec(c, w, mode);
        ASSERT_GE(expected.size(), n);
        expected.resize(n);
        ASSERT_EQ(v.size(), n);
        EXPECT_TRUE(std::equal(v.begin(), v.end(), expected.begin()))
            << "db" << order << " " << to_string(mode) << " n=" << n;
      }
    }
  }
}

TEST(Wavelet, PeriodizationConservesEnergy) {
  const auto x = noise(1024, 3);
  const double ex = std::inner_product(x.begin(), x.end(), x.begin(), 0.0);
  for (int n = 2; n <= 10; ++n) {
    const Wavelet w(n);
    const auto c = wavedec(x, w, ExtensionMode::Periodization, max_level(x.size(), w));
    double ec = 0;
    for (const auto& a : c.coefficients)
      ec += std::inner_product(a.begin(), a.end(), a.begin(), 0.0);
    EXPECT_NEAR(ec / ex, 1.0, 1e-13);
  }
}

TEST(Wavelet, LengthsAndMaxLevel) {
  const Wavelet w(4);  // F = 8
  EXPECT_EQ(dwt_coefficient_length(1000, 8, ExtensionMode::Symmetric), 503u);
  EXPECT_EQ(dwt_coefficient_length(1001, 8, ExtensionMode::Periodization), 501u);
  EXPECT_EQ(max_level(1000, w), 7);  // ⌊log2(1000/7)⌋ = ⌊7.16⌋
  EXPECT_EQ(max_level(6, w), 0);
  EXPECT_EQ(max_level(7, w), 0);
  EXPECT_EQ(max_level(14, w), 1);
}

TEST(Wavelet, BadInputThrows) {
  EXPECT_THROW(Wavelet(1), InputError);
  EXPECT_THROW(Wavelet(11), InputError);
  EXPECT_THROW(Wavelet::from_name("haar"), InputError);
  EXPECT_THROW(Wavelet::from_name("db01"), InputError);
  EXPECT_EQ(Wavelet::from_name("DB7").order(), 7);
  EXPECT_THROW(extension_mode_from_string("zero"), InputError);
  const Wavelet w(4);
  std::vector<double> empty;
  EXPECT_THROW(wavedec(empty, w, ExtensionMode::Symmetric, 1), InputError);
  auto x = noise(100, 1);
  EXPECT_THROW(wavedec(x, w, ExtensionMode::Symmetric, 4), InputError);  // max level 3
  EXPECT_THROW(wavedec(x, w, ExtensionMode::Symmetric, 0), InputError);
  x[5] = std::nan("");
  EXPECT_THROW(wavedec(x, w, ExtensionMode::Symmetric, 2), InputError);
}

TEST(Denoise, ThresholdFunctions) {
  EXPECT_DOUBLE_EQ(soft_threshold(3.0, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(soft_threshold(-3.0, 1.0), -2.0);
  EXPECT_DOUBLE_EQ(soft_threshold(0.5, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(hard_threshold(-3.0, 1.0), -3.0);
  EXPECT_DOUBLE_EQ(hard_threshold(0.99, 1.0), 0.0);
  const std::vector<double> v{-4, 1, 3, -2};
  EXPECT_DOUBLE_EQ(median_abs(v), 2.5);
}

TEST(Denoise, SureThresholdMinimisesTheRiskEstimate) {
  // Brute force over a fine grid of t against the closed-form SURE.
  auto x = noise(300, 5);
  for (std::size_t i = 0; i < 30; ++i) x[i] += 6.0;
  const double t = sure_threshold(x);
  auto sure = [&](double tt) {
    double r = static_cast<double>(x.size());
    for (double v : x) r += (std::abs(v) <= tt ? -2.0 : 0.0) + std::min(v * v, tt * tt);
    return r;
  };
  const double limit = std::sqrt(2.0 * std::log(300.0));
  for (double tt = 0.0; tt <= limit; tt += 0.001) EXPECT_LE(sure(t), sure(tt) + 1e-9);
}

TEST(Denoise, RemovesWhiteNoiseAroundASmoothSignal) {
  const std::size_t n = 4096;
  auto x = noise(n, 11, 0.1);
  std::vector<double> s(n);
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = std::sin(2.0 * M_PI * static_cast<double>(i) / 1024.0);
    x[i] += s[i];
  }
  for (auto rule : {ThresholdRule::Universal, ThresholdRule::Sure}) {
    DenoiseOptions o;
    o.level = 6;
    o.rule = rule;
    const auto r = denoise(x, o);
    EXPECT_NEAR(r.noise_sigma, 0.1, 0.01);
    double e_raw = 0, e_den = 0;
    for (std::size_t i = 0; i < n; ++i) {
      e_raw += (x[i] - s[i]) * (x[i] - s[i]);
      e_den += (r.values[i] - s[i]) * (r.values[i] - s[i]);
    }
    EXPECT_LT(e_den, 0.2 * e_raw);
    ASSERT_EQ(r.thresholds.size(), 6u);
  }
}

TEST(Denoise, ConstantSeriesIsUnchanged) {
  std::vector<double> x(500, 0.25);
  DenoiseOptions o;
  const auto r = denoise(x, o);
  EXPECT_EQ(r.noise_sigma, 0.0);
  for (double v : r.values) EXPECT_NEAR(v, 0.25, 1e-14);
}

TEST(Denoise, MedianAbsAgreesWithSorting) {
  std::mt19937_64 g(21);
  std::normal_distribution<double> n01;
  for (std::size_t n : {1u, 2u, 3u, 10u, 1001u, 100000u, 100001u}) {
    std::vector<double> v(n);
    for (auto& x : v) x = n01(g) * 1e-5;
    if (n > 10) {
      for (std::size_t i = 0; i < n / 10; ++i) v[i] = 0.0;        // ties and zeros
      for (std::size_t i = n / 10; i < n / 5; ++i) v[i] = -3e-6;  // repeated values of both signs
    }
    std::vector<double> a(n);
    for (std::size_t i = 0; i < n; ++i) a[i] = std::abs(v[i]);
    std::sort(a.begin(), a.end());
    const double expected = n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
    EXPECT_EQ(median_abs(v), expected) << n;
  }
}
