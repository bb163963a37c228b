#include "meridian/geodesy/ellipsoid.hpp"

#include <array>
#include <cctype>
#include <string>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::geodesy {

// Constants: see the table in ellipsoid.hpp (EPSG 7030, 7019, 1024, 7024, 7049).
Ellipsoid wgs84() { return {"WGS84", 6378137.0, 1.0 / 298.257223563}; }
Ellipsoid grs80() { return {"GRS80", 6378137.0, 1.0 / 298.257222101}; }
Ellipsoid cgcs2000() { return {"CGCS2000", 6378137.0, 1.0 / 298.257222101}; }
Ellipsoid krassovsky1940() { return {"Krassovsky1940", 6378245.0, 1.0 / 298.3}; }
Ellipsoid iag75() { return {"IAG75", 6378140.0, 1.0 / 298.257}; }

namespace {

// Lower case without '-', '_' and spaces, so "IAG-75" == "iag 75" == "IAG75".
std::string normalise(std::string_view name) {
  std::string s;
  s.reserve(name.size());
  for (const char c : name) {
    if (c == '-' || c == '_' || c == ' ') continue;
    s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return s;
}

}  // namespace

Ellipsoid ellipsoid_by_name(std::string_view name) {
  struct Alias {
    std::string_view key;  // already normalised
    Ellipsoid (*make)();
  };
  static constexpr std::array<Alias, 16> kAliases{{
      {"wgs84", wgs84},
      {"wgs1984", wgs84},
      {"grs80", grs80},
      {"grs1980", grs80},
      {"cgcs2000", cgcs2000},
      {"krassovsky1940", krassovsky1940},
      {"krassovsky", krassovsky1940},
      {"krasovsky1940", krassovsky1940},
      {"krasovsky", krassovsky1940},
      {"beijing54", krassovsky1940},
      {"beijing1954", krassovsky1940},
      {"iag75", iag75},
      {"iugg75", iag75},
      {"xian80", iag75},
      {"xian1980", iag75},
      {"iag1975", iag75},
  }};
  const std::string key = normalise(name);
  for (const Alias& a : kAliases)
    if (a.key == key) return a.make();
  throw InputError(fmt::format(
      "unknown ellipsoid \"{}\"; accepted: WGS84, GRS80, CGCS2000, Krassovsky1940 "
      "(Krassovsky, Beijing54), IAG75 (IAG-75, Xian80)",
      name));
}

}  // namespace meridian::geodesy
