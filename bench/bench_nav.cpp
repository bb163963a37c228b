// Marine navigation: the line — 10 hours of DR at 1 Hz with range LOPs from three
// stations every 5 s (36 001 epochs, 21 603 LOPs) — through every method including both
// smoothers (nav::process), and its parts.
//   build/bench/bench_nav --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "meridian/nav/navigation.hpp"
#include "meridian/nav/simulator.hpp"

namespace {
namespace nv = meridian::nav;

const nv::Input& ten_hours() {
  static const nv::Input in = [] {
    nv::SimulationOptions o;
    o.scenario = nv::Scenario::A;
    o.seed = 42;
    o.duration_s = 36000.0;
    o.step_s = 1.0;
    o.lop_interval_s = 5.0;
    return nv::simulate(o).input;
  }();
  return in;
}

void NavProcessTenHours(benchmark::State& state) {
  const nv::Input& in = ten_hours();
  for (auto _ : state) {
    nv::Result r = nv::process(in);
    benchmark::DoNotOptimize(r.methods.data());
  }
  state.counters["epochs"] = static_cast<double>(in.dr.size());
  state.counters["epochs_per_s"] =
      benchmark::Counter(static_cast<double>(in.dr.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(NavProcessTenHours)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
