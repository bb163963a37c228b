#include "meridian/geodesy/grid.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <utility>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/TransverseMercator.hpp>
#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/checks.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::geodesy {
namespace {

using units::kDegree;

constexpr double kUtmScale = 0.9996;
constexpr double kFalseEasting_m = 500000.0;
constexpr double kUtmSouthFalseNorthing_m = 10000000.0;
constexpr double kZonePrefix_m = 1e6;
// Beyond 6000 km·k0 from the central meridian the series is meaningless; the
// 45° meridian itself stays below 5700 km·k0 (on the equator).
constexpr double kMaxProjectedEasting_m = 6.0e6;
// Slack for values that are mathematically on a limit but rounded past it.
constexpr double kAngleSlack_rad = 1e-15;

// A zone width fraction closer than this to an integer is snapped onto the
// boundary (degree→radian→degree rounding moves 6° to 5.999999999999999°).
constexpr double kZoneSnap = 1e-12;

struct Projected {
  double x_east_m;   // no FE, no prefix, includes k0
  double y_north_m;  // no FN
  double gamma_deg;
  double k;
};

struct Unprojected {
  double lat_deg;
  double dlon_deg;   // λ − λ0
  double gamma_deg;
  double k;
};

std::string ellipsoid_label(const Ellipsoid& e) {
  if (!e.name.empty()) return e.name;
  return fmt::format("a={} m, f={}", e.a_m, e.f);
}

// Longitude in degrees with up to nine decimals and a hemisphere letter.
std::string longitude_label(double lon_rad) {
  const double deg = std::round(lon_rad / kDegree * 1e9) / 1e9;
  return deg < 0 ? fmt::format("{}W", -deg) : fmt::format("{}E", deg);
}

// A GeographicLib projection object is a few dozen doubles computed in well
// under a microsecond, so it is built per call rather than cached in the
// (header-visible) grid class.
GeographicLib::TransverseMercator projection(const GridDefinition& d) {
  return {d.ellipsoid.a_m, d.ellipsoid.f, d.scale_factor};
}

double prefix_m(const GridDefinition& d) {
  return d.zone_prefix ? d.zone * kZonePrefix_m : 0.0;
}

// The standard systems fix CM, k0, FE and FN; a definition that disagrees
// with its own zone is contradictory input.
void require_equal(double actual, double expected, double tol, const char* what,
                   const GridDefinition& d) {
  if (std::abs(actual - expected) > tol)
    throw InputError(fmt::format("{} of {} is {} but the zone requires {}; use ZoneSystem::Custom "
                                 "for a non-standard grid",
                                 what, describe(d), actual, expected));
}

void validate(const GridDefinition& d) {
  require_finite(d.ellipsoid.a_m, "ellipsoid semi-major axis a (m)");
  require_finite(d.ellipsoid.f, "ellipsoid flattening f");
  require_finite(d.central_meridian_rad, "central meridian (rad)");
  require_finite(d.scale_factor, "central scale factor k0");
  require_finite(d.false_easting_m, "false easting (m)");
  require_finite(d.false_northing_m, "false northing (m)");
  if (d.ellipsoid.a_m <= 0)
    throw InputError(fmt::format("ellipsoid semi-major axis a = {} m must be positive",
                                 d.ellipsoid.a_m));
  if (d.ellipsoid.f < 0 || d.ellipsoid.f > 0.01)
    throw InputError(fmt::format(
        "ellipsoid flattening f = {} is outside [0, 0.01] (1/f ≈ 298 for the Earth)",
        d.ellipsoid.f));
  if (d.scale_factor <= 0)
    throw InputError(fmt::format("central scale factor k0 = {} must be positive", d.scale_factor));
  if (std::abs(d.central_meridian_rad) > 2 * units::kPi)
    throw InputError(fmt::format("central meridian {} rad is outside [-2pi, 2pi]",
                                 d.central_meridian_rad));

  double cm_deg = 0;
  switch (d.system) {
    case ZoneSystem::GaussKruger3:
      if (d.zone < 1 || d.zone > 120)
        throw InputError(fmt::format("Gauss-Kruger 3deg zone {} is outside 1..120", d.zone));
      cm_deg = 3.0 * d.zone;
      break;
    case ZoneSystem::GaussKruger6:
      if (d.zone < 1 || d.zone > 60)
        throw InputError(fmt::format("Gauss-Kruger 6deg zone {} is outside 1..60", d.zone));
      cm_deg = 6.0 * d.zone - 3.0;
      break;
    case ZoneSystem::UTM:
      if (d.zone < 1 || d.zone > 60)
        throw InputError(fmt::format("UTM zone {} is outside 1..60", d.zone));
      cm_deg = 6.0 * d.zone - 183.0;
      break;
    case ZoneSystem::Custom:
      if (d.zone_prefix && (d.zone < 1 || d.zone > 999))
        throw InputError(fmt::format(
            "zone {} cannot prefix eastings (zone_prefix needs a zone in 1..999)", d.zone));
      return;
  }
  // Compare modulo 2π so that zone 120's 360° may also be written as 0°.
  const double cm_error = wrap_signed_rad(d.central_meridian_rad - cm_deg * kDegree);
  if (std::abs(cm_error) > 1e-12)
    throw InputError(fmt::format(
        "central meridian of {} is {} deg but the zone requires {} deg; use ZoneSystem::Custom "
        "for a non-standard grid",
        describe(d), d.central_meridian_rad / kDegree, cm_deg));
  const bool is_utm = d.system == ZoneSystem::UTM;
  require_equal(d.scale_factor, is_utm ? kUtmScale : 1.0, 1e-12, "scale factor k0", d);
  require_equal(d.false_easting_m, kFalseEasting_m, 1e-9, "false easting (m)", d);
  require_equal(d.false_northing_m, is_utm && !d.north ? kUtmSouthFalseNorthing_m : 0.0, 1e-9,
                "false northing (m)", d);
}

GridDefinition standard(ZoneSystem system, int zone, double cm_deg, const Ellipsoid& e,
                        bool zone_prefix) {
  GridDefinition d;
  d.system = system;
  d.zone = zone;
  d.central_meridian_rad = cm_deg * kDegree;
  d.scale_factor = 1.0;
  d.false_easting_m = kFalseEasting_m;
  d.false_northing_m = 0.0;
  d.zone_prefix = zone_prefix;
  d.ellipsoid = e;
  return d;
}

// Zone index from a longitude measured in zone widths from the first zone's
// western edge: floor, after snapping values that rounding put just west of
// a boundary onto it.
int zone_index(double q) {
  const double r = std::round(q);
  if (std::abs(q - r) < kZoneSnap) q = r;
  return static_cast<int>(std::floor(q));
}

// Longitude in degrees east, in [0, 360).
double lon_deg_0_360(double lon_rad) {
  require_finite(lon_rad, "longitude (rad)");
  double d = std::fmod(lon_rad / kDegree, 360.0);
  if (d < 0) d += 360.0;
  if (d >= 360.0) d -= 360.0;
  return d;
}

Projected project(const GridDefinition& d, double lat_rad, double dlon_rad) {
  Projected p{};
  projection(d).Forward(0.0, lat_rad / kDegree, dlon_rad / kDegree, p.x_east_m, p.y_north_m,
                        p.gamma_deg, p.k);
  return p;
}

Unprojected unproject(const GridDefinition& d, double x_north_m, double y_east_m) {
  require_finite(x_north_m, "grid northing x (m)");
  require_finite(y_east_m, "grid easting y (m)");
  const double e = y_east_m - d.false_easting_m - prefix_m(d);
  const double n = x_north_m - d.false_northing_m;
  if (std::abs(e) > kMaxProjectedEasting_m * d.scale_factor)
    throw InputError(fmt::format(
        "grid point (x {:.3f} m, y {:.3f} m) is {:.0f} km from the central meridian of {} "
        "(limit {:.0f} km)",
        x_north_m, y_east_m, std::abs(e) / 1000, describe(d),
        kMaxProjectedEasting_m * d.scale_factor / 1000));
  Unprojected u{};
  projection(d).Reverse(0.0, e, n, u.lat_deg, u.dlon_deg, u.gamma_deg, u.k);
  if (std::abs(u.dlon_deg) * kDegree > kMaxCentralMeridianOffset_rad + kAngleSlack_rad)
    throw InputError(fmt::format(
        "grid point (x {:.3f} m, y {:.3f} m) lies {:.6f} deg of longitude from the central "
        "meridian of {} (limit 45 deg)",
        x_north_m, y_east_m, u.dlon_deg, describe(d)));
  return u;
}

}  // namespace

