#include "meridian/dov/simulator.hpp"

#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/geodesy/ellipsoid.hpp"
#include "meridian/geodesy/frames.hpp"

namespace meridian::dov {
namespace {

void require(bool ok, const char* name, const char* what, double value) {
  if (!ok)
    throw InputError(fmt::format("simulation.{} must be {}, is {}", name, what, value),
                     ErrorContext{{}, {}, std::string("simulation.") + name});
}

/// One second-order Gauss–Markov process (x, δ) with its exact discrete step (file comment).
class GaussMarkov2 {
 public:
  GaussMarkov2(double omega0, double zeta, double sigma, double dt) {
    if (omega0 <= 0.0) {  // stationary: δ constant, x frozen
      phi_ = Eigen::Matrix2d::Identity();
      chol_.setZero();
      p_inf_ = Eigen::Vector2d(sigma * 1.0, sigma).cwiseAbs2().asDiagonal();
      return;
    }
    const double a = zeta * omega0;
    const double wd = omega0 * std::sqrt(1.0 - zeta * zeta);
    const double e = std::exp(-a * dt);
    const double c = std::cos(wd * dt);
    const double s = std::sin(wd * dt);
    phi_ << e * (c + (a / wd) * s), e * s / wd, -e * (omega0 * omega0 / wd) * s,
        e * (c - (a / wd) * s);
    p_inf_ = Eigen::Vector2d(sigma / omega0, sigma).cwiseAbs2().asDiagonal();
    const Eigen::Matrix2d q = p_inf_ - phi_ * p_inf_ * phi_.transpose();
    // 2×2 Cholesky, q symmetric positive (semi-)definite.
    const double l00 = std::sqrt(std::max(0.0, q(0, 0)));
    const double l10 = l00 > 0.0 ? q(1, 0) / l00 : 0.0;
    const double l11 = std::sqrt(std::max(0.0, q(1, 1) - l10 * l10));
    chol_ << l00, 0.0, l10, l11;
  }
  Eigen::Vector2d draw_stationary(std::mt19937_64& rng, std::normal_distribution<double>& nd) const {
    return Eigen::Vector2d(std::sqrt(p_inf_(0, 0)) * nd(rng), std::sqrt(p_inf_(1, 1)) * nd(rng));
  }
  Eigen::Vector2d step(const Eigen::Vector2d& x, std::mt19937_64& rng,
                       std::normal_distribution<double>& nd) const {
    const Eigen::Vector2d u(nd(rng), nd(rng));
    return phi_ * x + chol_ * u;
  }

