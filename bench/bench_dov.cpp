// Dynamic deflection of the vertical: filter + RTS smoother over a long simulated line, read
// from the binary line format and from CSV through the streaming runner (io::run_dov_stream,
// as `meridian dov process --json` runs it: no profile written), from memory (the numerics
// alone), and the two readers alone. Epochs per CPU second of the benchmark's thread (the
// workflow is single-threaded) as a counter: the machine is shared, so wall time is not used.
//   MERIDIAN_BENCH_DOV_EPOCHS=360000 build/bench/bench_dov --benchmark_repetitions=3
// The line (1 h at 100 Hz by default; spec §7 errors, V = 5 m/s) is simulated once and written
// to a temporary directory, removed at exit. Peak memory is measured on the CLI with
// /usr/bin/time -v (docs/benchmarks.md).
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "meridian/dov/simulator.hpp"
#include "meridian/dov/streaming.hpp"
#include "meridian/io/dov_binary.hpp"
#include "meridian/io/dov_files.hpp"
#include "meridian/io/dov_jobs.hpp"
#include "meridian/io/dov_writers.hpp"

namespace {
namespace fs = std::filesystem;
using namespace meridian;

std::size_t epochs() {
  const char* e = std::getenv("MERIDIAN_BENCH_DOV_EPOCHS");
  return e && *e ? std::strtoull(e, nullptr, 10) : 360000;
}

struct Line {
  dov::Input input;
  fs::path dir;
  std::string csv_config, bin_config;
  ~Line() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

const Line& line() {
  static const Line l = [] {
    Line x;
    dov::SimulationOptions so;
    so.rate_hz = 100.0;
    so.duration_s = static_cast<double>(epochs() - 1) / so.rate_hz;
    so.seed = 5;
    x.input = dov::simulate(so);
    for (dov::Truth& t : x.input.truth) t.state.reset();
    x.dir = fs::temp_directory_path() / ("meridian-bench-dov-" + std::to_string(::getpid()));
    fs::create_directories(x.dir);
    std::ofstream(x.dir / "line.csv", std::ios::binary) << io::dov_line_csv(x.input);
    std::ofstream(x.dir / "line.bin", std::ios::binary) << io::dov_line_binary(x.input);
    std::ofstream(x.dir / "csv.yaml") << "line: line.csv\n";
    std::ofstream(x.dir / "bin.yaml") << "line: line.bin\n";
    x.csv_config = (x.dir / "csv.yaml").string();
    x.bin_config = (x.dir / "bin.yaml").string();
    return x;
  }();
  return l;
}

void rate(benchmark::State& state, std::size_t n) {
  state.counters["epochs"] = static_cast<double>(n);
  state.counters["epochs_per_s"] = benchmark::Counter(static_cast<double>(n),
                                                      benchmark::Counter::kIsIterationInvariantRate);
}

// The streaming runner on the line a configuration names, without a sink (no profile).
void run_config(benchmark::State& state, const std::string& config) {
  const io::DovConfig c = io::read_dov_config(config);
  for (auto _ : state) {
    dov::Result r = io::run_dov_stream(c, {});
    benchmark::DoNotOptimize(r.summary.mean_nis);
  }
  rate(state, line().input.samples.size());
}
void DovProcessBinary(benchmark::State& state) { run_config(state, line().bin_config); }
void DovProcessCsv(benchmark::State& state) { run_config(state, line().csv_config); }
BENCHMARK(DovProcessBinary)->Unit(benchmark::kMillisecond);
BENCHMARK(DovProcessCsv)->Unit(benchmark::kMillisecond);

// The numerics alone (samples from memory, no sink).
void DovProcessFromMemory(benchmark::State& state) {
  const dov::Input& in = line().input;
  for (auto _ : state) {
    // process(Input) would keep the epochs; the stream without a sink does not
    class Source final : public dov::SampleSource {
     public:
      explicit Source(const dov::Input& i) : i_(i) {}
      std::size_t next(std::vector<dov::Sample>& s, std::vector<dov::Truth>& t,
                       std::size_t max) override {
        const std::size_t n = std::min(max, i_.samples.size() - at_);
        s.assign(i_.samples.begin() + static_cast<std::ptrdiff_t>(at_),
                 i_.samples.begin() + static_cast<std::ptrdiff_t>(at_ + n));
        t.assign(i_.truth.begin() + static_cast<std::ptrdiff_t>(at_),
                 i_.truth.begin() + static_cast<std::ptrdiff_t>(at_ + n));
        at_ += n;
        return n;
      }
      bool has_truth() const override { return true; }

     private:
      const dov::Input& i_;
      std::size_t at_ = 0;
    } source(in);
    dov::Result r = dov::process_stream(source, in.options, {});
    benchmark::DoNotOptimize(r.summary.mean_nis);
  }
  rate(state, in.samples.size());
}
BENCHMARK(DovProcessFromMemory)->Unit(benchmark::kMillisecond);

void read_all(benchmark::State& state, const fs::path& file) {
  for (auto _ : state) {
    io::DovLineReader r(file.string());
    io::DovLine chunk;
    std::size_t n = 0;
    while (r.next(chunk, 65536)) n += chunk.samples.size();
    benchmark::DoNotOptimize(n);
  }
  rate(state, line().input.samples.size());
}
void DovReadBinary(benchmark::State& state) { read_all(state, line().dir / "line.bin"); }
void DovReadCsv(benchmark::State& state) { read_all(state, line().dir / "line.csv"); }
BENCHMARK(DovReadBinary)->Unit(benchmark::kMillisecond);
BENCHMARK(DovReadCsv)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