GridDefinition gauss_kruger_3(int zone, const Ellipsoid& e, bool zone_prefix) {
  if (zone < 1 || zone > 120)
    throw InputError(fmt::format("Gauss-Kruger 3deg zone {} is outside 1..120", zone));
  return standard(ZoneSystem::GaussKruger3, zone, 3.0 * zone, e, zone_prefix);
}

GridDefinition gauss_kruger_6(int zone, const Ellipsoid& e, bool zone_prefix) {
  if (zone < 1 || zone > 60)
    throw InputError(fmt::format("Gauss-Kruger 6deg zone {} is outside 1..60", zone));
  return standard(ZoneSystem::GaussKruger6, zone, 6.0 * zone - 3.0, e, zone_prefix);
}

GridDefinition utm(int zone, bool north, const Ellipsoid& e) {
  if (zone < 1 || zone > 60) throw InputError(fmt::format("UTM zone {} is outside 1..60", zone));
  GridDefinition d = standard(ZoneSystem::UTM, zone, 6.0 * zone - 183.0, e, false);
  d.north = north;
  d.scale_factor = kUtmScale;
  d.false_northing_m = north ? 0.0 : kUtmSouthFalseNorthing_m;
  return d;
}

int gauss_kruger_3_zone(double lon_rad) {
  // Zone n spans [3n − 1.5°, 3n + 1.5°); [358.5°, 360°) ∪ [0°, 1.5°) is zone 120.
  const int z = zone_index((lon_deg_0_360(lon_rad) + 1.5) / 3.0);
  return z == 0 ? 120 : z;
}

