#include "meridian/gravity/normal_gravity.hpp"

#include <cmath>
#include <numbers>

#include "meridian/core/error.hpp"

namespace meridian::gravity {
namespace {

// q(z)/z³ with x = z², z = E/u (H&M eq. 2-57, q = ½[(1 + 3/z²) atan z − 3/z]).
// Series Σ_{k≥1} (−1)^{k+1} 2k x^{k−1} / ((2k+1)(2k+3)) avoids the
// cancellation of the closed form for Earth-like x ≈ 0.0067.
double q_over_z3(double x) {
  if (x < 0.25) {
    double sum = 0, p = 1;
    for (int k = 1; k < 60; ++k) {
      const double term = (k % 2 ? 2.0 : -2.0) * k * p / ((2.0 * k + 1) * (2.0 * k + 3));
      sum += term;
      if (std::abs(term) < 1e-18 * std::abs(sum)) break;
      p *= x;
    }
    return sum;
  }
  const double z = std::sqrt(x);
  return 0.5 * ((1 + 3 / x) * std::atan(z) - 3 / z) / (x * z);
}

// q'(z)/z² (H&M eq. 2-67, q' = 3(1 + 1/z²)(1 − atan(z)/z) − 1):
// series Σ_{k≥1} (−1)^{k+1} 6 x^{k−1} / ((2k+1)(2k+3)).
double qp_over_z2(double x) {
  if (x < 0.25) {
    double sum = 0, p = 1;
    for (int k = 1; k < 60; ++k) {
      const double term = (k % 2 ? 6.0 : -6.0) * p / ((2.0 * k + 1) * (2.0 * k + 3));
      sum += term;
      if (std::abs(term) < 1e-18 * std::abs(sum)) break;
      p *= x;
    }
    return sum;
  }
  const double z = std::sqrt(x);
  return (3 * (1 + 1 / x) * (1 - std::atan(z) / z) - 1) / x;
}

// J2 of a level ellipsoid with flattening f (H&M eq. 2-90).
double j2_from_f(double a, double gm, double omega, double f) {
  const double e2 = f * (2 - f), b = a * (1 - f), ep2 = e2 / ((1 - f) * (1 - f));
  return (e2 - 2 * omega * omega * b * b * b / (15 * gm * q_over_z3(ep2))) / 3;
}

}  // namespace

NormalFieldParameters wgs84_normal_field() { return {}; }

NormalFieldParameters grs80_normal_field() {
  NormalFieldParameters p;
  p.name = "GRS80";
  p.a_m = 6378137.0;
  p.gm_m3_s2 = 3986005e8;
  p.omega_rad_s = 7292115e-11;
  p.flattening = 0;
  p.j2 = 108263e-8;
  return p;
}

NormalGravity::NormalGravity(const NormalFieldParameters& p)
    : a_(p.a_m), gm_(p.gm_m3_s2), omega_(p.omega_rad_s) {
  if (!(std::isfinite(a_) && a_ > 0)) throw InputError("reference ellipsoid: a must be positive", {"", {}, "a_m"});
  if (!(std::isfinite(gm_) && gm_ > 0)) throw InputError("reference ellipsoid: GM must be positive", {"", {}, "gm_m3_s2"});
  if (!(std::isfinite(omega_) && omega_ >= 0))
    throw InputError("reference ellipsoid: angular velocity must be >= 0", {"", {}, "omega_rad_s"});
  if (p.j2 != 0) {
    if (!(std::isfinite(p.j2) && p.j2 > 0)) throw InputError("reference ellipsoid: J2 must be positive", {"", {}, "j2"});
    // J2(f) increases monotonically with f: bisect on f ∈ (0, 0.2].
    double lo = 0, hi = 0.2;
    if (j2_from_f(a_, gm_, omega_, hi) < p.j2)
      throw InputError("reference ellipsoid: J2 too large for a level ellipsoid", {"", {}, "j2"});
    for (int i = 0; i < 200 && hi - lo > 0; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid == lo || mid == hi) break;
      (j2_from_f(a_, gm_, omega_, mid) < p.j2 ? lo : hi) = mid;
    }
    f_ = 0.5 * (lo + hi);
    j2_ = p.j2;
  } else {
    if (!(std::isfinite(p.flattening) && p.flattening > 0 && p.flattening < 0.2))
      throw InputError("reference ellipsoid: flattening must lie in (0, 0.2)", {"", {}, "flattening"});
    f_ = p.flattening;
    j2_ = j2_from_f(a_, gm_, omega_, f_);
  }
  b_ = a_ * (1 - f_);
  e2_ = f_ * (2 - f_);
  ep2_ = e2_ / ((1 - f_) * (1 - f_));
  E_ = a_ * std::sqrt(e2_);
  q0_ = q_over_z3(ep2_);
  // H&M eqs. 2-73, 2-74 with e' q0'/q0 = H/Q.
  const double P = qp_over_z2(ep2_) / (6 * q0_);
  gamma_e_ = gm_ / (a_ * b_) - (1 + P) * a_ * omega_ * omega_;
  gamma_p_ = gm_ / (a_ * a_) + 2 * P * b_ * omega_ * omega_;
  // Somigliana: γ = (a γe cos²φ + b γp sin²φ)/√(a² cos²φ + b² sin²φ)
  //             = (γe + k sin²φ)/√(1 − e² sin²φ), k = (b γp − a γe)/a.
  k_ = (b_ * gamma_p_ - a_ * gamma_e_) / a_;
}

