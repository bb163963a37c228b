// The navigation methods against independent references: batch least squares of the whole
// line, the filter module's RTS smoother, closed forms; the chain parameters; bad input.
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/filter/kalman_filter.hpp"
#include "meridian/filter/rts_smoother.hpp"
#include "meridian/filter/smoother_storage.hpp"
#include "meridian/nav/navigation.hpp"
#include "meridian/nav/simulator.hpp"

namespace meridian::nav {
namespace {

// A straight line at 5 m/s, heading 60°, DR exact (no bias, no noise) unless changed.
Input straight_line(int samples, double step_s) {
  Input in;
  const double c = std::cos(1.0471975511965976);
  const double s = std::sin(1.0471975511965976);
  for (int i = 0; i < samples; ++i) {
    DrSample d;
    d.time_s = i * step_s;
    d.v_north_m_s = 5.0 * c;
    d.v_east_m_s = 5.0 * s;
    in.dr.push_back(d);
    in.truth.push_back({d.time_s, 5.0 * d.time_s * c, 5.0 * d.time_s * s});
  }
  in.stations = {{"A", 20000.0, -5000.0}, {"B", -10000.0, -10000.0}, {"C", 5000.0, 30000.0}};
  in.options.rejection = Rejection::WTest;
  in.options.alpha = 1e-12;  // nothing is rejected
  in.options.sequential_sigma_velocity_m_s = 0.0;
  in.options.bias_start_s = 1e9;  // method I never starts: the forward run has no bias
  return in;
}

void add_ranges(Input& in, double sigma_m, std::uint64_t seed, double every_s = 5.0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, sigma_m);
  double next = 0.0;
  for (const TruthPoint& t : in.truth) {
    if (t.time_s < next - 1e-9) continue;
    next += every_s;
    for (std::size_t s = 0; s < in.stations.size(); ++s) {
      Lop l;
      l.time_s = t.time_s;
      l.station = s;
      l.sigma_m = sigma_m;
      l.value_m = std::hypot(t.x_north_m - in.stations[s].x_north_m,
                             t.y_east_m - in.stations[s].y_east_m) + n(rng);
      in.lops.push_back(l);
    }
  }
}

const MethodResult& method(const Result& r, Method m) {
  const MethodResult* p = r.find(m);
  if (!p) throw std::runtime_error("method missing: " + to_string(m));
  return *p;
}

TEST(NavSequential, EqualsBatchLeastSquaresOfTheWholeLineWithExactDr) {
  // With exact DR every position is p₀ + DR_k: the sequential adjustment's last estimate must
  // be the least-squares p₀ of all LOPs and the prior (Gauss–Newton, iterated to convergence,
  // written here independently), carried to the last epoch.
  Input in = straight_line(121, 5.0);
  add_ranges(in, 50.0, 11);
  in.initial = {30.0, -20.0, 1000.0};
  const Result r = process(in);
  Eigen::Vector2d p0(in.initial.x_north_m, in.initial.y_east_m);
  Eigen::Matrix2d N;
  for (int it = 0; it < 20; ++it) {
    N = Eigen::Matrix2d::Identity() / (1000.0 * 1000.0);
    Eigen::Vector2d u = (Eigen::Vector2d(in.initial.x_north_m, in.initial.y_east_m) - p0) /
                        (1000.0 * 1000.0);
    for (const Lop& l : in.lops) {
      const auto k = static_cast<std::size_t>(std::lround(l.time_s / 5.0));
      const Eigen::Vector2d pk = p0 + Eigen::Vector2d(in.truth[k].x_north_m, in.truth[k].y_east_m);
      const Eigen::Vector2d d = pk - Eigen::Vector2d(in.stations[l.station].x_north_m,
                                                     in.stations[l.station].y_east_m);
      const Eigen::RowVector2d a = d.transpose() / d.norm();
      N += a.transpose() * a / (l.sigma_m * l.sigma_m);
      u += a.transpose() * (l.value_m - d.norm()) / (l.sigma_m * l.sigma_m);
    }
    p0 += N.ldlt().solve(u);
  }
  const Eigen::Matrix2d Q = N.inverse();
  const TrackPoint& last = method(r, Method::SequentialNoBias).track.back();
  const Eigen::Vector2d expected = p0 + Eigen::Vector2d(in.truth.back().x_north_m, in.truth.back().y_east_m);
  // The EKF linearises each epoch once at its predicted position (tens of metres from the
  // final one at the start, ranges of 10–30 km): a second-order difference of a few mm.
  EXPECT_NEAR(last.x_north_m, expected(0), 0.02);
  EXPECT_NEAR(last.y_east_m, expected(1), 0.02);
  EXPECT_NEAR(last.covariance(0, 0), Q(0, 0), 1e-3 * Q(0, 0));
  EXPECT_NEAR(last.covariance(1, 1), Q(1, 1), 1e-3 * Q(1, 1));
  EXPECT_NEAR(last.covariance(0, 1), Q(0, 1), 1e-3 * std::sqrt(Q(0, 0) * Q(1, 1)));
  // The backward correction over the whole line gives every epoch the same information.
  Input whole = in;
  whole.options.backward_window_s = 1e6;
  const Result rw = process(whole);  // kept: a reference into a temporary result dangled here
  const TrackPoint& first = method(rw, Method::Backward).track.front();
  EXPECT_NEAR(first.x_north_m, p0(0), 0.02);
  EXPECT_NEAR(first.y_east_m, p0(1), 0.02);
  EXPECT_NEAR(first.covariance(0, 0), Q(0, 0), 1e-3 * Q(0, 0));
}

TEST(NavBackward, WholeLineWindowEqualsTheRtsSmootherOfTheSameModel) {
  // Fixes only (a linear model), noisy DR: the backward correction with a window covering the
  // line is the two-filter fixed-interval smoother of the sequential model, which the filter
  // module's RTS smoother (a different algorithm) must reproduce.
  Input in = straight_line(200, 2.0);
  in.options.sequential_sigma_velocity_m_s = 0.3;
  in.options.backward_window_s = 1e6;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  for (std::size_t k = 0; k < in.truth.size(); k += 7)
    in.fixes.push_back({in.truth[k].time_s, in.truth[k].x_north_m + 8.0 * n(rng),
                        in.truth[k].y_east_m + 8.0 * n(rng), 64.0 * Eigen::Matrix2d::Identity()});
  in.initial = {0.0, 0.0, 20.0};
  const Result r = process(in);

  filter::Estimate<2> init{Eigen::Vector2d(0.0, 0.0), 400.0 * Eigen::Matrix2d::Identity()};
  filter::KalmanFilter<2> kf(init);
  filter::SmootherStorage<2> storage;
  std::size_t f = 0;
  for (std::size_t k = 0; k < in.dr.size(); ++k) {
    if (k > 0) {
      const double dt = in.dr[k].time_s - in.dr[k - 1].time_s;
      const Eigen::Vector2d x =
          kf.estimate().x + dt * Eigen::Vector2d(in.dr[k].v_north_m_s, in.dr[k].v_east_m_s);
      kf.predict_extended(x, Eigen::Matrix2d::Identity(), dt * dt * 0.09 * Eigen::Matrix2d::Identity());
    }
    if (f < in.fixes.size() && in.fixes[f].time_s == in.dr[k].time_s) {
      const Eigen::Vector2d z(in.fixes[f].x_north_m, in.fixes[f].y_east_m);
      kf.update(z, Eigen::Matrix2d::Identity(), in.fixes[f].covariance);
      ++f;
    }
    storage.append(kf.predicted(), kf.transition(), kf.estimate());
  }
  const auto smoothed = filter::rts_smooth(storage);
  const MethodResult& bw = method(r, Method::Backward);
  for (std::size_t k = 0; k < smoothed.size(); ++k) {
    EXPECT_NEAR(bw.track[k].x_north_m, smoothed[k].x(0), 1e-7) << k;
    EXPECT_NEAR(bw.track[k].y_east_m, smoothed[k].x(1), 1e-7) << k;
    EXPECT_NEAR(bw.track[k].covariance(0, 0), smoothed[k].P(0, 0), 1e-9 * smoothed[k].P(0, 0)) << k;
    EXPECT_NEAR(bw.track[k].covariance(0, 1), smoothed[k].P(0, 1), 1e-9 * smoothed[k].P(0, 0)) << k;
  }
  // The forward run (no bias) is the filter.
  const MethodResult& fwd = method(r, Method::SequentialNoBias);
  EXPECT_NEAR(fwd.track.back().x_north_m, kf.estimate().x(0), 1e-9);
}

TEST(NavFixClosure, RemovesAConstantDrBiasBetweenExactFixes) {
  // DR with a constant speed error of +0.5 m/s, exact fixes every 60 s: the error between
  // fixes grows linearly, so distributing each closure linearly in time removes it.
  Input in = straight_line(361, 5.0);
  const double c = std::cos(1.0471975511965976);
  const double s = std::sin(1.0471975511965976);
  for (DrSample& d : in.dr) {
    d.v_north_m_s += 0.5 * c;
    d.v_east_m_s += 0.5 * s;
  }
  for (std::size_t k = 0; k < in.truth.size(); k += 12)
    in.fixes.push_back({in.truth[k].time_s, in.truth[k].x_north_m, in.truth[k].y_east_m,
                        1e-4 * Eigen::Matrix2d::Identity()});
  in.options.sequential_sigma_velocity_m_s = 0.5;
  in.initial = {0.0, 0.0, 1.0};
  const Result r = process(in);
  const MethodResult& fc = method(r, Method::FixClosure);
  const MethodResult& fw = method(r, Method::SequentialBiasI);
  ASSERT_TRUE(fc.errors && fw.errors);
  EXPECT_LT(fc.errors->max_error_m, 0.05);
  EXPECT_GT(fw.errors->max_error_m, 10.0);  // 0.5 m/s over up to 55 s
}

TEST(NavChains, EstimatesARangeOffsetWithItsSigma) {
  // Station A's ranges carry +30 m (an offset of its chain): every method that estimates it
  // recovers it within 3σ, and the smoother with σ below 8 m (6.1 m here).
  SimulationOptions o;
  o.scenario = Scenario::B;
  o.seed = 3;
  o.blunder_probability = 0.0;
  SimulatedLine line = simulate(o);
  line.input.chains.push_back({"A", false, true, 1e-3, 1000.0});
  for (Lop& l : line.input.lops)
    if (l.station == 0) {
      l.value_m += 30.0;
      l.chain = 0;
    }
  const Result r = process(line.input);
  for (Method m : {Method::SequentialNoBias, Method::Backward, Method::Ekf, Method::Rts}) {
    const MethodResult& mr = method(r, m);
    ASSERT_EQ(mr.parameters.size(), 1u) << to_string(m);
    EXPECT_EQ(mr.parameters[0].name, "offset_m");
    EXPECT_LT(std::abs(mr.parameters[0].value - 30.0), 3.0 * mr.parameters[0].sigma)
        << to_string(m) << " " << mr.parameters[0].value << " ± " << mr.parameters[0].sigma;
  }
  EXPECT_LT(method(r, Method::Rts).parameters[0].sigma, 8.0);
  // Without the parameter the same data are worse.
  Input plain = line.input;
  plain.chains.clear();
  for (Lop& l : plain.lops) l.chain = Lop::kNoChain;
  EXPECT_LT(method(r, Method::Rts).errors->rms_m, method(process(plain), Method::Rts).errors->rms_m);
}

TEST(NavScenarios, EveryOutputIsFiniteAndFlagsTheInjectedBlunders) {
  SimulationOptions o;
  o.scenario = Scenario::A;
  o.seed = 9;
  o.fix_interval_s = 300.0;
  const SimulatedLine line = simulate(o);
  const Result r = process(line.input);
  ASSERT_EQ(r.methods.size(), kAllMethods.size());
  for (const MethodResult& m : r.methods)
    for (const TrackPoint& t : m.track) {
      ASSERT_TRUE(std::isfinite(t.x_north_m) && std::isfinite(t.y_east_m)) << to_string(m.method);
      ASSERT_TRUE(t.covariance.allFinite()) << to_string(m.method);
      ASSERT_GT(t.covariance(0, 0), 0.0) << to_string(m.method);
    }
  ASSERT_FALSE(line.blunders.empty());
  // The RTS smoother's filter (w-test) rejects every injected blunder (300–800 m, σ 50 m).
  for (std::size_t b : line.blunders) {
    bool found = false;
    for (const RejectedObservation& x : r.rejected)
      found |= x.method == Method::Ekf && x.kind == RejectedObservation::Kind::Lop && x.index == b;
    EXPECT_TRUE(found) << "blunder " << b;
  }
}

// Bad input ------------------------------------------------------------------------------

std::string field_of(const Input& in) {
  try {
    process(in);
  } catch (const InputError& e) {
    return e.context().field;
  }
  return "(no error)";
}

TEST(NavInitialFix, IsMovedByTheDrToTheFirstEpochAndNotUsedTwice) {
  // Exact DR at 5.5 m/s east from (0, 0) at t = 0; exact fixes at t = −4 s (0, −22) and
  // t = 600 s (0, 3300), σ 1 m; no initial position but the first fix. Moved by the DR to
  // t = 0 the fix is (0, 0): every method is exact and no fix is rejected. The σ at epoch 0
  // are the fix's grown by the DR over 4 s (hand-computed below), not halved by using the
  // fix a second time.
  Input in;
  const double sv = 0.01;  // white σ per velocity component (m/s)
  for (int i = 0; i <= 240; ++i) {
    DrSample d;
    d.time_s = 5.0 * i;
    d.v_east_m_s = 5.5;
    d.covariance = sv * sv * Eigen::Matrix2d::Identity();
    in.dr.push_back(d);
    in.truth.push_back({d.time_s, 0.0, 5.5 * d.time_s});
  }
  in.fixes.push_back({-4.0, 0.0, -22.0, Eigen::Matrix2d::Identity()});
  in.fixes.push_back({600.0, 0.0, 3300.0, Eigen::Matrix2d::Identity()});
  in.initial = {500.0, 500.0, 1.0};  // not used
  in.initial_fix = 0;
  const Result r = process(in);
  EXPECT_TRUE(r.rejected.empty()) << r.rejected.front().reason;
  ASSERT_EQ(r.skipped.size(), 1u);
  EXPECT_EQ(r.skipped[0].index, 0u);
  EXPECT_EQ(r.fixes_used, 1u);
  for (const MethodResult& m : r.methods) {
    ASSERT_TRUE(m.errors) << to_string(m.method);
    EXPECT_LT(m.errors->max_error_m, 1e-6) << to_string(m.method);
  }
  const double dr_var = 1.0 + 16.0 * sv * sv;
  const double seq_var = 1.0 + 16.0 * (sv * sv + 0.4 * 0.4);
  const double ekf_var = dr_var + 16.0 * 1.0;  // + (4 s · σ_W = 1 m/s)²: the bias's share
  EXPECT_NEAR(method(r, Method::DeadReckoning).track[0].covariance(0, 0), dr_var, 1e-12);
  EXPECT_NEAR(method(r, Method::SequentialNoBias).track[0].covariance(1, 1), seq_var, 1e-12);
  EXPECT_NEAR(method(r, Method::Ekf).track[0].covariance(1, 1), ekf_var, 1e-9);
  // A fix after the first epoch is moved back over the DR increments that precede it.
  Input late = in;
  late.fixes[0] = {7.0, 0.0, 38.5, Eigen::Matrix2d::Identity()};
  const Result rl = process(late);
  EXPECT_NEAR(method(rl, Method::DeadReckoning).track[0].y_east_m, 0.0, 1e-12);
  // the increment over (0, 5] s and 2 s of the next interval: independent white noise
  EXPECT_NEAR(method(rl, Method::DeadReckoning).track[0].covariance(1, 1),
              1.0 + (25.0 + 4.0) * sv * sv, 1e-12);
  // Farther before the first epoch than max_reduction_s: an error naming the fix.
  Input early = in;
  early.fixes[0].time_s = -11.0;
  EXPECT_THROW(
      {
        try {
          process(early);
        } catch (const InputError& e) {
          EXPECT_EQ(e.context().field, "fixes[0].time_s");
          throw;
        }
      },
      InputError);
}

TEST(NavBadInput, NamesTheFieldOfEveryInvalidValue) {
  const Input good = [] {
    Input in = straight_line(20, 5.0);
    add_ranges(in, 50.0, 1);
    return in;
  }();
  Input a = good;
  a.dr[3].time_s = a.dr[2].time_s;  // duplicated time
  EXPECT_EQ(field_of(a), "dr[3].time_s");
  Input b = good;
  b.dr[5].time_s += 100.0;
  for (std::size_t k = 6; k < b.dr.size(); ++k) b.dr[k].time_s += 100.0;
  EXPECT_EQ(field_of(b), "dr[5].time_s");  // a gap beyond max_dr_gap_s
  Input c = good;
  c.lops[4].sigma_m = 0.0;
  EXPECT_EQ(field_of(c), "lops[4].sigma_m");
  Input d = good;
  d.lops[2].station = 7;
  EXPECT_EQ(field_of(d), "lops[2].station");
  Input e = good;
  e.dr[1].v_east_m_s = std::nan("");
  EXPECT_EQ(field_of(e), "dr[1].v_east_m_s");
  Input f = good;
  f.options.alpha = 0.0;
  EXPECT_EQ(field_of(f), "options.alpha");
  Input g = good;
  g.dr.resize(1);
  EXPECT_EQ(field_of(g), "dr");
  Input h = good;
  h.fixes.push_back({10.0, 0.0, 0.0, -Eigen::Matrix2d::Identity()});
  EXPECT_EQ(field_of(h), "fixes[0].covariance");
  Input i = good;  // 95 s / 1e-9 s: 9.5e10 bins (std::bad_alloc before)
  i.options.statistics_bin_s = 1e-9;
  EXPECT_EQ(field_of(i), "options.statistics_bin_s");
}

TEST(NavBadInput, SkipsRejectsAndWarnsWhereItCanContinue) {
  Input in = straight_line(240, 5.0);
  add_ranges(in, 50.0, 2);
  // LOPs only in the first 5 and the last 5 minutes: a 10-minute gap of dead reckoning.
  std::vector<Lop> kept;
  for (const Lop& l : in.lops)
    if (l.time_s < 300.0 || l.time_s >= 900.0) kept.push_back(l);
  in.lops = kept;
  // A station on the ship: 0.5 m from the initial position, observed at t = 0 (the
  // direction to it is undefined there); observed 100 m: misclosure 100 − 0.5 m.
  in.initial = {0.0, 0.0, 10.0};
  in.stations.push_back({"ship", 0.5, 0.0});
  in.lops.push_back({0.0, LopType::Range, 3, 0, 100.0, 50.0, Lop::kNoChain});
  // A LOP 3 s before the DR (within max_reduction_s: reduced to epoch 0 with the first
  // sample's velocity, not skipped), one after the end of the DR, a fix 2 km off the track.
  in.lops.push_back({-3.0, LopType::Range, 0, 0,
                     std::hypot(-3.0 * in.dr[0].v_north_m_s - in.stations[0].x_north_m,
                                -3.0 * in.dr[0].v_east_m_s - in.stations[0].y_east_m),
                     50.0, Lop::kNoChain});
  in.lops.push_back({5000.0, LopType::Range, 0, 0, 20000.0, 50.0, Lop::kNoChain});
  in.fixes.push_back({600.0, in.truth[120].x_north_m + 2000.0, in.truth[120].y_east_m,
                      25.0 * Eigen::Matrix2d::Identity()});
  const Result r = process(in);
  ASSERT_EQ(r.skipped.size(), 1u);
  EXPECT_EQ(r.skipped[0].index, in.lops.size() - 1);
  EXPECT_NE(r.skipped[0].reason.find("outside the dead-reckoning span"), std::string::npos);
  bool ship = false;
  bool fix = false;
  for (const RejectedObservation& x : r.rejected) {
    EXPECT_FALSE(x.kind == RejectedObservation::Kind::Lop && x.index == in.lops.size() - 2) << x.reason;
    const bool at_station = x.kind == RejectedObservation::Kind::Lop && x.index == in.lops.size() - 3;
    if (at_station) {
      EXPECT_NEAR(x.misclosure_m, 99.5, 1e-9) << "observed − computed, not 0";
    }
    ship |= at_station && x.reason.find("within 1 m of a station") != std::string::npos;
    fix |= x.kind == RejectedObservation::Kind::Fix && x.index == 0 && x.misclosure_m > 1900.0;
  }
  EXPECT_TRUE(ship);
  EXPECT_TRUE(fix);
  EXPECT_TRUE(method(r, Method::Ekf).track[120].flags & kFlaggedFix);
  bool gap = false;
  for (const std::string& w : r.warnings) gap |= w.find("no observation used by") != std::string::npos;
  EXPECT_TRUE(gap);
}

TEST(NavPresentation, ThresholdReasonsAndWhatTheSigmaMean) {
  // A LOP 432.9 m short at t = 300 s, exact DR and σ 1 m ranges otherwise: the threshold
  // rejects it with |misclosure| in the reason and the signed value in misclosure_m.
  Input in = straight_line(121, 5.0);
  add_ranges(in, 1.0, 5, 30.0);
  in.options.rejection = Rejection::Threshold;
  in.initial = {0.0, 0.0, 1.0};
  for (Lop& l : in.lops)
    if (l.time_s == 300.0 && l.station == 0) l.value_m -= 432.9;
  const Result r = process(in);
  bool seen = false;
  for (const RejectedObservation& x : r.rejected) {
    if (x.method != Method::SequentialBiasI) continue;
    seen = true;
    EXPECT_NEAR(x.misclosure_m, -432.9, 5.0);
    EXPECT_EQ(x.reason.rfind("|misclosure| 43", 0), 0u) << x.reason;
    EXPECT_NE(x.reason.find(" m > 100 m"), std::string::npos) << x.reason;
  }
  EXPECT_TRUE(seen);
  // The notes say which σ are rigorous.
  std::string notes;
  for (const std::string& n : r.notes) notes += n + "\n";
  EXPECT_NE(notes.find("σ of dead-reckoning: the white noise of the DR samples only"), std::string::npos);
  EXPECT_NE(notes.find("-bias-II, backward and fix-closure: not rigorous"), std::string::npos);
  EXPECT_NE(notes.find("σ of ekf and rts: rigorous under their model"), std::string::npos);
}

}  // namespace
}  // namespace meridian::nav
