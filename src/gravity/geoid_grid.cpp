#include "meridian/gravity/geoid_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gravity {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw IoError("cannot open geoid grid", {p.string(), {}, ""});
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <class T>
T big_endian(const char* p) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof b);
  if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + sizeof b);
  T v;
  std::memcpy(&v, b, sizeof v);
  return v;
}

void finish_longitudes(GeoidGrid& g, bool duplicate_last) {
  const double period = 2 * std::numbers::pi / std::abs(g.dlon_rad);
  const long cols360 = std::lround(period);
  const int span = duplicate_last ? g.cols - 1 : g.cols;
  g.wraps_longitude = std::abs(period - static_cast<double>(cols360)) < 1e-6 && span >= cols360;
  g.lon_period_cols = g.wraps_longitude ? static_cast<int>(cols360) : 0;
}

GeoidGrid read_gtx(const std::filesystem::path& path) {
  const std::string file = path.string(), d = slurp(path);
  if (d.size() < 40) throw ParseError("file too short for a .gtx header (40 bytes)", {file, {}, "header"});
  GeoidGrid g;
  g.source_file = file;
  g.format = "gtx";
  const double lat0 = big_endian<double>(d.data()), lon0 = big_endian<double>(d.data() + 8);
  const double dlat = big_endian<double>(d.data() + 16), dlon = big_endian<double>(d.data() + 24);
  g.rows = big_endian<std::int32_t>(d.data() + 32);
  g.cols = big_endian<std::int32_t>(d.data() + 36);
  if (!(std::isfinite(lat0) && std::isfinite(lon0) && dlat > 0 && dlon > 0 && g.rows >= 2 && g.cols >= 2 &&
        lat0 >= -90 && lat0 + (g.rows - 1) * dlat <= 90 + 1e-9))
    throw ParseError(fmt::format("implausible .gtx header: origin {} {}, step {} {}, size {} x {}", lat0, lon0, dlat, dlon,
                                 g.rows, g.cols),
                     {file, {}, "header"});
  const std::size_t n = static_cast<std::size_t>(g.rows) * static_cast<std::size_t>(g.cols);
  if (d.size() != 40 + 4 * n)
    throw ParseError(fmt::format("file has {} bytes, a {} x {} grid needs {}", d.size(), g.rows, g.cols, 40 + 4 * n),
                     {file, {}, "data"});
  g.first_lat_rad = lat0 * kDeg;
  g.first_lon_rad = lon0 * kDeg;
  g.dlat_rad = dlat * kDeg;
  g.dlon_rad = dlon * kDeg;
  g.f32_.resize(n);
  for (std::size_t k = 0; k < n; ++k) g.f32_[k] = big_endian<float>(d.data() + 40 + 4 * k);
  finish_longitudes(g, true);
  return g;
}

GeoidGrid read_pgm(const std::filesystem::path& path) {
  const std::string file = path.string(), d = slurp(path);
  std::size_t pos = 0;
  int line = 0;
  auto next_line = [&]() -> std::string {
    const std::size_t e = d.find('\n', pos);
    if (e == std::string::npos) throw ParseError("truncated PGM header", {file, line, "header"});
    std::string s = d.substr(pos, e - pos);
    pos = e + 1;
    ++line;
    return s;
  };
  if (next_line() != "P5") throw ParseError("not a binary PGM (first line must be P5)", {file, 1, "header"});
  GeoidGrid g;
  g.source_file = file;
  g.format = "pgm";
  bool have_offset = false, have_scale = false;
  std::string s;
  while (true) {
    s = next_line();
    if (s.empty()) continue;
    if (s[0] != '#') break;
    std::istringstream is(s.substr(1));
    std::string key;
    is >> key;
    if (key == "Offset") have_offset = static_cast<bool>(is >> g.offset_m_);
    if (key == "Scale") have_scale = static_cast<bool>(is >> g.scale_m_) && g.scale_m_ > 0;
  }
  std::istringstream size(s);
  if (!(size >> g.cols >> g.rows) || g.cols < 2 || g.rows < 2 || g.cols % 2 || g.rows % 2 == 0)
    throw ParseError("bad raster size \"" + s + "\" (need even width, odd height)", {file, line, "size"});
  const int size_line = line;
  if (next_line() != "65535") throw ParseError("maxval must be 65535 (16-bit)", {file, size_line + 1, "maxval"});
  if (!have_offset || !have_scale) throw ParseError("missing # Offset or positive # Scale comment", {file, {}, "header"});
  const std::size_t n = static_cast<std::size_t>(g.rows) * static_cast<std::size_t>(g.cols);
  if (d.size() - pos != 2 * n)
    throw ParseError(fmt::format("{} data bytes, a {} x {} raster needs {}", d.size() - pos, g.cols, g.rows, 2 * n),
                     {file, {}, "data"});
  g.u16_.resize(n);
  for (std::size_t k = 0; k < n; ++k) g.u16_[k] = big_endian<std::uint16_t>(d.data() + pos + 2 * k);
  g.first_lat_rad = std::numbers::pi / 2;
  g.dlat_rad = -std::numbers::pi / (g.rows - 1);
  g.first_lon_rad = 0;
  g.dlon_rad = 2 * std::numbers::pi / g.cols;
  finish_longitudes(g, false);
  return g;
}

