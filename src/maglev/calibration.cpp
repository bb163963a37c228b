#include "meridian/maglev/calibration.hpp"

#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "context.hpp"
#include "meridian/adjust/least_squares.hpp"
#include "meridian/adjust/nonlinear.hpp"
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
  bool same = true;
  for (const auto& s : in.setups) same = same && s.mean1_A.value == s.mean2_A.value;
  if (same)
    throw InputError(
        "position 1 and position 2 have the same means at every set-up (one column or series "
        "given for both positions?)",
        at("setups"));
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

// Where the straight lines meet: sin α* = u = (c2 − c1)/(k1 − k2), I* = k1·u + c1, σ by
// first-order propagation. Throws NumericalError for parallel lines or |u| ≥ 1. The starting
// point of the exact fit (linear_best_azimuth_rad and constant_deviation_A set).
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
  r.linear_best_azimuth_rad = {as, std::sqrt(gu.dot(C * gu)) / std::cos(as)};
  r.constant_deviation_A = {is, std::sqrt(gi.dot(C * gi))};
}

// The exact model I_p = k_p·sin(α − α*) + I* for both positions at once, x = (k1, k2, α*, I*),
// observations (mean1 of every set-up, then mean2), from the straight lines' solution in r.
// Sets position1/2 (curves, residuals, the positions' shares of the test), best_azimuth_rad,
// constant_deviation_A, fit_test, covariance, iterations; returns the covariance.
Eigen::Matrix4d fit_exact(const LineObservations& o, double alpha, CalibrationResult& r) {
  const std::size_t n = o.azimuth_rad.size();
  const auto N = static_cast<Eigen::Index>(n);
  Eigen::VectorXd l(2 * N), s(2 * N);
  for (Eigen::Index j = 0; j < N; ++j) {
    const auto u = static_cast<std::size_t>(j);
    l(j) = o.mean1_A[u].value;
    s(j) = o.mean1_A[u].sigma;
    l(N + j) = o.mean2_A[u].value;
    s(N + j) = o.mean2_A[u].sigma;
  }
  adjust::NonlinearModel m;
  m.predict = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd f(2 * N);
    for (Eigen::Index j = 0; j < N; ++j) {
      const double sn = std::sin(o.azimuth_rad[static_cast<std::size_t>(j)] - x(2));
      f(j) = x(0) * sn + x(3);
      f(N + j) = x(1) * sn + x(3);
    }
    return f;
  };
  m.jacobian = [&](const Eigen::VectorXd& x) {
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * N, 4);
    for (Eigen::Index j = 0; j < N; ++j) {
      const double d = o.azimuth_rad[static_cast<std::size_t>(j)] - x(2);
      J(j, 0) = std::sin(d);
      J(N + j, 1) = std::sin(d);
      J(j, 2) = -x(0) * std::cos(d);
      J(N + j, 2) = -x(1) * std::cos(d);
      J(j, 3) = J(N + j, 3) = 1.0;
    }
    return J;
  };
  Eigen::Vector4d x0(r.position1.slope_A_per_rad.value, r.position2.slope_A_per_rad.value,
                     r.linear_best_azimuth_rad.value, r.constant_deviation_A.value);
  adjust::NonlinearOptions opt;
  opt.step_tolerance = 1e-10;
  // Steps far below the straight lines' σ do not matter (and rounding hides them).
  opt.step_scale = Eigen::Vector4d(r.position1.slope_A_per_rad.sigma,
                                   r.position2.slope_A_per_rad.sigma,
                                   std::max(r.linear_best_azimuth_rad.sigma, 1e-12),
                                   std::max(r.constant_deviation_A.sigma, 1e-18));
  const Eigen::MatrixXd sigma_ll = s.array().square().matrix().asDiagonal();
  const adjust::NonlinearResult f = adjust::solve_nonlinear(m, l, sigma_ll, x0, opt);
  const Eigen::Matrix4d C = f.covariance_aposteriori;
  r.iterations = f.iterations;
  r.fit_test = adjust::global_test(f, alpha);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      r.covariance[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = C(i, j);
  const double as = f.x(2), is = f.x(3);
  r.best_azimuth_rad = {as, std::sqrt(C(2, 2))};
  r.constant_deviation_A = {is, std::sqrt(C(3, 3))};
  for (int p = 0; p < 2; ++p) {
    LineFit& lf = p == 0 ? r.position1 : r.position2;
    const double k = f.x(p);
    // c = I* − k·sin α*: gradient in (k1, k2, α*, I*).
    Eigen::Vector4d gk = Eigen::Vector4d::Zero(), gc = Eigen::Vector4d::Zero();
    gk(p) = 1.0;
    gc(p) = -std::sin(as);
    gc(2) = -k * std::cos(as);
    gc(3) = 1.0;
    lf.slope_A_per_rad = {k, std::sqrt(C(p, p))};
    lf.intercept_A = {is - k * std::sin(as), std::sqrt(gc.dot(C * gc))};
    lf.covariance = gk.dot(C * gc);
    const auto v = f.residuals.segment(p * N, N);
    lf.residuals_A.assign(v.data(), v.data() + v.size());
    const double vtpv = (v.array() / s.segment(p * N, N).array()).square().sum();
    lf.global_test = adjust::global_test(vtpv, static_cast<int>(n) - 2, alpha);
  }
  return C;
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
  if (r.fit_test.rejected)
    r.warnings.push_back(fmt::format(
        "model check: the residuals of k·sin(α − α*) + I* exceed the means' σ (σ̂0 = {:.2f}, "
        "p = {:.3g}): the σ of the means are optimistic or the model does not hold (σ of the "
        "results scaled by σ̂0)",
        r.fit_test.sigma0, r.fit_test.p_value));
  if (r.mean_line.global_test.dof > 0 && r.mean_line.global_test.rejected)
    r.warnings.push_back(fmt::format(
        "the mean line's residuals exceed the means' σ (σ̂0 = {:.2f}): the σ may be optimistic",
        r.mean_line.global_test.sigma0));
  if (in.nominal_scale_A_s_per_rad) {
    const double q = r.scale_A_s_per_rad.value / *in.nominal_scale_A_s_per_rad;
    r.scale_ratio_to_nominal = q;
    if (!(std::abs(std::log10(std::abs(q))) < 1.5) || q < 0.0) {
      r.unit_slip_suspected = true;
      r.warnings.push_back(fmt::format(
          "UNIT SLIP? K from the slopes ({:.6g} A·s/rad) is {:.3g} × the nominal K ({:.6g}): the "
          "currents are not in the unit their header states (values in A under an [mA] header "
          "give K 1000× too small); every result in A is off by the same factor",
          r.scale_A_s_per_rad.value, q, *in.nominal_scale_A_s_per_rad));
    }
  }
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
  } catch (Error& e) {
    e.add_context("", std::nullopt, "setups");
    throw;
  }
  const double f = 2.0 * units::kEarthRotationRate_rad_s * std::cos(in.latitude_rad);
  {
    // The straight lines: the starting point, and their α*, K for comparison.
    const Eigen::Matrix4d CL = line_covariance(r.position1, r.position2);
    intersect(CL, r);
    const Eigen::Vector4d g(1.0 / f, 0, -1.0 / f, 0);
    r.linear_scale_A_s_per_rad = {
        (r.position1.slope_A_per_rad.value - r.position2.slope_A_per_rad.value) / f,
        std::sqrt(g.dot(CL * g))};
  }
  Eigen::Matrix4d C;
  try {
    C = fit_exact(o, in.alpha, r);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "setups");
    throw;
  }
  const double k1 = r.position1.slope_A_per_rad.value, k2 = r.position2.slope_A_per_rad.value;
  const Eigen::Vector4d g_trend(1, 1, 0, 0);
  r.trend_deviation_A_per_rad = {k1 + k2, std::sqrt(g_trend.dot(C * g_trend))};
  r.trend_z = r.trend_deviation_A_per_rad.value / r.trend_deviation_A_per_rad.sigma;
  r.trend_significant =
      adjust::student_t_two_sided_probability(r.trend_z, r.fit_test.dof) < in.alpha;
  const Eigen::Vector4d g_scale(1.0 / f, -1.0 / f, 0, 0);
  r.scale_A_s_per_rad = {(k1 - k2) / f, std::sqrt(g_scale.dot(C * g_scale))};
  // The mean line about the fitted α*.
  {
    std::vector<double> shifted = o.azimuth_rad;
    for (double& a : shifted) a -= r.best_azimuth_rad.value;
    try {
      r.mean_line = fit_line(shifted, o.mean_A, in.alpha);
    } catch (Error& e) {
      e.add_context("", std::nullopt, "setups");
      throw;
    }
  }
  r.mean_slope_z = r.mean_line.slope_A_per_rad.value / r.mean_line.slope_A_per_rad.sigma;
  r.mean_line_constant = adjust::normal_two_sided_probability(r.mean_slope_z) >= in.alpha;
  add_findings(in, f, r);
  return r;
}

}  // namespace meridian::maglev
