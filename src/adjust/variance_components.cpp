#include "meridian/adjust/variance_components.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "detail.hpp"
#include "meridian/core/error.hpp"

namespace meridian::adjust {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

using detail::kNaN;
// A component driven below this fraction of the largest one by a step that would make it
// negative has reached the boundary θ_k = 0: it is clipped.
constexpr double kClipFraction = 1e-9;
// A damped step leaves at least this fraction of a component that the full step would make
// negative, so the iteration approaches the boundary geometrically instead of jumping past it.
constexpr double kKeepFraction = 0.01;
// Step halvings of the likelihood safeguard before the step is taken as it is.
constexpr int kMaxHalvings = 30;

// One evaluation at θ⁰ over the active components: the normal matrix N (½·Helmert's H) and
// right-hand side r of the VCE equations, both over the active components in order.
// s is the data part of the observed information, S_kl = lᵀP̄Q_kP̄Q_lP̄l, so that the Hessian
// of the restricted log-likelihood is N − S and its gradient r − N·θ⁰.
struct Equations {
  MatrixXd n;
  VectorXd r;
  MatrixXd s;
};

CovarianceFactor factor_covariance(const std::vector<VarianceComponent>& comps,
                                   const VectorXd& theta, const std::vector<bool>& active) {
  const Index n = comps.front().factor.rows();
  MatrixXd d = MatrixXd::Zero(n, n);
  std::string zero;
  for (std::size_t k = 0; k < comps.size(); ++k) {
    if (active[k]) {
      d.selfadjointView<Eigen::Lower>().rankUpdate(comps[k].factor, theta(static_cast<Index>(k)));
    } else {
      zero += (zero.empty() ? "" : ", ") + comps[k].name;
    }
  }
  d = d.selfadjointView<Eigen::Lower>();
  try {
    return CovarianceFactor(d);
  } catch (const NumericalError& e) {
    if (zero.empty()) throw NumericalError("variance components: " + e.message());
    throw NumericalError(
        fmt::format("variance components: with {} set to 0 the covariance is "
                    "singular ({})",
                    zero, e.message()));
  }
}

std::vector<MatrixXd> whitened_factors(const std::vector<VarianceComponent>& comps,
                                       const std::vector<bool>& active,
                                       const CovarianceFactor& cov) {
  std::vector<MatrixXd> out;
  for (std::size_t k = 0; k < comps.size(); ++k) {
    if (!active[k]) continue;
    MatrixXd f = comps[k].factor;
    cov.whiten(f);
    out.push_back(std::move(f));
  }
  return out;
}

// Least-squares VCE through the orthonormal basis U of the whitened design.
Equations lsvce_equations(const MatrixXd& A, const VectorXd& l,
                          const std::vector<VarianceComponent>& comps, const VectorXd& theta,
                          const std::vector<bool>& active) {
  const CovarianceFactor cov = factor_covariance(comps, theta, active);
  MatrixXd aw = A;
  cov.whiten(aw);
  VectorXd lw = l;
  cov.whiten(lw);
  const MatrixXd u = detail::thin_q(
      detail::full_rank_qr(std::move(aw), detail::default_rank_tolerance(A.rows(), A.cols())));
  const VectorXd rw = lw - u * (u.transpose() * lw);  // −L⁻¹·v
  std::vector<MatrixXd> h = whitened_factors(comps, active, cov);
  for (MatrixXd& f : h) f -= u * (u.transpose() * f);  // (I − U·Uᵀ)·F̄_k
  const auto k = static_cast<Index>(h.size());
  Equations e{MatrixXd(k, k), VectorXd(k), MatrixXd(k, k)};
  std::vector<VectorXd> w;  // L⁻ᵀ·w_k = P̄·Q_k·P̄·l with w_k = M·F̄_k·F̄_kᵀ·M·L⁻¹l
  for (Index a = 0; a < k; ++a) {
    const VectorXd t = h[a].transpose() * rw;
    e.r(a) = 0.5 * t.squaredNorm();
    w.push_back(h[a] * t);
    for (Index b = 0; b <= a; ++b)
      e.n(a, b) = e.n(b, a) = 0.5 * (h[a].transpose() * h[b]).squaredNorm();
  }
  for (Index a = 0; a < k; ++a)
    for (Index b = 0; b <= a; ++b) e.s(a, b) = e.s(b, a) = w[a].dot(w[b]);
  return e;
}

// Helmert's equations H·θ = q written out with the normal matrix N_A = AᵀPA.
Equations helmert_equations(const MatrixXd& A, const VectorXd& l,
                            const std::vector<VarianceComponent>& comps, const VectorXd& theta,
                            const std::vector<bool>& active) {
  const CovarianceFactor cov = factor_covariance(comps, theta, active);
  MatrixXd aw = A;
  cov.whiten(aw);
  VectorXd lw = l;
  cov.whiten(lw);
  const MatrixXd na = aw.transpose() * aw;
  const Eigen::LLT<MatrixXd> chol(na);
  if (chol.info() != Eigen::Success)
    throw NumericalError("variance components: the normal matrix AᵀPA is not positive definite");
  const VectorXd x = chol.solve(aw.transpose() * lw);
  const VectorXd vw = aw * x - lw;  // L⁻¹·v
  const std::vector<MatrixXd> fb = whitened_factors(comps, active, cov);
  const auto k = static_cast<Index>(fb.size());
  std::vector<MatrixXd> g;       // AᵀP·F_k = L̄ᵀ·F̄_k
  std::vector<MatrixXd> ninv_w;  // N_A⁻¹·AᵀPQ_kPA
  for (const MatrixXd& f : fb) {
    g.push_back(aw.transpose() * f);
    ninv_w.push_back(chol.solve(g.back() * g.back().transpose()));
  }
  Equations e{MatrixXd(k, k), VectorXd(k), MatrixXd(k, k)};
  std::vector<VectorXd> w;  // (I − Ā·N_A⁻¹·Āᵀ)·F̄_k·F̄_kᵀ·L⁻¹v, Ā = L⁻¹A
  for (Index a = 0; a < k; ++a) {
    VectorXd y = fb[a] * (fb[a].transpose() * vw);
    y -= aw * chol.solve(aw.transpose() * y);
    w.push_back(std::move(y));
  }
  for (Index a = 0; a < k; ++a)
    for (Index b = 0; b <= a; ++b) e.s(a, b) = e.s(b, a) = w[a].dot(w[b]);
  for (Index a = 0; a < k; ++a) {
    e.r(a) = 0.5 * (fb[a].transpose() * vw).squaredNorm();
    for (Index b = 0; b <= a; ++b) {
      const MatrixXd s = fb[a].transpose() * fb[b];  // F̄_aᵀ·F̄_b
      const double t1 = s.squaredNorm();             // tr(PQ_aPQ_b)
      const double t2 = chol.solve(g[a] * s * g[b].transpose()).trace();
      const double t3 = (ninv_w[a] * ninv_w[b]).trace();
      e.n(a, b) = e.n(b, a) = 0.5 * (t1 - 2.0 * t2 + t3);
    }
  }
  return e;
}

// The restricted log-likelihood at θ (−∞ when D(θ) is not positive definite there).
double reml_at(const MatrixXd& A, const VectorXd& l, const std::vector<VarianceComponent>& comps,
               const VectorXd& theta, const std::vector<bool>& active) {
  try {
    return gls_log_likelihood(A, l, factor_covariance(comps, theta, active)).reml;
  } catch (const NumericalError&) {
    return -std::numeric_limits<double>::infinity();
  }
}

Equations equations(VceMethod m, const MatrixXd& A, const VectorXd& l,
                    const std::vector<VarianceComponent>& comps, const VectorXd& theta,
                    const std::vector<bool>& active) {
  return m == VceMethod::Helmert ? helmert_equations(A, l, comps, theta, active)
                                 : lsvce_equations(A, l, comps, theta, active);
}

// Solve N·θ = r; N scaled to unit diagonal first so the test does not depend on units.
VectorXd solve_equations(const Equations& e, const VectorXd& theta,
                         const std::vector<std::string>& names) {
  const VectorXd d = e.n.diagonal();
  for (Index a = 0; a < d.size(); ++a)
    if (!(d(a) > 0.0))
      throw NumericalError(
          fmt::format("variance components: {} is not determined by the "
                      "observations (its cofactor lies in the column space of A)",
                      names[static_cast<std::size_t>(a)]));
  const VectorXd s = d.cwiseSqrt().cwiseInverse();
  const MatrixXd ns = s.asDiagonal() * e.n * s.asDiagonal();
  const Eigen::LLT<MatrixXd> chol(ns);
  const double tiny = 1e-12;
  bool ok = chol.info() == Eigen::Success;
  if (ok) {
    const MatrixXd L = chol.matrixL();
    for (Index a = 0; a < L.rows(); ++a) ok = ok && L(a, a) * L(a, a) > tiny;
  }
  if (!ok) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw NumericalError(
        fmt::format("variance components cannot be separated: the cofactor "
                    "matrices of {} are (nearly) proportional on the residuals",
                    list));
  }
  // Newton's step on the restricted likelihood where its Hessian N − S is negative definite
  // (fast near the maximum, where plain scoring θ = N⁻¹·r can cycle when the components are
  // strongly correlated); the scoring step otherwise.
  const VectorXd scoring = s.asDiagonal() * chol.solve(s.asDiagonal() * e.r);
  const MatrixXd js = s.asDiagonal() * (e.s - e.n) * s.asDiagonal();
  const Eigen::LLT<MatrixXd> jchol(js);
  if (jchol.info() != Eigen::Success) return scoring;
  const VectorXd grad = e.r - e.n * theta;
  const VectorXd newton = theta + s.asDiagonal() * jchol.solve(s.asDiagonal() * grad);
  return newton.allFinite() ? newton : scoring;
}

