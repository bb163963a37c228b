#include "meridian/gyro/determination.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/plausibility.hpp"

namespace meridian::gyro {
namespace {

MethodResult run_nontracking(NonTrackingMethod m, const DeterminationInput& in,
                             const Instrument& inst, const ZeroPosition& zero,
                             const ReduceOptions& options) {
  MethodResult r;
  r.method = m;
  if (m == NonTrackingMethod::LeastSquares) {
    r.fit = fit_nontracking(in.nontracking, inst, options.unified_fit);
    r.beta = r.fit->as_beta_result();
  } else {
    r.beta = reduce_nontracking(m, in.nontracking, inst);
  }
  if (r.beta->transit_delta_n_rad && inst.transit_factor_rad_per_div_s)
    r.north = north_from_delta(in.clamp_reading_rad, *r.beta->transit_delta_n_rad, inst, zero);
  else
    r.north = north_from_nontracking(in.clamp_reading_rad, r.beta->beta_div, inst, zero);
  r.approximation_error_rad =
      (1.0 + inst.torsion_ratio.value) * inst.scale_value_rad * r.beta->approximation_error_div;
  // The small-angle error matters only against this run's own σ(N_G).
  if (std::string w = small_angle_warning(*r.beta, r.approximation_error_rad, r.north.sigma_rad);
      !w.empty())
    r.beta->warnings.push_back(std::move(w));
  return r;
}

MethodResult run_tracking(ReversalMethod m, const DeterminationInput& in, const Instrument& inst,
                          const ZeroPosition& zero) {
  MethodResult r;
  r.method = m;
  TrackingResult t = reduce_tracking(m, in.tracking, inst, zero);
  r.reversal = t.fit;
  r.north = t.north;
  return r;
}

// A graduation outside the range of the observed reversal readings cannot
// have been crossed: catch it before a fit absorbs it into a wrong amplitude.
// The margin allows for reading noise and slow damping between a crossing
// and the reversals.
void check_levels_reached(const NonTrackingObservations& o) {
  if (o.reversals_div.size() < 2) return;
  const auto [lo, hi] = std::minmax_element(o.reversals_div.begin(), o.reversals_div.end());
  const double margin = std::max(3.0 * o.sigma_reading_div, 0.02 * 0.5 * (*hi - *lo));
  for (std::size_t i = 0; i < o.crossings.size(); ++i) {
    const double a = o.crossings[i].level_div;
    if (a < *lo - margin || a > *hi + margin)
      throw InputError(fmt::format("level {} div lies beyond the reversal readings ({} ... {} div): "
                                   "the light mark never reaches it",
                                   a, *lo, *hi),
                       {"", std::nullopt, fmt::format("crossings[{}].level_div", i)});
  }
}

// The requested method as the mode's own kind of method.
template <class M>
M requested_method(const DeterminationInput& in) {
  if (const M* m = std::get_if<M>(&*in.method)) return *m;
  throw InputError(fmt::format("method \"{}\" is not a {} method", to_string(*in.method), to_string(in.mode)),
                   {"", std::nullopt, "method"});
}

// The target rounds reduced; a target reading given as well must agree.
TargetDirection reduce_target(const DeterminationInput& in) {
  TargetDirection t = reduce_target_rounds(in.target_rounds, in.target_round_sigma_rad);
  if (in.target_reading_rad) {
    const double d = wrap_signed_rad(in.target_reading_rad->value - t.reading_rad.value);
    if (std::fabs(d) > 0.5 * units::kArcsecond)
      throw InputError(fmt::format("target_reading differs by {:+.1f}\" from the mean of the target rounds",
                                   units::rad_to_arcsec(d)),
                       {"", std::nullopt, "target_reading"});
  }
  return t;
}

// Rounds that disagree, or a 2C that jumps between rounds, point at a face
// reading booked wrong (the mean still moves by half of it). Meridian's
// plausibility limits: rounds within max(10", 3·σ·√2), 2C within 20".
std::optional<std::string> target_rounds_warning(const TargetDirection& t, double sigma_round_rad) {
  if (t.round_rad.size() < 2) return std::nullopt;
  const RoundsAgreement a = rounds_agreement(t, sigma_round_rad);
  if (a.agree) return std::nullopt;
  return fmt::format("the target rounds disagree: directions spread by {:.1f}\" (limit {:.1f}\"), 2C varies by "
                     "{:.1f}\" (limit 20\"): a face reading booked wrong?",
                     units::rad_to_arcsec(t.spread_rad), units::rad_to_arcsec(a.spread_limit_rad),
                     units::rad_to_arcsec(a.two_c_variation_rad));
}

}  // namespace

std::string to_string(Mode m) { return m == Mode::Tracking ? "tracking" : "non-tracking"; }

std::string to_string(const Method& m) {
  return std::visit([](auto x) { return to_string(x); }, m);
}

Method method_from_string(Mode mode, const std::string& name) {
  if (mode == Mode::NonTracking) return nontracking_method_from_string(name);
  return reversal_method_from_string(name);
}

std::string method_request_name(const std::optional<Method>& requested) {
  return requested ? to_string(*requested) : std::string("all");
}

namespace {

// The zero position α_p to apply: from the motor-off runs when given (their summary and warnings
// go into `out`), else the one given directly.
ZeroPosition zero_position_of(const DeterminationInput& in, const Instrument& inst, const ReduceOptions& options,
                              DeterminationResult& out) {
  if (!in.zero_before && !in.zero_after) return in.zero_position;
  try {
    out.zero_position = summarise_zero_position(in.zero_before, in.zero_after, options.zero_position_method,
                                                inst.sigma_reading_div, options.zero_position_tolerance_div);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "zero_position");
    throw;
  }
  for (const auto& w : out.zero_position->warnings) out.warnings.push_back(w);
  return out.zero_position->mean_div;
}

// Every applicable non-tracking method (a method that fails numerically is a warning); the
// primary result is the first of lsq, direct, timed-amplitude-1/-2, transit, time-difference.
void all_nontracking(const DeterminationInput& in, const Instrument& inst, const ZeroPosition& zero,
                     const ReduceOptions& options, DeterminationResult& out) {
  std::vector<NonTrackingMethod> methods = applicable_methods(in.nontracking);
  if (methods.empty())
    throw InputError("no non-tracking method is applicable to the observations given "
                     "(need crossings with times and, for most methods, reversals or period_s)");
  for (NonTrackingMethod m : methods) {
    try {
      out.all.push_back(run_nontracking(m, in, inst, zero, options));
    } catch (const NumericalError& e) {
      out.warnings.push_back(fmt::format("{}: {}", to_string(m), e.what()));
    }
  }
  if (out.all.empty()) throw NumericalError("every applicable method failed: " + out.warnings.back());
  static constexpr NonTrackingMethod order[] = {
      NonTrackingMethod::LeastSquares,    NonTrackingMethod::Direct,  NonTrackingMethod::TimedAmplitude1,
      NonTrackingMethod::TimedAmplitude2, NonTrackingMethod::Transit, NonTrackingMethod::TimeDifference};
  for (NonTrackingMethod preferred : order)
    for (const auto& r : out.all)
      if (r.method == Method{preferred}) {
        out.primary = r;
        return;
      }
  out.primary = out.all.front();
}

void reduce_nontracking_run(const DeterminationInput& in, const Instrument& inst, const ZeroPosition& zero,
                            const ReduceOptions& options, DeterminationResult& out) {
  check_plausible(in.nontracking);
  check_levels_reached(in.nontracking);
  if (!in.method)
    all_nontracking(in, inst, zero, options, out);
  else
    out.primary = run_nontracking(requested_method<NonTrackingMethod>(in), in, inst, zero, options);
  if (out.primary.beta)
    for (const auto& w : out.primary.beta->warnings) out.warnings.push_back(w);
}

void reduce_tracking_run(const DeterminationInput& in, const Instrument& inst, const ZeroPosition& zero,
                         DeterminationResult& out) {
  if (!in.method) {
    const int n = static_cast<int>(in.tracking.reversals_rad.size());
    for (ReversalMethod m : {ReversalMethod::TwoPoint, ReversalMethod::Schuler, ReversalMethod::LinearLsq,
                             ReversalMethod::NonlinearLsq}) {
      if (m != ReversalMethod::TwoPoint && n < 3) continue;
      try {
        out.all.push_back(run_tracking(m, in, inst, zero));
      } catch (const NumericalError& e) {
        out.warnings.push_back(fmt::format("{}: {}", to_string(m), e.what()));
      }
    }
    // None: surface the real input problem (too few or bad readings).
    if (out.all.empty()) out.all.push_back(run_tracking(ReversalMethod::TwoPoint, in, inst, zero));
    out.primary = out.all.back();
  } else {
    out.primary = run_tracking(requested_method<ReversalMethod>(in), in, inst, zero);
  }
  if (const std::string w = reading_sigma_warning(*out.primary.reversal, units::kArcsecond, "\"", 1); !w.empty())
    out.warnings.push_back(in.label.empty() ? "tracking run: " + w
                                            : fmt::format("tracking run \"{}\": {}", in.label, w));
}

}  // namespace

