#include "meridian/io/gravity_geoid_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/utf8.hpp"
#include "gravity_text.hpp"

namespace meridian::io {
namespace {

using gravity::GeoidGrid;

constexpr double kMinStep_deg = 1e-6;

constexpr double kDeg = std::numbers::pi / 180;

template <class T>
T big_endian(const char* p) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof b);
  if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + sizeof b);
  T v;
  std::memcpy(&v, b, sizeof v);
  return v;
}

GeoidGrid read_gtx(const std::filesystem::path& path) {
  const std::string file = path.string(), d = detail::read_whole_file(path, "geoid grid");
  if (d.size() < 40) throw ParseError("file too short for a .gtx header (40 bytes)", {file, {}, "header"});
  GeoidGrid g;
  g.source_file = file;
  g.format = "gtx";
  const double lat0 = big_endian<double>(d.data()), lon0 = big_endian<double>(d.data() + 8);
  const double dlat = big_endian<double>(d.data() + 16), dlon = big_endian<double>(d.data() + 24);
  g.rows = big_endian<std::int32_t>(d.data() + 32);
  g.cols = big_endian<std::int32_t>(d.data() + 36);
  if (g.rows == 1 || g.cols == 1)
    throw ParseError(fmt::format("a {} x {} .gtx grid (a single {}) cannot be interpolated: this reader needs at least "
                                 "2 rows and 2 columns",
                                 g.rows, g.cols, g.rows == 1 ? "parallel" : "meridian"),
                     {file, {}, "header"});
  // Negated comparisons so that NaN fails every test.
  // Steps below 1e-6 deg (0.1 m) are no geoid grid (and a denormal step made
  // the slope deflection infinite).
  const bool ok = lat0 >= -90 && lat0 <= 90 && lon0 >= -360 && lon0 <= 360 && dlat >= kMinStep_deg && dlat <= 180 &&
                  dlon >= kMinStep_deg && dlon <= 360 && g.rows >= 2 && g.cols >= 2 &&
                  lat0 + (g.rows - 1) * dlat <= 90 + 1e-9 && (g.cols - 1) * dlon <= 360 + 1e-9;
  if (!ok)
    throw ParseError(fmt::format("implausible .gtx header: origin {} {}, step {} {}, size {} x {}", lat0, lon0, dlat, dlon,
                                 g.rows, g.cols),
                     {file, {}, "header"});
  const std::size_t n = static_cast<std::size_t>(g.rows) * static_cast<std::size_t>(g.cols);
  if ((d.size() - 40) % 4 != 0 || (d.size() - 40) / 4 != n)
    throw ParseError(fmt::format("file has {} bytes, a {} x {} grid needs {}", d.size(), g.rows, g.cols, 40 + 4 * n),
                     {file, {}, "data"});
  g.first_lat_rad = lat0 * kDeg;
  g.first_lon_rad = lon0 * kDeg;
  g.dlat_rad = dlat * kDeg;
  g.dlon_rad = dlon * kDeg;
  g.f32_.resize(n);
  for (std::size_t k = 0; k < n; ++k) g.f32_[k] = big_endian<float>(d.data() + 40 + 4 * k);
  g.set_longitude_period(dlon);
  return g;
}

// The lines of a PGM header, numbered for errors.
class PgmHeader {
 public:
  PgmHeader(const std::string& file, const std::string& bytes) : file_(file), d_(bytes) {}

  std::string next_line() {
    const std::size_t e = d_.find('\n', pos_);
    if (e == std::string::npos) throw ParseError("truncated PGM header", {file_, line_, "header"});
    if (e - pos_ > detail::kMaxTextLineBytes) throw detail::line_too_long(file_, line_ + 1);
    std::string s = d_.substr(pos_, e - pos_);
    pos_ = e + 1;
    ++line_;
    return s;
  }

