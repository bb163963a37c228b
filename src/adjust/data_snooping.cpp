#include "meridian/adjust/data_snooping.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/adjust/statistics.hpp"
#include "meridian/core/error.hpp"

namespace meridian::adjust {
namespace {

struct Pass {
  int index = -1;
  double w = 0.0, t = 0.0;
};

// The observation of largest |t_i| = |w_i|/σ̂_(i), σ̂_(i)² = (Ω − w_i²)/(dof − 1).
Pass largest_t(const LeastSquaresResult& r) {
  Pass p;
  for (Eigen::Index i = 0; i < r.w_statistics.size(); ++i) {
    const double w = r.w_statistics(i);
    if (!std::isfinite(w)) continue;
    const double rest = std::max(r.vtpv - w * w, 0.0) / (r.dof - 1);
    const double t = rest > 0.0 ? w / std::sqrt(rest) : (w >= 0 ? 1.0 : -1.0) * HUGE_VAL;
    if (p.index < 0 || std::fabs(t) > std::fabs(p.t)) p = {static_cast<int>(i), w, t};
  }
  return p;
}

}  // namespace

SnoopingResult iterated_data_snooping(const Eigen::MatrixXd& A, const Eigen::VectorXd& l,
                                      const CovarianceFactor& Q, const SnoopingOptions& options) {
  if (!(options.alpha0 > 0.0 && options.alpha0 < 1.0))
    throw InputError(fmt::format("data snooping: alpha0 must be in (0, 1), is {}", options.alpha0));
  if (options.max_outliers < 0)
    throw InputError(
        fmt::format("data snooping: max_outliers must be >= 0, is {}", options.max_outliers));
  SnoopingResult out;
  Eigen::MatrixXd Ak = A;
  out.final_fit = solve_linear(Ak, l, Q);
  for (;;) {
    const LeastSquaresResult& r = out.final_fit;
    if (r.dof < 2) break;  // σ̂_(i) needs dof − 1 ≥ 1
    const Pass p = largest_t(r);
    out.last_largest_index = p.index;
    out.last_largest_t = p.t;
    if (p.index < 0) break;
    const double k = student_t_two_sided_critical(options.alpha0, r.dof - 1);
    if (!(std::fabs(p.t) > k) || static_cast<int>(out.outliers.size()) >= options.max_outliers ||
        r.dof < 3)
      break;
    SnoopedOutlier o;
    o.index = p.index;
    o.w = p.w;
    o.t = p.t;
    o.critical = k;
    o.dof = r.dof;
    out.outliers.push_back(o);
    // The mean-shift model: l_i = a_iᵀx + ∇ + e_i, i.e. l + v = A·x + e_i·∇.
    Ak.conservativeResize(Eigen::NoChange, Ak.cols() + 1);
    Ak.col(Ak.cols() - 1).setZero();
    Ak(p.index, Ak.cols() - 1) = 1.0;
    out.final_fit = solve_linear(Ak, l, Q);
    out.last_largest_index = -1;
    out.last_largest_t = 0.0;
  }
  const auto u = A.cols();
  for (std::size_t j = 0; j < out.outliers.size(); ++j) {
    const auto c = u + static_cast<Eigen::Index>(j);
    // v = A·x + e_i·∇ − l, so ∇ is what l_i has in excess of A·x.
    out.outliers[j].error = out.final_fit.x(c);
    out.outliers[j].sigma_error = out.final_fit.sigma_aposteriori(static_cast<int>(c));
  }
  return out;
}

}  // namespace meridian::adjust
