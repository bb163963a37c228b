#include "meridian/gyro/unified_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "format.hpp"
#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {
namespace {

using units::kPi;
using units::kTwoPi;

// Parameter order of the full vector and of the reported covariance.
enum Param : int { kBeta = 0, kAmp = 1, kT0 = 2, kPeriod = 3, kDamping = 4 };

// The asin argument is kept inside (−1, 1) while iterating so that a trial
// step past a level's reach gives a large but finite misfit, which the
// Levenberg–Marquardt step control rejects.
constexpr double kMaxSine = 1.0 - 1e-12;

using detail::num;

// One crossing time with its phase branch: east θ = asin(q) + 2πm, west
// θ = π − asin(q) + 2πm, q = (a − β)/B, t = t0 + T_B·θ/(2π).
struct TimeObs {
  std::size_t group = 0;
  std::size_t index = 0;
  double level = 0.0;
  int direction = 1;
  double time = 0.0;
  long cycle = 0;
};

// One reversal reading a_r = β + side·B·e^{−k(t_r − t0)}.
struct ReadingObs {
  std::size_t index = 0;
  double reading = 0.0;
  int side = 1;
  double time = 0.0;  // only used with damping (then reversal_times_s is required)
};

using Params = std::array<double, 5>;

double branch_phase(double level, int direction, const Params& p) {
  const double q = std::clamp((level - p[kBeta]) / p[kAmp], -kMaxSine, kMaxSine);
  const double psi = std::asin(q);
  return direction > 0 ? psi : kPi - psi;
}

// Predicted passage time; with damping, Newton on
// g(t) = β + B·e^{−k(t−t0)}·sin(2π(t−t0)/T) − a from the undamped time.
double predict_time(const TimeObs& o, const Params& p, bool damped) {
  double t = p[kT0] + p[kPeriod] * (branch_phase(o.level, o.direction, p) +
                                    kTwoPi * static_cast<double>(o.cycle)) /
                          kTwoPi;
  if (!damped || p[kDamping] == 0.0) return t;
  const double w = kTwoPi / p[kPeriod];
  for (int it = 0; it < 50; ++it) {
    const double s = t - p[kT0];
    const double e = std::exp(-p[kDamping] * s);
    const double g = p[kBeta] + p[kAmp] * e * std::sin(w * s) - o.level;
    const double gt = p[kAmp] * e * (w * std::cos(w * s) - p[kDamping] * std::sin(w * s));
    if (gt == 0.0) break;
    const double step = g / gt;
    t -= step;
    if (std::abs(step) < 1e-13 * std::max(1.0, std::abs(t))) break;
  }
  return t;
}

// ∂t/∂(β, B, t0, T, k) by implicit differentiation of g(t; p) = 0.
std::array<double, 5> time_partials(double t, const Params& p) {
  const double s = t - p[kT0];
  const double w = kTwoPi / p[kPeriod];
  const double k = p[kDamping];
  const double e = std::exp(-k * s);
  const double phi = w * s;
  const double b = p[kAmp];
  double gt = b * e * (w * std::cos(phi) - k * std::sin(phi));
  if (std::abs(gt) < 1e-300) gt = std::copysign(1e-300, gt);
  return {-1.0 / gt, -e * std::sin(phi) / gt, 1.0, b * e * std::cos(phi) * phi / (p[kPeriod] * gt),
          s * b * e * std::sin(phi) / gt};
}

struct Problem {
  std::vector<TimeObs> times;
  std::vector<ReadingObs> readings;
  bool period_obs = false;
  double period_value = 0.0;
  double period_sigma = 0.0;
  bool damped = false;
  std::vector<int> free;  // full index of each estimated parameter
  Params fixed{};         // values of the parameters held fixed

