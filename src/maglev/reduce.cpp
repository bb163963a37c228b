#include "meridian/maglev/reduce.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::maglev {
namespace {

// Step 1 of a position (when processing): the segment tests on the series with the drift taken
// out (`x`), so a drift is not mistaken for non-stationarity; the samples of the rejected
// segments leave the mask. The tests' errors name the position ("position1.segment_length").
void select_stable_segments(const ReduceOptions& o, const std::string& name,
                            std::span<const double> x, PositionResult& r,
                            std::vector<std::string>& warnings) {
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
  std::fill(r.kept_mask.begin(), r.kept_mask.end(), 1);
  for (const auto& seg : r.stationarity->segments)
    if (!seg.kept)
      std::fill(r.kept_mask.begin() + static_cast<std::ptrdiff_t>(seg.begin),
                r.kept_mask.begin() + static_cast<std::ptrdiff_t>(seg.end), 0);
}

// Step 2, one run [i, j) of consecutive kept samples of `x` (drift removed) denoised on its own
// into r.cleaned_A (the drift added back), at the level asked or the deepest the run allows (a run
// too short for level 1 stays raw). The wavelet σ of the position is that of its longest run.
void denoise_run(std::size_t i, std::size_t j, std::span<const double> x,
                 std::span<const double> drift, const DenoiseOptions& asked,
                 const std::string& name, PositionResult& r, std::size_t& longest,
                 std::vector<std::string>& notes) {
  const std::span<const double> run(x.data() + i, j - i);
  const int level = std::min(asked.level, max_level(run.size(), Wavelet(asked.wavelet_order)));
  r.denoise_levels.push_back(level);
  if (level < 1) return;
  DenoiseOptions d = asked;
  d.level = level;
  const auto den = denoise(run, d);
  for (std::size_t k = 0; k < den.values.size() && i + k < j; ++k)
    r.cleaned_A[i + k] = den.values[k] + drift[i + k];
  if (run.size() > longest) {
    longest = run.size();
    r.noise_sigma_A = den.noise_sigma;
  }
  if (level < asked.level)
    notes.push_back(fmt::format("{}: samples {}…{} denoised with level {} (too short for {})", name,
                                i, j - 1, level, asked.level));
}

// The kept samples of a position, raw and cleaned, drift removed, in order.
struct KeptSamples {
  std::vector<double> raw, cleaned;
};

// Step 2: the runs of consecutive kept samples, each denoised on its own (when processing and
// denoising).
KeptSamples clean_kept_runs(const ReduceOptions& o, const std::string& name,
                            std::span<const double> x, std::span<const double> drift,
                            PositionResult& r, std::vector<std::string>& notes) {
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
    if (o.process && o.denoise) denoise_run(i, j, x, drift, o.denoising, name, r, longest, notes);
    for (std::size_t m = i; m < j; ++m) k.cleaned.push_back(r.cleaned_A[m] - drift[m]);
    i = j;
  }
  return k;
}

// Step 3: the means of the kept samples (drift removed), cleaned, median and Huber.
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

PositionResult start_position(const PositionSeries& s) {
  PositionResult r;
  r.series = s;
  r.samples = s.current_A.size();
  r.raw = mean_with_autocorrelation(s.current_A);
  r.variance_raw_A2 = r.raw.variance;
  r.kept_mask.assign(r.samples, 1);
  r.cleaned_A = s.current_A;
  return r;
}

// The drift of `fit` at every sample of `s` (zeros without a fit).
std::vector<double> drift_values(const PositionSeries& s, const LevelDriftFit* fit) {
  std::vector<double> d(s.time_s.size(), 0.0);
  if (fit)
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = fit->drift_at(s.time_s[i]);
  return d;
}

std::vector<double> minus(std::span<const double> a, std::span<const double> b) {
  std::vector<double> c(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) c[i] = a[i] - b[i];
  return c;
}

// The positions and the drift of one determination while they are found together.
struct Determination {
  PositionResult p1, p2;
  std::vector<TimeBlock> blocks;
  int order = 0;                       // drift order fitted (0: none)
  std::optional<LevelDriftFit> fit;    // on the kept raw samples
  std::vector<double> d1, d2;          // drift at every sample
};

