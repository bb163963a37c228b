#pragma once
/// \file grid.hpp
/// Transverse Mercator grids (Gauss–Krüger 3° and 6° zones, UTM) through
/// GeographicLib::TransverseMercator (Krüger series, accurate to 5 nm within
/// 3900 km of the central meridian). Meridian never hand-codes the series.
///
/// Conventions: latitudes/longitudes in radians (north/east positive);
/// grid coordinates x = northing, y = easting in metres (surveying
/// convention); meridian convergence γ is the bearing of grid north measured
/// clockwise from true north (GeographicLib's definition), so that a grid
/// azimuth is T = α − γ for a geodetic azimuth α. γ > 0 east of the central
/// meridian in the northern hemisphere.

#include <string>

#include "meridian/geodesy/ellipsoid.hpp"

namespace meridian::geodesy {

enum class ZoneSystem { GaussKruger3, GaussKruger6, UTM, Custom };

/// A complete transverse Mercator grid definition.
struct GridDefinition {
  ZoneSystem system = ZoneSystem::GaussKruger6;
  int zone = 0;                   ///< zone number (GK: 1…120 for 3°, 1…60 for 6°; UTM 1…60)
  bool north = true;              ///< UTM hemisphere (false easting/northing choice)
  double central_meridian_rad = 0.0;
  double scale_factor = 1.0;      ///< k0 on the central meridian (GK 1, UTM 0.9996)
  double false_easting_m = 500000.0;
  double false_northing_m = 0.0;  ///< UTM south: 10 000 000 m
  /// GK practice writes the zone number before the easting (e.g. 38 500 000 m).
  /// When true, grid eastings in and out include zone·1e6.
  bool zone_prefix = false;
  Ellipsoid ellipsoid = wgs84();
};

/// Gauss–Krüger 3° zone n: central meridian 3n° E, k0 = 1, FE 500 km.
GridDefinition gauss_kruger_3(int zone, const Ellipsoid& e, bool zone_prefix = false);
/// Gauss–Krüger 6° zone n: central meridian (6n − 3)° E, k0 = 1, FE 500 km.
GridDefinition gauss_kruger_6(int zone, const Ellipsoid& e, bool zone_prefix = false);
/// UTM zone n (1…60), hemisphere, k0 = 0.9996, FE 500 km, FN 0 / 10 000 km.
GridDefinition utm(int zone, bool north, const Ellipsoid& e = wgs84());
/// Zone containing a longitude (radians) in each system.
int gauss_kruger_3_zone(double lon_rad);
int gauss_kruger_6_zone(double lon_rad);
int utm_zone(double lon_rad);

/// Human-readable description, e.g. "Gauss-Kruger 3deg zone 38 (CM 114E), CGCS2000".
std::string describe(const GridDefinition& g);

/// A point on the grid with its local projection properties.
struct GridPoint {
  double x_north_m = 0.0;
  double y_east_m = 0.0;          ///< includes FE (and the zone prefix when set)
  double convergence_rad = 0.0;   ///< γ, see the file comment
  double scale = 1.0;             ///< point scale factor k
};

/// A geographic point with its local projection properties.
struct GeographicPoint {
  double lat_rad = 0.0;
  double lon_rad = 0.0;
  double convergence_rad = 0.0;
  double scale = 1.0;
};

/// An immutable transverse Mercator grid.
class TransverseMercatorGrid {
 public:
  /// Throws InputError for invalid definitions (zone out of range, a ≤ 0…).
  explicit TransverseMercatorGrid(GridDefinition def);
  const GridDefinition& definition() const { return def_; }
  /// Geographic → grid. |lat| ≤ π/2. Throws InputError for non-finite input
  /// or a point more than 45° of longitude from the central meridian.
  GridPoint forward(double lat_rad, double lon_rad) const;
  /// Grid → geographic.
  GeographicPoint reverse(double x_north_m, double y_east_m) const;

 private:
  GridDefinition def_;
};

/// Arc-to-chord correction δ at C for the line C→D (radians), computed
/// rigorously: δ = T_chord − (α_CD − γ_C), where T_chord = atan2(y_D − y_C,
/// x_D − x_C) is the grid azimuth of the straight chord, α_CD the geodesic
/// azimuth at C (GeographicLib::Geodesic on the grid's ellipsoid) and γ_C the
/// convergence at C. Thus T_chord = α − γ + δ.
double arc_to_chord(const TransverseMercatorGrid& grid, double x_c_m, double y_c_m,
                    double x_d_m, double y_d_m);

}  // namespace meridian::geodesy