void validate(const MatrixXd& A, const VectorXd& l, const std::vector<VarianceComponent>& comps,
              const VceOptions& o) {
  if (comps.empty()) throw InputError("variance components: no components given");
  if (A.cols() < 1) throw InputError("design matrix A has no columns (no parameters)");
  if (l.size() != A.rows())
    throw InputError(
        fmt::format("observation vector l has {} entries but A has {} rows", l.size(), A.rows()));
  const Index n = A.rows();
  const auto k = static_cast<Index>(comps.size());
  if (n - A.cols() < k)
    throw InputError(
        fmt::format("variance components: {} components need at least {} degrees "
                    "of freedom, the model has {} ({} observations, {} parameters)",
                    k, k, n - A.cols(), n, A.cols()));
  detail::check_finite(A, "design matrix A");
  detail::check_finite(l, "observation vector l");
  for (const auto& c : comps) {
    if (c.factor.rows() != n || c.factor.cols() < 1)
      throw InputError(fmt::format("variance component {}: factor is {}×{}, expected {} rows",
                                   c.name, c.factor.rows(), c.factor.cols(), n));
    detail::check_finite(c.factor, "factor of a variance component");
    if (c.factor.isZero(0.0))
      throw InputError(fmt::format("variance component {}: its cofactor matrix is zero", c.name));
  }
  if (o.initial.size() != 0) {
    if (o.initial.size() != k)
      throw InputError(fmt::format("variance components: {} initial values for {} components",
                                   o.initial.size(), k));
    for (Index a = 0; a < k; ++a)
      if (!(std::isfinite(o.initial(a)) && o.initial(a) > 0.0))
        throw InputError(
            fmt::format("variance components: initial value of {} must be finite "
                        "and > 0, is {}",
                        comps[static_cast<std::size_t>(a)].name, o.initial(a)));
  }
  if (o.max_iterations < 1)
    throw InputError(
        fmt::format("variance components: max_iterations must be ≥ 1, is {}", o.max_iterations));
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0))
    throw InputError(
        fmt::format("variance components: tolerance must be in (0, 1), is {}", o.tolerance));
}

