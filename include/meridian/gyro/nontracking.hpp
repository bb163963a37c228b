#pragma once
/// \file nontracking.hpp
/// Non-tracking (alidade clamped) reductions of a gyro-theodolite
/// oscillation (gyro-theodolite spec §4): transit, time-difference, direct
/// solution, timed-amplitude I and II. Each turns timed crossings and
/// reversal readings into the equilibrium scale reading β with a σ
/// propagated from the observation σ and the constants' σ.
///
/// Model (N1), damping neglected: a(t) = β + B·sin(2π(t − t0)/T_B).
/// Scale readings in divisions (div), positive east; times in seconds.

#include <optional>
#include <string>
#include <vector>

#include "meridian/gyro/instrument.hpp"

namespace meridian::gyro {

/// Timed passages of the light mark over one scale graduation.
struct Crossing {
  double level_div = 0.0;          ///< the graduation a (div)
  std::vector<double> times_s;     ///< consecutive passages, strictly increasing (s)
  /// Direction of motion at times_s[0]: +1 east (increasing scale reading),
  /// −1 west. Consecutive passages of one level alternate direction.
  int first_direction = +1;
};

/// Everything observed in one non-tracking determination.
struct NonTrackingObservations {
  std::vector<Crossing> crossings;
  std::vector<double> reversals_div;       ///< reversal (turning-point) readings, alternating
  std::vector<double> reversal_times_s;    ///< optional, same length as reversals_div when given
  std::optional<Uncertain> period_s;       ///< T_B when known (s)
  double sigma_time_s = kDefaultSigmaTime_s;               ///< per-determination timing σ (s)
  double sigma_reading_div = kDefaultSigmaReading_div;         ///< per-determination reading σ (div)
};

/// The transit and time-difference results of a run warn when their
/// approximation error carried to N_G exceeds this fraction of the run's
/// σ(N_G) (small_angle_warning): an error of 0.1 σ moves the result by a
/// tenth of its σ and the total error √(σ² + e²) by 0.5 %.
inline constexpr double kSmallAngleWarningFraction = 0.1;
/// ... and exceeds this (arcsec): spec §8.1's tolerance for exact methods, so
/// that data with σ = 0 do not warn about rounding-level errors.
inline constexpr double kSmallAngleWarningFloorArcsec = 0.01;

/// The simple (closed-form) methods.
enum class NonTrackingMethod {
  Transit,          ///< §4.1, level-0 crossings + amplitude from reversals
  TimeDifference,   ///< §4.2, two levels, small-angle form
  Direct,           ///< §4.3, two levels, exact, T_B known
  TimedAmplitude1,  ///< §4.4
  TimedAmplitude2,  ///< §4.5
  LeastSquares,     ///< §4.6, unified fit of all observations (unified_fit.hpp)
};

/// Name used in files and reports: "transit", "time-difference", "direct",
/// "timed-amplitude-1", "timed-amplitude-2", "lsq".
std::string to_string(NonTrackingMethod m);
/// Inverse of to_string; throws InputError listing the accepted names.
NonTrackingMethod nontracking_method_from_string(const std::string& name);

/// Result of one reduction.
struct BetaResult {
  NonTrackingMethod method = NonTrackingMethod::Transit;
  Uncertain beta_div;                  ///< β and σ(β) (div)
  /// For the transit method only: ΔN = c·B·Δt in radians with σ, where c is
  /// the calibrated factor when the instrument has one, else
  /// (1+λ)·τ·π/(2T_B). Empty for other methods.
  std::optional<Uncertain> transit_delta_n_rad;
  /// Transit only: the time difference d·Δt (s) with d the direction of the
  /// first transit, i.e. signed as for an eastward first transit, so that
  /// β ≈ π·B·Δt/(2T_B) and ΔN = c·B·Δt (Δt = 4u for n > 3 transits).
  std::optional<Uncertain> time_difference_s;
  /// Estimated approximation error of the method for these data,
  /// β_method − β_exact (div), computed from the implied B and T_B; 0 for
  /// exact methods. Small-angle methods are within this of the truth.
  double approximation_error_div = 0.0;
  std::optional<Uncertain> amplitude_div;   ///< B implied/used (div)
  std::optional<Uncertain> period_s;        ///< T_B implied/used (s)
  /// Transit with period_s booked: T_B that the transit times alone imply (s, with σ), which
  /// the campaign holds the booked period to.
  std::optional<Uncertain> period_from_passages_s;
  std::vector<std::string> warnings;        ///< e.g. transit times against period_s
  std::vector<std::string> assumptions;     ///< e.g. "k = 0 (damping neglected)"
};

/// Check observations that every method relies on: finite values, σ ≥ 0,
/// first_direction ±1, strictly increasing times, alternating reversals,
/// reversal_times_s matching reversals_div, T_B > 0. Throws InputError
/// naming the field, e.g. "crossings[1].times_s: times must increase
/// (t2 = 35.2 ≤ t1 = 50.9)". Called by reduce_nontracking and fit_nontracking.
void validate_nontracking(const NonTrackingObservations& obs);

/// Run one simple method (or, for LeastSquares, fit_nontracking with
/// default options). σ(β) is the first-order propagation of σ_t (every
/// time), σ_a (every reversal reading; levels are exact graduations) and
/// σ(T_B); ΔN of the transit method also carries σ(λ), σ(τ) or σ(c).
/// For N_G from the transit method with a calibrated c use
/// north_from_delta(transit_delta_n_rad); otherwise north_from_nontracking(β).
/// Throws InputError naming the missing or bad
/// observation (e.g. "crossings: the time-difference method needs two levels
/// with three crossings each") and NumericalError where the data admit no
/// solution (a level the light mark never reaches).
BetaResult reduce_nontracking(NonTrackingMethod method, const NonTrackingObservations& obs,
                              const Instrument& inst);

/// The methods applicable to these observations (those whose inputs are
/// present), in the order of the enum. LeastSquares is listed when
/// unified_fit_applicable(obs) holds.
std::vector<NonTrackingMethod> applicable_methods(const NonTrackingObservations& obs);

/// Time difference of three consecutive crossings: Δt = −t1 + 2t2 − t3 (s).
double time_difference_s(double t1, double t2, double t3);

/// The small-angle warning of a transit or time-difference result `r` of one
/// run: `error_rad` is its approximation error carried to N_G (radians,
/// (1+λ)·τ·r.approximation_error_div), `sigma_rad` the run's σ(N_G)
/// (radians). Returns the warning naming the method when |error_rad| >
/// kSmallAngleWarningFraction·sigma_rad and > kSmallAngleWarningFloorArcsec,
/// else an empty string. reduce_determination adds it to the result's
/// warnings; reduce_nontracking only reports the error.
std::string small_angle_warning(const BetaResult& r, double error_rad, double sigma_rad);

/// Empirical transit factor c from two clamp positions (spec §4.1):
/// c = (N′₂ − N′₁)/(B₁·Δt₁ − B₂·Δt₂), radians per (div·s), with σ
/// propagated from σ(B), σ(Δt) given in the arguments.
Uncertain calibrate_transit_factor(double clamp1_rad, Uncertain amplitude1_div, Uncertain dt1_s,
                                   double clamp2_rad, Uncertain amplitude2_div, Uncertain dt2_s);

}  // namespace meridian::gyro
