// Unified least-squares fit of (N1) to all non-tracking observations
// (gyro-theodolite spec §4.6). Data from closed-form inversion of (N1), or,
// with damping, from a bracketed root search of (N1) itself.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/nontracking.hpp"
#include "meridian/gyro/unified_fit.hpp"
#include "nontracking_truth.hpp"

namespace {

using meridian::InputError;
using meridian::gyro::Crossing;
using meridian::gyro::Instrument;
using meridian::gyro::NonTrackingMethod;
using meridian::gyro::NonTrackingObservations;
using meridian::gyro::Uncertain;
using meridian::gyro::UnifiedFitOptions;
using meridian::gyro::UnifiedFitResidual;
using meridian::gyro::UnifiedFitResult;
using meridian::units::kArcsecond;
using meridian::units::kPi;
using meridian_test::scenario_instrument;

// (N1): a(t) = β + B·e^{−k(t−t0)}·sin(2π(t − t0)/T).
struct Oscillation {
  double beta = -0.12;
  double amp = 9.0;
  double period = 440.0;
  double t0 = 50.0;
  double k = 0.0;

  double w() const { return 2.0 * kPi / period; }
  double value(double t) const {
    const double s = t - t0;
    return beta + amp * std::exp(-k * s) * std::sin(w() * s);
  }
  // Exact turning points: ȧ = 0 ⇔ tan(ω·s) = ω/k ⇔ ω·s = atan2(ω, k) + mπ.
  double turning(int m) const { return t0 + (std::atan2(w(), k) + m * kPi) / w(); }
};

// Passages of `level` from t_from on: a(t) is monotone between turning points,
// so each half-cycle holds at most one root; bisection to rounding.
Crossing passages(const Oscillation& o, double level, double t_from, int count) {
  Crossing c;
  c.level_div = level;
  for (int m = static_cast<int>(std::floor((t_from - o.t0) / o.period * 2.0)) - 2;
       static_cast<int>(c.times_s.size()) < count; ++m) {
    double lo = o.turning(m);
    double hi = o.turning(m + 1);
    const double flo = o.value(lo) - level;
    const double fhi = o.value(hi) - level;
    if (flo * fhi >= 0.0) continue;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      if ((o.value(mid) - level < 0.0) == (flo < 0.0))
        lo = mid;
      else
        hi = mid;
    }
    const double t = 0.5 * (lo + hi);
    if (t < t_from) continue;
    if (c.times_s.empty()) c.first_direction = fhi > flo ? +1 : -1;
    c.times_s.push_back(t);
  }
  return c;
}

void add_reversals(NonTrackingObservations& obs, const Oscillation& o, double t_from, int count) {
  for (int m = static_cast<int>(std::floor((t_from - o.t0) / o.period * 2.0)) - 2;
       static_cast<int>(obs.reversals_div.size()) < count; ++m) {
    const double t = o.turning(m);
    if (t < t_from) continue;
    obs.reversals_div.push_back(o.value(t));
    obs.reversal_times_s.push_back(t);
  }
}

NonTrackingObservations scenario_observations(const Oscillation& o, double t_from,
                                              int per_level = 3, int reversals = 2) {
  NonTrackingObservations obs;
  for (double level : {0.0, -2.0, 2.0})
    obs.crossings.push_back(passages(o, level, t_from, per_level));
  add_reversals(obs, o, t_from + 60.0, reversals);
  return obs;
}

// ---------------------------------------------------------------------------