  int n() const {
    return static_cast<int>(times.size() + readings.size()) + (period_obs ? 1 : 0);
  }
  Params expand(const Eigen::VectorXd& x) const {
    Params p = fixed;
    for (std::size_t j = 0; j < free.size(); ++j) p[free[j]] = x(static_cast<Eigen::Index>(j));
    return p;
  }
  Eigen::VectorXd predict(const Eigen::VectorXd& x) const {
    const Params p = expand(x);
    Eigen::VectorXd f(n());
    Eigen::Index r = 0;
    for (const TimeObs& o : times) f(r++) = predict_time(o, p, damped);
    for (const ReadingObs& o : readings)
      f(r++) = p[kBeta] + o.side * p[kAmp] *
                              (damped ? std::exp(-p[kDamping] * (o.time - p[kT0])) : 1.0);
    if (period_obs) f(r++) = p[kPeriod];
    return f;
  }
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& x) const {
    const Params p = expand(x);
    Eigen::MatrixXd full = Eigen::MatrixXd::Zero(n(), 5);
    Eigen::Index r = 0;
    for (const TimeObs& o : times) {
      const auto d = time_partials(predict_time(o, p, damped), p);
      for (int j = 0; j < 5; ++j) full(r, j) = d[static_cast<std::size_t>(j)];
      ++r;
    }
    for (const ReadingObs& o : readings) {
      const double dtr = o.time - p[kT0];
      const double e = damped ? std::exp(-p[kDamping] * dtr) : 1.0;
      full(r, kBeta) = 1.0;
      full(r, kAmp) = o.side * e;
      if (damped) {
        full(r, kT0) = o.side * p[kAmp] * e * p[kDamping];
        full(r, kDamping) = -o.side * p[kAmp] * e * dtr;
      }
      ++r;
    }
    if (period_obs) full(r, kPeriod) = 1.0;
    Eigen::MatrixXd J(n(), static_cast<Eigen::Index>(free.size()));
    for (std::size_t j = 0; j < free.size(); ++j)
      J.col(static_cast<Eigen::Index>(j)) = full.col(free[j]);
    return J;
  }
};

std::size_t count_times(const NonTrackingObservations& obs) {
  std::size_t n = 0;
  for (const Crossing& c : obs.crossings) n += c.times_s.size();
  return n;
}

std::optional<double> period_start(const NonTrackingObservations& obs) {
  if (obs.period_s) return obs.period_s->value;
  double sum = 0.0;
  int n = 0;
  for (const Crossing& c : obs.crossings)
    for (std::size_t k = 0; k + 2 < c.times_s.size(); ++k) {
      sum += c.times_s[k + 2] - c.times_s[k];
      ++n;
    }
  if (n > 0) return sum / n;
  const auto& rt = obs.reversal_times_s;
  if (rt.size() >= 2) return 2.0 * (rt.back() - rt.front()) / static_cast<double>(rt.size() - 1);
  return std::nullopt;
}

bool fixed_period(const NonTrackingObservations& obs, const UnifiedFitOptions& options) {
  return options.use_known_period && obs.period_s && obs.period_s->sigma == 0.0;
}

