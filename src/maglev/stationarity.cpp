#include "meridian/maglev/stationarity.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "meridian/maglev/series_statistics.hpp"

namespace meridian::maglev {

std::vector<std::size_t> StationarityResult::rejected() const {
  std::vector<std::size_t> r;
  for (std::size_t i = 0; i < segments.size(); ++i)
    if (!segments[i].kept) r.push_back(i);
  return r;
}

StationarityResult test_stationarity(std::span<const double> x, const StationarityOptions& o) {
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(x[i])) throw InputError(fmt::format("sample {} is not a finite number", i));
  if (!(o.alpha > 0.0 && o.alpha < 1.0))
    throw InputError(fmt::format("significance level {} is not in (0, 1)", o.alpha),
                     ErrorContext{{}, std::nullopt, "alpha"});
  const std::size_t L =
      o.segment_length == 0 ? std::max<std::size_t>(64, n / 20) : o.segment_length;
  if (L < 32)
    throw InputError(fmt::format("segment length {} is too short (at least 32 samples)", L),
                     ErrorContext{{}, std::nullopt, "segment_length"});
  if (n < 2 * L)
    throw InputError(fmt::format("{} samples are too few for two segments of {}", n, L),
                     ErrorContext{{}, std::nullopt, "segment_length"});
  const int M = o.autocovariance_lags;
  if (M < 1 || static_cast<std::size_t>(M) >= L / 4)
    throw InputError(
        fmt::format("{} autocovariance lags are not possible with segments of {} (1 … {})", M, L,
                    L / 4 - 1),
        ErrorContext{{}, std::nullopt, "autocovariance_lags"});
  // Lags of the reference autocovariance: enough for the long-run variance, at most L/4.
  const int J = static_cast<int>(std::min<std::size_t>(L / 4, 200));

  StationarityResult r;
  r.segment_length = L;
  std::size_t begin = 0;
  while (begin < n) {
    std::size_t end = std::min(n, begin + L);
    if (n - end < L / 2) end = n;  // a short remainder joins this segment
    SegmentTest s;
    s.begin = begin;
    s.end = end;
    r.segments.push_back(s);
    begin = end;
  }
  const std::size_t S = r.segments.size();
  r.segment_alpha = o.family_wise ? o.alpha / static_cast<double>(S) : o.alpha;
  std::vector<std::vector<double>> acov(S);
  for (std::size_t i = 0; i < S; ++i) {
    auto& s = r.segments[i];
    const auto seg = x.subspan(s.begin, s.end - s.begin);
    double sum = 0.0;
    for (double v : seg) sum += v;
    s.mean = sum / static_cast<double>(seg.size());
    acov[i] = autocovariance(seg, s.mean, J);
  }
  // Robust start: medians over the segments.
  std::vector<double> tmp(S);
  for (std::size_t i = 0; i < S; ++i) tmp[i] = r.segments[i].mean;
  double mu = median(tmp);
  std::vector<double> gamma(static_cast<std::size_t>(J) + 1);
  for (std::size_t k = 0; k < gamma.size(); ++k) {
    for (std::size_t i = 0; i < S; ++i) tmp[i] = acov[i][k];
    gamma[k] = median(tmp);
  }
  std::vector<char> kept(S, 1), previous;
  std::size_t n_kept = n;
  const double chi_dof = static_cast<double>(M + 1);
  for (int pass = 1; pass <= 20; ++pass) {
    r.passes = pass;
    const LongRunVariance lr = long_run_variance(gamma);
    // Bartlett's V_k, with γ_{−j} = γ_j and 0 beyond J.
    auto g = [&](long j) {
      const auto a = static_cast<std::size_t>(std::labs(j));
      return a < gamma.size() ? gamma[a] : 0.0;
    };
    std::vector<double> v(static_cast<std::size_t>(M) + 1);
    for (int k = 0; k <= M; ++k) {
      double s = 0.0;
      for (long j = -J; j <= J; ++j) s += g(j) * g(j) + g(j + k) * g(j - k);
      v[static_cast<std::size_t>(k)] = s;
    }
    for (std::size_t i = 0; i < S; ++i) {
      auto& s = r.segments[i];
      const double m = static_cast<double>(s.end - s.begin);
      const double frac = 1.0 / m + (kept[i] ? -1.0 : 1.0) / static_cast<double>(n_kept);
      const double var = lr.long_run * std::max(frac, 1.0 / m * 1e-3);
      s.z_mean = var > 0.0 ? (s.mean - mu) / std::sqrt(var) : (s.mean == mu ? 0.0 : HUGE_VAL);
      s.p_mean = std::isfinite(s.z_mean) ? adjust::normal_two_sided_probability(s.z_mean) : 0.0;
      double q = 0.0;
      bool finite = true;
      for (int k = 0; k <= M; ++k) {
        const double vk = v[static_cast<std::size_t>(k)] / m;
        const double d = acov[i][static_cast<std::size_t>(k)] - gamma[static_cast<std::size_t>(k)];
        if (vk > 0.0) {
          q += d * d / vk;
        } else if (d != 0.0) {
          finite = false;
        }
      }
      s.q_autocovariance = finite ? q : HUGE_VAL;
      s.p_autocovariance = finite ? adjust::chi_squared_upper_probability(q, chi_dof) : 0.0;
      s.mean_passed = s.p_mean >= r.segment_alpha;
      s.autocovariance_passed = s.p_autocovariance >= r.segment_alpha;
      s.kept = s.mean_passed && s.autocovariance_passed;
    }
    previous = kept;
    for (std::size_t i = 0; i < S; ++i) kept[i] = r.segments[i].kept ? 1 : 0;
    r.long_run_variance = lr.long_run;
    // New reference from the kept segments.
    n_kept = 0;
    double sum = 0.0;
    std::fill(gamma.begin(), gamma.end(), 0.0);
    for (std::size_t i = 0; i < S; ++i) {
      if (!kept[i]) continue;
      const auto& s = r.segments[i];
      const std::size_t m = s.end - s.begin;
      n_kept += m;
      sum += s.mean * static_cast<double>(m);
      for (std::size_t k = 0; k < gamma.size(); ++k)
        gamma[k] += acov[i][k] * static_cast<double>(m);
    }
    if (n_kept == 0)
      throw NumericalError(fmt::format(
          "no stable segment: all {} segments of {} samples fail the stationarity tests at α = {}",
          S, L, o.alpha));
    mu = sum / static_cast<double>(n_kept);
    for (double& gk : gamma) gk /= static_cast<double>(n_kept);
    r.reference_mean = mu;
    r.reference_autocovariance = gamma;
    r.kept_samples = n_kept;
    if (kept == previous) break;
  }
  return r;
}

}  // namespace meridian::maglev
