#include "meridian/adjust/nonlinear.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::adjust {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kInf = std::numeric_limits<double>::infinity();

// LM damping stays within these bounds: below, the augmented system of a rank-deficient
// Jacobian is singular to working precision; above, the step is zero anyway.
constexpr double kMinDamping = 1e-20;
constexpr double kMaxDamping = 1e300;

Index first_non_finite(const VectorXd& v) {
  for (Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v(i))) return i;
  return -1;
}

// Undamped Gauss–Newton step for min ‖J̃·δ + r̃‖, as the basic solution when J̃ is rank
// deficient (rank tested as in the linear solver, on unit columns).
struct GaussNewtonStep {
  VectorXd delta;
  Index rank = 0;
  Index dependent = -1;  // first undetermined parameter when rank < u
};

GaussNewtonStep gauss_newton_step(const MatrixXd& jw, const VectorXd& rw, double tol) {
  const Index u = jw.cols();
  VectorXd scale(u);
  MatrixXd js = jw;
  for (Index j = 0; j < u; ++j) {
    const double norm = js.col(j).stableNorm();
    scale(j) = norm > 0.0 ? norm : 1.0;
    js.col(j) /= scale(j);
  }
  const Eigen::ColPivHouseholderQR<MatrixXd> qr(js);
  const MatrixXd& r = qr.matrixQR();
  const auto& perm = qr.colsPermutation().indices();
  GaussNewtonStep step;
  const double r00 = std::abs(r(0, 0));
  while (step.rank < u && std::abs(r(step.rank, step.rank)) > tol * r00) ++step.rank;
  if (step.rank < u) step.dependent = perm(step.rank);
  VectorXd c = -rw;
  c.applyOnTheLeft(qr.householderQ().adjoint());
  VectorXd y = VectorXd::Zero(u);
  const Index k = step.rank;
  y.head(k) = r.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(c.head(k));
  step.delta.resize(u);
  for (Index i = 0; i < u; ++i) step.delta(perm(i)) = y(i) / scale(perm(i));
  return step;
}

// Levenberg–Marquardt step: min ‖J̃·δ + r̃‖² + λ‖D·δ‖², solved as the stacked least-squares
// problem [J̃·D⁻¹; √λ·I]·(D·δ) = [−r̃; 0] by QR (no normal equations).
VectorXd lm_step(const MatrixXd& jw, const VectorXd& rw, const VectorXd& d, double lambda) {
  const Index n = jw.rows();
  const Index u = jw.cols();
  MatrixXd aug(n + u, u);
  aug.topRows(n) = jw * d.cwiseInverse().asDiagonal();
  aug.bottomRows(u) = std::sqrt(lambda) * MatrixXd::Identity(u, u);
  VectorXd rhs = VectorXd::Zero(n + u);
  rhs.head(n) = -rw;
  const VectorXd ds = Eigen::HouseholderQR<MatrixXd>(aug).solve(rhs);
  return ds.cwiseQuotient(d);
}

}  // namespace

