// Unit tests of the simple non-tracking reductions (spec §4.1–4.5). Expected
// values come from closed forms of the model (N1), never from the code.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/nontracking.hpp"
#include "nontracking_truth.hpp"

namespace {

using meridian::InputError;
using meridian::NumericalError;
using meridian::gyro::BetaResult;
using meridian::gyro::Crossing;
using meridian::gyro::Instrument;
using meridian::gyro::NonTrackingMethod;
using meridian::gyro::NonTrackingObservations;
using meridian::gyro::Uncertain;
using meridian::units::kArcsecond;
using meridian::units::kPi;

using meridian_test::Truth;
using meridian_test::passages;
using meridian_test::add_reversals;
using meridian_test::scenario_instrument;

// Exact effective time difference d·Δt of a level: −2·T·ψ/π.
double exact_dt(const Truth& o, double level) {
  return -2.0 * o.period * std::asin((level - o.beta) / o.amp) / kPi;
}

template <class F>
std::string error_text(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

// ---------------------------------------------------------------------------

TEST(NonTrackingBasics, MethodNamesRoundTrip) {
  for (NonTrackingMethod m :
       {NonTrackingMethod::Transit, NonTrackingMethod::TimeDifference, NonTrackingMethod::Direct,
        NonTrackingMethod::TimedAmplitude1, NonTrackingMethod::TimedAmplitude2,
        NonTrackingMethod::LeastSquares})
    EXPECT_EQ(meridian::gyro::nontracking_method_from_string(meridian::gyro::to_string(m)), m);
  EXPECT_EQ(meridian::gyro::to_string(NonTrackingMethod::TimedAmplitude1), "timed-amplitude-1");
  const std::string msg =
      error_text([] { meridian::gyro::nontracking_method_from_string("schuler"); });
  EXPECT_NE(msg.find("time-difference"), std::string::npos) << msg;
  EXPECT_THROW(meridian::gyro::nontracking_method_from_string("schuler"), InputError);
}

TEST(NonTrackingBasics, TimeDifferenceDefinition) {
  EXPECT_DOUBLE_EQ(meridian::gyro::time_difference_s(1.0, 5.0, 7.0), -1.0 + 10.0 - 7.0);
}

// (β − a) = B·sin(π·Δt/(2T_B)) for an eastward first passage, derived by hand:
// θ1 = ψ, θ2 = π − ψ, θ3 = 2π + ψ ⇒ Δt = −4ψ·T/(2π) ⇒ sin(πΔt/(2T)) = −sin ψ = (β − a)/B.
TEST(NonTrackingSign, EastFirstPassageGivesPositiveDeltaTForBetaAboveLevel) {
  const Truth o{0.7, 9.0, 440.0, 50.0};
  const Crossing c = passages(o, 0.0, 40.0, 3);
  ASSERT_EQ(c.first_direction, +1);
  const double dt = meridian::gyro::time_difference_s(c.times_s[0], c.times_s[1], c.times_s[2]);
  EXPECT_GT(dt, 0.0);  // β > a
  EXPECT_NEAR(o.amp * std::sin(kPi * dt / (2.0 * o.period)), o.beta - 0.0, 1e-12);
}

TEST(NonTrackingSign, WestFirstPassageFlipsTheSign) {
  const Truth o{0.7, 9.0, 440.0, 50.0};
  const Crossing c = passages(o, 0.0, 100.0, 3);  // the first passage after 100 s is westward
  ASSERT_EQ(c.first_direction, -1);
  const double dt = meridian::gyro::time_difference_s(c.times_s[0], c.times_s[1], c.times_s[2]);
  EXPECT_LT(dt, 0.0);
  EXPECT_NEAR(o.amp * std::sin(kPi * -dt / (2.0 * o.period)), o.beta, 1e-12);

  // The transit method must give the same β for both starting directions.
  for (double t_from : {40.0, 100.0}) {
    NonTrackingObservations obs;
    obs.crossings.push_back(passages(o, 0.0, t_from, 3));
    add_reversals(obs, o, t_from, 2);
    obs.period_s = Uncertain{o.period, 0.0};
    const BetaResult r =
        meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, scenario_instrument());
    EXPECT_NEAR(r.beta_div.value - r.approximation_error_div, o.beta, 1e-9) << t_from;
    EXPECT_NEAR(r.beta_div.value, o.amp * std::asin(o.beta / o.amp), 1e-9) << t_from;
    ASSERT_TRUE(r.time_difference_s);
    EXPECT_NEAR(r.time_difference_s->value, exact_dt(o, 0.0), 1e-9);  // d·Δt
  }
}

// Five transits, T_B unknown: Δt = (−2t1 + 3t2 − 2t3 + 3t4 − 2t5)/3 (spec §4.1),
// also for times that do not fit the model exactly.
TEST(NonTrackingTransit, FiveTransitsPeriodUnknownReproducesTheSpecFormula) {
  const Truth o{-0.35, 8.0, 430.0, 20.0};
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 10.0, 5));
  ASSERT_EQ(obs.crossings[0].first_direction, +1);
  const double noise[] = {0.31, -0.22, 0.13, 0.0, -0.41};
  for (int i = 0; i < 5; ++i) obs.crossings[0].times_s[i] += noise[i];
  add_reversals(obs, o, 10.0, 2);
  const auto& t = obs.crossings[0].times_s;
  const double dt_spec = (-2 * t[0] + 3 * t[1] - 2 * t[2] + 3 * t[3] - 2 * t[4]) / 3.0;

  // T_B from an independent least-squares solution of t_i = t0 + (i−1)h + (−1)^i u.
  Eigen::MatrixXd A(5, 3);
  Eigen::VectorXd l(5);
  for (int i = 0; i < 5; ++i) {
    A(i, 0) = 1.0;
    A(i, 1) = i;
    A(i, 2) = (i % 2 == 0) ? -1.0 : 1.0;
    l(i) = t[i];
  }
  const Eigen::VectorXd x = (A.transpose() * A).ldlt().solve(A.transpose() * l);
  EXPECT_NEAR(4.0 * x(2), dt_spec, 1e-9);
  const double period = 2.0 * x(1);

  const BetaResult r =
      meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, scenario_instrument());
  ASSERT_TRUE(r.time_difference_s && r.period_s && r.amplitude_div);
  EXPECT_NEAR(r.time_difference_s->value, dt_spec, 1e-9);
  EXPECT_NEAR(r.period_s->value, period, 1e-9);
  EXPECT_NEAR(r.amplitude_div->value, o.amp, 1e-12);
  EXPECT_NEAR(r.beta_div.value, kPi * o.amp * dt_spec / (2.0 * period), 1e-12);
  EXPECT_NEAR(r.approximation_error_div,
              r.beta_div.value - o.amp * std::sin(kPi * dt_spec / (2.0 * period)), 1e-12);
  // σ(Δt) of this linear estimator: σ_t·sqrt(4+9+4+9+4)/3.
  EXPECT_NEAR(r.time_difference_s->sigma, obs.sigma_time_s * std::sqrt(30.0) / 3.0, 1e-9);
}

