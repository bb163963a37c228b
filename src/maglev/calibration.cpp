#include "meridian/maglev/calibration.hpp"

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "context.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::maglev {
namespace {
using detail::at;

LineFit fit_line(const std::vector<double>& az, const std::vector<Uncertain>& y, double alpha) {
  const auto n = static_cast<Eigen::Index>(az.size());
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd l(n), s(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    A(i, 0) = std::sin(az[static_cast<std::size_t>(i)]);
    A(i, 1) = 1.0;
    l(i) = y[static_cast<std::size_t>(i)].value;
    s(i) = y[static_cast<std::size_t>(i)].sigma;
  }
  const auto r = adjust::solve_linear_diagonal(A, l, s);
  LineFit f;
  f.slope_A_per_rad = {r.x(0), std::sqrt(r.cofactor(0, 0))};
  f.intercept_A = {r.x(1), std::sqrt(r.cofactor(1, 1))};
  f.covariance = r.cofactor(0, 1);
  f.residuals_A.assign(r.residuals.data(), r.residuals.data() + r.residuals.size());
  f.global_test = adjust::global_test(r, alpha);
  return f;
}


// The set-ups as observations of the three lines (position 1, position 2, their mean), after
// checking them (see calibration.hpp's errors).
struct LineObservations {
  std::vector<double> azimuth_rad;
  std::vector<Uncertain> mean1_A, mean2_A, mean_A;
};

LineObservations observations(const CalibrationInput& in) {
  if (in.setups.size() < 3)
    throw InputError(fmt::format("{} set-ups are too few (at least 3 azimuths)", in.setups.size()),
                     at("setups"));
  if (!std::isfinite(in.latitude_rad) || std::abs(in.latitude_rad) >= units::kPi / 2)
    throw InputError("the latitude must be within ±90° (exclusive)", at("latitude"));
  LineObservations o;
  for (std::size_t i = 0; i < in.setups.size(); ++i) {
    const auto& s = in.setups[i];
    for (const Uncertain* u : {&s.mean1_A, &s.mean2_A})
      if (!std::isfinite(u->value) || !(u->sigma > 0.0) || !std::isfinite(u->sigma))
        throw InputError("a mean needs a finite value and a σ > 0",
                         at(fmt::format("setups[{}]", i)));
    if (!std::isfinite(s.azimuth_rad))
      throw InputError("azimuth is not finite", at(fmt::format("setups[{}].azimuth", i)));
    o.azimuth_rad.push_back(s.azimuth_rad);
    o.mean1_A.push_back(s.mean1_A);
    o.mean2_A.push_back(s.mean2_A);
    o.mean_A.push_back({0.5 * (s.mean1_A.value + s.mean2_A.value),
                        0.5 * std::hypot(s.mean1_A.sigma, s.mean2_A.sigma)});
  }
  bool distinct = false;
  for (double a : o.azimuth_rad) distinct = distinct || a != o.azimuth_rad[0];
  if (!distinct) throw InputError("the set-up azimuths must not all be equal", at("setups"));
  return o;
}

// The covariance of (k1, c1, k2, c2): the two lines are independent.
Eigen::Matrix4d line_covariance(const LineFit& p1, const LineFit& p2) {
  Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
  C(0, 0) = std::pow(p1.slope_A_per_rad.sigma, 2);
  C(1, 1) = std::pow(p1.intercept_A.sigma, 2);
  C(0, 1) = C(1, 0) = p1.covariance;
  C(2, 2) = std::pow(p2.slope_A_per_rad.sigma, 2);
  C(3, 3) = std::pow(p2.intercept_A.sigma, 2);
  C(2, 3) = C(3, 2) = p2.covariance;
  return C;
}

// Where the lines meet: sin α* = u = (c2 − c1)/(k1 − k2), I* = k1·u + c1, σ by first-order
// propagation. Throws NumericalError for parallel lines or |u| ≥ 1.
void intersect(const Eigen::Matrix4d& C, CalibrationResult& r) {
  const double k1 = r.position1.slope_A_per_rad.value, c1 = r.position1.intercept_A.value;
  const double k2 = r.position2.slope_A_per_rad.value, c2 = r.position2.intercept_A.value;
  const double dk = k1 - k2;
  if (std::abs(dk) <= 1e-12 * (std::abs(k1) + std::abs(k2)) || dk == 0.0)
    throw NumericalError("the two lines are parallel (k1 = k2): no intersection", at("setups"));
  const double u = (c2 - c1) / dk;
  if (!(std::abs(u) < 1.0))
    throw NumericalError(fmt::format("the lines intersect at sin α* = {:.6g}, outside (−1, 1)", u),
                         at("setups"));
  const double as = std::asin(u);
  const double is = k1 * u + c1;
  // ∂u/∂(k1, c1, k2, c2); ∂α*/∂· = ∂u/∂· / cos α*.
  const Eigen::Vector4d gu(-u / dk, -1.0 / dk, u / dk, 1.0 / dk);
  Eigen::Vector4d gi = k1 * gu;
  gi(0) += u;
  gi(1) += 1.0;
  r.best_azimuth_rad = {as, std::sqrt(gu.dot(C * gu)) / std::cos(as)};
  r.constant_deviation_A = {is, std::sqrt(gi.dot(C * gi))};
}

// The analysis' warnings and notes: trend deviation, mean line, slopes against a nominal K, the
// lines' global tests. `f` = 2·ω_e·cos φ.
void add_findings(const CalibrationInput& in, double f, CalibrationResult& r) {
  if (r.trend_significant)
    r.warnings.push_back(
        fmt::format("trend deviation: the slopes differ in magnitude (k1 + k2 = {:.6g} A/rad, z = "
                    "{:.2f}): the result "
                    "depends on the set-up azimuth; set up near α* = {:.1f}″",
                    r.trend_deviation_A_per_rad.value, r.trend_z,
                    r.best_azimuth_rad.value / units::kArcsecond));
  if (!r.mean_line_constant)
    r.warnings.push_back(
        fmt::format("calibration defect: the mean line (I1 + I2)/2 has a slope of {:.6g} A/rad "
                    "(z = {:.2f}): the constant deviation is not constant",
                    r.mean_line.slope_A_per_rad.value, r.mean_slope_z));
  if (in.nominal_scale_A_s_per_rad) {
    const double a = *in.nominal_scale_A_s_per_rad * f / 2.0;
    const double z1 = (r.position1.slope_A_per_rad.value - a) / r.position1.slope_A_per_rad.sigma;
    const double z2 = (r.position2.slope_A_per_rad.value + a) / r.position2.slope_A_per_rad.sigma;
    r.notes.push_back(fmt::format(
        "slopes against ±K·ω·cos φ = ±{:.6g} A/rad: z1 = {:.2f}, z2 = {:.2f}", a, z1, z2));
  }
  for (const LineFit* lf : {&r.position1, &r.position2, &r.mean_line})
    if (lf->global_test.dof > 0 && lf->global_test.rejected)
      r.warnings.push_back(fmt::format(
          "a line's residuals exceed the means' σ (σ̂0 = {:.2f}): the σ may be optimistic",
          lf->global_test.sigma0));
}

}  // namespace

