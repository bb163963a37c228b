#include "meridian/gyro/nontracking.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "format.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/unified_fit.hpp"

namespace meridian::gyro {
namespace {

using units::kPi;
using Vec = std::vector<double>;

[[noreturn]] void throw_input(const std::string& field, const std::string& message) {
  throw InputError(message, ErrorContext{"", std::nullopt, field});
}

[[noreturn]] void throw_numerical(const std::string& field, const std::string& message) {
  throw NumericalError(message, ErrorContext{"", std::nullopt, field});
}

using detail::num;

std::string times_field(std::size_t c) { return fmt::format("crossings[{}].times_s", c); }

// Direction of passage j of a level: consecutive passages alternate.
int direction_at(const Crossing& c, std::size_t j) {
  return (j % 2 == 0) ? c.first_direction : -c.first_direction;
}

// ---------------------------------------------------------------------------
// σ propagation: first-order, independent inputs, central-difference Jacobian.
// The step is 1e-3·σ_j: small enough that the truncation error is negligible
// for these smooth functions, large enough to stay far above rounding.

struct Propagated {
  Vec value;
  Vec sigma;
};

Propagated propagate(const std::function<Vec(const Vec&)>& f, const std::vector<Uncertain>& in) {
  Vec x(in.size());
  for (std::size_t j = 0; j < in.size(); ++j) x[j] = in[j].value;
  Propagated p;
  p.value = f(x);
  Vec var(p.value.size(), 0.0);
  for (std::size_t j = 0; j < in.size(); ++j) {
    if (!(in[j].sigma > 0.0)) continue;
    const double h = 1e-3 * in[j].sigma;
    Vec xp = x;
    Vec xm = x;
    xp[j] += h;
    xm[j] -= h;
    const double h2 = xp[j] - xm[j];  // the step actually taken
    const Vec fp = f(xp);
    const Vec fm = f(xm);
    for (std::size_t i = 0; i < var.size(); ++i) {
      const double d = (fp[i] - fm[i]) / h2 * in[j].sigma;
      var[i] += d * d;
    }
  }
  p.sigma.resize(var.size());
  for (std::size_t i = 0; i < var.size(); ++i) p.sigma[i] = std::sqrt(var[i]);
  return p;
}

// ---------------------------------------------------------------------------
// Shared pieces

void require_period(const NonTrackingObservations& obs, const char* method) {
  if (!obs.period_s)
    throw_input("period_s", fmt::format("the {} method needs the period T_B", method));
}

Uncertain period_input(const NonTrackingObservations& obs) {
  return {obs.period_s->value, obs.period_s->sigma};
}

// Amplitude from alternating reversal readings: mean over consecutive pairs of
// |a_i − a_{i+1}|/2 (= (|a_e| + |a_w|)/2 when the pair straddles the zero).
double amplitude_from_reversals(const double* a, std::size_t n) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i) sum += std::abs(a[i] - a[i + 1]) / 2.0;
  return sum / static_cast<double>(n - 1);
}

// Index of the first crossing of the scale zero with at least `min_times` passages.
std::optional<std::size_t> find_zero_level(const NonTrackingObservations& obs,
                                           std::size_t min_times) {
  for (std::size_t c = 0; c < obs.crossings.size(); ++c)
    if (obs.crossings[c].level_div == 0.0 && obs.crossings[c].times_s.size() >= min_times) return c;
  return std::nullopt;
}

// ---------------------------------------------------------------------------
// Level selection for the two-level methods (time-difference, direct)

struct LevelPair {
  std::size_t i = 0;
  std::size_t j = 0;
  bool opposite = true;  // the levels lie on either side of the centre
};

// Sign of (β − a) from the first three passages: sign(d·Δt).
int side_of_centre(const Crossing& c) {
  const double dt = time_difference_s(c.times_s[0], c.times_s[1], c.times_s[2]);
  const double s = c.first_direction * dt;
  return s > 0.0 ? 1 : (s < 0.0 ? -1 : 0);
}

// Rule: among levels with ≥ 3 passages, the pair on opposite sides of the
// centre with the largest separation (best conditioned); if no such pair, the
// pair with the largest separation. Ties keep the input order.
std::optional<LevelPair> select_two_levels(const NonTrackingObservations& obs) {
  std::optional<LevelPair> best;
  double best_sep = -1.0;
  bool best_opp = false;
  for (std::size_t i = 0; i < obs.crossings.size(); ++i) {
    if (obs.crossings[i].times_s.size() < 3) continue;
    for (std::size_t j = i + 1; j < obs.crossings.size(); ++j) {
      if (obs.crossings[j].times_s.size() < 3) continue;
      const double sep = std::abs(obs.crossings[j].level_div - obs.crossings[i].level_div);
      if (sep == 0.0) continue;
      const bool opp = side_of_centre(obs.crossings[i]) * side_of_centre(obs.crossings[j]) < 0;
      if (!best || (opp && !best_opp) || (opp == best_opp && sep > best_sep)) {
        best = LevelPair{i, j, opp};
        best_sep = sep;
        best_opp = opp;
      }
    }
  }
  return best;
}