std::vector<std::string> active_names(const std::vector<VarianceComponent>& comps,
                                      const std::vector<bool>& active) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < comps.size(); ++k)
    if (active[k]) out.push_back(comps[k].name);
  return out;
}

std::string component_list(const std::vector<VarianceComponent>& comps, const VectorXd& theta) {
  std::string s;
  for (std::size_t k = 0; k < comps.size(); ++k)
    s += fmt::format("{}{} = {:.6g}", s.empty() ? "" : ", ", comps[k].name,
                     theta(static_cast<Index>(k)));
  return s;
}

// The iteration's state: the components, which are still estimated (the others are clipped to 0),
// and the restricted likelihood at θ when known.
struct VceState {
  VectorXd theta;
  std::vector<bool> active;
  double here_cache = kNaN;
};

// The scoring solution mapped back to all components, and the damping α of a step that would
// make a component negative.
struct VceUpdate {
  VectorXd full;
  double alpha = 1.0;
};

VceUpdate scoring_update(const MatrixXd& A, const VectorXd& l, const std::vector<VarianceComponent>& comps,
                         VceMethod method, const VceState& s) {
  const auto K = static_cast<Index>(comps.size());
  const Equations e = equations(method, A, l, comps, s.theta, s.active);
  VectorXd theta_active(e.r.size());
  for (Index k = 0, j = 0; k < K; ++k)
    if (s.active[static_cast<std::size_t>(k)]) theta_active(j++) = s.theta(k);
  const VectorXd step = solve_equations(e, theta_active, active_names(comps, s.active));
  VceUpdate u{s.theta, 1.0};
  Index j = 0;
  for (Index k = 0; k < K; ++k) {
    if (!s.active[static_cast<std::size_t>(k)]) continue;
    u.full(k) = step(j++);
    if (u.full(k) < kKeepFraction * s.theta(k))
      u.alpha = std::min(u.alpha, (1.0 - kKeepFraction) * s.theta(k) / (s.theta(k) - u.full(k)));
  }
  return u;
}