// Five transits, T_B known: LS in (t0, u) with l_i = t_i − (i−1)T/2 gives
// u = (Σl + 5·Σ(−1)^i l_i)/24 (normal equations [5 −1; −1 5]).
TEST(NonTrackingTransit, FiveTransitsPeriodKnown) {
  const Truth o{0.3, 9.0, 440.0, 50.0};
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 100.0, 5));  // first passage westward
  ASSERT_EQ(obs.crossings[0].first_direction, -1);
  const double noise[] = {-0.1, 0.25, 0.05, -0.3, 0.2};
  for (int i = 0; i < 5; ++i) obs.crossings[0].times_s[i] += noise[i];
  add_reversals(obs, o, 100.0, 3);
  obs.period_s = Uncertain{o.period, 0.2};
  double s = 0.0, s_alt = 0.0;
  for (int i = 0; i < 5; ++i) {
    const double li = obs.crossings[0].times_s[i] - i * o.period / 2.0;
    s += li;
    s_alt += ((i % 2 == 0) ? -1.0 : 1.0) * li;
  }
  const double u = (s + 5.0 * s_alt) / 24.0;
  const double dt = -4.0 * u;  // westward first transit: the sign flips
  // B from three reversals: mean of |a1 − a2|/2 and |a2 − a3|/2.
  const auto& a = obs.reversals_div;
  const double amp = (std::abs(a[0] - a[1]) + std::abs(a[1] - a[2])) / 4.0;
  const BetaResult r =
      meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, scenario_instrument());
  EXPECT_NEAR(r.time_difference_s->value, dt, 1e-9);
  EXPECT_NEAR(r.beta_div.value, kPi * amp * dt / (2.0 * o.period), 1e-12);
  EXPECT_NEAR(r.beta_div.value, o.beta, 0.03);  // the data are only slightly perturbed
  EXPECT_DOUBLE_EQ(r.period_s->value, o.period);
  EXPECT_DOUBLE_EQ(r.period_s->sigma, 0.2);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  // σ(B): ∂B/∂a = (±1/4, ±1/2, ±1/4) ⇒ σ_a·sqrt(1/16 + 1/4 + 1/16).
  EXPECT_NEAR(r.amplitude_div->sigma, obs.sigma_reading_div * std::sqrt(0.375), 1e-9);
}