DeterminationResult reduce_determination(const DeterminationInput& in, const Instrument& inst,
                                         const ReduceOptions& options) {
  DeterminationResult out;
  out.label = in.label;
  out.mode = in.mode;
  out.method = in.method;
  const ZeroPosition zero = zero_position_of(in, inst, options, out);
  out.zero_position_used = zero;
  if (!in.target_rounds.empty()) {
    out.target = reduce_target(in);
    if (auto w = target_rounds_warning(*out.target, in.target_round_sigma_rad)) out.warnings.push_back(*w);
  }
  if (in.mode == Mode::NonTracking)
    reduce_nontracking_run(in, inst, zero, options, out);
  else
    reduce_tracking_run(in, inst, zero, out);
  return out;
}

Uncertain gyro_azimuth(const DeterminationResult& r, const DeterminationInput& in) {
  if (!r.target && !in.target_reading_rad)
    throw InputError("no target reading for this determination", {"", std::nullopt, "target_reading"});
  const Uncertain t = r.target ? r.target->reading_rad : *in.target_reading_rad;
  return {wrap_positive_rad(t.value - r.primary.north.north_rad), std::hypot(t.sigma, r.primary.north.sigma_rad)};
}

bool same_observations(const DeterminationInput& a, const DeterminationInput& b) {
  if (a.mode != b.mode) return false;
  if (a.mode == Mode::Tracking) return a.tracking.reversals_rad == b.tracking.reversals_rad;
  const auto& x = a.nontracking;
  const auto& y = b.nontracking;
  if (x.crossings.size() != y.crossings.size() || x.reversals_div != y.reversals_div) return false;
  for (std::size_t i = 0; i < x.crossings.size(); ++i)
    if (x.crossings[i].level_div != y.crossings[i].level_div || x.crossings[i].times_s != y.crossings[i].times_s)
      return false;
  return !x.crossings.empty() || !x.reversals_div.empty();
}

}  // namespace meridian::gyro