// A component that is already at rounding level of the largest and still heads below zero has
// reached the boundary: clip it (with a note). True when one was clipped.
bool clip_negative(VceState& s, const VectorXd& full, const std::vector<VarianceComponent>& comps, int it,
                   VceResult& res) {
  const double largest = full.maxCoeff();
  bool clipped_now = false;
  for (Index k = 0; k < static_cast<Index>(comps.size()); ++k) {
    const auto ks = static_cast<std::size_t>(k);
    if (s.active[ks] && full(k) < 0.0 && s.theta(k) <= kClipFraction * std::max(largest, s.theta.maxCoeff())) {
      s.active[ks] = false;
      s.theta(k) = 0.0;
      clipped_now = true;
      res.notes.push_back(fmt::format("{} estimated negative ({:.3g}) at iteration {}: set to 0 and held there",
                                      comps[ks].name, full(k), it));
    }
  }
  if (std::none_of(s.active.begin(), s.active.end(), [](bool a) { return a; }))
    throw NumericalError("variance components: every component was estimated negative");
  return clipped_now;
}

// Scoring can overshoot when the components are strongly correlated (it then cycles): halve the
// step until the restricted likelihood does not decrease (a safeguarded scoring step).
void safeguarded_step(VceState& s, const VceUpdate& u, const MatrixXd& A, const VectorXd& l,
                      const std::vector<VarianceComponent>& comps) {
  const double here = std::isnan(s.here_cache) ? reml_at(A, l, comps, s.theta, s.active) : s.here_cache;
  double alpha = u.alpha;
  VectorXd next = s.theta + alpha * (u.full - s.theta);
  double there = reml_at(A, l, comps, next, s.active);
  for (int h = 0; h < kMaxHalvings && !(there >= here - 1e-12 * std::fabs(here)); ++h) {
    alpha *= 0.5;
    next = s.theta + alpha * (u.full - s.theta);
    there = reml_at(A, l, comps, next, s.active);
  }
  s.theta = next;
  s.here_cache = there;
}

// The converged components, which were clipped, and (with details) their covariance N⁻¹ at θ̂
// over the active components and the adjustment at θ̂; the likelihood always.
void finish_vce(VceResult& res, const MatrixXd& A, const VectorXd& l, const std::vector<VarianceComponent>& comps,
                const VceOptions& options, const VceState& s) {
  const auto K = static_cast<Index>(comps.size());
  res.components = s.theta;
  res.clipped.resize(comps.size());
  for (std::size_t k = 0; k < comps.size(); ++k) res.clipped[k] = !s.active[k];
  if (!options.details) {
    res.covariance = MatrixXd::Constant(K, K, kNaN);
    res.likelihood = gls_log_likelihood(A, l, factor_covariance(comps, s.theta, s.active));
    return;
  }
  const Equations e = equations(VceMethod::LsVce, A, l, comps, s.theta, s.active);
  const MatrixXd cov_active = e.n.ldlt().solve(MatrixXd::Identity(e.n.rows(), e.n.cols()));
  res.covariance = MatrixXd::Zero(K, K);
  std::vector<Index> idx;
  for (Index k = 0; k < K; ++k)
    if (s.active[static_cast<std::size_t>(k)]) idx.push_back(k);
  for (std::size_t a = 0; a < idx.size(); ++a)
    for (std::size_t b = 0; b < idx.size(); ++b)
      res.covariance(idx[a], idx[b]) = cov_active(static_cast<Index>(a), static_cast<Index>(b));
  const CovarianceFactor cov = factor_covariance(comps, s.theta, s.active);
  res.adjustment = solve_linear(A, l, cov);
  res.likelihood = gls_log_likelihood(A, l, cov);
}

}  // namespace