TEST(NonTrackingTransit, WarnsWhenTimesContradictTheGivenPeriod) {
  const Truth o{0.1, 9.0, 440.0, 50.0};
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 40.0, 3));
  add_reversals(obs, o, 40.0, 2);
  obs.period_s = Uncertain{450.0, 0.5};  // 10 s off
  const BetaResult r =
      meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, scenario_instrument());
  bool found = false;
  for (const auto& w : r.warnings) found = found || w.find("inconsistent") != std::string::npos;
  EXPECT_TRUE(found);
}

TEST(NonTrackingTransit, ReportsTheSmallAngleError) {
  const Truth o{1.5, 9.0, 440.0, 50.0};
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 40.0, 3));
  add_reversals(obs, o, 40.0, 2);
  const BetaResult r =
      meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, scenario_instrument());
  // error = B·(x − asin... ) closed form: β_small = B·asin(β/B).
  const double err = o.amp * std::asin(o.beta / o.amp) - o.beta;
  EXPECT_NEAR(r.approximation_error_div, err, 1e-10);
}

// The warning rule: |error in N_G| > 0.1·σ(N_G) of the run, and > 0.01″.
TEST(NonTrackingTransit, SmallAngleWarningRule) {
  BetaResult r;
  r.method = NonTrackingMethod::Transit;
  r.approximation_error_div = 0.00165;
  using meridian::gyro::small_angle_warning;
  const double e = 1.157 * kArcsecond;
  EXPECT_TRUE(small_angle_warning(r, e, 14.0 * kArcsecond).empty());  // 8 % of σ
  EXPECT_TRUE(small_angle_warning(r, -e, 14.0 * kArcsecond).empty());
  EXPECT_FALSE(small_angle_warning(r, e, 11.0 * kArcsecond).empty());  // 10.5 % of σ
  const std::string w = small_angle_warning(r, -e, 11.0 * kArcsecond);
  EXPECT_EQ(w.rfind("transit: the small-angle approximation error", 0), 0u) << w;
  EXPECT_NE(w.find("11.00″"), std::string::npos) << w;
  // σ = 0 (noise-free weights): only errors above 0.01″ warn.
  EXPECT_TRUE(small_angle_warning(r, 0.009 * kArcsecond, 0.0).empty());
  EXPECT_FALSE(small_angle_warning(r, 0.011 * kArcsecond, 0.0).empty());
}