LevelPair require_two_levels(const NonTrackingObservations& obs, const char* method) {
  const auto p = select_two_levels(obs);
  if (!p)
    throw_input("crossings", fmt::format("the {} method needs two different levels with three "
                                         "consecutive crossings each",
                                         method));
  return *p;
}

std::string level_pair_note(const NonTrackingObservations& obs, const LevelPair& p) {
  return fmt::format("levels {} div (crossings[{}]) and {} div (crossings[{}]), first three "
                     "passages of each",
                     num(obs.crossings[p.i].level_div), p.i, num(obs.crossings[p.j].level_div),
                     p.j);
}

// Effective time difference d·Δt (sign as for an eastward first passage) with
// the check that the level is reached: |Δt| < T_B.
double effective_dt(double t1, double t2, double t3, int d, double period, std::size_t crossing) {
  const double dt = d * time_difference_s(t1, t2, t3);
  if (!(std::abs(dt) < period))
    throw_numerical(times_field(crossing),
                    fmt::format("|Δt| = {} s is not less than T_B = {} s: the three passages are "
                                "not consecutive crossings of a level the light mark reaches",
                                num(std::abs(dt)), num(period)));
  return dt;
}

// ---------------------------------------------------------------------------
// Transit (§4.1)

// The crossing of the scale zero the transit method times, after checking that the
// observations and the instrument allow the method.
std::size_t transit_crossing(const NonTrackingObservations& obs, const Instrument& inst) {
  const auto zc = find_zero_level(obs, 3);
  if (!zc)
    throw_input("crossings", "the transit method needs three crossings of the scale zero "
                             "(a crossing entry with level_div = 0 and at least three times)");
  if (obs.reversals_div.size() < 2)
    throw_input("reversals_div", fmt::format("the transit method needs two reversal readings "
                                             "(one each side) for the amplitude B (found {})",
                                             obs.reversals_div.size()));
  const bool calibrated = inst.transit_factor_rad_per_div_s.has_value();
  if (!calibrated && !(inst.scale_value_rad > 0.0))
    throw_input("scale_value_rad", "the transit method needs the scale value τ > 0 "
                                   "(or a calibrated transit factor c)");
  return *zc;
}

// The transit method's inputs with their σ: n times, nr readings, [T_B], then λ, τ or c.
std::vector<Uncertain> transit_inputs(const NonTrackingObservations& obs, const Instrument& inst,
                                      const Crossing& cr) {
  std::vector<Uncertain> in;
  for (double t : cr.times_s) in.push_back({t, obs.sigma_time_s});
  for (double a : obs.reversals_div) in.push_back({a, obs.sigma_reading_div});
  if (obs.period_s) in.push_back(period_input(obs));
  if (inst.transit_factor_rad_per_div_s) {
    in.push_back(*inst.transit_factor_rad_per_div_s);
  } else {
    in.push_back(inst.torsion_ratio);
    in.push_back({inst.scale_value_rad, inst.sigma_scale_value_rad});
  }
  return in;
}

// Least squares t_i = t0 + (i−1)·T_B/2 + (−1)^i·u (i = 1…n), equal weights, with T_B given or
// estimated: (u, T_B).
std::pair<double, double> transit_times_fit(const double* t, std::size_t n, std::optional<double> period) {
  const Eigen::Index rows = static_cast<Eigen::Index>(n);
  const Eigen::Index cols = period ? 2 : 3;
  Eigen::MatrixXd A(rows, cols);
  Eigen::VectorXd l(rows);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const double sgn = (r % 2 == 0) ? -1.0 : 1.0;  // (−1)^i with i = r + 1
    A(r, 0) = 1.0;
    A(r, 1) = sgn;
    l(r) = t[r];
    if (period)
      l(r) -= static_cast<double>(r) * *period / 2.0;
    else
      A(r, 2) = static_cast<double>(r);
  }
  const auto ls = adjust::solve_linear_diagonal(A, l, Eigen::VectorXd::Ones(rows));
  return std::pair<double, double>{ls.x(1), period ? *period : 2.0 * ls.x(2)};
}

// The period and the time difference of the propagated transit (outputs 3 and 4) must describe
// consecutive transits, and the amplitude (output 2) must not be zero.
void check_transit(const Propagated& p, std::size_t zc) {
  const double T = p.value[3];
  if (!(T > 0.0))
    throw_numerical(times_field(zc), fmt::format("the period from the transits is {} s", num(T)));
  if (!(std::abs(p.value[4]) < T))
    throw_numerical(times_field(zc),
                    fmt::format("|Δt| = {} s is not less than T_B = {} s: the passages are not "
                                "consecutive transits of the scale zero",
                                num(std::abs(p.value[4])), num(T)));
  if (!(p.value[2] > 0.0))
    throw_numerical("reversals_div", "the reversal readings give a zero amplitude B");
}