// Reason why the fit cannot run: (field, message), or nothing.
std::optional<std::pair<std::string, std::string>> not_applicable(
    const NonTrackingObservations& obs, const UnifiedFitOptions& options) {
  const std::size_t nt = count_times(obs);
  const std::size_t nr = obs.reversals_div.size();
  if (nt == 0)
    return std::pair{std::string("crossings"), std::string("the unified fit needs crossing times")};
  if (!(obs.sigma_time_s > 0.0))
    return std::pair{std::string("sigma_time_s"), std::string("the unified fit needs σ_t > 0")};
  if (nr > 0 && !(obs.sigma_reading_div > 0.0))
    return std::pair{std::string("sigma_reading_div"),
                     std::string("the unified fit needs σ_a > 0 to weight the reversal readings")};
  // β and B are separated (and start values found, see pair_start) by two of:
  // a level timed twice in succession, a reversal reading (two at most count).
  std::vector<double> levels;
  for (const Crossing& c : obs.crossings)
    if (c.times_s.size() >= 2 &&
        std::find(levels.begin(), levels.end(), c.level_div) == levels.end())
      levels.push_back(c.level_div);
  if (levels.size() + std::min<std::size_t>(nr, 2) < 2)
    return std::pair{std::string("crossings"),
                     std::string("the unified fit needs two consecutive passages of two levels, "
                                 "or of one level and a reversal reading, or two reversal "
                                 "readings, to separate β from B")};
  if (!period_start(obs))
    return std::pair{std::string("period_s"),
                     std::string("the unified fit needs a start value for T_B: give period_s, "
                                 "three passages of one level or two timed reversals")};
  if (options.estimate_damping && nr > 0 && obs.reversal_times_s.empty())
    return std::pair{std::string("reversal_times_s"),
                     std::string("estimating the damping k with reversal readings needs their "
                                 "times")};
  const bool period_obs = options.use_known_period && obs.period_s && obs.period_s->sigma > 0.0;
  const std::size_t u =
      (options.estimate_damping ? 5u : 4u) - (fixed_period(obs, options) ? 1u : 0u);
  const std::size_t n = nt + nr + (period_obs ? 1u : 0u);
  if (n < u)
    return std::pair{std::string("crossings"),
                     fmt::format("the unified fit has {} observations for {} parameters", n, u)};
  return std::nullopt;
}

// Start (β, B) from the general relations a − β = q·B: two consecutive
// passages t1, t2 of a level (t1 in direction d) bracket the turning point on
// side d, so q = d·cos(π(t2 − t1)/T_B); a reversal on side s gives q = s.
std::optional<std::pair<double, double>> pair_start(const NonTrackingObservations& obs,
                                                    double period) {
  std::vector<std::pair<double, double>> eq;  // (q, a)
  std::vector<double> seen;
  for (const Crossing& c : obs.crossings) {
    if (c.times_s.size() < 2 || std::find(seen.begin(), seen.end(), c.level_div) != seen.end())
      continue;
    const double gap = c.times_s[1] - c.times_s[0];
    if (!(gap < period)) continue;
    seen.push_back(c.level_div);
    eq.emplace_back(c.first_direction * std::cos(kPi * gap / period), c.level_div);
  }
  const auto& rv = obs.reversals_div;
  for (std::size_t k = 0; k < rv.size(); ++k) {
    int side = 0;
    if (rv.size() >= 2) {
      side = (rv[0] > rv[1]) == (k % 2 == 0) ? 1 : -1;
    } else if (!seen.empty()) {
      side = rv[0] > seen.front() ? 1 : -1;  // a reversal lies beyond the levels it bounds
    }
    if (side != 0) eq.emplace_back(side, rv[k]);
  }
  if (eq.size() < 2) return std::nullopt;
  // Least squares in (β, B) from β + q·B = a (2×2 normal equations).
  double n = 0.0, sq = 0.0, sqq = 0.0, sa = 0.0, sqa = 0.0;
  for (const auto& [q, a] : eq) {
    n += 1.0;
    sq += q;
    sqq += q * q;
    sa += a;
    sqa += q * a;
  }
  const double det = n * sqq - sq * sq;
  if (!(std::abs(det) > 1e-12 * n * std::max(sqq, 1.0))) return std::nullopt;
  const double amp = (n * sqa - sq * sa) / det;
  const double beta = (sa - sq * amp) / n;
  if (!(amp > 0.0) || !std::isfinite(beta)) return std::nullopt;
  return std::pair{beta, amp};
}

struct Start {
  double beta = 0.0;
  double amp = 0.0;
  double t0 = 0.0;
  double period = 0.0;
  std::string source;
};

