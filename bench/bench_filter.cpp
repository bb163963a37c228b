// Google Benchmark of the estimation core on the deflection model's shape (8 states, 2
// observations, docs/filter.md): the forward filter alone, forward filter + RTS smoother with
// the records in memory and spilled to disk, and the peak memory of a 10⁷-epoch line on the
// spill path (`--spill-line=10000000`, see main()). Figures and the commands that produce them:
// docs/benchmarks.md.
//
// Observations are simulated once (4096 epochs of the model, reused cyclically) so the loop
// measures the filter, not the random number generator.
#include <sys/resource.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "example_models.hpp"
#include "meridian/filter/discretisation.hpp"
#include "meridian/filter/kalman_filter.hpp"
#include "meridian/filter/rts_smoother.hpp"
#include "meridian/filter/smoother_storage.hpp"

namespace {

using namespace meridian::filter;
using namespace meridian::filter::examples;
constexpr int N = DovState::size;
constexpr int M = DovObservation::size;

struct Scenario {
  DiscreteModel<N> step;
  Matrix<M, N> H;
  Matrix<M, M> R;
  Estimate<N> initial;
  std::vector<Vector<M>> z;
};

const Scenario& scenario() {
  static const Scenario s = [] {
    const DovParameters p;
    Scenario out{discretise(dov_model(p), 0.1),
                 dov_observation_matrix(),
                 dov_observation_covariance(p),
                 dov_initial(p),
                 {}};
    std::mt19937_64 rng(1);
    Vector<N> truth = out.initial.x + draw<N>(out.initial.P, rng);
    for (int k = 0; k < 4096; ++k) {
      if (k > 0) truth = out.step.phi * truth + draw<N>(out.step.q, rng);
      out.z.push_back(out.H * truth + draw<M>(out.R, rng));
    }
    return out;
  }();
  return s;
}

// The forward filter over `epochs`, each epoch appended to `storage` when given: in the compact
// layout (append(filter), P⁻ recomputed by the backward pass) or the full one (P⁻ stored).
void forward(std::int64_t epochs, SmootherStorage<N>* storage, bool compact = true) {
  const Scenario& s = scenario();
  KalmanFilter<N> kf(s.initial);
  const std::size_t cycle = s.z.size();
  for (std::int64_t k = 0; k < epochs; ++k) {
    if (k > 0) kf.predict(s.step);
    kf.update(s.z[static_cast<std::size_t>(k) % cycle], s.H, s.R);
    if (storage == nullptr) continue;
    if (compact)
      storage->append(kf);
    else
      storage->append(kf.predicted(), kf.transition(), kf.estimate());
  }
  benchmark::DoNotOptimize(kf.estimate().x.data());
}

// Forward + RTS; the sink keeps the sum of the smoothed δη so nothing is optimised away.
double forward_and_smooth(std::int64_t epochs, const StorageOptions& options, bool compact) {
  SmootherStorage<N> storage(N, options);
  forward(epochs, &storage, compact);
  double sum = 0.0;
  rts_smooth(storage, [&](Eigen::Index, const Estimate<N>& e) { sum += e.x(DovState::delta_eta); });
  return sum;
}

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss in KiB on Linux
}

void BM_Forward(benchmark::State& state) {
  for (auto _ : state) forward(state.range(0), nullptr);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_Forward)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

// Records in memory (no limit), Φ constant (stored once); argument 1: compact records (424
// bytes per epoch, P⁻ recomputed in the backward pass), 0: full records (712 bytes, P⁻ stored).
void BM_ForwardRtsMemory(benchmark::State& state) {
  StorageOptions options;
  options.memory_limit_bytes = std::numeric_limits<std::size_t>::max();
  for (auto _ : state)
    benchmark::DoNotOptimize(forward_and_smooth(state.range(0), options, state.range(1) != 0));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_ForwardRtsMemory)
    ->ArgNames({"epochs", "compact"})
    ->Args({100'000, 1})
    ->Args({100'000, 0})
    ->Unit(benchmark::kMillisecond);

// Default options: records beyond 32 MB go to the spill file
// (std::filesystem::temp_directory_path()); compact or full records as above.
void BM_ForwardRtsSpill(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(forward_and_smooth(state.range(0), {}, state.range(1) != 0));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_ForwardRtsSpill)
    ->ArgNames({"epochs", "compact"})
    ->Args({1'000'000, 1})
    ->Args({1'000'000, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace

// `bench_filter --spill-line=EPOCHS`: instead of the benchmarks, one forward + RTS pass over a
// line of EPOCHS epochs with the default storage options (records beyond 32 MB spilled to a
// temporary file, compact records of 424 bytes per epoch; `--full` for the 712-byte records),
// printing the wall time, epochs per second, the spill
// file's size and the process's peak resident memory (getrusage ru_maxrss) — the peak memory
// measurement of docs/benchmarks.md, run in a process of its own.
int main(int argc, char** argv) {
  const std::string flag = "--spill-line=";
  bool compact = true;
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--full") compact = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind(flag, 0) != 0) continue;
    const std::int64_t epochs = std::stoll(arg.substr(flag.size()));
    scenario();  // simulate the observations before the clock starts
    const auto t0 = std::chrono::steady_clock::now();
    SmootherStorage<N> storage(N, StorageOptions{});
    forward(epochs, &storage, compact);
    const auto t1 = std::chrono::steady_clock::now();
    double sum = 0.0;
    rts_smooth(storage,
               [&](Eigen::Index, const Estimate<N>& e) { sum += e.x(DovState::delta_eta); });
    const auto t2 = std::chrono::steady_clock::now();
    const double fwd_s = std::chrono::duration<double>(t1 - t0).count();
    const double rts_s = std::chrono::duration<double>(t2 - t1).count();
    std::printf("epochs %lld  forward %.2f s  rts %.2f s  total %.2f s  %.0f epochs/s\n",
                static_cast<long long>(epochs), fwd_s, rts_s, fwd_s + rts_s,
                static_cast<double>(epochs) / (fwd_s + rts_s));
    std::printf("%s records  spilled %s  file %.1f MB  peak RSS %.1f MB  (checksum %.3e)\n",
                compact ? "compact" : "full", storage.spilled() ? "yes" : "no", static_cast<double>(storage.file_bytes()) / 1e6,
                peak_rss_mb(), sum);
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