int gauss_kruger_6_zone(double lon_rad) {
  const int z = zone_index(lon_deg_0_360(lon_rad) / 6.0) + 1;
  return z > 60 ? z - 60 : z;  // 359.9999999999999° snapped onto 360° = 0°
}

int utm_zone(double lon_rad) {
  double d = lon_deg_0_360(lon_rad);  // → [−180°, 180°)
  if (d >= 180.0) d -= 360.0;
  const int z = zone_index((d + 180.0) / 6.0) + 1;
  return z > 60 ? z - 60 : z;
}

std::string describe(const GridDefinition& g) {
  std::string s;
  switch (g.system) {
    case ZoneSystem::GaussKruger3:
    case ZoneSystem::GaussKruger6:
      s = fmt::format("Gauss-Kruger {}deg zone {} (CM {})",
                      g.system == ZoneSystem::GaussKruger3 ? 3 : 6, g.zone,
                      longitude_label(g.central_meridian_rad));
      break;
    case ZoneSystem::UTM:
      s = fmt::format("UTM zone {}{} (CM {})", g.zone, g.north ? 'N' : 'S',
                      longitude_label(g.central_meridian_rad));
      break;
    case ZoneSystem::Custom:
      s = fmt::format("Transverse Mercator (CM {}, k0 {}, FE {} m, FN {} m)",
                      longitude_label(g.central_meridian_rad), g.scale_factor, g.false_easting_m,
                      g.false_northing_m);
      break;
  }
  s += ", " + ellipsoid_label(g.ellipsoid);
  if (g.zone_prefix) s += fmt::format(", eastings prefixed with zone {}", g.zone);
  return s;
}

TransverseMercatorGrid::TransverseMercatorGrid(GridDefinition def) : def_(std::move(def)) {
  validate(def_);
}

