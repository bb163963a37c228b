#include "meridian/gyro/reversal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "meridian/adjust/least_squares.hpp"
#include "meridian/adjust/nonlinear.hpp"
#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"

namespace meridian::gyro {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double alt_sign(int i) { return (i % 2 == 0) ? 1.0 : -1.0; }  // (−1)^i

// Linear LS of (R2); i runs 1…n.
adjust::LeastSquaresResult fit_linear(std::span<const double> r) {
  const int n = static_cast<int>(r.size());
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd l(n);
  for (int k = 0; k < n; ++k) {
    const int i = k + 1;
    A(k, 0) = 1.0;
    A(k, 1) = alt_sign(i);
    A(k, 2) = -alt_sign(i) * (2.0 * i - 1.0);
    l(k) = r[static_cast<std::size_t>(k)];
  }
  return adjust::solve_linear_diagonal(A, l, Eigen::VectorXd::Ones(n));
}

// σ of the centre by the policy of ReversalResult. With a stated reading σ
// the a-priori σ is used: with 2–3 degrees of freedom (5–6 reversals) σ̂0 is
// a poor estimate of σ (its mean is 0.89 σ for dof = 2) and the a-posteriori
// σ understates the scatter. The global test guards the stated σ; when it
// rejects, the readings scatter more than stated and the larger σ̂0 is used.
void fill_sigma(ReversalResult& res, double sigma_reading, double q) {
  res.cofactor_centre = q;
  const bool stated = std::isfinite(sigma_reading) && sigma_reading > 0.0;
  res.sigma_reading = stated ? sigma_reading : kNaN;
  if (stated && res.dof > 0) {
    const double ratio = res.sigma0 / sigma_reading;
    res.reading_sigma_test =
        adjust::global_test(res.dof * ratio * ratio, res.dof, kReadingSigmaTestAlpha);
    res.sigma_is_aposteriori = res.reading_sigma_test->rejected;
    res.centre.sigma = (res.sigma_is_aposteriori ? res.sigma0 : sigma_reading) * std::sqrt(q);
  } else if (res.dof > 0) {
    res.centre.sigma = res.sigma0 * std::sqrt(q);
    res.sigma_is_aposteriori = true;
  } else if (stated) {
    res.centre.sigma = sigma_reading * std::sqrt(q);
  } else {
    res.centre.sigma = kNaN;
    res.notes.push_back("no redundancy and no a-priori reading sigma: sigma of the centre unknown");
  }
}

// The σ of one reading that fill_sigma chose (NaN when none).
double reading_sigma_used(const ReversalResult& res) {
  if (res.sigma_is_aposteriori) return res.sigma0;
  return std::isfinite(res.sigma_reading) ? res.sigma_reading : kNaN;
}

// Successive Schuler means (r_i + 2r_{i+1} + r_{i+2})/4 and their spread.
void fill_partial_means(ReversalResult& res, std::span<const double> r) {
  for (std::size_t i = 0; i + 2 < r.size(); ++i)
    res.partial_means.push_back(0.25 * (r[i] + 2.0 * r[i + 1] + r[i + 2]));
  if (res.partial_means.size() >= 2) {
    const auto [lo, hi] = std::minmax_element(res.partial_means.begin(), res.partial_means.end());
    res.partial_means_spread = *hi - *lo;
  }
}

}  // namespace

std::string to_string(ReversalMethod m) {
  switch (m) {
    case ReversalMethod::TwoPoint: return "two-point";
    case ReversalMethod::Schuler: return "schuler";
    case ReversalMethod::LinearLsq: return "lsq-linear";
    case ReversalMethod::NonlinearLsq: return "lsq";
  }
  return "?";
}

ReversalMethod reversal_method_from_string(const std::string& name) {
  for (auto m : {ReversalMethod::TwoPoint, ReversalMethod::Schuler, ReversalMethod::LinearLsq,
                 ReversalMethod::NonlinearLsq})
    if (to_string(m) == name) return m;
  throw InputError(fmt::format(
      "unknown tracking method \"{}\" (expected two-point, schuler, lsq-linear, lsq or all)", name),
      {"", std::nullopt, "method"});
}

