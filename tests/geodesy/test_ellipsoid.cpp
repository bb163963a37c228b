#include <gtest/gtest.h>

#include <string>

#include "meridian/core/error.hpp"
#include "meridian/geodesy/ellipsoid.hpp"

namespace mg = meridian::geodesy;

TEST(Ellipsoid, DefiningConstants) {
  EXPECT_EQ(mg::wgs84().a_m, 6378137.0);
  EXPECT_DOUBLE_EQ(1.0 / mg::wgs84().f, 298.257223563);
  EXPECT_EQ(mg::grs80().a_m, 6378137.0);
  EXPECT_DOUBLE_EQ(1.0 / mg::grs80().f, 298.257222101);
  EXPECT_EQ(mg::cgcs2000().a_m, 6378137.0);
  EXPECT_DOUBLE_EQ(1.0 / mg::cgcs2000().f, 298.257222101);
  EXPECT_EQ(mg::krassovsky1940().a_m, 6378245.0);
  EXPECT_DOUBLE_EQ(1.0 / mg::krassovsky1940().f, 298.3);
  EXPECT_EQ(mg::iag75().a_m, 6378140.0);
  EXPECT_DOUBLE_EQ(1.0 / mg::iag75().f, 298.257);
}

TEST(Ellipsoid, Cgcs2000HasTheGrs80Shape) {
  EXPECT_EQ(mg::cgcs2000().a_m, mg::grs80().a_m);
  EXPECT_EQ(mg::cgcs2000().f, mg::grs80().f);
  EXPECT_NE(mg::cgcs2000().name, mg::grs80().name);
}

TEST(Ellipsoid, ByNameCanonicalAndAliases) {
  const std::pair<const char*, const char*> cases[] = {
      {"WGS84", "WGS84"},          {"wgs-84", "WGS84"},
      {"WGS 1984", "WGS84"},       {"grs80", "GRS80"},
      {"GRS_1980", "GRS80"},       {"CGCS2000", "CGCS2000"},
      {"cgcs 2000", "CGCS2000"},   {"Krassovsky1940", "Krassovsky1940"},
      {"KRASSOVSKY", "Krassovsky1940"}, {"Krasovsky 1940", "Krassovsky1940"},
      {"Beijing54", "Krassovsky1940"},  {"beijing_1954", "Krassovsky1940"},
      {"IAG75", "IAG75"},          {"IAG-75", "IAG75"},
      {"Xian80", "IAG75"},         {"xian 1980", "IAG75"},
  };
  for (const auto& [alias, canonical] : cases) {
    SCOPED_TRACE(alias);
    EXPECT_EQ(mg::ellipsoid_by_name(alias).name, canonical);
  }
  EXPECT_EQ(mg::ellipsoid_by_name("xian80").a_m, 6378140.0);
}

TEST(Ellipsoid, BadNameThrowsNamingIt) {
  for (const char* bad : {"Bessel1841", "", "WGS72", "Krassovsky1942"}) {
    SCOPED_TRACE(bad);
    try {
      mg::ellipsoid_by_name(bad);
      FAIL() << "no exception";
    } catch (const meridian::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string("\"") + bad + "\""), std::string::npos) << what;
      EXPECT_NE(what.find("CGCS2000"), std::string::npos) << what;
    }
  }
}