// The transit's result from its propagated outputs, with what it assumed and, for a given T_B,
// the check of the transits' own period against it.
BetaResult transit_result(const Propagated& p, const NonTrackingObservations& obs, std::size_t zc,
                          std::size_t n, bool calibrated) {
  const bool known = obs.period_s.has_value();
  BetaResult r;
  r.method = NonTrackingMethod::Transit;
  r.beta_div = {p.value[0], p.sigma[0]};
  r.transit_delta_n_rad = Uncertain{p.value[1], p.sigma[1]};
  r.amplitude_div = Uncertain{p.value[2], p.sigma[2]};
  r.period_s = Uncertain{p.value[3], p.sigma[3]};
  r.time_difference_s = Uncertain{p.value[4], p.sigma[4]};
  r.approximation_error_div = p.value[0] - p.value[5];
  r.assumptions.push_back("k = 0 (damping neglected)");
  r.assumptions.push_back("small-angle form β = π·B·Δt/(2T_B)");
  r.assumptions.push_back(fmt::format("transits: crossings[{}], {} passages{}", zc, n, n > 3 ? " (least squares)" : ""));
  if (known)
    r.assumptions.push_back("T_B = period_s");
  else
    r.assumptions.push_back(n == 3 ? "T_B = t3 − t1 from the transits"
                                   : "T_B estimated from the transits (least squares)");
  if (obs.reversals_div.size() > 2)
    r.assumptions.push_back("B = mean of |a_i − a_(i+1)|/2 over consecutive reversal pairs");
  if (calibrated)
    r.assumptions.push_back("ΔN = c·B·Δt with the calibrated transit factor c");
  else
    r.assumptions.push_back("ΔN = c·B·Δt with c = (1+λ)·τ·π/(2T_B)");
  if (known) {
    // Times against the given T_B: the transits' own period estimate. σ of the
    // difference from the timing σ and σ(T_B); 1 ms floor for rounded times.
    r.period_from_passages_s = Uncertain{p.value[6], p.sigma[6]};
    const double diff = p.value[6] - obs.period_s->value;
    const double sd = std::hypot(p.sigma[6], obs.period_s->sigma);
    if (std::abs(diff) > std::max(3.0 * sd, 1e-3))
      r.warnings.push_back(fmt::format(
          "transit: the transit times imply T_B = {:.3f} s, inconsistent with period_s = {:.3f} s "
          "(difference {:.3f} s, more than 3σ = {:.3f} s)",
          p.value[6], obs.period_s->value, diff, 3.0 * sd));
  }
  return r;
}

BetaResult transit(const NonTrackingObservations& obs, const Instrument& inst) {
  const std::size_t zc = transit_crossing(obs, inst);
  const bool calibrated = inst.transit_factor_rad_per_div_s.has_value();
  const Crossing& cr = obs.crossings[zc];
  const std::size_t n = cr.times_s.size();
  const std::size_t nr = obs.reversals_div.size();
  const bool known = obs.period_s.has_value();
  const int d = cr.first_direction;

  // Outputs: β_small, ΔN, B, T_B used, d·Δt, β_exact, T_B from the transits alone.
  const auto f = [&](const Vec& x) -> Vec {
    const double* t = x.data();
    const double B = amplitude_from_reversals(x.data() + n, nr);
    std::size_t k = n + nr;
    const std::optional<double> period = known ? std::optional<double>(x[k++]) : std::nullopt;
    double u = 0.0;
    double free_period = 0.0;
    if (n == 3) {
      u = time_difference_s(t[0], t[1], t[2]) / 4.0;  // the LS solution for n = 3, either way
      free_period = t[2] - t[0];
    } else {
      free_period = transit_times_fit(t, n, std::nullopt).second;
      u = transit_times_fit(t, n, period).first;
    }
    const double T = period ? *period : free_period;
    const double dt = d * 4.0 * u;
    const double beta_small = kPi * B * dt / (2.0 * T);
    const double beta_exact = B * std::sin(kPi * dt / (2.0 * T));
    const double dn = calibrated ? x[k] * B * dt : (1.0 + x[k]) * x[k + 1] * beta_small;
    return {beta_small, dn, B, T, dt, beta_exact, free_period};
  };

  const Propagated p = propagate(f, transit_inputs(obs, inst, cr));
  check_transit(p, zc);
  return transit_result(p, obs, zc, n, calibrated);
}

// ---------------------------------------------------------------------------
// Time difference (§4.2) and direct solution (§4.3)

// The first three passages of both levels of the pair, each with σ_t.
std::vector<Uncertain> two_level_times(const NonTrackingObservations& obs, const LevelPair& lp) {
  std::vector<Uncertain> in;
  for (std::size_t c : {lp.i, lp.j})
    for (std::size_t k = 0; k < 3; ++k) in.push_back({obs.crossings[c].times_s[k], obs.sigma_time_s});
  return in;
}

// The direct solution (§4.3) from the sines s_x of the two levels:
// (β − a_x) = B·s_x ⇒ β and B. Also the exact reference of the time-difference method.
struct TwoLevelSolution {
  double beta, amplitude;
};
TwoLevelSolution solve_two_levels(double ai, double aj, double si, double sj) {
  if (sj == si)
    throw_numerical("crossings", "both levels give the same time difference: no solution");
  return {(ai * sj - aj * si) / (sj - si), (aj - ai) / (si - sj)};
}

void require_positive_amplitude(double b_div) {
  if (!(b_div > 0.0))
    throw_numerical("crossings", fmt::format("the crossing times imply a non-positive amplitude "
                                             "B = {} div",
                                             num(b_div)));
}

