#pragma once
/// \file simulator.hpp
/// Simulated rotor-current series of model (M1) (maglev-gyro spec §4): for a
/// chosen α_1, K, b and latitude, each position's series is
///
///   I(t_i) = A·sin α_k + b + w_i + u_i + d·(t_i − t_d) + q·(t_i − t_d)² + Σ bursts
///            + s·exp(−(t_i − t_0)/τ) + Σ steps,
///   w_i ~ N(0, σ_w²) white, u_i = φ·u_{i−1} + N(0, σ_u²) (AR(1), started
///   stationary), d the drift (A/s), q its quadratic term (A/s²), t_d the drift's origin on the
///   common clock (default t_0: the series' start), s·exp(…) a settling transient after the
///   rotation, a step adding its size from its time on,
///
/// sampled at `rate_hz` from t_0 = start_s. A burst of interference over
/// [begin_s, end_s) adds offset_A + amplitude_A·sin(2π·∫f dt) whose
/// frequency sweeps linearly from f_begin to f_end (a vibration of varying
/// frequency with a disturbance torque), under a raised-cosine envelope
/// (rise and fall of 10 % of the burst each).
///
/// Deterministic for a seed (std::mt19937_64; the same seed gives the same
/// series on one standard library). Units: SI (A, s, Hz, rad).
/// Errors: InputError for a non-positive rate or sample count, σ < 0,
/// |φ| ≥ 1, a burst with end ≤ begin or a negative frequency, a burst that touches no
/// sample (its times are on the series' clock, which starts at start_s).

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "meridian/maglev/calibration.hpp"
#include "meridian/maglev/reduce.hpp"

