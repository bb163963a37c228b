#include "meridian/maglev/denoise.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::maglev {

std::string to_string(ThresholdKind kind) { return kind == ThresholdKind::Soft ? "soft" : "hard"; }
std::string to_string(ThresholdRule rule) {
  return rule == ThresholdRule::Universal ? "universal" : "sure";
}

ThresholdKind threshold_kind_from_string(std::string_view text) {
  if (text == "soft") return ThresholdKind::Soft;
  if (text == "hard") return ThresholdKind::Hard;
  throw InputError(fmt::format("unknown threshold \"{}\" (soft or hard)", text),
                   ErrorContext{{}, std::nullopt, "threshold"});
}

ThresholdRule threshold_rule_from_string(std::string_view text) {
  if (text == "universal") return ThresholdRule::Universal;
  if (text == "sure") return ThresholdRule::Sure;
  throw InputError(fmt::format("unknown threshold rule \"{}\" (universal or sure)", text),
                   ErrorContext{{}, std::nullopt, "rule"});
}

double soft_threshold(double d, double lambda) noexcept {
  const double m = std::abs(d) - lambda;
  if (m <= 0.0) return 0.0;
  return d > 0.0 ? m : -m;
}

double hard_threshold(double d, double lambda) noexcept { return std::abs(d) < lambda ? 0.0 : d; }

double median_abs(std::span<const double> v) {
  if (v.empty()) throw InputError("the median of no values");
  // Selection without copying the whole array: the bit patterns of non-negative doubles order
  // as unsigned integers, so a histogram of their top 16 bits finds the bucket(s) holding the
  // middle rank(s); only those values are copied and partially sorted.
  const std::size_t n = v.size();
  const std::size_t k_hi = n / 2;
  const std::size_t k_lo = n % 2 == 0 ? n / 2 - 1 : n / 2;
  auto key = [](double x) {
    return static_cast<std::uint32_t>(std::bit_cast<std::uint64_t>(std::abs(x)) >> 48);
  };
  std::vector<std::uint32_t> hist(1u << 16, 0);
  for (double x : v) ++hist[key(x)];
  auto locate = [&](std::size_t k, std::size_t& before) {
    std::size_t cum = 0;
    for (std::uint32_t b = 0;; ++b) {
      if (cum + hist[b] > k) {
        before = cum;
        return b;
      }
      cum += hist[b];
    }
  };
  std::size_t before_lo = 0, before_hi = 0;
  const std::uint32_t b_lo = locate(k_lo, before_lo);
  const std::uint32_t b_hi = locate(k_hi, before_hi);
  std::vector<double> lo, hi;
  lo.reserve(hist[b_lo]);
  if (b_hi != b_lo) hi.reserve(hist[b_hi]);
  for (double x : v) {
    const std::uint32_t k = key(x);
    if (k == b_lo) {
      lo.push_back(std::abs(x));
    } else if (k == b_hi) {
      hi.push_back(std::abs(x));
    }
  }
  auto select = [](std::vector<double>& a, std::size_t r) {
    std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(r), a.end());
    return a[r];
  };
  const double upper = b_hi == b_lo ? select(lo, k_hi - before_lo) : select(hi, k_hi - before_hi);
  if (n % 2 == 1) return upper;
  const double lower = select(lo, k_lo - before_lo);
  return 0.5 * (lower + upper);
}

double sure_threshold(std::span<const double> x) {
  if (x.empty()) throw InputError("SURE threshold of no coefficients");
  const std::size_t n = x.size();
  std::vector<double> s(n);
  for (std::size_t i = 0; i < n; ++i) s[i] = x[i] * x[i];
  std::sort(s.begin(), s.end());
  const double nd = static_cast<double>(n);
  const double limit = std::sqrt(2.0 * std::log(std::max(nd, 2.0)));
  // SURE(t_k) with t_k² = s[k]: n − 2(k+1) + Σ_{i≤k} s_i + (n−k−1)·s_k; t = 0 gives n·1 − 2·0 … =
  // n.
  double best_t = 0.0;
  double best_risk = nd;  // t = 0: nothing shrunk, risk n
  double cumulative = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    cumulative += s[k];
    const double t = std::sqrt(s[k]);
    if (t > limit) break;
    const double risk =
        nd - 2.0 * static_cast<double>(k + 1) + cumulative + static_cast<double>(n - k - 1) * s[k];
    if (risk < best_risk) {
      best_risk = risk;
      best_t = t;
    }
  }
  return best_t;
}

