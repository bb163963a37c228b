// The engine against GeographicLib's GravityModel on the same coefficient
// file (GeographicLib reads the .egm/.egm.cof our writer produced).

#include <GeographicLib/GravityCircle.hpp>
#include <GeographicLib/GravityModel.hpp>
#include <gtest/gtest.h>

#include <algorithm>

#include "gravity_test_support.hpp"
#include "meridian/gravity/gravity_circle.hpp"
#include "test_units.hpp"

namespace {

using namespace gtest_gravity;
using gtest_gravity::kArcsec;
using meridian::gravity::FieldValues;
using meridian::gravity::GravityField;
using meridian::gravity::GravityModelData;

struct MaxDiff {
  double xi_arcsec = 0, eta_arcsec = 0, geoid_m = 0, anomaly_m_s2 = 0, t_m2_s2 = 0;
};

// Compare at `pts`; returns the largest differences.
MaxDiff compare(const GravityField& field, const GeographicLib::GravityModel& gl, const std::vector<TestPoint>& pts) {
  MaxDiff d;
  std::vector<meridian::gravity::GeodeticPoint> gp;
  for (const auto& p : pts) gp.push_back(geodetic(p));
  const std::vector<FieldValues> v = field.evaluate(gp);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const TestPoint& p = pts[i];
    double dg01, xi, eta;
    gl.SphericalAnomaly(p.lat_deg, p.lon_deg, p.h_m, dg01, xi, eta);
    const double n = gl.GeoidHeight(p.lat_deg, p.lon_deg);
    SCOPED_TRACE(testing::Message() << "lat " << p.lat_deg << " lon " << p.lon_deg << " h " << p.h_m);
    d.xi_arcsec = std::max(d.xi_arcsec, std::abs(v[i].xi_rad / kArcsec - xi * 3600));
    d.eta_arcsec = std::max(d.eta_arcsec, std::abs(v[i].eta_rad / kArcsec - eta * 3600));
    d.geoid_m = std::max(d.geoid_m, std::abs(v[i].geoid_m - n));
    d.anomaly_m_s2 = std::max(d.anomaly_m_s2, std::abs(v[i].anomaly_m_s2 - dg01));
    EXPECT_NEAR(v[i].xi_rad / kArcsec, xi * 3600, 1e-6);
    EXPECT_NEAR(v[i].eta_rad / kArcsec, eta * 3600, 1e-6);
    EXPECT_NEAR(v[i].geoid_m, n, 1e-6);
    EXPECT_NEAR(v[i].anomaly_m_s2, dg01, 1e-10);  // m/s² (1e-5 mGal)
  }
  return d;
}

void report(const char* what, const MaxDiff& d) {
  std::printf("[ %s ] max |diff| vs GeographicLib: xi %.3e\", eta %.3e\", N %.3e m, Dg %.3e mGal\n", what, d.xi_arcsec,
              d.eta_arcsec, d.geoid_m, d.anomaly_m_s2 * 1e5);
}

TEST(GravityVsGeographicLib, SyntheticDegree360) {
  const std::string name = synthetic_files(360);
  const GeographicLib::GravityModel gl(name, scratch_dir().string());
  const GravityModelData m = meridian::io::read_egm_file(scratch_dir() / (name + ".egm"));
  const GravityField field(m);
  const auto pts = test_points(60, 7);
  report("degree 360", compare(field, gl, pts));
}

TEST(GravityVsGeographicLib, SyntheticDegree2190AtAFewPoints) {
  const std::string name = synthetic_files(2190);
  const GeographicLib::GravityModel gl(name, scratch_dir().string());
  const GravityField field(meridian::io::read_egm_file(scratch_dir() / (name + ".egm")));
  ASSERT_EQ(field.max_degree(), 2190);
  const std::vector<TestPoint> pts = {{89.7, 12.5, 3000}, {-90, 0, 0}, {37.3, -122.1, -500}, {-12.9, 100.2, 10000},
                                      {0.1, 179.9, 0}};
  report("degree 2190", compare(field, gl, pts));
}

