#include "meridian/nav/navigation.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "methods.hpp"

namespace meridian::nav {

double TrackPoint::sigma_x_m() const { return std::sqrt(covariance(0, 0)); }
double TrackPoint::sigma_y_m() const { return std::sqrt(covariance(1, 1)); }

const MethodResult* Result::find(Method m) const {
  for (const auto& r : methods)
    if (r.method == m) return &r;
  return nullptr;
}

void validate(const Options& o) {
  const auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0))
      throw InputError(fmt::format("must be finite and > 0, got {}", v),
                       {{}, {}, std::string("options.") + name});
  };
  const auto non_negative = [](double v, const char* name) {
    if (!(std::isfinite(v) && v >= 0.0))
      throw InputError(fmt::format("must be finite and >= 0, got {}", v),
                       {{}, {}, std::string("options.") + name});
  };
  positive(o.threshold_m, "threshold_m");
  if (!(o.alpha > 0.0 && o.alpha < 1.0))
    throw InputError(fmt::format("must be in (0, 1), got {}", o.alpha), {{}, {}, "options.alpha"});
  positive(o.segment_s, "segment_s");
  non_negative(o.bias_start_s, "bias_start_s");
  non_negative(o.backward_window_s, "backward_window_s");
  positive(o.fix_tolerance_m, "fix_tolerance_m");
  non_negative(o.max_reduction_s, "max_reduction_s");
  non_negative(o.sequential_sigma_velocity_m_s, "sequential_sigma_velocity_m_s");
  positive(o.max_dr_gap_s, "max_dr_gap_s");
  positive(o.bias_sigma_m_s, "bias_sigma_m_s");
  non_negative(o.bias_random_walk_m_s_per_sqrt_s, "bias_random_walk_m_s_per_sqrt_s");
  positive(o.bias_correlation_time_s, "bias_correlation_time_s");
  positive(o.statistics_bin_s, "statistics_bin_s");
  positive(o.warn_gap_s, "warn_gap_s");
}

namespace {

using detail::Prepared;

MethodResult dead_reckoning(const Prepared& p) {
  MethodResult r;
  r.method = Method::DeadReckoning;
  r.track.reserve(p.epochs);
  Eigen::Matrix2d cov = p.initial_cov;
  for (std::size_t k = 0; k < p.epochs; ++k) {
    cov += p.q_incr[k];
    TrackPoint t;
    t.time_s = p.t[k];
    t.x_north_m = p.dr[k](0);
    t.y_east_m = p.dr[k](1);
    t.covariance = cov;
    r.track.push_back(t);
  }
  return r;
}

std::optional<ErrorStatistics> error_statistics(const Prepared& p, const MethodResult& m) {
  const double bin = p.input->options.statistics_bin_s;
  const auto bins = static_cast<std::size_t>(std::floor((p.t.back() - p.t.front()) / bin)) + 1;
  std::vector<double> sum(bins, 0.0);
  std::vector<std::size_t> count(bins, 0);
  ErrorStatistics s;
  s.bin_s = bin;
  double total = 0.0;
  double nees = 0.0;
  for (std::size_t k = 0; k < p.epochs; ++k) {
    if (!p.truth[k]) continue;
    const TrackPoint& t = m.track[k];
    const Eigen::Vector2d d = Eigen::Vector2d(t.x_north_m, t.y_east_m) - *p.truth[k];
    const double e2 = d.squaredNorm();
    total += e2;
    s.max_error_m = std::max(s.max_error_m, std::sqrt(e2));
    nees += d.dot(t.covariance.ldlt().solve(d));
    ++s.epochs;
    const auto b = std::min(bins - 1, static_cast<std::size_t>((p.t[k] - p.t.front()) / bin));
    sum[b] += e2;
    ++count[b];
  }
  if (s.epochs == 0) return std::nullopt;
  s.rms_m = std::sqrt(total / static_cast<double>(s.epochs));
  s.mean_nees = nees / static_cast<double>(s.epochs);
  s.per_minute_rms_m.resize(bins);
  for (std::size_t b = 0; b < bins; ++b)
    s.per_minute_rms_m[b] = count[b] ? std::sqrt(sum[b] / static_cast<double>(count[b]))
                                     : std::numeric_limits<double>::quiet_NaN();
  return s;
}

void warn_gaps(const Prepared& p, const MethodResult& m, std::vector<std::string>& warnings) {
  double last = p.t.front();
  bool any = false;
  const auto check = [&](double until) {
    if (until - last > p.input->options.warn_gap_s)
      warnings.push_back(fmt::format(
          "no observation used by {} from {:.1f} s to {:.1f} s ({:.0f} s of dead reckoning only)",
          to_string(m.method), last, until, until - last));
  };
  for (const TrackPoint& t : m.track) {
    if (t.flags & (kUsedLop | kUsedFix)) {
      check(t.time_s);
      last = t.time_s;
      any = true;
    }
  }
  check(p.t.back());
  (void)any;
}

// The sequential family on N states, the EKF on NE.
template <int N, int NE>
void run_methods(const Prepared& p, const detail::Screening& sc, Result& res,
                 std::vector<detail::Monitor>& monitors, Progress* progress) {
  using detail::BiasMethod;
  const auto slot = [&](Method m) -> detail::Monitor& { return monitors[static_cast<std::size_t>(m)]; };
  {
    detail::ForwardRun<N> no_bias =
        detail::run_sequential<N>(p, Method::SequentialNoBias, BiasMethod::None, sc, res.rejected);
    slot(Method::SequentialNoBias) = std::move(no_bias.monitor);
    res.methods.push_back(std::move(no_bias.result));
  }
  detail::ForwardRun<N> bias_i =
      detail::run_sequential<N>(p, Method::SequentialBiasI, BiasMethod::I, sc, res.rejected);
  res.methods.push_back(bias_i.result);
  {
    detail::ForwardRun<N> bias_ii =
        detail::run_sequential<N>(p, Method::SequentialBiasII, BiasMethod::II, sc, res.rejected);
    slot(Method::SequentialBiasII) = std::move(bias_ii.monitor);
    res.methods.push_back(std::move(bias_ii.result));
  }
  res.methods.push_back(detail::run_backward<N>(p, bias_i));
  if (!p.fixes.empty()) res.methods.push_back(detail::run_fix_closure<N>(p, bias_i));
  slot(Method::SequentialBiasI) = std::move(bias_i.monitor);
  for (MethodResult& m : detail::run_ekf_rts<NE>(p, sc, res.rejected, progress, slot(Method::Ekf)))
    res.methods.push_back(std::move(m));
}

}  // namespace