void warn_if_extrapolated(BetaResult& r, const LevelPair& lp, const char* method) {
  if (!lp.opposite)
    r.warnings.push_back(fmt::format("{}: no two timed levels lie on opposite sides of the centre; "
                                     "β is extrapolated",
                                     method));
}

BetaResult time_difference_method(const NonTrackingObservations& obs) {
  const LevelPair lp = require_two_levels(obs, "time-difference");
  const Crossing& ci = obs.crossings[lp.i];
  const Crossing& cj = obs.crossings[lp.j];
  const double ai = ci.level_div;
  const double aj = cj.level_div;
  const std::vector<Uncertain> in = two_level_times(obs, lp);

  // Outputs: β (small angle), T_B implied (mean t3 − t1), B and β from the
  // arcsine (direct) form with that T_B.
  const auto f = [&](const Vec& x) -> Vec {
    const double T = ((x[2] - x[0]) + (x[5] - x[3])) / 2.0;
    if (!(T > 0.0))
      throw_numerical(times_field(lp.i), "the implied period t3 − t1 is not positive");
    const double dti = effective_dt(x[0], x[1], x[2], ci.first_direction, T, lp.i);
    const double dtj = effective_dt(x[3], x[4], x[5], cj.first_direction, T, lp.j);
    if (dtj == dti)
      throw_numerical("crossings", "both levels give the same time difference: no solution");
    const double beta = (ai * dtj - aj * dti) / (dtj - dti);
    const TwoLevelSolution exact =
        solve_two_levels(ai, aj, std::sin(kPi * dti / (2.0 * T)), std::sin(kPi * dtj / (2.0 * T)));
    return {beta, T, exact.amplitude, exact.beta};
  };
  const Propagated p = propagate(f, in);
  require_positive_amplitude(p.value[2]);
  BetaResult r;
  r.method = NonTrackingMethod::TimeDifference;
  r.beta_div = {p.value[0], p.sigma[0]};
  r.period_s = Uncertain{p.value[1], p.sigma[1]};
  r.amplitude_div = Uncertain{p.value[2], p.sigma[2]};
  r.approximation_error_div = p.value[0] - p.value[3];
  r.assumptions.push_back("k = 0 (damping neglected)");
  r.assumptions.push_back("small-angle form (β − a) ∝ Δt_a");
  r.assumptions.push_back(level_pair_note(obs, lp));
  r.assumptions.push_back("implied T_B = mean of t3 − t1 of the two levels; implied B and the "
                          "approximation error from the arcsine form with that T_B");
  warn_if_extrapolated(r, lp, "time-difference");
  return r;
}

BetaResult direct_method(const NonTrackingObservations& obs) {
  require_period(obs, "direct-solution");
  const LevelPair lp = require_two_levels(obs, "direct-solution");
  const Crossing& ci = obs.crossings[lp.i];
  const Crossing& cj = obs.crossings[lp.j];
  const double ai = ci.level_div;
  const double aj = cj.level_div;
  std::vector<Uncertain> in = two_level_times(obs, lp);
  in.push_back(period_input(obs));
  const auto f = [&](const Vec& x) -> Vec {
    const double T = x[6];
    const double si = std::sin(kPi * effective_dt(x[0], x[1], x[2], ci.first_direction, T, lp.i) /
                               (2.0 * T));
    const double sj = std::sin(kPi * effective_dt(x[3], x[4], x[5], cj.first_direction, T, lp.j) /
                               (2.0 * T));
    const TwoLevelSolution sol = solve_two_levels(ai, aj, si, sj);
    return {sol.beta, sol.amplitude};
  };
  const Propagated p = propagate(f, in);
  require_positive_amplitude(p.value[1]);
  BetaResult r;
  r.method = NonTrackingMethod::Direct;
  r.beta_div = {p.value[0], p.sigma[0]};
  r.amplitude_div = Uncertain{p.value[1], p.sigma[1]};
  r.period_s = period_input(obs);
  r.assumptions.push_back("k = 0 (damping neglected)");
  r.assumptions.push_back(level_pair_note(obs, lp));
  warn_if_extrapolated(r, lp, "direct");
  return r;
}

// ---------------------------------------------------------------------------
// Timed amplitude I (§4.4) and II (§4.5)

// TA-I: passages `first`, `first + 1` of crossings[crossing] and reversal `other`.
struct PairChoice {
  std::size_t crossing = 0;
  std::size_t first = 0;   // passages first, first + 1
  std::size_t other = 0;   // reversal index
  bool timed = false;      // TA-I: the reversal was chosen by its time
};

// TA-I rule: the first pair of consecutive passages (crossings in input
// order, passages in time order) with a reversal reading between them — by
// reversal_times_s when given, otherwise the first reversal reading on the
// outward side of the level (east of it when the pair starts eastward).
std::optional<PairChoice> select_ta1(const NonTrackingObservations& obs) {
  const bool timed = !obs.reversal_times_s.empty();
  for (std::size_t c = 0; c < obs.crossings.size(); ++c) {
    const Crossing& cr = obs.crossings[c];
    for (std::size_t j = 0; j + 1 < cr.times_s.size(); ++j) {
      const int d = direction_at(cr, j);
      for (std::size_t r = 0; r < obs.reversals_div.size(); ++r) {
        const bool ok = timed ? (obs.reversal_times_s[r] > cr.times_s[j] &&
                                 obs.reversal_times_s[r] < cr.times_s[j + 1])
                              : d * (obs.reversals_div[r] - cr.level_div) > 0.0;
        if (ok) return PairChoice{c, j, r, timed};
      }
    }
  }
  return std::nullopt;
}

