#pragma once
/// \file station_simulator.hpp
/// A simulated field book of one station: several determinations of one
/// mode with the same true gyro north, as `meridian gyro simulate --mode
/// non-tracking|tracking` writes them (docs/gyro-simulator.md). The result
/// is a ReduceInput, so it can be written (io::reduce_file_yaml) or reduced
/// directly, plus the truth in words for the file's header.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/reduce.hpp"
#include "meridian/gyro/simulator.hpp"

namespace meridian::gyro {

struct StationSimulation {
  Mode mode = Mode::NonTracking;
  int determinations = 1;                       ///< seeds seed, seed+1, …
  // Instrument and station.
  double scale_value_rad = 600.0 * units::kArcsecond;  ///< τ
  double torsion_ratio = 0.30;                  ///< λ at the station (ignored with `physics`)
  double latitude_rad = 34.2 * units::kDegree;  ///< station latitude φ
  /// Derive T_B and λ at the station from the physical description instead.
  std::optional<PhysicalGyro> physics;
  // Noise of every observed series (NoiseModel; σ = 0 gives noise-free
  // data, which then still carry the default σ as weights).
  NoiseModel::Kind noise = NoiseModel::White;
  double rho1 = 0.5, rho2 = 0.0;                ///< Markov coefficients
  double sigma_time_s = kDefaultSigmaTime_s;    ///< timing noise σ (s)
  double sigma_reading_div = kDefaultSigmaReading_div;  ///< scale reading noise σ (div)
  // Non-tracking truth (N1) and what is observed.
  double beta_div = -0.12, amplitude_div = 9.0, period_s = 440.0, t0_s = 50.0, damping_per_s = 0.0;
  std::vector<double> levels_div{-2.0, 0.0, 2.0};
  int crossings_per_level = 3, reversals = 2;
  double clamp_rad = 0.0;                       ///< N′ (β is the equilibrium reading for it)
  /// Further clamp readings, used in turn by determinations 2, 3, … (then
  /// again from N′): the same gyro north N_G = N′ + (1+λ)·τ·β seen from
  /// other clamps, as for calibrating the transit factor (east and west of
  /// north). Empty: every determination is clamped at N′.
  std::vector<double> other_clamps_rad;
  bool known_period = true;                     ///< write period_s into the file
  // Tracking truth (R1).
  double centre_rad = (12.0 * 60.0 + 34.0) * units::kArcsecond;  ///< M
  double tracking_amplitude_div = 8.0, kappa = 0.002;
  int tracking_reversals = 5;
  double sigma_tracking_rad = 0.0;              ///< circle reading noise σ (rad)
  /// σ_2 of the initial state(s) X of Markov tracking noise (gyro-stochastic spec §2–§3:
  /// ε = C·Δ + B·X, D(Δ_i) = σ_1² = sigma_tracking_rad², D(X) = σ_2²), rad, finite, ≥ 0.
  /// NaN (the default): σ_2 = σ_1. Ignored for white noise. The timing and scale-reading noise
  /// of non-tracking runs always have σ_2 = σ_1.
  double sigma_initial_tracking_rad = std::numeric_limits<double>::quiet_NaN();
};

struct SimulatedStation {
  ReduceInput input;
  /// The truth and how it was derived, one line each (for the file header).
  std::vector<std::string> truth;
};

/// Simulate the determinations (deterministic for a seed; see simulator.hpp).
/// Throws InputError for invalid parameters (simulator.hpp, constants.hpp).
SimulatedStation simulate_station(const StationSimulation& sim, std::uint64_t seed, Progress* progress = nullptr);

}  // namespace meridian::gyro
