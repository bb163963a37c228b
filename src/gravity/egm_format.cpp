#include "meridian/gravity/egm_format.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#ifdef __SSE2__
#include <emmintrin.h>
#endif
#include <fstream>
#include <limits>
#include <string>

#include <string_view>

#include <fmt/format.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/utf8.hpp"
#include "text_util.hpp"

namespace meridian::gravity {
namespace {

static_assert(std::endian::native == std::endian::little, "the .egm.cof reader assumes a little-endian host");

constexpr std::size_t kIdLength = 8;
// A geoid correction set (metres; a few metres at most for real models) with a coefficient
// beyond this is a damaged file: it gave geoid heights of 1e300 m (trial finding).
constexpr double kMaxCorrection_m = 1000.0;

// GeographicLib's "fract": a number or "p/q".
std::optional<double> parse_fract(std::string_view s) {
  const std::size_t slash = s.find('/');
  if (slash == std::string_view::npos) return detail::parse_double(s);
  const auto a = detail::parse_double(s.substr(0, slash)), b = detail::parse_double(s.substr(slash + 1));
  if (!a || !b || *b == 0) return std::nullopt;
  return *a / *b;
}

// Whether every |v[k]| <= limit (false for NaN), eight at a time with SSE2 compares: the scalar
// loop (one comparison and a flag per value) took 2.3 ms of a 29 ms load at degree 2190.
bool all_within(const double* v, std::uint64_t count, double limit) noexcept {
  std::uint64_t k = 0;
  bool all = true;
#ifdef __SSE2__
  const __m128d hi = _mm_set1_pd(limit), lo = _mm_set1_pd(-limit);
  __m128d ok = _mm_castsi128_pd(_mm_set1_epi32(-1));
  for (; k + 8 <= count; k += 8)
    for (int j = 0; j < 8; j += 2) {
      const __m128d x = _mm_loadu_pd(v + k + j);
      ok = _mm_and_pd(ok, _mm_and_pd(_mm_cmple_pd(x, hi), _mm_cmpge_pd(x, lo)));  // false for NaN
    }
  all = _mm_movemask_pd(ok) == 3;
#endif
  for (; k < count; ++k) all = all && std::abs(v[k]) <= limit;
  return all;
}

class CofReader {
 public:
  explicit CofReader(const std::string& file) : file_(file), in_(file, std::ios::binary) {
    if (!in_) throw IoError("cannot open coefficient file", {file, {}, ""});
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
    in_.seekg(0);
  }
  // The position is counted here, not asked of the stream (tellg is a system call).
  std::uint64_t offset() const { return pos_; }
  void need(std::uint64_t bytes, const char* what) {
    if (pos_ + bytes > size_)
      throw ParseError(fmt::format("file truncated: {} needs {} bytes at offset {}, file has {}", what, bytes, pos_, size_),
                       {file_, {}, what});
  }
  void read(void* dst, std::uint64_t bytes, const char* what) {
    need(bytes, what);
    in_.read(static_cast<char*>(dst), static_cast<std::streamsize>(bytes));
    if (!in_) throw IoError(fmt::format("read error at offset {}", pos_), {file_, {}, what});
    pos_ += bytes;
  }
  void skip(std::uint64_t bytes, const char* what) {
    if (bytes == 0) return;
    need(bytes, what);
    in_.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
    pos_ += bytes;
  }
  // One coefficient set with truncation; returns nullopt for N = M = −1.
  std::optional<SphericalHarmonicCoefficients> coefficients(const Truncation& t, const char* what, int* file_n) {
    std::int32_t nm[2];
    read(nm, sizeof nm, what);
    const int n0 = nm[0], m0 = nm[1];
    if (file_n) *file_n = n0;
    if (n0 == -1 && m0 == -1) return std::nullopt;
    if (!(n0 >= m0 && m0 >= 0) || n0 > 100000)
      throw ParseError(fmt::format("bad degree and order {} {} at offset {}{}", n0, m0, offset() - sizeof nm,
                                   std::string_view(what) == "correction"
                                       ? " (where the file's layout puts the correction set: if the gravitational "
                                         "set's N, M are wrong, its coefficients end elsewhere)"
                                       : ""),
                       {file_, {}, what});
    // The whole set must be in the file before anything is allocated, so a
    // header claiming a huge degree is a truncated file, not an allocation.
    const std::uint64_t N0 = static_cast<std::uint64_t>(n0), M0 = static_cast<std::uint64_t>(m0);
    const std::uint64_t c_count = (M0 + 1) * (N0 + 1) - M0 * (M0 + 1) / 2;  // columns m = 0..M0 of length N0 + 1 − m
    need(8 * (2 * c_count - (N0 + 1)), what);
    const int n = t.max_degree < 0 ? n0 : std::min(t.max_degree, n0);
    const int m = std::min({t.max_order < 0 ? n : t.max_order, m0, n});
    // Without truncation the file fills every value (C̄, and S̄ from column m = 1 on): no zero fill.
    SphericalHarmonicCoefficients c = n == n0 && m == m0 ? SphericalHarmonicCoefficients(n, m, SphericalHarmonicCoefficients::Unfilled{})
                                                         : SphericalHarmonicCoefficients(n, m);
    // Fully normalised gravitational coefficients are at most 1 in absolute
    // value (C̄00 = 1; |C̄20| ≈ 4.8e-4 for the Earth); the correction set is
    // in metres, at most kMaxCorrection_m.
    const bool normalised = std::string_view(what) == "gravitational";
    const double limit = normalised ? 1.0 : kMaxCorrection_m;
    // A branch-free scan (NaN fails the comparison) of what was just read, while it is in cache;
    // the loop at the end finds the entry to name.
    int out_of_range = 0;
    auto scan = [&](const double* v, std::uint64_t count) { out_of_range |= !all_within(v, count, limit); };
    // C: columns m = 0..m0 of length n0 + 1 − m; S: columns m = 1..m0. Without truncation the
    // file's columns are the set's own layout: read in large chunks (S̄ from column m = 1 on).
    if (n == n0 && m == m0) {
      constexpr std::uint64_t kChunk = 32768;  // 256 KB
      auto read_scanned = [&](double* dst, std::uint64_t count) {
        for (std::uint64_t k = 0; k < count; k += kChunk) {
          const std::uint64_t len = std::min(kChunk, count - k);
          read(dst + k, 8 * len, what);
          scan(dst + k, len);
        }
      };
      read_scanned(c.c_data(), c_count);
      read_scanned(c.s_data() + (N0 + 1), c_count - (N0 + 1));
    } else {
      for (int pass = 0; pass < 2; ++pass) {
        double* dst = pass == 0 ? c.c_data() : c.s_data();
        for (int mm = pass; mm <= m0; ++mm) {
          const std::uint64_t len = static_cast<std::uint64_t>(n0 + 1 - mm);
          if (mm > m) {
            skip(len * 8, what);
            continue;
          }
          const std::uint64_t keep = static_cast<std::uint64_t>(n + 1 - mm);
          read(dst + c.index(mm, mm), keep * 8, what);
          scan(dst + c.index(mm, mm), keep);
          skip((len - keep) * 8, what);
        }
      }
    }
    for (std::size_t k = 0; out_of_range != 0 && k < c.size(); ++k) {
      for (const bool sine : {false, true}) {
        const double v = sine ? c.s_values()[k] : c.c_values()[k];
        if (std::abs(v) <= limit) continue;
        // Name the coefficient, not its position in memory (S̄ has no m = 0 column in the file).
        int mm = 0;
        while (mm < c.max_order() && c.index(mm + 1, mm + 1) <= k) ++mm;
        const int nn = mm + static_cast<int>(k - c.index(mm, mm));
        const std::string name = fmt::format("{}({}, {})", sine ? "S" : "C", nn, mm);
        if (!std::isfinite(v))
          throw ParseError(fmt::format("non-finite coefficient {} ({}) of the {} set", name, v, what),
                           {file_, {}, what});
        throw ParseError(normalised ? fmt::format("coefficient {} = {:g} of the {} set is not a fully normalised "
                                                  "coefficient (|value| <= 1)",
                                                  name, v, what)
                                    : fmt::format("coefficient {} = {:g} m of the {} set is beyond {:g} m: not a "
                                                  "geoid correction (damaged file?)",
                                                  name, v, what, kMaxCorrection_m),
                         {file_, {}, what});
      }
    }
    return c;
  }
  void expect_end() {
    if (offset() != size_)
      throw ParseError(fmt::format("{} bytes of extra data after the coefficients (offset {})", size_ - offset(), offset()),
                       {file_, {}, ""});
  }

