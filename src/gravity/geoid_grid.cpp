#include "meridian/gravity/geoid_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gravity {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// Keys' cubic convolution weights (a = −1/2) for fraction x ∈ [0, 1];
// exactly (0, 1, 0, 0) at x = 0 and (0, 0, 1, 0) at x = 1.
void cubic_weights(double x, double w[4]) {
  w[0] = ((-0.5 * x + 1.0) * x - 0.5) * x;
  w[1] = (1.5 * x - 2.5) * x * x + 1.0;
  w[2] = ((-1.5 * x + 2.0) * x + 0.5) * x;
  w[3] = (0.5 * x - 0.5) * x * x;
}

std::string deg(double rad) { return fmt::format("{:.6f}", rad / kDeg); }

// Where a point falls in the grid: the cell's south-west (first) node and
// the fractions inside it.
struct Cell {
  int iy = 0, ix = 0;
  double y = 0, x = 0;
};

Cell locate(const GeoidGrid& g, double lat_rad, double lon_rad) {
  const std::string& file = g.source_file;
  if (!std::isfinite(lat_rad) || std::abs(lat_rad) > std::numbers::pi / 2)
    throw InputError(fmt::format("latitude {} deg is not within [-90, 90]", lat_rad / kDeg), {file, {}, "lat"});
  if (!std::isfinite(lon_rad)) throw InputError("longitude is not a finite number", {file, {}, "lon"});
  constexpr double eps = 1e-9;  // in grid steps
  // On a grid line within rounding: exactly on it, so the weights of the
  // nodes beyond it are exactly zero and those nodes are not needed.
  auto snap = [](double f) { return std::abs(f - std::round(f)) < eps ? std::round(f) : f; };
  const double fy = snap((lat_rad - g.first_lat_rad) / g.dlat_rad);
  if (fy < -eps || fy > g.rows - 1 + eps) {
    const double a = g.first_lat_rad, b = g.first_lat_rad + (g.rows - 1) * g.dlat_rad;
    throw InputError(fmt::format("latitude {} deg is outside the grid's latitudes [{}, {}] deg", deg(lat_rad),
                                 deg(std::min(a, b)), deg(std::max(a, b))),
                     {file, {}, "lat"});
  }
  // The one place longitudes are reduced: east of the grid's first column, modulo 360°.
  const double turn = 2 * std::numbers::pi;
  double east = std::fmod(lon_rad - g.first_lon_rad, turn);
  if (east < 0) east += turn;
  double fx = snap(east / g.dlon_rad);
  const double turn_cols = turn / g.dlon_rad;
  if (fx > turn_cols - eps) fx = 0;  // a hair west of the first column
  Cell c;
  if (g.wraps_longitude) {
    c.ix = static_cast<int>(std::floor(fx)) % g.lon_period_cols;
    c.x = fx - std::floor(fx);
  } else {
    if (fx > g.cols - 1 + eps)
      throw InputError(fmt::format("longitude {} deg is outside the grid's longitudes [{}, {}] deg (compared modulo 360 deg)",
                                   deg(lon_rad), deg(g.first_lon_rad), deg(g.first_lon_rad + (g.cols - 1) * g.dlon_rad)),
                       {file, {}, "lon"});
    c.ix = std::clamp(static_cast<int>(std::floor(fx)), 0, g.cols - 2);
    c.x = std::clamp(fx - c.ix, 0.0, 1.0);
  }
  c.iy = std::clamp(static_cast<int>(std::floor(fy)), 0, g.rows - 2);
  c.y = std::clamp(fy - c.iy, 0.0, 1.0);
  return c;
}

// n×n nodes from (r0, c0) with weights wy ⊗ wx; columns wrap on a global grid.
struct Stencil {
  int n = 2, r0 = 0, c0 = 0;
  double wy[4] = {}, wx[4] = {};
};

