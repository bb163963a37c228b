// Local frames and the deflection-of-the-vertical convention
// (geodesy/frames.hpp). References: GeographicLib::Geocentric (its ENU→ECEF
// rotation matrix and ECEF positions), GeographicLib::LocalCartesian (its
// rotation matrix and local coordinates), and closed forms.

#include <gtest/gtest.h>

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/geodesy/frames.hpp"

namespace mg = meridian::geodesy;
namespace mu = meridian::units;
using mu::deg_to_rad;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

const std::vector<double> kLatitudes_deg{-90,   -89.999, -67.3, -45, -12.5, 0,
                                         0.001, 23.4,    45,    60,  89.9,  90};
const std::vector<double> kLongitudes_deg{-180, -123.4, -1e-3, 0, 37.8, 90, 114.3, 179.99, 250};

// GeographicLib's row-major 9-vector as a matrix.
Eigen::Matrix3d to_matrix(const std::vector<double>& m) {
  Eigen::Matrix3d r;
  r << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  return r;
}

// GeographicLib::Geocentric::Forward: ECEF position and M with v_ecef = M·v_enu.
struct GeoForward {
  Eigen::Vector3d x;
  Eigen::Matrix3d m;
};
GeoForward geocentric(const GeographicLib::Geocentric& g, double lat_deg, double lon_deg,
                      double h) {
  std::vector<double> m(9);
  GeoForward f;
  g.Forward(lat_deg, lon_deg, h, f.x.x(), f.x.y(), f.x.z(), m);
  f.m = to_matrix(m);
  return f;
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

TEST(Frames, EcefToEnuIsTransposeOfGeocentricMatrix) {
  const GeographicLib::Geocentric& wgs = GeographicLib::Geocentric::WGS84();
  double worst = 0;
  for (double lat : kLatitudes_deg)
    for (double lon : kLongitudes_deg) {
      SCOPED_TRACE(testing::Message() << "lat " << lat << " lon " << lon);
      const Eigen::Matrix3d r = mg::rotation_ecef_to_enu(deg_to_rad(lat), deg_to_rad(lon));
      const double d = max_abs(r - geocentric(wgs, lat, lon, 0).m.transpose());
      EXPECT_LT(d, 1e-15);
      worst = std::max(worst, d);
      EXPECT_LT(max_abs(r * r.transpose() - Eigen::Matrix3d::Identity()), 1e-15);
      EXPECT_NEAR(r.determinant(), 1.0, 1e-15);
    }
  std::printf("[ frames   ] ECEF->ENU vs GeographicLib::Geocentric M^T: max |diff| %.2e\n", worst);
}

TEST(Frames, EcefToEnuAgreesWithLocalCartesian) {
  // LocalCartesian(origin).Forward(point) returns the local coordinates of
  // the point and M with v_enu(origin) = M·v_enu(point); hence
  // M = R(origin)·R(point)ᵀ and (x, y, z) = R(origin)·(X_point − X_origin).
  const GeographicLib::Geocentric earth(6378137.0, 1 / 298.257222101);  // CGCS2000
  double worst_m = 0, worst_xyz = 0;
  for (double lat0 : {-89.5, -33.9, 0.0, 30.6, 51.5, 90.0})
    for (double lon0 : {-75.0, 0.0, 114.3}) {
      const GeographicLib::LocalCartesian lc(lat0, lon0, 120.0, earth);
      const Eigen::Matrix3d r0 = mg::rotation_ecef_to_enu(deg_to_rad(lat0), deg_to_rad(lon0));
      const Eigen::Vector3d x0 = geocentric(earth, lat0, lon0, 120.0).x;
      for (double dlat : {-1.3, 0.0, 0.01, 2.5})
        for (double dlon : {-3.0, 0.0, 0.2}) {
          const double lat = std::clamp(lat0 + dlat, -90.0, 90.0), lon = lon0 + dlon;
          SCOPED_TRACE(testing::Message() << lat0 << " " << lon0 << " -> " << lat << " " << lon);
          std::vector<double> m(9);
          Eigen::Vector3d local;
          lc.Forward(lat, lon, 850.0, local.x(), local.y(), local.z(), m);
          const Eigen::Matrix3d r = mg::rotation_ecef_to_enu(deg_to_rad(lat), deg_to_rad(lon));
          const double dm = max_abs(r0 * r.transpose() - to_matrix(m));
          EXPECT_LT(dm, 1e-14);
          const Eigen::Vector3d mine = r0 * (geocentric(earth, lat, lon, 850.0).x - x0);
          const double dx = (mine - local).norm();
          EXPECT_LT(dx, 1e-6);  // metres, over up to ~400 km
          worst_m = std::max(worst_m, dm);
          worst_xyz = std::max(worst_xyz, dx);
        }
    }
  std::printf("[ frames   ] vs GeographicLib::LocalCartesian: max |dM| %.2e, max |d xyz| %.2e m\n",
              worst_m, worst_xyz);
}

TEST(Frames, NedIsEnuReordered) {
  const Eigen::Matrix3d p = mg::rotation_enu_to_ned();
  EXPECT_EQ(p * p, Eigen::Matrix3d::Identity());
  EXPECT_EQ(p, p.transpose());
  EXPECT_EQ(mg::rotation_ned_to_enu(), p);
  // Both frames are right-handed: P is a proper rotation (180° about the
  // north-east bisector), not a reflection.
  EXPECT_EQ(p.determinant(), 1.0);
  EXPECT_EQ(p * Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(2, 1, -3));
  for (double lat : kLatitudes_deg)
    for (double lon : kLongitudes_deg) {
      const Eigen::Matrix3d enu = mg::rotation_ecef_to_enu(deg_to_rad(lat), deg_to_rad(lon));
      const Eigen::Matrix3d ned = mg::rotation_ecef_to_ned(deg_to_rad(lat), deg_to_rad(lon));
      EXPECT_EQ(ned.row(0), enu.row(1));
      EXPECT_EQ(ned.row(1), enu.row(0));
      EXPECT_EQ(ned.row(2), -enu.row(2));
      EXPECT_NEAR(ned.determinant(), 1.0, 1e-15);
    }
}

TEST(Frames, EnuAxesPointWhereTheirNamesSay) {
  // At φ = 0, λ = 90° E: east = −X, north = +Z, up = +Y.
  const Eigen::Matrix3d r = mg::rotation_ecef_to_enu(0.0, deg_to_rad(90));
  EXPECT_LT((r * Eigen::Vector3d(-1, 0, 0) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((r * Eigen::Vector3d(0, 0, 1) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
  EXPECT_LT((r * Eigen::Vector3d(0, 1, 0) - Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
}

TEST(Frames, GeocentricLatitudeAgreesWithGeographicLib) {
  double worst = 0;
  for (const mg::Ellipsoid& e :
       {mg::wgs84(), mg::krassovsky1940(), mg::Ellipsoid{"f=0.01", 6.4e6, 0.01}}) {
    const GeographicLib::Geocentric g(e.a_m, e.f);
    for (double lat : kLatitudes_deg)
      for (double h : {-11000.0, 0.0, 1500.0, 35786e3}) {
        SCOPED_TRACE(testing::Message() << e.name << " lat " << lat << " h " << h);
        const Eigen::Vector3d x = geocentric(g, lat, 37.0, h).x;
        const double ref = std::atan2(x.z(), std::hypot(x.x(), x.y()));
        const double psi = mg::geocentric_latitude_rad(deg_to_rad(lat), h, e);
        EXPECT_NEAR(psi, ref, 2e-15);
        worst = std::max(worst, std::abs(psi - ref));
      }
  }
  std::printf(
      "[ frames   ] geocentric latitude vs GeographicLib::Geocentric: max |diff| %.2e rad\n",
      worst);
  // On the ellipsoid tan ψ = (1 − e²) tan φ; φ − ψ is largest at
  // tan φ = 1/√(1 − e²): 11′32.7″ for WGS84.
  const mg::Ellipsoid w = mg::wgs84();
  const double e2 = w.f * (2 - w.f);
  const double phi = std::atan(1 / std::sqrt(1 - e2));
  const double d = phi - mg::geocentric_latitude_rad(phi, 0.0, w);
  EXPECT_NEAR(d, phi - std::atan(std::sqrt(1 - e2)), 1e-16);
  EXPECT_NEAR(mu::rad_to_arcsec(d), 11 * 60 + 32.7, 0.05);
  EXPECT_EQ(mg::geocentric_latitude_rad(0.0, 100.0, w), 0.0);
}

TEST(Frames, GeocentricToGeodeticFrameAgreesWithGeographicLib) {
  // The geocentric local frame at (ψ, λ) has the axes of GeographicLib's ENU
  // at latitude ψ, so R = M(φ)ᵀ·M(ψ); and the radius vector of the point,
  // rotated into geodetic ENU, is R·(0, 0, 1).
  const GeographicLib::Geocentric& wgs = GeographicLib::Geocentric::WGS84();
  double worst = 0;
  for (double lat : kLatitudes_deg)
    for (double h : {0.0, 8848.0}) {
      SCOPED_TRACE(testing::Message() << "lat " << lat << " h " << h);
      const GeoForward p = geocentric(wgs, lat, 114.3, h);
      const double psi = std::atan2(p.x.z(), std::hypot(p.x.x(), p.x.y()));
      const GeoForward q = geocentric(wgs, mu::rad_to_deg(psi), 114.3, h);
      const Eigen::Matrix3d r = mg::rotation_geocentric_to_enu(deg_to_rad(lat), psi);
      const double d = max_abs(r - p.m.transpose() * q.m);
      EXPECT_LT(d, 1e-15);
      worst = std::max(worst, d);
      const Eigen::Vector3d radial_enu = p.m.transpose() * p.x.normalized();
      EXPECT_LT((r * Eigen::Vector3d::UnitZ() - radial_enu).norm(), 1e-15);
      // The radius points south of the normal in the north (φ > ψ), north of it in the south.
      if (lat > 0.5 && lat < 89.5) {
        EXPECT_LT(radial_enu.y(), -1e-4);
      }
      if (lat < -0.5 && lat > -89.5) {
        EXPECT_GT(radial_enu.y(), 1e-4);
      }
    }
  std::printf("[ frames   ] geocentric->ENU vs GeographicLib M(phi)^T M(psi): max |diff| %.2e\n",
              worst);
}

TEST(Frames, ExactZenithAgreesWithLocalCartesian) {
  // The ENU "up" of (Φ, Λ) expressed at the origin (φ, λ) is
  // M·(0, 0, 1) with LocalCartesian(φ, λ).Forward(Φ, Λ).
  double worst = 0;
  for (double lat : {-60.0, -5.0, 0.0, 37.85, 80.0})
    for (double dphi_arcsec : {-40.0, 0.0, 12.5, 3600.0})
      for (double dlam_arcsec : {-25.0, 0.0, 7.0}) {
        const double lon = 112.55;
        const double alat = lat + dphi_arcsec / 3600, alon = lon + dlam_arcsec / 3600;
        const GeographicLib::LocalCartesian lc(lat, lon);
        std::vector<double> m(9);
        double x, y, z;
        lc.Forward(alat, alon, 0.0, x, y, z, m);
        const Eigen::Vector3d ref = to_matrix(m).col(2);
        const Eigen::Vector3d v = mg::astronomic_zenith_enu(deg_to_rad(alat), deg_to_rad(alon),
                                                            deg_to_rad(lat), deg_to_rad(lon));
        EXPECT_LT((v - ref).norm(), 1e-15);
        worst = std::max(worst, (v - ref).norm());
      }
  std::printf("[ frames   ] astronomic zenith vs GeographicLib::LocalCartesian: max |diff| %.2e\n",
              worst);
}

TEST(Frames, DeflectionSigns) {
  const double phi = deg_to_rad(37.85), lam = deg_to_rad(112.55);
  const double s = mu::arcsec_to_rad(5.0);
  // Astronomic zenith north of the geodetic one (Φ > φ): ξ > 0, n > 0.
  {
    const mg::Deflection d = mg::deflection_from_astronomic(phi + s, lam, phi, lam);
    EXPECT_NEAR(mu::rad_to_arcsec(d.xi_rad), 5.0, 1e-9);
    EXPECT_EQ(d.eta_rad, 0.0);
    const Eigen::Vector3d v = mg::astronomic_zenith_enu(phi + s, lam, phi, lam);
    EXPECT_GT(v.y(), 0.0);
    EXPECT_NEAR(v.x(), 0.0, 1e-16);
    EXPECT_GT(mg::deflection_from_zenith_enu(v, phi).xi_rad, 0.0);
    EXPECT_GT(mg::deflection_from_zenith_enu_first_order(v).xi_rad, 0.0);
    // A vector tilted to the north, built by hand.
    const Eigen::Vector3d north_tilt(0.0, std::sin(s), std::cos(s));
    EXPECT_NEAR(mu::rad_to_arcsec(mg::deflection_from_zenith_enu(north_tilt, phi).xi_rad), 5.0,
                1e-9);
  }
  // Astronomic zenith east of the geodetic one (Λ > λ): η > 0, e > 0;
  // η = (Λ − λ)·cos φ.
  {
    const mg::Deflection d = mg::deflection_from_astronomic(phi, lam + s, phi, lam);
    EXPECT_NEAR(mu::rad_to_arcsec(d.eta_rad), 5.0 * std::cos(phi), 1e-9);
    const Eigen::Vector3d v = mg::astronomic_zenith_enu(phi, lam + s, phi, lam);
    EXPECT_GT(v.x(), 0.0);
    EXPECT_GT(mg::deflection_from_zenith_enu(v, phi).eta_rad, 0.0);
    EXPECT_GT(mg::astronomic_zenith_enu_first_order({0.0, 1e-5}).x(), 0.0);
  }
  // Λ − λ is reduced to [−π, π): 359°59′55″ − 0° is −5″.
  const mg::Deflection w = mg::deflection_from_astronomic(phi, 2 * mu::kPi - s, phi, 0.0);
  EXPECT_NEAR(mu::rad_to_arcsec(w.eta_rad), -5.0 * std::cos(phi), 1e-6);
}

TEST(Frames, ExactAndFirstOrderAgreeToSecondOrder) {
  // Expanding the exact vector: e = η − ξη·tan φ + O(θ³),
  // n = ξ + (η²/2)·tan φ + O(θ³), u = 1 − θ²/2 + O(θ⁴); the normalised
  // (η, ξ, 1) has the same u to O(θ⁴). So the difference is O(θ²) with
  // these leading terms, and O(θ³) after removing them.
  for (double lat_deg : {-70.0, -30.0, 0.0, 30.0, 45.0, 75.0}) {
    const double phi = deg_to_rad(lat_deg), t = std::tan(phi);
    for (double theta : {1e-6, 1e-5, 1e-4, 1e-3, 1e-2})
      for (double dir_deg : {0.0, 35.0, 90.0, 160.0, 225.0, 300.0}) {
        SCOPED_TRACE(testing::Message()
                     << "lat " << lat_deg << " theta " << theta << " dir " << dir_deg);
        const mg::Deflection d{0.999 * theta * std::cos(deg_to_rad(dir_deg)),
                               0.999 * theta * std::sin(deg_to_rad(dir_deg))};
        const Eigen::Vector3d exact = mg::astronomic_zenith_enu(d, phi);
        const Eigen::Vector3d first = mg::astronomic_zenith_enu_first_order(d);
        const Eigen::Vector3d diff = exact - first;
        const double scale = theta * theta * (1 + std::abs(t));
        EXPECT_LE(diff.norm(), scale);
        const Eigen::Vector3d second(-d.xi_rad * d.eta_rad * t, 0.5 * d.eta_rad * d.eta_rad * t,
                                     0.0);
        EXPECT_LE((diff - second).norm(), 3 * theta * theta * theta * (1 + t * t) + 1e-15);
        EXPECT_NEAR(exact.norm(), 1.0, 1e-15);
      }
  }
  // The documented example: ξ = η = 1′ at 45°: east component −8.5e-8 rad.
  const double am = mu::arcsec_to_rad(60);
  const Eigen::Vector3d diff = mg::astronomic_zenith_enu({am, am}, deg_to_rad(45)) -
                               mg::astronomic_zenith_enu_first_order({am, am});
  EXPECT_NEAR(diff.x(), -am * am, 1e-10);
  EXPECT_NEAR(diff.x(), -8.5e-8, 0.05e-8);
}

TEST(Frames, RoundTrips) {
  for (double lat_deg : {-89.0, -45.0, 0.0, 12.0, 60.0, 89.5})
    for (double xi_arcsec : {-1800.0, -20.0, 0.0, 3.3})
      for (double eta_arcsec : {-7.0, 0.0, 45.0, 2000.0}) {
        SCOPED_TRACE(testing::Message() << lat_deg << " " << xi_arcsec << " " << eta_arcsec);
        const double phi = deg_to_rad(lat_deg);
        const mg::Deflection d{mu::arcsec_to_rad(xi_arcsec), mu::arcsec_to_rad(eta_arcsec)};
        const mg::Deflection e =
            mg::deflection_from_zenith_enu(mg::astronomic_zenith_enu(d, phi), phi);
        EXPECT_NEAR(e.xi_rad, d.xi_rad, 5e-16);
        EXPECT_NEAR(e.eta_rad, d.eta_rad, 1e-15);
        const mg::Deflection f =
            mg::deflection_from_zenith_enu_first_order(mg::astronomic_zenith_enu_first_order(d));
        EXPECT_DOUBLE_EQ(f.xi_rad, d.xi_rad);
        EXPECT_DOUBLE_EQ(f.eta_rad, d.eta_rad);
        // Through astronomic coordinates: Φ, Λ → vector → (ξ, η) equals the definition.
        const double lam = deg_to_rad(-71.1);
        const double alat = phi + d.xi_rad, alon = lam + d.eta_rad / std::cos(phi);
        const mg::Deflection g =
            mg::deflection_from_zenith_enu(mg::astronomic_zenith_enu(alat, alon, phi, lam), phi);
        const mg::Deflection h = mg::deflection_from_astronomic(alat, alon, phi, lam);
        EXPECT_NEAR(g.xi_rad, h.xi_rad, 5e-16);
        EXPECT_NEAR(g.eta_rad, h.eta_rad, 1e-13);  // Λ − λ differenced at |λ| ~ 1.2 rad
      }
  // A vector of any length is accepted.
  const mg::Deflection k =
      mg::deflection_from_zenith_enu(Eigen::Vector3d(2e-5, -3e-5, 1.0) * 7.5, 0.3);
  const mg::Deflection k1 = mg::deflection_from_zenith_enu(Eigen::Vector3d(2e-5, -3e-5, 1.0), 0.3);
  EXPECT_NEAR(k.xi_rad, k1.xi_rad, 2e-16);  // Φ − φ at |φ| = 0.3
  EXPECT_NEAR(k.eta_rad, k1.eta_rad, 2e-16);
}

TEST(Frames, BadInputThrows) {
  using meridian::InputError;
  const double over = deg_to_rad(90.0001);
  EXPECT_THROW(mg::rotation_ecef_to_enu(over, 0.0), InputError);
  EXPECT_THROW(mg::rotation_ecef_to_enu(-over, 0.0), InputError);
  EXPECT_THROW(mg::rotation_ecef_to_enu(kNan, 0.0), InputError);
  EXPECT_THROW(mg::rotation_ecef_to_enu(0.1, std::numeric_limits<double>::infinity()), InputError);
  EXPECT_THROW(mg::rotation_ecef_to_ned(over, 0.0), InputError);
  EXPECT_NO_THROW(mg::rotation_ecef_to_enu(mu::kPi / 2, 0.0));
  EXPECT_THROW(mg::geocentric_latitude_rad(over, 0.0, mg::wgs84()), InputError);
  EXPECT_THROW(mg::geocentric_latitude_rad(0.5, kNan, mg::wgs84()), InputError);
  EXPECT_THROW(mg::geocentric_latitude_rad(0.5, -6.4e6, mg::wgs84()), InputError);
  EXPECT_THROW(mg::geocentric_latitude_rad(0.5, 0.0, mg::Ellipsoid{"bad", -1.0, 0.0}), InputError);
  EXPECT_THROW(mg::rotation_geocentric_to_enu(0.5, over), InputError);
  EXPECT_THROW(mg::deflection_from_astronomic(over, 0.0, 0.5, 0.0), InputError);
  EXPECT_THROW(mg::deflection_from_astronomic(0.5, 0.0, 0.5, kNan), InputError);
  EXPECT_THROW(mg::astronomic_zenith_enu(0.5, 0.0, over, 0.0), InputError);
  // Deflections beyond 0.01 rad (e.g. arc-seconds passed as radians).
  EXPECT_THROW(mg::astronomic_zenith_enu(mg::Deflection{5.0, 0.0}, 0.5), InputError);
  EXPECT_THROW(mg::astronomic_zenith_enu(mg::Deflection{0.0, -0.0101}, 0.5), InputError);
  EXPECT_THROW(mg::astronomic_zenith_enu_first_order({kNan, 0.0}), InputError);
  EXPECT_THROW(mg::astronomic_zenith_enu_first_order({0.0, 0.02}), InputError);
  // η / cos φ needs |φ| < 90°; Φ = φ + ξ must stay within ±90°.
  EXPECT_THROW(mg::astronomic_zenith_enu(mg::Deflection{0.0, 1e-5}, mu::kPi / 2), InputError);
  EXPECT_THROW(mg::astronomic_zenith_enu(mg::Deflection{1e-3, 0.0}, mu::kPi / 2 - 1e-4),
               InputError);
  EXPECT_THROW(mg::deflection_from_zenith_enu(Eigen::Vector3d::Zero(), 0.5), InputError);
  EXPECT_THROW(mg::deflection_from_zenith_enu(Eigen::Vector3d(0, kNan, 1), 0.5), InputError);
  EXPECT_THROW(mg::deflection_from_zenith_enu(Eigen::Vector3d::UnitZ(), over), InputError);
  EXPECT_THROW(mg::deflection_from_zenith_enu_first_order(Eigen::Vector3d(0.1, 0, 0)), InputError);
  EXPECT_THROW(mg::deflection_from_zenith_enu_first_order(Eigen::Vector3d(0, 0, -1)), InputError);
}
