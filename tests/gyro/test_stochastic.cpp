// Stochastic models of reversal-point series (gyro-stochastic spec): the Markov factors
// against the unrolled recursion, ρ = 0 against ordinary least squares and the spec's closed
// forms, the computational routes against each other, the signal prediction against the
// dense textbook formula, bad input.
#include <cmath>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/gyro/markov_covariance.hpp"
#include "meridian/gyro/stochastic.hpp"

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using meridian::InputError;
using meridian::NumericalError;
using namespace meridian::gyro;
using ::testing::HasSubstr;

constexpr double kDeg = M_PI / 180.0;
constexpr double kArcsec = kDeg / 3600.0;

// ε by running the recursion ε_i = Δ_i + ρ_1·ε_{i−1} + ρ_2·ε_{i−2} with ε_0 = X_1,
// ε_{−1} = X_2 (Markov-1: ρ_2 = 0, X_0 = X_1).
VectorXd recursion(const VectorXd& delta, double x1, double x2, double rho1, double rho2) {
  const Index n = delta.size();
  VectorXd e(n);
  double em1 = x1, em2 = x2;  // ε_{i−1}, ε_{i−2}
  for (Index i = 0; i < n; ++i) {
    e(i) = delta(i) + rho1 * em1 + rho2 * em2;
    em2 = em1;
    em1 = e(i);
  }
  return e;
}

TEST(MarkovCovariance, Markov1FactorsAreTheUnrolledRecursion) {
  for (int n = 1; n <= 6; ++n)
    for (double rho : {-0.7, 0.0, 0.3, 0.9}) {
      const MarkovFactors f = markov1_factors(n, rho);
      ASSERT_EQ(f.C.rows(), n);
      ASSERT_EQ(f.B.cols(), 1);
      for (int j = 0; j < n; ++j) {
        const VectorXd col = recursion(VectorXd::Unit(n, j), 0.0, 0.0, rho, 0.0);
        EXPECT_LT((f.C.col(j) - col).cwiseAbs().maxCoeff(), 1e-15) << n << " " << rho;
      }
      const VectorXd b = recursion(VectorXd::Zero(n), 1.0, 0.0, rho, 0.0);
      EXPECT_LT((f.B.col(0) - b).cwiseAbs().maxCoeff(), 1e-15);
      // Closed form of the spec: C_ij = ρ^{i−j}, B_i = ρ^i.
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(f.B(i, 0), std::pow(rho, i + 1), 1e-15);
        for (int j = 0; j <= i; ++j) EXPECT_NEAR(f.C(i, j), std::pow(rho, i - j), 1e-15);
        for (int j = i + 1; j < n; ++j) EXPECT_EQ(f.C(i, j), 0.0);
      }
      const MatrixXd D = f.covariance(4.0, 25.0);
      EXPECT_LT((D - (4.0 * f.C * f.C.transpose() + 25.0 * f.B * f.B.transpose())).norm(), 1e-12);
    }
}

TEST(MarkovCovariance, Markov2FactorsAreTheUnrolledRecursion) {
  for (int n = 1; n <= 6; ++n)
    for (auto [r1, r2] : {std::pair{0.5, 0.3}, std::pair{-0.4, 0.2}, std::pair{1.2, -0.5},
                          std::pair{0.0, 0.0}, std::pair{-0.9, -0.05}}) {
      const MarkovFactors f = markov2_factors(n, r1, r2);
      ASSERT_EQ(f.B.cols(), 2);
      for (int j = 0; j < n; ++j) {
        const VectorXd col = recursion(VectorXd::Unit(n, j), 0.0, 0.0, r1, r2);
        EXPECT_LT((f.C.col(j) - col).cwiseAbs().maxCoeff(), 1e-14) << n << " " << r1 << " " << r2;
      }
      EXPECT_LT((f.B.col(0) - recursion(VectorXd::Zero(n), 1.0, 0.0, r1, r2)).cwiseAbs().maxCoeff(),
                1e-14);
      EXPECT_LT((f.B.col(1) - recursion(VectorXd::Zero(n), 0.0, 1.0, r1, r2)).cwiseAbs().maxCoeff(),
                1e-14);
    }
  // The spec's check of ε_3.
  const double r1 = 0.6, r2 = -0.25;
  const MarkovFactors f = markov2_factors(3, r1, r2);
  EXPECT_NEAR(f.C(2, 1), r1, 1e-15);
  EXPECT_NEAR(f.C(2, 0), r1 * r1 + r2, 1e-15);
  EXPECT_NEAR(f.B(2, 0), r1 * r1 * r1 + 2.0 * r1 * r2, 1e-15);
  EXPECT_NEAR(f.B(2, 1), r1 * r1 * r2 + r2 * r2, 1e-15);
  // With ρ_2 = 0 Markov-2 is Markov-1.
  const MarkovFactors a = markov2_factors(6, 0.45, 0.0), b = markov1_factors(6, 0.45);
  EXPECT_LT((a.C - b.C).norm(), 1e-15);
  EXPECT_LT((a.B.col(0) - b.B.col(0)).norm(), 1e-15);
  EXPECT_EQ(a.B.col(1).norm(), 0.0);
}