 private:
  std::string file_;
  std::ifstream in_;
  std::uint64_t size_ = 0, pos_ = 0;
};

}  // namespace

GravityModelData read_egm_file(const std::filesystem::path& path, const Truncation& truncation) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw IoError("cannot open gravity model metadata file", {file, {}, ""});
  GravityModelData model;
  model.source_file = file;
  std::string line;
  int line_no = 1;
  if (!std::getline(in, line) || line.rfind("EGMF-", 0) != 0)
    throw ParseError("no EGMF-n signature on the first line (not a GeographicLib .egm file)", {file, 1, ""});
  if (line.substr(5, line.find_first_of(" \t\r", 5) - 5) != "1")
    throw ParseError("unsupported .egm version \"" + line.substr(5) + "\" (expected EGMF-1)", {file, 1, ""});
  double a = NAN, gm = NAN, omega = NAN, f = NAN, j2 = NAN, zeta0 = 0, corrmult = 1;
  model.gm_m3_s2 = model.radius_m = NAN;
  std::string id;
  std::vector<std::string_view> fields;
  while (std::getline(in, line)) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    detail::split_fields(line, fields);
    if (fields.empty()) continue;
    const std::string key(fields[0]);
    std::string val = fields.size() > 1 ? line.substr(static_cast<std::size_t>(fields[1].data() - line.data())) : "";
    while (!val.empty() && std::isspace(static_cast<unsigned char>(val.back()))) val.pop_back();
    auto number = [&]() {
      const auto v = parse_fract(val);
      if (!v || !std::isfinite(*v)) throw ParseError(fmt::format("{} is not a number: \"{}\"", key, val), {file, line_no, key});
      return *v;
    };
    auto text = [&]() {
      if (const auto bad = first_invalid_utf8(val))
        throw ParseError(fmt::format("{} is not UTF-8 text (byte 0x{:02X} at position {})", key,
                                     static_cast<unsigned char>(val[*bad]), *bad + 1),
                         {file, line_no, key});
      return val;
    };
    if (key == "Name") model.name = text();
    else if (key == "Description") model.description = text();
    else if (key == "ModelRadius") model.radius_m = number();
    else if (key == "ModelMass") model.gm_m3_s2 = number();
    else if (key == "AngularVelocity") omega = number();
    else if (key == "ReferenceRadius") a = number();
    else if (key == "ReferenceMass") gm = number();
    else if (key == "Flattening") f = number();
    else if (key == "DynamicalFormFactor") j2 = number();
    else if (key == "HeightOffset") zeta0 = number();
    else if (key == "CorrectionMultiplier") corrmult = number();
    else if (key == "ID") id = val;
    else if (key == "Normalization") {
      if (val != "FULL" && val != "Full" && val != "full")
        throw ParseError("normalization \"" + val + "\" is not supported (only FULL)", {file, line_no, key});
      model.normalization = val;
    } else if (key == "ByteOrder") {
      if (val != "Little" && val != "little")
        throw ParseError("byte order \"" + val + "\" is not supported (only Little)", {file, line_no, key});
    }
  }
  auto require = [&](double v, const char* key) {
    if (!(std::isfinite(v) && v > 0)) throw ParseError(fmt::format("missing or non-positive {}", key), {file, {}, key});
  };
  require(model.radius_m, "ModelRadius");
  require(model.gm_m3_s2, "ModelMass");
  require(a, "ReferenceRadius");
  require(gm, "ReferenceMass");
  if (!(std::isfinite(omega) && omega >= 0)) throw ParseError("missing AngularVelocity", {file, {}, "AngularVelocity"});
  if (std::isfinite(f) == std::isfinite(j2))
    throw ParseError("exactly one of Flattening and DynamicalFormFactor must be given", {file, {}, "Flattening"});
  if (!(corrmult > 0)) throw ParseError("CorrectionMultiplier must be positive", {file, {}, "CorrectionMultiplier"});
  if (id.size() != kIdLength) throw ParseError("ID must have exactly 8 characters, got \"" + id + "\"", {file, {}, "ID"});
  model.reference = NormalFieldParameters{model.name.empty() ? "reference" : model.name + " reference", a, gm, omega,
                                          std::isfinite(f) ? f : 0.0, std::isfinite(j2) ? j2 : 0.0};
  if (model.name.empty()) model.name = path.stem().string();

  const std::string cof = file + ".cof";
  CofReader r(cof);
  char fid[kIdLength];
  r.read(fid, kIdLength, "ID");
  if (std::string(fid, kIdLength) != id)
    throw ParseError(fmt::format("ID mismatch: {} has \"{}\", {} has \"{}\"", file, id, cof, std::string(fid, kIdLength)),
                     {cof, {}, "ID"});
  int file_n = 0;
  auto c = r.coefficients(truncation, "gravitational", &file_n);
  if (!c) throw ParseError("the gravitational coefficient set is empty (N = M = -1)", {cof, {}, "gravitational"});
  if (c->c(0, 0) != 0) throw ParseError("the degree 0 coefficient must be 0 in a .egm.cof file", {cof, {}, "C00"});
  c->set(0, 0, 1.0, 0.0);
  model.coefficients = std::move(*c);
  model.file_max_degree = file_n;
  if (auto corr = r.coefficients(truncation, "correction", nullptr)) {
    model.correction = GeoidCorrection{std::move(*corr), corrmult, zeta0};
  } else if (zeta0 != 0) {
    model.correction = GeoidCorrection{SphericalHarmonicCoefficients(0, 0), corrmult, zeta0};
  }
  r.expect_end();
  return model;
}