LevelDriftFit fit_on(const Determination& d, std::span<const double> v1,
                     std::span<const double> v2, int order) {
  LevelDriftData data{&d.p1.series, &d.p2.series, v1, v2, d.p1.kept_mask, d.p2.kept_mask,
                      &d.blocks};
  return fit_levels_and_drift(data, order);
}

// The settling blocks: the blocks on the common clock, or each position's series as one block.
std::vector<TimeBlock> settling_blocks(const Determination& d) {
  if (!d.blocks.empty()) return d.blocks;
  const auto whole = [](int p, const PositionSeries& s) {
    return TimeBlock{p, 0, s.time_s.size(), s.time_s.front(), s.time_s.back()};
  };
  return {whole(1, d.p1.series), whole(2, d.p2.series)};
}

// The level of position p (fit or mean of its kept detrended samples), its σ and σ²_LR.
struct LevelNoise {
  double level = 0.0, sigma = 0.0, lrv = 0.0;
};
LevelNoise level_noise(const Determination& d, int p, std::span<const double> x) {
  LevelNoise l;
  if (d.fit) {
    l.level = d.fit->beta(p - 1);
    l.sigma = std::sqrt(d.fit->covariance(p - 1, p - 1));
    l.lrv = d.fit->long_run_variance_A2;
    return l;
  }
  const auto& m = p == 1 ? d.p1.kept_mask : d.p2.kept_mask;
  std::vector<double> k;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (m[i]) k.push_back(x[i]);
  if (k.size() < 2) return l;
  const MeanEstimate e = mean_with_autocorrelation(k);
  l.level = e.mean;
  l.sigma = e.sigma;
  l.lrv = e.variance * static_cast<double>(e.n) / e.n_eff;
  return l;
}

// The settling cut of every block (given, or detected on the residuals of the current fit) and
// the masks of the samples cut (1: cut).
std::vector<SettlingCut> settling_cuts(const ReduceOptions& o, const Determination& d,
                                       std::span<const double> x1, std::span<const double> x2,
                                       std::vector<char>& cut1, std::vector<char>& cut2) {
  std::vector<SettlingCut> cuts;
  cut1.assign(x1.size(), 0);
  cut2.assign(x2.size(), 0);
  if (!o.settling.cut_s && !o.settling.detect) return cuts;
  const auto blocks = settling_blocks(d);
  const LevelNoise ln[2] = {level_noise(d, 1, x1), level_noise(d, 2, x2)};
  std::size_t G = 1;
  for (const auto& b : blocks) G = std::max(G, settling_time_constants(b.end_s - b.begin_s, b.end - b.begin).size());
  const double alpha = o.stationarity.alpha / static_cast<double>(G * blocks.size());
  for (const TimeBlock& b : blocks) {
    const PositionSeries& s = b.position == 1 ? d.p1.series : d.p2.series;
    const auto x = b.position == 1 ? x1 : x2;
    std::optional<SettlingCut> c;
    if (o.settling.cut_s) {
      c = SettlingCut{b.position, b.begin_s, *o.settling.cut_s};
    } else {
      const LevelNoise& l = ln[b.position - 1];
      std::vector<double> r(x.begin() + static_cast<std::ptrdiff_t>(b.begin),
                            x.begin() + static_cast<std::ptrdiff_t>(b.end));
      for (double& v : r) v -= l.level;
      // σ²_LR of the block's second half: a transient left in the residuals (every block's in
      // the first pass) would inflate the residuals' σ²_LR and hide itself.
      const std::span<const double> tail = std::span<const double>(r).subspan(r.size() / 2);
      double lrv = l.lrv;
      if (tail.size() >= 16) {
        const MeanEstimate e = mean_with_autocorrelation(tail);
        if (e.n_eff > 0.0) lrv = e.variance * static_cast<double>(e.n) / e.n_eff;
      }
      c = detect_settling(std::span<const double>(s.time_s).subspan(b.begin, b.end - b.begin), r,
                          lrv, l.sigma, alpha);
    }
    if (!c) continue;
    c->position = b.position;
    auto& cut = b.position == 1 ? cut1 : cut2;
    for (std::size_t i = b.begin; i < b.end && s.time_s[i] < b.begin_s + c->cut_s; ++i) {
      cut[i] = 1;
      ++c->samples_cut;
    }
    cuts.push_back(*c);
  }
  return cuts;
}

