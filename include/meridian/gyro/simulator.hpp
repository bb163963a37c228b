#pragma once
/// \file simulator.hpp
/// Observation simulator for gyro-theodolites (gyro-theodolite spec §8):
/// tracking reversal readings (R1), zero-position (motor-off) reversal
/// readings, and non-tracking crossing times and reversal readings (N1),
/// with white or Markov-1/-2 coloured noise (gyro-stochastic spec §2–§3).
///
/// Determinism: every function that draws random numbers takes an explicit
/// 64-bit seed (or an engine) and uses std::mt19937_64 and
/// std::normal_distribution only; nothing global is touched. The same seed
/// gives the same series on the same standard library (libstdc++'s normal
/// algorithm is fixed; another library may give other, equally valid,
/// deviates).
///
/// Units: circle readings and angles in radians (normalised to [0, 2π) on
/// output), scale readings in divisions (div, positive east), times in
/// seconds.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "meridian/gyro/constants.hpp"
#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/nontracking.hpp"

namespace meridian::gyro {

// ---------------------------------------------------------------------------
// Noise
// ---------------------------------------------------------------------------

/// Error model of one observed series ε_1 … ε_n (gyro-stochastic spec §2–§3):
///   White:   ε_i = Δ_i
///   Markov1: ε_i = Δ_i + ρ1·ε_{i−1},              ε_0 = X_0
///   Markov2: ε_i = Δ_i + ρ1·ε_{i−1} + ρ2·ε_{i−2},  ε_0 = X_1, ε_{−1} = X_2
/// with Δ_i ~ N(0, sigma²) independent and the initial states X ~ N(0,
/// sigma_initial²) independent of Δ and of each other.
struct NoiseModel {
  enum Kind { White, Markov1, Markov2 };
  Kind kind = White;
  /// σ of the driving white noise Δ (unit of the quantity: rad, div or s;
  /// finite, ≥ 0). 0 gives noise-free data.
  double sigma = 0.0;
  /// ρ1, used by Markov1 and Markov2 (dimensionless). Markov1 needs |ρ1| < 1.
  double rho1 = 0.0;
  /// ρ2, used by Markov2 only; must be 0 for Markov1. Markov2 needs the AR(2)
  /// stationarity triangle ρ1 + ρ2 < 1, ρ2 − ρ1 < 1, |ρ2| < 1.
  double rho2 = 0.0;
  /// σ of the initial states X (same unit as sigma, finite, ≥ 0; unused for
  /// White). stationary_sigma() gives the value that makes a Markov-1
  /// series stationary from its first element.
  double sigma_initial = 0.0;