// ΔN = c·B·Δt with a calibrated c; λ and τ then play no part.
TEST(NonTrackingTransit, CalibratedFactorIsUsedForDeltaN) {
  const Truth o{-0.6, 9.0, 440.0, 50.0};
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 40.0, 3));
  add_reversals(obs, o, 40.0, 2);
  Instrument inst = scenario_instrument();
  const double c = 2.79 * kArcsecond;
  inst.transit_factor_rad_per_div_s = Uncertain{c, 0.01 * kArcsecond};
  inst.torsion_ratio = {0.9, 0.1};  // would change ΔN if it were used
  const BetaResult r = meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst);
  const double dt = exact_dt(o, 0.0);
  ASSERT_TRUE(r.transit_delta_n_rad);
  EXPECT_NEAR(r.transit_delta_n_rad->value / kArcsecond, c * o.amp * dt / kArcsecond, 1e-9);
  // σ from σ(c) alone when σ_t = σ_a = 0.
  obs.sigma_time_s = 0.0;
  obs.sigma_reading_div = 0.0;
  const BetaResult r0 = meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst);
  EXPECT_NEAR(r0.transit_delta_n_rad->sigma / kArcsecond, 0.01 * o.amp * std::abs(dt), 1e-6);
  EXPECT_DOUBLE_EQ(r0.beta_div.sigma, 0.0);

  // Without c: ΔN = (1+λ)·τ·β_small, σ including σ(λ) and σ(τ).
  Instrument plain = scenario_instrument();
  plain.torsion_ratio = {0.3, 0.01};
  plain.sigma_scale_value_rad = 1.0 * kArcsecond;
  const BetaResult r1 = meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, plain);
  const double beta_small = o.amp * std::asin(o.beta / o.amp);
  EXPECT_NEAR(r1.transit_delta_n_rad->value / kArcsecond, 1.3 * 600.0 * beta_small, 1e-9);
  const double sd = std::hypot(600.0 * beta_small * 0.01, 1.3 * 1.0 * beta_small);
  EXPECT_NEAR(r1.transit_delta_n_rad->sigma / kArcsecond, sd, 1e-6);
}

// Two clamp positions 12′ either side of north (spec §4.1). Expected c from
// the closed-form Δt = (2T/π)·asin(β/B) of each clamp.
TEST(NonTrackingTransit, CalibrateTransitFactorFromTwoClamps) {
  const double lam = 0.3;
  const double tau = 600.0 * kArcsecond;
  const double north = 1.0;
  const double clamp1 = north + 12.0 * 60.0 * kArcsecond;  // east of north
  const double clamp2 = north - 12.0 * 60.0 * kArcsecond;  // west of north
  const Truth o1{(north - clamp1) / ((1 + lam) * tau), 9.0, 440.0, 50.0};
  const Truth o2{(north - clamp2) / ((1 + lam) * tau), 8.5, 440.0, 75.0};
  const Instrument inst = scenario_instrument();
  BetaResult r[2];
  int k = 0;
  for (const Truth& o : {o1, o2}) {
    NonTrackingObservations obs;
    obs.crossings.push_back(passages(o, 0.0, 30.0, 3));
    add_reversals(obs, o, 30.0, 2);
    r[k++] = meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst);
  }
  const double dt1 = 2.0 * o1.period / kPi * std::asin(o1.beta / o1.amp);
  const double dt2 = 2.0 * o2.period / kPi * std::asin(o2.beta / o2.amp);
  EXPECT_NEAR(r[0].time_difference_s->value, dt1, 1e-9);
  EXPECT_NEAR(r[1].time_difference_s->value, dt2, 1e-9);
  const Uncertain c = meridian::gyro::calibrate_transit_factor(
      clamp1, *r[0].amplitude_div, *r[0].time_difference_s, clamp2, *r[1].amplitude_div,
      *r[1].time_difference_s);
  const double expected = (clamp2 - clamp1) / (o1.amp * dt1 - o2.amp * dt2);
  EXPECT_NEAR(c.value / expected, 1.0, 1e-10);
  // Close to the computed (1+λ)·τ·π/(2T_B) = 2.785″/(div·s) (spec §8.2).
  EXPECT_NEAR(c.value / kArcsecond, 2.785, 0.01);
  EXPECT_NEAR(1.3 * 600.0 * kPi / 880.0, 2.785, 5e-4);

  // σ: analytic partials of c = ΔN′/(B1Δt1 − B2Δt2).
  const Uncertain b1{9.0, 0.03}, t1{dt1, 0.2}, b2{8.5, 0.04}, t2{dt2, 0.25};
  const Uncertain cs = meridian::gyro::calibrate_transit_factor(clamp1, b1, t1, clamp2, b2, t2);
  const double den = 9.0 * dt1 - 8.5 * dt2;
  const double g = (clamp2 - clamp1) / (den * den);
  const double sd = std::sqrt(std::pow(g * dt1 * 0.03, 2) + std::pow(g * 9.0 * 0.2, 2) +
                              std::pow(g * dt2 * 0.04, 2) + std::pow(g * 8.5 * 0.25, 2));
  EXPECT_NEAR(cs.sigma / sd, 1.0, 1e-9);

  EXPECT_THROW(meridian::gyro::calibrate_transit_factor(clamp1, b1, t1, clamp1, b2, t2),
               InputError);
  EXPECT_THROW(meridian::gyro::calibrate_transit_factor(clamp1, b1, t1, clamp2, b1, t1),
               NumericalError);
}