 private:
  Eigen::Matrix2d phi_, chol_, p_inf_;
};

/// The exact step of φ̇ = −Ω×φ − ε·e_U over dt (file comment); Ω = w·u in ENU, u a unit
/// vector, w ≥ 0 (rad/s).
Eigen::Vector3d attitude_step(const Eigen::Vector3d& phi, const Eigen::Vector3d& u, double w,
                              double eps_u, double dt) {
  if (w == 0.0) return phi - Eigen::Vector3d(0.0, 0.0, eps_u * dt);
  const Eigen::Matrix3d k = cross_matrix(u);
  const double wt = w * dt;
  const Eigen::Matrix3d e =
      Eigen::Matrix3d::Identity() - std::sin(wt) * k + (1.0 - std::cos(wt)) * (k * k);
  const Eigen::Matrix3d j = dt * Eigen::Matrix3d::Identity() - ((1.0 - std::cos(wt)) / w) * k +
                            (dt - std::sin(wt) / w) * (k * k);
  return e * phi - j * Eigen::Vector3d(0.0, 0.0, eps_u);
}

/// The checks of the file comment's options (InputError "simulation.<name>").
void validate(const SimulationOptions& o) {
  const double max_lat = 89.0 * units::kDegree;
  require(std::isfinite(o.start_lat_rad) && std::abs(o.start_lat_rad) < max_lat, "start_lat_rad",
          "finite and within ±89°", o.start_lat_rad);
  require(std::isfinite(o.start_lon_rad), "start_lon_rad", "finite", o.start_lon_rad);
  require(std::isfinite(o.height_m), "height_m", "finite", o.height_m);
  require(std::isfinite(o.heading_rad), "heading_rad", "finite", o.heading_rad);
  require(std::isfinite(o.speed_m_s) && o.speed_m_s >= 0.0, "speed_m_s", "finite and ≥ 0",
          o.speed_m_s);
  require(std::isfinite(o.rate_hz) && o.rate_hz > 0.0, "rate_hz", "finite and > 0", o.rate_hz);
  require(std::isfinite(o.duration_s) && o.duration_s * o.rate_hz >= 1.0, "duration_s",
          "finite and ≥ 1/rate_hz", o.duration_s);
  require(std::isfinite(o.start_time_s), "start_time_s", "finite", o.start_time_s);
  require(std::isfinite(o.eps_u_rad_s), "eps_u_rad_s", "finite", o.eps_u_rad_s);
  require(o.initial_attitude_error_rad.allFinite(), "initial_attitude_error_rad", "finite",
          o.initial_attitude_error_rad.norm());
  require(std::isfinite(o.sigma_ins_rad) && o.sigma_ins_rad >= 0.0, "sigma_ins_rad",
          "finite and ≥ 0", o.sigma_ins_rad);
  const ModelOptions& tm = o.truth_model;
  require(std::isfinite(tm.zeta) && tm.zeta > 0.0 && tm.zeta < 1.0, "truth_model.zeta",
          "in (0, 1)", tm.zeta);
  require(std::isfinite(tm.sigma_model_rad) && tm.sigma_model_rad >= 0.0,
          "truth_model.sigma_model_rad", "finite and ≥ 0", tm.sigma_model_rad);
  require(std::isfinite(tm.correlation_length_m) && tm.correlation_length_m > 0.0,
          "truth_model.correlation_length_m", "finite and > 0", tm.correlation_length_m);
  require(std::isfinite(tm.omega_ie_rad_s) && tm.omega_ie_rad_s >= 0.0,
          "truth_model.omega_ie_rad_s", "finite and ≥ 0", tm.omega_ie_rad_s);
  require(std::isfinite(tm.stationary_speed_m_s) && tm.stationary_speed_m_s >= 0.0,
          "truth_model.stationary_speed_m_s", "finite and ≥ 0", tm.stationary_speed_m_s);
}

/// The radii of curvature N (prime vertical) and M (meridian) of WGS84 at latitude `lat`,
/// plus the height.
struct Radii {
  double n_m, m_m;
};
Radii radii(const geodesy::Ellipsoid& ell, double e2, double lat, double height_m) {
  const double sl = std::sin(lat);
  const double w = std::sqrt(1.0 - e2 * sl * sl);
  return {ell.a_m / w + height_m, ell.a_m * (1.0 - e2) / (w * w * w) + height_m};
}

/// A simulated line between its samples (file comment): the track, the two Gauss–Markov
/// processes (x_E, δη) and (x_N, δξ), the LGU/GNSS attitude error φ and the random stream.
class Simulation {
 public:
  Simulation(const SimulationOptions& o, double dt)
      : o_(o),
        dt_(dt),
        field_(o.model_field ? o.model_field : ModelField(synthetic_model_deflection)),
        ell_(geodesy::wgs84()),
        e2_(ell_.f * (2.0 - ell_.f)),
        rng_(o.seed),
        gm_(is_stationary(o.speed_m_s, o.truth_model)
                ? 0.0
                : 2.0 * units::kPi * o.speed_m_s / o.truth_model.correlation_length_m,
            o.truth_model.zeta, o.truth_model.sigma_model_rad, dt),
        phi_(o.initial_attitude_error_rad),
        lat_(o.start_lat_rad),
        lon_(o.start_lon_rad) {
    east_ = gm_.draw_stationary(rng_, nd_);
    north_ = gm_.draw_stationary(rng_, nd_);
  }

  /// From sample k−1 to sample k: the track, then the attitude error and the processes.
  void advance(std::size_t k) {
    const Radii r = radii(ell_, e2_, lat_, o_.height_m);
    const double lat_prev = lat_;
    lat_ += o_.speed_m_s * std::cos(o_.heading_rad) * dt_ / r.m_m;
    lon_ += o_.speed_m_s * std::sin(o_.heading_rad) * dt_ / (r.n_m * std::cos(lat_prev));
    if (!(std::abs(lat_) < kMaxLat))
      throw InputError(fmt::format("the track reaches latitude {:.4f}° at sample {} (limit "
                                   "±89°)",
                                   lat_ / units::kDegree, k),
                       ErrorContext{{}, {}, "simulation.duration_s"});
    const double lat_mid = 0.5 * (lat_ + lat_prev);
    Eigen::Vector3d u(0.0, std::cos(lat_mid), std::sin(lat_mid));
    double rate = o_.truth_model.omega_ie_rad_s;  // |Ω|
    if (o_.transport_rate) add_transport_rate(lat_mid, u, rate);
    phi_ = attitude_step(phi_, u, rate, o_.eps_u_rad_s, dt_);
    east_ = gm_.step(east_, rng_, nd_);
    north_ = gm_.step(north_, rng_, nd_);
  }