// Start values from the first simple method that works (T_B from period_s,
// or the crossing/reversal times when not given).
Start start_values(const NonTrackingObservations& obs, const Instrument& inst) {
  Start s;
  s.period = *period_start(obs);
  NonTrackingObservations o = obs;
  if (!o.period_s) o.period_s = Uncertain{s.period, 0.0};
  bool found = false;
  for (NonTrackingMethod m : {NonTrackingMethod::Direct, NonTrackingMethod::TimedAmplitude2,
                              NonTrackingMethod::TimedAmplitude1, NonTrackingMethod::Transit,
                              NonTrackingMethod::TimeDifference}) {
    try {
      const BetaResult r = reduce_nontracking(m, o, inst);
      if (!r.amplitude_div || !(r.amplitude_div->value > 0.0) || !std::isfinite(r.beta_div.value))
        continue;
      s.beta = r.beta_div.value;
      s.amp = r.amplitude_div->value;
      s.source = to_string(m);
      found = true;
      break;
    } catch (const Error&) {
      // try the next method
    }
  }
  if (!found) {
    if (const auto ps = pair_start(obs, s.period)) {
      s.beta = ps->first;
      s.amp = ps->second;
      s.source = "passage-pair and reversal";
      found = true;
    }
  }
  if (!found)
    throw NumericalError("no start values for the unified fit: none of the simple methods "
                         "applies to these data",
                         ErrorContext{"", std::nullopt, "crossings"});
  // t0 from every passage (mean over the phase-aligned estimates).
  Params p{s.beta, s.amp, 0.0, s.period, 0.0};
  std::optional<double> ref;
  double sum = 0.0;
  int n = 0;
  for (const Crossing& c : obs.crossings)
    for (std::size_t k = 0; k < c.times_s.size(); ++k) {
      const int d = (k % 2 == 0) ? c.first_direction : -c.first_direction;
      double t0 = c.times_s[k] - s.period * branch_phase(c.level_div, d, p) / kTwoPi;
      if (!ref) ref = t0;
      t0 -= s.period * std::round((t0 - *ref) / s.period);
      sum += t0;
      ++n;
    }
  s.t0 = sum / n;
  return s;
}

// Phase branches (cycle numbers) of every passage for the parameters p.
void assign_cycles(std::vector<TimeObs>& times, const Params& p) {
  for (TimeObs& o : times) {
    const double theta = kTwoPi * (o.time - p[kT0]) / p[kPeriod];
    o.cycle = std::lround((theta - branch_phase(o.level, o.direction, p)) / kTwoPi);
  }
}

// ---------------------------------------------------------------------------------------------
// The steps of fit_nontracking.

// The observation equations: every crossing time on its phase branch, the reversal
// readings (sides alternate; the first from its neighbour, or from the start β when there
// is only one), period_s as an observation of T_B when given with σ > 0; the parameters
// (β, B, t0[, T_B][, k]) with the start values in `fixed`.
Problem build_problem(const NonTrackingObservations& obs, const UnifiedFitOptions& options,
                      const Start& st) {
  Problem pb;
  pb.damped = options.estimate_damping;
  for (std::size_t c = 0; c < obs.crossings.size(); ++c) {
    const Crossing& cr = obs.crossings[c];
    for (std::size_t k = 0; k < cr.times_s.size(); ++k)
      pb.times.push_back(TimeObs{c, k, cr.level_div,
                                 (k % 2 == 0) ? cr.first_direction : -cr.first_direction,
                                 cr.times_s[k], 0});
  }
  const auto& rv = obs.reversals_div;
  if (!rv.empty()) {
    int side = rv.size() >= 2 ? (rv[0] > rv[1] ? 1 : -1) : (rv[0] > st.beta ? 1 : -1);
    for (std::size_t k = 0; k < rv.size(); ++k, side = -side)
      pb.readings.push_back(
          ReadingObs{k, rv[k], side, obs.reversal_times_s.empty() ? 0.0 : obs.reversal_times_s[k]});
  }
  pb.period_obs = options.use_known_period && obs.period_s && obs.period_s->sigma > 0.0;
  if (pb.period_obs) {
    pb.period_value = obs.period_s->value;
    pb.period_sigma = obs.period_s->sigma;
  }
  pb.fixed = {st.beta, st.amp, st.t0, st.period, 0.0};
  pb.free = {kBeta, kAmp, kT0};
  if (!fixed_period(obs, options)) pb.free.push_back(kPeriod);
  if (pb.damped) pb.free.push_back(kDamping);
  return pb;
}