// §4.5 reduces to §4.4 when t3 = t_r and a_x = a_r.
TEST(NonTrackingTimedAmplitude, MethodTwoReducesToMethodOne) {
  const Truth o{0.3, 9.0, 440.0, 50.0};
  NonTrackingObservations obs;
  Crossing c = passages(o, 1.0, 40.0, 2);
  c.times_s[1] += 0.7;  // imperfect data: both methods must still agree
  obs.crossings.push_back(c);
  const double tr = (c.times_s[0] + c.times_s[1]) / 2.0;
  const double ar = 9.2;
  obs.crossings.push_back(Crossing{ar, {tr}, +1});
  obs.reversals_div = {ar};
  obs.period_s = Uncertain{o.period, 0.0};
  const Instrument inst = scenario_instrument();
  const BetaResult r1 =
      meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude1, obs, inst);
  const BetaResult r2 =
      meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude2, obs, inst);
  const double C = std::cos(kPi * (c.times_s[1] - c.times_s[0]) / o.period);
  EXPECT_NEAR(r1.beta_div.value, (1.0 - ar * C) / (1.0 - C), 1e-12);
  EXPECT_NEAR(r2.beta_div.value, r1.beta_div.value, 1e-12);
}

// Timed amplitude II written out (§4.5) with its σ from the analytic partials
// of docs §6.2 (T_B exact): the reference for the choice of t3 below.
struct Ta2Reference {
  double beta, sigma;
};
Ta2Reference ta2_reference(double a, double t1, double t2, double ax, double t3, double T,
                           double sigma_t) {
  const double c12 = std::cos(kPi * (t2 - t1) / T);
  const double s12 = std::sin(kPi * (t2 - t1) / T);
  const double c3 = std::cos(2.0 * kPi * (t3 - (t1 + t2) / 2.0) / T);
  const double s3 = std::sin(2.0 * kPi * (t3 - (t1 + t2) / 2.0) / T);
  const double D = c3 - c12;
  const double beta = (a * c3 - ax * c12) / D;
  const double db_dc3 = (a - beta) / D;
  const double db_dc12 = (beta - ax) / D;
  const double d1 = db_dc3 * (kPi / T) * s3 + db_dc12 * (kPi / T) * s12;  // ∂β/∂t1
  const double d2 = db_dc3 * (kPi / T) * s3 - db_dc12 * (kPi / T) * s12;  // ∂β/∂t2
  const double d3 = db_dc3 * -(2.0 * kPi / T) * s3;                       // ∂β/∂t3
  return {beta, sigma_t * std::sqrt(d1 * d1 + d2 * d2 + d3 * d3)};
}