TEST(GravityVsGeographicLib, TruncationOnLoadMatchesGeographicLibTruncation) {
  const std::string name = synthetic_files(360);
  const GeographicLib::GravityModel gl(name, scratch_dir().string(), 120, 80);
  const GravityField field(meridian::io::read_egm_file(scratch_dir() / (name + ".egm"), {120, 80}));
  EXPECT_EQ(field.max_degree(), 120);
  EXPECT_EQ(field.max_order(), 80);
  compare(field, gl, test_points(20, 11));
}

TEST(GravityVsGeographicLib, CircleMatchesGravityCircle) {
  const std::string name = synthetic_files(360);
  const GeographicLib::GravityModel gl(name, scratch_dir().string());
  const GravityField field(meridian::io::read_egm_file(scratch_dir() / (name + ".egm")));
  for (const double lat : {-89.9, 12.0, 60.5}) {
    const GeographicLib::GravityCircle glc = gl.Circle(lat, 0.0);
    const meridian::gravity::GravityCircle c(field, lat * meridian::units::kDegree, 0.0);
    for (double lon = -180; lon < 180; lon += 17.3) {
      double dg01, xi, eta;
      glc.SphericalAnomaly(lon, dg01, xi, eta);
      const FieldValues v = c.evaluate(lon * meridian::units::kDegree);
      EXPECT_NEAR(v.xi_rad / kArcsec, xi * 3600, 1e-6) << lat << " " << lon;
      EXPECT_NEAR(v.eta_rad / kArcsec, eta * 3600, 1e-6) << lat << " " << lon;
      EXPECT_NEAR(v.geoid_m, glc.GeoidHeight(lon), 1e-6) << lat << " " << lon;
    }
  }
}

TEST(GravityVsGeographicLib, GeoidCorrectionSetAndHeightOffset) {
  // A model with a zeta-to-N correction set, written by us, read by both.
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 40;
  o.seed = 5;
  GravityModelData m = meridian::gravity::make_synthetic_model(o);
  meridian::gravity::SphericalHarmonicCoefficients corr(12, 12);
  for (int n = 0; n <= 12; ++n)
    for (int k = 0; k <= n; ++k) corr.set(n, k, 0.3 / (n + 1) * std::cos(n * 7.0 + k), 0.2 / (n + 1) * std::sin(n + 3.0 * k));
  m.correction = meridian::gravity::GeoidCorrection{corr, 1.5, -0.41};
  m.name = "corrtest";
  meridian::io::write_egm_files(m, scratch_dir() / "corrtest");
  const GeographicLib::GravityModel gl("corrtest", scratch_dir().string());
  const GravityField field(meridian::io::read_egm_file(scratch_dir() / "corrtest.egm"));
  for (const auto& p : test_points(10, 3)) {
    const auto v = field.evaluate(geodetic(p), meridian::gravity::Quantities::Geoid);
    EXPECT_NEAR(v.geoid_m, gl.GeoidHeight(p.lat_deg, p.lon_deg), 1e-9) << p.lat_deg << " " << p.lon_deg;
  }
}

