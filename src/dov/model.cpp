#include "meridian/dov/model.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::dov {
namespace {

void require(bool ok, const std::string& field, const std::string& what, double value) {
  if (!ok)
    throw InputError(fmt::format("{} must be {}, is {}", field, what, value),
                     ErrorContext{{}, {}, field});
}

void check_lat_speed(double lat_rad, double speed_m_s) {
  require(std::isfinite(lat_rad) && std::abs(lat_rad) <= units::kPi / 2.0, "lat_rad",
          "finite and within ±π/2", lat_rad);
  require(std::isfinite(speed_m_s) && speed_m_s >= 0.0, "speed_m_s", "finite and ≥ 0", speed_m_s);
}

}  // namespace

void validate(const ModelOptions& o) {
  require(std::isfinite(o.zeta) && o.zeta > 0.0, "options.zeta", "finite and > 0", o.zeta);
  require(std::isfinite(o.sigma_model_rad) && o.sigma_model_rad > 0.0, "options.sigma_model_rad",
          "finite and > 0", o.sigma_model_rad);
  require(std::isfinite(o.correlation_length_m) && o.correlation_length_m > 0.0,
          "options.correlation_length_m", "finite and > 0", o.correlation_length_m);
  require(std::isfinite(o.omega_ie_rad_s) && o.omega_ie_rad_s >= 0.0, "options.omega_ie_rad_s",
          "finite and ≥ 0", o.omega_ie_rad_s);
  require(std::isfinite(o.stationary_speed_m_s) && o.stationary_speed_m_s >= 0.0,
          "options.stationary_speed_m_s", "finite and ≥ 0", o.stationary_speed_m_s);
}

bool is_stationary(double speed_m_s, const ModelOptions& options) {
  // V = 0 is stationary even with a threshold of 0.
  return speed_m_s < options.stationary_speed_m_s || speed_m_s == 0.0;
}

double omega0_rad_s(double speed_m_s, const ModelOptions& options) {
  require(std::isfinite(speed_m_s) && speed_m_s >= 0.0, "speed_m_s", "finite and ≥ 0", speed_m_s);
  if (is_stationary(speed_m_s, options)) return 0.0;
  return 2.0 * units::kPi * speed_m_s / options.correlation_length_m;
}

double process_noise_density(double speed_m_s, const ModelOptions& options) {
  const double s = options.sigma_model_rad;
  return s * s * 4.0 * options.zeta * omega0_rad_s(speed_m_s, options);
}

Eigen::Vector3d transport_rate(double lat_rad, double lat_rate_rad_s, double lon_rate_rad_s) {
  require(std::isfinite(lat_rad) && std::abs(lat_rad) <= 0.5 * units::kPi, "lat_rad",
          "finite and within ±90°", lat_rad);
  require(std::isfinite(lat_rate_rad_s), "lat_rate_rad_s", "finite", lat_rate_rad_s);
  require(std::isfinite(lon_rate_rad_s), "lon_rate_rad_s", "finite", lon_rate_rad_s);
  return {-lat_rate_rad_s, lon_rate_rad_s * std::cos(lat_rad), lon_rate_rad_s * std::sin(lat_rad)};
}

filter::ContinuousModel<State::size, Noise::size> continuous_model(
    double lat_rad, double speed_m_s, const ModelOptions& options,
    const Eigen::Vector3d& transport_rate_rad_s) {
  validate(options);
  check_lat_speed(lat_rad, speed_m_s);
  require(transport_rate_rad_s.allFinite(), "transport_rate_rad_s", "finite",
          transport_rate_rad_s.norm());
  using S = State;
  using W = Noise;
  filter::ContinuousModel<S::size, W::size> m;
  m.F.setZero();
  m.G.setZero();
  m.q_c.setZero();
  // Ω = ω_ie·(0, cos L, sin L) + ω_en; the sums keep the Earth-rate entries bit for bit when
  // ω_en = 0.
  const double east = transport_rate_rad_s.x();                                             // Ω_E
  const double north = options.omega_ie_rad_s * std::cos(lat_rad) + transport_rate_rad_s.y();  // Ω_N
  const double up = options.omega_ie_rad_s * std::sin(lat_rad) + transport_rate_rad_s.z();     // Ω_U
  // φ̇ = −Ω×φ − ε_U·e_U.
  m.F(S::phi_e, S::phi_n) = up;
  m.F(S::phi_e, S::phi_u) = -north;
  m.F(S::phi_n, S::phi_e) = -up;
  m.F(S::phi_u, S::phi_e) = north;
  if (east != 0.0) {  // (no −0.0 entries in the Earth-rate model's F)
    m.F(S::phi_n, S::phi_u) = east;
    m.F(S::phi_u, S::phi_n) = -east;
  }
  m.F(S::phi_u, S::eps_u) = -1.0;
  m.G(S::delta_eta, W::w_e) = 1.0;
  m.G(S::delta_xi, W::w_n) = 1.0;
  if (is_stationary(speed_m_s, options)) return m;  // δ constant, x frozen, q = 0
  const double w0 = omega0_rad_s(speed_m_s, options);
  const double q = process_noise_density(speed_m_s, options);
  m.F(S::x_e, S::delta_eta) = 1.0;
  m.F(S::delta_eta, S::x_e) = -w0 * w0;
  m.F(S::delta_eta, S::delta_eta) = -2.0 * options.zeta * w0;
  m.F(S::x_n, S::delta_xi) = 1.0;
  m.F(S::delta_xi, S::x_n) = -w0 * w0;
  m.F(S::delta_xi, S::delta_xi) = -2.0 * options.zeta * w0;
  m.q_c(W::w_e, W::w_e) = q;
  m.q_c(W::w_n, W::w_n) = q;
  return m;
}