// The two passages of a level either side of the turning point at t_r are
// mirror images; which one is "nearest" to t_r is decided by the timing noise
// alone, and choosing by it biased TA-II by −3.8″ (issue 15). Whichever of the
// two the noise moves towards t_r, the rule takes the same one: the first
// passage after t_r.
TEST(NonTrackingTimedAmplitude, MethodTwoThirdPassageDoesNotFollowTheNoise) {
  const Truth o;  // spec §8.2
  const Instrument inst = scenario_instrument();
  for (double shift : {-0.3, 0.3}) {  // the earlier (−) or the later (+) passage moved inwards
    NonTrackingObservations obs;
    obs.crossings.push_back(passages(o, -2.0, 30.0, 3));  // a = −2: 35.263, 284.737; t_r = 160
    obs.crossings.push_back(passages(o, 2.0, 30.0, 3));   // 66.652, 253.348, 506.652
    obs.period_s = Uncertain{o.period, 0.0};
    std::vector<double>& t = obs.crossings[1].times_s;
    if (shift < 0.0)
      t[0] -= shift;
    else
      t[1] -= shift;
    const double t1 = obs.crossings[0].times_s[0];
    const double t2 = obs.crossings[0].times_s[1];
    const Ta2Reference ref = ta2_reference(-2.0, t1, t2, 2.0, t[1], o.period, obs.sigma_time_s);
    const BetaResult r =
        meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude2, obs, inst);
    EXPECT_NEAR(r.beta_div.value, ref.beta, 1e-12) << "shift " << shift;
    EXPECT_NEAR(r.beta_div.sigma, ref.sigma, 1e-9) << "shift " << shift;
  }
}

// Of the other levels the one giving the smallest σ(β) is used (σ from the
// analytic partials), not the one nearest in time: with a = 0 and β = −0.12
// level +2 is nearer to t_r but level −2 gives σ 11 % smaller.
TEST(NonTrackingTimedAmplitude, MethodTwoUsesTheBestConditionedLevel) {
  const Instrument inst = scenario_instrument();
  for (double beta : {-0.12, 0.5, -0.8}) {
    const Truth o{beta, 9.0, 440.0, 50.0};
    NonTrackingObservations obs;
    for (double level : {0.0, 2.0, -2.0}) obs.crossings.push_back(passages(o, level, 30.0, 3));
    obs.period_s = Uncertain{o.period, 0.0};
    const auto& z = obs.crossings[0].times_s;
    double best = INFINITY;
    for (std::size_t x : {1u, 2u}) {
      const auto& t = obs.crossings[x].times_s;
      ASSERT_LT(t[0], (z[0] + z[1]) / 2.0);  // the first passage after t_r is t[1]
      ASSERT_GT(t[1], (z[0] + z[1]) / 2.0);
      best = std::min(best, ta2_reference(0.0, z[0], z[1], obs.crossings[x].level_div, t[1],
                                          o.period, obs.sigma_time_s)
                                .sigma);
    }
    const BetaResult r =
        meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude2, obs, inst);
    EXPECT_NEAR(r.beta_div.value, beta, 1e-12);
    EXPECT_NEAR(r.beta_div.sigma, best, 1e-9) << "β = " << beta;
  }
}

// σ of the timed-amplitude I method from analytic partials:
// β = (a − a_r·C)/(1 − C), C = cos(πΔ/T), ∂β/∂C = (β − a_r)/(1 − C),
// ∂C/∂Δ = −(π/T)·sin(πΔ/T), ∂β/∂a_r = −C/(1 − C), ∂C/∂T = (πΔ/T²)·sin(πΔ/T).
TEST(NonTrackingTimedAmplitude, MethodOneSigmaMatchesAnalyticPartials) {
  const Truth o{-0.12, 9.0, 440.0, 50.0};
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 40.0, 2));
  add_reversals(obs, o, 100.0, 1);
  obs.period_s = Uncertain{o.period, 0.4};
  obs.sigma_time_s = 0.1;
  obs.sigma_reading_div = 0.05;
  const BetaResult r = meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude1, obs,
                                                          scenario_instrument());
  const double d = obs.crossings[0].times_s[1] - obs.crossings[0].times_s[0];
  const double C = std::cos(kPi * d / o.period);
  const double S = std::sin(kPi * d / o.period);
  const double ar = o.beta + o.amp;
  const double dbdc = (o.beta - ar) / (1.0 - C);
  const double sd_d = dbdc * -(kPi / o.period) * S * std::sqrt(2.0) * 0.1;
  const double sd_a = -C / (1.0 - C) * 0.05;
  const double sd_t = dbdc * (kPi * d / (o.period * o.period)) * S * 0.4;
  EXPECT_NEAR(r.beta_div.value, o.beta, 1e-12);
  EXPECT_NEAR(r.beta_div.sigma, std::sqrt(sd_d * sd_d + sd_a * sd_a + sd_t * sd_t), 1e-9);
}