TEST(UnifiedFit, Scenario2PeriodHeldFixed) {
  const Oscillation o;
  NonTrackingObservations obs = scenario_observations(o, 30.0);
  obs.period_s = Uncertain{440.0, 0.0};
  const Instrument inst = scenario_instrument();
  const UnifiedFitResult r = meridian::gyro::fit_nontracking(obs, inst);
  EXPECT_NEAR(r.beta_div.value, -0.12, 1e-9);
  EXPECT_NEAR(r.amplitude_div.value, 9.0, 1e-9);
  EXPECT_NEAR(r.t0_s.value, 50.0, 1e-7);
  EXPECT_DOUBLE_EQ(r.period_s.value, 440.0);
  EXPECT_DOUBLE_EQ(r.period_s.sigma, 0.0);
  ASSERT_EQ(r.covariance.rows(), 4);
  EXPECT_EQ(r.covariance(3, 3), 0.0);
  EXPECT_EQ(r.dof, 9 + 2 - 3);
  EXPECT_LT(r.sigma0, 1e-4);
  EXPECT_GT(r.beta_div.sigma, 0.0);
  EXPECT_NEAR(r.beta_div.sigma, std::sqrt(r.covariance(0, 0)), 1e-15);
  EXPECT_FALSE(r.period_residual);
  ASSERT_EQ(r.residuals.size(), 11u);
  EXPECT_EQ(r.residuals[3].kind, UnifiedFitResidual::Kind::CrossingTime);
  EXPECT_EQ(r.residuals[3].group, 1);
  EXPECT_EQ(r.residuals[3].index, 0);
  EXPECT_DOUBLE_EQ(r.residuals[3].observed, obs.crossings[1].times_s[0]);
  EXPECT_EQ(r.residuals[10].kind, UnifiedFitResidual::Kind::ReversalReading);
  EXPECT_EQ(r.residuals[10].index, 1);
  const double dn =
      meridian::gyro::north_from_nontracking(0.0, r.beta_div, inst).delta_n_rad / kArcsecond;
  EXPECT_NEAR(dn, -93.600, 0.01);
  // The comparison table holds every simple method.
  ASSERT_EQ(r.simple_methods.size(), 5u);
  EXPECT_EQ(r.simple_methods[0].method, NonTrackingMethod::Transit);
  EXPECT_EQ(r.simple_methods[4].method, NonTrackingMethod::TimedAmplitude2);
  // And the BetaResult view agrees with reduce_nontracking(LeastSquares).
  const auto b = meridian::gyro::reduce_nontracking(NonTrackingMethod::LeastSquares, obs, inst);
  EXPECT_EQ(b.method, NonTrackingMethod::LeastSquares);
  EXPECT_DOUBLE_EQ(b.beta_div.value, r.beta_div.value);
  EXPECT_DOUBLE_EQ(b.beta_div.sigma, r.beta_div.sigma);
}

TEST(UnifiedFit, PeriodAsObservationAndFree) {
  const Oscillation o{0.45, 8.5, 452.0, 12.0, 0.0};
  NonTrackingObservations obs = scenario_observations(o, 100.0);
  obs.period_s = Uncertain{452.0, 0.5};
  const UnifiedFitResult r = meridian::gyro::fit_nontracking(obs, scenario_instrument());
  EXPECT_NEAR(r.beta_div.value, 0.45, 1e-9);
  EXPECT_NEAR(r.period_s.value, 452.0, 1e-7);
  EXPECT_LT(r.period_s.sigma, 0.5);
  ASSERT_TRUE(r.period_residual);
  EXPECT_NEAR(r.period_residual->residual, 0.0, 1e-6);
  EXPECT_EQ(r.dof, 9 + 2 + 1 - 4);

  UnifiedFitOptions free;
  free.use_known_period = false;
  const UnifiedFitResult f = meridian::gyro::fit_nontracking(obs, scenario_instrument(), free);
  EXPECT_NEAR(f.beta_div.value, 0.45, 1e-9);
  EXPECT_NEAR(f.period_s.value, 452.0, 1e-7);
  EXPECT_FALSE(f.period_residual);
  EXPECT_EQ(f.dof, 9 + 2 - 4);
  // Without the period observation T_B is less well determined.
  EXPECT_GT(f.period_s.sigma, r.period_s.sigma);
}

// Observations long after t0 with no period given: the phase branches must
// still be assigned correctly.
TEST(UnifiedFit, FarFromT0AndWithoutReversals) {
  const Oscillation o{-0.7, 9.5, 433.0, 0.0, 0.0};
  NonTrackingObservations obs;
  for (double level : {-3.0, 0.0, 1.5}) obs.crossings.push_back(passages(o, level, 5000.0, 4));
  const UnifiedFitResult r = meridian::gyro::fit_nontracking(obs, scenario_instrument());
  EXPECT_NEAR(r.beta_div.value, -0.7, 1e-9);
  EXPECT_NEAR(r.amplitude_div.value, 9.5, 1e-9);
  EXPECT_NEAR(r.period_s.value, 433.0, 1e-7);
  // t0 is defined modulo T_B.
  const double phase = std::remainder(r.t0_s.value - o.t0, o.period);
  EXPECT_NEAR(phase, 0.0, 1e-6);
}

// No simple method applies (two passages of one level, two reversals outside
// them, no period): start values from the passage-pair relation
// a − β = d·B·cos(π(t2 − t1)/T_B) and the reversals; dof = 0.
TEST(UnifiedFit, MinimalDataWithoutSimpleMethods) {
  const Oscillation o;
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 30.0, 2));
  add_reversals(obs, o, 300.0, 2);
  ASSERT_EQ(meridian::gyro::applicable_methods(obs),
            std::vector<NonTrackingMethod>{NonTrackingMethod::LeastSquares});
  const UnifiedFitResult r = meridian::gyro::fit_nontracking(obs, scenario_instrument());
  EXPECT_NEAR(r.beta_div.value, -0.12, 1e-9);
  EXPECT_NEAR(r.amplitude_div.value, 9.0, 1e-9);
  EXPECT_EQ(r.dof, 0);
  EXPECT_TRUE(std::isnan(r.sigma0));
  EXPECT_TRUE(r.simple_methods.empty());
}

