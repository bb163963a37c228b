// The full stochastic comparison of one reversal series (white noise, three covariance
// functions, Markov-1 and Markov-2 on the grid and by maximum restricted likelihood, VCE to
// convergence at every ρ): target well under 100 ms for 20 reversal points.
//   build/bench/bench_gyro_stochastic

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

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
  in.readings = series(static_cast<int>(state.range(0)), 3);
  for (auto _ : state) benchmark::DoNotOptimize(analyse_stochastic(in));
  state.SetLabel("all models, ML and grids");
}
BENCHMARK(FullComparison)->Arg(20)->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);

void Markov1Only(benchmark::State& state) {
  StochasticInput in;
  in.readings = series(static_cast<int>(state.range(0)), 3);
  in.options.covariance_functions = false;
  in.options.markov2 = false;
  for (auto _ : state) benchmark::DoNotOptimize(analyse_stochastic(in));
}
BENCHMARK(Markov1Only)->Arg(20)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
