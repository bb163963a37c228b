#include "meridian/maglev/reduce.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "context.hpp"
#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::maglev {
namespace {
using detail::at;

PositionResult process_position(const PositionSeries& s, const ReduceOptions& o,
                                std::vector<std::string>& notes, std::vector<std::string>& warnings,
                                const std::string& name) {
  PositionResult r;
  const auto& x = s.current_A;
  r.samples = x.size();
  r.raw = mean_with_autocorrelation(x);
  r.variance_raw_A2 = r.raw.variance;
  r.kept_mask.assign(x.size(), 1);
  r.cleaned_A = x;
  if (o.process) {
    try {
      r.stationarity = test_stationarity(x, o.stationarity);
    } catch (Error& e) {
      e.add_context("", std::nullopt, name);
      throw;
    }
    // The segment tests treat a segment as many correlation times long; when it is not, they
    // are approximate (the segment statistics are far from normal) and lose power.
    const double tau = r.stationarity->correlation_time_samples;
    const auto L = static_cast<double>(r.stationarity->segment_length);
    if (tau > 0.1 * L)
      warnings.push_back(fmt::format(
          "{}: the noise is correlated over about {:.0f} samples, comparable to the segments of {}: "
          "the segment tests are approximate; consider a longer --segment or --no-process",
          name, tau, r.stationarity->segment_length));
    for (const auto& seg : r.stationarity->segments)
      if (!seg.kept)
        std::fill(r.kept_mask.begin() + static_cast<std::ptrdiff_t>(seg.begin),
                  r.kept_mask.begin() + static_cast<std::ptrdiff_t>(seg.end), 0);
  }
  std::vector<double> kept_raw, kept_clean;
  kept_raw.reserve(x.size());
  kept_clean.reserve(x.size());
  // Runs of consecutive kept samples, each denoised on its own.
  std::size_t longest = 0;
  for (std::size_t i = 0; i < x.size();) {
    if (!r.kept_mask[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < x.size() && r.kept_mask[j]) ++j;
    const std::span<const double> run(x.data() + i, j - i);
    kept_raw.insert(kept_raw.end(), run.begin(), run.end());
    if (o.process && o.denoise) {
      const Wavelet w(o.denoising.wavelet_order);
      const int level = std::min(o.denoising.level, max_level(run.size(), w));
      r.denoise_levels.push_back(level);
      if (level >= 1) {
        DenoiseOptions d = o.denoising;
        d.level = level;
        const auto den = denoise(run, d);
        std::copy(den.values.begin(), den.values.end(),
                  r.cleaned_A.begin() + static_cast<std::ptrdiff_t>(i));
        if (run.size() > longest) {
          longest = run.size();
          r.noise_sigma_A = den.noise_sigma;
        }
        if (level < o.denoising.level)
          notes.push_back(fmt::format("{}: samples {}…{} denoised with level {} (too short for {})",
                                      name, i, j - 1, level, o.denoising.level));
      }
    }
    kept_clean.insert(kept_clean.end(), r.cleaned_A.begin() + static_cast<std::ptrdiff_t>(i),
                      r.cleaned_A.begin() + static_cast<std::ptrdiff_t>(j));
    i = j;
  }
  r.kept_samples = kept_raw.size();
  // σ of the kept mean: the same estimator as for all samples (series_statistics.hpp), applied to
  // the kept samples as one series, so the same samples always give the same σ. (A pooled
  // within-segment autocovariance with the segment means removed misses the low-frequency
  // variance that limits a mean: σ 2–3.6× too small for AR(1) φ ≥ 0.95.)
  r.kept = mean_with_autocorrelation(kept_raw);
  if (r.kept.lag_limit_reached)
    notes.push_back(
        fmt::format("{}: the series is correlated beyond {} lags; σ of its mean may be optimistic",
                    name, kMaxLongRunLag));
  double sum = 0.0;
  for (double v : kept_clean) sum += v;
  const double mc = sum / static_cast<double>(kept_clean.size());
  double var = 0.0;
  for (double v : kept_clean) var += (v - mc) * (v - mc);
  r.variance_cleaned_A2 = var / static_cast<double>(kept_clean.size());
  r.cleaned_mean_A = {mc, r.kept.sigma};
  r.median_A = median(kept_raw);
  try {
    r.huber_A = huber_mean(kept_raw, r.kept.n_eff, o.huber_k);
  } catch (const NumericalError& e) {
    r.huber_failed = e.message();
  }
  return r;
}
}  // namespace

void validate_series(const PositionSeries& s, const std::string& field) {
  if (s.current_A.empty()) throw InputError("the series is empty", at(field + ".current_A"));
  if (s.time_s.size() != s.current_A.size())
    throw InputError(fmt::format("{} times for {} currents", s.time_s.size(), s.current_A.size()),
                     at(field + ".time_s"));
  for (std::size_t i = 0; i < s.current_A.size(); ++i) {
    if (!std::isfinite(s.current_A[i]))
      throw InputError(fmt::format("sample {} is not a finite number", i),
                       at(fmt::format("{}.current_A[{}]", field, i)));
    if (!std::isfinite(s.time_s[i]))
      throw InputError(fmt::format("time {} is not a finite number", i),
                       at(fmt::format("{}.time_s[{}]", field, i)));
    if (i > 0 && !(s.time_s[i] > s.time_s[i - 1]))
      throw InputError(
          fmt::format("time does not increase ({} s after {} s)", s.time_s[i], s.time_s[i - 1]),
          at(fmt::format("{}.time_s[{}]", field, i)));
  }
  const auto [lo, hi] = std::minmax_element(s.current_A.begin(), s.current_A.end());
  if (*lo == *hi)
    throw InputError(
        fmt::format("no variation in the series (every sample is {} A): a mean with a σ needs "
                    "noise (a noise-free simulation cannot be reduced)",
                    *lo),
        at(field + ".current_A"));
}

ReduceResult process(const ReduceInput& in, Progress* progress) {
  validate_series(in.position1, "position1");
  validate_series(in.position2, "position2");
  ReduceResult r;
  r.amplitude_A = directive_amplitude(in.scale_A_s_per_rad, in.latitude_rad);
  report_progress(progress, 0, 2, "positions");
  r.position1 = process_position(in.position1, in.options, r.notes, r.warnings, "position1");
  report_progress(progress, 1, 2, "positions");
  r.position2 = process_position(in.position2, in.options, r.notes, r.warnings, "position2");
  report_progress(progress, 2, 2, "positions");
  const auto solve = [&](Uncertain m1, Uncertain m2) {
    return two_position(m1, m2, in.scale_A_s_per_rad, in.latitude_rad, in.circle_reading1_rad);
  };
  r.plain = solve({r.position1.raw.mean, r.position1.raw.sigma},
                  {r.position2.raw.mean, r.position2.raw.sigma});
  r.processed = solve(r.position1.cleaned_mean_A, r.position2.cleaned_mean_A);
  // Median and Huber: secondary, for comparison; a failure there does not stop the determination.
  const double eff = std::sqrt(units::kPi / 2.0);
  try {
    r.median = solve({r.position1.median_A, eff * r.position1.kept.sigma},
                     {r.position2.median_A, eff * r.position2.kept.sigma});
  } catch (const NumericalError& e) {
    r.warnings.push_back(fmt::format("median solution: {}", e.message()));
  }
  try {
    if (!r.position1.huber_failed.empty() || !r.position2.huber_failed.empty())
      throw NumericalError(r.position1.huber_failed + r.position2.huber_failed);
    r.huber = solve(r.position1.huber_A, r.position2.huber_A);
  } catch (const NumericalError& e) {
    r.warnings.push_back(fmt::format("Huber solution: {}", e.message()));
  }
  if (!in.options.process) r.notes.push_back("not processed: plain means of all samples");
  // σ from a handful of samples (or of effective samples) is itself very uncertain.
  for (const auto* p : {&r.position1, &r.position2})
    if (p->kept.n_eff < 30.0)
      r.warnings.push_back(fmt::format(
          "position {}: the σ of its mean rests on {} samples (n_eff {:.1f}): it is itself "
          "uncertain by ±{:.0f} % or more",
          p == &r.position1 ? 1 : 2, p->kept.n, p->kept.n_eff,
          100.0 / std::sqrt(2.0 * std::max(p->kept.n_eff - 1.0, 1.0))));
  if (in.options.prior_bias_A) {
    const auto& b = *in.options.prior_bias_A;
    const double s = std::sqrt(r.position1.cleaned_mean_A.sigma * r.position1.cleaned_mean_A.sigma +
                               r.position2.cleaned_mean_A.sigma * r.position2.cleaned_mean_A.sigma +
                               4.0 * b.sigma * b.sigma);
    ReduceResult::Symmetry sym;
    const double d =
        r.position1.cleaned_mean_A.value + r.position2.cleaned_mean_A.value - 2.0 * b.value;
    sym.z = s > 0.0 ? d / s : (d == 0.0 ? 0.0 : HUGE_VAL);
    sym.p = std::isfinite(sym.z) ? adjust::normal_two_sided_probability(sym.z) : 0.0;
    sym.passed = sym.p >= in.options.stationarity.alpha;
    r.symmetry = sym;
    if (!sym.passed)
      r.warnings.push_back(
          fmt::format("symmetry check failed: the positions are not symmetric about the prior bias "
                      "{:.6g} A (z = {:.2f}); "
                      "one position may still be disturbed or the bias has changed",
                      b.value, sym.z));
  }
  if (in.chain) {
    const auto& c = *in.chain;
    gyro::AzimuthChainInput ci;
    const double ag =
        std::remainder(c.target_reading_rad.value - r.processed.north_rad.value, 2.0 * units::kPi);
    ci.gyro_azimuth_rad = {ag, std::hypot(c.target_reading_rad.sigma, r.processed.north_rad.sigma)};
    ci.instrument_constant_rad = c.instrument_constant_rad;
    ci.latitude_rad = in.latitude_rad;
    ci.eta_rad = c.eta_rad;
    ci.convergence_rad = c.convergence_rad;
    try {
      r.chain = gyro::azimuth_chain(ci);
    } catch (Error& e) {
      e.add_context("", std::nullopt, "chain");
      throw;
    }
  }
  return r;
}

}  // namespace meridian::maglev
