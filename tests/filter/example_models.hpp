#pragma once
// Example models of the filter tests and benchmark, written the way a workflow defines its
// model: named state, noise and observation indices, no bare numbers (docs/filter.md).
//
// * The deflection-of-the-vertical model of shared/spec/deflection.md §3–4 (8 states,
//   2 noise inputs, 2 observations), with the spec's typical values.
// * A 2-D constant-velocity model (4 states, white acceleration noise), the navigation
//   workflow's shape (position observed).
// Plus the simulation helpers the tests share.
#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "meridian/core/units.hpp"
#include "meridian/filter/discretisation.hpp"
#include "meridian/filter/estimate.hpp"

namespace meridian::filter::examples {

// ---------------------------------------------------------------------------------------------
// Deflection of the vertical from INS/GNSS attitude differences (deflection.md).

/// States: LGU attitude errors (rad), vertical gyro bias (rad/s), the second-order
/// Gauss–Markov DOV model errors with their intermediate states x_E, x_N (rad·s).
struct DovState {
  static constexpr int phi_e = 0;      ///< φ_E (rad)
  static constexpr int phi_n = 1;      ///< φ_N (rad)
  static constexpr int phi_u = 2;      ///< φ_U (rad)
  static constexpr int eps_u = 3;      ///< ε_U, equivalent vertical gyro bias (rad/s)
  static constexpr int x_e = 4;        ///< x_E, ẋ_E = δη (rad·s)
  static constexpr int x_n = 5;        ///< x_N, ẋ_N = δξ (rad·s)
  static constexpr int delta_eta = 6;  ///< δη, model error of η (rad)
  static constexpr int delta_xi = 7;   ///< δξ, model error of ξ (rad)
  static constexpr int size = 8;
};
struct DovNoise {
  static constexpr int w_e = 0;  ///< drives δη
  static constexpr int w_n = 1;  ///< drives δξ
  static constexpr int size = 2;
};
struct DovObservation {
  static constexpr int east = 0;   ///< ΔΦ_E − ξ_G
  static constexpr int north = 1;  ///< ΔΦ_N + η_G
  static constexpr int size = 2;
};

struct DovParameters {
  double lat_rad = 45.0 * units::kDegree;
  double speed_m_s = 5.0;
  double zeta = 0.05;
  double sigma_model_rad = 3.0 * units::kArcsecond;  ///< σ of δη, δξ
  double sigma_obs_rad = 0.5 * units::kArcsecond;    ///< σ of each observation
  double omega_ie_rad_s = units::kEarthRotationRate_rad_s;
  /// ω0 = 2π·V/10 000 m (rad/s).
  double omega0() const { return 2.0 * units::kPi * speed_m_s / 10000.0; }
  /// q = σ²·4ζω0, so that δη, δξ have the stationary standard deviation σ.
  double q() const { return sigma_model_rad * sigma_model_rad * 4.0 * zeta * omega0(); }
};

inline ContinuousModel<DovState::size, DovNoise::size> dov_model(const DovParameters& p) {
  using S = DovState;
  using W = DovNoise;
  ContinuousModel<S::size, W::size> m;
  m.F.setZero();
  m.G.setZero();
  m.q_c.setZero();
  const double sl = p.omega_ie_rad_s * std::sin(p.lat_rad);
  const double cl = p.omega_ie_rad_s * std::cos(p.lat_rad);
  m.F(S::phi_e, S::phi_n) = sl;
  m.F(S::phi_e, S::phi_u) = -cl;
  m.F(S::phi_n, S::phi_e) = -sl;
  m.F(S::phi_u, S::phi_e) = cl;
  m.F(S::phi_u, S::eps_u) = -1.0;
  const double w0 = p.omega0();
  m.F(S::x_e, S::delta_eta) = 1.0;
  m.F(S::delta_eta, S::x_e) = -w0 * w0;
  m.F(S::delta_eta, S::delta_eta) = -2.0 * p.zeta * w0;
  m.F(S::x_n, S::delta_xi) = 1.0;
  m.F(S::delta_xi, S::x_n) = -w0 * w0;
  m.F(S::delta_xi, S::delta_xi) = -2.0 * p.zeta * w0;
  m.G(S::delta_eta, W::w_e) = 1.0;
  m.G(S::delta_xi, W::w_n) = 1.0;
  m.q_c(W::w_e, W::w_e) = p.q();
  m.q_c(W::w_n, W::w_n) = p.q();
  return m;
}

/// y = H·x + v: ΔΦ_E − ξ_G = φ_E + δξ, ΔΦ_N + η_G = φ_N − δη (deflection.md §4).
inline Matrix<DovObservation::size, DovState::size> dov_observation_matrix() {
  using S = DovState;
  using O = DovObservation;
  Matrix<O::size, S::size> H = Matrix<O::size, S::size>::Zero();
  H(O::east, S::phi_e) = 1.0;
  H(O::east, S::delta_xi) = 1.0;
  H(O::north, S::phi_n) = 1.0;
  H(O::north, S::delta_eta) = -1.0;
  return H;
}

inline Matrix<DovObservation::size, DovObservation::size> dov_observation_covariance(
    const DovParameters& p) {
  const double r = p.sigma_obs_rad * p.sigma_obs_rad;
  return (Vector<DovObservation::size>() << r, r).finished().asDiagonal();
}

/// Initial estimate: zero, the spec's typical P0 for the attitude and bias states and the
/// stationary variances of the Gauss–Markov states (σ/ω0 for x_E, x_N; σ for δη, δξ).
inline Estimate<DovState::size> dov_initial(const DovParameters& p) {
  using S = DovState;
  Vector<S::size> sd;
  sd(S::phi_e) = 2.0 * units::kArcsecond;
  sd(S::phi_n) = 2.0 * units::kArcsecond;
  sd(S::phi_u) = 5.0 * units::kArcsecond;
  sd(S::eps_u) = 0.003 * units::kDegree / 3600.0;
  sd(S::x_e) = p.sigma_model_rad / p.omega0();
  sd(S::x_n) = p.sigma_model_rad / p.omega0();
  sd(S::delta_eta) = p.sigma_model_rad;
  sd(S::delta_xi) = p.sigma_model_rad;
  return {Vector<S::size>::Zero(), sd.cwiseAbs2().asDiagonal()};
}

// ---------------------------------------------------------------------------------------------
// 2-D constant velocity, position observed (the navigation workflow's shape).

struct CvState {
  static constexpr int x = 0;   ///< north (m)
  static constexpr int y = 1;   ///< east (m)
  static constexpr int vx = 2;  ///< north velocity (m/s)
  static constexpr int vy = 3;  ///< east velocity (m/s)
  static constexpr int size = 4;
};
struct CvNoise {
  static constexpr int ax = 0;  ///< north acceleration (m/s²)
  static constexpr int ay = 1;  ///< east acceleration (m/s²)
  static constexpr int size = 2;
};

/// White acceleration of spectral density q_m2_s3 on each axis.
inline ContinuousModel<CvState::size, CvNoise::size> cv_model(double q_m2_s3) {
  using S = CvState;
  using W = CvNoise;
  ContinuousModel<S::size, W::size> m;
  m.F.setZero();
  m.G.setZero();
  m.F(S::x, S::vx) = 1.0;
  m.F(S::y, S::vy) = 1.0;
  m.G(S::vx, W::ax) = 1.0;
  m.G(S::vy, W::ay) = 1.0;
  m.q_c = q_m2_s3 * Matrix<W::size, W::size>::Identity();
  return m;
}

/// Position observed: rows x, y.
inline Matrix<2, CvState::size> cv_position_matrix() {
  Matrix<2, CvState::size> H = Matrix<2, CvState::size>::Zero();
  H(0, CvState::x) = 1.0;
  H(1, CvState::y) = 1.0;
  return H;
}

// ---------------------------------------------------------------------------------------------
// Simulation.

/// A draw from N(0, C) for a symmetric positive semi-definite C (eigen-decomposition, so a
/// singular C — a process noise with few inputs — is fine). The decomposition runs on a
/// dynamic-size copy: one Eigen solver instantiation for every N instead of one per size, which
/// took several seconds of compile time per size in each test file (the draw's cost is not measured).
template <int N>
Vector<N> draw(const Matrix<N, N>& C, std::mt19937_64& rng) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(C)};
  std::normal_distribution<double> nd;
  Eigen::VectorXd u(C.rows());
  for (Eigen::Index i = 0; i < u.size(); ++i)
    u(i) = nd(rng) * std::sqrt(std::max(0.0, es.eigenvalues()(i)));
  return Vector<N>(es.eigenvectors() * u);
}

}  // namespace meridian::filter::examples
