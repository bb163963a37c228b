#include "meridian/gravity/grid_spec.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/gravity_field.hpp"

namespace meridian::gravity {
namespace {

constexpr double kGridRelTolerance = 1e-9;  // spans that must be whole multiples of the spacing

// (span / spacing) as a whole number; -1 when it is not one.
long long whole_intervals(double span_deg, double spacing_deg) {
  const double n = span_deg / spacing_deg;
  if (n < 1 - kGridRelTolerance) return 0;  // the spacing is larger than the span: no interval
  const double k = std::round(n);
  if (!(std::abs(n - k) <= kGridRelTolerance * std::max(1.0, n))) return -1;
  return static_cast<long long>(k);
}

std::string_view grid_trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool grid_parse_number(std::string_view s, double& out) {
  s = grid_trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(out);
}

double grid_parse_one_spacing(std::string_view s) {
  s = grid_trim(s);
  double factor = 1.0;
  if (!s.empty()) {
    const char u = s.back();
    if (u == 'd' || u == 'D') s.remove_suffix(1);
    else if (u == 'm' || u == 'M') factor = 1.0 / 60.0, s.remove_suffix(1);
    else if (u == 's' || u == 'S') factor = 1.0 / 3600.0, s.remove_suffix(1);
  }
  double v = 0;
  if (!grid_parse_number(s, v))
    throw InputError(fmt::format("cannot read spacing \"{}\": expected a number with an optional unit d, m or s "
                                 "(e.g. 30s, 5m, 0.5d, 0.25)",
                                 std::string(s)),
                     {"", {}, "--spacing"});
  if (!(v > 0)) throw InputError(fmt::format("spacing must be positive, got {}", v), {"", {}, "--spacing"});
  return v * factor;
}

}  // namespace

std::string_view to_string(GridQuantity q) noexcept {
  switch (q) {
    case GridQuantity::Xi: return "xi";
    case GridQuantity::Eta: return "eta";
    case GridQuantity::Geoid: return "geoid";
    case GridQuantity::Anomaly: return "anomaly";
    case GridQuantity::DisturbanceEast: return "dg_east";
    case GridQuantity::DisturbanceNorth: return "dg_north";
    case GridQuantity::DisturbanceUp: return "dg_up";
  }
  return "?";
}

GridQuantity grid_quantity_from_string(std::string_view name) {
  for (GridQuantity q : {GridQuantity::Xi, GridQuantity::Eta, GridQuantity::Geoid, GridQuantity::Anomaly,
                         GridQuantity::DisturbanceEast, GridQuantity::DisturbanceNorth, GridQuantity::DisturbanceUp})
    if (name == to_string(q)) return q;
  if (name == "n") return GridQuantity::Geoid;
  if (name == "dg") return GridQuantity::Anomaly;
  throw InputError(fmt::format("unknown quantity \"{}\" (xi, eta, geoid, anomaly, dg_east, dg_north, dg_up)",
                               std::string(name)),
                   {"", {}, "quantities"});
}

std::vector<GridQuantity> parse_grid_quantities(std::string_view list) {
  std::vector<GridQuantity> quantities;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view name = list.substr(start, comma - start);
    if (!name.empty()) quantities.push_back(grid_quantity_from_string(name));
    start = comma + 1;
  }
  return quantities;
}

std::string_view to_string(GridRegistration r) noexcept {
  return r == GridRegistration::Pixel ? "pixel" : "gridline";
}

