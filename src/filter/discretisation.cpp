#include "meridian/filter/discretisation.hpp"

#include <cmath>

#include <fmt/format.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "meridian/core/error.hpp"

namespace meridian::filter {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

void check_finite(const MatrixXd& m, const char* name) {
  if (!m.allFinite()) throw InputError(fmt::format("{} has a non-finite entry", name));
}

}  // namespace

DiscreteModel<Eigen::Dynamic> discretise_dynamic(const MatrixXd& F, const MatrixXd& G,
                                                 const MatrixXd& q_c, double dt_s,
                                                 Discretisation method) {
  const Index n = F.rows();
  if (n < 1 || F.cols() != n)
    throw InputError(
        fmt::format("dynamics matrix F must be square and not empty, is {}×{}", n, F.cols()));
  if (G.rows() != n || G.cols() < 1)
    throw InputError(
        fmt::format("noise input matrix G is {}×{}, expected {} rows", G.rows(), G.cols(), n));
  const Index w = G.cols();
  if (q_c.rows() != w || q_c.cols() != w)
    throw InputError(fmt::format("noise density Q_c is {}×{}, expected {}×{} (columns of G)",
                                 q_c.rows(), q_c.cols(), w, w));
  check_finite(F, "dynamics matrix F");
  check_finite(G, "noise input matrix G");
  check_finite(q_c, "noise density Q_c");
  const double q_scale = q_c.cwiseAbs().maxCoeff();
  if ((q_c - q_c.transpose()).cwiseAbs().maxCoeff() > 1e-12 * q_scale)
    throw InputError("noise density Q_c is not symmetric");
  if ((q_c.diagonal().array() < 0.0).any())
    throw InputError("noise density Q_c has a negative diagonal element");
  if (!(std::isfinite(dt_s) && dt_s > 0.0))
    throw InputError(fmt::format("time step Δt must be finite and > 0, is {} s", dt_s));

  DiscreteModel<Eigen::Dynamic> d;
  const MatrixXd gqg = G * q_c * G.transpose();
  switch (method) {
    case Discretisation::VanLoan: {
      // Q_d is linear in Q_c: exponentiate with Q_c scaled to unit size, scale back.
      const double s = q_scale > 0.0 ? q_scale : 1.0;
      MatrixXd a = MatrixXd::Zero(2 * n, 2 * n);
      a.topLeftCorner(n, n) = -F * dt_s;
      a.topRightCorner(n, n) = gqg * (dt_s / s);
      a.bottomRightCorner(n, n) = F.transpose() * dt_s;
      const MatrixXd b = a.exp();
      d.phi = b.bottomRightCorner(n, n).transpose();
      d.q = s * (d.phi * b.topRightCorner(n, n));
      break;
    }
    case Discretisation::FirstOrder:
      d.phi = MatrixXd::Identity(n, n) + F * dt_s;
      d.q = gqg * dt_s;
      break;
    case Discretisation::FirstOrderDiscreteNoise:
      d.phi = MatrixXd::Identity(n, n) + F * dt_s;
      d.q = gqg * (dt_s * dt_s);
      break;
    default:
      throw InputError("unknown discretisation method");
  }
  d.q = (0.5 * (d.q + d.q.transpose())).eval();
  if (!d.phi.allFinite() || !d.q.allFinite())
    throw NumericalError(
        fmt::format("the discretised model is not finite (‖F‖·Δt too large: "
                    "Δt = {} s)",
                    dt_s));
  return d;
}

}  // namespace meridian::filter
