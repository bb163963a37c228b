// dov/euler.hpp: the matrix of heading, pitch, roll against matrices built by hand for single
// rotations, against the product of Eigen's AngleAxis rotations in the stated z-x-y sequence,
// and the geometric meaning of each angle (where the forward and right axes point).
#include <cmath>
#include <tuple>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meridian/core/units.hpp"
#include "meridian/dov/euler.hpp"

namespace {

using meridian::dov::body_to_nav_from_euler;
constexpr double kDeg = meridian::units::kDegree;

TEST(DovEuler, SingleRotationsByHand) {
  // heading east: the body's forward axis (y) is east, its right axis (x) south
  Eigen::Matrix3d east;
  east << 0, 1, 0,  //
      -1, 0, 0,     //
      0, 0, 1;
  EXPECT_LT((body_to_nav_from_euler(90 * kDeg, 0, 0) - east).cwiseAbs().maxCoeff(), 1e-15);
  // 30° nose up, heading north: forward = (0, cos 30°, sin 30°), up = (0, −sin 30°, cos 30°)
  const double c = std::cos(30 * kDeg), s = std::sin(30 * kDeg);
  Eigen::Matrix3d up;
  up << 1, 0, 0,  //
      0, c, -s,   //
      0, s, c;
  EXPECT_LT((body_to_nav_from_euler(0, 30 * kDeg, 0) - up).cwiseAbs().maxCoeff(), 1e-15);
  // 30° right side down, heading north: right = (cos 30°, 0, −sin 30°)
  Eigen::Matrix3d roll;
  roll << c, 0, s,  //
      0, 1, 0,      //
      -s, 0, c;
  EXPECT_LT((body_to_nav_from_euler(0, 0, 30 * kDeg) - roll).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(DovEuler, SequenceZxyAndTheAxesItMoves) {
  for (const auto& [h, p, r] : {std::tuple{37.0, 4.0, -7.0}, std::tuple{-170.0, -30.0, 20.0},
                                 std::tuple{250.0, 80.0, 175.0}}) {
    const Eigen::Matrix3d m = body_to_nav_from_euler(h * kDeg, p * kDeg, r * kDeg);
    const Eigen::Matrix3d ref =
        (Eigen::AngleAxisd(-h * kDeg, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(p * kDeg, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(r * kDeg, Eigen::Vector3d::UnitY()))
            .toRotationMatrix();
    EXPECT_LT((m - ref).cwiseAbs().maxCoeff(), 1e-15) << h;
    EXPECT_LT((m.transpose() * m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_NEAR(m.determinant(), 1.0, 1e-15);
    // forward axis: azimuth ψ clockwise from north, elevation θ
    const Eigen::Vector3d fwd = m.col(1);
    EXPECT_NEAR(std::asin(fwd.z()), p * kDeg, 1e-14);
    EXPECT_NEAR(std::remainder(std::atan2(fwd.x(), fwd.y()) - h * kDeg, 2 * M_PI), 0.0, 1e-14);
    // roll: the right axis dips below the horizontal by asin(cos θ · sin φ)
    EXPECT_NEAR(m(2, 0), -std::cos(p * kDeg) * std::sin(r * kDeg), 1e-15);
  }
}

}  // namespace
