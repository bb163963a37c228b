#include "meridian/gyro/constants.hpp"

#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gyro {
namespace {

using units::kTwoPi;

void require_positive(double v, std::string_view what, std::string_view unit) {
  if (!std::isfinite(v) || v <= 0.0)
    throw InputError(fmt::format("{} must be finite and > 0 (got {} {})", what, v, unit));
}

void require_sigma(double s, std::string_view what) {
  if (!std::isfinite(s) || s < 0.0)
    throw InputError(fmt::format("σ of {} must be finite and ≥ 0 (got {})", what, s));
}

}  // namespace

void check_latitude(double lat_rad, double limit_rad) {
  if (!std::isfinite(limit_rad) || limit_rad <= 0.0 || limit_rad >= units::kPi / 2)
    throw InputError(fmt::format("latitude limit {:.1f}° must lie strictly between 0° and 90°",
                                 units::rad_to_deg(limit_rad)));
  if (!std::isfinite(lat_rad)) throw InputError("latitude is not a finite number");
  if (std::abs(lat_rad) > limit_rad)
    throw InputError(fmt::format("latitude {:.1f}° is above the usable limit {:.1f}° (cos φ → 0)",
                                 units::rad_to_deg(lat_rad), units::rad_to_deg(limit_rad)));
}

GyroPeriods periods_from_physics(const PhysicalGyro& gyro, double latitude_rad,
                                 double latitude_limit_rad) {
  require_positive(gyro.spin_momentum_Nms, "spin angular momentum H", "N·m·s");
  require_positive(gyro.moment_of_inertia_kgm2, "moment of inertia J_z", "kg·m²");
  require_positive(gyro.tape_torsion_Nm_per_rad, "tape torsion constant D_B", "N·m/rad");
  check_latitude(latitude_rad, latitude_limit_rad);

  const double jz = gyro.moment_of_inertia_kgm2;
  const double db = gyro.tape_torsion_Nm_per_rad;
  const double dk =
      gyro.spin_momentum_Nms * units::kEarthRotationRate_rad_s * std::cos(latitude_rad);
  GyroPeriods p;
  p.directive_torque_Nm_per_rad = dk;
  p.tracking_s = kTwoPi * std::sqrt(jz / dk);
  p.free_s = kTwoPi * std::sqrt(jz / db);
  p.nontracking_s = kTwoPi * std::sqrt(jz / (dk + db));
  p.torsion_ratio = db / dk;
  return p;
}

double torsion_ratio_from_free_period(double tracking_period_s, double free_period_s) {
  require_positive(tracking_period_s, "tracking period T_A", "s");
  require_positive(free_period_s, "free (motor-off) period T_F", "s");
  const double r = tracking_period_s / free_period_s;
  return r * r;
}

double torsion_ratio_from_nontracking_period(double tracking_period_s,
                                             double nontracking_period_s) {
  require_positive(tracking_period_s, "tracking period T_A", "s");
  require_positive(nontracking_period_s, "non-tracking period T_B", "s");
  // The tape adds to the restoring torque, so the clamped oscillation is faster.
  if (nontracking_period_s >= tracking_period_s)
    throw InputError(fmt::format(
        "non-tracking period T_B = {} s must be shorter than the tracking period T_A = {} s "
        "(λ = (T_A/T_B)² − 1 must be > 0)",
        nontracking_period_s, tracking_period_s));
  const double r = tracking_period_s / nontracking_period_s;
  return r * r - 1.0;
}

Uncertain torsion_ratio_from_free_period(Uncertain tracking_period_s, Uncertain free_period_s) {
  require_sigma(tracking_period_s.sigma, "the tracking period T_A");
  require_sigma(free_period_s.sigma, "the free period T_F");
  const double ta = tracking_period_s.value;
  const double tf = free_period_s.value;
  const double lam = torsion_ratio_from_free_period(ta, tf);
  const double d_ta = 2.0 * ta / (tf * tf);
  const double d_tf = -2.0 * ta * ta / (tf * tf * tf);
  return {lam, std::hypot(d_ta * tracking_period_s.sigma, d_tf * free_period_s.sigma)};
}

Uncertain torsion_ratio_from_nontracking_period(Uncertain tracking_period_s,
                                                Uncertain nontracking_period_s) {
  require_sigma(tracking_period_s.sigma, "the tracking period T_A");
  require_sigma(nontracking_period_s.sigma, "the non-tracking period T_B");
  const double ta = tracking_period_s.value;
  const double tb = nontracking_period_s.value;
  const double lam = torsion_ratio_from_nontracking_period(ta, tb);
  const double d_ta = 2.0 * ta / (tb * tb);
  const double d_tb = -2.0 * ta * ta / (tb * tb * tb);
  return {lam, std::hypot(d_ta * tracking_period_s.sigma, d_tb * nontracking_period_s.sigma)};
}

Uncertain rescale_torsion_ratio(Uncertain lambda0, double lat0_rad, double lat_rad,
                                double latitude_limit_rad) {
  if (!std::isfinite(lambda0.value) || lambda0.value < 0.0)
    throw InputError(fmt::format("torsion ratio λ must be finite and ≥ 0 (got {})", lambda0.value));
  require_sigma(lambda0.sigma, "the torsion ratio λ");
  check_latitude(lat0_rad, latitude_limit_rad);
  check_latitude(lat_rad, latitude_limit_rad);
  // D_B is a tape property, D_K ∝ cos φ, hence λ ∝ 1/cos φ.
  const double f = std::cos(lat0_rad) / std::cos(lat_rad);
  return {lambda0.value * f, lambda0.sigma * f};
}

Uncertain rescale_transit_factor(Uncertain c0, double lambda0, double lat0_rad, double lat_rad,
                                 double latitude_limit_rad) {
  if (!std::isfinite(c0.value) || c0.value <= 0.0)
    throw InputError(fmt::format("transit factor c must be finite and > 0 (got {})", c0.value));
  require_sigma(c0.sigma, "the transit factor c");
  const double lambda = rescale_torsion_ratio({lambda0, 0.0}, lat0_rad, lat_rad, latitude_limit_rad).value;
  const double f = std::pow((1.0 + lambda) / (1.0 + lambda0), 1.5) * std::sqrt(std::cos(lat_rad) / std::cos(lat0_rad));
  return {c0.value * f, c0.sigma * f};
}

}  // namespace meridian::gyro
