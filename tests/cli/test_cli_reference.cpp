// `meridian gravity point` against GeographicLib's own command-line tool
// Gravity (Debian geographiclib-tools, installed by scripts/setup.sh) on the
// same model file. CTest label `reference`: fails when the tool is missing.

#include <cstdlib>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"

namespace {

using meridian_test::CmdResult;
class GravityCli : public meridian_test::CliTest {};

}  // namespace

TEST_F(GravityCli, PointJsonMatchesGeographicLibGravityTool) {
  ASSERT_EQ(run("gravity synth-model --degree 60 --seed 3 --out m").code, 0);
  const CmdResult r = run("gravity point --model m.egm -33.5 151.25 120 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"xi_arcsec", "eta_arcsec", "geoid_m"}) EXPECT_TRUE(j.contains(k)) << k;
  // The .gfc copy is the same model.
  const auto g = nlohmann::json::parse(run("gravity point --model m.gfc --json -- -33.5 151.25 120").out);
  EXPECT_NEAR(g["xi_arcsec"].get<double>(), j["xi_arcsec"].get<double>(), 1e-9);
  ASSERT_EQ(std::system("command -v Gravity > /dev/null 2>&1"), 0)
      << "GeographicLib's Gravity tool is needed (Debian geographiclib-tools; scripts/setup.sh installs it)";
  // Gravity -A prints Dg01 (mGal), xi, eta (arcsec); -H prints N (m).
  const CmdResult a = shell("echo '-33.5 151.25 120' | Gravity -n m -d . -A -p 9");
  const CmdResult h = shell("echo '-33.5 151.25' | Gravity -n m -d . -H -p 9");
  ASSERT_EQ(a.code, 0) << a.err;
  double dg, xi, eta, n;
  std::istringstream(a.out) >> dg >> xi >> eta;
  std::istringstream(h.out) >> n;
  EXPECT_NEAR(j["xi_arcsec"].get<double>(), xi, 1e-6);
  EXPECT_NEAR(j["eta_arcsec"].get<double>(), eta, 1e-6);
  EXPECT_NEAR(j["geoid_m"].get<double>(), n, 1e-6);
}