// TA-II candidates. The pair t1, t2 = passages 1 and 2 of the first level
// timed at least twice that has another level timed. For every other level
// (crossing entry) one passage is a candidate for t3: the first passage after
// t_r = (t1 + t2)/2, else the last one before. Which passage of a level is
// nearest to t_r must not be decided by the times: the two passages of a
// level on either side of the turning point at t_r are its mirror images
// (equally near for k = 0), so "nearest" would pick the one that the timing
// noise moved towards t_r — a selection bias of order σ_t (−3.8″ at the
// simulator's defaults). Before/after t_r is a safe decision: a passage lies
// seconds, not σ_t, away from the turning point.
struct Ta2Candidates {
  std::size_t crossing = 0;                                // level a, passages 0 and 1
  std::vector<std::pair<std::size_t, std::size_t>> third;  // (crossing, passage) per other level
};

std::optional<Ta2Candidates> ta2_candidates(const NonTrackingObservations& obs) {
  for (std::size_t c = 0; c < obs.crossings.size(); ++c) {
    const Crossing& cr = obs.crossings[c];
    if (cr.times_s.size() < 2) continue;
    const double tr = (cr.times_s[0] + cr.times_s[1]) / 2.0;
    Ta2Candidates out;
    out.crossing = c;
    for (std::size_t x = 0; x < obs.crossings.size(); ++x) {
      const std::vector<double>& tx = obs.crossings[x].times_s;
      if (obs.crossings[x].level_div == cr.level_div || tx.empty()) continue;
      const auto after = std::upper_bound(tx.begin(), tx.end(), tr);
      const std::size_t k =
          after != tx.end() ? static_cast<std::size_t>(after - tx.begin()) : tx.size() - 1;
      out.third.emplace_back(x, k);
    }
    if (!out.third.empty()) return out;
  }
  return std::nullopt;
}

// cos(π(t2 − t1)/T) after checking that t1, t2 can bracket one reversal.
double bracket_cos(double t1, double t2, double T, std::size_t crossing) {
  const double gap = t2 - t1;
  if (!(gap > 0.0 && gap < T))
    throw_numerical(times_field(crossing),
                    fmt::format("t2 − t1 = {} s is not between 0 and T_B = {} s: the two passages "
                                "cannot bracket a single reversal",
                                num(gap), num(T)));
  return std::cos(kPi * gap / T);
}

BetaResult timed_amplitude_1(const NonTrackingObservations& obs) {
  require_period(obs, "timed-amplitude I");
  if (obs.reversals_div.empty())
    throw_input("reversals_div", "the timed-amplitude method I needs a reversal reading");
  const auto ch = select_ta1(obs);
  if (!ch)
    throw_input("crossings", obs.reversal_times_s.empty()
                                 ? "the timed-amplitude method I needs two consecutive passages "
                                   "of one level and a reversal reading beyond that level"
                                 : "the timed-amplitude method I needs two consecutive passages "
                                   "of one level whose times bracket a reversal time");
  const Crossing& cr = obs.crossings[ch->crossing];
  const double a = cr.level_div;
  const double ar = obs.reversals_div[ch->other];
  const int d = direction_at(cr, ch->first);
  if (!(d * (ar - a) > 0.0))
    throw_input(fmt::format("reversals_div[{}]", ch->other),
                fmt::format("the reversal reading {} div lies between passages {} and {} of level "
                            "{} div but not beyond that level in the direction of motion",
                            num(ar), ch->first + 1, ch->first + 2, num(a)));
  const std::vector<Uncertain> in = {{cr.times_s[ch->first], obs.sigma_time_s},
                                     {cr.times_s[ch->first + 1], obs.sigma_time_s},
                                     {ar, obs.sigma_reading_div},
                                     period_input(obs)};
  const auto f = [&](const Vec& x) -> Vec {
    const double C = bracket_cos(x[0], x[1], x[3], ch->crossing);
    const double beta = (a - x[2] * C) / (1.0 - C);
    return {beta, std::abs(x[2] - beta)};
  };
  const Propagated p = propagate(f, in);
  BetaResult r;
  r.method = NonTrackingMethod::TimedAmplitude1;
  r.beta_div = {p.value[0], p.sigma[0]};
  r.amplitude_div = Uncertain{p.value[1], p.sigma[1]};
  r.period_s = period_input(obs);
  r.assumptions.push_back("k = 0 (damping neglected)");
  r.assumptions.push_back(fmt::format(
      "level {} div (crossings[{}]) passages {} and {}, reversal reversals_div[{}] = {} div {}",
      num(a), ch->crossing, ch->first + 1, ch->first + 2, ch->other, num(ar),
      ch->timed ? "(bracketed by time)"
                : "(no reversal_times_s: the first reversal beyond the level is assumed to lie "
                  "between the two passages)"));
  return r;
}

