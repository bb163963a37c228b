#include "meridian/adjust/two_component_reml.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "detail.hpp"
#include "meridian/core/error.hpp"

namespace meridian::adjust {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

using detail::kLog2Pi;
constexpr double kMinusInf = -std::numeric_limits<double>::infinity();
// The grid in v = ln τ reaches this far beyond 1/λ_max and 1/λ_min, where the profile is within
// e^−14 ≈ 1e-6 (relative) of its limits τ → 0 and τ → ∞.
constexpr double kGridReach = 14.0;
constexpr double kGridStep = 0.5;
// Q_1 is singular on the residual space when a pivot of its Cholesky factor falls below this
// fraction of the largest diagonal entry of Kᵀ·Q_1·K.
constexpr double kSingular = 1e-13;

// The profile of the restricted likelihood over the ratio τ = θ_2/θ_1 (θ_1 = s, θ_2 = s·τ,
// s profiled out): everything depends on the data through λ_j, z_j² and z0² only.
struct Profile {
  int r = 0;              // n − u
  VectorXd lambda;        // eigenvalues of L⁻¹·S_2·L⁻ᵀ that are not structurally zero
  VectorXd z2;            // z_j² for those
  double z0sq = 0.0;      // Σ z_j² over the structural zeros (λ = 0)
  double constant = 0.0;  // r·ln 2π + 2·Σ ln L_ii
  bool second_definite = false;  // λ_j > 0 for all r: θ_1 = 0 is admissible