void check_reversal_sequence(std::span<const double> r, int min_count) {
  if (static_cast<int>(r.size()) < min_count)
    throw InputError(fmt::format("{} reversal readings given, at least {} needed", r.size(), min_count));
  // The field is the offending element ("[3]"; callers prefix the list's name).
  const auto at = [](std::size_t i) { return ErrorContext{"", std::nullopt, fmt::format("[{}]", i)}; };
  for (std::size_t i = 0; i < r.size(); ++i)
    if (!std::isfinite(r[i])) throw InputError(fmt::format("reading {} is not a finite number", i + 1), at(i));
  for (std::size_t i = 1; i < r.size(); ++i) {
    const double d = r[i] - r[i - 1];
    if (d == 0.0)
      throw InputError(fmt::format("readings {} and {} are equal: not a reversal sequence", i, i + 1), at(i));
    if (i >= 2 && (d > 0) == (r[i - 1] - r[i - 2] > 0))
      throw InputError(fmt::format(
                           "reading {} does not alternate about the centre: readings {}, {}, {} move the same way",
                           i + 1, i - 1, i, i + 1),
                       at(i));
  }
  // Successive readings lie on either side of the centre (the mean of the
  // midpoints): a reading with its sign lost can still zig-zag, but it then
  // falls on its neighbour's side, far from the centre compared with the swing.
  if (r.size() < 3) return;
  double centre = 0.0, swing = 0.0;
  for (std::size_t i = 1; i < r.size(); ++i) {
    centre += (r[i] + r[i - 1]) / 2.0;
    swing += std::fabs(r[i] - r[i - 1]) / 2.0;
  }
  centre /= static_cast<double>(r.size() - 1);
  swing /= static_cast<double>(r.size() - 1);
  for (std::size_t i = 1; i < r.size(); ++i) {
    const double a = r[i - 1] - centre, b = r[i] - centre;
    if (a * b > 0.0 && std::min(std::fabs(a), std::fabs(b)) > 0.25 * swing)
      throw InputError(fmt::format("reading {} lies on the same side of the centre as reading {}: a sign or a digit "
                                   "booked wrong?",
                                   i + 1, i),
                       at(i));
  }
}

std::vector<double> unwrap_circle_readings(std::span<const double> r) {
  std::vector<double> out(r.begin(), r.end());
  if (out.empty()) return out;
  for (std::size_t i = 1; i < out.size(); ++i)
    out[i] = out[0] + wrap_signed_rad(out[i] - out[0]);
  return out;
}

