// The wavelet transform and the universal-threshold denoising against
// PyWavelets (Debian python3-pywt, installed by scripts/setup.sh): the test
// runs tests/maglev/pywt_reference.py and compares every case to 1e-10.
// CTest label `reference`: fails (never skips) when Python, numpy or pywt is missing.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "meridian/maglev/denoise.hpp"
#include "meridian/maglev/wavelet.hpp"

using namespace meridian::maglev;

namespace {

struct Case {
  std::string name, wavelet, mode, threshold;
  int level = 0;
  std::map<std::string, std::vector<double>> arrays;
};

std::vector<double> parse_values(std::istringstream& in) {
  std::vector<double> v;
  std::string tok;
  while (in >> tok) v.push_back(std::strtod(tok.c_str(), nullptr));
  return v;
}

std::vector<Case> load_cases() {
  const auto out = std::filesystem::temp_directory_path() /
                   fmt::format("meridian_pywt_reference_{}.txt", static_cast<long>(::getpid()));
  const std::string cmd = fmt::format("{} {}/tests/maglev/pywt_reference.py {}", MERIDIAN_PYTHON3,
                                      MERIDIAN_SOURCE_DIR, out.string());
  const int rc = std::system(cmd.c_str());
  if (rc != 0) {
    ADD_FAILURE() << "the PyWavelets reference could not be generated (Debian python3-pywt and "
                     "python3-numpy are needed; scripts/setup.sh installs them): "
                  << cmd;
    return {};
  }
  std::ifstream f(out);
  std::vector<Case> cases;
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "case") {
      Case c;
      in >> c.name >> c.wavelet >> c.mode >> c.level >> c.threshold;
      cases.push_back(std::move(c));
    } else if (key != "end") {
      cases.back().arrays[key] = parse_values(in);
    }
  }
  std::filesystem::remove(out);
  return cases;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> c = load_cases();
  return c;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

}  // namespace

bool is_sure(const Case& c) { return c.threshold.rfind("sure-", 0) == 0; }

TEST(WaveletReference, CasesCoverEveryWaveletAndMode) {
  ASSERT_FALSE(cases().empty());
  std::map<std::string, int> seen;
  for (const auto& c : cases())
    if (!is_sure(c)) ++seen[c.wavelet + "/" + c.mode];
  for (int n = 2; n <= 10; ++n)
    for (const char* mode : {"symmetric", "periodization"})
      EXPECT_GT(seen[fmt::format("db{}/{}", n, mode)], 0) << n << mode;
}

TEST(WaveletReference, WavedecMatchesPywt) {
  ASSERT_FALSE(cases().empty());
  for (const auto& c : cases()) {
    if (is_sure(c)) continue;
    SCOPED_TRACE(fmt::format("{} {} {} level {}", c.name, c.wavelet, c.mode, c.level));
    const Wavelet w = Wavelet::from_name(c.wavelet);
    const auto mode = extension_mode_from_string(c.mode);
    const auto coeffs = wavedec(c.arrays.at("x"), w, mode, c.level);
    ASSERT_EQ(coeffs.coefficients.size(), static_cast<std::size_t>(c.level) + 1);
    for (int k = 0; k <= c.level; ++k) {
      const auto& ref = c.arrays.at(fmt::format("c{}", k));
      const auto& got = coeffs.coefficients[static_cast<std::size_t>(k)];
      ASSERT_EQ(got.size(), ref.size()) << "c" << k;
      EXPECT_LT(max_abs_diff(got, ref), 1e-10) << "c" << k;
    }
  }
}

TEST(WaveletReference, WaverecMatchesPywt) {
  ASSERT_FALSE(cases().empty());
  for (const auto& c : cases()) {
    if (is_sure(c)) continue;
    SCOPED_TRACE(fmt::format("{} {} {} level {}", c.name, c.wavelet, c.mode, c.level));
    const Wavelet w = Wavelet::from_name(c.wavelet);
    const auto mode = extension_mode_from_string(c.mode);
    WaveletCoefficients in;
    for (int k = 0; k <= c.level; ++k)
      in.coefficients.push_back(c.arrays.at(fmt::format("c{}", k)));
    const auto rec = waverec(in, w, mode);
    const auto& ref = c.arrays.at("rec");
    ASSERT_EQ(rec.size(), ref.size());
    EXPECT_LT(max_abs_diff(rec, ref), 1e-10);
  }
}

TEST(WaveletReference, UniversalDenoisingMatchesPywt) {
  ASSERT_FALSE(cases().empty());
  for (const auto& c : cases()) {
    if (is_sure(c)) continue;
    SCOPED_TRACE(
        fmt::format("{} {} {} level {} {}", c.name, c.wavelet, c.mode, c.level, c.threshold));
    DenoiseOptions o;
    o.wavelet_order = Wavelet::from_name(c.wavelet).order();
    o.level = c.level;
    o.mode = extension_mode_from_string(c.mode);
    o.kind = threshold_kind_from_string(c.threshold);
    o.rule = ThresholdRule::Universal;
    const auto r = denoise(c.arrays.at("x"), o);
    const auto& ref = c.arrays.at("den");
    ASSERT_EQ(r.values.size(), ref.size());
    EXPECT_LT(max_abs_diff(r.values, ref), 1e-10);
  }
}

// SURE + hard: the threshold equals one |d_i|, and that tie keeps the coefficient (|d| ≥ λ, as
// pywt.threshold 'hard' does); the generator computes SURE by brute force.
TEST(WaveletReference, SureDenoisingMatchesPywtIncludingTheTie) {
  ASSERT_FALSE(cases().empty());
  int n = 0;
  for (const auto& c : cases()) {
    if (!is_sure(c)) continue;
    ++n;
    SCOPED_TRACE(fmt::format("{} {} {} level {} {}", c.name, c.wavelet, c.mode, c.level,
                             c.threshold));
    DenoiseOptions o;
    o.wavelet_order = Wavelet::from_name(c.wavelet).order();
    o.level = c.level;
    o.mode = extension_mode_from_string(c.mode);
    o.kind = threshold_kind_from_string(c.threshold.substr(5));
    o.rule = ThresholdRule::Sure;
    const auto r = denoise(c.arrays.at("x"), o);
    const auto& ref = c.arrays.at("den");
    ASSERT_EQ(r.values.size(), ref.size());
    EXPECT_LT(max_abs_diff(r.values, ref), 1e-10);
  }
  EXPECT_EQ(n, 24);
}
