#include "meridian/gyro/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/checks.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {
namespace {

using units::kTwoPi;

void require_nonnegative(double v, std::string_view what) {
  if (!std::isfinite(v) || v < 0.0)
    throw InputError(fmt::format("{} must be finite and ≥ 0 (got {})", what, v));
}

void require_positive(double v, std::string_view what) {
  if (!std::isfinite(v) || v <= 0.0)
    throw InputError(fmt::format("{} must be finite and > 0 (got {})", what, v));
}

// Independent, reproducible streams from one user seed: std::seed_seq's
// algorithm is fixed by the standard, so the streams are too.
std::mt19937_64 make_stream(std::uint64_t seed, std::uint32_t stream) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed & 0xffffffffU),
                    static_cast<std::uint32_t>(seed >> 32), stream};
  return std::mt19937_64(seq);
}

// Reversal series x_i = centre + (−1)^i·A·e^{−iκ} + ε_i, i = 1 … n (R1).
std::vector<double> reversal_series(double centre, double amplitude, double kappa, int n,
                                    const NoiseModel& noise, std::uint64_t seed) {
  require_finite(centre, "centre of the oscillation");
  require_nonnegative(amplitude, "amplitude");
  require_nonnegative(kappa, "decay per half period κ");
  if (n < 2) throw InputError(fmt::format("reversals: need n ≥ 2 reversal points (got {})", n));
  validate_noise_model(noise);
  std::mt19937_64 rng(seed);
  const std::vector<double> eps = generate_noise(noise, static_cast<std::size_t>(n), rng);
  std::vector<double> r(eps.size());
  for (int i = 1; i <= n; ++i) {
    const double sign = (i % 2 == 0) ? 1.0 : -1.0;
    r[i - 1] = centre + sign * amplitude * std::exp(-i * kappa) + eps[i - 1];
  }
  return r;
}

void validate_tracking(const TrackingSimulation& sim) {
  require_finite(sim.centre_rad, "centre_rad");
  require_nonnegative(sim.amplitude_rad, "amplitude_rad");
  require_nonnegative(sim.kappa, "kappa");
  require_nonnegative(sim.period_s, "period_s");
  require_finite(sim.t0_s, "t0_s");
}

// (N1) with its derivative and exact turning points.
class Oscillation {
 public:
  explicit Oscillation(const NonTrackingSimulation& s)
      : beta_(s.beta_div),
        b_(s.amplitude_div),
        t0_(s.t0_s),
        k_(s.damping_per_s),
        w_(kTwoPi / s.period_s),
        // ȧ = 0 ⇔ tan(ω·s) = ω/k: ω·s = atan2(ω, k) + mπ (exact with damping).
        phase_(std::atan2(w_, k_)) {}

  double beta() const { return beta_; }
  double value(double t) const {
    const double s = t - t0_;
    return beta_ + b_ * std::exp(-k_ * s) * std::sin(w_ * s);
  }
  double rate(double t) const {
    const double s = t - t0_;
    return b_ * std::exp(-k_ * s) * (w_ * std::cos(w_ * s) - k_ * std::sin(w_ * s));
  }
  double turning_time(long m) const {
    return t0_ + (phase_ + static_cast<double>(m) * units::kPi) / w_;
  }
  // Index of the first turning point at or after t.
  long first_turning_at_or_after(double t) const {
    long m = static_cast<long>(std::ceil((w_ * (t - t0_) - phase_) / units::kPi));
    while (turning_time(m) < t) ++m;
    while (turning_time(m - 1) >= t) --m;
    return m;
  }

  // Root of value(t) = level in [lo, hi], where value is monotone and
  // f(lo), f(hi) have opposite signs: Newton safeguarded by bisection.
  double solve(double level, double lo, double hi) const {
    double flo = value(lo) - level;
    double x = lo + (hi - lo) * flo / (flo - (value(hi) - level));
    for (int iter = 0; iter < 200; ++iter) {
      const double fx = value(x) - level;
      if (fx == 0.0) return x;
      if ((fx < 0.0) == (flo < 0.0)) {
        lo = x;
        flo = fx;
      } else {
        hi = x;
      }
      const double d = rate(x);
      double xn = (d != 0.0) ? x - fx / d : lo - 1.0;
      if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
      const double step = std::abs(xn - x);
      x = xn;
      if (step < 5e-13 || hi - lo < 1e-12) break;
    }
    return x;
  }

 private:
  double beta_, b_, t0_, k_, w_, phase_;
};

