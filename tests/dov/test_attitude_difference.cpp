// The attitude-difference observation (dov/attitude_difference.hpp) against independent
// references: Eigen's AngleAxis (an independent log/exp implementation), the spec's
// skew-symmetric part against the exact log map, and the DOV sign convention through the
// geometric astronomic zenith of geodesy/frames.hpp.
#include <cmath>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "dov_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/dov/attitude_difference.hpp"
#include "meridian/geodesy/frames.hpp"

namespace {

using meridian::InputError;
using meridian::dov::AttitudeDifference;
using meridian::dov::check_rotation;
using meridian::dov::cross_matrix;
using meridian::dov::Extraction;
using meridian::dov::extract;
using meridian::dov::rotation_from_difference;
using meridian::dov::rotation_vector;
using meridian::dov::skew_symmetric_part;
namespace units = meridian::units;

using meridian_test::kAs;

Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> nd;
  Eigen::Quaterniond q(nd(rng), nd(rng), nd(rng), nd(rng));
  q.normalize();
  return q.toRotationMatrix();
}

TEST(AttitudeDifference, ExactExtractionInvertsEigenAngleAxis) {
  // C = exp(−[ΔΦ×]) is the rotation by angle |ΔΦ| about −ΔΦ/|ΔΦ| (Eigen, right-handed).
  std::mt19937_64 rng(7);
  std::normal_distribution<double> nd;
  for (double scale : {1e-9, 1e-6, 1e-4, 1e-2, 0.5, 2.0}) {
    for (int i = 0; i < 20; ++i) {
      Eigen::Vector3d a(nd(rng), nd(rng), nd(rng));
      a *= scale / a.norm();
      const Eigen::Matrix3d c = Eigen::AngleAxisd(a.norm(), -a.normalized()).toRotationMatrix();
      const AttitudeDifference d = rotation_vector(c);
      EXPECT_NEAR(d.east_rad, a(0), 1e-15 + 1e-12 * scale) << scale;
      EXPECT_NEAR(d.north_rad, a(1), 1e-15 + 1e-12 * scale) << scale;
      EXPECT_NEAR(d.up_rad, a(2), 1e-15 + 1e-12 * scale) << scale;
      // and rotation_from_difference is Eigen's matrix
      EXPECT_LT((rotation_from_difference(d) - c).cwiseAbs().maxCoeff(), 1e-15 + 1e-13 * scale);
    }
  }
}

TEST(AttitudeDifference, SkewPartIsTheSpecsElements) {
  // 1-based C(2,3), C(3,1), C(1,2) of an arbitrary matrix.
  Eigen::Matrix3d c;
  c << 11, 12, 13, 21, 22, 23, 31, 32, 33;
  const AttitudeDifference d = skew_symmetric_part(c);
  EXPECT_EQ(d.east_rad, 23);
  EXPECT_EQ(d.north_rad, 31);
  EXPECT_EQ(d.up_rad, 12);
  EXPECT_EQ(extract(c, Extraction::SkewSymmetric).up_rad, 12);
}

TEST(AttitudeDifference, SkewPartAgreesWithLogMapToSecondOrder) {
  // For a small rotation the skew elements differ from the exact rotation vector by the
  // symmetric part ½[ΔΦ×]², i.e. by at most ~|ΔΦ|²/2 — at the arcsecond level far below 1e-3″.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> nd;
  for (double size_as : {0.1, 1.0, 10.0, 60.0, 600.0}) {
    double worst = 0.0;
    for (int i = 0; i < 50; ++i) {
      Eigen::Vector3d a(nd(rng), nd(rng), nd(rng));
      a *= size_as * kAs / a.norm();
      const Eigen::Matrix3d c = rotation_from_difference({a(0), a(1), a(2)});
      const Eigen::Vector3d skew = skew_symmetric_part(c).vector();
      const Eigen::Vector3d exact = rotation_vector(c).vector();
      const double diff = (skew - exact).cwiseAbs().maxCoeff();
      const double theta = a.norm();
      EXPECT_LE(diff, 0.5 * theta * theta * 1.0001 + 1e-18) << size_as;
      worst = std::max(worst, diff);
    }
    // arcsecond-level agreement: ≤ 2.4e-4″ at 10″, ≤ 0.009″ at 60″ (θ²/2)
    if (size_as <= 10.0) {
      EXPECT_LT(worst / kAs, 3e-4) << size_as;
    }
    if (size_as <= 60.0) {
      EXPECT_LT(worst / kAs, 1e-2) << size_as;
    }
  }
  // and the difference is really there for a large angle (the check can fail)
  const Eigen::Matrix3d c = rotation_from_difference({0.01, 0.02, -0.015});
  EXPECT_GT((skew_symmetric_part(c).vector() - rotation_vector(c).vector()).cwiseAbs().maxCoeff(),
            1e-5);
}