// Observed values l and their (diagonal) covariance, in the order of Problem::predict.
struct WeightedObservations {
  Eigen::VectorXd l;
  Eigen::MatrixXd sigma_ll;
};

WeightedObservations weighted_observations(const Problem& pb,
                                           const NonTrackingObservations& obs) {
  const int n = pb.n();
  WeightedObservations w;
  w.l.resize(n);
  Eigen::VectorXd sd(n);
  Eigen::Index r = 0;
  for (const TimeObs& o : pb.times) {
    w.l(r) = o.time;
    sd(r++) = obs.sigma_time_s;
  }
  for (const ReadingObs& o : pb.readings) {
    w.l(r) = o.reading;
    sd(r++) = obs.sigma_reading_div;
  }
  if (pb.period_obs) {
    w.l(r) = pb.period_value;
    sd(r++) = pb.period_sigma;
  }
  w.sigma_ll = sd.array().square().matrix().asDiagonal();
  return w;
}

// Convergence scaled per parameter: times by T_B, k by 1e-3/s, β and B by 1 div.
adjust::NonlinearOptions solver_options(const Problem& pb, double period_start_s) {
  const auto u = static_cast<Eigen::Index>(pb.free.size());
  adjust::NonlinearOptions nl;
  nl.step_tolerance = 1e-10;
  nl.step_scale.resize(u);
  for (Eigen::Index j = 0; j < u; ++j) {
    const int p = pb.free[static_cast<std::size_t>(j)];
    nl.step_scale(j) = (p == kT0 || p == kPeriod) ? period_start_s : (p == kDamping ? 1e-3 : 1.0);
  }
  return nl;
}

struct Solution {
  adjust::NonlinearResult lsq;  // of the last pass
  Params p{};                   // all five parameters at the solution
  int iterations = 0;           // summed over the passes
};

// Solve; re-assign the phase branches from the solution and repeat when any passage changed
// branch (a poor start can put one on the wrong cycle). Updates pb.times' cycles.
Solution solve(Problem& pb, const WeightedObservations& w, const adjust::NonlinearOptions& nl) {
  const auto u = static_cast<Eigen::Index>(pb.free.size());
  Eigen::VectorXd x(u);
  for (Eigen::Index j = 0; j < u; ++j) x(j) = pb.fixed[pb.free[static_cast<std::size_t>(j)]];
  assign_cycles(pb.times, pb.fixed);

  Solution sol;
  for (int pass = 0;; ++pass) {
    const Problem& cp = pb;
    adjust::NonlinearModel model;
    model.predict = [&cp](const Eigen::VectorXd& xx) { return cp.predict(xx); };
    model.jacobian = [&cp](const Eigen::VectorXd& xx) { return cp.jacobian(xx); };
    sol.lsq = adjust::solve_nonlinear(model, w.l, w.sigma_ll, x, nl);
    sol.iterations += sol.lsq.iterations;
    x = sol.lsq.x;
    std::vector<TimeObs> again = pb.times;
    assign_cycles(again, pb.expand(x));
    bool same = true;
    for (std::size_t k = 0; k < again.size(); ++k)
      same = same && again[k].cycle == pb.times[k].cycle;
    if (same) break;
    if (pass >= 4)
      throw NumericalError("the unified fit does not settle on one phase branch per crossing "
                           "(the crossing times may be mislabelled: check first_direction)",
                           ErrorContext{"", std::nullopt, "crossings"});
    pb.times = std::move(again);
  }
  sol.p = pb.expand(x);
  return sol;
}