int column(const GeoidGrid& g, int c) {
  return g.wraps_longitude ? ((c % g.lon_period_cols) + g.lon_period_cols) % g.lon_period_cols : c;
}

// The first node with a non-zero weight that holds no data, or the sum.
struct Sum {
  double value = 0;
  std::optional<std::pair<int, int>> missing;  // (row, column) in the file
};

Sum weighted_sum(const GeoidGrid& g, const Stencil& s) {
  Sum out;
  for (int j = 0; j < s.n; ++j)
    for (int i = 0; i < s.n; ++i) {
      const double w = s.wy[j] * s.wx[i];
      if (w == 0) continue;
      const int r = s.r0 + j, c = column(g, s.c0 + i);
      const std::optional<double> v = g.node_m(r, c);
      if (!v) {
        out.missing.emplace(r, c);
        return out;
      }
      out.value += w * *v;
    }
  return out;
}

std::string node_description(const GeoidGrid& g, int r, int c) {
  const double v = g.stored_m(r, c);
  return fmt::format("node (row {}, column {}) at lat {} deg, lon {} deg, which holds {:g} ({})", r, c, deg(g.first_lat_rad + r * g.dlat_rad),
                     deg(g.first_lon_rad + c * g.dlon_rad), v,
                     static_cast<float>(v) == GeoidGrid::kGtxNoData ? "the GTX no-data value"
                     : std::isfinite(v) ? fmt::format("not a geoid height: |N| > {} m means no data", GeoidGrid::kMaxGeoidHeight_m)
                                        : "not a number");
}

}  // namespace

// Whole turns of 360° in the columns: wrap when cols·Δλ reaches 360° (with
// or without a repeated first column) and 360°/Δλ is a whole number.
void GeoidGrid::set_longitude_period(double dlon_deg) noexcept {
  const double period = 360.0 / dlon_deg;
  if (!(period <= cols + 1.0)) return;  // regional (also keeps lround in range)
  const long cols360 = std::lround(period);
  wraps_longitude = std::abs(period - static_cast<double>(cols360)) < 1e-9 * period && cols >= cols360;
  lon_period_cols = wraps_longitude ? static_cast<int>(cols360) : 0;
}

std::optional<double> GeoidGrid::node_m(int r, int c) const noexcept {
  const double v = stored_m(r, c);
  if (u16_.empty() && f32_[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c)] ==
                          kGtxNoData)
    return std::nullopt;
  if (!std::isfinite(v) || std::abs(v) > kMaxGeoidHeight_m) return std::nullopt;
  return v;
}

GridHeight grid_geoid_height(const GeoidGrid& g, double lat_rad, double lon_rad, GridInterpolation interp) {
  const Cell cell = locate(g, lat_rad, lon_rad);
  Stencil bilinear{2, cell.iy, cell.ix, {1 - cell.y, cell.y}, {1 - cell.x, cell.x}};
  GridHeight h;
  h.used = GridInterpolation::Bilinear;
  if (interp == GridInterpolation::Bicubic) {
    const bool inside = cell.iy >= 1 && cell.iy + 2 <= g.rows - 1 &&
                        (g.wraps_longitude || (cell.ix >= 1 && cell.ix + 2 <= g.cols - 1));
    if (inside) {
      Stencil cubic{4, cell.iy - 1, cell.ix - 1, {}, {}};
      cubic_weights(cell.y, cubic.wy);
      cubic_weights(cell.x, cubic.wx);
      const Sum s = weighted_sum(g, cubic);
      if (!s.missing) {
        h.geoid_m = s.value;
        h.used = GridInterpolation::Bicubic;
        return h;
      }
      h.note = "bicubic interpolation needs " + node_description(g, s.missing->first, s.missing->second) +
               "; bilinear interpolation from the 4 nodes around the point was used";
    } else {
      h.note = "bicubic interpolation needs 4 x 4 nodes and the point is in a cell at the grid's edge; bilinear "
               "interpolation from the 4 nodes around the point was used";
    }
  }
  const Sum s = weighted_sum(g, bilinear);
  if (s.missing) {
    const auto [r, c] = *s.missing;
    throw InputError(fmt::format("no geoid height at {} deg, {} deg: bilinear interpolation needs {}", deg(lat_rad),
                                 deg(lon_rad), node_description(g, r, c)),
                     {g.source_file, {}, fmt::format("node({},{})", r, c)});
  }
  h.geoid_m = s.value;
  return h;
}

