#include "meridian/io/gravity_egm.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#ifdef __SSE2__
#include <emmintrin.h>
#endif
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/atomic_file.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/utf8.hpp"
#include "gravity_text.hpp"

namespace meridian::io {
namespace {

using gravity::GeoidCorrection;
using gravity::GravityModelData;
using gravity::NormalFieldParameters;
using gravity::SphericalHarmonicCoefficients;
using gravity::Truncation;

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

// Degree and order of a coefficient set as its file states them, and its C̄ count.
struct SetSize {
  int n0 = 0, m0 = 0;
  std::uint64_t c_count = 0;  // columns m = 0..m0 of length n0 + 1 − m
};

class CofReader {
 public:
  explicit CofReader(const std::string& file) : file_(file), in_((detail::check_readable_path(file), file), std::ios::binary) {
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
    const std::optional<SetSize> size = set_size(what, file_n);
    if (!size) return std::nullopt;
    const int n = t.max_degree < 0 ? size->n0 : std::min(t.max_degree, size->n0);
    const int m = std::min({t.max_order < 0 ? n : t.max_order, size->m0, n});
    const bool whole = n == size->n0 && m == size->m0;
    // Without truncation the file fills every value (C̄, and S̄ from column m = 1 on): no zero fill.
    SphericalHarmonicCoefficients c = whole ? SphericalHarmonicCoefficients(n, m, SphericalHarmonicCoefficients::Unfilled{})
                                            : SphericalHarmonicCoefficients(n, m);
    // Fully normalised gravitational coefficients are at most 1 in absolute
    // value (C̄00 = 1; |C̄20| ≈ 4.8e-4 for the Earth); the correction set is
    // in metres, at most kMaxCorrection_m.
    const bool normalised = std::string_view(what) == "gravitational";
    const double limit = normalised ? 1.0 : kMaxCorrection_m;
    const bool in_range = whole ? read_whole_set(c, *size, what, limit) : read_truncated_set(c, *size, what, limit);
    if (!in_range) name_out_of_range(c, what, normalised, limit);
    return c;
  }

  void expect_end() {
    if (offset() != size_)
      throw ParseError(fmt::format("{} bytes of extra data after the coefficients (offset {})", size_ - offset(), offset()),
                       {file_, {}, ""});
  }

 private:
  // N, M of the next set (nullopt for N = M = −1), checked, and the whole set present in the
  // file before anything is allocated: a header claiming a huge degree is a truncated file, not
  // an allocation.
  std::optional<SetSize> set_size(const char* what, int* file_n) {
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
    const std::uint64_t N0 = static_cast<std::uint64_t>(n0), M0 = static_cast<std::uint64_t>(m0);
    const SetSize size{n0, m0, (M0 + 1) * (N0 + 1) - M0 * (M0 + 1) / 2};
    need(8 * (2 * size.c_count - (N0 + 1)), what);
    return size;
  }

  // Without truncation the file's columns are the set's own layout: read in large chunks
  // (S̄ from column m = 1 on), each scanned (branch-free; NaN fails the comparison) while it is
  // in cache. False when a value is beyond `limit`.
  bool read_whole_set(SphericalHarmonicCoefficients& c, const SetSize& size, const char* what, double limit) {
    constexpr std::uint64_t kChunk = 32768;  // 256 KB
    int out_of_range = 0;
    auto read_scanned = [&](double* dst, std::uint64_t count) {
      for (std::uint64_t k = 0; k < count; k += kChunk) {
        const std::uint64_t len = std::min(kChunk, count - k);
        read(dst + k, 8 * len, what);
        out_of_range |= !all_within(dst + k, len, limit);
      }
    };
    const std::uint64_t n0_plus_1 = static_cast<std::uint64_t>(size.n0) + 1;
    read_scanned(c.c_data(), size.c_count);
    read_scanned(c.s_data() + n0_plus_1, size.c_count - n0_plus_1);
    return out_of_range == 0;
  }