void validate_nontracking(const NonTrackingSimulation& s) {
  require_finite(s.beta_div, "beta_div");
  require_positive(s.amplitude_div, "amplitude_div");
  require_positive(s.period_s, "period_s (T_B)");
  require_finite(s.t0_s, "t0_s");
  require_nonnegative(s.damping_per_s, "damping_per_s");
  require_finite(s.start_time_s, "start_time_s");
  // Half-cycle indices are kept in a long; far beyond 1e9 periods doubles
  // cannot resolve the phase anyway.
  if (std::abs(s.start_time_s - s.t0_s) > 1e9 * s.period_s)
    throw InputError("start_time_s is more than 1e9 periods away from t0_s");
  for (std::size_t i = 0; i < s.levels_div.size(); ++i) {
    require_finite(s.levels_div[i], fmt::format("levels_div[{}]", i));
    for (std::size_t j = 0; j < i; ++j)
      if (s.levels_div[j] == s.levels_div[i])
        throw InputError(fmt::format("levels_div: level {} div is listed twice", s.levels_div[i]));
  }
  if (!s.levels_div.empty() && s.crossings_per_level < 1)
    throw InputError(
        fmt::format("crossings_per_level must be ≥ 1 (got {})", s.crossings_per_level));
  if (s.reversals < 0) throw InputError(fmt::format("reversals must be ≥ 0 (got {})", s.reversals));
  if (s.levels_div.empty() && s.reversals == 0)
    throw InputError("nothing to simulate: no levels to time and no reversals to read");
  if (s.known_period_s) require_positive(*s.known_period_s, "known_period_s");
  require_nonnegative(s.known_period_sigma_s, "known_period_sigma_s");
  if (s.reported_sigma_time_s) require_positive(*s.reported_sigma_time_s, "reported_sigma_time_s");
  if (s.reported_sigma_reading_div)
    require_positive(*s.reported_sigma_reading_div, "reported_sigma_reading_div");
  validate_noise_model(s.time_noise);
  validate_noise_model(s.reading_noise);
}

// Consecutive passages of one level from start_time_s on, with the
// direction of the first.
Crossing time_level(const Oscillation& osc, double level, int count, double start) {
  Crossing c;
  c.level_div = level;
  const double off = level - osc.beta();
  // Between consecutive turning points a(t) is monotone, so each half-cycle
  // holds at most one root; begin with the half-cycle containing start.
  for (long m = osc.first_turning_at_or_after(start) - 1;
       static_cast<int>(c.times_s.size()) < count; ++m) {
    const double lo = osc.turning_time(m);
    const double hi = osc.turning_time(m + 1);
    const double flo = osc.value(lo) - level;
    const double fhi = osc.value(hi) - level;
    if ((flo < 0.0 && fhi > 0.0) || (flo > 0.0 && fhi < 0.0)) {
      const double t = osc.solve(level, lo, hi);
      if (t >= start) {
        if (c.times_s.empty()) c.first_direction = (fhi > flo) ? +1 : -1;
        c.times_s.push_back(t);
      }
      continue;
    }
    // The endpoints straddle β, so the level lies beyond the extreme on its
    // side; with k ≥ 0 later extremes are no larger: it is never reached.
    const double ext = ((osc.value(lo) - osc.beta() < 0.0) == (off < 0.0)) ? lo : hi;
    const double amp = std::abs(osc.value(ext) - osc.beta());
    if (c.times_s.empty())
      throw InputError(fmt::format(
          "level {:g} div is never reached by the light mark after t = {:g} s: "
          "|level − β| = {:g} div ≥ amplitude {:g} div",
          level, start, std::abs(off), amp));
    throw InputError(fmt::format(
        "level {:g} div: only {} of {} passages occur before the damped amplitude "
        "({:g} div at t = {:g} s) falls to |level − β| = {:g} div",
        level, c.times_s.size(), count, amp, ext, std::abs(off)));
  }
  return c;
}

}  // namespace

// ---------------------------------------------------------------------------
// Noise
// ---------------------------------------------------------------------------

