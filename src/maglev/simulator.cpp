#include "meridian/maglev/simulator.hpp"

#include <cmath>
#include <random>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::maglev {

PositionSeries simulate_series(double mean_A, const NoiseSpec& spec, std::uint64_t seed) {
  if (spec.samples < 2 || !(spec.rate_hz > 0.0))
    throw InputError("the simulator needs ≥ 2 samples and a rate > 0");
  if (!(spec.white_sigma_A >= 0.0) || !(spec.ar1_sigma_A >= 0.0))
    throw InputError("noise σ must be ≥ 0");
  if (!(std::abs(spec.ar1_phi) < 1.0))
    throw InputError("the AR(1) coefficient must be within (−1, 1)");
  if (spec.settling_A != 0.0 && !(spec.settling_tau_s > 0.0))
    throw InputError("the settling time constant must be > 0");
  const double last_s = spec.start_s + static_cast<double>(spec.samples - 1) / spec.rate_hz;
  for (const auto& b : spec.bursts) {
    if (!(b.end_s > b.begin_s) || b.frequency_begin_hz < 0.0 || b.frequency_end_hz < 0.0)
      throw InputError(fmt::format("burst [{} s, {} s) is empty or has a negative frequency",
                                   b.begin_s, b.end_s));
    // A burst that touches no sample would be silently absent from the series.
    if (b.end_s <= spec.start_s || b.begin_s > last_s)
      throw InputError(fmt::format("burst [{} s, {} s) lies outside the series [{} s, {} s]",
                                   b.begin_s, b.end_s, spec.start_s, last_s));
  }
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  PositionSeries s;
  s.time_s.resize(spec.samples);
  s.current_A.resize(spec.samples);
  const double dt = 1.0 / spec.rate_hz;
  double u = spec.ar1_sigma_A > 0.0
                 ? n01(rng) * spec.ar1_sigma_A / std::sqrt(1.0 - spec.ar1_phi * spec.ar1_phi)
                 : 0.0;
  for (std::size_t i = 0; i < spec.samples; ++i) {
    const double t = spec.start_s + static_cast<double>(i) * dt;
    s.time_s[i] = t;
    if (i > 0) u = spec.ar1_phi * u + spec.ar1_sigma_A * n01(rng);
    const double w = spec.white_sigma_A * n01(rng);
    const double td = t - spec.drift_origin_s.value_or(spec.start_s);
    double v = mean_A + w + u + spec.drift_A_per_s * td + spec.drift_quadratic_A_per_s2 * td * td;
    if (spec.settling_A != 0.0) v += spec.settling_A * std::exp(-(t - spec.start_s) / spec.settling_tau_s);
    for (const Step& st : spec.steps)
      if (t >= st.time_s) v += st.size_A;
    for (const auto& b : spec.bursts) {
      if (t < b.begin_s || t >= b.end_s) continue;
      const double len = b.end_s - b.begin_s;
      const double tau = t - b.begin_s;
      // Linear chirp: phase = 2π(f0·τ + (f1 − f0)·τ²/(2·len)).
      const double phase = 2.0 * units::kPi *
                           (b.frequency_begin_hz * tau +
                            (b.frequency_end_hz - b.frequency_begin_hz) * tau * tau / (2.0 * len));
      const double edge = 0.1 * len;
      double env = 1.0;
      if (tau < edge) env = 0.5 * (1.0 - std::cos(units::kPi * tau / edge));
      if (len - tau < edge) env = 0.5 * (1.0 - std::cos(units::kPi * (len - tau) / edge));
      v += env * (b.offset_A + b.amplitude_A * std::sin(phase));
    }
    s.current_A[i] = v;
  }
  return s;
}

ReduceInput simulate_determination(const TwoPositionTruth& truth, const NoiseSpec& spec1,
                                   const NoiseSpec& spec2, std::uint64_t seed) {
  ReduceInput in;
  in.scale_A_s_per_rad = {truth.scale_A_s_per_rad, 0.0};
  in.latitude_rad = truth.latitude_rad;
  in.circle_reading1_rad = {truth.circle_reading1_rad, 0.0};
  const double A =
      truth.scale_A_s_per_rad * units::kEarthRotationRate_rad_s * std::cos(truth.latitude_rad);
  const double s = std::sin(truth.alpha1_rad);
  in.position1 = simulate_series(A * s + truth.bias_A, spec1, seed);
  in.position2 = simulate_series(-A * s + truth.bias_A, spec2, seed + 1);
  return in;
}

CalibrationInput simulate_calibration(const CalibrationTruth& truth, const NoiseSpec& spec,
                                      std::uint64_t seed) {
  CalibrationInput in;
  in.latitude_rad = truth.latitude_rad;
  const double is = truth.constant_deviation_A;
  std::uint64_t s = seed;
  for (double a : truth.azimuths_rad) {
    const double sn = std::sin(a - truth.best_azimuth_rad);
    const auto p1 = simulate_series(truth.slope1_A * sn + is, spec, s++);
    const auto p2 = simulate_series(truth.slope2_A * sn + is, spec, s++);
    const auto m1 = mean_with_autocorrelation(p1.current_A);
    const auto m2 = mean_with_autocorrelation(p2.current_A);
    in.setups.push_back({a, {m1.mean, m1.sigma}, {m2.mean, m2.sigma}});
  }
  return in;
}

