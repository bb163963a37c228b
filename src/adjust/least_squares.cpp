#include "meridian/adjust/least_squares.hpp"

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

using detail::kNaN;

// (Q_vv)_ii = Σ_ii − ‖(L·Q1)_i‖² loses about ε·Σ_ii to cancellation; below this fraction
// of Σ_ii the observation is uncontrolled and w_i is undefined (likewise (P·Q_vv·P)_ii
// against (Σ⁻¹)_ii for Baarda's w).
constexpr double kTinyQvv = 1e-12;

// Baarda's w for correlated observations: P·v = L⁻ᵀ·ṽ and P·Q_vv·P = L⁻ᵀ·(I − Q1·Q1ᵀ)·L⁻¹,
// so (P·Q_vv·P)_ii = (Σ⁻¹)_ii − ‖(L⁻ᵀ·Q1)_i‖² with (Σ⁻¹)_ii the squared norm of column i of L⁻¹.
VectorXd w_statistics(const VectorXd& vw, const MatrixXd& lt_q1, const CovarianceFactor& cov) {
  const Index n = vw.size();
  VectorXd pv = vw;
  cov.whiten_transposed(pv);
  MatrixXd linv = MatrixXd::Identity(n, n);
  cov.whiten(linv);
  VectorXd w(n);
  for (Index i = 0; i < n; ++i) {
    const double pii = linv.col(i).squaredNorm();
    const double pqp = pii - lt_q1.row(i).squaredNorm();
    w(i) = pqp > kTinyQvv * pii ? pv(i) / std::sqrt(pqp) : kNaN;
  }
  return w;
}

// Statistics from the whitened, scaled factorisation  L⁻¹·A·S⁻¹·P = Q·R.
LeastSquaresResult finish(const detail::ScaledQr& s, const VectorXd& lw,
                          const CovarianceFactor& cov) {
  const auto& qr = s.qr;
  const Index n = lw.size();
  const Index u = s.scale.size();
  const auto& perm = qr.colsPermutation().indices();
  const auto R = qr.matrixQR().topLeftCorner(u, u).triangularView<Eigen::Upper>();

  // c = Qᵀ·l̃; its first u entries give x, the rest are the whitened residuals in Q-space.
  VectorXd c = lw;
  c.applyOnTheLeft(qr.householderQ().adjoint());

  LeastSquaresResult res;
  VectorXd y = c.head(u);
  R.solveInPlace(y);
  res.x.resize(u);
  for (Index k = 0; k < u; ++k) res.x(perm(k)) = y(k) / s.scale(perm(k));

  // Q_xx = S⁻¹·P·R⁻¹·R⁻ᵀ·Pᵀ·S⁻¹ from triangular solves.
  MatrixXd rinv = MatrixXd::Identity(u, u);
  R.solveInPlace(rinv);
  MatrixXd m(u, u);
  for (Index k = 0; k < u; ++k) m.row(perm(k)) = rinv.row(k) / s.scale(perm(k));
  MatrixXd lower = MatrixXd::Zero(u, u);
  lower.selfadjointView<Eigen::Lower>().rankUpdate(m);
  res.cofactor = lower.selfadjointView<Eigen::Lower>();  // exactly symmetric

  // Whitened residuals ṽ = L⁻¹(A·x̂ − l) = −Q·[0; c₂], free of the cancellation in A·x̂ − l.
  VectorXd vw = VectorXd::Zero(n);
  vw.tail(n - u) = -c.tail(n - u);
  vw.applyOnTheLeft(qr.householderQ());
  res.vtpv = c.tail(n - u).squaredNorm();
  res.residuals = vw;
  cov.colour(res.residuals);

  // Whitened residual projector I − Q1·Q1ᵀ mapped back: Q_vv·Σ⁻¹ = L·(I − Q1·Q1ᵀ)·L⁻¹, so
  // r_i = 1 − Σ_k (L·Q1)_ik·(L⁻ᵀ·Q1)_ik and (Q_vv)_ii = Σ_ii − ‖(L·Q1)_i‖².
  MatrixXd q1 = MatrixXd::Identity(n, u);
  q1.applyOnTheLeft(qr.householderQ());
  MatrixXd b = q1;
  cov.colour(b);
  MatrixXd cm = std::move(q1);
  cov.whiten_transposed(cm);
  res.redundancy.resize(n);
  res.qvv_diagonal.resize(n);
  res.standardized_residuals.resize(n);
  const VectorXd& var = cov.variances();
  for (Index i = 0; i < n; ++i) {
    res.redundancy(i) = 1.0 - b.row(i).dot(cm.row(i));
    const double qvv = var(i) - b.row(i).squaredNorm();
    res.qvv_diagonal(i) = qvv;
    res.standardized_residuals(i) =
        qvv > kTinyQvv * var(i) ? res.residuals(i) / std::sqrt(qvv) : kNaN;
  }
  res.w_statistics =
      cov.is_diagonal() ? res.standardized_residuals : w_statistics(vw, cm, cov);

  res.dof = static_cast<int>(n - u);
  res.sigma0 = res.dof > 0 ? std::sqrt(res.vtpv / res.dof) : kNaN;
  res.covariance_aposteriori =
      res.dof > 0 ? MatrixXd(res.sigma0 * res.sigma0 * res.cofactor) : res.cofactor;
  return res;
}

