// Maglev gyro: wavelet denoising of 10^6 samples (db4, 6 levels, soft universal threshold,
// symmetric extension — compared with PyWavelets by bench/pywt_denoise_timing.py on the same
// machine), reading a 10^6-line CSV, and a whole 40 000-sample two-position determination.
//   build/bench/bench_maglev --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "meridian/io/maglev_files.hpp"
#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/reduce.hpp"
#include "meridian/maglev/simulator.hpp"

namespace {
namespace mg = meridian::maglev;

const std::vector<double>& million() {
  static const std::vector<double> x = [] {
    mg::NoiseSpec s;
    s.samples = 1000000;
    s.white_sigma_A = 1e-5;
    s.ar1_phi = 0.8;
    s.ar1_sigma_A = 2e-6;
    return mg::simulate_series(0.01, s, 42).current_A;
  }();
  return x;
}

void Denoise1M(benchmark::State& state) {
  const auto& x = million();
  mg::DenoiseOptions o;
  o.wavelet_order = 4;
  o.level = 6;
  o.mode = mg::ExtensionMode::Symmetric;
  for (auto _ : state) {
    auto r = mg::denoise(x, o);
    benchmark::DoNotOptimize(r.values.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(x.size()));
}
BENCHMARK(Denoise1M)->Unit(benchmark::kMillisecond);

void ReadCsv1M(benchmark::State& state) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("meridian_bench_maglev_" + std::to_string(::getpid()) + ".csv");
  {
    mg::NoiseSpec s;
    s.samples = 1000000;
    std::ofstream(path) << meridian::io::maglev_series_csv(mg::simulate_series(0.01, s, 1));
  }
  for (auto _ : state) {
    auto f = meridian::io::read_maglev_series_file(path.string());
    benchmark::DoNotOptimize(f.series.current_A.data());
  }
  std::filesystem::remove(path);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 1000000);
}
BENCHMARK(ReadCsv1M)->Unit(benchmark::kMillisecond);

void Determination40k(benchmark::State& state) {
  mg::TwoPositionTruth t;
  t.alpha1_rad = 0.02;
  mg::NoiseSpec s;
  s.samples = 20000;
  s.white_sigma_A = 1e-5;
  s.ar1_phi = 0.8;
  s.ar1_sigma_A = 2e-6;
  mg::NoiseSpec d = s;
  d.bursts.push_back({63.0, 103.0, 2e-3, 6e-4, 0.5, 8.0});
  const auto in = mg::simulate_determination(t, d, s, 7);
  for (auto _ : state) {
    auto r = mg::process(in);
    benchmark::DoNotOptimize(r.processed.alpha1_rad.value);
  }
}
BENCHMARK(Determination40k)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