// Without reversal times the reversal beyond the level in the direction of the
// first passage is used: a pair starting westward takes the west reversal.
TEST(NonTrackingTimedAmplitude, ReversalChosenBySideWithoutTimes) {
  const Truth o{0.25, 9.0, 440.0, 50.0};
  NonTrackingObservations obs;
  Crossing c = passages(o, 0.0, 100.0, 2);
  ASSERT_EQ(c.first_direction, -1);
  obs.crossings.push_back(c);
  obs.reversals_div = {o.beta + o.amp, o.beta - o.amp};  // east first; the west one applies
  obs.period_s = Uncertain{o.period, 0.0};
  const BetaResult r = meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude1, obs,
                                                          scenario_instrument());
  EXPECT_NEAR(r.beta_div.value, o.beta, 1e-12);
  EXPECT_NEAR(r.amplitude_div->value, o.amp, 1e-12);
}

TEST(NonTrackingBasics, ApplicableMethods) {
  const Truth o;
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 30.0, 3));
  using V = std::vector<NonTrackingMethod>;
  EXPECT_EQ(meridian::gyro::applicable_methods(obs), V{});
  add_reversals(obs, o, 100.0, 2);
  EXPECT_EQ(meridian::gyro::applicable_methods(obs),
            (V{NonTrackingMethod::Transit, NonTrackingMethod::LeastSquares}));
  obs.crossings.push_back(passages(o, 2.0, 30.0, 3));
  obs.period_s = Uncertain{o.period, 0.0};
  EXPECT_EQ(meridian::gyro::applicable_methods(obs),
            (V{NonTrackingMethod::Transit, NonTrackingMethod::TimeDifference,
               NonTrackingMethod::Direct, NonTrackingMethod::TimedAmplitude1,
               NonTrackingMethod::TimedAmplitude2, NonTrackingMethod::LeastSquares}));
}

// ---------------------------------------------------------------------------
// Bad input

NonTrackingObservations good_observations() {
  const Truth o;
  NonTrackingObservations obs;
  obs.crossings.push_back(passages(o, 0.0, 30.0, 3));
  obs.crossings.push_back(passages(o, -2.0, 30.0, 3));
  obs.crossings.push_back(passages(o, 2.0, 30.0, 3));
  add_reversals(obs, o, 100.0, 2);
  obs.period_s = Uncertain{o.period, 0.0};
  return obs;
}

template <class E, class F>
void expect_error(F&& f, const std::string& field, const std::string& text = {}) {
  bool thrown = false;
  try {
    f();
  } catch (const E& e) {
    thrown = true;
    EXPECT_EQ(e.context().field, field) << e.what();
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    if (!text.empty()) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    thrown = true;
  }
  EXPECT_TRUE(thrown) << "no exception for " << field;
}

TEST(NonTrackingBadInput, TimesNotIncreasing) {
  NonTrackingObservations obs = good_observations();
  obs.crossings[1].times_s = {50.9, 35.2, 300.0};
  for (auto m : {NonTrackingMethod::Transit, NonTrackingMethod::TimeDifference,
                 NonTrackingMethod::LeastSquares})
    expect_error<InputError>(
        [&] { meridian::gyro::reduce_nontracking(m, obs, scenario_instrument()); },
        "crossings[1].times_s", "times must increase (t2 = 35.2 ≤ t1 = 50.9)");
}

TEST(NonTrackingBadInput, NonFiniteValues) {
  const Instrument inst = scenario_instrument();
  NonTrackingObservations obs = good_observations();
  obs.crossings[2].times_s[1] = std::nan("");
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Direct, obs, inst); },
      "crossings[2].times_s[1]", "finite");
  obs = good_observations();
  obs.reversals_div[1] = INFINITY;
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst); },
      "reversals_div[1]");
  obs = good_observations();
  obs.crossings[0].level_div = std::nan("");
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst); },
      "crossings[0].level_div");
  obs = good_observations();
  obs.period_s = Uncertain{-440.0, 0.0};
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Direct, obs, inst); },
      "period_s");
  obs = good_observations();
  obs.sigma_time_s = -0.1;
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Direct, obs, inst); },
      "sigma_time_s");
  obs = good_observations();
  obs.crossings[0].first_direction = 0;
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Direct, obs, inst); },
      "crossings[0].first_direction");
}