namespace {
// A burst [begin, end) or a step at `begin` touches the block [first, last].
bool touches(double begin, double end, const NoiseSpec& b) {
  const double last = b.start_s + static_cast<double>(b.samples - 1) / b.rate_hz;
  return end > b.start_s && begin <= last;
}
}  // namespace

std::vector<std::pair<int, NoiseSpec>> block_noise(const DeterminationSimulation& sim) {
  const NoiseSpec& n = sim.noise;
  bool has1 = false, has2 = false;
  for (int p : sim.sequence) {
    if (p != 1 && p != 2)
      throw InputError(fmt::format("a block of position {} (1 or 2)", p));
    (p == 1 ? has1 : has2) = true;
  }
  if (!has1 || !has2) throw InputError("the sequence of blocks needs both positions");
  std::vector<std::pair<int, NoiseSpec>> blocks;
  double start = n.start_s, first[2] = {NAN, NAN};
  for (int p : sim.sequence) {
    NoiseSpec b = n;
    b.bursts.clear();
    b.steps.clear();
    b.start_s = start;
    if (!sim.drift_restarts) b.drift_origin_s = n.start_s;
    b.settling_A = p == 1 ? n.settling_A : -n.settling_A;
    if (std::isnan(first[p - 1])) first[p - 1] = start;
    blocks.emplace_back(p, b);
    start += static_cast<double>(n.samples) / n.rate_hz + sim.pause_s;
  }
  for (const PositionBurst& pb : sim.bursts) {
    if (pb.position != 1 && pb.position != 2)
      throw InputError(fmt::format("a burst of position {} (1 or 2)", pb.position));
    Burst burst = pb.burst;
    burst.begin_s += first[pb.position - 1];
    burst.end_s += first[pb.position - 1];
    bool placed = false;
    for (auto& [p, b] : blocks)
      if (p == pb.position && touches(burst.begin_s, burst.end_s, b)) {
        b.bursts.push_back(burst);
        placed = true;
      }
    if (!placed)
      throw InputError(fmt::format("burst [{} s, {} s) of position {} lies outside the series",
                                   pb.burst.begin_s, pb.burst.end_s, pb.position));
  }
  for (const PositionStep& ps : sim.steps) {
    if (ps.position != 1 && ps.position != 2)
      throw InputError(fmt::format("a step of position {} (1 or 2)", ps.position));
    Step st = ps.step;
    st.time_s += first[ps.position - 1];
    bool placed = false;
    for (auto& [p, b] : blocks) {
      if (p != ps.position) continue;
      const double last = b.start_s + static_cast<double>(b.samples - 1) / b.rate_hz;
      if (st.time_s <= last) {
        b.steps.push_back(st);
        placed = true;
      }
    }
    if (!placed)
      throw InputError(fmt::format("step at {} s of position {} comes after its last sample",
                                   ps.step.time_s, ps.position));
  }
  return blocks;
}

std::pair<NoiseSpec, NoiseSpec> position_noise(const DeterminationSimulation& sim) {
  const auto blocks = block_noise(sim);
  std::optional<NoiseSpec> s[2];
  for (const auto& [p, b] : blocks)
    if (!s[p - 1]) s[p - 1] = b;
  return {*s[0], *s[1]};
}

ReduceInput simulate_determination(const DeterminationSimulation& sim) {
  const TwoPositionTruth& t = sim.truth;
  ReduceInput in;
  in.scale_A_s_per_rad = {t.scale_A_s_per_rad, 0.0};
  in.latitude_rad = t.latitude_rad;
  in.circle_reading1_rad = {t.circle_reading1_rad, 0.0};
  const double A = t.scale_A_s_per_rad * units::kEarthRotationRate_rad_s * std::cos(t.latitude_rad);
  const double m = A * std::sin(t.alpha1_rad);
  std::uint64_t seed = sim.seed;
  for (const auto& [p, b] : block_noise(sim)) {
    const PositionSeries s = simulate_series(p == 1 ? m + t.bias_A : -m + t.bias_A, b, seed++);
    PositionSeries& into = p == 1 ? in.position1 : in.position2;
    into.time_s.insert(into.time_s.end(), s.time_s.begin(), s.time_s.end());
    into.current_A.insert(into.current_A.end(), s.current_A.begin(), s.current_A.end());
  }
  return in;
}

CalibrationTruth calibration_truth(const CalibrationSimulation& sim) {
  CalibrationTruth t;
  t.azimuths_rad = sim.azimuths_rad;
  const double A =
      sim.scale_A_s_per_rad * units::kEarthRotationRate_rad_s * std::cos(sim.latitude_rad);
  t.slope1_A = A * sim.slope_ratio1;
  t.slope2_A = -A * sim.slope_ratio2;
  t.best_azimuth_rad = sim.best_azimuth_rad;
  t.constant_deviation_A = sim.constant_deviation_A;
  t.latitude_rad = sim.latitude_rad;
  return t;
}

CalibrationInput simulate_calibration(const CalibrationSimulation& sim) {
  return simulate_calibration(calibration_truth(sim), sim.noise, sim.seed);
}

}  // namespace meridian::maglev