namespace {

void two_point_centre(ReversalResult& res, std::span<const double> r, double sigma_reading) {
  const int n = static_cast<int>(r.size());
  res.centre.value = 0.5 * (r[0] + r[1]);
  res.amplitude = Uncertain{0.5 * (r[1] - r[0]), kNaN};
  res.residuals = {0.0, 0.0};
  res.sigma0 = kNaN;
  fill_sigma(res, sigma_reading, 0.5);
  res.notes.push_back("damping neglected");
  if (n > 2) res.notes.push_back(fmt::format("only the first two of {} readings used", n));
}

void schuler_centre(ReversalResult& res, std::span<const double> r, double sigma_reading) {
  const int n = static_cast<int>(r.size());
  // M = (r1 + 3r2 + 4r3 + … + 4r_{n−2} + 3r_{n−1} + rn)/(4(n−2)): the mean of the
  // n−2 successive means (r_i + 2r_{i+1} + r_{i+2})/4.
  std::vector<double> w(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i + 2 < n; ++i) {
    w[i] += 0.25;
    w[i + 1] += 0.5;
    w[i + 2] += 0.25;
  }
  double m = 0, q = 0;
  for (int i = 0; i < n; ++i) {
    w[i] /= (n - 2);
    m += w[i] * r[i];
    q += w[i] * w[i];
  }
  res.centre.value = m;
  if (n > 3) {
    const auto lin = fit_linear(r);  // σ̂0 of one reading from the redundant linear model
    res.dof = lin.dof;
    res.sigma0 = lin.sigma0;
    res.residuals.assign(lin.residuals.data(), lin.residuals.data() + n);
    res.notes.push_back("sigma0 of a reading from the linearised least-squares fit (R2)");
  } else {
    res.sigma0 = kNaN;
    res.residuals.assign(static_cast<std::size_t>(n), 0.0);
  }
  fill_sigma(res, sigma_reading, q);
  res.notes.push_back("linear damping assumed (exact for e^{-i kappa} to first order)");
}

// Centre, amplitude and damping of a least-squares fit ((R2), or (R1) by Gauss–Newton) with
// their σ by the policy of fill_sigma.
template <class Fit>
void take_fit(ReversalResult& res, const Fit& fit, double sigma_reading) {
  res.centre.value = fit.x(0);
  res.dof = fit.dof;
  res.sigma0 = fit.sigma0;
  res.residuals.assign(fit.residuals.data(), fit.residuals.data() + fit.residuals.size());
  fill_sigma(res, sigma_reading, fit.cofactor(0, 0));
  res.amplitude = Uncertain{fit.x(1), reading_sigma_used(res) * std::sqrt(fit.cofactor(1, 1))};
  res.damping = Uncertain{fit.x(2), reading_sigma_used(res) * std::sqrt(fit.cofactor(2, 2))};
}

void linear_centre(ReversalResult& res, std::span<const double> r, double sigma_reading) {
  const int n = static_cast<int>(r.size());
  take_fit(res, fit_linear(r), sigma_reading);
  if (n > 10) res.notes.push_back("more than 10 reversals add little precision (q_MM ~ 1/n)");
}

// (R1), r_i = M + (−1)^i·A·e^{−iκ}, i = 1 … n, with its Jacobian.
adjust::NonlinearModel damped_reversal_model(int n) {
  adjust::NonlinearModel model;
  model.predict = [n](const Eigen::VectorXd& x) {
    Eigen::VectorXd f(n);
    for (int k = 0; k < n; ++k) {
      const int i = k + 1;
      f(k) = x(0) + alt_sign(i) * x(1) * std::exp(-i * x(2));
    }
    return f;
  };
  model.jacobian = [n](const Eigen::VectorXd& x) {
    Eigen::MatrixXd J(n, 3);
    for (int k = 0; k < n; ++k) {
      const int i = k + 1;
      const double e = std::exp(-i * x(2));
      J(k, 0) = 1.0;
      J(k, 1) = alt_sign(i) * e;
      J(k, 2) = -alt_sign(i) * x(1) * i * e;
    }
    return J;
  };
  return model;
}

void nonlinear_centre(ReversalResult& res, std::span<const double> r, double sigma_reading) {
  const int n = static_cast<int>(r.size());
  const auto lin = fit_linear(r);
  // Start: A = A′ + c, κ = 2c/(A′ + c) from matching (R2) to the expansion of (R1).
  const double a0 = lin.x(1) + lin.x(2);
  const double k0 = a0 != 0.0 ? 2.0 * lin.x(2) / a0 : 0.0;
  Eigen::VectorXd l(n);
  for (int k = 0; k < n; ++k) l(k) = r[static_cast<std::size_t>(k)];
  adjust::NonlinearOptions opt;
  opt.step_scale = Eigen::Vector3d(std::fabs(lin.x(0)) + std::fabs(a0), std::fabs(a0), 1.0);
  const auto nl = adjust::solve_nonlinear(damped_reversal_model(n), l, Eigen::MatrixXd::Identity(n, n),
                                          Eigen::Vector3d(lin.x(0), a0, k0), opt);
  take_fit(res, nl, sigma_reading);
  res.notes.push_back(fmt::format("non-linear fit converged in {} iterations", nl.iterations));
}

}  // namespace

ReversalResult estimate_centre(ReversalMethod method, std::span<const double> r,
                               double sigma_reading) {
  ReversalResult res;
  res.method = method;
  check_reversal_sequence(r, method == ReversalMethod::TwoPoint ? 2 : 3);
  if (method != ReversalMethod::TwoPoint) fill_partial_means(res, r);
  switch (method) {
    case ReversalMethod::TwoPoint: two_point_centre(res, r, sigma_reading); break;
    case ReversalMethod::Schuler: schuler_centre(res, r, sigma_reading); break;
    case ReversalMethod::LinearLsq: linear_centre(res, r, sigma_reading); break;
    case ReversalMethod::NonlinearLsq: nonlinear_centre(res, r, sigma_reading); break;
  }
  return res;
}

std::string reading_sigma_warning(const ReversalResult& r, double unit,
                                  std::string_view unit_symbol, int decimals) {
  if (!r.reading_sigma_test || !r.reading_sigma_test->rejected) return {};
  const adjust::GlobalTestResult& g = *r.reading_sigma_test;
  return fmt::format(
      "the reversal readings scatter more than stated: sigma0 = {:.{}f}{} against the stated "
      "{:.{}f}{} ({} degrees of freedom; global test T = {:.2f} > {:.2f} at alpha = {:g} %); "
      "the larger, a-posteriori sigma is used",
      r.sigma0 / unit, decimals, unit_symbol, r.sigma_reading / unit, decimals, unit_symbol, g.dof,
      g.vtpv, g.critical_value, 100.0 * g.alpha);
}

}  // namespace meridian::gyro