TEST(UnifiedFit, RecoversDamping) {
  const Oscillation o{0.2, 9.0, 440.0, 50.0, 1e-5};
  NonTrackingObservations obs = scenario_observations(o, 30.0, 6, 5);
  UnifiedFitOptions opt;
  opt.estimate_damping = true;
  const UnifiedFitResult r = meridian::gyro::fit_nontracking(obs, scenario_instrument(), opt);
  ASSERT_EQ(r.covariance.rows(), 5);
  EXPECT_NEAR(r.beta_div.value * 780.0, 0.2 * 780.0, 0.01);
  EXPECT_NEAR(r.damping_per_s.value / 1e-5, 1.0, 1e-3);
  EXPECT_NEAR(r.amplitude_div.value, 9.0, 1e-4);
  EXPECT_NEAR(r.period_s.value, 440.0, 1e-4);
  EXPECT_GT(r.damping_per_s.sigma, 0.0);

  // Ignoring the damping biases B and leaves systematic residuals.
  const UnifiedFitResult u = meridian::gyro::fit_nontracking(obs, scenario_instrument());
  EXPECT_EQ(u.damping_per_s.value, 0.0);
  EXPECT_GT(u.sigma0, 10.0 * r.sigma0);
}

TEST(UnifiedFit, BlunderIsFlagged) {
  const Oscillation o;
  NonTrackingObservations obs = scenario_observations(o, 30.0, 4, 4);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 0.1);
  for (auto& c : obs.crossings)
    for (double& t : c.times_s) t += g(rng);
  obs.crossings[2].times_s[1] += 3.0;  // 30σ
  const UnifiedFitResult r = meridian::gyro::fit_nontracking(obs, scenario_instrument());
  bool chi2 = false, named = false;
  for (const auto& w : r.warnings) {
    chi2 = chi2 || w.find("χ²") != std::string::npos;
    named = named || w.find("crossings[2].times_s[1]") != std::string::npos;
  }
  EXPECT_TRUE(chi2);
  EXPECT_TRUE(named);
  // v = fitted − observed: the late time gets a negative residual.
  for (const auto& v : r.residuals)
    if (v.kind == UnifiedFitResidual::Kind::CrossingTime && v.group == 2 && v.index == 1) {
      EXPECT_LT(v.residual, -1.0);
    }
  double sum_r = 0.0;
  for (const auto& v : r.residuals) sum_r += v.redundancy;
  EXPECT_NEAR(sum_r, r.dof, 1e-6);
}

TEST(UnifiedFit, NotApplicable) {
  const Oscillation o;
  const Instrument inst = scenario_instrument();
  // One level, no reversals: β and B cannot be separated.
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 30.0, 5));
  EXPECT_FALSE(meridian::gyro::unified_fit_applicable(obs));
  try {
    meridian::gyro::fit_nontracking(obs, inst);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "crossings");
  }
  // σ_t = 0 cannot weight the times.
  obs = scenario_observations(o, 30.0);
  obs.sigma_time_s = 0.0;
  EXPECT_THROW(meridian::gyro::fit_nontracking(obs, inst), InputError);
  // Damping with reversal readings needs their times.
  obs = scenario_observations(o, 30.0);
  obs.reversal_times_s.clear();
  UnifiedFitOptions opt;
  opt.estimate_damping = true;
  EXPECT_FALSE(meridian::gyro::unified_fit_applicable(obs, opt));
  try {
    meridian::gyro::fit_nontracking(obs, inst, opt);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "reversal_times_s");
  }
  // Too few observations: two passages and a timed reversal for β, B, t0, k (T_B fixed).
  obs = NonTrackingObservations{};
  obs.crossings.push_back(passages(o, 0.0, 30.0, 2));
  obs.reversals_div = {8.88};
  obs.reversal_times_s = {160.0};
  obs.period_s = Uncertain{440.0, 0.0};
  EXPECT_TRUE(meridian::gyro::unified_fit_applicable(obs));
  EXPECT_FALSE(meridian::gyro::unified_fit_applicable(obs, opt));
  try {
    meridian::gyro::fit_nontracking(obs, inst, opt);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("3 observations for 4 parameters"), std::string::npos)
        << e.what();
  }
  // Without period_s, T_B needs three passages of a level or two timed reversals.
  obs.period_s.reset();
  obs.reversal_times_s.clear();
  try {
    meridian::gyro::fit_nontracking(obs, inst);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "period_s");
  }
}

}  // namespace