NonlinearResult solve_nonlinear(const NonlinearModel& model, const VectorXd& l,
                                const MatrixXd& sigma_ll, const VectorXd& x0,
                                const NonlinearOptions& options) {
  const Index n = l.size();
  const Index u = x0.size();
  if (!model.predict) throw InputError("non-linear model has no prediction function");
  if (u < 1) throw InputError("starting point x0 is empty (no parameters)");
  if (n < u)
    throw InputError(fmt::format("fewer observations ({}) than parameters ({})", n, u));
  if (sigma_ll.rows() != n || sigma_ll.cols() != n)
    throw InputError(fmt::format("observation covariance is {}×{} but l has {} entries",
                                 sigma_ll.rows(), sigma_ll.cols(), n));
  if (const Index i = first_non_finite(l); i >= 0)
    throw InputError(fmt::format("observation vector l has a non-finite value ({}) at index {}",
                                 l(i), i));
  if (const Index i = first_non_finite(x0); i >= 0)
    throw InputError(fmt::format("starting point x0 has a non-finite value ({}) at index {}",
                                 x0(i), i));
  if (options.max_iterations < 1)
    throw InputError(fmt::format("max_iterations must be ≥ 1, is {}", options.max_iterations));
  if (!(std::isfinite(options.step_tolerance) && options.step_tolerance > 0.0))
    throw InputError(fmt::format("step_tolerance must be positive and finite, is {}",
                                 options.step_tolerance));
  if (options.levenberg_marquardt &&
      !(std::isfinite(options.initial_damping) && options.initial_damping > 0.0))
    throw InputError(fmt::format("initial_damping must be positive and finite, is {}",
                                 options.initial_damping));
  if (!model.jacobian &&
      !(std::isfinite(options.difference_step) && options.difference_step > 0.0))
    throw InputError(fmt::format("difference_step must be positive and finite, is {}",
                                 options.difference_step));
  if (!std::isfinite(options.rank_tolerance))
    throw InputError(fmt::format("rank_tolerance must be finite, is {}", options.rank_tolerance));
  VectorXd scale = VectorXd::Ones(u);
  if (options.step_scale.size() != 0) {
    if (options.step_scale.size() != u)
      throw InputError(fmt::format("step_scale has {} entries for {} parameters",
                                   options.step_scale.size(), u));
    for (Index j = 0; j < u; ++j)
      if (!(std::isfinite(options.step_scale(j)) && options.step_scale(j) > 0.0))
        throw InputError(fmt::format("step_scale[{}] must be positive and finite, is {}", j,
                                     options.step_scale(j)));
    scale = options.step_scale;
  }

  const CovarianceFactor cov(sigma_ll);
  double rank_tol = options.rank_tolerance;
  if (!(rank_tol > 0.0)) {
    rank_tol = 100.0 * static_cast<double>(std::max(n, u)) * kEps;
    // Central differences carry relative errors ≈ ε/h, which would hide an exact dependency.
    if (!model.jacobian) rank_tol = std::max(rank_tol, 1000.0 * kEps / options.difference_step);
  }

  const auto predict = [&](const VectorXd& x) {
    VectorXd f = model.predict(x);
    if (f.size() != n)
      throw InputError(fmt::format("model returned {} predicted observations, expected {}",
                                   f.size(), n));
    return f;
  };
  int steps = 0;
  const auto jacobian = [&](const VectorXd& x) {
    MatrixXd j;
    if (model.jacobian) {
      j = model.jacobian(x);
      if (j.rows() != n || j.cols() != u)
        throw InputError(fmt::format("model Jacobian is {}×{}, expected {}×{}", j.rows(),
                                     j.cols(), n, u));
    } else {
      j.resize(n, u);
      for (Index c = 0; c < u; ++c) {
        VectorXd xp = x;
        VectorXd xm = x;
        const double h = options.difference_step * (std::abs(x(c)) + scale(c));
        xp(c) += h;
        xm(c) -= h;
        const VectorXd fp = predict(xp);
        const VectorXd fm = predict(xm);
        if (first_non_finite(fp) >= 0 || first_non_finite(fm) >= 0)
          throw NumericalError(fmt::format(
              "model prediction is not finite when differencing parameter {} by ±{:.3g} "
              "(iteration {})", c, h, steps));
        j.col(c) = (fp - fm) / (xp(c) - xm(c));  // the representable step
      }
    }
    for (Index c = 0; c < u; ++c)
      for (Index i = 0; i < n; ++i)
        if (!std::isfinite(j(i, c)))
          throw NumericalError(fmt::format(
              "Jacobian is not finite at ({}, {}) (iteration {})", i, c, steps));
    return j;
  };
  // Whitened misclosure r̃ = L⁻¹(f(x) − l); vᵀPv = ‖r̃‖².
  const auto whitened_residual = [&](const VectorXd& f) {
    VectorXd r = f - l;
    cov.whiten(r);
    return r;
  };
  const auto small = [&](const VectorXd& delta, const VectorXd& x) {
    for (Index j = 0; j < u; ++j)
      if (!(std::abs(delta(j)) <= options.step_tolerance * (std::abs(x(j)) + scale(j))))
        return false;
    return true;
  };

  VectorXd x = x0;
  VectorXd f = predict(x);
  if (const Index i = first_non_finite(f); i >= 0)
    throw NumericalError(fmt::format(
        "model prediction is not finite at the starting point (observation {} is {})", i, f(i)));
  VectorXd rw = whitened_residual(f);
  double cost = rw.squaredNorm();
  MatrixXd jac = jacobian(x);
  MatrixXd jw = jac;
  cov.whiten(jw);

  VectorXd d = VectorXd::Zero(u);  // Marquardt scaling, the largest column norms seen (Moré)
  double lambda = options.initial_damping;
  double nu = 2.0;
  VectorXd last_step;

  while (true) {
    const GaussNewtonStep gn = gauss_newton_step(jw, rw, rank_tol);
    if (small(gn.delta, x)) break;
    if (steps == options.max_iterations) {
      Index worst = 0;
      double worst_ratio = 0.0;
      for (Index j = 0; j < u; ++j) {
        const double ratio =
            std::abs(last_step(j)) / (options.step_tolerance * (std::abs(x(j)) + scale(j)));
        if (!(ratio <= worst_ratio)) {
          worst = j;
          worst_ratio = ratio;
        }
      }
      throw NumericalError(fmt::format(
          "no convergence within {} iterations: the last step changed parameter {} by {:.3g} "
          "({:.3g} times its tolerance), vᵀPv = {:.6g}",
          options.max_iterations, worst, last_step(worst), worst_ratio, cost));
    }

    if (!options.levenberg_marquardt) {
      if (gn.rank < u)
        throw NumericalError(fmt::format(
            "normal matrix is singular: parameter {} is not determined by the observations "
            "(Jacobian rank {} of {} at iteration {})", gn.dependent, gn.rank, u, steps + 1));
      x += gn.delta;
      last_step = gn.delta;
      ++steps;
      f = predict(x);
      if (const Index i = first_non_finite(f); i >= 0)
        throw NumericalError(fmt::format(
            "model prediction is not finite after Gauss–Newton step {} (observation {}); "
            "Levenberg–Marquardt damping may help", steps, i));
      rw = whitened_residual(f);
      cost = rw.squaredNorm();
      jac = jacobian(x);
      jw = jac;
      cov.whiten(jw);
      continue;
    }

    // Damped trial steps until vᵀPv decreases (Nielsen's update of λ).
    for (Index j = 0; j < u; ++j) d(j) = std::max(d(j), jw.col(j).stableNorm());
    const VectorXd dd = (d.array() > 0.0).select(d, VectorXd::Ones(u));
    bool stalled = false;
    while (true) {
      const VectorXd delta = lm_step(jw, rw, dd, lambda);
      const VectorXd x_new = x + delta;
      const VectorXd f_new = predict(x_new);
      VectorXd rw_new;
      double cost_new = kInf;
      if (first_non_finite(f_new) < 0) {
        rw_new = whitened_residual(f_new);
        cost_new = rw_new.squaredNorm();
      }
      if (cost_new < cost) {
        const double predicted = cost - (rw + jw * delta).squaredNorm();
        const double rho = predicted > 0.0 ? (cost - cost_new) / predicted : 1.0;
        lambda = std::max(kMinDamping,
                          lambda * std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)));
        nu = 2.0;
        x = x_new;
        f = f_new;
        rw = std::move(rw_new);
        cost = cost_new;
        last_step = delta;
        ++steps;
        break;
      }
      // A step below the tolerance that cannot reduce vᵀPv: the minimum is reached to
      // rounding level even if the Gauss–Newton step is larger than the tolerance.
      if (small(delta, x)) {
        stalled = true;
        break;
      }
      lambda *= nu;
      nu *= 2.0;
      if (!(lambda < kMaxDamping))
        throw NumericalError(fmt::format(
            "Levenberg–Marquardt damping overflowed at iteration {} without reducing "
            "vᵀPv = {:.6g}", steps + 1, cost));
    }
    if (stalled) break;
    jac = jacobian(x);
    jw = jac;
    cov.whiten(jw);
  }

  // Statistics of the linearised problem l − f(x) + v = J·Δx at the last iterate.
  LinearOptions lin_options;
  lin_options.rank_tolerance = rank_tol;
  const LeastSquaresResult lin = solve_linear(jac, l - f, cov, lin_options);
  NonlinearResult res;
  static_cast<LeastSquaresResult&>(res) = lin;
  res.x = x + lin.x;
  res.iterations = steps;
  res.converged = true;
  return res;
}

}  // namespace meridian::adjust
