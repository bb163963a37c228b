#include "meridian/dov/attitude_difference.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::dov {

void check_rotation(const Eigen::Matrix3d& m, const std::string& field, double tolerance) {
  if (!(std::isfinite(tolerance) && tolerance > 0.0))
    throw InputError(fmt::format("orthogonality tolerance must be finite and > 0, is {}", tolerance),
                     ErrorContext{{}, {}, field});
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(m(i, j)))
        throw InputError(fmt::format("attitude matrix has a non-finite element ({}) at row {}, "
                                     "column {} (1-based)",
                                     m(i, j), i + 1, j + 1),
                         ErrorContext{{}, {}, field});
  const double err = (m.transpose() * m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(err <= tolerance))
    throw InputError(fmt::format("attitude matrix is not orthogonal: max |(CᵀC − I)_ij| = {:.3g} "
                                 "> tolerance {:.3g}",
                                 err, tolerance),
                     ErrorContext{{}, {}, field});
  if (!(m.determinant() > 0.0))
    throw InputError("attitude matrix has determinant −1 (a reflection, not a rotation)",
                     ErrorContext{{}, {}, field});
}

Eigen::Matrix3d attitude_difference_matrix(const Eigen::Matrix3d& lgu_body_to_nav,
                                           const Eigen::Matrix3d& ins_body_to_nav) {
  return lgu_body_to_nav * ins_body_to_nav.transpose();
}

AttitudeDifference skew_symmetric_part(const Eigen::Matrix3d& c) {
  // 1-based C(2,3), C(3,1), C(1,2).
  return {c(1, 2), c(2, 0), c(0, 1)};
}

AttitudeDifference rotation_vector(const Eigen::Matrix3d& c, const std::string& field) {
  // s = vee(Cᵀ − C) = 2 sin θ · (unit axis of Cᵀ): the rotation vector of Cᵀ = exp([ΔΦ×]).
  const Eigen::Vector3d s(c(1, 2) - c(2, 1), c(2, 0) - c(0, 2), c(0, 1) - c(1, 0));
  const double sin_theta = 0.5 * s.norm();
  const double cos_theta = 0.5 * (c.trace() - 1.0);
  const double theta = std::atan2(sin_theta, cos_theta);
  if (theta > std::numbers::pi - 1e-6)
    throw InputError(fmt::format("attitude difference of {:.6f} rad is too close to π for a "
                                 "rotation vector",
                                 theta),
                     ErrorContext{{}, {}, field});
  double factor;  // θ/(2 sin θ)
  if (theta < 1e-4) {
    const double t2 = theta * theta;
    factor = 0.5 + t2 / 12.0 + 7.0 * t2 * t2 / 720.0;
  } else {
    factor = theta / (2.0 * std::sin(theta));
  }
  const Eigen::Vector3d v = factor * s;
  return {v(0), v(1), v(2)};
}

AttitudeDifference extract(const Eigen::Matrix3d& c, Extraction method, const std::string& field) {
  switch (method) {
    case Extraction::Exact:
      return rotation_vector(c, field);
    case Extraction::SkewSymmetric:
      return skew_symmetric_part(c);
  }
  throw InputError("unknown attitude-difference extraction", ErrorContext{{}, {}, field});
}

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a(2), a(1), a(2), 0.0, -a(0), -a(1), a(0), 0.0;
  return m;
}

Eigen::Matrix3d rotation_from_difference(const AttitudeDifference& d) {
  // exp([a×]) = I + (sin θ/θ)[a×] + ((1 − cos θ)/θ²)[a×]², a = −ΔΦ, θ = |a|.
  const Eigen::Vector3d a = -d.vector();
  const double theta = a.norm();
  const Eigen::Matrix3d k = cross_matrix(a);
  double s, c;
  if (theta < 1e-4) {
    const double t2 = theta * theta;
    s = 1.0 - t2 / 6.0 + t2 * t2 / 120.0;
    c = 0.5 - t2 / 24.0 + t2 * t2 / 720.0;
  } else {
    s = std::sin(theta) / theta;
    c = (1.0 - std::cos(theta)) / (theta * theta);
  }
  return Eigen::Matrix3d::Identity() + s * k + c * (k * k);
}

}  // namespace meridian::dov
