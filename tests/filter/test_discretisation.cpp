// Discretisation against closed forms: Van Loan for a double integrator and a second-order
// Gauss–Markov process, the first-order option's convergence, and the semigroup property of
// the deflection model.
#include <cmath>

#include <gtest/gtest.h>

#include "example_models.hpp"
#include "meridian/core/error.hpp"
#include "meridian/filter/discretisation.hpp"
#include "test_support.hpp"

namespace {

using meridian::InputError;
using meridian::filter::ContinuousModel;
using meridian::filter::DiscreteModel;
using meridian::filter::Discretisation;
using meridian::filter::discretise;
using meridian::filter::Matrix;
using namespace meridian::filter::examples;

// Position-like and rate-like states of a scalar double integrator / oscillator.
struct Osc {
  static constexpr int pos = 0;
  static constexpr int rate = 1;
  static constexpr int size = 2;
};

ContinuousModel<Osc::size, 1> double_integrator(double q) {
  ContinuousModel<Osc::size, 1> m;
  m.F.setZero();
  m.F(Osc::pos, Osc::rate) = 1.0;
  m.G.setZero();
  m.G(Osc::rate, 0) = 1.0;
  m.q_c(0, 0) = q;
  return m;
}

// ẍ + 2ζω0·ẋ + ω0²·x = w, E[w w] = q·δ.
ContinuousModel<Osc::size, 1> gauss_markov2(double omega0, double zeta, double q) {
  ContinuousModel<Osc::size, 1> m = double_integrator(q);
  m.F(Osc::rate, Osc::pos) = -omega0 * omega0;
  m.F(Osc::rate, Osc::rate) = -2.0 * zeta * omega0;
  return m;
}

// Closed form of exp(F·Δt) for the underdamped oscillator (ζ < 1).
Matrix<2, 2> gauss_markov2_phi(double omega0, double zeta, double dt) {
  const double a = zeta * omega0;
  const double wd = omega0 * std::sqrt(1.0 - zeta * zeta);
  const double e = std::exp(-a * dt);
  const double c = std::cos(wd * dt);
  const double s = std::sin(wd * dt);
  Matrix<2, 2> phi;
  phi(Osc::pos, Osc::pos) = e * (c + a / wd * s);
  phi(Osc::pos, Osc::rate) = e * s / wd;
  phi(Osc::rate, Osc::pos) = -e * omega0 * omega0 / wd * s;
  phi(Osc::rate, Osc::rate) = e * (c - a / wd * s);
  return phi;
}

// Stationary covariance: diag(q/(4ζω0³), q/(4ζω0)).
Matrix<2, 2> gauss_markov2_stationary(double omega0, double zeta, double q) {
  Matrix<2, 2> p = Matrix<2, 2>::Zero();
  p(Osc::pos, Osc::pos) = q / (4.0 * zeta * omega0 * omega0 * omega0);
  p(Osc::rate, Osc::rate) = q / (4.0 * zeta * omega0);
  return p;
}

double rel(const Matrix<2, 2>& a, const Matrix<2, 2>& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(VanLoan, DoubleIntegratorMatchesClosedForm) {
  const double q = 0.37;
  for (const double dt : {0.01, 1.0, 7.5}) {
    const DiscreteModel<2> d = discretise(double_integrator(q), dt);
    Matrix<2, 2> phi;
    phi << 1.0, dt, 0.0, 1.0;
    Matrix<2, 2> qd;
    qd << q * dt * dt * dt / 3.0, q * dt * dt / 2.0, q * dt * dt / 2.0, q * dt;
    EXPECT_LT(rel(d.phi, phi), 1e-14) << dt;
    // Every entry, relative to itself (they differ by orders of magnitude for small Δt).
    EXPECT_LT((d.q - qd).cwiseQuotient(qd).cwiseAbs().maxCoeff(), 1e-13) << dt;
  }
}

TEST(VanLoan, SecondOrderGaussMarkovMatchesClosedForm) {
  const double omega0 = 0.5;
  const double zeta = 0.3;
  const double q = 2.0e-3;
  const Matrix<2, 2> p_inf = gauss_markov2_stationary(omega0, zeta, q);
  for (const double dt : {0.2, 1.0, 3.0, 10.0}) {
    const DiscreteModel<2> d = discretise(gauss_markov2(omega0, zeta, q), dt);
    const Matrix<2, 2> phi = gauss_markov2_phi(omega0, zeta, dt);
    // For a stationary process P∞ = Φ·P∞·Φᵀ + Q_d, so Q_d = P∞ − Φ·P∞·Φᵀ exactly.
    const Matrix<2, 2> qd = p_inf - phi * p_inf * phi.transpose();
    EXPECT_LT(rel(d.phi, phi), 1e-13) << dt;
    EXPECT_LT(meridian::filter::testing::covariance_difference(d.q, qd), 1e-12) << dt;
  }
}

TEST(VanLoan, LongStepReachesStationaryVariances) {
  // After many correlation times Φ → 0 and Q_d → P∞: q/(4ζω0³) and q/(4ζω0).
  const double omega0 = 0.5;
  const double zeta = 0.3;
  const double q = 2.0e-3;
  const DiscreteModel<2> d = discretise(gauss_markov2(omega0, zeta, q), 400.0);
  const double var_pos = q / (4.0 * zeta * omega0 * omega0 * omega0);
  const double var_rate = q / (4.0 * zeta * omega0);
  EXPECT_NEAR(d.q(Osc::pos, Osc::pos) / var_pos, 1.0, 1e-12);
  EXPECT_NEAR(d.q(Osc::rate, Osc::rate) / var_rate, 1.0, 1e-12);
  EXPECT_LT(std::abs(d.q(Osc::pos, Osc::rate)), 1e-12 * std::sqrt(var_pos * var_rate));
  EXPECT_LT(d.phi.cwiseAbs().maxCoeff(), 1e-20);
}

TEST(VanLoan, DeflectionModelSatisfiesTheSemigroupProperty) {
  // Two steps of Δt equal one of 2Δt: Φ(2Δt) = Φ², Q_d(2Δt) = Φ·Q_d·Φᵀ + Q_d. Checks the
  // scaling of a Q_c of 1e-13 rad²/s against F entries of order 1.
  const DovParameters p;
  const auto model = dov_model(p);
  const auto one = discretise(model, 1.0);
  const auto two = discretise(model, 2.0);
  const Matrix<8, 8> phi2 = one.phi * one.phi;
  const Matrix<8, 8> q2 = one.phi * one.q * one.phi.transpose() + one.q;
  EXPECT_LT((two.phi - phi2).cwiseAbs().maxCoeff(), 1e-14);
  // Q_d is singular in the attitude states (no noise reaches them): compare the noise block.
  const auto block = [](const Matrix<8, 8>& m) { return m.bottomRightCorner<4, 4>().eval(); };
  EXPECT_LT(meridian::filter::testing::covariance_difference(block(two.q), block(q2)), 1e-12);
  // The stationary variance of δη, δξ is σ² (q = σ²·4ζω0): Q_d → σ² after a long step.
  const auto far = discretise(model, 2.0e5);
  EXPECT_NEAR(
      far.q(DovState::delta_eta, DovState::delta_eta) / (p.sigma_model_rad * p.sigma_model_rad),
      1.0, 1e-9);
}

TEST(FirstOrder, ErrorShrinksWithTheStep) {
  const auto model = gauss_markov2(0.5, 0.3, 2.0e-3);
  double prev_phi = 0.0;
  double prev_q = 0.0;
  for (const double dt : {0.1, 0.01, 0.001}) {
    const auto exact = discretise(model, dt, Discretisation::VanLoan);
    const auto approx = discretise(model, dt, Discretisation::FirstOrder);
    const double e_phi = (approx.phi - exact.phi).cwiseAbs().maxCoeff();
    const double e_q = rel(approx.q, exact.q);
    if (prev_phi > 0.0) {
      // Φ error O(Δt²): ×100 smaller per decade; relative Q_d error O(Δt): ×10.
      EXPECT_GT(prev_phi / e_phi, 80.0) << dt;
      EXPECT_LT(prev_phi / e_phi, 120.0) << dt;
      EXPECT_GT(prev_q / e_q, 8.0) << dt;
      EXPECT_LT(prev_q / e_q, 12.0) << dt;
    }
    prev_phi = e_phi;
    prev_q = e_q;
  }
  EXPECT_LT(prev_phi, 1e-6);
}

TEST(FirstOrder, DiscreteNoiseFormIsDtSquaredTimesQ) {
  // The published method's Q_d = Δt²·G·Q·Gᵀ equals the PSD form when Q = Q_c/Δt.
  const double dt = 0.25;
  auto model = gauss_markov2(0.5, 0.3, 2.0e-3);
  const auto psd = discretise(model, dt, Discretisation::FirstOrder);
  model.q_c /= dt;
  const auto discrete = discretise(model, dt, Discretisation::FirstOrderDiscreteNoise);
  EXPECT_EQ(discrete.phi, psd.phi);
  EXPECT_LT(rel(discrete.q, psd.q), 1e-15);
  EXPECT_DOUBLE_EQ(discrete.q(Osc::rate, Osc::rate), dt * dt * model.q_c(0, 0));
}

TEST(Discretise, RejectsBadInput) {
  auto model = double_integrator(1.0);
  EXPECT_THROW(discretise(model, 0.0), InputError);
  EXPECT_THROW(discretise(model, std::nan("")), InputError);
  model.F(0, 0) = std::nan("");
  EXPECT_THROW(discretise(model, 1.0), InputError);
  model = double_integrator(-1.0);
  EXPECT_THROW(discretise(model, 1.0), InputError);
  EXPECT_THROW(meridian::filter::discretise_dynamic(
                   Eigen::MatrixXd::Zero(2, 3), Eigen::MatrixXd::Zero(2, 1),
                   Eigen::MatrixXd::Zero(1, 1), 1.0, Discretisation::VanLoan),
               InputError);
}

}  // namespace