namespace meridian::maglev {

struct Burst {
  double begin_s = 0.0, end_s = 0.0;
  double amplitude_A = 0.0;  ///< oscillation amplitude
  double offset_A = 0.0;     ///< mean shift while the burst lasts (at full envelope)
  double frequency_begin_hz = 1.0, frequency_end_hz = 5.0;
};

/// A step of the current (a mechanical or electrical jump): `size_A` from `time_s` on.
struct Step {
  double time_s = 0.0;
  double size_A = 0.0;
};

struct NoiseSpec {
  std::size_t samples = 20000;
  double rate_hz = 100.0;
  double start_s = 0.0;
  double white_sigma_A = 1e-5;
  double ar1_phi = 0.0;      ///< AR(1) coefficient, |φ| < 1
  double ar1_sigma_A = 0.0;  ///< σ of the AR(1) innovation
  double drift_A_per_s = 0.0;
  double drift_quadratic_A_per_s2 = 0.0;
  /// t_d of the drift on the common clock; unset: start_s (the drift starts with this series).
  std::optional<double> drift_origin_s;
  double settling_A = 0.0;      ///< settling transient amplitude at start_s
  double settling_tau_s = 20.0; ///< its time constant (> 0 when settling_A ≠ 0)
  std::vector<Burst> bursts;
  std::vector<Step> steps;      ///< times on the series' clock
};

/// The true determination.
struct TwoPositionTruth {
  double alpha1_rad = 0.0;
  double scale_A_s_per_rad = 8000.0;  ///< K
  double bias_A = 2e-4;               ///< b
  double latitude_rad = 0.6;          ///< φ
  double circle_reading1_rad = 0.0;   ///< r_1
};

/// `mean_A` plus the noise of `spec` (see the file comment).
PositionSeries simulate_series(double mean_A, const NoiseSpec& spec, std::uint64_t seed);

/// A whole determination: a ReduceInput (default options, σ(K) = σ(r_1) = 0)
/// with position 1 from spec1 (seed) and position 2 from spec2 (seed + 1).
ReduceInput simulate_determination(const TwoPositionTruth& truth, const NoiseSpec& spec1,
                                   const NoiseSpec& spec2, std::uint64_t seed);

/// A multi-angle calibration experiment (spec §2, §4): at each set-up
/// azimuth α_j the position means follow the exact curves of a misaligned
/// instrument Ī_k = k_k·sin(α_j − α*) + I*, which meet at (α*, I*).
struct CalibrationTruth {
  std::vector<double> azimuths_rad;   ///< α_j
  double slope1_A = 0.48;             ///< k_1 (A per unit sin α)
  double slope2_A = -0.48;            ///< k_2
  double best_azimuth_rad = 0.0;      ///< α*
  double constant_deviation_A = 0.0;  ///< I*
  double latitude_rad = 0.6;
};

/// Series of spec at every set-up (seeds seed, seed + 1, …), reduced to means
/// with σ by mean_with_autocorrelation. Throws as simulate_series.
CalibrationInput simulate_calibration(const CalibrationTruth& truth, const NoiseSpec& spec,
                                      std::uint64_t seed);

/// A burst of interference on one position, its times counted from the start of that
/// position's series.
struct PositionBurst {
  int position = 1;  ///< 1 or 2
  Burst burst;
};

/// A step of one position, its time counted from the start of that position's first block; it
/// stays for the rest of that position's samples.
struct PositionStep {
  int position = 1;  ///< 1 or 2
  Step step;
};

/// A determination as `maglev simulate` records it (and meridian.maglev.simulate): blocks of
/// `noise.samples` samples at the positions of `sequence` in time order (1-2, 1-2-1, 1-2-2-1,
/// 1-2-1-2, …), each starting `pause_s` after the one before ends, all on one clock starting at
/// noise.start_s. The drift of `noise` is continuous on that clock (origin noise.start_s, unless
/// `drift_restarts`: each block's drift from its own start, the old behaviour, which cancels).
/// After each rotation a settling transient +settling_A (position 1) or −settling_A (position 2)
/// decays with settling_tau_s. Bursts and steps are placed on their position's clock (from the
/// start of its first block).
struct DeterminationSimulation {
  TwoPositionTruth truth;
  NoiseSpec noise;  ///< of every block (its bursts and steps ignored); the clock starts at noise.start_s
  std::vector<PositionBurst> bursts;
  std::vector<PositionStep> steps;
  std::vector<int> sequence{1, 2};
  double pause_s = 30.0;
  bool drift_restarts = false;
  std::uint64_t seed = 1;  ///< block b (0-based) uses seed + b
};

/// The noise of every block of `sim` in time order (position, spec with its start, drift origin,
/// settling, bursts and steps placed). Throws InputError for a sequence without both positions or
/// with a position other than 1 or 2, a burst or step of another position, a burst or step that
/// touches no sample.
std::vector<std::pair<int, NoiseSpec>> block_noise(const DeterminationSimulation& sim);

/// The noise of each position's first block (block_noise).
std::pair<NoiseSpec, NoiseSpec> position_noise(const DeterminationSimulation& sim);

/// The blocks of block_noise simulated (block b with seed + b) and joined per position.
ReduceInput simulate_determination(const DeterminationSimulation& sim);

/// A calibration experiment as `maglev simulate --calibration-azimuths` describes it: the
/// slopes as ratios of the ideal ±A, A = K·ω_e·cos φ (k_1 = ratio1·A, k_2 = −ratio2·A).
struct CalibrationSimulation {
  std::vector<double> azimuths_rad;  ///< α_j
  double scale_A_s_per_rad = 8000.0;  ///< K
  double latitude_rad = 0.6;          ///< φ
  double slope_ratio1 = 1.0, slope_ratio2 = 1.0;
  double best_azimuth_rad = 0.0;      ///< α*
  double constant_deviation_A = 0.0;  ///< I*
  NoiseSpec noise;
  std::uint64_t seed = 1;
};

/// The lines of `sim`.
CalibrationTruth calibration_truth(const CalibrationSimulation& sim);

/// simulate_calibration(calibration_truth(sim), sim.noise, sim.seed).
CalibrationInput simulate_calibration(const CalibrationSimulation& sim);

}  // namespace meridian::maglev