TEST(MarkovCovariance, StationarityIsChecked) {
  EXPECT_TRUE(ar2_stationary(0.5, 0.3));
  EXPECT_TRUE(ar2_stationary(1.5, -0.6));
  EXPECT_FALSE(ar2_stationary(0.5, 0.5));   // ρ1 + ρ2 = 1
  EXPECT_FALSE(ar2_stationary(-0.5, 0.6));  // ρ2 − ρ1 > 1
  EXPECT_FALSE(ar2_stationary(0.0, -1.0));  // |ρ2| = 1
  EXPECT_FALSE(ar2_stationary(std::nan(""), 0.0));
  auto msg = [](auto f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(msg([] { markov2_factors(5, 0.7, 0.4); }), HasSubstr("rho1 + rho2 < 1 is violated"));
  EXPECT_THAT(msg([] { markov2_factors(5, -0.7, 0.4); }), HasSubstr("rho2 - rho1 < 1 is violated"));
  EXPECT_THAT(msg([] { markov1_factors(5, 1.0); }), HasSubstr("outside the stationary region"));
  EXPECT_THROW(markov1_factors(0, 0.5), InputError);
  EXPECT_THROW(markov1_factors(4, 0.5).covariance(-1.0, 1.0), InputError);
}

std::vector<double> simulated_series(int n, double rho, double s1, double s2, std::uint64_t seed,
                                     Eigen::Vector3d y = {754.0, 4800.0, 3.0}) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  VectorXd delta(n);
  for (int i = 0; i < n; ++i) delta(i) = s1 * N(rng);
  const VectorXd e = recursion(delta, s2 * N(rng), 0.0, rho, 0.0);
  const VectorXd l = reversal_design(n) * y + e;
  return {l.data(), l.data() + n};
}

TEST(Stochastic, DesignIsR2) {
  const MatrixXd G = reversal_design(3);
  // r_i = M + (−1)^i·A′ + (−1)^{i+1}·(2i − 1)·c
  EXPECT_EQ(G.row(0), Eigen::RowVector3d(1.0, -1.0, 1.0));
  EXPECT_EQ(G.row(1), Eigen::RowVector3d(1.0, 1.0, -3.0));
  EXPECT_EQ(G.row(2), Eigen::RowVector3d(1.0, -1.0, 5.0));
}