// Step 1 with the drift and the settling: the drift fitted on the samples kept so far (all at
// first), the settling cuts found on its residuals, the segment tests run on the series without
// the drift, the cut samples removed, until the kept sets repeat (at most 4 passes).
void select_with_drift(const ReduceOptions& o, Determination& d, std::vector<SettlingCut>& cuts,
                       std::vector<std::string>& warnings) {
  std::vector<std::string> w;
  for (int pass = 0; pass < 4; ++pass) {
    if (d.order > 0)
      d.fit = fit_on(d, d.p1.series.current_A, d.p2.series.current_A, d.order);
    d.d1 = drift_values(d.p1.series, d.fit ? &*d.fit : nullptr);
    d.d2 = drift_values(d.p2.series, d.fit ? &*d.fit : nullptr);
    if (!o.process) return;
    const auto m1 = d.p1.kept_mask, m2 = d.p2.kept_mask;
    const auto x1 = minus(d.p1.series.current_A, d.d1), x2 = minus(d.p2.series.current_A, d.d2);
    std::vector<char> c1, c2;
    cuts = settling_cuts(o, d, x1, x2, c1, c2);
    w.clear();
    select_stable_segments(o, "position1", x1, d.p1, w);
    select_stable_segments(o, "position2", x2, d.p2, w);
    for (std::size_t i = 0; i < c1.size(); ++i) d.p1.kept_mask[i] &= static_cast<char>(!c1[i]);
    for (std::size_t i = 0; i < c2.size(); ++i) d.p2.kept_mask[i] &= static_cast<char>(!c2[i]);
    if (m1 == d.p1.kept_mask && m2 == d.p2.kept_mask) break;
  }
  warnings.insert(warnings.end(), w.begin(), w.end());
  if (d.order > 0) {  // on the last pass's masks
    d.fit = fit_on(d, d.p1.series.current_A, d.p2.series.current_A, d.order);
    d.d1 = drift_values(d.p1.series, &*d.fit);
    d.d2 = drift_values(d.p2.series, &*d.fit);
  }
}

// What the settling cuts say (notes; a cut limited to half a block is a warning).
void explain_settling(const std::vector<SettlingCut>& cuts, ReduceResult& r) {
  for (const SettlingCut& c : cuts) {
    const std::string what =
        c.detected ? fmt::format("detected (exponential {:+.3e} A, τ {:.0f} s, z {:.1f})",
                                 c.amplitude_A, c.tau_s, c.z)
                   : std::string("given");
    r.notes.push_back(fmt::format("position {} block at {:.3f} s: settling cut {:.1f} s ({} "
                                  "samples), {}",
                                  c.position, c.block_begin_s, c.cut_s, c.samples_cut, what));
    if (c.limited)
      r.warnings.push_back(fmt::format(
          "position {} block at {:.3f} s: the settling transient lasts beyond half the block; the "
          "cut stops there and what is left of it may bias α1",
          c.position, c.block_begin_s));
  }
}