void validate_noise_model(const NoiseModel& m) {
  require_nonnegative(m.sigma, "noise sigma");
  require_nonnegative(m.sigma_initial, "noise sigma_initial");
  require_finite(m.rho1, "noise rho1");
  require_finite(m.rho2, "noise rho2");
  switch (m.kind) {
    case NoiseModel::White:
      if (m.rho1 != 0.0 || m.rho2 != 0.0)
        throw InputError(fmt::format(
            "white noise takes no ρ (got ρ1 = {}, ρ2 = {}); choose Markov1 or Markov2", m.rho1,
            m.rho2));
      return;
    case NoiseModel::Markov1:
      if (m.rho2 != 0.0)
        throw InputError(fmt::format("Markov-1 noise takes ρ1 only (got ρ2 = {})", m.rho2));
      if (!(std::abs(m.rho1) < 1.0))
        throw InputError(
            fmt::format("Markov-1 noise with ρ = {} is not stationary (need |ρ| < 1)", m.rho1));
      return;
    case NoiseModel::Markov2:
      if (!(m.rho1 + m.rho2 < 1.0 && m.rho2 - m.rho1 < 1.0 && std::abs(m.rho2) < 1.0))
        throw InputError(fmt::format(
            "Markov-2 noise with ρ1 = {}, ρ2 = {} is not stationary (need ρ1 + ρ2 < 1, "
            "ρ2 − ρ1 < 1, |ρ2| < 1)",
            m.rho1, m.rho2));
      return;
  }
  throw InputError("unknown noise model kind");
}

double stationary_sigma(const NoiseModel& m) {
  validate_noise_model(m);
  switch (m.kind) {
    case NoiseModel::White:
      return m.sigma;
    case NoiseModel::Markov1:
      return m.sigma / std::sqrt(1.0 - m.rho1 * m.rho1);
    case NoiseModel::Markov2: {
      const double r1 = m.rho1;
      const double r2 = m.rho2;
      return m.sigma * std::sqrt((1.0 - r2) / ((1.0 + r2) * ((1.0 - r2) * (1.0 - r2) - r1 * r1)));
    }
  }
  return m.sigma;
}

std::vector<double> generate_noise(const NoiseModel& m, std::size_t n, std::mt19937_64& rng) {
  validate_noise_model(m);
  // A fresh distribution per call: no cached deviate leaks between series.
  std::normal_distribution<double> normal(0.0, 1.0);
  double prev1 = 0.0;  // ε_{i−1}
  double prev2 = 0.0;  // ε_{i−2}
  if (m.kind == NoiseModel::Markov1) {
    prev1 = m.sigma_initial * normal(rng);  // X_0
  } else if (m.kind == NoiseModel::Markov2) {
    prev1 = m.sigma_initial * normal(rng);  // X_1 = ε_0
    prev2 = m.sigma_initial * normal(rng);  // X_2 = ε_{−1}
  }
  std::vector<double> eps(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = m.sigma * normal(rng);
    double e = delta;
    if (m.kind == NoiseModel::Markov1) e += m.rho1 * prev1;
    if (m.kind == NoiseModel::Markov2) e += m.rho1 * prev1 + m.rho2 * prev2;
    eps[i] = e;
    prev2 = prev1;
    prev1 = e;
  }
  return eps;
}

// ---------------------------------------------------------------------------
// Tracking and zero position
// ---------------------------------------------------------------------------

TrackingSeries simulate_tracking_series(const TrackingSimulation& sim, std::uint64_t seed) {
  validate_tracking(sim);
  TrackingSeries out;
  out.readings_rad =
      reversal_series(sim.centre_rad, sim.amplitude_rad, sim.kappa, sim.reversals,
                      sim.reading_noise, seed);
  for (double& r : out.readings_rad) r = wrap_positive_rad(r);
  if (sim.period_s > 0.0) {
    out.times_s.resize(out.readings_rad.size());
    for (std::size_t i = 0; i < out.times_s.size(); ++i)
      out.times_s[i] = sim.t0_s + static_cast<double>(i + 1) * sim.period_s / 2.0;
  }
  return out;
}

std::vector<double> simulate_tracking(const TrackingSimulation& sim, std::uint64_t seed) {
  return simulate_tracking_series(sim, seed).readings_rad;
}

std::vector<double> simulate_zero_position(double alpha_p_div, double amplitude_div, double kappa,
                                           int n, const NoiseModel& noise_div,
                                           std::uint64_t seed) {
  return reversal_series(alpha_p_div, amplitude_div, kappa, n, noise_div, seed);
}

// ---------------------------------------------------------------------------
// Non-tracking
// ---------------------------------------------------------------------------

double nontracking_reading_div(const NonTrackingSimulation& sim, double t_s) {
  require_finite(sim.beta_div, "beta_div");
  require_positive(sim.amplitude_div, "amplitude_div");
  require_positive(sim.period_s, "period_s (T_B)");
  require_finite(sim.t0_s, "t0_s");
  require_nonnegative(sim.damping_per_s, "damping_per_s");
  return Oscillation(sim).value(t_s);
}