void GridSpec::validate() const {
  const ErrorContext region{"", {}, "region"}, spacing{"", {}, "spacing"};
  if (!std::isfinite(west_deg) || !std::isfinite(east_deg) || !std::isfinite(south_deg) || !std::isfinite(north_deg))
    throw InputError("region W/E/S/N must be finite numbers", region);
  if (!(west_deg < east_deg))
    throw InputError(fmt::format("region: W ({}) must be less than E ({})", west_deg, east_deg), region);
  if (east_deg - west_deg > 360.0 + 1e-9)
    throw InputError(fmt::format("region: E − W = {}° is more than 360°", east_deg - west_deg), region);
  if (!(south_deg < north_deg))
    throw InputError(fmt::format("region: S ({}) must be less than N ({})", south_deg, north_deg), region);
  if (south_deg < -90.0 || north_deg > 90.0)
    throw InputError(fmt::format("region: S ({}) and N ({}) must lie within [-90, 90]", south_deg, north_deg),
                     region);
  if (!(lon_spacing_deg > 0) || !(lat_spacing_deg > 0) || !std::isfinite(lon_spacing_deg) ||
      !std::isfinite(lat_spacing_deg))
    throw InputError("spacing must be positive and finite", spacing);
  const long long nx = whole_intervals(east_deg - west_deg, lon_spacing_deg);
  const long long ny = whole_intervals(north_deg - south_deg, lat_spacing_deg);
  if (nx == 0 || ny == 0)
    throw InputError(fmt::format("spacing {}°/{}° gives no node in the region {}/{}/{}/{} ({} registration)",
                                 lon_spacing_deg, lat_spacing_deg, west_deg, east_deg, south_deg, north_deg,
                                 to_string(registration)),
                     spacing);
  if (nx < 0)
    throw InputError(fmt::format("the region's width E − W = {}° is not a whole multiple of the longitude spacing {}°",
                                 east_deg - west_deg, lon_spacing_deg),
                     spacing);
  if (ny < 0)
    throw InputError(fmt::format("the region's height N − S = {}° is not a whole multiple of the latitude spacing {}°",
                                 north_deg - south_deg, lat_spacing_deg),
                     spacing);
  const double extra = registration == GridRegistration::Gridline ? 1.0 : 0.0;
  const double nodes = (static_cast<double>(nx) + extra) * (static_cast<double>(ny) + extra);
  if (nodes > static_cast<double>(kMaxNodes))
    throw InputError(fmt::format("the grid has {:.4g} nodes, more than the {} allowed (choose a larger spacing or a "
                                 "smaller region)",
                                 nodes, kMaxNodes),
                     spacing);
  if (!std::isfinite(height_m) || height_m < kMinHeight_m || height_m > kMaxHeight_m)
    throw InputError(fmt::format("height {} m is outside [{}, {}] m", height_m, kMinHeight_m, kMaxHeight_m),
                     {"", {}, "height"});
  if (quantities.empty()) throw InputError("no quantity requested", {"", {}, "quantities"});
  for (std::size_t i = 0; i < quantities.size(); ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (quantities[i] == quantities[k])
        throw InputError(fmt::format("quantity {} is requested twice", to_string(quantities[i])),
                         {"", {}, "quantities"});
}

std::size_t GridSpec::columns() const {
  const long long nx = whole_intervals(east_deg - west_deg, lon_spacing_deg);
  return static_cast<std::size_t>(std::max(0LL, nx)) + (registration == GridRegistration::Gridline ? 1 : 0);
}

std::size_t GridSpec::rows() const {
  const long long ny = whole_intervals(north_deg - south_deg, lat_spacing_deg);
  return static_cast<std::size_t>(std::max(0LL, ny)) + (registration == GridRegistration::Gridline ? 1 : 0);
}

double GridSpec::lon_deg(std::size_t i) const {
  if (registration == GridRegistration::Pixel) return west_deg + (static_cast<double>(i) + 0.5) * lon_spacing_deg;
  if (i + 1 == columns()) return east_deg;
  return west_deg + static_cast<double>(i) * lon_spacing_deg;
}

double GridSpec::lat_deg(std::size_t j) const {
  if (registration == GridRegistration::Pixel) return south_deg + (static_cast<double>(j) + 0.5) * lat_spacing_deg;
  if (j + 1 == rows()) return north_deg;
  return south_deg + static_cast<double>(j) * lat_spacing_deg;
}

double GridSpec::lon_rad(std::size_t i) const { return units::deg_to_rad(lon_deg(i)); }

double GridSpec::lat_rad(std::size_t j) const {
  return std::clamp(units::deg_to_rad(lat_deg(j)), -units::kPi / 2, units::kPi / 2);
}

bool GridSpec::global_longitude() const { return std::abs(east_deg - west_deg - 360.0) <= 1e-9; }

std::size_t GridSpec::samples_per_turn() const {
  const long long n = whole_intervals(360.0, lon_spacing_deg);
  return n > 0 ? static_cast<std::size_t>(n) : 0;
}

void parse_grid_region(std::string_view text, GridSpec& spec) {
  const std::string_view t = grid_trim(text);
  if (t == "g") {
    spec.west_deg = 0, spec.east_deg = 360, spec.south_deg = -90, spec.north_deg = 90;
    return;
  }
  if (t == "d") {
    spec.west_deg = -180, spec.east_deg = 180, spec.south_deg = -90, spec.north_deg = 90;
    return;
  }
  double v[4];
  std::string_view rest = t;
  for (int k = 0; k < 4; ++k) {
    const std::size_t slash = rest.find('/');
    const std::string_view part = k < 3 ? rest.substr(0, slash) : rest;
    if ((k < 3 && slash == std::string_view::npos) || !grid_parse_number(part, v[k]))
      throw InputError(fmt::format("cannot read region \"{}\": expected W/E/S/N in decimal degrees "
                                   "(e.g. -10/30/35/60), g or d",
                                   std::string(text)),
                       {"", {}, "--region"});
    if (k < 3) rest = rest.substr(slash + 1);
  }
  spec.west_deg = v[0], spec.east_deg = v[1], spec.south_deg = v[2], spec.north_deg = v[3];
}

void parse_grid_spacing(std::string_view text, double& lon_deg, double& lat_deg) {
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) {
    lon_deg = lat_deg = grid_parse_one_spacing(text);
    return;
  }
  lon_deg = grid_parse_one_spacing(text.substr(0, slash));
  lat_deg = grid_parse_one_spacing(text.substr(slash + 1));
}

}  // namespace meridian::gravity