TEST(NonTrackingBadInput, ReversalsNotAlternating) {
  NonTrackingObservations obs = good_observations();
  obs.reversals_div = {8.88, -9.12, -8.0};
  obs.reversal_times_s.clear();
  expect_error<InputError>(
      [&] {
        meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, scenario_instrument());
      },
      "reversals_div[2]", "alternate");
  obs.reversals_div = {8.88, -9.12};
  obs.reversal_times_s = {160.0};
  expect_error<InputError>(
      [&] {
        meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, scenario_instrument());
      },
      "reversal_times_s");
}

TEST(NonTrackingBadInput, TooFewCrossingsOrReversals) {
  const Instrument inst = scenario_instrument();
  NonTrackingObservations obs = good_observations();
  obs.reversals_div = {8.88};
  obs.reversal_times_s = {160.0};
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst); },
      "reversals_div", "two reversal readings");
  obs = good_observations();
  obs.crossings[0].times_s.pop_back();
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst); },
      "crossings", "three crossings of the scale zero");
  obs = good_observations();
  obs.crossings.resize(1);
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::TimeDifference, obs, inst); },
      "crossings", "two different levels");
  obs = good_observations();
  obs.reversals_div.clear();
  obs.reversal_times_s.clear();
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude1, obs, inst); },
      "reversals_div");
}

TEST(NonTrackingBadInput, PeriodMissingWhereRequired) {
  NonTrackingObservations obs = good_observations();
  obs.period_s.reset();
  for (auto m : {NonTrackingMethod::Direct, NonTrackingMethod::TimedAmplitude1,
                 NonTrackingMethod::TimedAmplitude2})
    expect_error<InputError>(
        [&] { meridian::gyro::reduce_nontracking(m, obs, scenario_instrument()); }, "period_s",
        "T_B");
  // The transit and time-difference methods do not need it.
  EXPECT_NO_THROW(meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs,
                                                     scenario_instrument()));
  EXPECT_NO_THROW(meridian::gyro::reduce_nontracking(NonTrackingMethod::TimeDifference, obs,
                                                     scenario_instrument()));
}

TEST(NonTrackingBadInput, LevelNotReached) {
  const Instrument inst = scenario_instrument();
  NonTrackingObservations obs = good_observations();
  // |Δt| = 480 s > T_B: no level of the oscillation gives these passages.
  obs.crossings[1].times_s = {0.0, 10.0, 500.0};
  expect_error<NumericalError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Direct, obs, inst); },
      "crossings[1].times_s", "not less than T_B");
  // Two passages further apart than T_B cannot bracket one reversal.
  obs = good_observations();
  obs.crossings[0].times_s = {50.0, 500.0, 600.0};
  obs.reversal_times_s.clear();
  expect_error<NumericalError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude1, obs, inst); },
      "crossings[0].times_s", "cannot bracket");
}

TEST(NonTrackingBadInput, ReversalOnTheWrongSide) {
  NonTrackingObservations obs = good_observations();
  // Claim the east reversal happened between the level-0 passages that bracket
  // the west one.
  obs.reversal_times_s = {300.0, 400.0};
  obs.crossings.resize(1);
  obs.crossings[0].times_s = {50.934, 269.066, 490.934};
  expect_error<InputError>(
      [&] {
        meridian::gyro::reduce_nontracking(NonTrackingMethod::TimedAmplitude1, obs,
                                           scenario_instrument());
      },
      "reversals_div[0]", "not beyond that level");
}

TEST(NonTrackingBadInput, InstrumentWithoutScaleValueForTransit) {
  NonTrackingObservations obs = good_observations();
  Instrument inst;
  expect_error<InputError>(
      [&] { meridian::gyro::reduce_nontracking(NonTrackingMethod::Transit, obs, inst); },
      "scale_value_rad");
}

}  // namespace