Result process(const Input& input, Progress* progress) {
  const Prepared p = detail::prepare(input);
  const Options& o = input.options;
  Result res;
  res.epochs = p.epochs;
  res.lops_used = p.lops.size();
  res.fixes_used = p.fixes.size();
  res.skipped = p.skipped;
  res.notes = p.notes;
  res.warnings = p.warnings;

  detail::Screening sc;
  sc.rejection = o.rejection;
  sc.threshold_m = o.threshold_m;
  sc.w_critical = adjust::normal_two_sided_critical(o.alpha);
  sc.fix_chi2_limit = adjust::chi_squared_upper_quantile(o.alpha, 2.0);
  sc.fix_tolerance_m = o.fix_tolerance_m;

  res.methods.push_back(dead_reckoning(p));
  report_progress(progress, 0, 2 * p.epochs, "sequential");
  std::vector<detail::Monitor> monitors(kAllMethods.size());
  if (p.n_params == 0)
    run_methods<2, 4>(p, sc, res, monitors, progress);
  else
    run_methods<Eigen::Dynamic, Eigen::Dynamic>(p, sc, res, monitors, progress);

  for (MethodResult& m : res.methods) {
    m.errors = error_statistics(p, m);
    if (m.method == Method::SequentialBiasI || m.method == Method::Ekf) warn_gaps(p, m, res.warnings);
  }
  detail::check_consistency(p, sc, monitors, res);
  res.notes.push_back(fmt::format(
      "sequential methods: gross LOP errors rejected by {}; the EKF uses the w-test at α = {:g} "
      "(|w| > {:.2f}); a fix more than {:g} m or χ²(2) > {:.2f} from the track is flagged",
      o.rejection == Rejection::Threshold ? fmt::format("|misclosure| > {:g} m", o.threshold_m)
                                          : fmt::format("the w-test at α = {:g}", o.alpha),
      o.alpha, sc.w_critical, o.fix_tolerance_m, sc.fix_chi2_limit));
  res.notes.push_back(fmt::format(
      "method II segments of {:g} s; backward window {:g} s; EKF bias model {} (prior σ {:g} m/s)",
      o.segment_s, o.backward_window_s,
      o.bias_model == BiasModel::RandomWalk
          ? fmt::format("random walk, {:g} m/s/√s", o.bias_random_walk_m_s_per_sqrt_s)
          : fmt::format("Gauss–Markov, τ = {:g} s, σ = {:g} m/s", o.bias_correlation_time_s,
                        o.bias_sigma_m_s),
      o.bias_sigma_m_s));
  if (!p.fixes.empty())
    res.notes.push_back(
        "fix-closure: the σ shown are those of sequential-bias-I (the linear distribution of "
        "a closure has no rigorous covariance)");
  // What each method's σ means (docs/navigation.md, "Consistency of the σ").
  res.notes.push_back(
      "σ of dead-reckoning: the white noise of the DR samples only, not a speed or heading "
      "bias: its real error can be many times larger");
  res.notes.push_back(fmt::format(
      "σ of sequential-no-bias, -bias-I, -bias-II, backward and fix-closure: not rigorous: they "
      "carry the DR with sequential_sigma_velocity_m_s = {:g} m/s per velocity component, a "
      "setting that stands in for the bias they do not model, and scale with it (simulated "
      "scenario A: mean NEES 4 to 7 instead of 2)",
      o.sequential_sigma_velocity_m_s));
  res.notes.push_back(
      "σ of ekf and rts: rigorous under their model (DR white noise, the bias model above, the "
      "stated σ of the LOPs and fixes); consistent in simulation when that model holds");
  if (progress) progress->finish();
  return res;
}

}  // namespace meridian::nav
