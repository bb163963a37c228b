#pragma once
/// \file simulator.hpp
/// Simulated rotor-current series of model (M1) (maglev-gyro spec §4): for a
/// chosen α_1, K, b and latitude, each position's series is
///
///   I(t_i) = A·sin α_k + b + w_i + u_i + d·(t_i − t_0) + Σ bursts,
///   w_i ~ N(0, σ_w²) white, u_i = φ·u_{i−1} + N(0, σ_u²) (AR(1), started
///   stationary), d the drift (A/s),
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

struct NoiseSpec {
  std::size_t samples = 20000;
  double rate_hz = 100.0;
  double start_s = 0.0;
  double white_sigma_A = 1e-5;
  double ar1_phi = 0.0;      ///< AR(1) coefficient, |φ| < 1
  double ar1_sigma_A = 0.0;  ///< σ of the AR(1) innovation
  double drift_A_per_s = 0.0;
  std::vector<Burst> bursts;
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
/// azimuth α_j the position means follow the lines Ī_k = k_k·sin α_j + c_k
/// with c_k = I* − k_k·sin α*, so the lines meet at (α*, I*).
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

/// A determination as `maglev simulate` records it (and meridian.maglev.simulate): both positions
/// with the noise of `noise` (its bursts ignored), position 2 starting `pause_s` after position 1
/// ends, the bursts placed on their position's clock.
struct DeterminationSimulation {
  TwoPositionTruth truth;
  NoiseSpec noise;  ///< of both positions; position 1 starts at noise.start_s
  std::vector<PositionBurst> bursts;
  double pause_s = 30.0;
  std::uint64_t seed = 1;  ///< position 1; position 2 seed + 1
};

/// The noise of each position of `sim` (position 2's start and both positions' bursts placed).
/// Throws InputError for a burst of a position other than 1 or 2.
std::pair<NoiseSpec, NoiseSpec> position_noise(const DeterminationSimulation& sim);

/// simulate_determination(truth, position_noise(sim), seed).
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