  // q(τ) = z0² + Σ z_j²/(1 + τ·λ_j) and Σ ln(1 + τ·λ_j), with τ = e^v.
  double at_log_ratio(double v) const {
    const double t = std::exp(v);
    double q = z0sq, logdet = 0.0;
    for (Index j = 0; j < lambda.size(); ++j) {
      const double d = 1.0 + t * lambda(j);
      q += z2(j) / d;
      logdet += std::log(d);
    }
    return -0.5 * (constant + logdet + r * std::log(q / r) + r);
  }
  // τ = 0 (θ_2 = 0).
  double at_zero_ratio() const {
    return -0.5 * (constant + r * std::log((z0sq + z2.sum()) / r) + r);
  }
  // τ → ∞ (θ_1 = 0, θ_2 = s): −∞ unless Q_2 is definite on the residual space.
  double at_infinite_ratio() const {
    if (!second_definite) return kMinusInf;
    double q = 0.0, logdet = 0.0;
    for (Index j = 0; j < lambda.size(); ++j) {
      q += z2(j) / lambda(j);
      logdet += std::log(lambda(j));
    }
    return -0.5 * (constant + logdet + r * std::log(q / r) + r);
  }
  // First and second derivative of at_log_ratio in v.
  std::pair<double, double> derivatives(double v) const {
    const double t = std::exp(v);
    double q = z0sq, sa = 0.0, saa = 0.0, T = 0.0, T1 = 0.0;
    for (Index j = 0; j < lambda.size(); ++j) {
      const double d = 1.0 + t * lambda(j);
      const double a = t * lambda(j) / d;
      q += z2(j) / d;
      sa += a;
      saa += a * (1.0 - a);
      T += z2(j) * a / d;
      T1 += z2(j) * a * (1.0 - 2.0 * a) / d;
    }
    const double g = -0.5 * (sa - r * T / q);
    const double h = -0.5 * (saa - r * (T1 / q + (T / q) * (T / q)));
    return {g, h};
  }
  double scale_at(double v) const {
    const double t = std::exp(v);
    double q = z0sq;
    for (Index j = 0; j < lambda.size(); ++j) q += z2(j) / (1.0 + t * lambda(j));
    return q / r;
  }
};

void check_component(const VarianceComponent& c, Index n) {
  if (c.factor.rows() != n || c.factor.cols() < 1)
    throw InputError(fmt::format("variance component {}: factor is {}×{}, expected {} rows", c.name,
                                 c.factor.rows(), c.factor.cols(), n));
  detail::check_finite(c.factor, "factor of a variance component");
}

void check_reml_arguments(const MatrixXd& A, const VectorXd& l, const VarianceComponent& first,
                          const VarianceComponent& second) {
  const Index n = A.rows();
  const Index u = A.cols();
  if (u < 1) throw InputError("design matrix A has no columns (no parameters)");
  if (n < u + 2)
    throw InputError(fmt::format(
        "two variance components need at least 2 degrees of freedom, the model has {} ({} "
        "observations, {} parameters)",
        n - u, n, u));
  if (l.size() != n)
    throw InputError(
        fmt::format("observation vector l has {} entries but A has {} rows", l.size(), n));
  detail::check_finite(A, "design matrix A");
  detail::check_finite(l, "observation vector l");
  check_component(first, n);
  check_component(second, n);
}

// The problem on the residual space (the last r columns of Q in A·Π = Q·R), whitened by the
// Cholesky factor L of S_1 = G_1·G_1ᵀ there and diagonalised by the SVD of L⁻¹·G_2: the profile.
Profile residual_profile(const MatrixXd& A, const VectorXd& l, const VarianceComponent& first,
                         const VarianceComponent& second) {
  const Index n = A.rows();
  const Index u = A.cols();
  const detail::ScaledQr s = detail::full_rank_qr(A, detail::default_rank_tolerance(n, u));
  const Index r = n - u;
  const auto qt = s.qr.householderQ().adjoint();
  const MatrixXd g1 = (qt * first.factor).bottomRows(r);
  const MatrixXd g2 = (qt * second.factor).bottomRows(r);
  const VectorXd y = (qt * l).tail(r);

  MatrixXd s1 = MatrixXd::Zero(r, r);
  s1.selfadjointView<Eigen::Lower>().rankUpdate(g1);
  const double s1_max = s1.diagonal().maxCoeff();
  const Eigen::LLT<MatrixXd> chol(s1);
  const auto L = chol.matrixL();
  bool ok = chol.info() == Eigen::Success && s1_max > 0.0;
  for (Index i = 0; ok && i < r; ++i)
    ok = chol.matrixLLT()(i, i) * chol.matrixLLT()(i, i) > kSingular * s1_max;
  if (!ok)
    throw NumericalError(fmt::format(
        "variance components: the cofactor matrix of {} is singular on the residual space (a "
        "combination of the residuals has no variance without {})",
        first.name, second.name));

  MatrixXd h = g2;
  L.solveInPlace(h);
  VectorXd w = y;
  L.solveInPlace(w);
  if (!(y.norm() > 1e-12 * l.norm()))
    throw NumericalError(
        "variance components: the observations lie in the column space of A (no residual): "
        "the likelihood has no maximum");

  Profile p;
  p.r = static_cast<int>(r);
  p.constant =
      static_cast<double>(r) * kLog2Pi + 2.0 * chol.matrixLLT().diagonal().array().log().sum();
  const Eigen::JacobiSVD<MatrixXd> svd(h, Eigen::ComputeThinU);
  const VectorXd sv = svd.singularValues();
  const Index k = sv.size();
  p.lambda = sv.cwiseAbs2();
  const VectorXd z = svd.matrixU().transpose() * w;
  p.z2 = z.cwiseAbs2();
  p.z0sq = k < r ? std::max(0.0, w.squaredNorm() - p.z2.sum()) : 0.0;
  const double lambda_max = p.lambda.size() ? p.lambda.maxCoeff() : 0.0;
  if (!(lambda_max > 0.0))
    throw NumericalError(fmt::format(
        "variance components: {} is not determined by the observations (its cofactor lies in "
        "the column space of A)",
        second.name));
  p.second_definite = k == r && p.lambda.minCoeff() > 1e-12 * lambda_max;
  return p;
}

// The profile on a grid in v = ln τ reaching kGridReach beyond 1/λ_max and 1/λ_min.
struct ProfileGrid {
  double lo = 0.0, hi = 0.0;  // the ends the grid must cover (its last point may lie beyond hi)
  std::vector<double> v, f;
  int best = 0;  // index of the largest f
};

ProfileGrid profile_grid(const Profile& p) {
  const double lambda_max = p.lambda.maxCoeff();
  double lambda_min = lambda_max;
  for (Index j = 0; j < p.lambda.size(); ++j)
    if (p.lambda(j) > 1e-14 * lambda_max) lambda_min = std::min(lambda_min, p.lambda(j));
  const double v_lo = -std::log(lambda_max) - kGridReach;
  const double v_hi = -std::log(lambda_min) + kGridReach;
  const int m = static_cast<int>(std::ceil((v_hi - v_lo) / kGridStep)) + 1;
  ProfileGrid g{v_lo, v_hi, std::vector<double>(static_cast<std::size_t>(m)),
                std::vector<double>(static_cast<std::size_t>(m)), 0};
  for (int i = 0; i < m; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    g.v[iu] = v_lo + i * kGridStep;
    g.f[iu] = p.at_log_ratio(g.v[iu]);
    if (g.f[iu] > g.f[static_cast<std::size_t>(g.best)]) g.best = i;
  }
  return g;
}

// The maximum of the profile inside the bracket of the grid's best point (beyond the grid's
// ends: as far again as it reaches): golden section, then Newton's method to rounding. (v, f).
std::pair<double, double> refine_maximum(const Profile& p, const ProfileGrid& grid) {
  const auto m = static_cast<int>(grid.v.size());
  const int best = grid.best;
  double a = best > 0 ? grid.v[static_cast<std::size_t>(best - 1)] : grid.lo - 2.0 * kGridReach;
  double b = best < m - 1 ? grid.v[static_cast<std::size_t>(best + 1)] : grid.hi + 2.0 * kGridReach;
  const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - gr * (b - a), d = a + gr * (b - a);
  double fc = p.at_log_ratio(c), fd = p.at_log_ratio(d);
  while (b - a > 1e-6 * (1.0 + std::fabs(a) + std::fabs(b))) {
    if (fc >= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - gr * (b - a);
      fc = p.at_log_ratio(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + gr * (b - a);
      fd = p.at_log_ratio(d);
    }
  }
  double v = fc >= fd ? c : d;
  double fv = std::max(fc, fd);
  for (int it = 0; it < 20; ++it) {
    const auto [g, hh] = p.derivatives(v);
    if (!(hh < 0.0)) break;
    const double next = v - g / hh;
    const double fn = p.at_log_ratio(next);
    if (!(fn >= fv - 1e-13 * (1.0 + std::fabs(fv)))) break;
    const bool done = std::fabs(next - v) <= 1e-15 * (1.0 + std::fabs(v));
    v = next;
    fv = fn;
    if (done) break;
  }
  return {v, fv};
}

}  // namespace

TwoComponentReml maximise_two_component_reml(const MatrixXd& A, const VectorXd& l,
                                             const VarianceComponent& first,
                                             const VarianceComponent& second) {
  check_reml_arguments(A, l, first, second);
  const Profile p = residual_profile(A, l, first, second);
  // The grid, and the limits τ = 0 and τ = ∞ as candidates of their own.
  const ProfileGrid grid = profile_grid(p);
  const double f_zero = p.at_zero_ratio();
  const double f_inf = p.at_infinite_ratio();

  TwoComponentReml out;
  out.residual_dimension = p.r;
  const double f_grid = grid.f[static_cast<std::size_t>(grid.best)];
  if (f_zero >= f_grid && f_zero >= f_inf) {
    out.components = {p.z0sq / p.r + p.z2.sum() / p.r, 0.0};
    out.at_zero[1] = true;
    out.reml = f_zero;
    return out;
  }
  if (f_inf > f_grid) {
    double q = 0.0;
    for (Index j = 0; j < p.lambda.size(); ++j) q += p.z2(j) / p.lambda(j);
    out.components = {0.0, q / p.r};
    out.at_zero[0] = true;
    out.reml = f_inf;
    return out;
  }
  const auto [v, fv] = refine_maximum(p, grid);
  const double scale = p.scale_at(v);
  out.components = {scale, scale * std::exp(v)};
  out.reml = fv;
  return out;
}

}  // namespace meridian::adjust
