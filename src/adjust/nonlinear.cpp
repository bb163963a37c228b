#include "meridian/adjust/nonlinear.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "detail.hpp"

namespace meridian::adjust {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kInf = std::numeric_limits<double>::infinity();

// LM damping stays within these bounds: below, the augmented system of a rank-deficient
// Jacobian is singular to working precision; above, the step is zero anyway.
constexpr double kMinDamping = 1e-20;
constexpr double kMaxDamping = 1e300;

// Undamped Gauss–Newton step for min ‖J̃·δ + r̃‖, as the basic solution when J̃ is rank
// deficient (rank tested as in the linear solver, on unit columns).
struct GaussNewtonStep {
  VectorXd delta;
  Index rank = 0;
  Index dependent = -1;  // first undetermined parameter when rank < u
};

GaussNewtonStep gauss_newton_step(const MatrixXd& jw, const VectorXd& rw, double tol) {
  const Index u = jw.cols();
  const detail::ScaledQr s = detail::scaled_qr(jw);
  const auto& qr = s.qr;
  const MatrixXd& r = qr.matrixQR();
  GaussNewtonStep step;
  step.rank = s.rank(tol);
  if (step.rank < u) step.dependent = s.column_at(step.rank);
  VectorXd c = -rw;
  c.applyOnTheLeft(qr.householderQ().adjoint());
  VectorXd y = VectorXd::Zero(u);
  const Index k = step.rank;
  y.head(k) = r.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(c.head(k));
  const auto& perm = qr.colsPermutation().indices();
  step.delta.resize(u);
  for (Index i = 0; i < u; ++i) step.delta(perm(i)) = y(i) / s.scale(perm(i));
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

// ---------------------------------------------------------------------------------------------
// The steps of solve_nonlinear.

// Sizes, finiteness and options; returns the step scale (ones unless given).
VectorXd validate(const NonlinearModel& model, const VectorXd& l, const MatrixXd& sigma_ll,
                  const VectorXd& x0, const NonlinearOptions& options) {
  const Index n = l.size();
  const Index u = x0.size();
  if (!model.predict) throw InputError("non-linear model has no prediction function");
  if (u < 1) throw InputError("starting point x0 is empty (no parameters)");
  if (n < u)
    throw InputError(fmt::format("fewer observations ({}) than parameters ({})", n, u));
  if (sigma_ll.rows() != n || sigma_ll.cols() != n)
    throw InputError(fmt::format("observation covariance is {}×{} but l has {} entries",
                                 sigma_ll.rows(), sigma_ll.cols(), n));
  detail::check_finite(l, "observation vector l");
  detail::check_finite(x0, "starting point x0");
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
  if (options.step_scale.size() == 0) return VectorXd::Ones(u);
  if (options.step_scale.size() != u)
    throw InputError(fmt::format("step_scale has {} entries for {} parameters",
                                 options.step_scale.size(), u));
  for (Index j = 0; j < u; ++j)
    if (!(std::isfinite(options.step_scale(j)) && options.step_scale(j) > 0.0))
      throw InputError(fmt::format("step_scale[{}] must be positive and finite, is {}", j,
                                   options.step_scale(j)));
  return options.step_scale;
}

double rank_tolerance(const NonlinearModel& model, const NonlinearOptions& options, Index n,
                      Index u) {
  if (options.rank_tolerance > 0.0) return options.rank_tolerance;
  const double tol = detail::default_rank_tolerance(n, u);
  // Central differences carry relative errors ≈ ε/h, which would hide an exact dependency.
  return model.jacobian ? tol
                        : std::max(tol, 1000.0 * detail::kEps / options.difference_step);
}

// The whitened problem r̃(x) = L⁻¹(f(x) − l) with the model's size checks.
class Problem {
 public:
  Problem(const NonlinearModel& model, const VectorXd& l, const CovarianceFactor& cov,
          const NonlinearOptions& options, VectorXd scale)
      : model_(model), l_(l), cov_(cov), options_(options), scale_(std::move(scale)) {}

  Index n() const { return l_.size(); }
  Index u() const { return scale_.size(); }

  VectorXd predict(const VectorXd& x) const {
    VectorXd f = model_.predict(x);
    if (f.size() != n())
      throw InputError(fmt::format("model returned {} predicted observations, expected {}",
                                   f.size(), n()));
    return f;
  }

  // ∂f/∂x at x, analytic or by central differences; `steps` (the steps taken so far) only
  // labels error messages.
  MatrixXd jacobian(const VectorXd& x, int steps) const {
    const Index n = this->n();
    const Index u = this->u();
    MatrixXd j;
    if (model_.jacobian) {
      j = model_.jacobian(x);
      if (j.rows() != n || j.cols() != u)
        throw InputError(fmt::format("model Jacobian is {}×{}, expected {}×{}", j.rows(),
                                     j.cols(), n, u));
    } else {
      j.resize(n, u);
      for (Index c = 0; c < u; ++c) {
        VectorXd xp = x;
        VectorXd xm = x;
        const double h = options_.difference_step * (std::abs(x(c)) + scale_(c));
        xp(c) += h;
        xm(c) -= h;
        const VectorXd fp = predict(xp);
        const VectorXd fm = predict(xm);
        if (detail::first_non_finite(fp) >= 0 || detail::first_non_finite(fm) >= 0)
          throw NumericalError(fmt::format(
              "model prediction is not finite when differencing parameter {} by ±{:.3g} "
              "(iteration {})", c, h, steps));
        j.col(c) = (fp - fm) / (xp(c) - xm(c));  // the representable step
      }
    }
    if (const detail::Cell bad = detail::first_non_finite(j); bad.found())
      throw NumericalError(fmt::format("Jacobian is not finite at ({}, {}) (iteration {})",
                                       bad.row, bad.col, steps));
    return j;
  }

  // Whitened misclosure r̃ = L⁻¹(f(x) − l); vᵀPv = ‖r̃‖².
  VectorXd whitened_residual(const VectorXd& f) const {
    VectorXd r = f - l_;
    cov_.whiten(r);
    return r;
  }

  MatrixXd whitened(MatrixXd m) const {
    cov_.whiten(m);
    return m;
  }

  // The convergence test: every |δ_j| ≤ step_tolerance·(|x_j| + step_scale_j).
  bool small(const VectorXd& delta, const VectorXd& x) const {
    for (Index j = 0; j < u(); ++j)
      if (!(std::abs(delta(j)) <= tolerance(j, x))) return false;
    return true;
  }
  double tolerance(Index j, const VectorXd& x) const {
    return options_.step_tolerance * (std::abs(x(j)) + scale_(j));
  }

  const VectorXd& observations() const { return l_; }
  const CovarianceFactor& covariance() const { return cov_; }

 private:
  const NonlinearModel& model_;
  const VectorXd& l_;
  const CovarianceFactor& cov_;
  const NonlinearOptions& options_;
  VectorXd scale_;
};

// The current iterate with its prediction, whitened misclosure, vᵀPv and Jacobians.
struct Iterate {
  VectorXd x;
  VectorXd f;           // f(x)
  VectorXd rw;          // r̃ = L⁻¹(f − l)
  double cost = 0.0;    // vᵀPv = ‖r̃‖²
  MatrixXd jac;         // J(x)
  MatrixXd jw;          // L⁻¹·J(x)
  VectorXd last_step;   // the last step taken (empty before the first)
  int steps = 0;        // steps taken
};

void relinearise(const Problem& pb, Iterate& it) {
  it.jac = pb.jacobian(it.x, it.steps);
  it.jw = pb.whitened(it.jac);
}

Iterate start(const Problem& pb, const VectorXd& x0) {
  Iterate it;
  it.x = x0;
  it.f = pb.predict(it.x);
  if (const Index i = detail::first_non_finite(it.f); i >= 0)
    throw NumericalError(fmt::format(
        "model prediction is not finite at the starting point (observation {} is {})", i,
        it.f(i)));
  it.rw = pb.whitened_residual(it.f);
  it.cost = it.rw.squaredNorm();
  relinearise(pb, it);
  return it;
}

[[noreturn]] void throw_no_convergence(const Problem& pb, const Iterate& it,
                                       int max_iterations) {
  Index worst = 0;
  double worst_ratio = 0.0;
  for (Index j = 0; j < pb.u(); ++j) {
    const double ratio = std::abs(it.last_step(j)) / pb.tolerance(j, it.x);
    if (!(ratio <= worst_ratio)) {
      worst = j;
      worst_ratio = ratio;
    }
  }
  throw NumericalError(fmt::format(
      "no convergence within {} iterations: the last step changed parameter {} by {:.3g} "
      "({:.3g} times its tolerance), vᵀPv = {:.6g}",
      max_iterations, worst, it.last_step(worst), worst_ratio, it.cost));
}

// One plain (undamped, unchecked) Gauss–Newton step; relinearises at the new iterate.
void gauss_newton_iteration(const Problem& pb, Iterate& it, const GaussNewtonStep& gn) {
  const Index u = pb.u();
  if (gn.rank < u)
    throw NumericalError(fmt::format(
        "normal matrix is singular: parameter {} is not determined by the observations "
        "(Jacobian rank {} of {} at iteration {})", gn.dependent, gn.rank, u, it.steps + 1));
  it.x += gn.delta;
  it.last_step = gn.delta;
  ++it.steps;
  it.f = pb.predict(it.x);
  if (const Index i = detail::first_non_finite(it.f); i >= 0)
    throw NumericalError(fmt::format(
        "model prediction is not finite after Gauss–Newton step {} (observation {}); "
        "Levenberg–Marquardt damping may help", it.steps, i));
  it.rw = pb.whitened_residual(it.f);
  it.cost = it.rw.squaredNorm();
  relinearise(pb, it);
}

// Levenberg–Marquardt damping state: Marquardt scaling d (the largest column norms of L⁻¹·J
// seen, Moré), λ and Nielsen's factor ν.
struct Damping {
  VectorXd d;
  double lambda = 0.0;
  double nu = 2.0;
};

enum class LmOutcome { Accepted, Stalled };

// Damped trial steps from the iterate until vᵀPv decreases (Nielsen's update of λ); then
// the iterate moves (Accepted, not yet relinearised). Stalled: a trial step below the
// tolerance fails to reduce vᵀPv, i.e. the minimum is reached to rounding level even if the
// Gauss–Newton step is larger than the tolerance.
LmOutcome levenberg_marquardt_iteration(const Problem& pb, Iterate& it, Damping& dm) {
  const Index u = pb.u();
  for (Index j = 0; j < u; ++j) dm.d(j) = std::max(dm.d(j), it.jw.col(j).stableNorm());
  const VectorXd dd = (dm.d.array() > 0.0).select(dm.d, VectorXd::Ones(u));
  while (true) {
    const VectorXd delta = lm_step(it.jw, it.rw, dd, dm.lambda);
    VectorXd x_new = it.x + delta;
    VectorXd f_new = pb.predict(x_new);
    VectorXd rw_new;
    double cost_new = kInf;
    if (detail::first_non_finite(f_new) < 0) {
      rw_new = pb.whitened_residual(f_new);
      cost_new = rw_new.squaredNorm();
    }
    if (cost_new < it.cost) {
      const double predicted = it.cost - (it.rw + it.jw * delta).squaredNorm();
      const double rho = predicted > 0.0 ? (it.cost - cost_new) / predicted : 1.0;
      dm.lambda = std::max(kMinDamping,
                           dm.lambda * std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)));
      dm.nu = 2.0;
      it.x = std::move(x_new);
      it.f = std::move(f_new);
      it.rw = std::move(rw_new);
      it.cost = cost_new;
      it.last_step = delta;
      ++it.steps;
      return LmOutcome::Accepted;
    }
    if (pb.small(delta, it.x)) return LmOutcome::Stalled;
    dm.lambda *= dm.nu;
    dm.nu *= 2.0;
    if (!(dm.lambda < kMaxDamping))
      throw NumericalError(fmt::format(
          "Levenberg–Marquardt damping overflowed at iteration {} without reducing "
          "vᵀPv = {:.6g}", it.steps + 1, it.cost));
  }
}