// B > 0, T_B > 0, and every timed level reached by the fitted oscillation.
void check_solution(const Problem& pb, const Params& p) {
  if (!(p[kAmp] > 0.0) || !(p[kPeriod] > 0.0))
    throw NumericalError(fmt::format("the unified fit converged to B = {} div, T_B = {} s",
                                     num(p[kAmp]), num(p[kPeriod])),
                         ErrorContext{"", std::nullopt, "crossings"});
  for (const TimeObs& o : pb.times) {
    const double t = predict_time(o, p, pb.damped);
    const double reach = p[kAmp] * (pb.damped ? std::exp(-p[kDamping] * (t - p[kT0])) : 1.0);
    if (!(std::abs(o.level - p[kBeta]) < reach))
      throw NumericalError(
          fmt::format("level {} div is not reached by the fitted oscillation (β = {} div, "
                      "B = {} div): |a − β| ≥ B",
                      num(o.level), num(p[kBeta]), num(reach)),
          ErrorContext{"", std::nullopt, fmt::format("crossings[{}].level_div", o.group)});
  }
}

// Parameters with their a-priori σ, the covariance in full parameter order, fit statistics
// and the residuals of every observation.
UnifiedFitResult map_result(const Problem& pb, const Solution& sol) {
  const adjust::NonlinearResult& res = sol.lsq;
  const Params& p = sol.p;
  const auto u = static_cast<Eigen::Index>(pb.free.size());
  UnifiedFitResult out;
  const int full = pb.damped ? 5 : 4;
  out.covariance = Eigen::MatrixXd::Zero(full, full);
  for (Eigen::Index a = 0; a < u; ++a)
    for (Eigen::Index b = 0; b < u; ++b)
      out.covariance(pb.free[static_cast<std::size_t>(a)], pb.free[static_cast<std::size_t>(b)]) =
          res.cofactor(a, b);
  const auto sig = [&](int i) { return std::sqrt(out.covariance(i, i)); };
  out.beta_div = {p[kBeta], sig(kBeta)};
  out.amplitude_div = {p[kAmp], sig(kAmp)};
  out.t0_s = {p[kT0], sig(kT0)};
  out.period_s = {p[kPeriod], sig(kPeriod)};
  out.damping_per_s = pb.damped ? Uncertain{p[kDamping], sig(kDamping)} : Uncertain{0.0, 0.0};
  out.dof = res.dof;
  out.sigma0 = res.dof > 0 ? res.sigma0 : std::numeric_limits<double>::quiet_NaN();
  out.iterations = sol.iterations;

  Eigen::Index r = 0;
  for (const TimeObs& o : pb.times) {
    out.residuals.push_back(UnifiedFitResidual{UnifiedFitResidual::Kind::CrossingTime,
                                               static_cast<int>(o.group), static_cast<int>(o.index),
                                               o.time, res.residuals(r),
                                               res.standardized_residuals(r), res.redundancy(r)});
    ++r;
  }
  for (const ReadingObs& o : pb.readings) {
    out.residuals.push_back(UnifiedFitResidual{UnifiedFitResidual::Kind::ReversalReading, 0,
                                               static_cast<int>(o.index), o.reading,
                                               res.residuals(r), res.standardized_residuals(r),
                                               res.redundancy(r)});
    ++r;
  }
  if (pb.period_obs)
    out.period_residual = UnifiedFitPeriodResidual{pb.period_value, res.residuals(r),
                                                   res.standardized_residuals(r),
                                                   res.redundancy(r)};
  return out;
}

void add_assumptions(UnifiedFitResult& out, const Problem& pb, bool period_fixed,
                     const Start& st) {
  out.assumptions.push_back(pb.damped ? "damping k estimated" : "k = 0 (damping neglected)");
  if (period_fixed)
    out.assumptions.push_back("T_B held fixed at period_s (given with σ = 0)");
  else if (pb.period_obs)
    out.assumptions.push_back("period_s used as an observation of T_B");
  else
    out.assumptions.push_back("T_B estimated from the crossing times");
  if (!pb.readings.empty())
    out.assumptions.push_back(pb.damped ? "reversal readings a_r = β ± B·e^{−k(t_r − t0)} at the "
                                          "given reversal times"
                                        : "reversal readings a_r = β ± B");
  out.assumptions.push_back("σ are a priori (from σ_t, σ_a, σ(T_B)); σ̂0 reported separately");
  out.assumptions.push_back("start values from the " + st.source + " method");
}