GridPoint TransverseMercatorGrid::forward(double lat_rad, double lon_rad) const {
  require_finite(lat_rad, "latitude (rad)");
  require_finite(lon_rad, "longitude (rad)");
  const double half_pi = units::kPi / 2;
  if (std::abs(lat_rad) > half_pi + kAngleSlack_rad)
    throw InputError(fmt::format("latitude {} rad ({} deg) is outside [-90, 90] deg", lat_rad,
                                 lat_rad / kDegree));
  lat_rad = std::clamp(lat_rad, -half_pi, half_pi);
  const double dlon = wrap_signed_rad(lon_rad - def_.central_meridian_rad);
  if (std::abs(dlon) > kMaxCentralMeridianOffset_rad + kAngleSlack_rad)
    throw InputError(fmt::format(
        "longitude {:.9f} deg is {:.6f} deg from the central meridian of {} (limit 45 deg)",
        lon_rad / kDegree, dlon / kDegree, describe(def_)));
  const Projected p = project(def_, lat_rad, dlon);
  GridPoint g;
  g.x_north_m = p.y_north_m + def_.false_northing_m;
  g.y_east_m = p.x_east_m + def_.false_easting_m + prefix_m(def_);
  g.convergence_rad = p.gamma_deg * kDegree;
  g.scale = p.k;
  return g;
}

GeographicPoint TransverseMercatorGrid::reverse(double x_north_m, double y_east_m) const {
  const Unprojected u = unproject(def_, x_north_m, y_east_m);
  GeographicPoint p;
  p.lat_rad = u.lat_deg * kDegree;
  p.lon_rad = def_.central_meridian_rad + u.dlon_deg * kDegree;
  p.convergence_rad = u.gamma_deg * kDegree;
  p.scale = u.k;
  return p;
}

double arc_to_chord(const TransverseMercatorGrid& grid, double x_c_m, double y_c_m,
                    double x_d_m, double y_d_m) {
  const GridDefinition& d = grid.definition();
  require_finite(x_d_m, "grid northing x_D (m)");
  require_finite(y_d_m, "grid easting y_D (m)");
  const Unprojected c = unproject(d, x_c_m, y_c_m);
  const Unprojected e = unproject(d, x_d_m, y_d_m);
  const double dx = x_d_m - x_c_m;
  const double dy = y_d_m - y_c_m;
  if (dx == 0 && dy == 0)
    throw InputError(fmt::format(
        "arc-to-chord needs two distinct points; C and D are both (x {:.3f} m, y {:.3f} m)",
        x_c_m, y_c_m));
  // Longitudes relative to the central meridian: the azimuth does not depend
  // on the origin of longitude and the small numbers keep full precision.
  double azi1_deg = 0;
  double azi2_deg = 0;
  GeographicLib::Geodesic(d.ellipsoid.a_m, d.ellipsoid.f)
      .Inverse(c.lat_deg, c.dlon_deg, e.lat_deg, e.dlon_deg, azi1_deg, azi2_deg);
  const double t_chord = std::atan2(dy, dx);
  const double t_geodesic = (azi1_deg - c.gamma_deg) * kDegree;
  return wrap_signed_rad(t_chord - t_geodesic);
}

double grid_azimuth(double x_c_m, double y_c_m, double x_d_m, double y_d_m) {
  const double dx = x_d_m - x_c_m, dy = y_d_m - y_c_m;
  if (!std::isfinite(dx) || !std::isfinite(dy))
    throw InputError("grid azimuth of a line: the coordinates must be finite");
  if (dx == 0 && dy == 0)
    throw InputError(fmt::format("grid azimuth of a line: both points are at (x {:.3f} m, y {:.3f} m)", x_c_m, y_c_m));
  return wrap_positive_rad(std::atan2(dy, dx));
}

double half_last_digit_m(std::string_view text) {
  const auto dot = text.find('.');
  if (dot == std::string_view::npos || text.find_first_of("eE") != std::string_view::npos) return 0.5;
  std::size_t decimals = 0;
  while (dot + 1 + decimals < text.size() && std::isdigit(static_cast<unsigned char>(text[dot + 1 + decimals])))
    ++decimals;
  return 0.5 * std::pow(10.0, -static_cast<double>(decimals));
}

double grid_azimuth_rounding(double x_c_m, double y_c_m, double x_d_m, double y_d_m, double x_half_unit_m,
                             double y_half_unit_m) {
  grid_azimuth(x_c_m, y_c_m, x_d_m, y_d_m);  // the same errors
  const double dx = x_d_m - x_c_m, dy = y_d_m - y_c_m;
  // dT = (dx·d(dy) − dy·d(dx))/s²
  return (y_half_unit_m * std::fabs(dx) + x_half_unit_m * std::fabs(dy)) / (dx * dx + dy * dy);
}

}  // namespace meridian::geodesy