TEST(Stochastic, RhoZeroIsOrdinaryLeastSquares) {
  // Markov-1 with ρ = 0: C = I, B = 0, D = σ1²·I; the GLS is OLS, and for n = 5 the spec's
  // closed form M = (2r1 + 3r2 + 2r3 + 3r4 + 2r5)/12 with q_MM = 0.2083.
  const std::vector<double> r{100.0, 910.0, 130.0, 880.0, 155.0};
  const MarkovFactors f = markov1_factors(5, 0.0);
  EXPECT_EQ(f.B.norm(), 0.0);
  const double s2 = 9.0;
  for (GlsRoute route : {GlsRoute::Whitening, GlsRoute::NormalEquations}) {
    const GlsFit g = reversal_gls(r, f.covariance(s2, 123.0), route);
    const double m = (2 * r[0] + 3 * r[1] + 2 * r[2] + 3 * r[3] + 2 * r[4]) / 12.0;
    EXPECT_NEAR(g.y(0), m, 1e-10);
    EXPECT_NEAR(g.covariance(0, 0) / s2, 0.2083, 5e-5);
    // Dense OLS reference.
    const MatrixXd G = reversal_design(5);
    const VectorXd l = Eigen::Map<const VectorXd>(r.data(), 5);
    const VectorXd y = (G.transpose() * G).inverse() * G.transpose() * l;
    EXPECT_LT((g.y - y).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(Stochastic, RoutesAgree) {
  // Whitening against normal equations: every model to 1e-9. Helmert against LS-VCE: the
  // models at fixed ρ to 1e-9; the ML models to the optimiser's tolerance (their ρ comes from
  // a search whose path depends on rounding).
  const auto r = simulated_series(20, 0.6, 2.0, 5.0, 11);
  StochasticInput a, b, c;
  a.kind = b.kind = c.kind = SeriesKind::Scale;  // fitted as given
  a.readings = b.readings = c.readings = r;
  b.options.route = GlsRoute::NormalEquations;
  c.options.vce_method = meridian::adjust::VceMethod::Helmert;
  const auto ra = analyse_stochastic(a);
  auto rel = [](double x, double y) { return std::fabs(x - y) / std::max(std::fabs(x), 1e-300); };
  for (const auto* other : {&b, &c}) {
    const auto rb = analyse_stochastic(*other);
    ASSERT_EQ(ra.models.size(), rb.models.size());
    for (std::size_t i = 0; i < ra.models.size(); ++i) {
      const auto& x = ra.models[i];
      const auto& y = rb.models[i];
      ASSERT_EQ(x.model, y.model);
      SCOPED_TRACE(to_string(x.model));
      const bool ml =
          x.model == StochasticModel::Markov1Ml || x.model == StochasticModel::Markov2Ml;
      const double tol = (ml && other == &c) ? 1e-4 : 1e-9;
      EXPECT_LT(rel(x.north.value, y.north.value), tol);
      EXPECT_LT(rel(x.north.sigma, y.north.sigma), tol);
      EXPECT_LT(rel(x.amplitude.value, y.amplitude.value), tol);
      EXPECT_LT(rel(x.amplitude.sigma, y.amplitude.sigma), tol);
      EXPECT_LT(rel(x.log_likelihood, y.log_likelihood), tol);
      for (std::size_t k = 0; k < x.rho.size(); ++k)
        EXPECT_LT(rel(x.rho[k], y.rho[k]), ml ? 1e-4 : 1e-9);
      if (std::isfinite(x.sigma1.value)) {
        EXPECT_LT(rel(x.sigma1.value, y.sigma1.value), tol);
      }
    }
  }
  // GLS routes on a Markov-2 covariance.
  const MatrixXd D = markov2_factors(20, 0.5, 0.3).covariance(4.0, 25.0);
  const GlsFit w = reversal_gls(r, D, GlsRoute::Whitening);
  const GlsFit ne = reversal_gls(r, D, GlsRoute::NormalEquations);
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(rel(w.y(k), ne.y(k)), 1e-9);
    EXPECT_LT(rel(w.covariance(k, k), ne.covariance(k, k)), 1e-9);
  }
}

TEST(Stochastic, SignalPredictionIsTheDenseFormula) {
  const auto r = simulated_series(16, 0.7, 2.0, 8.0, 5);
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given
  in.readings = r;
  in.options.covariance_functions = false;
  const auto res = analyse_stochastic(in);
  const ModelFit& f = res.fit(StochasticModel::Markov1Grid);
  const MarkovFactors mf = markov1_factors(16, f.rho[0]);
  const double s1 = f.sigma1.value * f.sigma1.value, s2 = f.sigma2.value * f.sigma2.value;
  const MatrixXd D = mf.covariance(s1, s2);
  const MatrixXd P = D.inverse();  // explicit inverse: the independent reference
  const MatrixXd G = reversal_design(16);
  const VectorXd l = Eigen::Map<const VectorXd>(r.data(), 16);
  const MatrixXd N = G.transpose() * P * G;
  const VectorXd y = N.inverse() * G.transpose() * P * l;
  EXPECT_NEAR(f.north.value, y(0), 1e-9 * std::fabs(y(0)));
  EXPECT_NEAR(f.north.sigma, std::sqrt(N.inverse()(0, 0)), 1e-9);
  const VectorXd xhat = s2 * mf.B.transpose() * P * (l - G * y);
  const VectorXd dy = N.inverse() * G.transpose() * P * mf.B * xhat;
  EXPECT_NEAR(f.signal_influence(0), dy(0), 1e-9 * std::max(1.0, std::fabs(dy(0))));
  EXPECT_NEAR(f.signal_influence(1), dy(1), 1e-9 * std::max(1.0, std::fabs(dy(1))));
}

TEST(Stochastic, ComparisonTableIsComplete) {
  const auto r = simulated_series(20, 0.6, 2.0, 5.0, 3);
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given
  in.readings = r;
  const auto res = analyse_stochastic(in);
  int recommended = 0;
  for (const auto& f : res.models) {
    SCOPED_TRACE(to_string(f.model));
    recommended += f.recommended ? 1 : 0;
    EXPECT_TRUE(std::isfinite(f.north.value) && std::isfinite(f.north.sigma));
    EXPECT_TRUE(std::isfinite(f.amplitude.value) && std::isfinite(f.amplitude.sigma));
    EXPECT_TRUE(std::isfinite(f.log_likelihood) && std::isfinite(f.aic) && std::isfinite(f.bic));
    EXPECT_NEAR(f.aic, -2.0 * f.log_likelihood + 2.0 * f.covariance_parameters, 1e-9);
    EXPECT_NEAR(f.bic, -2.0 * f.log_likelihood + f.covariance_parameters * std::log(17.0), 1e-9);
  }
  EXPECT_EQ(recommended, 1);
  EXPECT_TRUE(res.models[static_cast<std::size_t>(res.recommended)].recommended);
  // ML maximises what the grid samples.
  EXPECT_GE(res.fit(StochasticModel::Markov1Ml).log_likelihood,
            res.fit(StochasticModel::Markov1Grid).log_likelihood - 1e-9);
  EXPECT_GE(res.fit(StochasticModel::Markov2Ml).log_likelihood,
            res.fit(StochasticModel::Markov2Grid).log_likelihood - 1e-9);
  // Markov-1 is nested in Markov-2 (ρ2 = 0).
  EXPECT_GE(res.fit(StochasticModel::Markov2Ml).log_likelihood,
            res.fit(StochasticModel::Markov1Ml).log_likelihood - 1e-6);
  ASSERT_EQ(res.tests.size(), 2u);
  EXPECT_EQ(res.markov2_surface.rows(), 19);
  EXPECT_EQ(res.residual_autocorrelation.size(), 20u);
  EXPECT_DOUBLE_EQ(res.residual_autocorrelation[0], 1.0);
}

TEST(Stochastic, BadInput) {
  StochasticInput in;
  in.kind = SeriesKind::Scale;
  in.readings = {1.0, 9.0, 2.0, 8.0, 3.0};
  EXPECT_THAT(
      [&] {
        try {
          analyse_stochastic(in);
        } catch (const InputError& e) {
          return std::string(e.what());
        }
        return std::string();
      }(),
      HasSubstr("need at least 6 readings"));
  in.readings = {1.0, 9.0, 2.0, 8.0, 3.0, std::nan(""), 4.0};
  EXPECT_THROW(analyse_stochastic(in), InputError);
  // An exact fit of (R2): nothing to model.
  const VectorXd exact = reversal_design(8) * Eigen::Vector3d(10.0, 5.0, 0.1);
  in.readings.assign(exact.data(), exact.data() + 8);
  EXPECT_THROW(analyse_stochastic(in), InputError);
  // Not positive definite.
  const std::vector<double> r = simulated_series(6, 0.5, 1.0, 1.0, 1);
  EXPECT_THROW(reversal_gls(r, MatrixXd::Ones(6, 6)), NumericalError);
  EXPECT_THROW(reversal_gls(r, MatrixXd::Ones(6, 6), GlsRoute::NormalEquations), NumericalError);
  EXPECT_THROW(reversal_gls(r, MatrixXd::Identity(5, 5)), InputError);
  // Six readings: Markov-2 is left out with a note, the rest is computed.
  in.readings = r;
  const auto res = analyse_stochastic(in);
  EXPECT_THROW(res.fit(StochasticModel::Markov2Ml), InputError);
  EXPECT_THAT(res.notes, ::testing::Contains(HasSubstr("Markov-2 models need at least 8")));
}

// The tracking readings of examples/tracking.yaml in arcsec from 358° (7 readings, booked σ 8″).
std::vector<double> example_tracking() {
  const auto as = [](int d, int m, double sec) { return (d - 358) * 3600.0 + m * 60.0 + sec; };
  return {as(358, 52, 32.7236), as(361, 32, 16.9374), as(358, 52, 48.6998),
          as(361, 32, 3.9849),  as(358, 53, 5.6854),  as(361, 31, 43.6747),
          as(358, 53, 36.5974)};
}

// The same as booked: circle readings in radians, in [0, 2π) (they cross 0°/360°).
StochasticInput example_tracking_input() {
  StochasticInput in;
  in.kind = SeriesKind::Circle;
  for (double x : example_tracking())
    in.readings.push_back(std::fmod(358.0 * kDeg + x * kArcsec, 2.0 * M_PI));
  return in;
}

TEST(StochasticUnits, CircleReadingsAreFittedInArcsecFromTheirDegree) {
  // 358°52′32.7″, 1°32′16.9″, …: unwrapped across 360° and taken from 358°; the booked σ in
  // arc-seconds; the centre of white noise is the Schuler-type LS centre of those arc-seconds.
  StochasticInput in = example_tracking_input();
  in.booked_sigma = 8.0 * kArcsec;
  const StochasticResult res = analyse_stochastic(in);
  EXPECT_EQ(res.kind, SeriesKind::Circle);
  EXPECT_NEAR(res.reference_rad, 358.0 * kDeg, 1e-15);
  const std::vector<double> as = example_tracking();
  ASSERT_EQ(res.fitted_readings.size(), as.size());
  for (std::size_t i = 0; i < as.size(); ++i) EXPECT_NEAR(res.fitted_readings[i], as[i], 1e-8) << i;
  EXPECT_NEAR(res.booked_sigma, 8.0, 1e-12);
  EXPECT_EQ(fitted_unit(res.kind), "arcsec");
  // Scale readings are fitted as they are, in div.
  StochasticInput div;
  div.kind = SeriesKind::Scale;
  div.readings = as;
  div.booked_sigma = 8.0;
  const StochasticResult rd = analyse_stochastic(div);
  EXPECT_EQ(rd.reference_rad, 0.0);
  EXPECT_EQ(rd.fitted_readings, as);
  EXPECT_EQ(fitted_unit(rd.kind), "div");
  // The same fit, to rounding of the conversion.
  EXPECT_NEAR(res.fit(StochasticModel::WhiteNoise).north.value, rd.fit(StochasticModel::WhiteNoise).north.value,
              1e-7);
  EXPECT_NEAR(res.fit(StochasticModel::WhiteNoise).sigma1.value, rd.fit(StochasticModel::WhiteNoise).sigma1.value,
              1e-7);
}

bool is_c_type(StochasticModel m) {
  return m == StochasticModel::Exponential || m == StochasticModel::Gaussian ||
         m == StochasticModel::DampedCosine;
}

void expect_recommendation_and_tests_avoid_degenerate(const StochasticResult& res) {
  int recommended = 0;
  for (const auto& f : res.models) {
    SCOPED_TRACE(to_string(f.model));
    EXPECT_EQ(f.degenerate, !f.degenerate_reason.empty());
    if (f.recommended) {
      ++recommended;
      EXPECT_FALSE(f.degenerate) << f.degenerate_reason;
    }
  }
  EXPECT_EQ(recommended, 1);
  for (const auto& t : res.tests) {
    EXPECT_FALSE(res.fit(t.null_model).degenerate);
    EXPECT_FALSE(res.fit(t.alternative).degenerate);
  }
}

TEST(StochasticDegenerate, ZeroPositionRunFittedExactlyBySignal) {
  // A zero-position run booked to 0.1 div (user trial, finding 2). Readings 2–7 alone fit (R2)
  // exactly (checked here by a dense OLS), so a Markov model whose signal term absorbs reading 1
  // drives σ1 → 0 with an unbounded restricted likelihood.
  const std::vector<double> r{4.2, -3.7, 3.9, -3.5, 3.7, -3.3, 3.5};
  {
    const MatrixXd G = reversal_design(7).bottomRows(6);
    const VectorXd l = Eigen::Map<const VectorXd>(r.data() + 1, 6);
    const VectorXd y = (G.transpose() * G).inverse() * G.transpose() * l;
    // G's rows 2…7 of the 7-reading design, l the readings 2…7.
    ASSERT_LT((G * y - l).norm(), 1e-9);
  }
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given
  in.readings = r;
  const auto res = analyse_stochastic(in);
  const double sw = res.fit(StochasticModel::WhiteNoise).sigma1.value;
  int flagged = 0;
  for (const auto& f : res.models) {
    if (f.rho.empty()) continue;
    // σ1 far below the white-noise σ1 must be flagged.
    if (f.sigma1.value < kDegenerateSigma1Ratio * sw) {
      EXPECT_TRUE(f.degenerate) << to_string(f.model);
      EXPECT_THAT(f.degenerate_reason, HasSubstr("sigma1 -> 0"));
      ++flagged;
    }
  }
  EXPECT_GE(flagged, 1);  // the trial's markov1-ml
  expect_recommendation_and_tests_avoid_degenerate(res);
  EXPECT_THAT(res.notes, ::testing::Contains(HasSubstr("is degenerate")));
  // With the booked σ of the book (0.05 div; the readings are booked to 0.1 div, whose rounding
  // alone is 0.1/√12 = 0.029 div): no Markov model may claim σ1 < 0.2 × 0.05 and be recommended.
  in.booked_sigma = 0.05;
  const auto booked = analyse_stochastic(in);
  for (const auto& f : booked.models)
    if (!f.rho.empty() && f.sigma1.value < 0.01) {
      EXPECT_TRUE(f.degenerate) << to_string(f.model);
    }
  expect_recommendation_and_tests_avoid_degenerate(booked);
  const auto& rec = booked.models[static_cast<std::size_t>(booked.recommended)];
  EXPECT_GT(rec.sigma1.value, 0.01) << to_string(rec.model);
}

TEST(StochasticDegenerate, StationarityEdgeAndAbsurdAmplitude) {
  // examples/tracking.yaml (user trial, finding 8): Markov-1 ML runs to ρ ≈ −0.98 with an
  // amplitude thousands of arcsec from every other model.
  const StochasticInput in = example_tracking_input();
  const auto res = analyse_stochastic(in);
  const ModelFit& m1 = res.fit(StochasticModel::Markov1Ml);
  const ModelFit& w = res.fit(StochasticModel::WhiteNoise);
  if (std::fabs(m1.rho[0]) >= kStationarityEdge ||
      std::fabs(m1.amplitude.value - w.amplitude.value) > kDegenerateShift * w.sigma1.value) {
    EXPECT_TRUE(m1.degenerate);
  }
  ASSERT_TRUE(m1.degenerate) << "rho " << m1.rho[0] << " A " << m1.amplitude.value;
  expect_recommendation_and_tests_avoid_degenerate(res);
  // No model borrows the degenerate signal: the influence on A′ of white noise is either not
  // stated or that of a non-degenerate Markov model's signal, which moves A′ by far less than
  // the trial's −2625″.
  for (const auto& f : res.models) {
    if (f.rho.empty() && std::isfinite(f.signal_influence(1))) {
      EXPECT_LT(std::fabs(f.signal_influence(1)), kDegenerateShift * w.sigma1.value)
          << to_string(f.model);
    }
  }
}

TEST(StochasticDegenerate, LargestRootModulus) {
  // Markov-2 (ρ1, ρ2) = (−0.116, 0.883) (user trial, finding 9): z² + 0.116 z − 0.883 has the
  // root −1.0002, modulus ≥ the edge; (0.5, 0.3) has roots 0.852, −0.352 (inside).
  const std::vector<double> r = simulated_series(20, 0.5, 2.0, 2.0, 17);
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given
  in.readings = r;
  const auto res = analyse_stochastic(in);
  for (const auto& f : res.models) {
    if (f.rho.size() != 2) continue;
    const double r1 = f.rho[0], r2 = f.rho[1];
    // Independent: the companion matrix's eigenvalues.
    Eigen::Matrix2d comp;
    comp << r1, r2, 1.0, 0.0;
    const double root = comp.eigenvalues().cwiseAbs().maxCoeff();
    if (root >= kStationarityEdge) {
      EXPECT_TRUE(f.degenerate);
      EXPECT_THAT(f.degenerate_reason, HasSubstr("edge of the stationary region"));
    }
  }
}

TEST(StochasticCovarianceFunctions, AmplitudeIsRemlAtTheShape) {
  // a = v_Rᵀ R⁻¹ v_R/(n − 3) (dense inverse as the reference), the REML likelihood is maximal in
  // a there, and σ(σ1) = σ1/√(2(n − 3)).
  const auto r = simulated_series(20, 0.6, 2.0, 5.0, 23);
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given
  in.readings = r;
  const auto res = analyse_stochastic(in);
  const int n = 20;
  const MatrixXd G = reversal_design(n);
  const VectorXd l = Eigen::Map<const VectorXd>(r.data(), n);
  int seen = 0;
  for (const auto& f : res.models) {
    if (!is_c_type(f.model)) continue;
    SCOPED_TRACE(to_string(f.model));
    ++seen;
    EXPECT_TRUE(f.rho.empty());
    ASSERT_FALSE(f.shape.empty());
    MatrixXd R(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double k = std::abs(i - j), b = f.shape[0];
        R(i, j) = f.model == StochasticModel::Exponential ? std::exp(-k / b)
                  : f.model == StochasticModel::Gaussian  ? std::exp(-(k / b) * (k / b))
                                                          : std::exp(-k / b) * std::cos(f.shape[1] * k);
      }
    const MatrixXd P = R.inverse();
    const VectorXd y = (G.transpose() * P * G).inverse() * G.transpose() * P * l;
    const VectorXd v = l - G * y;
    const double a = v.dot(P * v) / (n - 3);
    EXPECT_NEAR(f.sigma1.value, std::sqrt(a), 1e-9 * std::sqrt(a));
    EXPECT_NEAR(f.sigma1.sigma, std::sqrt(a) / std::sqrt(2.0 * (n - 3)), 1e-9 * std::sqrt(a));
    // m_M from (GᵀD⁻¹G)⁻¹ with D = a·R.
    EXPECT_NEAR(f.north.sigma, std::sqrt(a * (G.transpose() * P * G).inverse()(0, 0)),
                1e-9 * f.north.sigma);
    // REML ℓ(a) = const − ((n−3)/2)·ln a − vᵀR⁻¹v/(2a): maximal at a; the reported ℓ is the
    // REML log-likelihood of D = a·R (dense formula).
    const auto reml = [&](double s) {
      const MatrixXd D = s * R;
      const MatrixXd Pi = D.inverse();
      const MatrixXd N = G.transpose() * Pi * G;
      const VectorXd yy = N.inverse() * G.transpose() * Pi * l;
      const VectorXd vv = l - G * yy;
      return -0.5 * ((n - 3) * std::log(2.0 * M_PI) + std::log(D.determinant()) +
                     std::log(N.determinant()) + vv.dot(Pi * vv));
    };
    EXPECT_GT(reml(a), reml(1.01 * a));
    EXPECT_GT(reml(a), reml(0.99 * a));
  }
  EXPECT_EQ(seen, 3);
}

TEST(StochasticCovarianceFunctions, ShapeAtTheGridEdgeIsSaidAndMatchesWhiteNoise) {
  // examples/tracking.yaml: c-exponential ends at b = 0.1 lag (user trial, finding 7), where
  // e^{−10} makes D practically a·I: σ1 and m must then be those of white noise (before the fix
  // σ1 was √((n−3)/n) of it).
  const StochasticInput in = example_tracking_input();
  const auto res = analyse_stochastic(in);
  const ModelFit& w = res.fit(StochasticModel::WhiteNoise);
  const ModelFit& e = res.fit(StochasticModel::Exponential);
  ASSERT_NEAR(e.shape[0], 0.1, 1e-12);
  EXPECT_THAT(e.notes, ::testing::Contains(HasSubstr("lower end of its search grid")));
  EXPECT_NEAR(e.sigma1.value / w.sigma1.value, 1.0, 1e-3);
  EXPECT_NEAR(e.north.sigma / w.north.sigma, 1.0, 1e-3);
}

TEST(StochasticChecks, BookedSigmaExcessIsABookingWarning) {
  StochasticInput in = example_tracking_input();
  in.booked_sigma = 8.0 * kArcsec;
  {
    const auto res = analyse_stochastic(in);
    // White-noise σ1 ≈ 5″ against 8″: consistent, no warning.
    EXPECT_TRUE(res.warnings.empty()) << res.warnings.front();
  }
  std::swap(in.readings[0], in.readings[1]);  // user trial, finding 10
  const auto res = analyse_stochastic(in);
  const double s1 = res.fit(StochasticModel::WhiteNoise).sigma1.value;
  ASSERT_GT(s1, 1000.0);
  EXPECT_THAT(res.warnings, ::testing::Contains(HasSubstr("booking error?")));
  // Nor a decay fitted to such readings: no (R2) length warning (it gave κ = 1.28 here).
  EXPECT_EQ(res.warnings.size(), 1u);
  EXPECT_EQ(res.r2_misfit_rms, 0.0);
  // Borderline: σ1 at the booked σ is no warning; the test rejects at α = 1 % when
  // (n − 3)·(σ1/σ)² > χ²_0.99(4) = 13.2767 (tables), i.e. σ/σ1 < √(4/13.2767) = 0.54889.
  in.readings = example_tracking_input().readings;
  const double s1w = analyse_stochastic(in).fit(StochasticModel::WhiteNoise).sigma1.value;
  in.booked_sigma = s1w * 0.54889 * 1.001 * kArcsec;  // just inside (not rejected)
  EXPECT_TRUE(analyse_stochastic(in).warnings.empty());
  in.booked_sigma = s1w * 0.54889 * 0.97 * kArcsec;  // T = 4/(0.54889·0.97)² ≈ 14.1 > 13.28
  const auto moderate = analyse_stochastic(in).warnings;
  EXPECT_THAT(moderate, ::testing::Contains(HasSubstr("scatter more than booked")));
  EXPECT_THAT(moderate, ::testing::Not(::testing::Contains(HasSubstr("booking error?"))));
}

// Noise-free (R1) readings r_i = M + (−1)^i·A·e^{−iκ}.
std::vector<double> r1_series(int n, double m, double a, double kappa) {
  std::vector<double> r;
  for (int i = 1; i <= n; ++i) r.push_back(m + (i % 2 == 0 ? 1.0 : -1.0) * a * std::exp(-i * kappa));
  return r;
}

TEST(StochasticChecks, LongSeriesMisfitOfR2IsWarned) {
  // Noise-free (R1) data: the OLS residuals of (R2) are exactly the misfit of the
  // linearisation, so the reported rms must match √(vᵀv/n) (up to the use of the fitted κ̂, Â′).
  const int n = 100;
  auto r = r1_series(n, 754.0, 4800.0, 0.002);
  const MatrixXd G = reversal_design(n);
  const VectorXd l = Eigen::Map<const VectorXd>(r.data(), n);
  const VectorXd y = (G.transpose() * G).inverse() * G.transpose() * l;
  const double rms = std::sqrt((l - G * y).squaredNorm() / n);
  // Leading order (the quadratic term, continuous): A·κ²/2·n²·√(1/180) ≈ 7.16″; the cubic
  // term (A·κ³·n³/6 = 6.4″ at i = n) lowers it, so only to 15 %.
  EXPECT_NEAR(rms, 4800.0 * 0.002 * 0.002 / 2.0 * n * n * std::sqrt(1.0 / 180.0), 0.15 * rms);
  // Add white noise of 5″ (fixed seed) so the series has the trial's scatter.
  std::mt19937_64 rng(6);
  std::normal_distribution<double> N(0.0, 5.0);
  for (double& x : r) x += N(rng);
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // fitted as given
  in.readings = r;
  in.options.markov2 = false;  // not needed here; keeps the test fast
  const auto res = analyse_stochastic(in);
  EXPECT_NEAR(res.r2_misfit_rms, rms, 0.05 * rms);
  EXPECT_THAT(res.warnings, ::testing::Contains(HasSubstr("long for the linearised model (R2)")));
  // The same noise without decay, and a short series with decay: no warning.
  in.readings = r1_series(n, 754.0, 4800.0, 0.0);
  std::mt19937_64 rng2(6);
  for (double& x : in.readings) x += N(rng2);
  EXPECT_TRUE(analyse_stochastic(in).warnings.empty());
  in.readings = r1_series(20, 754.0, 4800.0, 0.002);
  std::mt19937_64 rng3(6);
  for (double& x : in.readings) x += N(rng3);
  const auto short_res = analyse_stochastic(in);
  EXPECT_TRUE(short_res.warnings.empty());
  // A·κ²/2·20²·√(1/180) ≈ 0.29″, far below 0.25 × 5″.
  EXPECT_LT(short_res.r2_misfit_rms, 0.4);
}

}  // namespace