void check_rows(Index rows, Index expected, const char* what) {
  if (rows != expected)
    throw InputError(fmt::format("CovarianceFactor::{}: matrix has {} rows, expected {}", what,
                                 rows, expected));
}

}  // namespace

// ---------------------------------------------------------------------------------------------

double LeastSquaresResult::sigma_apriori(int i) const {
  if (i < 0 || i >= cofactor.rows())
    throw InputError(fmt::format("parameter index {} out of range [0, {})", i, cofactor.rows()));
  return std::sqrt(cofactor(i, i));
}

double LeastSquaresResult::sigma_aposteriori(int i) const {
  const double s = sigma_apriori(i);  // range check also when dof = 0
  return dof > 0 ? sigma0 * s : kNaN;
}

// ---------------------------------------------------------------------------------------------

CovarianceFactor::CovarianceFactor(const MatrixXd& sigma_ll) {
  const Index n = sigma_ll.rows();
  if (n == 0 || sigma_ll.cols() != n)
    throw InputError(fmt::format("observation covariance must be square and non-empty, is {}×{}",
                                 sigma_ll.rows(), sigma_ll.cols()));
  detail::check_finite(sigma_ll, "observation covariance");
  variances_ = sigma_ll.diagonal();
  for (Index i = 0; i < n; ++i)
    if (!(variances_(i) > 0.0))
      throw NumericalError(fmt::format(
          "observation covariance is not positive definite: variance of observation {} is {}", i,
          variances_(i)));
  bool diagonal = true;
  for (Index j = 0; j < n; ++j) {
    for (Index i = j + 1; i < n; ++i) {
      const double a = sigma_ll(i, j);
      const double b = sigma_ll(j, i);
      if (std::abs(a - b) > 1e-10 * std::sqrt(variances_(i) * variances_(j)))
        throw InputError(fmt::format(
            "observation covariance is not symmetric: element ({}, {}) = {} but ({}, {}) = {}", i,
            j, a, j, i, b));
      if (a != 0.0 || b != 0.0) diagonal = false;
    }
  }
  if (diagonal) {
    sigma_ = variances_.cwiseSqrt();
    return;
  }
  const Eigen::LLT<MatrixXd> llt(sigma_ll);
  if (llt.info() != Eigen::Success)
    throw NumericalError(
        "observation covariance is not positive definite (its Cholesky factorisation fails)");
  lower_ = llt.matrixL();
  // LLT accepts any positive pivot; a pivot at rounding level means a perfect correlation.
  const double tiny = 8.0 * static_cast<double>(n) * detail::kEps;
  for (Index i = 1; i < n; ++i) {
    if (!(lower_(i, i) * lower_(i, i) > tiny * variances_(i)))
      throw NumericalError(fmt::format(
          "observation covariance is not positive definite: observation {} is perfectly "
          "correlated with observations 0..{}", i, i - 1));
  }
}