// Levels whose propagated σ(β) lie within this fraction of the smallest count
// as equally well conditioned. σ(β) computed from noisy times varies between
// runs by 0.6 % (standard deviation at the simulator's defaults), so the
// choice between two levels depends on the noise only where their σ differ
// by 10 % ± about 2 %.
constexpr double kTa2EquallyConditioned = 0.10;

BetaResult timed_amplitude_2(const NonTrackingObservations& obs) {
  require_period(obs, "timed-amplitude II");
  const auto cand = ta2_candidates(obs);
  if (!cand)
    throw_input("crossings", "the timed-amplitude method II needs two passages of one level and "
                             "a passage of another level");
  const std::size_t c = cand->crossing;
  const Crossing& cr = obs.crossings[c];
  const double a = cr.level_div;

  // β and B for the third passage (crossing x, passage k); inputs t1, t2, t3, T_B.
  struct Solved {
    std::size_t x, k;
    Propagated p;
  };
  const auto solve = [&](std::size_t x, std::size_t k) {
    const double ax = obs.crossings[x].level_div;
    const std::vector<Uncertain> in = {{cr.times_s[0], obs.sigma_time_s},
                                       {cr.times_s[1], obs.sigma_time_s},
                                       {obs.crossings[x].times_s[k], obs.sigma_time_s},
                                       period_input(obs)};
    const auto f = [&](const Vec& v) -> Vec {
      const double T = v[3];
      const double c12 = bracket_cos(v[0], v[1], T, c);
      const double c3 = std::cos(2.0 * kPi * (v[2] - (v[0] + v[1]) / 2.0) / T);
      if (std::abs(c3 - c12) < 1e-12)
        throw_numerical("crossings",
                        "timed-amplitude II: the third passage gives the same phase "
                        "factor as the pair (C3 = C12); no solution");
      const double beta = (a * c3 - ax * c12) / (c3 - c12);
      // a − β = (a_r − β)·C12 and a_x − β = (a_r − β)·C3: B from the larger factor.
      const double B =
          std::abs(c12) > std::abs(c3) ? std::abs((a - beta) / c12) : std::abs((ax - beta) / c3);
      return {beta, B};
    };
    return Solved{x, k, propagate(f, in)};
  };

  // Level choice: the smallest propagated σ(β); levels within
  // kTa2EquallyConditioned of it are equal, and of those the level farthest
  // from a (then the first in input order) is used — exact graduations, so
  // the tie-break does not depend on the noise either.
  std::vector<Solved> solved;
  std::optional<NumericalError> failure;
  for (const auto& [x, k] : cand->third) {
    try {
      solved.push_back(solve(x, k));
    } catch (const NumericalError& e) {
      if (e.context().field != "crossings") throw;  // t1, t2 themselves are unusable
      if (!failure) failure = e;                    // this t3 only: try the other levels
    }
  }
  if (solved.empty()) throw *failure;
  double best_sigma = solved.front().p.sigma[0];
  for (const Solved& s : solved) best_sigma = std::min(best_sigma, s.p.sigma[0]);
  const Solved* ch = nullptr;
  for (const Solved& s : solved) {
    if (!(s.p.sigma[0] <= (1.0 + kTa2EquallyConditioned) * best_sigma)) continue;
    if (!ch ||
        std::abs(obs.crossings[s.x].level_div - a) > std::abs(obs.crossings[ch->x].level_div - a))
      ch = &s;
  }
  const double ax = obs.crossings[ch->x].level_div;

  BetaResult r;
  r.method = NonTrackingMethod::TimedAmplitude2;
  r.beta_div = {ch->p.value[0], ch->p.sigma[0]};
  r.amplitude_div = Uncertain{ch->p.value[1], ch->p.sigma[1]};
  r.period_s = period_input(obs);
  r.assumptions.push_back("k = 0 (damping neglected)");
  r.assumptions.push_back(fmt::format(
      "level {} div (crossings[{}]) passages 1 and 2; third passage crossings[{}].times_s[{}] of "
      "level {} div (of the other levels the best conditioned, smallest σ(β) within 10 % and "
      "then farthest from {} div; of its passages the first after t_r = (t1 + t2)/2, else the "
      "last before)",
      num(a), c, ch->x, ch->k, num(ax), num(a)));
  return r;
}

}  // namespace

// ---------------------------------------------------------------------------

std::string to_string(NonTrackingMethod m) {
  switch (m) {
    case NonTrackingMethod::Transit: return "transit";
    case NonTrackingMethod::TimeDifference: return "time-difference";
    case NonTrackingMethod::Direct: return "direct";
    case NonTrackingMethod::TimedAmplitude1: return "timed-amplitude-1";
    case NonTrackingMethod::TimedAmplitude2: return "timed-amplitude-2";
    case NonTrackingMethod::LeastSquares: return "lsq";
  }
  return "unknown";
}

NonTrackingMethod nontracking_method_from_string(const std::string& name) {
  for (NonTrackingMethod m :
       {NonTrackingMethod::Transit, NonTrackingMethod::TimeDifference, NonTrackingMethod::Direct,
        NonTrackingMethod::TimedAmplitude1, NonTrackingMethod::TimedAmplitude2,
        NonTrackingMethod::LeastSquares})
    if (to_string(m) == name) return m;
  throw InputError(fmt::format("unknown non-tracking method \"{}\" (accepted: transit, "
                               "time-difference, direct, timed-amplitude-1, timed-amplitude-2, "
                               "lsq)",
                               name),
                   ErrorContext{"", std::nullopt, "method"});
}