filter::DiscreteModel<State::size> discrete_model(double lat_rad, double speed_m_s, double dt_s,
                                                  const ModelOptions& options,
                                                  DiscretisationMethod method,
                                                  const Eigen::Vector3d& transport_rate_rad_s) {
  require(std::isfinite(dt_s) && dt_s > 0.0, "dt_s", "finite and > 0", dt_s);
  const auto m = continuous_model(lat_rad, speed_m_s, options, transport_rate_rad_s);
  switch (method) {
    case DiscretisationMethod::Exact:
      return filter::discretise(m, dt_s, filter::Discretisation::VanLoan);
    case DiscretisationMethod::PublishedFirstOrder:
      // q_c holds q, taken as the variance of a held noise sample: Q_d = Δt²·G·Q·Gᵀ.
      return filter::discretise(m, dt_s, filter::Discretisation::FirstOrderDiscreteNoise);
  }
  throw InputError("unknown discretisation method", ErrorContext{{}, {}, "options.discretisation"});
}

ObservationMatrix observation_matrix() {
  ObservationMatrix H = ObservationMatrix::Zero();
  H(Obs::east, State::phi_e) = 1.0;
  H(Obs::east, State::delta_xi) = 1.0;
  H(Obs::north, State::phi_n) = 1.0;
  H(Obs::north, State::delta_eta) = -1.0;
  return H;
}

ObservationCovariance observation_covariance(double sigma_east_rad, double sigma_north_rad) {
  require(std::isfinite(sigma_east_rad) && sigma_east_rad > 0.0, "options.sigma_obs_east_rad",
          "finite and > 0", sigma_east_rad);
  require(std::isfinite(sigma_north_rad) && sigma_north_rad > 0.0, "options.sigma_obs_north_rad",
          "finite and > 0", sigma_north_rad);
  ObservationCovariance R = ObservationCovariance::Zero();
  R(Obs::east, Obs::east) = sigma_east_rad * sigma_east_rad;
  R(Obs::north, Obs::north) = sigma_north_rad * sigma_north_rad;
  return R;
}

void validate(const InitialSigmas& s) {
  auto pos = [](double v, const char* name) {
    require(std::isfinite(v) && v > 0.0, std::string("options.initial.") + name, "finite and > 0",
            v);
  };
  pos(s.phi_e_rad, "phi_e_rad");
  pos(s.phi_n_rad, "phi_n_rad");
  pos(s.phi_u_rad, "phi_u_rad");
  pos(s.eps_u_rad_s, "eps_u_rad_s");
  if (s.x_rad_s) pos(*s.x_rad_s, "x_rad_s");
  if (s.delta_rad) pos(*s.delta_rad, "delta_rad");
}

filter::Estimate<State::size> initial_estimate(const InitialSigmas& sigmas,
                                               const ModelOptions& options,
                                               double reference_speed_m_s) {
  validate(sigmas);
  validate(options);
  StateVector sd;
  sd(State::phi_e) = sigmas.phi_e_rad;
  sd(State::phi_n) = sigmas.phi_n_rad;
  sd(State::phi_u) = sigmas.phi_u_rad;
  sd(State::eps_u) = sigmas.eps_u_rad_s;
  const double w0 = omega0_rad_s(reference_speed_m_s, options);
  const double sx = sigmas.x_rad_s ? *sigmas.x_rad_s
                                   : (w0 > 0.0 ? options.sigma_model_rad / w0
                                               : options.sigma_model_rad * 1.0);
  sd(State::x_e) = sx;
  sd(State::x_n) = sx;
  const double sdel = sigmas.delta_rad ? *sigmas.delta_rad : options.sigma_model_rad;
  sd(State::delta_eta) = sdel;
  sd(State::delta_xi) = sdel;
  return {StateVector::Zero(), sd.cwiseAbs2().asDiagonal()};
}

}  // namespace meridian::dov