// Median and Huber solutions: secondary, for comparison; a failure there is a warning, not the
// end of the determination.
// With a drift fitted they are of the samples with the drift taken out, their σ multiplied by
// the drift's σ inflation (an approximation: the drift's own uncertainty).
template <class Solve>
void compare_estimators(const Solve& solve, double inflation, ReduceResult& r) {
  const double eff = std::sqrt(units::kPi / 2.0) * inflation;
  try {
    r.median = solve({r.position1.median_A, eff * r.position1.kept.sigma},
                     {r.position2.median_A, eff * r.position2.kept.sigma});
  } catch (const NumericalError& e) {
    r.warnings.push_back(fmt::format("median solution: {}", e.message()));
  }
  try {
    if (!r.position1.huber_failed.empty() || !r.position2.huber_failed.empty())
      throw NumericalError(r.position1.huber_failed + r.position2.huber_failed);
    r.huber = solve({r.position1.huber_A.value, inflation * r.position1.huber_A.sigma},
                    {r.position2.huber_A.value, inflation * r.position2.huber_A.sigma});
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

// The same series for both positions (the same file given twice) gives α1 = 0 exactly and
// means nothing: refused.
void refuse_identical_positions(const PositionSeries& p1, const PositionSeries& p2) {
  if (p1.current_A == p2.current_A)
    throw InputError(
        fmt::format("position 2 is the same series as position 1 ({} identical currents): the "
                    "same file given for both positions?",
                    p1.current_A.size()),
        ErrorContext{{}, std::nullopt, "position2.current_A"});
}

// The currents' scale against A = K·ω_e·cos φ: the sample-to-sample noise of a position
// (1.4826·median|Δi|/√2, robust to bursts and drift) as an angle, σ_i / A. A real instrument's
// samples scatter by arcseconds to arcminutes; below kMinSampleNoise the currents are almost
// certainly 10³ too small for K (values in A under an [mA] header): a loud warning.
constexpr double kMinSampleNoise_rad = 0.5 * units::kArcsecond;

double sample_noise_A(const std::vector<double>& x) {
  if (x.size() < 3) return NAN;
  std::vector<double> d(x.size() - 1);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) d[i] = std::abs(x[i + 1] - x[i]);
  auto mid = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), mid, d.end());
  return 1.4826 * *mid / std::sqrt(2.0);
}

void check_current_scale(const ReduceInput& in, ReduceResult& r) {
  const double n1 = sample_noise_A(in.position1.current_A);
  const double n2 = sample_noise_A(in.position2.current_A);
  if (!std::isfinite(n1) || !std::isfinite(n2) || !(r.amplitude_A.value > 0.0)) return;
  r.sample_noise_rad = std::max(n1, n2) / r.amplitude_A.value;
  if (r.sample_noise_rad < kMinSampleNoise_rad) {
    r.unit_slip_suspected = true;
    r.warnings.push_back(fmt::format(
        "UNIT SLIP? the currents scatter by only {:.3g} A from sample to sample, {:.3g}″ of "
        "K·ω·cos φ = {:.6g} A (a real instrument: arcseconds or more): the currents look 1000× "
        "too small for K = {:.6g} A·s/rad (values in A under an [mA] header?); α1 and its σ "
        "are then wrong",
        std::max(n1, n2), units::rad_to_arcsec(r.sample_noise_rad), r.amplitude_A.value,
        r.scale_A_s_per_rad.value));
  }
}