  // The `# Key value` comments into g.metadata (Offset and Scale into g's storage); returns
  // the first line that is not a comment (the raster size).
  std::string comments(GeoidGrid& g) {
    bool have_offset = false, have_scale = false;
    int offset_line = 0, scale_line = 0;
    std::string s;
    while (true) {
      s = next_line();
      if (s.empty()) continue;
      if (s[0] != '#') break;
      if (const auto bad = first_invalid_utf8(s))
        throw ParseError(fmt::format("header comment is not UTF-8 text (byte 0x{:02X} at column {})",
                                     static_cast<unsigned char>(s[*bad]), *bad + 1),
                         {file_, line_, "header"});
      std::istringstream is(s.substr(1));
      std::string key, value;
      is >> key;
      std::getline(is >> std::ws, value);
      while (!value.empty() && std::isspace(static_cast<unsigned char>(value.back()))) value.pop_back();
      if (!key.empty() && !g.metadata.count(key)) g.metadata.emplace(key, value);
      // The two keys the heights depend on may be given once only.
      for (auto [name, at] : {std::pair<const char*, int*>{"Offset", &offset_line}, {"Scale", &scale_line}}) {
        if (key != name) continue;
        if (*at != 0)
          throw ParseError(fmt::format("# {} is given twice in the header, on lines {} and {}", name, *at, line_),
                           {file_, line_, name});
        *at = line_;
      }
      std::istringstream num(value);
      if (key == "Offset") have_offset = static_cast<bool>(num >> g.offset_m_) && std::isfinite(g.offset_m_);
      if (key == "Scale") have_scale = static_cast<bool>(num >> g.scale_m_) && g.scale_m_ > 0 && std::isfinite(g.scale_m_);
    }
    offset_and_scale_ = have_offset && have_scale;
    return s;
  }

  int line() const { return line_; }
  std::size_t position() const { return pos_; }
  bool has_offset_and_scale() const { return offset_and_scale_; }

 private:
  const std::string& file_;
  const std::string& d_;
  std::size_t pos_ = 0;
  int line_ = 0;
  bool offset_and_scale_ = false;
};

GeoidGrid read_pgm(const std::filesystem::path& path) {
  const std::string file = path.string(), d = detail::read_whole_file(path, "geoid grid");
  PgmHeader header(file, d);
  if (header.next_line() != "P5") throw ParseError("not a binary PGM (first line must be P5)", {file, 1, "header"});
  GeoidGrid g;
  g.source_file = file;
  g.format = "pgm";
  const std::string s = header.comments(g);
  std::istringstream size(s);
  if (!(size >> g.cols >> g.rows) || g.cols < 2 || g.rows < 2 || g.cols % 2 || g.rows % 2 == 0)
    throw ParseError("bad raster size \"" + s + "\" (need even width, odd height)", {file, header.line(), "size"});
  const int size_line = header.line();
  if (header.next_line() != "65535") throw ParseError("maxval must be 65535 (16-bit)", {file, size_line + 1, "maxval"});
  if (!header.has_offset_and_scale())
    throw ParseError("missing # Offset or positive # Scale comment", {file, {}, "header"});
  const std::size_t pos = header.position();
  const std::size_t n = static_cast<std::size_t>(g.rows) * static_cast<std::size_t>(g.cols);
  if ((d.size() - pos) % 2 != 0 || (d.size() - pos) / 2 != n)
    throw ParseError(fmt::format("{} data bytes, a {} x {} raster needs {}", d.size() - pos, g.cols, g.rows, 2 * n),
                     {file, {}, "data"});
  g.u16_.resize(n);
  for (std::size_t k = 0; k < n; ++k) g.u16_[k] = big_endian<std::uint16_t>(d.data() + pos + 2 * k);
  g.first_lat_rad = std::numbers::pi / 2;
  g.dlat_rad = -std::numbers::pi / (g.rows - 1);
  g.first_lon_rad = 0;
  g.dlon_rad = 2 * std::numbers::pi / g.cols;
  g.set_longitude_period(360.0 / g.cols);
  return g;
}

}  // namespace

GeoidGrid read_geoid_grid(const std::filesystem::path& path) {
  detail::check_readable_path(path);  // a directory is named as one, whatever its extension
  const std::string ext = detail::lower(path.extension().string());
  if (ext == ".gtx") return read_gtx(path);
  if (ext == ".pgm") return read_pgm(path);
  throw InputError("unknown geoid grid format \"" + ext + "\" (expected .gtx or .pgm)", {path.string(), {}, ""});
}

}  // namespace meridian::io