TEST(GravityVsGeographicLib, DegreeZeroTermMatchesWMinusU) {
  // With include_degree_zero, T = W − U exactly (with (GM_model − GM_ref)/r),
  // and |∇T| equals the norm of GeographicLib's Disturbance vector (which
  // includes that term in the gradient; its returned T does not).
  const std::string name = synthetic_files(360);
  const GeographicLib::GravityModel gl(name, scratch_dir().string());
  const GravityField field(meridian::io::read_egm_file(scratch_dir() / (name + ".egm")), {true, 1});
  for (const auto& p : test_points(5, 9)) {
    double x, y, z, gx, gy, gz, ux, uy, uz, dx, dy, dz;
    gl.ReferenceEllipsoid().Earth().Forward(p.lat_deg, p.lon_deg, p.h_m, x, y, z);
    const double t = gl.W(x, y, z, gx, gy, gz) - gl.ReferenceEllipsoid().U(x, y, z, ux, uy, uz);
    gl.Disturbance(p.lat_deg, p.lon_deg, p.h_m, dx, dy, dz);
    const auto v = field.evaluate(geodetic(p), meridian::gravity::Quantities::Deflection);
    EXPECT_NEAR(v.disturbing_potential_m2_s2, t, 1e-7);
    EXPECT_NEAR(std::hypot(std::hypot(v.dT_east_m_s2, v.dT_north_m_s2), v.dT_up_m_s2),
                std::hypot(std::hypot(dx, dy), dz), 1e-12);
  }
}

TEST(GravityVsGeographicLib, AstronomicDeflectionFromGravityVector) {
  // ξ_a = Φ − φ, η_a = (Λ − λ) cos φ of GeographicLib's full gravity vector
  // (Gravity(): g in the local geodetic east-north-up frame).
  const std::string name = synthetic_files(360);
  const GeographicLib::GravityModel gl(name, scratch_dir().string());
  const GravityField field(meridian::io::read_egm_file(scratch_dir() / (name + ".egm")));
  double worst = 0, worst_vs_spherical = 0;
  for (const auto& p : test_points(30, 13)) {
    double gx, gy, gz;
    gl.Gravity(p.lat_deg, p.lon_deg, p.h_m, gx, gy, gz);
    const double phi = p.lat_deg * meridian::units::kDegree, sp = std::sin(phi), cp = std::abs(p.lat_deg) == 90 ? 0 : std::cos(phi);
    const double ne = -gx, nn = -gy, nu = -gz;
    const double xp = nu * cp - nn * sp, z = nn * cp + nu * sp;
    const double xi = std::atan2(z, std::hypot(xp, ne)) - phi, eta = std::atan2(ne, xp) * cp;
    const FieldValues v = field.evaluate(geodetic(p), meridian::gravity::Quantities::Deflection);
    EXPECT_NEAR(v.xi_astro_rad / kArcsec, xi / kArcsec, 1e-6) << p.lat_deg << " " << p.lon_deg << " " << p.h_m;
    EXPECT_NEAR(v.eta_astro_rad / kArcsec, eta / kArcsec, 1e-6) << p.lat_deg << " " << p.lon_deg << " " << p.h_m;
    worst = std::max({worst, std::abs(v.xi_astro_rad - xi), std::abs(v.eta_astro_rad - eta)});
    if (std::abs(p.lat_deg) < 89) worst_vs_spherical = std::max(worst_vs_spherical, std::abs(v.xi_astro_rad - v.xi_rad));
  }
  std::printf("[ astronomic ] max |diff| vs GeographicLib Gravity(): %.3e\"; |xi_a - xi| up to %.3f\" (|lat| < 89)\n",
              worst / kArcsec, worst_vs_spherical / kArcsec);
}

TEST(GravityVsGeographicLib, RealEgm96WhenAvailable) {
  const fs::path dir = shared_gravity_dir();
  if (!fs::exists(dir / "egm96.egm")) GTEST_SKIP() << "../shared/data/gravity/egm96.egm not present (optional data)";
  const GeographicLib::GravityModel gl("egm96", dir.string());
  const GravityField field(meridian::io::read_egm_file(dir / "egm96.egm"));
  report("EGM96 .egm", compare(field, gl, test_points(12, 21)));
  // The ICGEM copy of the same coefficients gives the same field.
  const GravityField gfc(meridian::io::read_icgem_file(dir / "egm96.gfc"));
  report("EGM96 .gfc", compare(gfc, gl, test_points(12, 22)));
}

}  // namespace
