// The binary line format (io/dov_binary.hpp): the layout byte by byte as docs/file-formats.md
// writes it, the round trip bit for bit, and every error naming the file and sample index; the
// streaming workflow (dov/streaming.hpp) against the runner over the same line as CSV.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "dov_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/dov/simulator.hpp"
#include "meridian/dov/streaming.hpp"
#include "meridian/io/dov_binary.hpp"
#include "meridian/io/dov_files.hpp"
#include "meridian/io/dov_jobs.hpp"
#include "meridian/io/dov_writers.hpp"

// A named namespace: the unity build joins this file with test_io_dov.cpp.
namespace dov_binary_test {

using namespace meridian;
using meridian_test::kAs;
using meridian_test::write;

std::filesystem::path temp_dir(const std::string& name) {
  return meridian_test::temp_dir("dov_binary_" + name);
}

dov::Input small_line(double seconds = 120.0) {
  dov::SimulationOptions so;
  so.duration_s = seconds;
  so.seed = 11;
  return dov::simulate(so);
}

// Little-endian decoding by hand, as the documentation states the layout.
std::uint64_t le(const std::string& b, std::size_t at, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
  return v;
}
double le_double(const std::string& b, std::size_t at) {
  return std::bit_cast<double>(le(b, at, 8));
}

std::vector<dov::Sample> read_all(const std::string& bytes, std::vector<dov::Truth>& truth,
                                  const std::string& source = "line.bin") {
  std::istringstream in(bytes);
  io::DovBinaryReader r(in, source);
  std::vector<dov::Sample> s;
  while (r.next(s, &truth, 7) > 0) {
  }
  return s;
}

TEST(DovBinary, LayoutByteByByte) {
  const dov::Input in = small_line(10.0);
  const std::string b = io::dov_line_binary(in);
  const std::size_t n = in.samples.size();
  ASSERT_EQ(n, 11u);
  EXPECT_EQ(b.substr(0, 8), "MRDN-DOV");
  EXPECT_EQ(le(b, 8, 4), 1u);           // version
  EXPECT_EQ(le(b, 12, 4), 3u);          // model and truth
  EXPECT_EQ(le(b, 16, 4), 27u * 8u);    // record size: 23 + 2 + 2 doubles
  EXPECT_EQ(le(b, 20, 4), 0u);          // reserved
  EXPECT_EQ(le(b, 24, 8), n);           // count
  ASSERT_EQ(b.size(), 32 + n * 216);
  // record 4, field by field
  const std::size_t r = 32 + 4 * 216;
  const dov::Sample& s = in.samples[4];
  EXPECT_EQ(le_double(b, r + 0), s.time_s);
  EXPECT_EQ(le_double(b, r + 8), s.lat_rad);
  EXPECT_EQ(le_double(b, r + 16), s.lon_rad);
  EXPECT_EQ(le_double(b, r + 24), s.height_m);
  EXPECT_EQ(le_double(b, r + 32), s.speed_m_s);
  EXPECT_EQ(le_double(b, r + 40 + 8 * 5), s.lgu_body_to_nav(1, 2));  // lgu_23: row by row
  EXPECT_EQ(le_double(b, r + 112 + 8 * 7), s.ins_body_to_nav(2, 1));  // ins_32
  EXPECT_EQ(le_double(b, r + 184), s.model_eta_rad);
  EXPECT_EQ(le_double(b, r + 192), s.model_xi_rad);
  EXPECT_EQ(le_double(b, r + 200), in.truth[4].eta_rad);
  EXPECT_EQ(le_double(b, r + 208), in.truth[4].xi_rad);
}

TEST(DovBinary, RoundTripBitForBitAndWithoutModelOrTruth) {
  const dov::Input in = small_line();
  std::vector<dov::Truth> truth;
  const std::vector<dov::Sample> s = read_all(io::dov_line_binary(in), truth);
  ASSERT_EQ(s.size(), in.samples.size());
  ASSERT_EQ(truth.size(), in.truth.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    EXPECT_EQ(s[k].time_s, in.samples[k].time_s);
    EXPECT_EQ(s[k].lat_rad, in.samples[k].lat_rad);
    EXPECT_EQ(s[k].lon_rad, in.samples[k].lon_rad);
    EXPECT_EQ(s[k].lgu_body_to_nav, in.samples[k].lgu_body_to_nav);
    EXPECT_EQ(s[k].ins_body_to_nav, in.samples[k].ins_body_to_nav);
    EXPECT_EQ(s[k].model_eta_rad, in.samples[k].model_eta_rad);
    EXPECT_EQ(truth[k].xi_rad, in.truth[k].xi_rad);
  }
  // no model and no truth columns: 23 doubles a record, the model values NaN (to be filled)
  std::string b = io::dov_binary_header(2, false, false);
  for (int k = 0; k < 2; ++k) io::append_dov_binary_record(b, in.samples[k], nullptr, false, false);
  EXPECT_EQ(b.size(), 32u + 2u * 184u);
  std::istringstream is(b);
  io::DovBinaryReader r(is, "x.bin");
  EXPECT_FALSE(r.has_model());
  EXPECT_FALSE(r.has_truth());
  std::vector<dov::Sample> two;
  EXPECT_EQ(r.next(two, nullptr, 10), 2u);
  EXPECT_TRUE(std::isnan(two[1].model_xi_rad));
  EXPECT_EQ(two[1].ins_body_to_nav, in.samples[1].ins_body_to_nav);
  EXPECT_EQ(r.next(two, nullptr, 10), 0u);
}

// The error of reading `bytes`, with its field.
template <typename E>
std::pair<std::string, std::string> error_of(const std::string& bytes) {
  try {
    std::vector<dov::Truth> truth;
    read_all(bytes, truth);
  } catch (const E& e) {
    return {e.what(), e.context().field};
  } catch (const std::exception& e) {
    ADD_FAILURE() << "another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST(DovBinary, ErrorsNameTheFileAndTheSample) {
  const std::string good = io::dov_line_binary(small_line(10.0));
  // truncated in the middle of sample 5, and at a record boundary (sample 7 missing)
  auto [msg, field] = error_of<InputError>(good.substr(0, 32 + 5 * 216 + 100));
  EXPECT_EQ(field, "sample 5");
  EXPECT_NE(msg.find("line.bin"), std::string::npos) << msg;
  EXPECT_NE(msg.find("truncated"), std::string::npos) << msg;
  EXPECT_NE(msg.find("100 of its 216 bytes"), std::string::npos) << msg;
  EXPECT_EQ(error_of<InputError>(good.substr(0, 32 + 7 * 216)).second, "sample 7");
  // trailing bytes after the announced samples
  std::tie(msg, field) = error_of<InputError>(good + "x");
  EXPECT_NE(msg.find("after the last"), std::string::npos) << msg;
  // header: magic, version, flags, record size, a truncated header
  std::string bad = good;
  bad[3] = 'X';
  EXPECT_NE(error_of<ParseError>(bad).first.find("magic"), std::string::npos);
  bad = good;
  bad[8] = 2;
  EXPECT_NE(error_of<ParseError>(bad).first.find("version 2"), std::string::npos);
  bad = good;
  bad[12] = 7;
  EXPECT_NE(error_of<ParseError>(bad).first.find("flag"), std::string::npos);
  bad = good;
  bad[16] = 1;
  EXPECT_NE(error_of<ParseError>(bad).first.find("record size"), std::string::npos);
  EXPECT_NE(error_of<ParseError>(good.substr(0, 20)).first.find("header is truncated"),
            std::string::npos);
  // a non-finite value: NaN in lgu_22 of sample 3, infinity in the truth of sample 9
  bad = good;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(bad.data() + 32 + 3 * 216 + 40 + 8 * 4, &nan, 8);
  std::tie(msg, field) = error_of<InputError>(bad);
  EXPECT_EQ(field, "sample 3");
  EXPECT_NE(msg.find("lgu_22 is not finite"), std::string::npos) << msg;
  bad = good;
  const double inf = std::numeric_limits<double>::infinity();
  std::memcpy(bad.data() + 32 + 9 * 216 + 208, &inf, 8);
  std::tie(msg, field) = error_of<InputError>(bad);
  EXPECT_EQ(field, "sample 9");
  EXPECT_NE(msg.find("truth_xi_rad"), std::string::npos) << msg;
  // a latitude beyond ±90°
  bad = good;
  const double lat = 2.0;
  std::memcpy(bad.data() + 32 + 2 * 216 + 8, &lat, 8);
  EXPECT_EQ(error_of<InputError>(bad).second, "sample 2");
}

TEST(DovStreaming, BinaryAndCsvLinesGiveTheSameProfileThroughTheRunner) {
  const auto dir = temp_dir("runner");
  const dov::Input in = small_line(300.0);
  write(dir / "line.csv", io::dov_line_csv(in));
  // the binary line of what the CSV reader reads: the same doubles, so the same results
  const io::DovLine csv = io::read_dov_line_file((dir / "line.csv").string());
  dov::Input back;
  back.samples = csv.samples;
  back.truth = csv.truth;
  write(dir / "line.bin", io::dov_line_binary(back));
  write(dir / "csv.yaml", "line: line.csv\n");
  write(dir / "bin.yaml", "line: line.bin\nstatistics_start_s: 0\n");
  const dov::Result a = io::run_dov(io::read_dov_config((dir / "csv.yaml").string()));
  const dov::Result b = io::run_dov(io::read_dov_config((dir / "bin.yaml").string()));
  ASSERT_EQ(a.epochs.size(), in.samples.size());
  ASSERT_EQ(b.epochs.size(), a.epochs.size());
  for (std::size_t k = 0; k < a.epochs.size(); ++k) {
    EXPECT_EQ(a.epochs[k].smoothed.xi_rad, b.epochs[k].smoothed.xi_rad) << k;
    EXPECT_EQ(a.epochs[k].filtered.sigma_eta_rad, b.epochs[k].filtered.sigma_eta_rad) << k;
    EXPECT_EQ(a.epochs[k].lat_rad, b.epochs[k].lat_rad) << k;
    ASSERT_TRUE(b.epochs[k].truth.has_value());
    EXPECT_EQ(b.epochs[k].truth->eta_rad, back.truth[k].eta_rad);
  }
  EXPECT_EQ(a.summary.rms_smoothed->xi_rad, b.summary.rms_smoothed->xi_rad);
  // the streaming runner without a sink: the same summary, no epochs kept anywhere
  const dov::Result s =
      io::run_dov_stream(io::read_dov_config((dir / "bin.yaml").string()), {});
  EXPECT_TRUE(s.epochs.empty());
  EXPECT_EQ(s.summary.rms_smoothed->eta_rad, a.summary.rms_smoothed->eta_rad);
  EXPECT_EQ(s.summary.mean_nis, a.summary.mean_nis);
  EXPECT_EQ(s.summary.eps_u_rad_s, a.summary.eps_u_rad_s);
  std::filesystem::remove_all(dir);
}

TEST(DovStreaming, RunnerErrorsInABinaryLineNameTheSample) {
  const auto dir = temp_dir("errors");
  dov::Input in = small_line(60.0);
  in.samples[40].ins_body_to_nav(0, 0) *= 1.01;  // not orthogonal
  write(dir / "line.bin", io::dov_line_binary(in));
  write(dir / "dov.yaml", "line: line.bin\n");
  try {
    io::run_dov(io::read_dov_config((dir / "dov.yaml").string()));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "sample 40: ins_11…ins_33");
    EXPECT_NE(std::string(e.what()).find("line.bin"), std::string::npos) << e.what();
    EXPECT_FALSE(e.context().line.has_value());
  }
  std::filesystem::remove_all(dir);
}

// A source that hands out one sample at a time: the chunking is the source's business.
class OneByOne final : public dov::SampleSource {
 public:
  explicit OneByOne(const dov::Input& in) : in_(in) {}
  std::size_t next(std::vector<dov::Sample>& s, std::vector<dov::Truth>& t, std::size_t) override {
    s.clear();
    t.clear();
    if (k_ == in_.samples.size()) return 0;
    s.push_back(in_.samples[k_]);
    if (!in_.truth.empty()) t.push_back(in_.truth[k_]);
    ++k_;
    return 1;
  }
  bool has_truth() const override { return !in_.truth.empty(); }

