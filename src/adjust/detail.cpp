#include "detail.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::adjust::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

Index first_non_finite(const VectorXd& v) {
  for (Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v(i))) return i;
  return -1;
}

Cell first_non_finite(const MatrixXd& m) {
  for (Index j = 0; j < m.cols(); ++j)
    for (Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j))) return Cell{i, j};
  return {};
}

void check_finite(const MatrixXd& m, const char* name) {
  if (const Cell c = first_non_finite(m); c.found())
    throw InputError(fmt::format("{} has a non-finite value ({}) at ({}, {})", name,
                                 m(c.row, c.col), c.row, c.col));
}

void check_finite(const VectorXd& v, const char* name) {
  if (const Index i = first_non_finite(v); i >= 0)
    throw InputError(fmt::format("{} has a non-finite value ({}) at index {}", name, v(i), i));
}

double default_rank_tolerance(Index n, Index u) {
  return 100.0 * static_cast<double>(std::max(n, u)) * kEps;
}

ScaledQr scaled_qr(MatrixXd w) {
  const Index u = w.cols();
  ScaledQr s;
  s.scale.resize(u);
  for (Index j = 0; j < u; ++j) {
    const double norm = w.col(j).stableNorm();
    if (!(norm > 0.0) && s.first_zero_column < 0) s.first_zero_column = j;
    s.scale(j) = norm > 0.0 ? norm : 1.0;
    w.col(j) /= s.scale(j);
  }
  s.qr.compute(w);
  return s;
}

ScaledQr full_rank_qr(MatrixXd w, double tol) {
  const Index u = w.cols();
  ScaledQr s = scaled_qr(std::move(w));
  if (s.first_zero_column >= 0)
    throw NumericalError(fmt::format(
        "normal matrix is singular: parameter {} is not determined by the observations "
        "(its column of A is zero)", s.first_zero_column));
  if (const Index k = s.rank(tol); k < u)
    throw NumericalError(fmt::format(
        "normal matrix is singular: parameter {} is not determined by the observations "
        "(its column of A depends linearly on the others; rank {} of {})", s.column_at(k), k, u));
  return s;
}

MatrixXd thin_q(const ScaledQr& s) {
  MatrixXd q = MatrixXd::Identity(s.qr.rows(), s.qr.cols());
  q.applyOnTheLeft(s.qr.householderQ());
  return q;
}

Index ScaledQr::rank(double tol) const {
  const MatrixXd& r = qr.matrixQR();
  const Index u = r.cols();
  const double r00 = std::abs(r(0, 0));
  Index k = 0;
  while (k < u && std::abs(r(k, k)) > tol * r00) ++k;
  return k;
}

}  // namespace meridian::adjust::detail