double NormalGravity::jn(int n) const noexcept {
  if (n < 0 || n % 2) return 0;
  const int k = n / 2;
  double e2n = 1;
  for (int j = 0; j < k; ++j) e2n *= -e2_;
  return -3 * e2n * ((1 - k) + 5 * k * j2_ / e2_) / ((2 * k + 1) * (2 * k + 3));
}

double NormalGravity::surface_gravity_m_s2(double lat_rad) const noexcept {
  const double s = std::sin(lat_rad), s2 = s * s;
  return (gamma_e_ + k_ * s2) / std::sqrt(1 - e2_ * s2);
}

EcefPosition NormalGravity::to_ecef(double lat_rad, double lon_rad, double height_m) const noexcept {
  double sphi = std::sin(lat_rad), cphi = std::cos(lat_rad);
  if (std::abs(lat_rad) == std::numbers::pi / 2) cphi = 0;  // exact at the poles
  const double n = a_ / std::sqrt(1 - e2_ * sphi * sphi);
  const double p = (n + height_m) * cphi;
  return {p * std::cos(lon_rad), p * std::sin(lon_rad), (n * (1 - e2_) + height_m) * sphi};
}

EcefPosition NormalGravity::gravity_vector_m_s2(const EcefPosition& pos) const noexcept {
  // Ellipsoidal-harmonic coordinates (u, β) of the point (H&M eqs. 6-8).
  const double p = std::hypot(pos.x_m, pos.y_m), z = pos.z_m, r2 = p * p + z * z;
  const double Q = r2 - E_ * E_, t2 = 4 * E_ * E_ * z * z, disc = std::sqrt(Q * Q + t2);
  const double u = std::sqrt((Q >= 0 ? Q + disc : t2 / (disc - Q)) / 2);
  const double uE = std::hypot(u, E_);
  double sb = u != 0 ? z * uE : std::copysign(std::sqrt(-Q), z), cb = u != 0 ? p * u : p;
  const double s = std::hypot(sb, cb);
  sb = s != 0 ? sb / s : 1;
  cb = s != 0 ? cb / s : 0;
  const double invw = uE / std::hypot(u, E_ * sb);  // 1/w, H&M eq. 2-63
  // Gravitational part of U in (u, β) (H&M eqs. 2-62, 6-9, 6-10); with
  // x = (E/u)²: q/q0 = (b/u)³ Q(x)/Q(e'²) and E q'/q0 = b³ H(x)/(u² Q(e'²)).
  const double x = (E_ / u) * (E_ / u), bu = b_ / u;
  const double q = q_over_z3(x) / q0_ * bu * bu * bu;
  const double qp = b_ * bu * bu * qp_over_z2(x) / q0_;
  const double ang = (sb * sb - 1.0 / 3) / 2, aw2 = a_ * a_ * omega_ * omega_;
  const double gam_u = -(gm_ + aw2 * qp * ang) * invw / (uE * uE);
  const double gam_b = aw2 * q * sb * cb * invw / uE;
  const double t = u * invw / uE;
  // Back to Cartesian, then the centrifugal acceleration ω² p outward.
  const double gam_p = t * cb * gam_u - invw * sb * gam_b + omega_ * omega_ * p;
  const double gam_z = invw * sb * gam_u + t * cb * gam_b;
  const double cl = p != 0 ? pos.x_m / p : 1, sl = p != 0 ? pos.y_m / p : 0;
  return {gam_p * cl, gam_p * sl, gam_z};
}

double NormalGravity::gravity_magnitude_m_s2(const EcefPosition& pos) const noexcept {
  const EcefPosition g = gravity_vector_m_s2(pos);
  return std::hypot(std::hypot(g.x_m, g.y_m), g.z_m);
}

}  // namespace meridian::gravity