double time_difference_s(double t1, double t2, double t3) { return -t1 + 2.0 * t2 - t3; }

std::string small_angle_warning(const BetaResult& r, double error_rad, double sigma_rad) {
  const double size = std::abs(error_rad);
  if (!(size > kSmallAngleWarningFraction * sigma_rad &&
        size > kSmallAngleWarningFloorArcsec * units::kArcsecond))
    return {};
  return fmt::format(
      "{}: the small-angle approximation error is {:.5f} div = {:.3f}″ in N_G, more than {:g} of "
      "the run's σ(N_G) = {:.2f}″; prefer the direct solution or the unified least-squares fit",
      to_string(r.method), r.approximation_error_div, units::rad_to_arcsec(error_rad),
      kSmallAngleWarningFraction, units::rad_to_arcsec(sigma_rad));
}

void validate_nontracking(const NonTrackingObservations& obs) {
  if (!std::isfinite(obs.sigma_time_s) || obs.sigma_time_s < 0.0)
    throw_input("sigma_time_s",
                fmt::format("must be finite and ≥ 0 (got {})", num(obs.sigma_time_s)));
  if (!std::isfinite(obs.sigma_reading_div) || obs.sigma_reading_div < 0.0)
    throw_input("sigma_reading_div",
                fmt::format("must be finite and ≥ 0 (got {})", num(obs.sigma_reading_div)));
  for (std::size_t c = 0; c < obs.crossings.size(); ++c) {
    const Crossing& cr = obs.crossings[c];
    if (!std::isfinite(cr.level_div))
      throw_input(fmt::format("crossings[{}].level_div", c), "not a finite number");
    if (cr.first_direction != 1 && cr.first_direction != -1)
      throw_input(fmt::format("crossings[{}].first_direction", c),
                  fmt::format("must be +1 (east) or −1 (west), got {}", cr.first_direction));
    for (std::size_t k = 0; k < cr.times_s.size(); ++k) {
      if (!std::isfinite(cr.times_s[k]))
        throw_input(fmt::format("crossings[{}].times_s[{}]", c, k), "not a finite number");
      if (k > 0 && !(cr.times_s[k] > cr.times_s[k - 1]))
        throw_input(times_field(c), fmt::format("times must increase (t{} = {} ≤ t{} = {})", k + 1,
                                                num(cr.times_s[k]), k, num(cr.times_s[k - 1])));
    }
  }
  const auto& rv = obs.reversals_div;
  for (std::size_t k = 0; k < rv.size(); ++k) {
    if (!std::isfinite(rv[k]))
      throw_input(fmt::format("reversals_div[{}]", k), "not a finite number");
    if (k >= 1 && rv[k] == rv[k - 1])
      throw_input(fmt::format("reversals_div[{}]", k),
                  fmt::format("equals the previous reversal reading ({} div): consecutive "
                              "reversals lie on opposite sides of the centre",
                              num(rv[k])));
    // a_k must lie on the same side as a_(k−2) of the midpoint of a_(k−2), a_(k−1).
    const double mid = k >= 2 ? (rv[k - 2] + rv[k - 1]) / 2.0 : 0.0;
    if (k >= 2 && !((rv[k] - mid) * (rv[k - 2] - mid) > 0.0))
      throw_input(fmt::format("reversals_div[{}]", k),
                  fmt::format("reversal readings must alternate about the centre ({}, {}, {} "
                              "div do not)",
                              num(rv[k - 2]), num(rv[k - 1]), num(rv[k])));
  }
  const auto& rt = obs.reversal_times_s;
  if (!rt.empty() && rt.size() != rv.size())
    throw_input("reversal_times_s", fmt::format("has {} entries but reversals_div has {}",
                                                rt.size(), rv.size()));
  for (std::size_t k = 0; k < rt.size(); ++k) {
    if (!std::isfinite(rt[k]))
      throw_input(fmt::format("reversal_times_s[{}]", k), "not a finite number");
    if (k > 0 && !(rt[k] > rt[k - 1]))
      throw_input("reversal_times_s", fmt::format("times must increase (t{} = {} ≤ t{} = {})",
                                                  k + 1, num(rt[k]), k, num(rt[k - 1])));
  }
  if (obs.period_s) {
    if (!std::isfinite(obs.period_s->value) || !(obs.period_s->value > 0.0))
      throw_input("period_s", fmt::format("T_B must be finite and > 0 (got {})",
                                          num(obs.period_s->value)));
    if (!std::isfinite(obs.period_s->sigma) || obs.period_s->sigma < 0.0)
      throw_input("period_s.sigma", fmt::format("must be finite and ≥ 0 (got {})",
                                                num(obs.period_s->sigma)));
  }
}

