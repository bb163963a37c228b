#pragma once
/// \file simulator.hpp
/// Simulated lines for the dynamic DOV workflow (shared/spec/deflection.md §7): a carrier moving
/// at constant speed V and heading over a deflection field, with the two attitude solutions
/// built geometrically, so that the sign conventions of model.hpp are tested, not assumed.
///
/// Per sample t_k = start_time_s + k/rate_hz, k = 0 … ⌊duration·rate⌋:
/// * track: constant heading α (clockwise from north) and speed V on the WGS84 ellipsoid,
///   φ += V·cos α·Δt/M(φ), λ += V·sin α·Δt/(N(φ)·cos φ) at the step's start (a rhumb line to
///   first order), constant height;
/// * model deflection (η_G, ξ_G) = SimulationOptions::model_field(φ, λ, h) (default
///   synthetic_model_deflection);
/// * true deflection η = η_G + δη, ξ = ξ_G + δξ with (x_E, δη), (x_N, δξ) independent
///   second-order Gauss–Markov processes of model.hpp with truth_model's ζ (< 1), σ and λ,
///   started from their stationary distribution diag(σ²/ω₀², σ²) and stepped with the closed
///   form of the damped oscillator: with a = ζω₀, ω_d = ω₀√(1 − ζ²), c = cos ω_dΔt,
///   s = sin ω_dΔt, Φ = e^{−aΔt}·[[c + (a/ω_d)s, s/ω_d], [−(ω₀²/ω_d)s, c − (a/ω_d)s]] and
///   Q_d = P∞ − Φ·P∞·Φᵀ (exact for a stationary process; independent of filter's Van Loan).
///   Stationary carrier (V < stationary_speed_m_s): δ constant, drawn N(0, σ²), x frozen,
///   drawn N(0, (σ·1 s)²) (initial_estimate's convention);
/// * LGU/GNSS attitude error φ (psi-angle, attitude_difference.hpp) from φ(0) =
///   initial_attitude_error_rad by the exact solution of φ̇ = −Ω×φ − ε_U·e_U over each step
///   (Ω = ω_ie(0, cos L, sin L), L at the step's mid-point, plus with
///   SimulationOptions::transport_rate the track's exact transport rate
///   ω_en = (−L̇, λ̇·cos L, λ̇·sin L) = (−V·cos α/M, V·sin α/N, V·sin α·tan L/N) at that point
///   (model.hpp); with ω = |Ω|, u = Ω/ω and Rodrigues:
///   φ_{k+1} = exp(−[Ω×]Δt)·φ_k − J·ε_U·e_U, J = Δt·I − ((1 − cos ωΔt)/ω)[u×] +
///   (Δt − sin(ωΔt)/ω)[u×]²); ε_U constant;
/// * body attitude C_b^n: heading α about up, a 1° pitch oscillation (period 37 s) about east
///   and a 2° roll oscillation (period 11 s) about north; it cancels from the difference;
/// * n′: the rotation C_{n′}^n that turns the ellipsoid normal e_U into the exact astronomic
///   zenith u′ = geodesy::astronomic_zenith_enu({ξ, η}, φ) by the shortest path (so
///   C_{n′}^n·e_U = u′ ≈ (η, ξ, 1));
/// * LGU/GNSS C_b^n = exp(−[φ×])·C_b^n; INS/GNSS C_b^{n′} = exp(−[v×])·(C_{n′}^n)ᵀ·C_b^n with
///   v = (v_E, v_N, v_U) white, N(0, sigma_ins_rad²) each.
///
/// Sources: spec §7; the damped oscillator's transition matrix and Q_d = P∞ − ΦP∞Φᵀ of a
/// stationary process (the discrete Lyapunov equation; Gelb 1974, ch. 3 and 4); Rodrigues'
/// formula: Barfoot (2017), ch. 7.
///
/// Deterministic for a seed (std::mt19937_64 and std::normal_distribution: the same series on
/// one standard library). Units SI and radians.
/// Errors: InputError (field "simulation.<name>") for a non-finite or out-of-range option:
/// rate ≤ 0, duration < 1/rate, V < 0, σ < 0, ζ ≥ 1 or ≤ 0, |start latitude| ≥ 89°, a model
/// field that returns a non-finite value; geodesy's InputError if the track leaves ±89°.

#include <cstdint>
#include <functional>

#include <Eigen/Core>

#include "meridian/core/units.hpp"
#include "meridian/dov/deflection.hpp"

namespace meridian::dov {

/// A model deflection (η_G, ξ_G) in rad as a function of geodetic latitude, longitude (rad) and
/// height (m).
using ModelField = std::function<EtaXi(double lat_rad, double lon_rad, double height_m)>;

/// A smooth synthetic "global model" deflection for tests and examples (rad):
///   ξ_G = 6″·sin(φ/0.004) + 2″·cos(λ/0.006),  η_G = 5″·cos(λ/0.005) − 3″·sin(φ/0.007)
/// (φ, λ in rad: wavelengths 2π·0.004 rad ≈ 160 km and longer), |ξ_G|, |η_G| ≤ 8″.
EtaXi synthetic_model_deflection(double lat_rad, double lon_rad, double height_m);

struct SimulationOptions {
  double start_lat_rad = 30.0 * units::kDegree;
  double start_lon_rad = 114.0 * units::kDegree;
  double height_m = 0.0;
  double heading_rad = 60.0 * units::kDegree;  ///< α, clockwise from north
  double speed_m_s = 5.0;                      ///< V ≥ 0
  double rate_hz = 1.0;                        ///< > 0
  double duration_s = 4.0 * 3600.0;            ///< ≥ 1/rate
  double start_time_s = 0.0;
  /// ζ, σ and λ of the true short-wavelength part (the model error δη, δξ); sigma_model_rad
  /// of 0 is allowed here (no model error: truth = model).
  ModelOptions truth_model;
  double eps_u_rad_s = 0.003 * units::kDegree / 3600.0;      ///< true ε_U (rad/s)
  Eigen::Vector3d initial_attitude_error_rad = Eigen::Vector3d::Zero();  ///< φ(0), (E, N, U)
  double sigma_ins_rad = 0.5 * units::kArcsecond;  ///< σ of v_E, v_N, v_U (white), ≥ 0
  ModelField model_field;                          ///< empty: synthetic_model_deflection
  /// The true attitude error also turns with the transport rate (file comment); false: Earth
  /// rate only, the spec's model. Options::transport_rate is the processing side.
  bool transport_rate = false;
  std::uint64_t seed = 1;
};

/// The simulated line: samples, truth (with the full true state of every sample) and default
/// Options (the caller sets them to match or mismatch the truth).
Input simulate(const SimulationOptions& options);

}  // namespace meridian::dov