TEST(AttitudeDifference, BodyAttitudeCancels) {
  // C_{n′}^n = C_b^n·(C_b^{n′})ᵀ does not depend on the body attitude.
  std::mt19937_64 rng(3);
  const Eigen::Matrix3d tilt = rotation_from_difference({3e-5, -2e-5, 1e-5});
  for (int i = 0; i < 10; ++i) {
    const Eigen::Matrix3d body = random_rotation(rng);
    const Eigen::Matrix3d c =
        meridian::dov::attitude_difference_matrix(tilt * body, body);  // LGU = tilt·INS
    EXPECT_LT((c - tilt).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(AttitudeDifference, DeflectionSignThroughTheAstronomicZenith) {
  // The frame n′ levelled to the plumb line has its up axis along the astronomic zenith, which
  // geodesy gives (exactly) for ξ, η. With LGU in n and INS in n′ (no errors), the spec says
  // ΔΦ_E = ξ and ΔΦ_N = −η. Independent of dov's formulas: the zenith comes from geodesy.
  const double lat = 40.0 * units::kDegree;
  for (const auto& [xi, eta] : {std::pair{7.0, -4.0}, std::pair{-12.0, 9.0}, std::pair{30.0, 25.0}}) {
    const Eigen::Vector3d u =
        meridian::geodesy::astronomic_zenith_enu(meridian::geodesy::Deflection{xi * kAs, eta * kAs}, lat);
    const Eigen::Matrix3d plumb_to_nav =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), u).toRotationMatrix();
    const Eigen::Matrix3d body = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())
                                     .toRotationMatrix();
    const Eigen::Matrix3d lgu = body;                              // C_b^n
    const Eigen::Matrix3d ins = plumb_to_nav.transpose() * body;  // C_b^{n′}
    const AttitudeDifference d =
        rotation_vector(meridian::dov::attitude_difference_matrix(lgu, ins));
    // first-order agreement: the exact zenith differs from (η, ξ, 1)/norm by O(θ²·tan φ)
    // (frames.hpp: −ξη·tan φ east, (η²/2)·tan φ north), θ² = ξ² + η²: 0.014″ for (30″, 25″);
    // a sign error would be off by 2|ξ| or 2|η|.
    const double theta2 = (xi * xi + eta * eta) * kAs * kAs;
    const double tol_as = theta2 * (1.0 + std::tan(lat)) / kAs;
    EXPECT_NEAR(d.east_rad / kAs, xi, tol_as);
    EXPECT_NEAR(d.north_rad / kAs, -eta, tol_as);
    EXPECT_NEAR(d.up_rad / kAs, 0.0, tol_as);
  }
}

TEST(AttitudeDifference, PsiAngleErrorsAddWithTheSpecsSigns) {
  // LGU computed (I − [φ×])·C true, INS computed (I − [v×])·C true: ΔΦ = φ − v to first order.
  const Eigen::Vector3d phi(2e-5, -1e-5, 3e-5), v(-4e-6, 6e-6, 1e-6);
  const Eigen::Matrix3d body = Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d lgu = (Eigen::Matrix3d::Identity() - cross_matrix(phi)) * body;
  const Eigen::Matrix3d ins = (Eigen::Matrix3d::Identity() - cross_matrix(v)) * body;
  // (I − [φ×]) is orthogonal only to first order: take the exact rotations instead
  const Eigen::Matrix3d lgu_r = rotation_from_difference({phi(0), phi(1), phi(2)}) * body;
  const Eigen::Matrix3d ins_r = rotation_from_difference({v(0), v(1), v(2)}) * body;
  EXPECT_LT((lgu - lgu_r).cwiseAbs().maxCoeff(), 2e-9);
  EXPECT_LT((ins - ins_r).cwiseAbs().maxCoeff(), 2e-9);
  const Eigen::Vector3d d =
      rotation_vector(meridian::dov::attitude_difference_matrix(lgu_r, ins_r)).vector();
  EXPECT_LT((d - (phi - v)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(AttitudeDifference, CheckRotationRejectsBadMatrices) {
  const Eigen::Matrix3d good = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_NO_THROW(check_rotation(good, "samples[4].lgu_body_to_nav"));
  Eigen::Matrix3d scaled = good * (1.0 + 1e-6);
  try {
    check_rotation(scaled, "samples[4].lgu_body_to_nav");
    FAIL() << "a non-orthogonal matrix passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "samples[4].lgu_body_to_nav");
    EXPECT_NE(std::string(e.what()).find("not orthogonal"), std::string::npos) << e.what();
  }
  Eigen::Matrix3d nan = good;
  nan(2, 1) = std::nan("");
  try {
    check_rotation(nan, "samples[9].ins_body_to_nav");
    FAIL() << "a NaN matrix passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "samples[9].ins_body_to_nav");
    EXPECT_NE(std::string(e.what()).find("row 3, column 2"), std::string::npos) << e.what();
  }
  Eigen::Matrix3d reflection = good;
  reflection.col(0) *= -1.0;
  EXPECT_THROW(check_rotation(reflection, "x"), InputError);
  // just inside and just outside the tolerance
  Eigen::Matrix3d slightly = good;
  slightly(0, 0) += 2e-9;
  EXPECT_NO_THROW(check_rotation(slightly, "x"));
  slightly(0, 0) += 2e-8;
  EXPECT_THROW(check_rotation(slightly, "x"), InputError);
}

TEST(AttitudeDifference, NearPiIsAnError) {
  const Eigen::Matrix3d c =
      Eigen::AngleAxisd(units::kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_THROW(rotation_vector(c, "samples[0].lgu_body_to_nav"), InputError);
}

}  // namespace
