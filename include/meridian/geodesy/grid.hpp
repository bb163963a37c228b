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
/// meridian in the northern hemisphere (γ ≈ Δλ·sin φ; e.g. φ = 30° N, one
/// degree east of the central meridian, CGCS2000: γ = +0°30′00.139″), γ < 0
/// west of it; the signs flip in the southern hemisphere.
///
/// Domain: points more than kMaxCentralMeridianOffset_rad (45°) of longitude
/// from the central meridian are rejected; the 6th-order series is accurate
/// to nanometres within 35° and still far below a millimetre at 45°, and
/// such offsets are far outside any practical zone.

#include <string>
#include <string_view>

#include "meridian/core/units.hpp"
#include "meridian/geodesy/ellipsoid.hpp"

namespace meridian::geodesy {

/// Largest accepted |λ − λ0| (radians) in TransverseMercatorGrid.
inline constexpr double kMaxCentralMeridianOffset_rad = 45.0 * units::kDegree;

/// GaussKruger3/6: Chinese/Russian Gauss–Krüger zones numbered eastwards
/// from Greenwich (k0 = 1); UTM: Universal Transverse Mercator (k0 = 0.9996);
/// Custom: any central meridian, k0, false easting and northing.
enum class ZoneSystem { GaussKruger3, GaussKruger6, UTM, Custom };

/// A complete transverse Mercator grid definition. For the three standard
/// systems, TransverseMercatorGrid checks that the members agree with the
/// zone (central meridian, k0, false easting/northing); use Custom for any
/// other combination. Build standard definitions with gauss_kruger_3(),
/// gauss_kruger_6() and utm().
struct GridDefinition {
  ZoneSystem system = ZoneSystem::GaussKruger6;
  int zone = 0;                   ///< zone number (GK: 1…120 for 3°, 1…60 for 6°; UTM 1…60;
                                  ///< Custom: free, ≥ 1 only if zone_prefix)
  bool north = true;              ///< UTM hemisphere (false easting/northing choice);
                                  ///< ignored by Gauss–Krüger and Custom
  double central_meridian_rad = 0.0;  ///< λ0, radians east of Greenwich, |λ0| ≤ 2π
                                      ///< (GK zones use 0…2π, UTM −π…π)
  double scale_factor = 1.0;      ///< k0 on the central meridian (GK 1, UTM 0.9996), > 0
  double false_easting_m = 500000.0;  ///< added to the projected easting (metres)
  double false_northing_m = 0.0;  ///< added to the projected northing (metres);
                                  ///< UTM south: 10 000 000 m
  /// GK practice writes the zone number before the easting (e.g. 38 500 000 m).
  /// When true, grid eastings in and out include zone·1e6.
  bool zone_prefix = false;
  Ellipsoid ellipsoid = wgs84();  ///< a > 0, 0 ≤ f ≤ 0.01 (terrestrial figures)
};

/// Gauss–Krüger 3° zone n (1…120): central meridian 3n° E, k0 = 1, FE 500 km,
/// FN 0. Throws InputError for a zone out of range.
GridDefinition gauss_kruger_3(int zone, const Ellipsoid& e, bool zone_prefix = false);
/// Gauss–Krüger 6° zone n (1…60): central meridian (6n − 3)° E, k0 = 1,
/// FE 500 km, FN 0. Throws InputError for a zone out of range.
GridDefinition gauss_kruger_6(int zone, const Ellipsoid& e, bool zone_prefix = false);
/// UTM zone n (1…60): central meridian (6n − 183)°, k0 = 0.9996, FE 500 km,
/// FN 0 (north = true) or 10 000 km (north = false). Throws InputError for a
/// zone out of range.
GridDefinition utm(int zone, bool north, const Ellipsoid& e = wgs84());

/// Zone containing a longitude (radians east, any value; wrapped) in each
/// system. A longitude on a zone boundary belongs to the zone east of it
/// (longitudes within 1e-12 of a zone width of a boundary count as on it,
/// absorbing degree↔radian rounding). 3° zone n spans [3n − 1.5°, 3n + 1.5°),
/// 6° zone n spans [6n − 6°, 6n°) E, UTM zone n spans [6n − 186°, 6n − 180°).
/// utm_zone ignores the Norway/Svalbard exceptions (they need the latitude).
/// Throws InputError for a non-finite longitude.
int gauss_kruger_3_zone(double lon_rad);
int gauss_kruger_6_zone(double lon_rad);
int utm_zone(double lon_rad);

/// Human-readable description, e.g. "Gauss-Kruger 3deg zone 38 (CM 114E), CGCS2000".
std::string describe(const GridDefinition& g);

/// A point on the grid with its local projection properties.
struct GridPoint {
  double x_north_m = 0.0;         ///< northing including FN (metres)
  double y_east_m = 0.0;          ///< includes FE (and the zone prefix when set)
  double convergence_rad = 0.0;   ///< γ, see the file comment (radians)
  double scale = 1.0;             ///< point scale factor k (includes k0)
};

/// A geographic point with its local projection properties.
struct GeographicPoint {
  double lat_rad = 0.0;           ///< geodetic latitude φ, radians, [−π/2, π/2]
  double lon_rad = 0.0;           ///< longitude λ, radians east, within 45° of λ0 and
                                  ///< returned as λ0 + (λ − λ0) with |λ − λ0| ≤ π
  double convergence_rad = 0.0;   ///< γ, see the file comment (radians)
  double scale = 1.0;             ///< point scale factor k (includes k0)
};

/// An immutable transverse Mercator grid.
class TransverseMercatorGrid {
 public:
  /// Throws InputError for invalid definitions (zone out of range, a ≤ 0,
  /// f outside [0, 0.01], k0 ≤ 0, non-finite values, or a standard system
  /// whose central meridian, k0, FE or FN do not match its zone).
  explicit TransverseMercatorGrid(GridDefinition def);
  const GridDefinition& definition() const { return def_; }
  /// Geographic → grid. lat_rad: geodetic latitude, radians, |lat| ≤ π/2;
  /// lon_rad: radians east (any value, taken modulo 2π). Throws InputError
  /// for non-finite input, |lat| > π/2 or a point more than 45° of longitude
  /// from the central meridian.
  GridPoint forward(double lat_rad, double lon_rad) const;
  /// Grid → geographic. x_north_m: northing including FN; y_east_m: easting
  /// including FE and, if set, the zone prefix (metres). Throws InputError
  /// for non-finite input or a point that falls more than 45° of longitude
  /// from the central meridian (or farther than 6000 km·k0 from it).
  GeographicPoint reverse(double x_north_m, double y_east_m) const;

