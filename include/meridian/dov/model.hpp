#pragma once
/// \file model.hpp
/// The 8-state error and deflection model of the dynamic DOV method (shared/spec/deflection.md
/// §3–4): named state, noise and observation indices, the continuous model with the
/// second-order Gauss–Markov model error of the global gravity model, its discretisation, the
/// observation matrix and the initial estimate.
///
/// State x = [φ_E, φ_N, φ_U, ε_U, x_E, x_N, δη, δξ]ᵀ (State below), axes of the geodetic ENU
/// frame n (geodesy/frames.hpp):
/// * φ_E, φ_N, φ_U (rad): LGU/GNSS attitude errors in the psi-angle convention
///   (attitude_difference.hpp: computed C_b^n = (I − [φ×])·true C_b^n);
/// * ε_U (rad/s): equivalent vertical gyro bias, a random constant (ε̇_U = 0), with the sign
///   fixed by the dynamics below;
/// * x_E, x_N (rad·s): the intermediate states of the Gauss–Markov processes, ẋ_E = δη;
/// * δη, δξ (rad): errors of the model deflection, η = η_G + δη, ξ = ξ_G + δξ.
///
/// Dynamics, moving carrier (V ≥ ModelOptions::stationary_speed_m_s), Earth rate only
/// (Ω = ω_ie·(0, cos L, sin L) in ENU, L the geodetic latitude; φ̇ = −Ω×φ − ε_U·e_U):
///   φ̇_E =  ω_ie sin L·φ_N − ω_ie cos L·φ_U
///   φ̇_N = −ω_ie sin L·φ_E
///   φ̇_U =  ω_ie cos L·φ_E − ε_U
///   ε̇_U = 0
///   ẋ_E = δη,  δη̇ = −ω₀²·x_E − 2ζω₀·δη + w_E     (x_N, δξ, w_N likewise)
/// with ω₀ = 2π·V/λ (λ = ModelOptions::correlation_length_m, 10 km) and E[w_E(t)w_E(τ)] =
/// q·δ(t − τ), q = σ²·4ζω₀, so that δη, δξ are stationary with standard deviation σ (the
/// stationary covariance of (x, δ) is diag(σ²/ω₀², σ²)).
///
/// Transport rate (optional, Options::transport_rate): Ω = ω_ie + ω_en with
/// ω_en = (−L̇, λ̇·cos L, λ̇·sin L) in ENU — the rotation of the ENU frame as the carrier moves
/// over the ellipsoid, equal to (−v_N/(M + h), v_E/(N + h), v_E·tan L/(N + h)) with M, N the
/// meridian and prime-vertical radii (Titterton & Weston, Strapdown Inertial Navigation
/// Technology, 2nd ed., §3.5, in ENU axes). Then with Ω = (Ω_E, Ω_N, Ω_U):
///   φ̇_E =  Ω_U·φ_N − Ω_N·φ_U,   φ̇_N = −Ω_U·φ_E + Ω_E·φ_U,   φ̇_U = Ω_N·φ_E − Ω_E·φ_N − ε_U,
/// which for ω_en = 0 is the Earth-rate model above.
///
/// Stationary carrier (V < ModelOptions::stationary_speed_m_s, in particular V = 0): ω₀ → 0
/// makes q → 0 and the stationary variance σ²/ω₀² of x_E, x_N infinite. The model is then
/// stated explicitly instead of taken to the limit: the deflection at a point does not change,
/// so δη, δξ are random constants (δη̇ = δξ̇ = 0, no process noise), and x_E, x_N are frozen
/// and decoupled (ẋ = 0: they carry nothing while the carrier stands still and keep their
/// covariance for when it moves again). The attitude states are as above. The deflection is
/// then separated from φ_E, φ_N only through the Earth-rate dynamics of φ, i.e. slowly (hours).
///
/// Observation (spec §4): y = [ΔΦ_E − ξ_G, ΔΦ_N + η_G]ᵀ = H·x + v,
///   H = [[1,0,0,0,0,0,0,1], [0,1,0,0,0,0,−1,0]],  v ~ N(0, diag(r_E, r_N)).
///
/// Discretisation (filter/discretisation.hpp): Exact is Φ = exp(F·Δt) and Q_d by Van Loan's
/// method; PublishedFirstOrder reproduces the published method, Φ ≈ I + F·Δt and
/// Q_d = Δt²·G·Q·Gᵀ with Q = diag(q, q), i.e. the spectral density q taken as the variance of a
/// noise sample held over the step. At Δt = 1 s that Q_d equals q·Δt numerically; at 10 Hz it
/// is 10× too small. Only for comparisons.
///
/// Sources: shared/spec/deflection.md §3–5 (states, dynamics, q = σ²·4ζω₀, H, P₀); the
/// stationary covariance of the second-order Gauss–Markov process, diag(q/(4ζω₀³), q/(4ζω₀)):
/// the closed forms docs/filter.md verifies Van Loan against (A. Gelb (ed.), Applied Optimal
/// Estimation, MIT Press 1974, ch. 3, for the process); Van Loan: filter/discretisation.hpp.

