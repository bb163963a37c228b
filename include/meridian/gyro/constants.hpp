#pragma once
/// \file constants.hpp
/// Instrument-constant relations of a pendulous gyro-theodolite
/// (gyro-theodolite spec §1): directive torque, the tracking, non-tracking
/// and free (motor-off) periods, and the torsion ratio λ = D_B/D_K with its
/// dependence on latitude.
///
/// Relations implemented (J_z moment of inertia about the vertical, H spin
/// angular momentum, D_B tape torsion constant, ω_e Earth rotation rate):
///   D_K = H·ω_e·cos φ                  directive torque per radian
///   T_A = 2π·sqrt(J_z / D_K)           tracking period
///   T_F = 2π·sqrt(J_z / D_B)           free (motor-off) period
///   T_B = 2π·sqrt(J_z / (D_K + D_B))   non-tracking period
///   λ = D_B/D_K = (T_A/T_F)² = (T_A/T_B)² − 1
///   λ(φ) = λ(φ0)·cos φ0 / cos φ
///
/// Every function throws meridian::InputError for non-finite or out-of-range
/// input, with a message naming the offending quantity.

#include "meridian/core/units.hpp"
#include "meridian/gyro/instrument.hpp"

namespace meridian::gyro {

/// Default highest usable |latitude| (75°, radians). Near the poles the
/// directive torque ∝ cos φ vanishes and a gyro cannot find north.
inline constexpr double kDefaultLatitudeLimit_rad = 75.0 * units::kDegree;

/// Physical description of the sensitive element.
struct PhysicalGyro {
  /// H = J_x·Ω, spin angular momentum of the rotor (N·m·s, > 0).
  double spin_momentum_Nms = 0.0;
  /// J_z, moment of inertia of the suspended system about the vertical
  /// (kg·m², > 0).
  double moment_of_inertia_kgm2 = 0.0;
  /// D_B, torsion constant of the suspension tape (N·m/rad, > 0).
  double tape_torsion_Nm_per_rad = 0.0;
};

/// Periods and torque ratio of a gyro at one latitude.
struct GyroPeriods {
  double tracking_s = 0.0;                    ///< T_A (s)
  double nontracking_s = 0.0;                 ///< T_B (s), always < T_A
  double free_s = 0.0;                        ///< T_F, motor off (s)
  double torsion_ratio = 0.0;                 ///< λ = D_B/D_K (dimensionless)
  double directive_torque_Nm_per_rad = 0.0;   ///< D_K = H·ω_e·cos φ (N·m/rad)
};

/// Throw InputError when the latitude is not finite or |φ| exceeds the limit,
/// e.g. "latitude 80.0° is above the usable limit 75.0° (cos φ → 0)".
/// \param lat_rad station latitude φ (radians, positive north).
/// \param limit_rad highest usable |φ| (radians, in (0, π/2)); an invalid
///   limit is itself an InputError.
/// Latitudes exactly at the limit are accepted.
void check_latitude(double lat_rad, double limit_rad = kDefaultLatitudeLimit_rad);

/// Periods, λ and D_K from the physical description (spec §1).
/// \param gyro H, J_z, D_B; each must be finite and > 0.
/// \param latitude_rad station latitude φ (radians), checked with
///   check_latitude(latitude_rad, latitude_limit_rad).
/// \param latitude_limit_rad highest usable |φ| (radians).
GyroPeriods periods_from_physics(const PhysicalGyro& gyro, double latitude_rad,
                                 double latitude_limit_rad = kDefaultLatitudeLimit_rad);

/// λ = (T_A/T_F)² from the tracking period T_A and the free (motor-off)
/// period T_F, both in seconds, finite and > 0.
double torsion_ratio_from_free_period(double tracking_period_s, double free_period_s);

/// λ = (T_A/T_B)² − 1 from the tracking period T_A and the non-tracking
/// period T_B (seconds, finite, > 0, and T_B < T_A so that λ > 0).
double torsion_ratio_from_nontracking_period(double tracking_period_s,
                                             double nontracking_period_s);

/// As above with σ(λ) propagated to first order from σ(T_A), σ(T_F)
/// (independent, seconds, ≥ 0):
/// σ_λ² = (2T_A/T_F²·σ_A)² + (2T_A²/T_F³·σ_F)².
Uncertain torsion_ratio_from_free_period(Uncertain tracking_period_s, Uncertain free_period_s);

/// As above with σ(λ) from σ(T_A), σ(T_B) (independent, seconds, ≥ 0):
/// σ_λ² = (2T_A/T_B²·σ_A)² + (2T_A²/T_B³·σ_B)².
Uncertain torsion_ratio_from_nontracking_period(Uncertain tracking_period_s,
                                                Uncertain nontracking_period_s);

/// λ observed at latitude φ0 rescaled to latitude φ:
/// λ(φ) = λ(φ0)·cos φ0 / cos φ; σ scales by the same factor.
/// \param lambda0 λ(φ0) with σ (dimensionless, ≥ 0).
/// \param lat0_rad latitude of the calibration φ0 (radians).
/// \param lat_rad station latitude φ (radians).
/// \param latitude_limit_rad both latitudes are checked against it.
Uncertain rescale_torsion_ratio(Uncertain lambda0, double lat0_rad, double lat_rad,
                                double latitude_limit_rad = kDefaultLatitudeLimit_rad);

/// A transit factor c calibrated at latitude φ0 rescaled to latitude φ.
/// With c = (1+λ)·τ·π/(2T_B), T_B = 2π·sqrt(J_z/(D_K(1+λ))), D_K ∝ cos φ and
/// λ ∝ 1/cos φ (spec §1, §4.1):
///   c(φ) = c(φ0)·((1+λ)/(1+λ0))^{3/2}·sqrt(cos φ / cos φ0),  λ = λ0·cos φ0/cos φ.
/// The calibrated value keeps whatever the model does not describe; only the
/// latitude dependence of the model is applied. σ scales by the same factor
/// (the σ of λ0 changes the factor by far less than σ(c0) for any latitude
/// difference where a calibration is still used).
/// \param c0 c(φ0) with σ (rad/(div·s), > 0). \param lambda0 λ(φ0) (≥ 0).
/// \param lat0_rad, lat_rad latitudes φ0 and φ (radians), both checked against
/// `latitude_limit_rad`. Throws InputError for invalid values.
Uncertain rescale_transit_factor(Uncertain c0, double lambda0, double lat0_rad, double lat_rad,
                                 double latitude_limit_rad = kDefaultLatitudeLimit_rad);

}  // namespace meridian::gyro