 private:
  GridDefinition def_;
};

/// Grid azimuth of the chord C→D from plane coordinates (坐标方位角, the
/// "coordinate azimuth" of a traverse): T = atan2(y_D − y_C, x_D − x_C),
/// radians in [0, 2π), clockwise from grid north. x north, y east, metres
/// (any common origin). Worked example: C (0, 0), D (x −1, y +1) gives
/// T = 135° (south-east); swapping C and D gives 315°. Throws InputError for
/// non-finite input or coincident points.
double grid_azimuth(double x_c_m, double y_c_m, double x_d_m, double y_d_m);

/// Half the last digit of a coordinate as written (metres): "3611402.310" → 0.0005, "12" or
/// "1.2e3" → 0.5. The rounding of a booked coordinate, for grid_azimuth_rounding().
double half_last_digit_m(std::string_view text);

/// The largest change of grid_azimuth() (radians) when each of the four
/// coordinates is off by at most half its booked digit: `x_half_unit_m`,
/// `y_half_unit_m` are the sums of both points' half units (0.001 for two
/// points booked to 1 mm). Linearised: |dT| ≤ (u_y|Δx| + u_x|Δy|)/s². Throws
/// InputError as grid_azimuth().
double grid_azimuth_rounding(double x_c_m, double y_c_m, double x_d_m, double y_d_m, double x_half_unit_m,
                             double y_half_unit_m);

/// Arc-to-chord correction δ at C for the line C→D (radians), computed
/// rigorously: δ = T_chord − (α_CD − γ_C), where T_chord = atan2(y_D − y_C,
/// x_D − x_C) is the grid azimuth of the straight chord, α_CD the geodesic
/// azimuth at C (GeographicLib::Geodesic on the grid's ellipsoid) and γ_C the
/// convergence at C. Thus T_chord = α − γ + δ. The result is wrapped to
/// [−π, π).
///
/// Sign: the projected geodesic is concave towards the central meridian, so
/// for a line heading north east of the central meridian (northern or
/// southern hemisphere) δ < 0; for a line heading south there δ > 0.
/// The classical approximation (written for k0 = 1; otherwise use 6k0²R²) is
///   δ ≈ −(x_D − x_C)(2y'_C + y'_D) / (6R²)   [radians; ×ρ″ for arc-seconds]
/// with y' = easting − FE (− zone prefix) and R² = M·N at the line's mean
/// latitude. For 1 km lines within 250 km of the central meridian it agrees
/// with the rigorous value to 0.0004″ (the neglected terms are of relative
/// order (y'/R)², plus η² terms that make δ ≠ 0 on east–west lines).
///
/// Coordinates as in TransverseMercatorGrid::reverse (metres, x north, y east
/// with FE and prefix). Throws InputError if C and D coincide, for non-finite
/// input, or if either point is outside the grid's domain.
double arc_to_chord(const TransverseMercatorGrid& grid, double x_c_m, double y_c_m,
                    double x_d_m, double y_d_m);

}  // namespace meridian::geodesy
