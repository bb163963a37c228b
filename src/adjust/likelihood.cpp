#include "meridian/adjust/likelihood.hpp"

#include <cmath>

#include <fmt/format.h>

#include "detail.hpp"
#include "meridian/core/error.hpp"

namespace meridian::adjust {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

using detail::kLog2Pi;

void check_sizes(const MatrixXd& A, Index n_cov, const char* what) {
  if (A.cols() < 1) throw InputError("design matrix A has no columns (no parameters)");
  if (A.rows() <= A.cols())
    throw InputError(fmt::format("{}: needs more observations ({}) than parameters ({})", what,
                                 A.rows(), A.cols()));
  if (n_cov != A.rows())
    throw InputError(
        fmt::format("observation covariance is {}×{} but A has {} rows", n_cov, n_cov, A.rows()));
  detail::check_finite(A, "design matrix A");
}

// ln |det M| of a square matrix from its QR factorisation (Σ ln |R_kk|).
double log_abs_det_gram(const MatrixXd& w) {
  // det(WᵀW) = det(R)² for W = Q·R.
  const Eigen::HouseholderQR<MatrixXd> qr(w);
  return 2.0 * qr.matrixQR().diagonal().head(w.cols()).cwiseAbs().array().log().sum();
}

}  // namespace

GlsLikelihood gls_log_likelihood(const MatrixXd& A, const VectorXd& l, const CovarianceFactor& D) {
  check_sizes(A, D.size(), "log-likelihood");
  if (l.size() != A.rows())
    throw InputError(
        fmt::format("observation vector l has {} entries but A has {} rows", l.size(), A.rows()));
  detail::check_finite(l, "observation vector l");
  const Index n = A.rows();
  const Index u = A.cols();
  MatrixXd aw = A;
  D.whiten(aw);
  VectorXd lw = l;
  D.whiten(lw);
  const detail::ScaledQr s = detail::full_rank_qr(aw, detail::default_rank_tolerance(n, u));
  // Whitened residual: the part of L⁻¹·l outside the column space of L⁻¹·A.
  VectorXd c = lw;
  c.applyOnTheLeft(s.qr.householderQ().adjoint());

  GlsLikelihood g;
  g.observations = static_cast<int>(n);
  g.parameters = static_cast<int>(u);
  g.vtpv = c.tail(n - u).squaredNorm();
  g.log_det_covariance = D.log_determinant();
  g.log_det_normal = log_abs_det_gram(aw);
  g.log_det_design = log_abs_det_gram(A);
  const double nd = static_cast<double>(n);
  const double r = static_cast<double>(n - u);
  g.ml = -0.5 * (nd * kLog2Pi + g.log_det_covariance + g.vtpv);
  g.reml =
      -0.5 * (r * kLog2Pi + g.log_det_covariance + g.log_det_normal - g.log_det_design + g.vtpv);
  return g;
}

MatrixXd reml_fisher_information(const MatrixXd& A, const CovarianceFactor& D,
                                 const std::vector<MatrixXd>& derivatives) {
  check_sizes(A, D.size(), "Fisher information");
  const Index n = A.rows();
  const Index u = A.cols();
  MatrixXd aw = A;
  D.whiten(aw);
  const MatrixXd q = detail::thin_q(detail::full_rank_qr(aw, detail::default_rank_tolerance(n, u)));
  // P̄ = L⁻ᵀ·M·L⁻¹ with M = I − Q·Qᵀ, so tr(P̄·X·P̄·Y) = tr(M·X̄·M·Ȳ), X̄ = L⁻¹·X·L⁻ᵀ.
  std::vector<MatrixXd> proj;  // M·X̄_a·M
  std::vector<MatrixXd> bar;   // X̄_a
  for (std::size_t a = 0; a < derivatives.size(); ++a) {
    const MatrixXd& x = derivatives[a];
    if (x.rows() != n || x.cols() != n)
      throw InputError(fmt::format("derivative {} of the covariance is {}×{}, expected {}×{}", a,
                                   x.rows(), x.cols(), n, n));
    detail::check_finite(x, "derivative of the covariance");
    MatrixXd xb = x;
    D.whiten(xb);
    MatrixXd t = xb.transpose();
    D.whiten(t);  // L⁻¹·(L⁻¹·X)ᵀ = L⁻¹·Xᵀ·L⁻ᵀ = X̄ for symmetric X
    MatrixXd m = t - q * (q.transpose() * t);
    m -= (m * q) * q.transpose();
    proj.push_back(std::move(m));
    bar.push_back(std::move(t));
  }
  const auto k = static_cast<Index>(derivatives.size());
  MatrixXd info(k, k);
  for (Index a = 0; a < k; ++a)
    for (Index b = 0; b <= a; ++b) {
      // tr(M·X̄_a·M·X̄_b) = Σ_ij (M·X̄_a·M)_ij·(X̄_b)_ji
      const double t = proj[a].cwiseProduct(bar[b].transpose()).sum();
      info(a, b) = info(b, a) = 0.5 * t;
    }
  return info;
}

}  // namespace meridian::adjust
