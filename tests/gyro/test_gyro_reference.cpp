// Spec §8.5 against GeographicLib's own command-line tool
// TransverseMercatorProj (Debian geographiclib-tools, installed by
// scripts/setup.sh). CTest label `reference`: fails when the tool is missing.

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "meridian/core/units.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/campaign_simulator.hpp"

using namespace meridian;
using namespace meridian::gyro;

namespace {

double diff_arcsec(double a, double b) {
  return std::remainder(a - b, 2 * units::kPi) / units::kArcsecond;
}

// Run GeographicLib's own TransverseMercatorProj: returns gamma (degrees).
double tool_convergence_deg(double lat_deg, double lon_deg, double lon0_deg, double a, double f) {
  const std::string cmd = fmt::format("echo {:.12f} {:.12f} | TransverseMercatorProj -l {:.12f} -k 1 -e {:.4f} {:.15g} -p 12",
                                      lat_deg, lon_deg, lon0_deg, a, f);
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
  if (!p) ADD_FAILURE() << "cannot run TransverseMercatorProj";
  double x = 0, y = 0, gamma = 0, k = 0;
  if (!p || std::fscanf(p.get(), "%lf %lf %lf %lf", &x, &y, &gamma, &k) != 4)
    ADD_FAILURE() << "TransverseMercatorProj (Debian geographiclib-tools) is needed: " << cmd;
  return gamma;
}
}  // namespace

TEST(Campaign, GridAzimuthAgreesWithGeographicLibTool) {
  // Spec §8.5: T = α − γ + δ with γ from TransverseMercatorProj, to 0.001".
  const auto sim = simulate_campaign(example_campaign_truth(), 11);
  const auto r = process(sim.input);
  const auto& e = sim.input.grid.ellipsoid;
  const double gamma_tool =
      tool_convergence_deg(r.station.lat_rad / units::kDegree, r.station.lon_rad / units::kDegree,
                           sim.input.grid.central_meridian_rad / units::kDegree, e.a_m, e.f);
  const double t_independent =
      r.chain.geodetic_azimuth_rad.value - gamma_tool * units::kDegree + r.chain.arc_to_chord_rad;
  EXPECT_NEAR(diff_arcsec(r.chain.grid_azimuth_rad.value, t_independent), 0.0, 0.001);
  EXPECT_NEAR(r.chain.convergence_rad / units::kDegree, gamma_tool, 0.001 / 3600);
}

