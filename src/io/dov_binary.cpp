#include "meridian/io/dov_binary.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::io {
namespace {

constexpr std::size_t kBaseDoubles = 23;  // time, lat, lon, height, speed, 9 + 9 elements

template <typename T>
T swap_if_big(T v) {
  if constexpr (std::endian::native == std::endian::big) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    std::reverse(b, b + sizeof(T));
    std::memcpy(&v, b, sizeof(T));
  }
  return v;
}

template <typename T>
void put(std::string& out, T v) {
  v = swap_if_big(v);
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

template <typename T>
T get(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return swap_if_big(v);
}

std::size_t record_doubles(std::uint32_t flags) {
  return kBaseDoubles + ((flags & kDovBinaryHasModel) ? 2 : 0) +
         ((flags & kDovBinaryHasTruth) ? 2 : 0);
}

// Names of the record's doubles, for the error of a non-finite value.
const char* value_name(std::size_t i, std::uint32_t flags) {
  static constexpr const char* kBase[kBaseDoubles] = {
      "time_s", "lat_rad", "lon_rad", "height_m", "speed_m_s", "lgu_11", "lgu_12", "lgu_13",
      "lgu_21", "lgu_22",  "lgu_23",  "lgu_31",   "lgu_32",    "lgu_33", "ins_11", "ins_12",
      "ins_13", "ins_21",  "ins_22",  "ins_23",   "ins_31",    "ins_32", "ins_33"};
  if (i < kBaseDoubles) return kBase[i];
  i -= kBaseDoubles;
  if (flags & kDovBinaryHasModel) {
    if (i < 2) return i == 0 ? "model_eta_rad" : "model_xi_rad";
    i -= 2;
  }
  return i == 0 ? "truth_eta_rad" : "truth_xi_rad";
}

}  // namespace

bool is_dov_binary(const char* head, std::size_t size) {
  return size >= kDovBinaryMagic.size() &&
         std::memcmp(head, kDovBinaryMagic.data(), kDovBinaryMagic.size()) == 0;
}

std::string dov_binary_header(std::uint64_t count, bool has_model, bool has_truth) {
  const std::uint32_t flags =
      (has_model ? kDovBinaryHasModel : 0u) | (has_truth ? kDovBinaryHasTruth : 0u);
  std::string h(kDovBinaryMagic.data(), kDovBinaryMagic.size());
  put<std::uint32_t>(h, kDovBinaryVersion);
  put<std::uint32_t>(h, flags);
  put<std::uint32_t>(h, static_cast<std::uint32_t>(8 * record_doubles(flags)));
  put<std::uint32_t>(h, 0);
  put<std::uint64_t>(h, count);
  return h;
}

void append_dov_binary_record(std::string& out, const dov::Sample& s, const dov::Truth* truth,
                              bool has_model, bool has_truth) {
  if (has_truth != (truth != nullptr))
    throw InputError("a binary record needs its truth exactly when the file has truth columns");
  for (double v : {s.time_s, s.lat_rad, s.lon_rad, s.height_m, s.speed_m_s}) put(out, v);
  for (const Eigen::Matrix3d* m : {&s.lgu_body_to_nav, &s.ins_body_to_nav})
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) put(out, (*m)(i, j));
  if (has_model) {
    put(out, s.model_eta_rad);
    put(out, s.model_xi_rad);
  }
  if (has_truth) {
    put(out, truth->eta_rad);
    put(out, truth->xi_rad);
  }
}

std::string dov_line_binary(const dov::Input& input) {
  const bool truth = !input.truth.empty();
  std::string out = dov_binary_header(input.samples.size(), true, truth);
  out.reserve(out.size() + input.samples.size() * 8 * record_doubles(truth ? 3u : 1u));
  for (std::size_t k = 0; k < input.samples.size(); ++k)
    append_dov_binary_record(out, input.samples[k], truth ? &input.truth[k] : nullptr, true, truth);
  return out;
}