// Significance of the global test of the fit.
constexpr double kGlobalTestAlpha = 0.01;
// Critical value of the w-test for a blunder warning; |w| > 3.0 corresponds to α0 ≈ 0.27 %
// two-sided per observation.
constexpr double kBlunderCriticalW = 3.0;

// Warnings from the adjust global test (vᵀPv against χ²) and the w-test of the crossing
// times and reversal readings (the period observation is not tested).
void add_diagnostics(UnifiedFitResult& out, const Problem& pb,
                     const adjust::NonlinearResult& res) {
  if (out.dof <= 0) return;
  const adjust::GlobalTestResult global = adjust::global_test(res, kGlobalTestAlpha);
  if (global.rejected)
    out.warnings.push_back(fmt::format(
        "lsq: σ̂0 = {:.2f} ({} degrees of freedom) fails the χ² test at 99 % (vᵀPv = {:.2f} > "
        "{:.2f}): the observations disagree with the model or their σ are too small",
        out.sigma0, out.dof, global.vtpv, global.critical_value));
  const auto tested = static_cast<Eigen::Index>(pb.times.size() + pb.readings.size());
  const adjust::DataSnoopingResult w =
      adjust::w_test(res.w_statistics.head(tested), kBlunderCriticalW);
  if (!w.rejected.empty()) {
    const auto i = static_cast<std::size_t>(w.largest_index);
    const std::string where =
        i < pb.times.size()
            ? fmt::format("crossings[{}].times_s[{}]", pb.times[i].group, pb.times[i].index)
            : fmt::format("reversals_div[{}]", pb.readings[i - pb.times.size()].index);
    out.warnings.push_back(fmt::format(
        "lsq: the largest standardised residual is {:.2f} at {} (possible blunder)", w.largest_w,
        where));
  }
}

// Every applicable simple method on the same data, for the comparison table.
void compare_simple_methods(UnifiedFitResult& out, const NonTrackingObservations& obs,
                            const Instrument& inst) {
  for (NonTrackingMethod m : applicable_methods(obs)) {
    if (m == NonTrackingMethod::LeastSquares) continue;
    try {
      out.simple_methods.push_back(reduce_nontracking(m, obs, inst));
    } catch (const Error& e) {
      out.warnings.push_back(fmt::format("{} (comparison table): {}", to_string(m), e.what()));
    }
  }
}

}  // namespace

bool unified_fit_applicable(const NonTrackingObservations& obs, const UnifiedFitOptions& options) {
  return !not_applicable(obs, options).has_value();
}

BetaResult UnifiedFitResult::as_beta_result() const {
  BetaResult r;
  r.method = NonTrackingMethod::LeastSquares;
  r.beta_div = beta_div;
  r.amplitude_div = amplitude_div;
  r.period_s = period_s;
  r.approximation_error_div = 0.0;
  r.warnings = warnings;
  r.assumptions = assumptions;
  return r;
}

UnifiedFitResult fit_nontracking(const NonTrackingObservations& obs, const Instrument& inst,
                                 const UnifiedFitOptions& options) {
  validate_nontracking(obs);
  if (const auto why = not_applicable(obs, options))
    throw InputError(why->second, ErrorContext{"", std::nullopt, why->first});

  const Start st = start_values(obs, inst);
  Problem pb = build_problem(obs, options, st);
  const WeightedObservations w = weighted_observations(pb, obs);
  const Solution sol = solve(pb, w, solver_options(pb, st.period));
  check_solution(pb, sol.p);

  UnifiedFitResult out = map_result(pb, sol);
  add_assumptions(out, pb, fixed_period(obs, options), st);
  add_diagnostics(out, pb, sol.lsq);
  if (options.compare_simple_methods) compare_simple_methods(out, obs, inst);
  return out;
}

}  // namespace meridian::gyro