 private:
  const dov::Input& in_;
  std::size_t k_ = 0;
};

TEST(DovStreaming, EpochsInTimeOrderSpilledOrNotAndALongStationaryStart) {
  dov::Input in = small_line(600.0);
  // 5000 samples standing still before the line moves: more than one chunk of the workflow
  // (4096) wait for the reference speed (the first 300 s of motion), which sets the initial
  // σ of x_E, x_N.
  dov::Input stop = in;
  stop.samples.clear();
  stop.truth.clear();
  for (int k = 0; k < 5000; ++k) {
    dov::Sample s = in.samples.front();
    s.time_s = in.samples.front().time_s - 0.1 * (5000 - k);
    s.speed_m_s = 0.0;
    stop.samples.push_back(s);
    stop.truth.push_back(in.truth.front());
  }
  stop.samples.insert(stop.samples.end(), in.samples.begin(), in.samples.end());
  stop.truth.insert(stop.truth.end(), in.truth.begin(), in.truth.end());
  for (dov::Truth& t : stop.truth) t.state.reset();
  const dov::Result mem = dov::process(stop);
  bool named = false;
  for (const std::string& n : mem.notes)
    named = named || n.find(fmt::format("reference speed {:.4g} m/s", in.samples[0].speed_m_s)) !=
                         std::string::npos;
  EXPECT_TRUE(named);
  // one sample at a time, everything spilled to disk: the same epochs, in time order
  stop.options.storage.memory_limit_bytes = 0;
  OneByOne source(stop);
  std::vector<dov::EpochResult> got;
  const dov::Result line = dov::process_stream(
      source, stop.options, {[&](const dov::EpochResult& e) { got.push_back(e); }});
  ASSERT_EQ(got.size(), mem.epochs.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    const dov::EpochResult &a = mem.epochs[k], &b = got[k];
    EXPECT_EQ(a.time_s, b.time_s);
    EXPECT_EQ(a.smoothed.eta_rad, b.smoothed.eta_rad);
    EXPECT_EQ(a.filtered.sigma_xi_rad, b.filtered.sigma_xi_rad);
    EXPECT_EQ(a.innovation_north_rad, b.innovation_north_rad);
    EXPECT_EQ(a.truth->xi_rad, b.truth->xi_rad);
    if (k > 0) {
      EXPECT_GT(b.time_s, got[k - 1].time_s);
    }
  }
  EXPECT_EQ(line.summary.rms_smoothed->xi_rad, mem.summary.rms_smoothed->xi_rad);
}

// The epochs a streamed Result keeps for a report (EpochOutputs::keep_epochs = n): every k-th
// epoch from epoch 0, k the smallest power of two with ⌈N/k⌉ ≤ n; the sink still gets them all.
TEST(DovStreaming, KeptEpochsAreEveryKthWithTheSmallestPowerOfTwo) {
  dov::Input in = small_line(600.0);  // 601 epochs
  in.origin = {"a line in memory", "", ""};
  in.options.gate_alpha = 0.01;
  const dov::Result all = dov::process(in);
  const std::size_t n = all.epochs.size();
  EXPECT_EQ(all.epoch_stride, 1u);
  EXPECT_EQ(all.options.gate_alpha, 0.01);  // the Result carries its options and origin
  EXPECT_EQ(all.origin.input, "a line in memory");
  for (const std::size_t at_most : {std::size_t{1}, std::size_t{50}, std::size_t{1000}, n}) {
    std::size_t k = 1;
    while ((n + k - 1) / k > at_most) k *= 2;
    OneByOne source(in);
    std::size_t handed = 0;
    const dov::Result kept = dov::process_stream(
        source, in.options, {[&](const dov::EpochResult&) { ++handed; }, at_most});
    EXPECT_EQ(handed, n);
    EXPECT_EQ(kept.epoch_stride, k) << at_most;
    ASSERT_EQ(kept.epochs.size(), (n + k - 1) / k) << at_most;
    for (std::size_t i = 0; i < kept.epochs.size(); ++i)
      EXPECT_EQ(kept.epochs[i].time_s, all.epochs[i * k].time_s) << at_most << " " << i;
    EXPECT_EQ(kept.summary.mean_nis, all.summary.mean_nis);
  }
}

}  // namespace dov_binary_test
