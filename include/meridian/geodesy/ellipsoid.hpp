#pragma once
/// \file ellipsoid.hpp
/// Reference ellipsoids used by Meridian's grid computations.
///
/// Defining constants (semi-major axis a, inverse flattening 1/f):
///
/// | name           | a (m)     | 1/f           | used by                         |
/// |----------------|-----------|---------------|---------------------------------|
/// | WGS84          | 6378137   | 298.257223563 | GPS, UTM                        |
/// | GRS80          | 6378137   | 298.257222101 | ITRF realisations, ETRS89, NAD83|
/// | CGCS2000       | 6378137   | 298.257222101 | China Geodetic CS 2000          |
/// | Krassovsky1940 | 6378245   | 298.3         | Beijing 1954                    |
/// | IAG75          | 6378140   | 298.257       | Xi'an 1980 (IUGG 1975 values)   |
///
/// GRS80's 1/f is derived from its defining GM, J2 and ω and is
/// 298.257222100882711…; the 9-decimal value above is the one EPSG (ellipsoid
/// 7019) and PROJ tabulate. CGCS2000 adopts a = 6378137 m and 1/f =
/// 298.257222101 as defining constants (EPSG ellipsoid 1024); its GM
/// (3.986004418e14 m³/s²) differs from GRS80's, which does not affect the
/// geometry. The two shapes differ by about 8 nm in the semi-minor axis, so
/// CGCS2000 and GRS80 grids agree to well below a micrometre.

#include <string>
#include <string_view>

namespace meridian::geodesy {

/// A named reference ellipsoid.
struct Ellipsoid {
  std::string name;        ///< canonical name, e.g. "WGS84"
  double a_m = 0.0;        ///< equatorial radius (metres), > 0
  double f = 0.0;          ///< flattening (dimensionless), 1/f ≈ 298.257…; 0 for a sphere
};

Ellipsoid wgs84();           ///< World Geodetic System 1984
Ellipsoid grs80();           ///< Geodetic Reference System 1980
Ellipsoid cgcs2000();        ///< China Geodetic Coordinate System 2000
Ellipsoid krassovsky1940();  ///< Beijing 1954
Ellipsoid iag75();           ///< Xi'an 1980

/// Look up an ellipsoid by name, case-insensitive, ignoring '-', '_' and
/// spaces: "WGS84" (also "WGS1984"), "GRS80" (also "GRS1980"), "CGCS2000",
/// "Krassovsky1940" (also "Krassovsky", "Krasovsky", "Krasovsky1940",
/// "Beijing54", "Beijing1954"), "IAG75" (also "IAG-75", "IUGG75", "Xian80",
/// "Xian1980"). Throws InputError naming the rejected value and listing the
/// accepted names otherwise.
Ellipsoid ellipsoid_by_name(std::string_view name);

}  // namespace meridian::geodesy