// Statistics of the linearised problem l − f(x) + v = J·Δx at the last iterate; x̂ = x + Δx.
NonlinearResult final_statistics(const Problem& pb, const Iterate& it, double rank_tol) {
  LinearOptions lin_options;
  lin_options.rank_tolerance = rank_tol;
  const LeastSquaresResult lin =
      solve_linear(it.jac, pb.observations() - it.f, pb.covariance(), lin_options);
  NonlinearResult res;
  static_cast<LeastSquaresResult&>(res) = lin;
  res.x = it.x + lin.x;
  res.iterations = it.steps;
  res.converged = true;
  return res;
}

}  // namespace

NonlinearResult solve_nonlinear(const NonlinearModel& model, const VectorXd& l,
                                const MatrixXd& sigma_ll, const VectorXd& x0,
                                const NonlinearOptions& options) {
  VectorXd scale = validate(model, l, sigma_ll, x0, options);
  const CovarianceFactor cov(sigma_ll);
  const double rank_tol = rank_tolerance(model, options, l.size(), x0.size());
  const Problem pb(model, l, cov, options, std::move(scale));

  Iterate it = start(pb, x0);
  Damping damping{VectorXd::Zero(pb.u()), options.initial_damping, 2.0};
  while (true) {
    const GaussNewtonStep gn = gauss_newton_step(it.jw, it.rw, rank_tol);
    if (pb.small(gn.delta, it.x)) break;  // converged
    if (it.steps == options.max_iterations) throw_no_convergence(pb, it, options.max_iterations);
    if (!options.levenberg_marquardt) {
      gauss_newton_iteration(pb, it, gn);
      continue;
    }
    if (levenberg_marquardt_iteration(pb, it, damping) == LmOutcome::Stalled) break;
    relinearise(pb, it);
  }
  return final_statistics(pb, it, rank_tol);
}

}  // namespace meridian::adjust
