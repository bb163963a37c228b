// The 8-state model (dov/model.hpp) against closed forms: the Earth-rate attitude dynamics
// against Eigen's AngleAxis (the exact rotation about Ω), the Gauss–Markov block against the
// damped oscillator and the Lyapunov equation, H against the spec's printed matrix, the
// stationary case and its unobservable direction, the published first-order form.
#include <bit>
#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "dov_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/model.hpp"

namespace {

using meridian::InputError;
using namespace meridian::dov;
namespace units = meridian::units;
using meridian_test::kAs;

TEST(DovModel, ObservationMatrixIsTheSpecs) {
  // spec §4: H = [[1,0,0,0,0,0,0,1], [0,1,0,0,0,0,−1,0]], in the state order of §3.
  Eigen::Matrix<double, 2, 8> spec;
  spec << 1, 0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, -1, 0;
  EXPECT_EQ(Eigen::MatrixXd(observation_matrix()), Eigen::MatrixXd(spec));
  // and the names are the spec's order
  EXPECT_EQ(State::phi_e, 0);
  EXPECT_EQ(State::eps_u, 3);
  EXPECT_EQ(State::delta_eta, 6);
  EXPECT_EQ(State::delta_xi, 7);
  EXPECT_EQ(State::size, 8);
}

TEST(DovModel, TransitionStaysWithinItsDeclaredStructure) {
  // The structure the workflow gives the filter's unrolled kernel (a Φ outside it would only be
  // slower): every discretisation, moving and stationary, with and without a transport rate,
  // at the equator and a pole.
  const auto rows = transition_structure();
  const ModelOptions o;
  int cases = 0;
  for (const auto method :
       {DiscretisationMethod::Exact, DiscretisationMethod::PublishedFirstOrder})
    for (const double lat : {0.0, 0.6, -1.2, meridian::units::kPi / 2.0})
      for (const double speed : {0.0, 0.005, 5.0, 250.0})
        for (const double dt : {0.01, 1.0, 60.0})
          for (const Eigen::Vector3d& w : {Eigen::Vector3d::Zero().eval(),
                                          Eigen::Vector3d(-3e-6, 2e-5, 1.5e-5)}) {
            const auto d = discrete_model(lat, speed, dt, o, method, w);
            for (int j = 0; j < State::size; ++j)
              for (int k = 0; k < State::size; ++k)
                if (((rows[static_cast<std::size_t>(j)] >> k) & 1u) == 0) {
                  // Steps up to 1 s (1–100 Hz lines): exact zeros. Longer ones may carry the
                  // exponential's round-off (1e-15 in ε_U's row at 60 s with a transport rate);
                  // such a Φ takes the generic kernel.
                  if (dt <= 1.0)
                    EXPECT_EQ(d.phi(j, k), 0.0) << "Φ(" << j << ", " << k << ") lat " << lat
                                                << " speed " << speed << " dt " << dt;
                  else
                    EXPECT_LT(std::abs(d.phi(j, k)), 1e-14);
                }
            ++cases;
          }
  EXPECT_EQ(cases, 2 * 4 * 4 * 3 * 2);
  int entries = 0;
  for (const std::uint32_t r : rows) entries += std::popcount(r);
  EXPECT_EQ(entries, 21);
}

TEST(DovModel, AttitudeBlockIsTheRotationAboutTheEarthRate) {
  // φ̇ = −Ω×φ with ε = 0: φ(t) = R(Ω, −|Ω|t)·φ(0), Ω = ω_ie(0, cos L, sin L) (ENU).
  ModelOptions o;
  const double lat = 37.0 * units::kDegree;
  const double dt = 3600.0;  // a long step, so the rotation is visible (15°)
  const auto d = discrete_model(lat, 5.0, dt, o);
  const Eigen::Vector3d axis(0.0, std::cos(lat), std::sin(lat));
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(-o.omega_ie_rad_s * dt, axis).toRotationMatrix();
  const Eigen::Matrix3d block = d.phi.topLeftCorner<3, 3>();
  EXPECT_LT((block - rot).cwiseAbs().maxCoeff(), 1e-12);
  // ε_U column: −∫₀^Δt R(Ω, −ωs) ds·e_U by numerical quadrature (Simpson, 2000 intervals)
  Eigen::Vector3d integral = Eigen::Vector3d::Zero();
  const int m = 2000;
  for (int i = 0; i <= m; ++i) {
    const double s = dt * i / m;
    const double w = (i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    integral += w * (Eigen::AngleAxisd(-o.omega_ie_rad_s * s, axis).toRotationMatrix() *
                     Eigen::Vector3d::UnitZ());
  }
  integral *= dt / (3.0 * m);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(d.phi(i, State::eps_u), -integral(i), 1e-9 * dt) << i;
  // spec §3 signs, entry by entry
  const auto c = continuous_model(lat, 5.0, o);
  const double w = o.omega_ie_rad_s;
  EXPECT_DOUBLE_EQ(c.F(State::phi_e, State::phi_n), w * std::sin(lat));
  EXPECT_DOUBLE_EQ(c.F(State::phi_e, State::phi_u), -w * std::cos(lat));
  EXPECT_DOUBLE_EQ(c.F(State::phi_n, State::phi_e), -w * std::sin(lat));
  EXPECT_DOUBLE_EQ(c.F(State::phi_u, State::phi_e), w * std::cos(lat));
  EXPECT_DOUBLE_EQ(c.F(State::phi_u, State::eps_u), -1.0);
}

TEST(DovModel, TransportRateOfARhumbLineIsTheTextbooksOmegaEn) {
  // ω_en in ENU from the velocity (Titterton & Weston §3.5, NED there, axes swapped here):
  // (−v_N/(M + h), v_E/(N + h), v_E·tan L/(N + h)), against transport_rate(L, L̇, λ̇) with
  // L̇ = v_N/(M + h), λ̇ = v_E/((N + h)·cos L) — the GRS80 radii written out here.
  const double a = 6378137.0, f = 1.0 / 298.257222101, e2 = f * (2.0 - f), h = 120.0;
  for (double lat_deg : {-71.0, 0.0, 23.5, 60.0}) {
    const double lat = lat_deg * units::kDegree;
    const double w = std::sqrt(1.0 - e2 * std::sin(lat) * std::sin(lat));
    const double n = a / w, m = a * (1.0 - e2) / (w * w * w);
    const double v_e = 180.0, v_n = -95.0;  // m/s
    const Eigen::Vector3d book(-v_n / (m + h), v_e / (n + h), v_e * std::tan(lat) / (n + h));
    const Eigen::Vector3d got =
        transport_rate(lat, v_n / (m + h), v_e / ((n + h) * std::cos(lat)));
    EXPECT_LT((got - book).norm(), 1e-15 * book.norm() + 1e-22) << lat_deg;
  }
  EXPECT_THROW(transport_rate(2.0, 0.0, 0.0), InputError);
  EXPECT_THROW(transport_rate(0.1, std::nan(""), 0.0), InputError);
}

TEST(DovModel, TransportRateAddsToTheEarthRateInMinusOmegaCross) {
  // φ̇ = −Ω×φ with Ω = ω_ie(0, cos L, sin L) + ω_en: the attitude block of F is −[Ω×], and the
  // exact Φ block is the rotation R(Ω, −|Ω|Δt) (Eigen's AngleAxis as the reference).
  ModelOptions o;
  const double lat = -42.0 * units::kDegree;
  const Eigen::Vector3d en(3.1e-5, -2.2e-5, 4.7e-5);  // a fast aircraft's size (rad/s)
  const Eigen::Vector3d omega =
      o.omega_ie_rad_s * Eigen::Vector3d(0.0, std::cos(lat), std::sin(lat)) + en;
  Eigen::Matrix3d cross;
  cross << 0.0, -omega.z(), omega.y(), omega.z(), 0.0, -omega.x(), -omega.y(), omega.x(), 0.0;
  const auto c = continuous_model(lat, 120.0, o, en);
  EXPECT_LT((Eigen::Matrix3d(c.F.topLeftCorner<3, 3>()) + cross).cwiseAbs().maxCoeff(), 1e-20);
  EXPECT_EQ(c.F(State::phi_u, State::eps_u), -1.0);
  const double dt = 1800.0;
  const auto d = discrete_model(lat, 120.0, dt, o, DiscretisationMethod::Exact, en);
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(-omega.norm() * dt, omega.normalized()).toRotationMatrix();
  EXPECT_LT((Eigen::Matrix3d(d.phi.topLeftCorner<3, 3>()) - rot).cwiseAbs().maxCoeff(), 1e-12);
  // ω_en = 0 is the spec's Earth-rate model, bit for bit.
  const auto plain = continuous_model(lat, 120.0, o);
  const auto zero = continuous_model(lat, 120.0, o, Eigen::Vector3d::Zero());
  EXPECT_EQ(plain.F, zero.F);
  EXPECT_THROW(continuous_model(lat, 120.0, o, Eigen::Vector3d(std::nan(""), 0.0, 0.0)),
               InputError);
}

TEST(DovModel, GaussMarkovBlockAgainstTheDampedOscillator) {
  ModelOptions o;
  const double v = 5.0, dt = 1.0;
  const double w0 = 2.0 * units::kPi * v / 10000.0;
  EXPECT_DOUBLE_EQ(omega0_rad_s(v, o), w0);
  EXPECT_DOUBLE_EQ(process_noise_density(v, o), std::pow(3.0 * kAs, 2) * 4.0 * 0.05 * w0);
  for (double step : {dt, 100.0, 5000.0}) {
    const auto d = discrete_model(0.5, v, step, o);
    const double a = 0.05 * w0, wd = w0 * std::sqrt(1.0 - 0.05 * 0.05);
    const double e = std::exp(-a * step), cs = std::cos(wd * step), sn = std::sin(wd * step);
    Eigen::Matrix2d phi;
    phi << e * (cs + a / wd * sn), e * sn / wd, -e * w0 * w0 / wd * sn, e * (cs - a / wd * sn);
    const Eigen::Matrix2d p_inf =
        Eigen::Vector2d(std::pow(3.0 * kAs / w0, 2), std::pow(3.0 * kAs, 2)).asDiagonal();
    const Eigen::Matrix2d q = p_inf - phi * p_inf * phi.transpose();
    for (int pair = 0; pair < 2; ++pair) {
      const int x = pair == 0 ? State::x_e : State::x_n;
      const int dl = pair == 0 ? State::delta_eta : State::delta_xi;
      Eigen::Matrix2d got_phi, got_q;
      got_phi << d.phi(x, x), d.phi(x, dl), d.phi(dl, x), d.phi(dl, dl);
      got_q << d.q(x, x), d.q(x, dl), d.q(dl, x), d.q(dl, dl);
      EXPECT_LT((got_phi - phi).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, step)) << step;
      // relative to σ_i σ_j of P∞
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          EXPECT_NEAR(got_q(i, j) / std::sqrt(p_inf(i, i) * p_inf(j, j)),
                      q(i, j) / std::sqrt(p_inf(i, i) * p_inf(j, j)), 1e-9)
              << step << " " << i << j;
    }
    // no coupling between the attitude and Gauss–Markov blocks
    EXPECT_EQ(d.phi(State::phi_e, State::delta_xi), 0.0);
    EXPECT_EQ(d.q(State::phi_e, State::phi_e), 0.0);
  }
  // After a very long step Q_d is the stationary covariance: σ(δ) = σ_model (q = σ²·4ζω₀).
  const auto d = discrete_model(0.5, v, 2.0e6, o);
  EXPECT_NEAR(std::sqrt(d.q(State::delta_xi, State::delta_xi)) / kAs, 3.0, 1e-6);
  EXPECT_NEAR(std::sqrt(d.q(State::x_n, State::x_n)) * w0 / kAs, 3.0, 1e-6);
}

TEST(DovModel, StationaryCase) {
  ModelOptions o;
  for (double v : {0.0, 0.005}) {  // V = 0 and below stationary_speed_m_s (0.1 m/s)
    EXPECT_TRUE(is_stationary(v, o));
    EXPECT_EQ(omega0_rad_s(v, o), 0.0);
    const auto d = discrete_model(0.6, v, 10.0, o);
    for (int i : {static_cast<int>(State::x_e), static_cast<int>(State::x_n),
                  static_cast<int>(State::delta_eta), static_cast<int>(State::delta_xi)}) {
      for (int j = 0; j < State::size; ++j) {
        EXPECT_NEAR(d.phi(i, j), i == j ? 1.0 : 0.0, 1e-15) << i << " " << j;
        EXPECT_EQ(d.q(i, j), 0.0);
      }
    }
    EXPECT_TRUE(d.phi.allFinite() && d.q.allFinite());
  }
  o.stationary_speed_m_s = 0.0;
  EXPECT_TRUE(is_stationary(0.0, o));  // V = 0 is stationary even with a zero threshold
  EXPECT_FALSE(is_stationary(1e-6, o));
}

TEST(DovModel, StationaryCaseHasTheUnobservableEastDirection) {
  // Standing still, d = (φ_N, φ_U, δη) += c·(1, tan L, 1) leaves y unchanged for ever:
  // H·d = 0 and F·d = 0. Moving, F·d ≠ 0 (δη has no constant part), so η becomes observable.
  ModelOptions o;
  const double lat = 0.6;
  StateVector d = StateVector::Zero();
  d(State::phi_n) = 1.0;
  d(State::phi_u) = std::tan(lat);
  d(State::delta_eta) = 1.0;
  EXPECT_LT((observation_matrix() * d).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((continuous_model(lat, 0.0, o).F * d).cwiseAbs().maxCoeff(), 1e-20);
  EXPECT_GT((continuous_model(lat, 5.0, o).F * d).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(DovModel, PublishedFirstOrder) {
  ModelOptions o;
  const double v = 5.0;
  const auto c = continuous_model(0.5, v, o);
  const double q = process_noise_density(v, o);
  for (double dt : {1.0, 0.1}) {
    const auto d = discrete_model(0.5, v, dt, o, DiscretisationMethod::PublishedFirstOrder);
    EXPECT_LT((d.phi - (StateMatrix::Identity() + c.F * dt)).cwiseAbs().maxCoeff(), 1e-18);
    EXPECT_DOUBLE_EQ(d.q(State::delta_eta, State::delta_eta), dt * dt * q);
    EXPECT_EQ(d.q(State::x_e, State::x_e), 0.0);
    // against the exact model: Q_d of δ is q·Δt to first order, so the published value is a
    // factor Δt smaller (equal at 1 Hz, 10× too small at 10 Hz)
    const auto exact = discrete_model(0.5, v, dt, o);
    EXPECT_NEAR(exact.q(State::delta_eta, State::delta_eta) / (q * dt), 1.0, 0.01);
  }
}

TEST(DovModel, InitialEstimate) {
  ModelOptions o;
  InitialSigmas s;
  const auto e = initial_estimate(s, o, 5.0);
  EXPECT_TRUE(e.x.isZero());
  EXPECT_DOUBLE_EQ(e.sigma(State::phi_e) / kAs, 2.0);
  EXPECT_DOUBLE_EQ(e.sigma(State::phi_u) / kAs, 5.0);
  EXPECT_NEAR(e.sigma(State::eps_u) * 3600.0 / units::kDegree, 0.003, 1e-15);
  EXPECT_NEAR(e.sigma(State::x_e), 3.0 * kAs / (2.0 * units::kPi * 5.0 / 10000.0), 1e-18);
  EXPECT_DOUBLE_EQ(e.sigma(State::delta_xi) / kAs, 3.0);
  EXPECT_TRUE((e.P - StateMatrix(e.P.diagonal().asDiagonal())).isZero());
  s.delta_rad = 1.0 * kAs;
  s.x_rad_s = 2.0;
  const auto f = initial_estimate(s, o, 0.0);
  EXPECT_DOUBLE_EQ(f.sigma(State::delta_eta) / kAs, 1.0);
  EXPECT_DOUBLE_EQ(f.sigma(State::x_n), 2.0);
  EXPECT_DOUBLE_EQ(initial_estimate(InitialSigmas{}, o, 0.0).sigma(State::x_n), 3.0 * kAs);
}

TEST(DovModel, Errors) {
  ModelOptions o;
  EXPECT_THROW(continuous_model(2.0, 5.0, o), InputError);
  EXPECT_THROW(continuous_model(0.5, -1.0, o), InputError);
  EXPECT_THROW(continuous_model(0.5, std::nan(""), o), InputError);
  EXPECT_THROW(discrete_model(0.5, 5.0, 0.0, o), InputError);
  EXPECT_THROW(discrete_model(0.5, 5.0, -1.0, o), InputError);
  EXPECT_THROW(observation_covariance(0.0, 1e-6), InputError);
  ModelOptions bad = o;
  bad.zeta = 0.0;
  try {
    validate(bad);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "options.zeta");
  }
  InitialSigmas s;
  s.phi_u_rad = -1.0;
  try {
    validate(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "options.initial.phi_u_rad");
  }
}

}  // namespace