CovarianceFactor CovarianceFactor::diagonal(const VectorXd& sigma) {
  if (sigma.size() == 0) throw InputError("no observation standard deviations given");
  for (Index i = 0; i < sigma.size(); ++i)
    if (!(std::isfinite(sigma(i)) && sigma(i) > 0.0))
      throw InputError(fmt::format(
          "standard deviation of observation {} must be positive and finite, is {}", i,
          sigma(i)));
  CovarianceFactor f;
  f.sigma_ = sigma;
  f.variances_ = sigma.array().square();
  return f;
}

double CovarianceFactor::log_determinant() const {
  if (is_diagonal()) return variances_.array().log().sum();
  return 2.0 * lower_.diagonal().array().log().sum();
}

void CovarianceFactor::whiten(Eigen::Ref<MatrixXd> m) const {
  check_rows(m.rows(), size(), "whiten");
  if (is_diagonal())
    m.array().colwise() /= sigma_.array();
  else
    lower_.triangularView<Eigen::Lower>().solveInPlace(m);
}

void CovarianceFactor::whiten_transposed(Eigen::Ref<MatrixXd> m) const {
  check_rows(m.rows(), size(), "whiten_transposed");
  if (is_diagonal())
    m.array().colwise() /= sigma_.array();
  else
    lower_.triangularView<Eigen::Lower>().transpose().solveInPlace(m);
}

void CovarianceFactor::colour(Eigen::Ref<MatrixXd> m) const {
  check_rows(m.rows(), size(), "colour");
  if (is_diagonal()) {
    m.array().colwise() *= sigma_.array();
  } else {
    const MatrixXd t = lower_.triangularView<Eigen::Lower>() * m;
    m = t;
  }
}

// ---------------------------------------------------------------------------------------------

LeastSquaresResult solve_linear(const MatrixXd& A, const VectorXd& l,
                                const CovarianceFactor& sigma_ll, const LinearOptions& options) {
  const Index n = A.rows();
  const Index u = A.cols();
  if (u < 1) throw InputError("design matrix A has no columns (no parameters)");
  if (n < u)
    throw InputError(
        fmt::format("fewer observations ({}) than parameters ({}): A is {}×{}", n, u, n, u));
  if (l.size() != n)
    throw InputError(fmt::format("observation vector l has {} entries but A has {} rows",
                                 l.size(), n));
  if (sigma_ll.size() != n)
    throw InputError(fmt::format("observation covariance is {}×{} but A has {} rows",
                                 sigma_ll.size(), sigma_ll.size(), n));
  detail::check_finite(A, "design matrix A");
  detail::check_finite(l, "observation vector l");
  if (std::isnan(options.rank_tolerance) || std::isinf(options.rank_tolerance))
    throw InputError(fmt::format("rank tolerance must be finite, is {}", options.rank_tolerance));
  const double tol = options.rank_tolerance > 0.0 ? options.rank_tolerance
                                                 : detail::default_rank_tolerance(n, u);

  // The triangular solves are backward stable with one perturbation of L for all columns, so
  // an exact dependency among the columns of A stays at rounding level in L⁻¹·A.
  MatrixXd aw = A;
  sigma_ll.whiten(aw);
  VectorXd lw = l;
  sigma_ll.whiten(lw);
  return finish(detail::full_rank_qr(std::move(aw), tol), lw, sigma_ll);
}

LeastSquaresResult solve_linear(const MatrixXd& A, const VectorXd& l, const MatrixXd& sigma_ll) {
  if (sigma_ll.rows() != l.size() || sigma_ll.cols() != l.size())
    throw InputError(fmt::format("observation covariance is {}×{} but l has {} entries",
                                 sigma_ll.rows(), sigma_ll.cols(), l.size()));
  return solve_linear(A, l, CovarianceFactor(sigma_ll));
}

LeastSquaresResult solve_linear_diagonal(const MatrixXd& A, const VectorXd& l,
                                         const VectorXd& sigma) {
  if (sigma.size() != l.size())
    throw InputError(fmt::format("{} standard deviations given for {} observations",
                                 sigma.size(), l.size()));
  return solve_linear(A, l, CovarianceFactor::diagonal(sigma));
}

}  // namespace meridian::adjust