std::string to_string(VceMethod m) { return m == VceMethod::Helmert ? "helmert" : "ls-vce"; }

VarianceComponent VarianceComponent::from_cofactor(std::string name, const MatrixXd& Q) {
  const Index n = Q.rows();
  if (n == 0 || Q.cols() != n)
    throw InputError(
        fmt::format("variance component {}: cofactor matrix must be square and "
                    "non-empty, is {}×{}",
                    name, Q.rows(), Q.cols()));
  detail::check_finite(Q, "cofactor matrix");
  const double scale = Q.cwiseAbs().maxCoeff();
  if (!((Q - Q.transpose()).cwiseAbs().maxCoeff() <= 1e-10 * scale))
    throw InputError(fmt::format("variance component {}: cofactor matrix is not symmetric", name));
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(0.5 * (Q + Q.transpose()));
  const VectorXd& lambda = eig.eigenvalues();  // ascending
  const double lmax = lambda(n - 1);
  if (!(lmax > 0.0))
    throw InputError(fmt::format("variance component {}: cofactor matrix is zero", name));
  if (lambda(0) < -1e-10 * lmax)
    throw InputError(
        fmt::format("variance component {}: cofactor matrix is not positive "
                    "semi-definite (eigenvalue {:.3g}, largest {:.3g})",
                    name, lambda(0), lmax));
  Index first = 0;
  while (first < n && lambda(first) <= 1e-14 * lmax) ++first;
  VarianceComponent c{std::move(name), MatrixXd(n, n - first)};
  for (Index j = first; j < n; ++j)
    c.factor.col(j - first) = eig.eigenvectors().col(j) * std::sqrt(lambda(j));
  return c;
}

MatrixXd assemble_covariance(const std::vector<VarianceComponent>& comps, const VectorXd& theta) {
  if (comps.empty()) throw InputError("variance components: no components given");
  if (theta.size() != static_cast<Index>(comps.size()))
    throw InputError(
        fmt::format("{} component values for {} components", theta.size(), comps.size()));
  const Index n = comps.front().factor.rows();
  MatrixXd d = MatrixXd::Zero(n, n);
  for (std::size_t k = 0; k < comps.size(); ++k) {
    if (comps[k].factor.rows() != n)
      throw InputError(fmt::format("variance component {}: factor has {} rows, expected {}",
                                   comps[k].name, comps[k].factor.rows(), n));
    d.noalias() += theta(static_cast<Index>(k)) * comps[k].factor * comps[k].factor.transpose();
  }
  return d;
}

double VceResult::sigma(int k) const {
  if (k < 0 || k >= components.size())
    throw InputError(fmt::format("component index {} out of range [0, {})", k, components.size()));
  if (clipped[static_cast<std::size_t>(k)]) return kNaN;
  return std::sqrt(covariance(k, k));
}

VceResult estimate_variance_components(const MatrixXd& A, const VectorXd& l,
                                       const std::vector<VarianceComponent>& comps,
                                       const VceOptions& options) {
  validate(A, l, comps, options);
  const auto K = static_cast<Index>(comps.size());
  VceState s{options.initial.size() ? options.initial : VectorXd::Ones(K), std::vector<bool>(comps.size(), true),
             kNaN};
  VceResult res;
  res.method = options.method;
  bool converged = false;
  double last_change = kNaN;
  for (int it = 1; it <= options.max_iterations && !converged; ++it) {
    res.iterations = it;
    const VceUpdate u = scoring_update(A, l, comps, options.method, s);
    if (clip_negative(s, u.full, comps, it, res)) {
      s.here_cache = kNaN;
      continue;
    }
    // The a-priori and the a-posteriori components agree: converged (take the update).
    last_change = (u.full - s.theta).cwiseAbs().maxCoeff() / std::max(u.full.maxCoeff(), s.theta.maxCoeff());
    if (u.alpha == 1.0 && last_change <= options.tolerance) {
      s.theta = u.full;
      converged = true;
      break;
    }
    safeguarded_step(s, u, A, l, comps);
  }
  if (!converged)
    throw NumericalError(
        fmt::format("variance components did not converge in {} iterations "
                    "(last relative change {:.3g}; {})",
                    options.max_iterations, last_change, component_list(comps, s.theta)));
  finish_vce(res, A, l, comps, options, s);
  return res;
}

}  // namespace meridian::adjust