void write_egm_files(const GravityModelData& model, const std::filesystem::path& prefix) {
  const SphericalHarmonicCoefficients& c = model.coefficients;
  if (c.c(0, 0) != 1.0)
    throw InputError(fmt::format("C00 = {} cannot be written to a GeographicLib file (it must be 1; rescale GM)", c.c(0, 0)),
                     {"", {}, "C00"});
  std::string id;
  for (char ch : model.name)
    if (std::isalnum(static_cast<unsigned char>(ch)) && id.size() < kIdLength)
      id += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  id.resize(kIdLength, 'X');
  const NormalFieldParameters& ref = model.reference;
  std::string meta = fmt::format(
      "EGMF-1\n# Gravity model written by Meridian\nName {}\nDescription {}\nModelRadius {:.17g}\nModelMass {:.17g}\n"
      "AngularVelocity {:.17g}\nReferenceRadius {:.17g}\nReferenceMass {:.17g}\n",
      model.name.empty() ? prefix.filename().string() : model.name,
      model.description.empty() ? "none" : model.description, model.radius_m, model.gm_m3_s2, ref.omega_rad_s, ref.a_m,
      ref.gm_m3_s2);
  meta += ref.j2 != 0 ? fmt::format("DynamicalFormFactor {:.17g}\n", ref.j2) : fmt::format("Flattening {:.17g}\n", ref.flattening);
  if (model.correction)
    meta += fmt::format("HeightOffset {:.17g}\nCorrectionMultiplier {:.17g}\n", model.correction->height_offset_m,
                        model.correction->multiplier);
  meta += "ID " + id + "\n";

  std::string bin = id;
  auto put = [&](const void* p, std::size_t bytes) { bin.append(static_cast<const char*>(p), bytes); };
  auto put_set = [&](const SphericalHarmonicCoefficients& s, bool zero_c00) {
    const std::int32_t nm[2] = {s.max_degree(), s.max_order()};
    put(nm, sizeof nm);
    std::vector<double> cv(s.c_values().begin(), s.c_values().end());
    if (zero_c00) cv[0] = 0;
    put(cv.data(), cv.size() * 8);
    const std::size_t s0 = static_cast<std::size_t>(s.max_degree()) + 1;  // skip the m = 0 column
    put(s.s_values().data() + s0, (s.size() - s0) * 8);
  };
  bin.reserve(8 + 16 + 16 * c.size());
  put_set(c, true);
  if (model.correction && model.correction->coefficients.size() > 0) {
    put_set(model.correction->coefficients, false);
  } else {
    const std::int32_t none[2] = {-1, -1};
    put(none, sizeof none);
  }
  std::filesystem::path egm = prefix;
  egm += ".egm";
  std::filesystem::path cof = prefix;
  cof += ".egm.cof";
  write_file_atomically(cof, bin);
  write_file_atomically(egm, meta);
}

}  // namespace meridian::gravity
