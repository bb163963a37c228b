#pragma once
/// \file ellipsoid.hpp
/// Reference ellipsoids used by Meridian's grid computations.

#include <string>
#include <string_view>

namespace meridian::geodesy {

/// A named reference ellipsoid.
struct Ellipsoid {
  std::string name;        ///< canonical name, e.g. "WGS84"
  double a_m = 0.0;        ///< equatorial radius (metres)
  double f = 0.0;          ///< flattening (dimensionless), 1/f ≈ 298.257…
};

Ellipsoid wgs84();
Ellipsoid grs80();
Ellipsoid cgcs2000();
Ellipsoid krassovsky1940();  ///< Beijing 1954
Ellipsoid iag75();           ///< Xi'an 1980

/// Look up an ellipsoid by name, case-insensitive, ignoring '-', '_' and
/// spaces: "WGS84", "GRS80", "CGCS2000", "Krassovsky1940" (also "Krassovsky",
/// "Beijing54"), "IAG75" (also "IAG-75", "Xian80"). Throws InputError listing
/// the accepted names otherwise.
Ellipsoid ellipsoid_by_name(std::string_view name);

}  // namespace meridian::geodesy
