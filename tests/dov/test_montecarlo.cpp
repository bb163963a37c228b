// Monte Carlo validation of the dov workflow's reported σ (label `montecarlo`: the Release pass
// of scripts/test.sh runs it, the sanitizer pass does not build it). §7 typical errors
// (σ_model 3″, r 0.5″, V 5 m/s, 1 Hz, 4 h) over 50 seeds, each with its initial LGU errors and
// ε_U drawn from P₀ (φ 2″, 2″, 5″; ε_U 0.003°/h) so the truth is a draw from the filter's own
// prior. Checked every 10 min (25 epochs, far apart compared with the errors' correlation):
// the ensemble-average NEES (8 states, filtered and smoothed) and NIS per epoch against their
// exact 95 % intervals, and the smoothed η, ξ errors against the reported σ. A filter that
// assumes half the true model σ fails the same check (the test can fail).
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "dov_test_support.hpp"
#include "meridian/dov/deflection.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/filter/consistency.hpp"

namespace {

using namespace meridian::dov;
using meridian::filter::ConsistencyRun;
using meridian::filter::MonteCarloConsistency;
namespace units = meridian::units;
using meridian_test::kAs;
constexpr int kSeeds = 50;
constexpr double kCheckEvery_s = 600.0;

struct Ensemble {
  MonteCarloConsistency filtered, smoothed;
  double mean_normalised_sq_smoothed = 0.0;  ///< mean of (error/σ)² of smoothed η, ξ
  double mean_normalised_sq_filtered = 0.0;
  std::size_t values = 0;
};

Ensemble run(double duration_s, double assumed_sigma_model_as) {
  std::vector<ConsistencyRun> filtered, smoothed;
  double sum_s = 0.0, sum_f = 0.0;
  std::size_t values = 0;
  for (int r = 0; r < kSeeds; ++r) {
    std::mt19937_64 rng(9000 + static_cast<std::uint64_t>(r));
    std::normal_distribution<double> nd;
    SimulationOptions so;
    so.duration_s = duration_s;
    so.seed = 100 + static_cast<std::uint64_t>(r);
    const InitialSigmas prior;
    so.initial_attitude_error_rad = Eigen::Vector3d(
        prior.phi_e_rad * nd(rng), prior.phi_n_rad * nd(rng), prior.phi_u_rad * nd(rng));
    so.eps_u_rad_s = prior.eps_u_rad_s * nd(rng);
    Input in = simulate(so);
    in.options.model.sigma_model_rad = assumed_sigma_model_as * kAs;
    const Result res = process(in);
    ConsistencyRun f, s;
    for (std::size_t k = 0; k < res.epochs.size(); ++k) {
      const EpochResult& e = res.epochs[k];
      if (std::fmod(e.time_s - res.epochs.front().time_s, kCheckEvery_s) != 0.0) continue;
      f.nees.push_back(*e.nees_filtered);
      f.nis.push_back(e.nis);
      s.nees.push_back(*e.nees_smoothed);
      const Truth& t = in.truth[k];
      const auto sq = [](double v) { return v * v; };
      sum_s += sq((e.smoothed.eta_rad - t.eta_rad) / e.smoothed.sigma_eta_rad) +
               sq((e.smoothed.xi_rad - t.xi_rad) / e.smoothed.sigma_xi_rad);
      sum_f += sq((e.filtered.eta_rad - t.eta_rad) / e.filtered.sigma_eta_rad) +
               sq((e.filtered.xi_rad - t.xi_rad) / e.filtered.sigma_xi_rad);
      values += 2;
    }
    filtered.push_back(std::move(f));
    smoothed.push_back(std::move(s));
  }
  Ensemble out;
  out.filtered = meridian::filter::summarise_consistency(filtered, State::size, Obs::size);
  out.smoothed = meridian::filter::summarise_consistency(smoothed, State::size, Obs::size);
  out.mean_normalised_sq_smoothed = sum_s / static_cast<double>(values);
  out.mean_normalised_sq_filtered = sum_f / static_cast<double>(values);
  out.values = values;
  return out;
}

void print(const char* name, const Ensemble& e) {
  std::printf(
      "%s: NEES filtered: %.0f %% of epochs inside [%.2f, %.2f], overall %.2f; smoothed: %.0f %% "
      "inside, overall %.2f; NIS: %.0f %% inside [%.2f, %.2f], overall %.3f; mean (e/σ)² of "
      "η, ξ: filtered %.3f, smoothed %.3f (%zu values)\n",
      name, 100.0 * e.filtered.nees.fraction_inside, e.filtered.nees.epoch_interval.lower,
      e.filtered.nees.epoch_interval.upper, e.filtered.nees.overall_average,
      100.0 * e.smoothed.nees.fraction_inside, e.smoothed.nees.overall_average,
      100.0 * e.filtered.nis.fraction_inside, e.filtered.nis.epoch_interval.lower,
      e.filtered.nis.epoch_interval.upper, e.filtered.nis.overall_average,
      e.mean_normalised_sq_filtered, e.mean_normalised_sq_smoothed, e.values);
}

TEST(DovMonteCarlo, NeesAndSigmaConsistentOver50Seeds) {
  const Ensemble e = run(4.0 * 3600.0, 3.0);
  print("correct model (σ_model 3″), 50 × 4 h", e);
  // each epoch's ensemble average is inside its exact 95 % interval with probability 0.95:
  // with 25 epochs, fewer than 80 % inside has probability < 0.01 for a correct filter
  EXPECT_GE(e.filtered.nees.fraction_inside, 0.8);
  EXPECT_GE(e.smoothed.nees.fraction_inside, 0.8);
  EXPECT_GE(e.filtered.nis.fraction_inside, 0.8);
  EXPECT_TRUE(e.filtered.nis.overall_inside());
  // Monte Carlo σ vs scatter: the mean of (error/σ)² over 2500 values is 1 ± 0.06 (95 %) for
  // independent values; 0.15 allows for the remaining correlation between epochs
  EXPECT_NEAR(e.mean_normalised_sq_smoothed, 1.0, 0.15);
  EXPECT_NEAR(e.mean_normalised_sq_filtered, 1.0, 0.15);
}

TEST(DovMonteCarlo, OptimisticModelFails) {
  const Ensemble e = run(3600.0, 1.5);  // the filter assumes 1.5″ for a 3″ truth
  print("optimistic model (σ_model 1.5″), 50 × 1 h", e);
  EXPECT_LT(e.smoothed.nees.fraction_inside, 0.5);
  EXPECT_GT(e.mean_normalised_sq_smoothed, 1.5);
}

}  // namespace