DovBinaryReader::DovBinaryReader(std::istream& in, std::string source)
    : in_(in), source_(std::move(source)) {
  const auto fail = [&](const std::string& what) {
    throw ParseError(fmt::format("not a DOV binary line of this version: {}", what),
                     ErrorContext{source_, std::nullopt, "header"});
  };
  char h[kDovBinaryHeaderBytes];
  in_.read(h, sizeof h);
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (!is_dov_binary(h, got)) fail("the file does not start with the magic \"MRDN-DOV\"");
  if (got < sizeof h)
    fail(fmt::format("the header is truncated ({} of {} bytes)", got, sizeof h));
  const auto version = get<std::uint32_t>(h + 8);
  if (version != kDovBinaryVersion)
    fail(fmt::format("format version {} (this build reads version {})", version,
                     kDovBinaryVersion));
  flags_ = get<std::uint32_t>(h + 12);
  if (flags_ & ~(kDovBinaryHasModel | kDovBinaryHasTruth))
    fail(fmt::format("unknown flag bits 0x{:x}", flags_));
  record_doubles_ = record_doubles(flags_);
  const auto record_bytes = get<std::uint32_t>(h + 16);
  if (record_bytes != 8 * record_doubles_)
    fail(fmt::format("record size {} bytes, {} expected for flags 0x{:x}", record_bytes,
                     8 * record_doubles_, flags_));
  if (get<std::uint32_t>(h + 20) != 0) fail("the reserved field is not 0");
  count_ = get<std::uint64_t>(h + 24);
}

std::size_t DovBinaryReader::next(std::vector<dov::Sample>& samples,
                                  std::vector<dov::Truth>* truth, std::size_t max) {
  const std::size_t record_bytes = 8 * record_doubles_;
  if (read_ == count_) {
    // Nothing may follow the last record.
    char extra;
    if (in_.read(&extra, 1).gcount() != 0)
      throw InputError(
          fmt::format("bytes after the last of the {} samples the header announces", count_),
          ErrorContext{source_, std::nullopt, fmt::format("sample {}", count_)});
    return 0;
  }
  if (has_truth() && truth == nullptr)
    throw InputError("the file has truth columns: pass a truth vector",
                     ErrorContext{source_, std::nullopt, {}});
  const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(std::max<std::size_t>(max, 1),
                                                                  count_ - read_));
  buffer_.resize(n * record_bytes);
  in_.read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  const auto got = static_cast<std::size_t>(in_.gcount());
  if (got < buffer_.size()) {
    const std::uint64_t k = read_ + got / record_bytes;
    throw InputError(fmt::format("the file is truncated: sample {} of the {} the header "
                                 "announces is incomplete ({} of its {} bytes)",
                                 k, count_, got % record_bytes, record_bytes),
                     ErrorContext{source_, std::nullopt, fmt::format("sample {}", k)});
  }
  samples.reserve(samples.size() + n);
  if (truth) truth->reserve(truth->size() + n);
  double v[kBaseDoubles + 4];
  for (std::size_t r = 0; r < n; ++r) {
    const char* p = buffer_.data() + r * record_bytes;
    const std::uint64_t k = read_ + r;
    // One test for the whole record (x·0 is 0 for finite x, NaN otherwise), the value named
    // only on failure: a test and branch per value was a third of the reader's time.
    double zero = 0.0;
    for (std::size_t i = 0; i < record_doubles_; ++i) {
      v[i] = get<double>(p + 8 * i);
      zero += v[i] * 0.0;
    }
    if (zero != 0.0) [[unlikely]]
      for (std::size_t i = 0; i < record_doubles_; ++i)
        if (!std::isfinite(v[i]))
          throw InputError(fmt::format("{} is not finite ({})", value_name(i, flags_), v[i]),
                           ErrorContext{source_, std::nullopt, fmt::format("sample {}", k)});
    if (std::abs(v[1]) > units::kPi / 2.0)
      throw InputError(fmt::format("latitude {}° is beyond ±90°", v[1] / units::kDegree),
                       ErrorContext{source_, std::nullopt, fmt::format("sample {}", k)});
    dov::Sample& s = samples.emplace_back();
    s.time_s = v[0];
    s.lat_rad = v[1];
    s.lon_rad = v[2];
    s.height_m = v[3];
    s.speed_m_s = v[4];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        s.lgu_body_to_nav(i, j) = v[5 + 3 * i + j];
        s.ins_body_to_nav(i, j) = v[14 + 3 * i + j];
      }
    std::size_t at = kBaseDoubles;
    if (has_model()) {
      s.model_eta_rad = v[at++];
      s.model_xi_rad = v[at++];
    } else {
      s.model_eta_rad = s.model_xi_rad = std::numeric_limits<double>::quiet_NaN();
    }
    if (has_truth()) {
      dov::Truth& t = truth->emplace_back();
      t.eta_rad = v[at++];
      t.xi_rad = v[at++];
    }
  }
  read_ += n;
  return n;
}

}  // namespace meridian::io