namespace {

void validate_instrument(const Instrument& inst) {
  if (!std::isfinite(inst.scale_value_rad) || inst.scale_value_rad < 0.0)
    throw_input("scale_value_rad", "τ must be finite and ≥ 0");
  if (!std::isfinite(inst.sigma_scale_value_rad) || inst.sigma_scale_value_rad < 0.0)
    throw_input("sigma_scale_value_rad", "must be finite and ≥ 0");
  if (!std::isfinite(inst.torsion_ratio.value) || inst.torsion_ratio.value < 0.0)
    throw_input("torsion_ratio", "λ must be finite and ≥ 0");
  if (!std::isfinite(inst.torsion_ratio.sigma) || inst.torsion_ratio.sigma < 0.0)
    throw_input("torsion_ratio.sigma", "must be finite and ≥ 0");
  if (const auto& c = inst.transit_factor_rad_per_div_s) {
    if (!std::isfinite(c->value) || !(c->value > 0.0))
      throw_input("transit_factor_rad_per_div_s", "c must be finite and > 0");
    if (!std::isfinite(c->sigma) || c->sigma < 0.0)
      throw_input("transit_factor_rad_per_div_s.sigma", "must be finite and ≥ 0");
  }
}

}  // namespace

BetaResult reduce_nontracking(NonTrackingMethod method, const NonTrackingObservations& obs,
                              const Instrument& inst) {
  validate_nontracking(obs);
  validate_instrument(inst);
  switch (method) {
    case NonTrackingMethod::Transit: return transit(obs, inst);
    case NonTrackingMethod::TimeDifference: return time_difference_method(obs);
    case NonTrackingMethod::Direct: return direct_method(obs);
    case NonTrackingMethod::TimedAmplitude1: return timed_amplitude_1(obs);
    case NonTrackingMethod::TimedAmplitude2: return timed_amplitude_2(obs);
    case NonTrackingMethod::LeastSquares: return fit_nontracking(obs, inst).as_beta_result();
  }
  throw InputError("unknown non-tracking method", ErrorContext{"", std::nullopt, "method"});
}

std::vector<NonTrackingMethod> applicable_methods(const NonTrackingObservations& obs) {
  std::vector<NonTrackingMethod> m;
  if (find_zero_level(obs, 3) && obs.reversals_div.size() >= 2)
    m.push_back(NonTrackingMethod::Transit);
  const bool two_levels = select_two_levels(obs).has_value();
  if (two_levels) m.push_back(NonTrackingMethod::TimeDifference);
  if (two_levels && obs.period_s) m.push_back(NonTrackingMethod::Direct);
  if (obs.period_s && select_ta1(obs)) m.push_back(NonTrackingMethod::TimedAmplitude1);
  if (obs.period_s && ta2_candidates(obs)) m.push_back(NonTrackingMethod::TimedAmplitude2);
  if (unified_fit_applicable(obs)) m.push_back(NonTrackingMethod::LeastSquares);
  return m;
}

Uncertain calibrate_transit_factor(double clamp1_rad, Uncertain amplitude1_div, Uncertain dt1_s,
                                   double clamp2_rad, Uncertain amplitude2_div, Uncertain dt2_s) {
  const std::pair<const char*, double> values[] = {
      {"clamp1_rad", clamp1_rad},           {"clamp2_rad", clamp2_rad},
      {"amplitude1_div", amplitude1_div.value}, {"amplitude1_div.sigma", amplitude1_div.sigma},
      {"dt1_s", dt1_s.value},               {"dt1_s.sigma", dt1_s.sigma},
      {"amplitude2_div", amplitude2_div.value}, {"amplitude2_div.sigma", amplitude2_div.sigma},
      {"dt2_s", dt2_s.value},               {"dt2_s.sigma", dt2_s.sigma}};
  for (const auto& [name, v] : values)
    if (!std::isfinite(v)) throw_input(name, "not a finite number");
  if (!(amplitude1_div.value > 0.0)) throw_input("amplitude1_div", "B must be > 0");
  if (!(amplitude2_div.value > 0.0)) throw_input("amplitude2_div", "B must be > 0");
  if (clamp1_rad == clamp2_rad)
    throw_input("clamp2_rad", "the two clamp positions must differ");
  const double p1 = amplitude1_div.value * dt1_s.value;
  const double p2 = amplitude2_div.value * dt2_s.value;
  const double den = p1 - p2;
  if (den == 0.0)
    throw_numerical("dt2_s", "B1·Δt1 = B2·Δt2: the two clamp positions give the same product; "
                             "no transit factor can be determined");
  // Clamp circle readings differ by a few arc-minutes: take the signed
  // difference on the circle.
  const double dn = std::remainder(clamp2_rad - clamp1_rad, 2.0 * kPi);
  const double c = dn / den;
  // ∂c/∂p1 = −c/den, ∂c/∂p2 = +c/den.
  const double g = c / den;
  const double var = std::pow(g * dt1_s.value * amplitude1_div.sigma, 2) +
                     std::pow(g * amplitude1_div.value * dt1_s.sigma, 2) +
                     std::pow(g * dt2_s.value * amplitude2_div.sigma, 2) +
                     std::pow(g * amplitude2_div.value * dt2_s.sigma, 2);
  if (!(c > 0.0))
    throw_numerical("dt2_s", fmt::format("the transit factor comes out non-positive (c = {} "
                                         "rad/(div·s)): check the signs of Δt and the clamps",
                                         num(c)));
  return {c, std::sqrt(var)};
}

}  // namespace meridian::gyro