#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "meridian/core/units.hpp"
#include "meridian/filter/discretisation.hpp"
#include "meridian/filter/estimate.hpp"

namespace meridian::dov {

/// State indices (names, never numbers).
struct State {
  enum : int {
    phi_e,      ///< φ_E (rad)
    phi_n,      ///< φ_N (rad)
    phi_u,      ///< φ_U (rad)
    eps_u,      ///< ε_U (rad/s)
    x_e,        ///< x_E (rad·s), ẋ_E = δη
    x_n,        ///< x_N (rad·s), ẋ_N = δξ
    delta_eta,  ///< δη (rad)
    delta_xi,   ///< δξ (rad)
    size
  };
};
/// Process-noise inputs.
struct Noise {
  enum : int {
    w_e,  ///< drives δη (white, rad/s; spectral density q in rad²/s)
    w_n,  ///< drives δξ
    size
  };
};
/// Observation components.
struct Obs {
  enum : int {
    east,   ///< ΔΦ_E − ξ_G (rad)
    north,  ///< ΔΦ_N + η_G (rad)
    size
  };
};

using StateVector = filter::Vector<State::size>;
using StateMatrix = filter::Matrix<State::size, State::size>;
using ObservationMatrix = filter::Matrix<Obs::size, State::size>;
using ObservationCovariance = filter::Matrix<Obs::size, Obs::size>;

/// Parameters of the deflection-error model (spec §3 defaults).
struct ModelOptions {
  double zeta = 0.05;                                 ///< damping ratio ζ, > 0
  double sigma_model_rad = 3.0 * units::kArcsecond;   ///< σ of δη, δξ, > 0 (rad)
  double correlation_length_m = 10000.0;              ///< λ in ω₀ = 2πV/λ, > 0 (m)
  double omega_ie_rad_s = units::kEarthRotationRate_rad_s;  ///< Earth rotation rate, ≥ 0
  /// Speeds below this are the stationary case (file comment), ≥ 0 (m/s). 0.1 m/s: above the
  /// speed over ground a GNSS receiver reports at rest (Doppler velocity noise of a few cm/s,
  /// e.g. 3 cm/s per horizontal component: the speed at rest is Rayleigh-distributed and
  /// exceeds 0.1 m/s in 0.4 % of samples), while a carrier slower than it moves less than
  /// 360 m in an hour, a small part of the 10 km correlation length. The workflow classes
  /// steps with hysteresis (deflection.hpp, Options::stationary_min_duration_s) and can take
  /// the threshold from a known speed σ instead (Options::speed_sigma_m_s).
  double stationary_speed_m_s = 0.1;
};

/// How the continuous model is discretised (file comment).
enum class DiscretisationMethod {
  Exact,                ///< Φ = exp(FΔt), Q_d by Van Loan (default)
  PublishedFirstOrder,  ///< Φ ≈ I + FΔt, Q_d = Δt²·G·Q·Gᵀ (the published method)
};

/// Throws InputError (field "options.<name>") unless every option is finite and in its range.
void validate(const ModelOptions& options);

/// True when speed_m_s < options.stationary_speed_m_s.
bool is_stationary(double speed_m_s, const ModelOptions& options);

/// ω₀ = 2π·V/λ (rad/s); 0 in the stationary case. speed_m_s must be finite and ≥ 0
/// (InputError otherwise).
double omega0_rad_s(double speed_m_s, const ModelOptions& options);

/// q = σ²·4ζω₀ (rad²/s); 0 in the stationary case.
double process_noise_density(double speed_m_s, const ModelOptions& options);

/// The transport rate ω_en = (−L̇, λ̇·cos L, λ̇·sin L) (rad/s, ENU; file comment) of a carrier
/// whose geodetic latitude changes at lat_rate_rad_s and longitude at lon_rate_rad_s (east
/// positive) at latitude lat_rad. Throws InputError unless all are finite and |L| ≤ π/2.
Eigen::Vector3d transport_rate(double lat_rad, double lat_rate_rad_s, double lon_rate_rad_s);

/// The continuous model at geodetic latitude lat_rad (|L| ≤ π/2) and speed speed_m_s (≥ 0),
/// moving or stationary (file comment); transport_rate_rad_s is ω_en in ENU (rad/s, zero: the
/// Earth-rate-only model of the spec). Throws InputError for values out of range.
filter::ContinuousModel<State::size, Noise::size> continuous_model(
    double lat_rad, double speed_m_s, const ModelOptions& options,
    const Eigen::Vector3d& transport_rate_rad_s = Eigen::Vector3d::Zero());

/// The model discretised over dt_s (> 0) by `method`. Throws InputError as continuous_model or
/// for dt_s not finite and > 0; NumericalError when the exponential is not finite.
filter::DiscreteModel<State::size> discrete_model(
    double lat_rad, double speed_m_s, double dt_s, const ModelOptions& options,
    DiscretisationMethod method = DiscretisationMethod::Exact,
    const Eigen::Vector3d& transport_rate_rad_s = Eigen::Vector3d::Zero());

/// Where Φ of discrete_model is nonzero: row j in the columns of the set bits of element j. The
/// attitude errors couple among themselves and with ε_U, ε_U is constant, and each
/// Gauss–Markov pair (x_E, δη), (x_N, δξ) couples only within itself (21 of 64 entries). Exact
/// for steps up to 1 s at any latitude, speed and transport rate with either discretisation
/// (tested); a long step may leave the exponential's round-off outside it (1e-15 in ε_U's row
/// at 60 s with a transport rate). The workflow gives it to the filter's structured kernel
/// (filter::structured_transition_kernel), which uses it only for speed: such a Φ takes the
/// generic path, with the same numbers.
constexpr std::array<std::uint32_t, State::size> transition_structure() {
  constexpr auto bit = [](int i) { return std::uint32_t{1} << i; };
  constexpr std::uint32_t attitude = bit(State::phi_e) | bit(State::phi_n) | bit(State::phi_u) |
                                     bit(State::eps_u);
  constexpr std::uint32_t east = bit(State::x_e) | bit(State::delta_eta);
  constexpr std::uint32_t north = bit(State::x_n) | bit(State::delta_xi);
  std::array<std::uint32_t, State::size> rows{};
  rows[State::phi_e] = rows[State::phi_n] = rows[State::phi_u] = attitude;
  rows[State::eps_u] = bit(State::eps_u);
  rows[State::x_e] = rows[State::delta_eta] = east;
  rows[State::x_n] = rows[State::delta_xi] = north;
  return rows;
}

/// H of the file comment.
ObservationMatrix observation_matrix();

/// R = diag(σ_E², σ_N²) (σ in rad, > 0; InputError otherwise).
ObservationCovariance observation_covariance(double sigma_east_rad, double sigma_north_rad);

/// Standard deviations of the initial estimate (x̂₀ = 0), spec §5 defaults for the attitude
/// and bias states. The Gauss–Markov states default to their stationary distribution so the
/// filter starts consistent with its own model: σ(δη) = σ(δξ) = σ_model and
/// σ(x_E) = σ(x_N) = σ_model/ω₀ at the reference speed (initial_estimate). The spec's
/// "(1″)²" for δη, δξ and x would contradict its σ = 3″ model; set them here to reproduce it.
struct InitialSigmas {
  double phi_e_rad = 2.0 * units::kArcsecond;
  double phi_n_rad = 2.0 * units::kArcsecond;
  double phi_u_rad = 5.0 * units::kArcsecond;
  double eps_u_rad_s = 0.003 * units::kDegree / 3600.0;  ///< 0.003°/h
  std::optional<double> x_rad_s;    ///< σ(x_E) = σ(x_N); default σ_model/ω₀
  std::optional<double> delta_rad;  ///< σ(δη) = σ(δξ); default σ_model
};

/// Throws InputError (field "options.initial.<name>") unless every σ is finite and > 0.
void validate(const InitialSigmas& sigmas);

/// x̂₀ = 0, P₀ = diag(σ²). Without x_rad_s, σ(x) = σ_model/ω₀(reference_speed_m_s); when that
/// speed is stationary, σ(x) = σ_model·1 s (x is then decoupled from everything the line
/// observes, so its value does not matter). Throws InputError as validate.
filter::Estimate<State::size> initial_estimate(const InitialSigmas& sigmas,
                                               const ModelOptions& options,
                                               double reference_speed_m_s);

}  // namespace meridian::dov