NonTrackingObservations simulate_nontracking(const NonTrackingSimulation& sim, std::uint64_t seed) {
  validate_nontracking(sim);
  const Oscillation osc(sim);
  NonTrackingObservations obs;

  for (double level : sim.levels_div)
    obs.crossings.push_back(time_level(osc, level, sim.crossings_per_level, sim.start_time_s));

  // Timing noise in stopwatch order: coloured noise correlates consecutive
  // presses, whichever graduation they belong to.
  std::vector<std::pair<double, std::pair<std::size_t, std::size_t>>> order;
  for (std::size_t l = 0; l < obs.crossings.size(); ++l)
    for (std::size_t i = 0; i < obs.crossings[l].times_s.size(); ++i)
      order.push_back({obs.crossings[l].times_s[i], {l, i}});
  std::sort(order.begin(), order.end());
  std::mt19937_64 time_rng = make_stream(seed, 1);
  const std::vector<double> dt = generate_noise(sim.time_noise, order.size(), time_rng);
  for (std::size_t j = 0; j < order.size(); ++j)
    obs.crossings[order[j].second.first].times_s[order[j].second.second] += dt[j];
  for (const Crossing& c : obs.crossings)
    for (std::size_t i = 1; i < c.times_s.size(); ++i)
      if (!(c.times_s[i] > c.times_s[i - 1]))
        throw InputError(fmt::format(
            "time_noise: timing noise made the passages of level {:g} div non-increasing "
            "(passage {} at {:g} s, passage {} at {:g} s); reduce the timing σ",
            c.level_div, i, c.times_s[i - 1], i + 1, c.times_s[i]));

  const auto n_rev = static_cast<std::size_t>(sim.reversals);
  std::mt19937_64 reading_rng = make_stream(seed, 2);
  const std::vector<double> da = generate_noise(sim.reading_noise, n_rev, reading_rng);
  const long m0 = osc.first_turning_at_or_after(sim.start_time_s);
  for (std::size_t j = 0; j < n_rev; ++j) {
    const double t = osc.turning_time(m0 + static_cast<long>(j));
    obs.reversals_div.push_back(osc.value(t) + da[j]);
    if (sim.record_reversal_times) obs.reversal_times_s.push_back(t);
  }

  if (sim.known_period_s) obs.period_s = Uncertain{*sim.known_period_s, sim.known_period_sigma_s};
  if (sim.reported_sigma_time_s) {
    obs.sigma_time_s = *sim.reported_sigma_time_s;
  } else if (const double s = stationary_sigma(sim.time_noise); s > 0.0) {
    obs.sigma_time_s = s;
  }
  if (sim.reported_sigma_reading_div) {
    obs.sigma_reading_div = *sim.reported_sigma_reading_div;
  } else if (const double s = stationary_sigma(sim.reading_noise); s > 0.0) {
    obs.sigma_reading_div = s;
  }
  return obs;
}

NonTrackingSimulation nontracking_simulation_from_physics(NonTrackingSimulation base,
                                                          const PhysicalGyro& gyro,
                                                          double latitude_rad,
                                                          double latitude_limit_rad) {
  base.period_s = periods_from_physics(gyro, latitude_rad, latitude_limit_rad).nontracking_s;
  return base;
}

TrackingSimulation tracking_simulation_from_physics(TrackingSimulation base,
                                                    const PhysicalGyro& gyro, double latitude_rad,
                                                    double latitude_limit_rad) {
  base.period_s = periods_from_physics(gyro, latitude_rad, latitude_limit_rad).tracking_s;
  return base;
}

double beta_for_north(double north_rad, double clamp_rad, const Instrument& inst,
                      double zero_position_div) {
  require_finite(north_rad, "north_rad");
  require_finite(clamp_rad, "clamp_rad");
  require_positive(inst.scale_value_rad, "scale value τ");
  require_nonnegative(inst.torsion_ratio.value, "torsion ratio λ");
  require_finite(zero_position_div, "zero_position_div");
  const double lam = inst.torsion_ratio.value;
  const double tau = inst.scale_value_rad;
  const double dn = wrap_signed_rad(north_rad - clamp_rad);
  return (dn + lam * tau * zero_position_div) / ((1.0 + lam) * tau);
}

double tracking_centre_for_north(double north_rad, const Instrument& inst,
                                 double zero_position_div) {
  require_finite(north_rad, "north_rad");
  require_positive(inst.scale_value_rad, "scale value τ");
  require_nonnegative(inst.torsion_ratio.value, "torsion ratio λ");
  require_finite(zero_position_div, "zero_position_div");
  return wrap_positive_rad(north_rad +
                           inst.torsion_ratio.value * inst.scale_value_rad * zero_position_div);
}

}  // namespace meridian::gyro