double grid_geoid_height_m(const GeoidGrid& g, double lat_rad, double lon_rad, GridInterpolation interp) {
  return grid_geoid_height(g, lat_rad, lon_rad, interp).geoid_m;
}

GridDeflection grid_deflection_fallback(const GeoidGrid& g, double lat_rad, double lon_rad, double a_m, double f,
                                        GridInterpolation interp) {
  const double e2 = f * (2 - f), s = std::sin(lat_rad), w = std::sqrt(1 - e2 * s * s);
  const double m_radius = a_m * (1 - e2) / (w * w * w), n_radius = a_m / w;  // meridian, prime vertical
  const double hy = std::abs(g.dlat_rad), hx = std::abs(g.dlon_rad);
  const double lat_n = std::min(lat_rad + hy, std::numbers::pi / 2), lat_s = std::max(lat_rad - hy, -std::numbers::pi / 2);
  auto n_at = [&](double la, double lo) { return grid_geoid_height_m(g, la, lo, interp); };
  GridDeflection d;
  d.xi_rad = -(n_at(lat_n, lon_rad) - n_at(lat_s, lon_rad)) / ((lat_n - lat_s) * m_radius);
  const double c = std::cos(lat_rad);
  d.eta_rad = c > 1e-12 ? -(n_at(lat_rad, lon_rad + hx) - n_at(lat_rad, lon_rad - hx)) / (2 * hx * n_radius * c) : 0.0;
  return d;
}

const char* to_string(GridInterpolation interpolation) noexcept {
  return interpolation == GridInterpolation::Bilinear ? "bilinear" : "bicubic";
}

GridModelInfo grid_model_info(const GeoidGrid& grid) {
  GridModelInfo info;
  info.format = grid.format;
  info.metadata = grid.metadata;
  if (const auto it = grid.metadata.find("Description"); it != grid.metadata.end() && !it->second.empty())
    info.model = it->second;
  info.warnings.push_back(fmt::format(
      "the .{} file does not state {}the degree, GM, reference radius, tide system or normalisation of the model its "
      "heights come from: check its tide system (mean-tide, zero-tide and tide-free geoids differ by up to decimetres "
      "at high latitudes) before combining these heights with others",
      grid.format, info.model ? "" : "the model, "));
  return info;
}

GridPointResult evaluate_grid_point(const GeoidGrid& grid, double lat_rad, double lon_rad,
                                    GridInterpolation interpolation) {
  GridPointResult r;
  r.grid_file = grid.source_file;
  r.grid = grid_model_info(grid);
  r.interpolation = interpolation;
  r.lat_rad = lat_rad;
  r.lon_rad = lon_rad;
  const GridHeight h = grid_geoid_height(grid, lat_rad, lon_rad, interpolation);
  r.geoid_m = h.geoid_m;
  r.interpolation_used = h.used;
  if (!h.note.empty()) r.notes.push_back(h.note);
  try {
    const GridDeflection d = grid_deflection_fallback(grid, lat_rad, lon_rad, 6378137.0, 1 / 298.257223563, interpolation);
    if (!std::isfinite(d.xi_rad) || !std::isfinite(d.eta_rad))
      throw InputError("the grid's slope is not finite here", {grid.source_file, {}, "lat"});
    r.fallback = d;
  } catch (const InputError& e) {
    r.fallback_unavailable =
        "the grid-gradient deflection needs N one grid step north, south, east and west of the point: " + e.message();
  }
  return r;
}

}  // namespace meridian::gravity