namespace {

// The thresholds of denoise() applied to the coefficients in place (wavelet.hpp's order), with
// σ, λ and the counts recorded in r; n is the series' length.
void threshold(const CoefficientViews& c, std::size_t n, const DenoiseOptions& options,
               DenoiseResult& r) {
  const int p = static_cast<int>(c.size()) - 1;
  r.noise_sigma = median_abs(c[static_cast<std::size_t>(p)]) / 0.6745;
  const double universal = r.noise_sigma * std::sqrt(2.0 * std::log(static_cast<double>(n)));
  for (int j = 1; j <= p; ++j) {
    const std::span<double> d = c[static_cast<std::size_t>(p - j + 1)];
    double lambda = universal;
    if (options.rule == ThresholdRule::Sure) {
      if (r.noise_sigma > 0.0) {
        std::vector<double> z(d.size());
        for (std::size_t i = 0; i < d.size(); ++i) z[i] = d[i] / r.noise_sigma;
        const double t = sure_threshold(z);
        // λ_j is the chosen coefficient's own |d_i| (σ·|d_i/σ| may differ from it in the last
        // bit), so that coefficient sits exactly on the threshold and the tie rule decides:
        // hard keeps |d| ≥ λ (pywt.threshold), soft shrinks it to 0.
        lambda = 0.0;
        if (t > 0.0) {
          double best = HUGE_VAL;
          for (double v : d)
            if (std::abs(std::abs(v) - r.noise_sigma * t) < best) {
              best = std::abs(std::abs(v) - r.noise_sigma * t);
              lambda = std::abs(v);
            }
        }
      } else {
        lambda = 0.0;
      }
    }
    std::size_t zeroed = 0;
    if (options.kind == ThresholdKind::Soft) {
      for (double& v : d) {
        const double m = std::abs(v) - lambda;
        v = m <= 0.0 ? 0.0 : std::copysign(m, v);
        zeroed += v == 0.0;
      }
    } else {
      for (double& v : d) {
        v = std::abs(v) < lambda ? 0.0 : v;
        zeroed += v == 0.0;
      }
    }
    r.thresholds.push_back(lambda);
    r.zeroed.push_back(zeroed);
    r.coefficients.push_back(d.size());
  }
}

}  // namespace

int default_level(std::size_t n, const Wavelet& wavelet) {
  return std::max(1, std::min(kDefaultLevel, max_level(n, wavelet)));
}

DenoiseResult denoise(std::span<const double> x, const DenoiseOptions& options) {
  const Wavelet wavelet(options.wavelet_order);
  DenoiseResult r;
  r.options = options;
  // wavedec, the thresholds in place, waverec: one scratch array for all levels.
  r.values = edit_coefficients(x, wavelet, options.mode, options.level,
                               [&](const CoefficientViews& c) { threshold(c, x.size(), options, r); });
  return r;
}

SeriesDenoising denoise_series(const PositionSeries& s, DenoiseOptions options) {
  if (options.level == 0) options.level = default_level(s.current_A.size(), Wavelet(options.wavelet_order));
  validate_series(s, "series");
  SeriesDenoising r;  // not an aggregate initialiser: GCC 12 destroys a partly built one twice on a throw
  r.denoising = denoise(s.current_A, options);
  r.series = {s.time_s, r.denoising.values};
  return r;
}

}  // namespace meridian::maglev
