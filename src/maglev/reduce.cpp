#include "meridian/maglev/reduce.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::maglev {
namespace {

// Step 1 of a position (when processing): the segment tests; the samples of the rejected
// segments leave the mask. The tests' errors name the position ("position1.segment_length").
void select_stable_segments(const ReduceOptions& o, const std::string& name, PositionResult& r,
                            std::vector<std::string>& warnings) {
  try {
    r.stationarity = test_stationarity(r.series.current_A, o.stationarity);
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

// Step 2, one run [i, j) of consecutive kept samples denoised on its own into r.cleaned_A, at the
// level asked or the deepest the run allows (a run too short for level 1 stays raw). The wavelet
// σ of the position is that of its longest denoised run.
void denoise_run(std::size_t i, std::size_t j, const DenoiseOptions& asked, const std::string& name,
                 PositionResult& r, std::size_t& longest, std::vector<std::string>& notes) {
  const std::span<const double> run(r.series.current_A.data() + i, j - i);
  const int level = std::min(asked.level, max_level(run.size(), Wavelet(asked.wavelet_order)));
  r.denoise_levels.push_back(level);
  if (level < 1) return;
  DenoiseOptions d = asked;
  d.level = level;
  const auto den = denoise(run, d);
  std::copy(den.values.begin(), den.values.end(),
            r.cleaned_A.begin() + static_cast<std::ptrdiff_t>(i));
  if (run.size() > longest) {
    longest = run.size();
    r.noise_sigma_A = den.noise_sigma;
  }
  if (level < asked.level)
    notes.push_back(fmt::format("{}: samples {}…{} denoised with level {} (too short for {})", name,
                                i, j - 1, level, asked.level));
}

// The kept samples of a position, raw and cleaned, in order.
struct KeptSamples {
  std::vector<double> raw, cleaned;
};

// Step 2: the runs of consecutive kept samples, each denoised on its own (when processing and
// denoising).
KeptSamples clean_kept_runs(const ReduceOptions& o, const std::string& name, PositionResult& r,
                            std::vector<std::string>& notes) {
  const auto& x = r.series.current_A;
  KeptSamples k;
  k.raw.reserve(x.size());
  k.cleaned.reserve(x.size());
  std::size_t longest = 0;
  for (std::size_t i = 0; i < x.size();) {
    if (!r.kept_mask[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < x.size() && r.kept_mask[j]) ++j;
    k.raw.insert(k.raw.end(), x.begin() + static_cast<std::ptrdiff_t>(i),
                 x.begin() + static_cast<std::ptrdiff_t>(j));
    if (o.process && o.denoise) denoise_run(i, j, o.denoising, name, r, longest, notes);
    k.cleaned.insert(k.cleaned.end(), r.cleaned_A.begin() + static_cast<std::ptrdiff_t>(i),
                     r.cleaned_A.begin() + static_cast<std::ptrdiff_t>(j));
    i = j;
  }
  return k;
}

// Step 3: the means of the kept samples, cleaned, median and Huber.
void kept_statistics(const KeptSamples& k, const ReduceOptions& o, const std::string& name,
                     PositionResult& r, std::vector<std::string>& notes) {
  r.kept_samples = k.raw.size();
  // σ of the kept mean: the same estimator as for all samples (series_statistics.hpp), applied to
  // the kept samples as one series, so the same samples always give the same σ. (A pooled
  // within-segment autocovariance with the segment means removed misses the low-frequency
  // variance that limits a mean: σ 2–3.6× too small for AR(1) φ ≥ 0.95.)
  r.kept = mean_with_autocorrelation(k.raw);
  if (r.kept.lag_limit_reached)
    notes.push_back(
        fmt::format("{}: the series is correlated beyond {} lags; σ of its mean may be optimistic",
                    name, kMaxLongRunLag));
  double sum = 0.0;
  for (double v : k.cleaned) sum += v;
  const double mc = sum / static_cast<double>(k.cleaned.size());
  double var = 0.0;
  for (double v : k.cleaned) var += (v - mc) * (v - mc);
  r.variance_cleaned_A2 = var / static_cast<double>(k.cleaned.size());
  r.cleaned_mean_A = {mc, r.kept.sigma};
  r.median_A = median(k.raw);
  try {
    r.huber_A = huber_mean(k.raw, r.kept.n_eff, o.huber_k);
  } catch (const NumericalError& e) {
    r.huber_failed = e.message();
  }
}

PositionResult process_position(const PositionSeries& s, const ReduceOptions& o,
                                const std::string& name, std::vector<std::string>& notes,
                                std::vector<std::string>& warnings) {
  PositionResult r;
  r.series = s;
  r.samples = s.current_A.size();
  r.raw = mean_with_autocorrelation(s.current_A);
  r.variance_raw_A2 = r.raw.variance;
  r.kept_mask.assign(r.samples, 1);
  r.cleaned_A = s.current_A;
  if (o.process) select_stable_segments(o, name, r, warnings);
  kept_statistics(clean_kept_runs(o, name, r, notes), o, name, r, notes);
  return r;
}

// Median and Huber solutions: secondary, for comparison; a failure there is a warning, not the
// end of the determination.
template <class Solve>
void compare_estimators(const Solve& solve, ReduceResult& r) {
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
}

// σ from a handful of samples (or of effective samples) is itself very uncertain.
void warn_few_samples(ReduceResult& r) {
  for (const auto* p : {&r.position1, &r.position2})
    if (p->kept.n_eff < 30.0)
      r.warnings.push_back(fmt::format(
          "position {}: the σ of its mean rests on {} samples (n_eff {:.1f}): it is itself "
          "uncertain by ±{:.0f} % or more",
          p == &r.position1 ? 1 : 2, p->kept.n, p->kept.n_eff,
          100.0 / std::sqrt(2.0 * std::max(p->kept.n_eff - 1.0, 1.0))));
}

// Spec §3 step 4: the two positions symmetric about the prior bias b₀.
ReduceResult::Symmetry symmetry_check(const Uncertain& b, double alpha, ReduceResult& r) {
  const Uncertain& m1 = r.position1.cleaned_mean_A;
  const Uncertain& m2 = r.position2.cleaned_mean_A;
  const double s = std::sqrt(m1.sigma * m1.sigma + m2.sigma * m2.sigma + 4.0 * b.sigma * b.sigma);
  ReduceResult::Symmetry sym;
  const double d = m1.value + m2.value - 2.0 * b.value;
  sym.z = s > 0.0 ? d / s : (d == 0.0 ? 0.0 : HUGE_VAL);
  sym.p = std::isfinite(sym.z) ? adjust::normal_two_sided_probability(sym.z) : 0.0;
  sym.passed = sym.p >= alpha;
  if (!sym.passed)
    r.warnings.push_back(
        fmt::format("symmetry check failed: the positions are not symmetric about the prior bias "
                    "{:.6g} A (z = {:.2f}); "
                    "one position may still be disturbed or the bias has changed",
                    b.value, sym.z));
  return sym;
}

// A_G = r_T − N_G, then the azimuth chain; its errors name "chain".
gyro::AzimuthChainResult target_azimuth(const ChainSetup& c, double latitude_rad,
                                        const TwoPositionSolution& s) {
  gyro::AzimuthChainInput ci;
  const double ag =
      std::remainder(c.target_reading_rad.value - s.north_rad.value, 2.0 * units::kPi);
  ci.gyro_azimuth_rad = {ag, std::hypot(c.target_reading_rad.sigma, s.north_rad.sigma)};
  ci.instrument_constant_rad = c.instrument_constant_rad;
  ci.latitude_rad = latitude_rad;
  ci.eta_rad = c.eta_rad;
  ci.convergence_rad = c.convergence_rad;
  try {
    return gyro::azimuth_chain(ci);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "chain");
    throw;
  }
}

}  // namespace

ReduceResult process(const ReduceInput& in, Progress* progress) {
  validate_series(in.position1, "position1");
  validate_series(in.position2, "position2");
  ReduceResult r;
  r.source = in.source;
  r.scale_A_s_per_rad = in.scale_A_s_per_rad;
  r.latitude_rad = in.latitude_rad;
  r.options = in.options;
  r.amplitude_A = directive_amplitude(in.scale_A_s_per_rad, in.latitude_rad);
  report_progress(progress, 0, 2, "positions");
  r.position1 = process_position(in.position1, in.options, "position1", r.notes, r.warnings);
  report_progress(progress, 1, 2, "positions");
  r.position2 = process_position(in.position2, in.options, "position2", r.notes, r.warnings);
  report_progress(progress, 2, 2, "positions");
  const auto solve = [&](Uncertain m1, Uncertain m2) {
    return two_position(m1, m2, in.scale_A_s_per_rad, in.latitude_rad, in.circle_reading1_rad);
  };
  r.plain = solve({r.position1.raw.mean, r.position1.raw.sigma},
                  {r.position2.raw.mean, r.position2.raw.sigma});
  r.processed = solve(r.position1.cleaned_mean_A, r.position2.cleaned_mean_A);
  compare_estimators(solve, r);
  if (!in.options.process) r.notes.push_back("not processed: plain means of all samples");
  warn_few_samples(r);
  if (in.options.prior_bias_A)
    r.symmetry = symmetry_check(*in.options.prior_bias_A, in.options.stationarity.alpha, r);
  if (in.chain) r.chain = target_azimuth(*in.chain, in.latitude_rad, r.processed);
  return r;
}

}  // namespace meridian::maglev
