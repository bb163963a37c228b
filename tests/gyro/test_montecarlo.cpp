// Monte Carlo validation of every estimator over several observing geometries
// (issue 15; spec §8.3): for each method, over kRuns independent simulated
// determinations,
//   * the mean error is within 3 standard errors of zero (exact methods) or
//     of the method's own computed approximation error (transit,
//     time-difference: mean of error − approximation error within 3 SE);
//   * the reported σ (mean over the runs) is within 10 % of the empirical
//     scatter of the estimates.
// The data come from the product's simulator (exact roots of (N1), (R1)) with
// white noise; the truth is the simulator's input. kRuns = 600: the standard
// error of an empirical σ is σ/sqrt(2n) = 2.9 %, so a σ 10 % off is 3.5
// standard errors away and the 25 % of the old timed-amplitude II fails
// outright. Deterministic seeds. CTest label `montecarlo` (ASan pass skips it).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "meridian/core/angle.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/nontracking.hpp"
#include "meridian/gyro/reversal.hpp"
#include "meridian/gyro/simulator.hpp"
#include "meridian/gyro/tracking.hpp"
#include "meridian/gyro/unified_fit.hpp"
#include "meridian/gyro/zero_position.hpp"

namespace {

using namespace meridian;
using namespace meridian::gyro;

constexpr int kRuns = 600;

// Errors of one method over the runs: e = estimate − truth, d = e − the
// method's approximation error, s = reported σ (all in one unit).
struct Sample {
  int n = 0;
  double sum_e = 0, sum_e2 = 0, sum_d = 0, sum_d2 = 0, sum_s = 0;
  void add(double e, double approx, double s) {
    ++n;
    sum_e += e;
    sum_e2 += e * e;
    sum_d += e - approx;
    sum_d2 += (e - approx) * (e - approx);
    sum_s += s;
  }
  double mean() const { return sum_e / n; }
  double scatter() const { return std::sqrt((sum_e2 - n * mean() * mean()) / (n - 1)); }
  double mean_d() const { return sum_d / n; }
  double se_d() const { return std::sqrt((sum_d2 - n * mean_d() * mean_d()) / (n - 1) / n); }
  double reported() const { return sum_s / n; }
};

// The assertions of the header, and one line of the table (values × unit).
void check(const std::string& where, const std::string& method, const Sample& s, double unit,
           const char* unit_name) {
  ASSERT_EQ(s.n, kRuns) << where << " " << method << ": the method failed in some runs";
  const double ratio = s.reported() / s.scatter();
  std::printf(
      "  %-34s %-18s mean error %+7.3f ± %5.3f%s (approx. %+7.3f)  σ reported %6.3f  "
      "empirical %6.3f  ratio %.3f\n",
      where.c_str(), method.c_str(), s.mean() * unit, s.se_d() * unit, unit_name,
      (s.mean() - s.mean_d()) * unit, s.reported() * unit, s.scatter() * unit, ratio);
  EXPECT_LT(std::abs(s.mean_d()), 3.0 * s.se_d()) << where << " " << method << ": biased";
  EXPECT_NEAR(ratio, 1.0, 0.10) << where << " " << method << ": reported σ against the scatter";
}

// ---------------------------------------------------------------------------
// Non-tracking

struct Geometry {
  std::string name;
  double beta_div = -0.12;
  std::vector<double> levels_div{-2.0, 0.0, 2.0};
  int crossings = 3;
  int reversals = 2;
  bool known_period = true;
  double noise_scale = 1.0;       // × (σ_t 0.1 s, σ_a 0.05 div)
  std::set<std::string> methods;  // expected to apply in every run
};

void run_nontracking(const Geometry& g, std::uint64_t seed) {
  Instrument inst;  // (1+λ)·τ = 780″/div converts β to ΔN in the table
  inst.scale_value_rad = 600.0 * units::kArcsecond;
  inst.torsion_ratio = {0.30, 0.0};
  NonTrackingSimulation sim;  // the simulator's defaults: B 9 div, T_B 440 s, t0 50 s, k 0
  sim.beta_div = g.beta_div;
  sim.amplitude_div = 9.0;
  sim.period_s = 440.0;
  sim.t0_s = 50.0;
  sim.levels_div = g.levels_div;
  sim.crossings_per_level = g.crossings;
  sim.reversals = g.reversals;
  sim.record_reversal_times = false;  // as `gyro simulate` writes them
  sim.time_noise = NoiseModel::white(0.1 * g.noise_scale);
  sim.reading_noise = NoiseModel::white(0.05 * g.noise_scale);
  if (g.known_period) sim.known_period_s = sim.period_s;

  UnifiedFitOptions fit_only;
  fit_only.compare_simple_methods = false;
  std::map<std::string, Sample> samples;
  for (int run = 0; run < kRuns; ++run) {
    const NonTrackingObservations obs =
        simulate_nontracking(sim, seed + static_cast<std::uint64_t>(run));
    for (NonTrackingMethod m : applicable_methods(obs)) {
      const BetaResult r = m == NonTrackingMethod::LeastSquares
                               ? fit_nontracking(obs, inst, fit_only).as_beta_result()
                               : reduce_nontracking(m, obs, inst);
      samples[to_string(m)].add(r.beta_div.value - g.beta_div, r.approximation_error_div,
                                r.beta_div.sigma);
    }
  }
  std::set<std::string> found;
  for (const auto& [name, s] : samples) found.insert(name);
  EXPECT_EQ(found, g.methods) << g.name;
  for (const auto& [name, s] : samples) check(g.name, name, s, 780.0, "″");
}

const std::set<std::string> kAllSix{"transit",           "time-difference",   "direct",
                                    "timed-amplitude-1", "timed-amplitude-2", "lsq"};

// The case: the simulator's defaults (levels −2/0/+2 div, 3 crossings
// each, 2 reversals, T_B known, β −0.12 div), and 10× less noise.
TEST(MonteCarloNonTracking, SimulatorDefaults) {
  run_nontracking({"β −0.12, levels −2/0/+2", -0.12, {-2.0, 0.0, 2.0}, 3, 2, true, 1.0, kAllSix},
                  20260100);
  run_nontracking({"β −0.12, noise ÷10", -0.12, {-2.0, 0.0, 2.0}, 3, 2, true, 0.1, kAllSix},
                  20260200);
}

// β far west and east of the clamp (the time-difference error grows with β).
TEST(MonteCarloNonTracking, BetaEitherSide) {
  run_nontracking({"β −0.8, levels −2/0/+2", -0.8, {-2.0, 0.0, 2.0}, 3, 2, true, 1.0, kAllSix},
                  20260300);
  run_nontracking({"β +0.5, levels −2/0/+2", 0.5, {-2.0, 0.0, 2.0}, 3, 2, true, 1.0, kAllSix},
                  20260400);
  // Level 0 listed first at β = 0: timed-amplitude II's pair is level 0 and
  // levels ±2 are exactly equally conditioned; the time-difference level pair
  // with level 0 on the centre.
  run_nontracking({"β 0, levels 0/+2/−2", 0.0, {0.0, 2.0, -2.0}, 3, 2, true, 1.0, kAllSix},
                  20260500);
}

// Other graduations and other sets of passages.
TEST(MonteCarloNonTracking, LevelsAndPassages) {
  run_nontracking({"β −0.12, levels −3/+3",
                   -0.12,
                   {-3.0, 3.0},
                   3,
                   2,
                   true,
                   1.0,
                   {"time-difference", "direct", "timed-amplitude-1", "timed-amplitude-2", "lsq"}},
                  20260600);
  run_nontracking({"β −0.12, level 0 only",
                   -0.12,
                   {0.0},
                   3,
                   2,
                   true,
                   1.0,
                   {"transit", "timed-amplitude-1", "lsq"}},
                  20260700);
  run_nontracking({"β −0.12, 2 crossings per level",
                   -0.12,
                   {-2.0, 0.0, 2.0},
                   2,
                   2,
                   true,
                   1.0,
                   {"timed-amplitude-1", "timed-amplitude-2", "lsq"}},
                  20260800);
  run_nontracking({"β −0.12, no reversal readings",
                   -0.12,
                   {-2.0, 0.0, 2.0},
                   3,
                   0,
                   true,
                   1.0,
                   {"time-difference", "direct", "timed-amplitude-2", "lsq"}},
                  20260900);
}

// T_B not given: transit takes t3 − t1 (5 transits: least squares), the fit
// estimates T_B.
TEST(MonteCarloNonTracking, PeriodUnknown) {
  run_nontracking({"β −0.12, T_B unknown",
                   -0.12,
                   {-2.0, 0.0, 2.0},
                   3,
                   2,
                   false,
                   1.0,
                   {"transit", "time-difference", "lsq"}},
                  20261000);
  run_nontracking(
      {"β −0.12, 5 transits, T_B unknown", -0.12, {0.0}, 5, 3, false, 1.0, {"transit", "lsq"}},
      20261100);
}

// ---------------------------------------------------------------------------
// Tracking (spec §8.4 geometry) and motor-off zero-position runs: (R1) with
// white reading noise, 5 reversals.

constexpr ReversalMethod kThreePoint[] = {ReversalMethod::Schuler, ReversalMethod::LinearLsq,
                                          ReversalMethod::NonlinearLsq};

TEST(MonteCarloTracking, StatedReadingSigma) {
  TrackingSimulation sim;
  sim.centre_rad = (12.0 * 60.0 + 34.0) * units::kArcsecond;  // M = 0°12′34″
  sim.amplitude_rad = 8.0 * 600.0 * units::kArcsecond;        // A = 8 div·τ
  sim.kappa = 0.002;
  sim.reversals = 5;
  sim.reading_noise = NoiseModel::white(8.0 * units::kArcsecond);
  Instrument inst;
  inst.scale_value_rad = 600.0 * units::kArcsecond;
  inst.torsion_ratio = {0.30, 0.0};
  std::map<std::string, Sample> stated, free;
  std::map<std::string, int> rejected;
  for (int run = 0; run < kRuns; ++run) {
    TrackingObservations obs;
    obs.reversals_rad = simulate_tracking(sim, 20262000 + static_cast<std::uint64_t>(run));
    for (ReversalMethod m : kThreePoint) {
      obs.sigma_reading_rad = 8.0 * units::kArcsecond;
      const TrackingResult r = reduce_tracking(m, obs, inst);
      stated[to_string(m)].add(wrap_signed_rad(r.north.north_rad - sim.centre_rad), 0.0,
                               r.north.sigma_rad);
      ASSERT_TRUE(r.fit.reading_sigma_test);
      rejected[to_string(m)] += r.fit.reading_sigma_test->rejected ? 1 : 0;
      obs.sigma_reading_rad = std::nan("");
      const TrackingResult a = reduce_tracking(m, obs, inst);
      free[to_string(m)].add(wrap_signed_rad(a.north.north_rad - sim.centre_rad), 0.0,
                             a.north.sigma_rad);
    }
  }
  for (const auto& [name, s] : stated) {
    check("tracking, 5 reversals, σ 8″ stated", name, s, 1.0 / units::kArcsecond, "″");
    // The global test at α = 1 % rejects about 1 % of the runs under H0
    // (binomial 6 ± 2.4 of 600).
    std::printf("  %-34s %-18s global test rejected %d of %d runs\n",
                "tracking, 5 reversals, σ 8″ stated", name.c_str(), rejected[name], kRuns);
    EXPECT_LE(rejected[name], 15) << name;
    EXPECT_GE(rejected[name], 1) << name;
  }
  // Without a stated σ the a-posteriori σ̂0·sqrt(q) is reported; with 2
  // degrees of freedom its mean is E[χ_2]/sqrt(2)·σ = (sqrt(π)/2)·σ = 0.886 σ
  // — why the a-priori σ is used when it is known.
  for (const auto& [name, s] : free) {
    const double ratio = s.reported() / s.scatter();
    std::printf("  %-34s %-18s σ reported %6.3f″ (a posteriori)  empirical %6.3f″  ratio %.3f\n",
                "tracking, 5 reversals, no σ stated", name.c_str(),
                s.reported() / units::kArcsecond, s.scatter() / units::kArcsecond, ratio);
    EXPECT_NEAR(ratio, std::sqrt(units::kPi) / 2.0, 0.06) << name;
  }
}

TEST(MonteCarloZeroPosition, InstrumentReadingSigma) {
  // As the campaign simulator's motor-off runs: A ≈ 6.5 div, κ = 0.01.
  std::map<std::string, Sample> samples;
  for (int run = 0; run < kRuns; ++run) {
    ZeroPositionRun zr;
    zr.reversals_div = simulate_zero_position(0.2, 6.5, 0.01, 5, NoiseModel::white(0.05),
                                              20263000 + static_cast<std::uint64_t>(run));
    for (ReversalMethod m : kThreePoint) {
      const ZeroPositionEstimate e = estimate_zero_position(zr, m, 0.05);
      samples[to_string(m)].add(e.fit.centre.value - 0.2, 0.0, e.fit.centre.sigma);
    }
  }
  for (const auto& [name, s] : samples) check("zero position, 5 reversals", name, s, 1.0, " div");
}

}  // namespace
