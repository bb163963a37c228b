// Kalman filter: steady-state Riccati closed form, the Joseph update against the textbook
// formula, sequential = joint update, fixed = dynamic size, gating of a planted outlier, and
// errors that name the epoch.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "example_models.hpp"
#include "meridian/core/error.hpp"
#include "meridian/filter/kalman_filter.hpp"
#include "test_support.hpp"

namespace {

using meridian::InputError;
using meridian::NumericalError;
using meridian::filter::Estimate;
using meridian::filter::Innovation;
using meridian::filter::InnovationGate;
using meridian::filter::KalmanFilter;
using meridian::filter::Matrix;
using meridian::filter::Vector;
using meridian::filter::testing::catch_error;
using meridian::filter::testing::covariance_difference;
using meridian::filter::testing::state_difference;
using namespace meridian::filter::examples;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kDov = DovState::size;

TEST(KalmanFilter, RandomWalkConvergesToSteadyStateRiccati) {
  // x_k = x_{k−1} + w, var q; z = x + v, var r. Steady state of the Riccati recursion:
  // P⁻ = (q + sqrt(q² + 4qr))/2, P⁺ = P⁻·r/(P⁻ + r).
  const double q = 0.5;
  const double r = 2.0;
  const double p_pred = 0.5 * (q + std::sqrt(q * q + 4.0 * q * r));
  const double p_filt = p_pred * r / (p_pred + r);
  KalmanFilter<1> kf({Vector<1>::Zero(), Matrix<1, 1>::Constant(100.0)});
  KalmanFilter<Eigen::Dynamic> dyn({VectorXd::Zero(1), MatrixXd::Constant(1, 1, 100.0)});
  std::mt19937_64 rng(7);
  std::normal_distribution<double> nd;
  for (int k = 0; k < 100; ++k) {
    if (k > 0) {
      kf.predict(Matrix<1, 1>::Ones(), Matrix<1, 1>::Constant(q));
      dyn.predict(MatrixXd::Ones(1, 1), MatrixXd::Constant(1, 1, q));
    }
    const double z = 3.0 + nd(rng);
    kf.update(Vector<1>::Constant(z), Matrix<1, 1>::Ones(), Matrix<1, 1>::Constant(r));
    dyn.update(VectorXd::Constant(1, z), MatrixXd::Ones(1, 1), MatrixXd::Constant(1, 1, r));
  }
  EXPECT_NEAR(kf.predicted().P(0, 0) / p_pred, 1.0, 1e-13);
  EXPECT_NEAR(kf.estimate().P(0, 0) / p_filt, 1.0, 1e-13);
  EXPECT_NEAR(dyn.estimate().P(0, 0) / p_filt, 1.0, 1e-13);
  EXPECT_EQ(kf.epoch(), 99);
}

// A filter of the deflection model advanced a few epochs, so P is full and correlated.
KalmanFilter<kDov> advanced_filter(int epochs, std::mt19937_64& rng) {
  const DovParameters p;
  const auto d = meridian::filter::discretise(dov_model(p), 1.0);
  KalmanFilter<kDov> kf(dov_initial(p));
  const auto H = dov_observation_matrix();
  const auto R = dov_observation_covariance(p);
  for (int k = 1; k <= epochs; ++k) {
    kf.predict(d);
    kf.update(draw<2>(R, rng), H, R);
  }
  kf.predict(d);
  return kf;
}

TEST(KalmanFilter, JosephUpdateMatchesTextbookFormula) {
  std::mt19937_64 rng(11);
  KalmanFilter<kDov> kf = advanced_filter(20, rng);
  const DovParameters p;
  const auto H = dov_observation_matrix();
  Matrix<2, 2> R = dov_observation_covariance(p);
  R(0, 1) = R(1, 0) = 0.3 * R(0, 0);  // correlated
  const Vector<2> z = draw<2>(R, rng);
  const Estimate<kDov> prior = kf.estimate();
  const Innovation<2> in = kf.update(z, H, R);

  // Textbook, dynamic sizes, explicit inverse: K = P·Hᵀ·S⁻¹, Joseph with I − K·H formed.
  const MatrixXd P = prior.P;
  const MatrixXd Hd = H;
  const MatrixXd S = Hd * P * Hd.transpose() + MatrixXd(R);
  const MatrixXd K = P * Hd.transpose() * S.inverse();
  const VectorXd nu = VectorXd(z) - Hd * VectorXd(prior.x);
  const MatrixXd A = MatrixXd::Identity(kDov, kDov) - K * Hd;
  const MatrixXd P_ref = A * P * A.transpose() + K * MatrixXd(R) * K.transpose();
  const VectorXd x_ref = VectorXd(prior.x) + K * nu;
  EXPECT_LT(state_difference(VectorXd(kf.estimate().x), x_ref, P_ref), 1e-10);
  EXPECT_LT(covariance_difference(MatrixXd(kf.estimate().P), P_ref), 1e-10);
  EXPECT_NEAR(in.nis, nu.dot(S.inverse() * nu), 1e-12 * in.nis);
  EXPECT_TRUE(in.accepted);
  EXPECT_EQ(kf.estimate().P, kf.estimate().P.transpose());  // exactly symmetric
}

TEST(KalmanFilter, SequentialScalarUpdatesEqualTheJointUpdate) {
  std::mt19937_64 rng(12);
  KalmanFilter<kDov> joint = advanced_filter(15, rng);
  KalmanFilter<kDov> seq = joint;
  const DovParameters p;
  const auto H = dov_observation_matrix();
  const auto R = dov_observation_covariance(p);
  const Vector<2> z = draw<2>(R, rng);
  joint.update(z, H, R);
  const auto out = seq.update_sequential(z, H, Vector<2>(R.diagonal()));
  EXPECT_EQ(out.rejected(), 0);
  EXPECT_LT(state_difference(seq.estimate().x, joint.estimate().x, joint.estimate().P), 1e-10);
  EXPECT_LT(covariance_difference(seq.estimate().P, joint.estimate().P), 1e-10);
}

TEST(KalmanFilter, FixedAndDynamicSizesAgree) {
  const DovParameters p;
  const auto d = meridian::filter::discretise(dov_model(p), 1.0);
  const auto H = dov_observation_matrix();
  const auto R = dov_observation_covariance(p);
  const auto init = dov_initial(p);
  KalmanFilter<kDov> fixed(init);
  KalmanFilter<Eigen::Dynamic> dyn({init.x, init.P});
  std::mt19937_64 rng(5);
  for (int k = 0; k < 200; ++k) {
    if (k > 0) {
      fixed.predict(d);
      dyn.predict(MatrixXd(d.phi), MatrixXd(d.q));
    }
    const Vector<2> z = draw<2>(R, rng);
    fixed.update(z, H, R);
    dyn.update(VectorXd(z), MatrixXd(H), MatrixXd(R));
  }
  EXPECT_LT(state_difference(VectorXd(fixed.estimate().x), dyn.estimate().x, dyn.estimate().P),
            1e-12);
  EXPECT_LT(covariance_difference(MatrixXd(fixed.estimate().P), dyn.estimate().P), 1e-12);
}

TEST(KalmanFilter, ExtendedFormsWithLinearFunctionsEqualTheLinearFilter) {
  std::mt19937_64 rng(13);
  KalmanFilter<kDov> a = advanced_filter(5, rng);
  KalmanFilter<kDov> b = a;
  const DovParameters p;
  const auto d = meridian::filter::discretise(dov_model(p), 1.0);
  const auto H = dov_observation_matrix();
  const auto R = dov_observation_covariance(p);
  const Vector<2> z = draw<2>(R, rng);
  a.update(z, H, R);
  b.update_extended(Vector<2>(z - H * b.estimate().x), H, R);
  a.predict(d);
  b.predict_extended(d.phi * b.estimate().x, d.phi, d.q);
  EXPECT_EQ(a.estimate().x, b.estimate().x);
  EXPECT_EQ(a.estimate().P, b.estimate().P);
}

// The 2-D constant-velocity model with position fixes every second, an outlier planted.
struct GateRun {
  std::vector<Innovation<2>> innovations;
  Estimate<CvState::size> final_estimate;
};

GateRun run_cv(int outlier_epoch, bool skip_outlier, double alpha) {
  const auto d = meridian::filter::discretise(cv_model(0.01), 1.0);
  const auto H = cv_position_matrix();
  const Matrix<2, 2> R = 25.0 * Matrix<2, 2>::Identity();
  Estimate<CvState::size> init{Vector<CvState::size>::Zero(),
                               Vector<CvState::size>(100.0, 100.0, 1.0, 1.0).asDiagonal()};
  KalmanFilter<CvState::size> kf(init, alpha > 0.0 ? InnovationGate(alpha) : InnovationGate());
  std::mt19937_64 rng(3);
  Vector<CvState::size> truth(10.0, -5.0, 2.0, 1.0);
  GateRun run;
  for (int k = 0; k < 60; ++k) {
    if (k > 0) {
      truth = d.phi * truth + draw<CvState::size>(d.q, rng);
      kf.predict(d);
    }
    Vector<2> z = H * truth + draw<2>(R, rng);
    if (k == outlier_epoch) {
      z(0) += 100.0;  // 20 σ
      if (skip_outlier) continue;
    }
    run.innovations.push_back(kf.update(z, H, R));
  }
  run.final_estimate = kf.estimate();
  return run;
}

TEST(KalmanFilter, GateRejectsAndReportsAPlantedOutlier) {
  // α = 1e-6: a correct observation is rejected with probability 1e-6 per epoch (6e-5 over the
  // line), so the one rejection expected is the planted 20 σ outlier (NIS ≈ 400 ≫ 27.6). At
  // α = 1e-3 this line has a genuine 3σ-class draw at epoch 22 (NIS 19.3) that is rejected.
  constexpr double kAlpha = 1e-6;
  const GateRun gated = run_cv(30, false, kAlpha);
  const Innovation<2>& bad = gated.innovations[30];
  EXPECT_FALSE(bad.accepted);
  EXPECT_EQ(bad.epoch, 30);
  // χ²_{1−α}(2) = −2·ln(α) (χ² with 2 degrees of freedom is exponential).
  EXPECT_NEAR(bad.gate_limit, -2.0 * std::log(kAlpha), 1e-9);
  EXPECT_GT(bad.nis, bad.gate_limit);
  int rejected = 0;
  for (const auto& in : gated.innovations) rejected += in.accepted ? 0 : 1;
  EXPECT_EQ(rejected, 1);
  // Rejected = never seen: the same final state as a filter that skipped the observation.
  const GateRun skipped = run_cv(30, true, kAlpha);
  EXPECT_EQ(gated.final_estimate.x, skipped.final_estimate.x);
  EXPECT_EQ(gated.final_estimate.P, skipped.final_estimate.P);
  // Without a gate the outlier is absorbed.
  const GateRun open = run_cv(30, false, 0.0);
  EXPECT_TRUE(open.innovations[30].accepted);
  EXPECT_TRUE(std::isinf(open.innovations[30].gate_limit));
  EXPECT_NE(open.final_estimate.x, skipped.final_estimate.x);
}

TEST(KalmanFilter, SequentialGateRejectsOnlyTheBadScalar) {
  const auto H = cv_position_matrix();
  Estimate<CvState::size> init{Vector<CvState::size>::Zero(),
                               Matrix<CvState::size, CvState::size>::Identity()};
  KalmanFilter<CvState::size> kf(init, InnovationGate(0.01));
  const auto out = kf.update_sequential(Vector<2>(0.5, 50.0), H, Vector<2>(1.0, 1.0));
  EXPECT_TRUE(out.accepted(0));
  EXPECT_FALSE(out.accepted(1));
  EXPECT_EQ(out.rejected(), 1);
  EXPECT_NEAR(out.nis(1), 50.0 * 50.0 / 2.0, 1e-9);
  EXPECT_EQ(kf.estimate().x(CvState::y), 0.0);  // untouched by the rejected scalar
  EXPECT_GT(kf.estimate().x(CvState::x), 0.0);
}

TEST(KalmanFilter, ErrorsNameTheEpoch) {
  const auto d = meridian::filter::discretise(cv_model(0.01), 1.0);
  const auto H = cv_position_matrix();
  const Matrix<2, 2> R = Matrix<2, 2>::Identity();
  Estimate<CvState::size> init{Vector<CvState::size>::Zero(),
                               Matrix<CvState::size, CvState::size>::Identity()};
  KalmanFilter<CvState::size> kf(init);
  for (int k = 1; k <= 5; ++k) kf.predict(d);
  const Estimate<CvState::size> before = kf.estimate();

  auto c = catch_error<InputError>([&] { kf.update(Vector<2>(1.0, kNaN), H, R); });
  EXPECT_TRUE(c.thrown);
  EXPECT_EQ(c.field, "epoch 5");
  EXPECT_THAT(c.what, HasSubstr("observation z has a non-finite value"));

  c = catch_error<NumericalError>([&] {
    kf.update(Vector<2>(1.0, 1.0), Matrix<2, CvState::size>::Zero(), Matrix<2, 2>::Zero());
  });
  EXPECT_TRUE(c.thrown);
  EXPECT_EQ(c.field, "epoch 5");
  EXPECT_THAT(c.what, HasSubstr("innovation covariance"));

  Matrix<CvState::size, CvState::size> q = d.q;
  q(0, 1) += 1.0;
  c = catch_error<InputError>([&] { kf.predict(d.phi, q); });
  EXPECT_EQ(c.field, "epoch 6");
  EXPECT_THAT(c.what, HasSubstr("not symmetric"));
  q = d.q;  // the constant Q_d passed five times (cached as checked): a changed one is checked
  q(2, 2) = kNaN;
  c = catch_error<InputError>([&] { kf.predict(d.phi, q); });
  EXPECT_EQ(c.field, "epoch 6");
  EXPECT_THAT(c.what, HasSubstr("process noise Q_d has a non-finite value"));

  c = catch_error<NumericalError>(
      [&] { kf.predict(1e200 * Matrix<CvState::size, CvState::size>::Identity(), d.q); });
  EXPECT_TRUE(c.thrown);
  EXPECT_EQ(c.field, "epoch 6");

  // Strong guarantee: the failed calls left the filter as it was.
  EXPECT_EQ(kf.epoch(), 5);
  EXPECT_EQ(kf.estimate().x, before.x);
  EXPECT_EQ(kf.estimate().P, before.P);

  Estimate<CvState::size> bad = init;
  bad.P(2, 2) = -1.0;
  c = catch_error<InputError>([&] { KalmanFilter<CvState::size> f(bad); });
  EXPECT_EQ(c.field, "epoch 0");
  bad = init;
  bad.P(0, 1) = bad.P(1, 0) = 2.0;  // symmetric, not positive definite
  c = catch_error<InputError>([&] { KalmanFilter<CvState::size> f(bad); });
  EXPECT_THAT(c.what, HasSubstr("not positive definite"));
  EXPECT_THROW(InnovationGate(0.0), InputError);
  EXPECT_THROW(InnovationGate(1.0), InputError);
}

TEST(KalmanFilter, DynamicSizeChecksShapes) {
  KalmanFilter<Eigen::Dynamic> kf({VectorXd::Zero(3), MatrixXd::Identity(3, 3)});
  const auto c = catch_error<InputError>(
      [&] { kf.update(VectorXd::Zero(2), MatrixXd::Zero(2, 4), MatrixXd::Identity(2, 2)); });
  EXPECT_TRUE(c.thrown);
  EXPECT_THAT(c.what, HasSubstr("observation matrix H is 2×4, expected 2×3"));
  EXPECT_THROW(kf.predict(MatrixXd::Identity(2, 2), MatrixXd::Zero(2, 2)), InputError);
}

}  // namespace
