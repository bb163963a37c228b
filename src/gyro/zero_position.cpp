#include "meridian/gyro/zero_position.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gyro {

ZeroPositionEstimate estimate_zero_position(const ZeroPositionRun& run, ReversalMethod method,
                                            double sigma_reading_div) {
  ZeroPositionEstimate est;
  try {
    est.fit = estimate_centre(method, run.reversals_div, sigma_reading_div);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "reversals_div");
    throw;
  }
  const auto& r = run.reversals_div;
  double swing = 0;
  for (std::size_t i = 1; i < r.size(); ++i) swing += std::fabs(r[i] - r[i - 1]);
  est.amplitude_div = 0.5 * swing / static_cast<double>(r.size() - 1);
  if (!run.times_s.empty()) {
    if (run.times_s.size() != r.size())
      throw InputError(fmt::format("{} times for {} reversal readings", run.times_s.size(), r.size()),
                       {"", std::nullopt, "times_s"});
    for (std::size_t i = 0; i < run.times_s.size(); ++i) {
      if (!std::isfinite(run.times_s[i]))
        throw InputError(fmt::format("time {} is not a finite number", i + 1), {"", std::nullopt, "times_s"});
      if (i > 0 && run.times_s[i] <= run.times_s[i - 1])
        throw InputError(fmt::format("times must increase (t{} = {} <= t{} = {})", i + 1,
                                     run.times_s[i], i, run.times_s[i - 1]),
                         {"", std::nullopt, "times_s"});
    }
    // Least-squares slope of t_i against i: half period. σ from the scatter
    // when there are more than two times.
    const std::size_t n = run.times_s.size();
    double mi = 0, mt = 0;
    for (std::size_t i = 0; i < n; ++i) {
      mi += static_cast<double>(i);
      mt += run.times_s[i];
    }
    mi /= static_cast<double>(n);
    mt /= static_cast<double>(n);
    double sii = 0, sit = 0;
    for (std::size_t i = 0; i < n; ++i) {
      sii += (static_cast<double>(i) - mi) * (static_cast<double>(i) - mi);
      sit += (static_cast<double>(i) - mi) * (run.times_s[i] - mt);
    }
    const double half = sit / sii;
    double sigma = std::numeric_limits<double>::quiet_NaN();
    if (n > 2) {
      double ss = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double v = mt + half * (static_cast<double>(i) - mi) - run.times_s[i];
        ss += v * v;
      }
      sigma = std::sqrt(ss / static_cast<double>(n - 2)) / std::sqrt(sii);
    }
    est.free_period_s = Uncertain{2.0 * half, 2.0 * sigma};
  }
  return est;
}

ZeroPositionSummary summarise_zero_position(const std::optional<ZeroPositionRun>& before,
                                            const std::optional<ZeroPositionRun>& after,
                                            ReversalMethod method, double sigma_reading_div,
                                            double tolerance_div) {
  if (!before && !after) throw InputError("no zero-position run given", {"", std::nullopt, "zero_position"});
  ZeroPositionSummary s;
  s.tolerance_div = tolerance_div;
  auto run = [&](const ZeroPositionRun& r, const char* field) {
    try {
      return estimate_zero_position(r, method, sigma_reading_div);
    } catch (Error& e) {
      e.add_context("", std::nullopt, field);
      throw;
    }
  };
  if (before) s.before = run(*before, "before");
  if (after) s.after = run(*after, "after");
  for (const auto& [est, name] : {std::pair{&s.before, "before"}, std::pair{&s.after, "after"}})
    if (*est)
      if (const std::string w = reading_sigma_warning((*est)->fit, 1.0, " div", 3); !w.empty())
        s.warnings.push_back(fmt::format("zero position {} the run: {}", name, w));
  if (s.before && s.after) {
    const Uncertain b = s.before->fit.centre, a = s.after->fit.centre;
    s.difference_div = a.value - b.value;
    double sigma_mean = 0.5 * std::hypot(a.sigma, b.sigma);
    const double half_diff = 0.5 * std::fabs(*s.difference_div);
    if (!(sigma_mean >= half_diff)) sigma_mean = half_diff;  // also replaces NaN
    s.mean_div = {0.5 * (a.value + b.value), sigma_mean};
    s.within_tolerance = std::fabs(*s.difference_div) <= tolerance_div;
    if (!s.within_tolerance)
      s.warnings.push_back(fmt::format(
          "zero position changed by {:.2f} div between before and after (tolerance {:.2f} div)",
          *s.difference_div, tolerance_div));
  } else {
    s.mean_div = s.before ? s.before->fit.centre : s.after->fit.centre;
    s.warnings.push_back("zero position observed only " + std::string(s.before ? "before" : "after") +
                         " the run: its stability is not checked");
  }
  return s;
}

}  // namespace meridian::gyro