  static NoiseModel white(double sigma) { return {White, sigma, 0.0, 0.0, 0.0}; }
  static NoiseModel markov1(double sigma, double rho, double sigma_initial) {
    return {Markov1, sigma, rho, 0.0, sigma_initial};
  }
  static NoiseModel markov2(double sigma, double rho1, double rho2, double sigma_initial) {
    return {Markov2, sigma, rho1, rho2, sigma_initial};
  }
};

/// Throw InputError unless the model is usable: finite, σ ≥ 0, and the
/// Markov coefficients stationary (see NoiseModel).
void validate_noise_model(const NoiseModel& model);

/// Standard deviation of the stationary process ε (same unit as sigma):
/// White σ; Markov1 σ/sqrt(1 − ρ²); Markov2
/// σ·sqrt((1 − ρ2) / ((1 + ρ2)·((1 − ρ2)² − ρ1²))). Validates the model.
double stationary_sigma(const NoiseModel& model);

/// n noise values ε_1 … ε_n drawn from `rng`. Draw order (fixed, so series
/// are reproducible): Markov1 X_0; Markov2 X_1 then X_2; then Δ_1 … Δ_n.
/// Standard normal deviates are drawn and scaled, so the same engine state
/// gives proportional series for different σ. Throws InputError for an
/// invalid model (validate_noise_model).
std::vector<double> generate_noise(const NoiseModel& model, std::size_t n,
                                   std::mt19937_64& rng);

// ---------------------------------------------------------------------------
// Tracking mode and zero position: reversal-point series (R1)
// ---------------------------------------------------------------------------

/// Tracking reversal readings r_i = M + (−1)^i·A·e^{−iκ} + ε_i, i = 1 … n.
struct TrackingSimulation {
  double centre_rad = 0.0;      ///< M, centre of the tracked oscillation (circle reading, rad)
  double amplitude_rad = 0.0;   ///< A (rad, finite, ≥ 0); r_1 lies west of M (A·e^{−κ} less)
  double kappa = 0.0;           ///< κ = k·T_A/2, decay per half period (finite, ≥ 0)
  int reversals = 5;            ///< n ≥ 2
  NoiseModel reading_noise;     ///< errors of the circle readings (rad)
  /// T_A (s). When > 0 the reversal times t_i = t0 + i·T_A/2 are returned by
  /// simulate_tracking_series; 0 means "no times".
  double period_s = 0.0;
  double t0_s = 0.0;            ///< t0 (s), the time of the (unobserved) reading i = 0
};

/// Readings and, when a period is given, their times.
struct TrackingSeries {
  std::vector<double> readings_rad;   ///< r_1 … r_n, normalised to [0, 2π)
  std::vector<double> times_s;        ///< t_1 … t_n, empty when period_s = 0
};

/// Circle readings r_1 … r_n (radians in [0, 2π), so a series around north
/// wraps, e.g. 359°41′ and 0°44′). Throws InputError for invalid input.
std::vector<double> simulate_tracking(const TrackingSimulation& sim, std::uint64_t seed);

/// As simulate_tracking (identical readings for the same seed) plus times.
TrackingSeries simulate_tracking_series(const TrackingSimulation& sim, std::uint64_t seed);

/// Zero-position (motor off, alidade clamped) scale readings at the
/// reversals of the free oscillation: a_i = α_p + (−1)^i·A·e^{−iκ} + ε_i,
/// i = 1 … n, in divisions (not wrapped).
/// \param alpha_p_div tape zero position α_p (div).
/// \param amplitude_div A (div, ≥ 0).
/// \param kappa decay per half period (≥ 0).
/// \param n number of reversals (≥ 2).
/// \param noise_div reading errors (div).
std::vector<double> simulate_zero_position(double alpha_p_div, double amplitude_div, double kappa,
                                           int n, const NoiseModel& noise_div,
                                           std::uint64_t seed);

// ---------------------------------------------------------------------------
// Non-tracking mode (N1)
// ---------------------------------------------------------------------------

/// Non-tracking oscillation a(t) = β + B·e^{−k(t−t0)}·sin(2π(t − t0)/T_B)
/// and what to observe of it.
struct NonTrackingSimulation {
  double beta_div = 0.0;        ///< β, equilibrium scale reading (div, finite)
  double amplitude_div = 0.0;   ///< B at t0 (div, > 0)
  double period_s = 0.0;        ///< T_B (s, > 0)
  double t0_s = 0.0;            ///< t0, a passage of β moving east (s)
  double damping_per_s = 0.0;   ///< k (1/s, ≥ 0)
  /// Graduations to time (div, distinct, finite), e.g. {0}, {−2, +2},
  /// {−2, 0, +2}. May be empty when only reversals are wanted.
  std::vector<double> levels_div = {0.0};
  /// Consecutive passages to time per level (≥ 1), from the first passage at
  /// or after start_time_s.
  int crossings_per_level = 3;
  double start_time_s = 0.0;    ///< observation start (s)
  /// Reversal readings to record: the first `reversals` turning points at or
  /// after start_time_s (≥ 0).
  int reversals = 2;
  /// Record the exact turning-point times in reversal_times_s.
  bool record_reversal_times = true;
  NoiseModel time_noise;        ///< stopwatch errors (s), applied to all crossings in time order
  NoiseModel reading_noise;     ///< scale reading errors (div), applied to the reversals
  /// T_B to put into the observations as known (s); empty = period unknown.
  std::optional<double> known_period_s;
  double known_period_sigma_s = 0.0;   ///< its σ (s, ≥ 0)
  /// σ to write into the observations; empty = the stationary σ of the
  /// noise model when > 0, else the NonTrackingObservations defaults
  /// (0.1 s, 0.05 div), so noise-free data still carry realistic weights.
  std::optional<double> reported_sigma_time_s;
  std::optional<double> reported_sigma_reading_div;
};

/// Simulated observations, in the form the reductions consume.
/// * crossings: one Crossing per level, in the order of levels_div; times are
///   the exact roots of a(t) = level (bracketed between turning points and
///   solved to 1e-12 s, damping included) plus timing noise; first_direction
///   is +1 when a(t) increases at the first passage.
/// * reversals_div: a(t) at the exact turning points (ȧ = 0) plus reading
///   noise; reversal_times_s their exact times (no noise) when recorded.
/// Time noise and reading noise come from two independent streams derived
/// from `seed`, so changing the number of reversals does not change the
/// crossing times.
/// Throws InputError for invalid parameters, for a level the light mark
/// never reaches (|level − β| ≥ the amplitude at that time; the message
/// names the level), and when timing noise makes a level's times
/// non-increasing.
NonTrackingObservations simulate_nontracking(const NonTrackingSimulation& sim, std::uint64_t seed);

/// Exact (noise-free) model value a(t) of (N1) in div.
double nontracking_reading_div(const NonTrackingSimulation& sim, double t_s);

/// `base` with period_s = T_B derived from the physical description at the
/// given latitude (periods_from_physics; same errors).
NonTrackingSimulation nontracking_simulation_from_physics(
    NonTrackingSimulation base, const PhysicalGyro& gyro, double latitude_rad,
    double latitude_limit_rad = kDefaultLatitudeLimit_rad);

/// `base` with period_s = T_A derived from the physical description.
TrackingSimulation tracking_simulation_from_physics(
    TrackingSimulation base, const PhysicalGyro& gyro, double latitude_rad,
    double latitude_limit_rad = kDefaultLatitudeLimit_rad);

/// Equilibrium scale reading β (div) that makes a non-tracking determination
/// clamped at N′ give gyro north N_G: inverse of
/// N_G = N′ + (1+λ)·τ·β − λ·τ·α_p, with N_G − N′ taken in [−π, π).
/// \param north_rad N_G (rad). \param clamp_rad N′ (rad).
/// \param inst τ (> 0) and λ (≥ 0) are used. \param zero_position_div α_p (div).
double beta_for_north(double north_rad, double clamp_rad, const Instrument& inst,
                      double zero_position_div = 0.0);

/// Tracking centre M (rad in [0, 2π)) that gives gyro north N_G:
/// inverse of N_G = M − λ·τ·α_p.
double tracking_centre_for_north(double north_rad, const Instrument& inst,
                                 double zero_position_div = 0.0);

}  // namespace meridian::gyro
