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
    double v = mean_A + w + u + spec.drift_A_per_s * (t - spec.start_s);
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
  const double u = std::sin(truth.best_azimuth_rad);
  const double c1 = truth.constant_deviation_A - truth.slope1_A * u;
  const double c2 = truth.constant_deviation_A - truth.slope2_A * u;
  std::uint64_t s = seed;
  for (double a : truth.azimuths_rad) {
    const auto p1 = simulate_series(truth.slope1_A * std::sin(a) + c1, spec, s++);
    const auto p2 = simulate_series(truth.slope2_A * std::sin(a) + c2, spec, s++);
    const auto m1 = mean_with_autocorrelation(p1.current_A);
    const auto m2 = mean_with_autocorrelation(p2.current_A);
    in.setups.push_back({a, {m1.mean, m1.sigma}, {m2.mean, m2.sigma}});
  }
  return in;
}

std::pair<NoiseSpec, NoiseSpec> position_noise(const DeterminationSimulation& sim) {
  const NoiseSpec& n = sim.noise;
  std::pair<NoiseSpec, NoiseSpec> s{n, n};
  s.second.start_s = n.start_s + static_cast<double>(n.samples) / n.rate_hz + sim.pause_s;
  for (const PositionBurst& b : sim.bursts) {
    if (b.position != 1 && b.position != 2)
      throw InputError(fmt::format("a burst of position {} (1 or 2)", b.position));
    NoiseSpec& p = b.position == 1 ? s.first : s.second;
    Burst burst = b.burst;
    burst.begin_s += p.start_s;
    burst.end_s += p.start_s;
    p.bursts.push_back(burst);
  }
  return s;
}

ReduceInput simulate_determination(const DeterminationSimulation& sim) {
  const auto [s1, s2] = position_noise(sim);
  return simulate_determination(sim.truth, s1, s2, sim.seed);
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
