// The full stochastic comparison of one reversal series (white noise, three covariance
// functions, Markov-1 and Markov-2 on the grid and by maximum restricted likelihood, VCE to
// convergence at every ρ): target well under 100 ms for 20 reversal points.
//   build/bench/bench_gyro_stochastic

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "meridian/adjust/two_component_reml.hpp"
#include "meridian/adjust/variance_components.hpp"
#include "meridian/core/error.hpp"
#include "meridian/gyro/markov_covariance.hpp"
#include "meridian/gyro/stochastic.hpp"

namespace {

using namespace meridian::gyro;

std::vector<double> series(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> N(0.0, 1.0);
  const MarkovFactors f = markov1_factors(n, 0.6);
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d(i) = 2.0 * N(rng);
  const Eigen::VectorXd l =
      reversal_design(n) * Eigen::Vector3d(754.0, 4800.0, 3.0) + f.C * d + f.B * (5.0 * N(rng));
  return {l.data(), l.data() + n};
}

void FullComparison(benchmark::State& state) {
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // arcsec-sized numbers, fitted as given
  in.readings = series(static_cast<int>(state.range(0)), 3);
  for (auto _ : state) benchmark::DoNotOptimize(analyse_stochastic(in));
  state.SetLabel("all models, ML and grids");
}
BENCHMARK(FullComparison)->Arg(20)->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);

void Markov1Only(benchmark::State& state) {
  StochasticInput in;
  in.kind = SeriesKind::Scale;  // arcsec-sized numbers, fitted as given
  in.readings = series(static_cast<int>(state.range(0)), 3);
  in.options.covariance_functions = false;
  in.options.markov2 = false;
  for (auto _ : state) benchmark::DoNotOptimize(analyse_stochastic(in));
}
BENCHMARK(Markov1Only)->Arg(20)->Unit(benchmark::kMillisecond);

// The inner step of the ρ searches, side by side: the maximum of the restricted likelihood over
// (σ_1², σ_2²) at each stationary point of the 19×19 Markov-2 grid, by the iterated VCE from the
// OLS variance (the reference; what the search did before) and in closed form (what it does).
template <bool kClosedForm>
void Markov2GridStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const auto r = series(n, 3);
  const Eigen::VectorXd l = Eigen::Map<const Eigen::VectorXd>(r.data(), n);
  const Eigen::MatrixXd G = reversal_design(n);
  std::vector<MarkovFactors> grid;
  for (int a = -9; a <= 9; ++a)
    for (int b = -9; b <= 9; ++b)
      if (ar2_stationary(0.1 * a, 0.1 * b)) grid.push_back(markov2_factors(n, 0.1 * a, 0.1 * b));
  const double s0sq =
      meridian::adjust::solve_linear(
          G, l, meridian::adjust::CovarianceFactor::diagonal(Eigen::VectorXd::Ones(n)))
          .vtpv /
      (n - 3);
  for (auto _ : state) {
    double sum = 0.0;
    for (const auto& f : grid) {
      const meridian::adjust::VarianceComponent c1{"sigma1^2", f.C}, c2{"sigma2^2", f.B};
      try {
        if constexpr (kClosedForm) {
          sum += meridian::adjust::maximise_two_component_reml(G, l, c1, c2).reml;
        } else {
          meridian::adjust::VceOptions o;
          o.details = false;
          o.initial = Eigen::Vector2d(s0sq, s0sq);
          sum += meridian::adjust::estimate_variance_components(G, l, {c1, c2}, o).likelihood.reml;
        }
      } catch (const meridian::Error&) {
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["points"] = static_cast<double>(grid.size());
}
BENCHMARK_TEMPLATE(Markov2GridStep, false)
    ->Name("Markov2Grid/IteratedVce")
    ->Arg(20)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(Markov2GridStep, true)
    ->Name("Markov2Grid/ClosedForm")
    ->Arg(20)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