  // C: columns m = 0..m0 of length n0 + 1 − m; S: columns m = 1..m0. The kept part of each
  // column is read and scanned, the rest skipped. False when a value is beyond `limit`.
  bool read_truncated_set(SphericalHarmonicCoefficients& c, const SetSize& size, const char* what, double limit) {
    const int n = c.max_degree(), m = c.max_order();
    int out_of_range = 0;
    for (int pass = 0; pass < 2; ++pass) {
      double* dst = pass == 0 ? c.c_data() : c.s_data();
      for (int mm = pass; mm <= size.m0; ++mm) {
        const std::uint64_t len = static_cast<std::uint64_t>(size.n0 + 1 - mm);
        if (mm > m) {
          skip(len * 8, what);
          continue;
        }
        const std::uint64_t keep = static_cast<std::uint64_t>(n + 1 - mm);
        read(dst + c.index(mm, mm), keep * 8, what);
        out_of_range |= !all_within(dst + c.index(mm, mm), keep, limit);
        skip((len - keep) * 8, what);
      }
    }
    return out_of_range == 0;
  }

  // A scan found a value beyond `limit`: throw naming the first one (its degree and order, not
  // its position in memory: S̄ has no m = 0 column in the file).
  void name_out_of_range(const SphericalHarmonicCoefficients& c, const char* what, bool normalised,
                                      double limit) const {
    for (std::size_t k = 0; k < c.size(); ++k) {
      for (const bool sine : {false, true}) {
        const double v = sine ? c.s_values()[k] : c.c_values()[k];
        if (std::abs(v) <= limit) continue;
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
  }

  std::string file_;
  std::ifstream in_;
  std::uint64_t size_ = 0, pos_ = 0;
};

// What the `.egm` text states, before the `.cof` is read.
struct EgmMetadata {
  GravityModelData model;  // without coefficients
  std::string id;
  double corrmult = 1, zeta0 = 0;
};

// The `.egm` file's keys (`Key value`, `#` comments); lines are numbered for errors.
class EgmMetadataReader {
 public:
  explicit EgmMetadataReader(const std::filesystem::path& path)
      : path_(path), file_(path.string()), in_((detail::check_readable_path(path), path)) {
    if (!in_) throw IoError("cannot open gravity model metadata file", {file_, {}, ""});
  }

  EgmMetadata read() {
    EgmMetadata meta;
    meta.model.source_file = file_;
    signature();
    meta.model.gm_m3_s2 = meta.model.radius_m = NAN;
    std::vector<std::string_view> fields;
    std::string line;
    while (detail::getline_bounded(in_, line, file_, line_no_ + 1)) {
      ++line_no_;
      if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
      detail::split_fields(line, fields);
      if (fields.empty()) continue;
      key_ = std::string(fields[0]);
      val_ = fields.size() > 1 ? line.substr(static_cast<std::size_t>(fields[1].data() - line.data())) : "";
      while (!val_.empty() && std::isspace(static_cast<unsigned char>(val_.back()))) val_.pop_back();
      key_value(meta);
    }
    finish(meta);
    return meta;
  }

 private:
  void signature() {
    std::string line;
    if (!detail::getline_bounded(in_, line, file_, 1) || line.rfind("EGMF-", 0) != 0)
      throw ParseError("no EGMF-n signature on the first line (not a GeographicLib .egm file)", {file_, 1, ""});
    if (line.substr(5, line.find_first_of(" \t\r", 5) - 5) != "1")
      throw ParseError("unsupported .egm version \"" + line.substr(5) + "\" (expected EGMF-1)", {file_, 1, ""});
  }

  double number() const {
    const auto v = parse_fract(val_);
    if (!v || !std::isfinite(*v)) throw ParseError(fmt::format("{} is not a number: \"{}\"", key_, val_), {file_, line_no_, key_});
    return *v;
  }

  std::string text() const {
    if (const auto bad = first_invalid_utf8(val_))
      throw ParseError(fmt::format("{} is not UTF-8 text (byte 0x{:02X} at position {})", key_,
                                   static_cast<unsigned char>(val_[*bad]), *bad + 1),
                       {file_, line_no_, key_});
    return val_;
  }

  // The line of each key that means something here; a second one is refused.
  void once() {
    static constexpr std::string_view kKeys[] = {
        "Name", "Description", "ModelRadius", "ModelMass", "AngularVelocity", "ReferenceRadius", "ReferenceMass",
        "Flattening", "DynamicalFormFactor", "HeightOffset", "CorrectionMultiplier", "ID", "Normalization",
        "ByteOrder"};
    if (std::find(std::begin(kKeys), std::end(kKeys), key_) == std::end(kKeys)) return;
    const auto [it, fresh] = key_lines_.emplace(key_, line_no_);
    if (!fresh)
      throw ParseError(fmt::format("{} is given twice, on lines {} and {}", key_, it->second, line_no_),
                       {file_, line_no_, key_});
  }

  std::optional<int> line_of(const std::string& key) const {
    const auto it = key_lines_.find(key);
    return it == key_lines_.end() ? std::nullopt : std::optional<int>(it->second);
  }

  void key_value(EgmMetadata& meta) {
    GravityModelData& model = meta.model;
    once();
    if (key_ == "Name") model.name = text();
    else if (key_ == "Description") model.description = text();
    else if (key_ == "ModelRadius") model.radius_m = number();
    else if (key_ == "ModelMass") model.gm_m3_s2 = number();
    else if (key_ == "AngularVelocity") omega_ = number();
    else if (key_ == "ReferenceRadius") a_ = number();
    else if (key_ == "ReferenceMass") gm_ = number();
    else if (key_ == "Flattening") f_ = number();
    else if (key_ == "DynamicalFormFactor") j2_ = number();
    else if (key_ == "HeightOffset") meta.zeta0 = number();
    else if (key_ == "CorrectionMultiplier") meta.corrmult = number();
    else if (key_ == "ID") meta.id = val_;
    else if (key_ == "Normalization") {
      if (val_ != "FULL" && val_ != "Full" && val_ != "full")
        throw ParseError("normalization \"" + val_ + "\" is not supported (only FULL)", {file_, line_no_, key_});
      model.normalization = val_;
    } else if (key_ == "ByteOrder") {
      if (val_ != "Little" && val_ != "little")
        throw ParseError("byte order \"" + val_ + "\" is not supported (only Little)", {file_, line_no_, key_});
    }
  }

  // Every required key given; the reference field and the default name.
  void finish(EgmMetadata& meta) const {
    GravityModelData& model = meta.model;
    auto require = [&](double v, const char* key) {
      if (!(std::isfinite(v) && v > 0)) throw ParseError(fmt::format("missing or non-positive {}", key), {file_, {}, key});
    };
    require(model.radius_m, "ModelRadius");
    require(model.gm_m3_s2, "ModelMass");
    require(a_, "ReferenceRadius");
    require(gm_, "ReferenceMass");
    detail::check_model_radius(model.radius_m, file_, line_of("ModelRadius"), "ModelRadius");
    detail::check_model_gm(model.gm_m3_s2, file_, line_of("ModelMass"), "ModelMass");
    detail::check_model_radius(a_, file_, line_of("ReferenceRadius"), "ReferenceRadius");
    detail::check_model_gm(gm_, file_, line_of("ReferenceMass"), "ReferenceMass");
    if (std::isfinite(f_)) detail::check_model_flattening(f_, file_, line_of("Flattening"), "Flattening");
    if (!(std::isfinite(omega_) && omega_ >= 0)) throw ParseError("missing AngularVelocity", {file_, {}, "AngularVelocity"});
    if (std::isfinite(f_) == std::isfinite(j2_))
      throw ParseError("exactly one of Flattening and DynamicalFormFactor must be given", {file_, {}, "Flattening"});
    if (!(meta.corrmult > 0)) throw ParseError("CorrectionMultiplier must be positive", {file_, {}, "CorrectionMultiplier"});
    if (meta.id.size() != kIdLength)
      throw ParseError("ID must have exactly 8 characters, got \"" + meta.id + "\"", {file_, {}, "ID"});
    model.reference = NormalFieldParameters{model.name.empty() ? "reference" : model.name + " reference", a_, gm_, omega_,
                                            std::isfinite(f_) ? f_ : 0.0, std::isfinite(j2_) ? j2_ : 0.0};
    if (model.name.empty()) model.name = path_.stem().string();
  }

  std::filesystem::path path_;
  std::string file_;
  std::ifstream in_;
  int line_no_ = 1;
  std::string key_, val_;
  std::map<std::string, int> key_lines_;  // key → its line
  double a_ = NAN, gm_ = NAN, omega_ = NAN, f_ = NAN, j2_ = NAN;
};

// The coefficient sets of the `.cof` beside `egm`: the ID, the gravitational set (C̄00 = 0 in
// the file, 1 in the model), the optional correction set, nothing after them.
void read_cof(const std::string& egm, const Truncation& truncation, EgmMetadata& meta) {
  GravityModelData& model = meta.model;
  const std::string cof = egm + ".cof";
  CofReader r(cof);
  char fid[kIdLength];
  r.read(fid, kIdLength, "ID");
  if (std::string(fid, kIdLength) != meta.id)
    throw ParseError(fmt::format("ID mismatch: {} has \"{}\", {} has \"{}\"", egm, meta.id, cof, std::string(fid, kIdLength)),
                     {cof, {}, "ID"});
  int file_n = 0;
  auto c = r.coefficients(truncation, "gravitational", &file_n);
  if (!c) throw ParseError("the gravitational coefficient set is empty (N = M = -1)", {cof, {}, "gravitational"});
  if (c->c(0, 0) != 0) throw ParseError("the degree 0 coefficient must be 0 in a .egm.cof file", {cof, {}, "C00"});
  c->set(0, 0, 1.0, 0.0);
  model.coefficients = std::move(*c);
  model.file_max_degree = file_n;
  if (auto corr = r.coefficients(truncation, "correction", nullptr)) {
    model.correction = GeoidCorrection{std::move(*corr), meta.corrmult, meta.zeta0};
  } else if (meta.zeta0 != 0) {
    model.correction = GeoidCorrection{SphericalHarmonicCoefficients(0, 0), meta.corrmult, meta.zeta0};
  }
  r.expect_end();
}

// The 8-character ID of a model written here: its name's letters and digits, upper case,
// padded with X.
std::string model_id(const std::string& name) {
  std::string id;
  for (char ch : name)
    if (std::isalnum(static_cast<unsigned char>(ch)) && id.size() < kIdLength)
      id += static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  id.resize(kIdLength, 'X');
  return id;
}

std::string egm_metadata_text(const GravityModelData& model, const std::filesystem::path& prefix, const std::string& id) {
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
  return meta;
}

std::string cof_bytes(const GravityModelData& model, const std::string& id) {
  const SphericalHarmonicCoefficients& c = model.coefficients;
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
  return bin;
}

}  // namespace

GravityModelData read_egm_file(const std::filesystem::path& path, const Truncation& truncation) {
  EgmMetadata meta = EgmMetadataReader(path).read();
  read_cof(path.string(), truncation, meta);
  return std::move(meta.model);
}

void write_egm_files(const GravityModelData& model, const std::filesystem::path& prefix) {
  const SphericalHarmonicCoefficients& c = model.coefficients;
  if (c.c(0, 0) != 1.0)
    throw InputError(fmt::format("C00 = {} cannot be written to a GeographicLib file (it must be 1; rescale GM)", c.c(0, 0)),
                     {"", {}, "C00"});
  const std::string id = model_id(model.name);
  const std::string meta = egm_metadata_text(model, prefix, id);
  const std::string bin = cof_bytes(model, id);
  std::filesystem::path egm = prefix;
  egm += ".egm";
  std::filesystem::path cof = prefix;
  cof += ".egm.cof";
  write_file_atomically(cof, bin);
  write_file_atomically(egm, meta);
}

}  // namespace meridian::io