// Spec §3 step 4: the two positions symmetric about the prior bias b₀.
ReduceResult::Symmetry symmetry_check(const Uncertain& b, double alpha, ReduceResult& r) {
  const Uncertain& m1 = r.position1.cleaned_mean_A;
  const Uncertain& m2 = r.position2.cleaned_mean_A;
  // σ(Ī_1 + Ī_2) = 2σ(b̂), which holds the levels' covariance of a drift fit.
  const double s = 2.0 * std::hypot(r.processed.bias_A.sigma, b.sigma);
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

// The drift order to fit: the one asked when the positions share one clock, else 0 (warned).
int usable_drift_order(const ReduceInput& in, const std::vector<TimeBlock>& blocks,
                       std::vector<std::string>& warnings) {
  const int order = drift_order(in.options.drift);
  if (order > 0 && blocks.empty())
    warnings.push_back(
        "the positions' times interleave or coincide, so they are not on one clock: a drift "
        "across the positions cannot be modelled and would bias α1 unseen (give both positions "
        "on the instrument's clock, or --drift none to accept it)");
  return blocks.empty() ? 0 : order;
}

// The drift's rate, its test, its separation from the azimuth and what it changed in α_1.
DriftResult summarize_drift(const Determination& d, const LevelDriftFit& fit, double alpha,
                            double alpha_levels_only_rad, const ReduceResult& r) {
  DriftResult dr;
  dr.model = d.order == 1 ? DriftModel::linear : DriftModel::quadratic;
  dr.sequence = block_sequence(d.blocks);
  dr.blocks = d.blocks;
  dr.reference_time_s = fit.reference_time_s;
  dr.rate_A_per_s = fit.rate_at(fit.reference_time_s);
  if (fit.order == 2) {
    const double h2 = fit.half_span_s * fit.half_span_s;
    dr.curvature_A_per_s2 = Uncertain{2.0 * fit.beta(3) / h2, 2.0 * std::sqrt(fit.covariance(3, 3)) / h2};
  }
  dr.z = dr.rate_A_per_s.sigma > 0.0 ? dr.rate_A_per_s.value / dr.rate_A_per_s.sigma : 0.0;
  dr.p = adjust::normal_two_sided_probability(dr.z);
  dr.significant = dr.p < alpha;
  dr.sigma_inflation = std::sqrt(std::max(1.0, fit.vif_difference));
  dr.separable = dr.sigma_inflation <= 3.0;
  dr.alpha1_correction_rad = r.processed.alpha1_rad.value - alpha_levels_only_rad;
  dr.long_run_variance_A2 = fit.long_run_variance_A2;
  dr.n_eff = fit.n_eff;
  return dr;
}

// What the drift result says in notes and warnings.
void explain_drift(const DriftResult& dr, ReduceResult& r) {
  const double as = units::kArcsecond;
  r.notes.push_back(fmt::format(
      "drift ({}) on the common clock, blocks {}: {:+.3e} ± {:.2e} A/s (z {:.1f}{}); modelled "
      "jointly with the levels, it moved α1 by {:+.2f}\" and multiplied σ(α1) by {:.2f}",
      to_string(dr.model), dr.sequence, dr.rate_A_per_s.value, dr.rate_A_per_s.sigma, dr.z,
      dr.significant ? ", significant" : ", not significant", dr.alpha1_correction_rad / as,
      dr.sigma_inflation));
  int blocks1 = 0, blocks2 = 0;
  for (const auto& b : dr.blocks) (b.position == 1 ? blocks1 : blocks2) += 1;
  if (blocks1 == 1 && blocks2 == 1)
    r.notes.push_back(
        "one block per position: the drift is told from the azimuth only by the slopes within "
        "the blocks (σ includes it); a 1-2-1 or 1-2-2-1 sequence cancels a linear drift by design");
  if (!dr.separable)
    r.warnings.push_back(fmt::format(
        "the drift cannot be well separated from the azimuth with blocks {}: σ(α1) is inflated "
        "×{:.1f} by the drift's uncertainty (measure a symmetric sequence, 1-2-1 or 1-2-2-1, or "
        "longer blocks)",
        dr.sequence, dr.sigma_inflation));
  if (dr.curvature_check_z && std::abs(*dr.curvature_check_z) > 3.0)
    r.warnings.push_back(fmt::format(
        "the drift is not linear (a quadratic term has z = {:.1f}): the linear model may bias "
        "α1; consider --drift quadratic",
        *dr.curvature_check_z));
}

// The z of a quadratic term fitted beside the linear one (a check of the linear model).
std::optional<double> curvature_check(const Determination& d) {
  try {
    const auto q = fit_on(d, d.p1.series.current_A, d.p2.series.current_A, 2);
    const double s = std::sqrt(q.covariance(3, 3));
    return s > 0.0 ? std::optional<double>(q.beta(3) / s) : std::nullopt;
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace

ReduceResult process(const ReduceInput& in, Progress* progress) {
  validate_series(in.position1, "position1");
  validate_series(in.position2, "position2");
  refuse_identical_positions(in.position1, in.position2);
  ReduceResult r;
  r.source = in.source;
  r.scale_A_s_per_rad = in.scale_A_s_per_rad;
  r.latitude_rad = in.latitude_rad;
  r.options = in.options;
  r.amplitude_A = directive_amplitude(in.scale_A_s_per_rad, in.latitude_rad);
  report_progress(progress, 0, 2, "positions");
  Determination d;
  d.p1 = start_position(in.position1);
  d.p2 = start_position(in.position2);
  d.blocks = time_blocks(in.position1, in.position2);
  d.order = usable_drift_order(in, d.blocks, r.warnings);
  try {
    select_with_drift(in.options, d, r.settling, r.warnings);
  } catch (const NumericalError& e) {
    if (e.context().field != "drift") throw;
    r.warnings.push_back(fmt::format("{}: the drift is not modelled and σ does not include it",
                                     e.message()));
    d.order = 0;
    d.fit.reset();
    d.p1.kept_mask.assign(d.p1.samples, 1);
    d.p2.kept_mask.assign(d.p2.samples, 1);
    select_with_drift(in.options, d, r.settling, r.warnings);
  }
  explain_settling(r.settling, r);
  report_progress(progress, 1, 2, "positions");
  kept_statistics(clean_kept_runs(in.options, "position1", minus(in.position1.current_A, d.d1),
                                  d.d1, d.p1, r.notes),
                  in.options, "position1", d.p1, r.notes);
  kept_statistics(clean_kept_runs(in.options, "position2", minus(in.position2.current_A, d.d2),
                                  d.d2, d.p2, r.notes),
                  in.options, "position2", d.p2, r.notes);
  report_progress(progress, 2, 2, "positions");
  const auto solve = [&](Uncertain m1, Uncertain m2) {
    return two_position(m1, m2, in.scale_A_s_per_rad, in.latitude_rad, in.circle_reading1_rad);
  };
  r.plain = solve({d.p1.raw.mean, d.p1.raw.sigma}, {d.p2.raw.mean, d.p2.raw.sigma});
  double inflation = 1.0;
  if (d.order > 0) {
    // The levels from the cleaned kept samples, their covariance from the raw kept residuals.
    const LevelDriftFit c = fit_on(d, d.p1.cleaned_A, d.p2.cleaned_A, d.order);
    const LevelDriftFit& f = *d.fit;
    d.p1.cleaned_mean_A = {c.beta(0), std::sqrt(f.covariance(0, 0))};
    d.p2.cleaned_mean_A = {c.beta(1), std::sqrt(f.covariance(1, 1))};
    r.processed = two_position(d.p1.cleaned_mean_A, d.p2.cleaned_mean_A, f.covariance(0, 1),
                               in.scale_A_s_per_rad, in.latitude_rad, in.circle_reading1_rad);
    const LevelDriftFit c0 = fit_on(d, d.p1.cleaned_A, d.p2.cleaned_A, 0);
    const double ratio0 =
        std::clamp((c0.beta(0) - c0.beta(1)) / (2.0 * r.amplitude_A.value), -1.0, 1.0);
    DriftResult dr = summarize_drift(d, f, in.options.stationarity.alpha, std::asin(ratio0), r);
    if (d.order == 1) dr.curvature_check_z = curvature_check(d);
    r.position1 = std::move(d.p1);
    r.position2 = std::move(d.p2);
    inflation = dr.sigma_inflation;
    explain_drift(dr, r);
    r.drift = std::move(dr);
  } else {
    r.position1 = std::move(d.p1);
    r.position2 = std::move(d.p2);
    r.processed = solve(r.position1.cleaned_mean_A, r.position2.cleaned_mean_A);
  }
  compare_estimators(solve, inflation, r);
  if (!in.options.process) r.notes.push_back(
        "not processed: every sample kept, no segment tests, no denoising");
  warn_few_samples(r);
  check_current_scale(in, r);
  if (in.options.prior_bias_A)
    r.symmetry = symmetry_check(*in.options.prior_bias_A, in.options.stationarity.alpha, r);
  if (in.chain) r.chain = target_azimuth(*in.chain, in.latitude_rad, r.processed);
  return r;
}

}  // namespace meridian::maglev