CalibrationResult calibrate(const CalibrationInput& in) {
  const LineObservations o = observations(in);
  CalibrationResult r;
  r.source = in.source;
  r.setups = in.setups;
  r.latitude_rad = in.latitude_rad;
  try {
    r.position1 = fit_line(o.azimuth_rad, o.mean1_A, in.alpha);
    r.position2 = fit_line(o.azimuth_rad, o.mean2_A, in.alpha);
    r.mean_line = fit_line(o.azimuth_rad, o.mean_A, in.alpha);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "setups");
    throw;
  }
  const Eigen::Matrix4d C = line_covariance(r.position1, r.position2);
  const double k1 = r.position1.slope_A_per_rad.value, k2 = r.position2.slope_A_per_rad.value;
  const Eigen::Vector4d g_trend(1, 0, 1, 0);
  r.trend_deviation_A_per_rad = {k1 + k2, std::sqrt(g_trend.dot(C * g_trend))};
  r.trend_z = r.trend_deviation_A_per_rad.value / r.trend_deviation_A_per_rad.sigma;
  r.trend_significant = adjust::normal_two_sided_probability(r.trend_z) < in.alpha;
  intersect(C, r);
  const double f = 2.0 * units::kEarthRotationRate_rad_s * std::cos(in.latitude_rad);
  const Eigen::Vector4d g_scale(1.0 / f, 0, -1.0 / f, 0);
  r.scale_A_s_per_rad = {(k1 - k2) / f, std::sqrt(g_scale.dot(C * g_scale))};
  r.mean_slope_z = r.mean_line.slope_A_per_rad.value / r.mean_line.slope_A_per_rad.sigma;
  r.mean_line_constant = adjust::normal_two_sided_probability(r.mean_slope_z) >= in.alpha;
  add_findings(in, f, r);
  return r;
}

}  // namespace meridian::maglev