  /// Sample k at time t and its truth.
  void sample(double t, std::size_t k, Sample& s, Truth& tr) {
    const EtaXi model = field_(lat_, lon_, o_.height_m);
    if (!std::isfinite(model.eta_rad) || !std::isfinite(model.xi_rad))
      throw InputError(fmt::format("the model field is not finite at sample {}", k),
                       ErrorContext{{}, {}, "simulation.model_field"});
    tr.eta_rad = model.eta_rad + east_(1);
    tr.xi_rad = model.xi_rad + north_(1);
    tr.state = state();
    const AttitudeDifference v{o_.sigma_ins_rad * nd_(rng_), o_.sigma_ins_rad * nd_(rng_),
                               o_.sigma_ins_rad * nd_(rng_)};
    const Eigen::Matrix3d body_to_nav = body_attitude(t);
    s.time_s = t;
    s.lat_rad = lat_;
    s.lon_rad = lon_;
    s.height_m = o_.height_m;
    s.speed_m_s = o_.speed_m_s;
    s.lgu_body_to_nav = rotation_from_difference({phi_(0), phi_(1), phi_(2)}) * body_to_nav;
    s.ins_body_to_nav =
        rotation_from_difference(v) * plumb_to_nav(tr).transpose() * body_to_nav;
    s.model_eta_rad = model.eta_rad;
    s.model_xi_rad = model.xi_rad;
  }

 private:
  static constexpr double kMaxLat = 89.0 * units::kDegree;

  // SimulationOptions::transport_rate: Ω = ω_ie·u + ω_en at the step's mid-point, from the
  // velocity (model.hpp's transport_rate with L̇ = V·cos α/M, λ̇ = V·sin α/(N·cos L)); on
  // return u is its direction and rate its size.
  void add_transport_rate(double lat_mid, Eigen::Vector3d& u, double& rate) const {
    const Radii r = radii(ell_, e2_, lat_mid, o_.height_m);
    const Eigen::Vector3d omega =
        rate * u + transport_rate(lat_mid, o_.speed_m_s * std::cos(o_.heading_rad) / r.m_m,
                                  o_.speed_m_s * std::sin(o_.heading_rad) /
                                      (r.n_m * std::cos(lat_mid)));
    rate = omega.norm();
    if (rate > 0.0) u = omega / rate;
  }

  // The true state [φ_E, φ_N, φ_U, ε_U, x_E, x_N, δη, δξ] now.
  StateVector state() const {
    StateVector x;
    x(State::phi_e) = phi_(0);
    x(State::phi_n) = phi_(1);
    x(State::phi_u) = phi_(2);
    x(State::eps_u) = o_.eps_u_rad_s;
    x(State::x_e) = east_(0);
    x(State::x_n) = north_(0);
    x(State::delta_eta) = east_(1);
    x(State::delta_xi) = north_(1);
    return x;
  }

  // C_b^n: heading about up, a 1° pitch oscillation (37 s) and a 2° roll oscillation (11 s).
  Eigen::Matrix3d body_attitude(double t) const {
    const double pitch = units::kDegree * std::sin(2.0 * units::kPi * t / 37.0);
    const double roll = 2.0 * units::kDegree * std::sin(2.0 * units::kPi * t / 11.0);
    return (Eigen::AngleAxisd(-o_.heading_rad, Eigen::Vector3d::UnitZ()) *
            Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitY()))
        .toRotationMatrix();
  }

  // C_{n′}^n: the shortest rotation of the normal e_U onto the true astronomic zenith.
  Eigen::Matrix3d plumb_to_nav(const Truth& tr) const {
    const Eigen::Vector3d zenith =
        geodesy::astronomic_zenith_enu(geodesy::Deflection{tr.xi_rad, tr.eta_rad}, lat_);
    return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(0.0, 0.0, 1.0), zenith)
        .toRotationMatrix();
  }

  const SimulationOptions& o_;
  const double dt_;
  const ModelField field_;
  const geodesy::Ellipsoid ell_;
  const double e2_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> nd_;
  const GaussMarkov2 gm_;
  Eigen::Vector2d east_, north_;  // (x_E, δη), (x_N, δξ)
  Eigen::Vector3d phi_;
  double lat_, lon_;
};

}  // namespace

EtaXi synthetic_model_deflection(double lat_rad, double lon_rad, double /*height_m*/) {
  const double as = units::kArcsecond;
  EtaXi d;
  d.xi_rad = 6.0 * as * std::sin(lat_rad / 0.004) + 2.0 * as * std::cos(lon_rad / 0.006);
  d.eta_rad = 5.0 * as * std::cos(lon_rad / 0.005) - 3.0 * as * std::sin(lat_rad / 0.007);
  return d;
}

Input simulate(const SimulationOptions& o) {
  validate(o);
  const auto samples = static_cast<std::size_t>(std::floor(o.duration_s * o.rate_hz + 1e-9)) + 1;
  const double dt = 1.0 / o.rate_hz;
  Simulation line(o, dt);
  Input in;
  in.samples.resize(samples);
  in.truth.resize(samples);
  for (std::size_t k = 0; k < samples; ++k) {
    if (k > 0) line.advance(k);
    line.sample(o.start_time_s + static_cast<double>(k) * dt, k, in.samples[k], in.truth[k]);
  }
  return in;
}

}  // namespace meridian::dov