// Keys' cubic convolution weights (a = −1/2) for fraction x ∈ [0, 1).
void cubic_weights(double x, double w[4]) {
  w[0] = ((-0.5 * x + 1.0) * x - 0.5) * x;
  w[1] = (1.5 * x - 2.5) * x * x + 1.0;
  w[2] = ((-1.5 * x + 2.0) * x + 0.5) * x;
  w[3] = (0.5 * x - 0.5) * x * x;
}

}  // namespace

GeoidGrid read_geoid_grid(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".gtx") return read_gtx(path);
  if (ext == ".pgm") return read_pgm(path);
  throw InputError("unknown geoid grid format \"" + ext + "\" (expected .gtx or .pgm)", {path.string(), {}, ""});
}

double grid_geoid_height_m(const GeoidGrid& g, double lat_rad, double lon_rad, GridInterpolation interp) {
  if (!std::isfinite(lat_rad) || !std::isfinite(lon_rad) || std::abs(lat_rad) > std::numbers::pi / 2)
    throw InputError("latitude/longitude outside the valid range", {g.source_file, {}, "lat"});
  const double fy = (lat_rad - g.first_lat_rad) / g.dlat_rad;
  double fx = (lon_rad - g.first_lon_rad) / g.dlon_rad;
  if (g.wraps_longitude) fx -= std::floor(fx / g.lon_period_cols) * g.lon_period_cols;
  const double eps = 1e-9;
  if (fy < -eps || fy > g.rows - 1 + eps || fx < -eps || (!g.wraps_longitude && fx > g.cols - 1 + eps))
    throw InputError(fmt::format("point {:.6f} {:.6f} deg is outside the geoid grid", lat_rad / kDeg, lon_rad / kDeg),
                     {g.source_file, {}, "lat"});
  const int iy = std::clamp(static_cast<int>(std::floor(fy)), 0, g.rows - 2);
  const int ix = g.wraps_longitude ? static_cast<int>(std::floor(fx)) : std::clamp(static_cast<int>(std::floor(fx)), 0, g.cols - 2);
  const double y = fy - iy, x = fx - ix;
  auto col = [&](int c) { return g.wraps_longitude ? ((c % g.lon_period_cols) + g.lon_period_cols) % g.lon_period_cols : c; };
  auto node = [&](int r, int c) {
    const double v = g.node_m(r, col(c));
    if (!std::isfinite(v)) throw InputError("the geoid grid has no data near this point", {g.source_file, {}, "lat"});
    return v;
  };
  const bool cubic_ok = interp == GridInterpolation::Bicubic && iy >= 1 && iy + 2 <= g.rows - 1 &&
                        (g.wraps_longitude || (ix >= 1 && ix + 2 <= g.cols - 1));
  if (!cubic_ok) {
    const double v00 = node(iy, ix), v01 = node(iy, ix + 1), v10 = node(iy + 1, ix), v11 = node(iy + 1, ix + 1);
    return (1 - y) * ((1 - x) * v00 + x * v01) + y * ((1 - x) * v10 + x * v11);
  }
  double wx[4], wy[4], h = 0;
  cubic_weights(x, wx);
  cubic_weights(y, wy);
  for (int j = 0; j < 4; ++j) {
    double row = 0;
    for (int i = 0; i < 4; ++i) row += wx[i] * node(iy - 1 + j, ix - 1 + i);
    h += wy[j] * row;
  }
  return h;
}

GridDeflection grid_deflection_fallback(const GeoidGrid& g, double lat_rad, double lon_rad, double a_m, double f) {
  const double e2 = f * (2 - f), s = std::sin(lat_rad), w = std::sqrt(1 - e2 * s * s);
  const double m_radius = a_m * (1 - e2) / (w * w * w), n_radius = a_m / w;  // meridian, prime vertical
  const double hy = std::abs(g.dlat_rad), hx = std::abs(g.dlon_rad);
  const double lat_n = std::min(lat_rad + hy, std::numbers::pi / 2), lat_s = std::max(lat_rad - hy, -std::numbers::pi / 2);
  GridDeflection d;
  d.xi_rad = -(grid_geoid_height_m(g, lat_n, lon_rad) - grid_geoid_height_m(g, lat_s, lon_rad)) / ((lat_n - lat_s) * m_radius);
  const double c = std::cos(lat_rad);
  d.eta_rad = c > 1e-12 ? -(grid_geoid_height_m(g, lat_rad, lon_rad + hx) - grid_geoid_height_m(g, lat_rad, lon_rad - hx)) /
                              (2 * hx * n_radius * c)
                        : 0.0;
  return d;
}

const char* to_string(GridInterpolation interpolation) noexcept {
  return interpolation == GridInterpolation::Bilinear ? "bilinear" : "bicubic";
}

GridPointResult evaluate_grid_point(const GeoidGrid& grid, double lat_rad, double lon_rad,
                                    GridInterpolation interpolation) {
  GridPointResult r;
  r.grid_file = grid.source_file;
  r.interpolation = interpolation;
  r.lat_rad = lat_rad;
  r.lon_rad = lon_rad;
  r.geoid_m = grid_geoid_height_m(grid, lat_rad, lon_rad, interpolation);
  r.fallback = grid_deflection_fallback(grid, lat_rad, lon_rad);
  return r;
}

}  // namespace meridian::gravity
