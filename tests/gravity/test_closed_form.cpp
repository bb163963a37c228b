// Single-harmonic models against closed forms, and structural properties
// (truncation equivalence, batch = single, circle = point).

#include <GeographicLib/NormalGravity.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "gravity_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/gravity/gravity_circle.hpp"
#include "test_units.hpp"

namespace {

using namespace gtest_gravity;
using gtest_gravity::kDeg;
using meridian::gravity::FieldValues;
using meridian::gravity::GeodeticPoint;
using meridian::gravity::GravityField;
using meridian::gravity::GravityModelData;
using meridian::gravity::Quantities;

// A model equal to the WGS84 normal gravitational field (zonal terms from
// GeographicLib's J_n) plus one harmonic C̄_nm cos mλ + S̄_nm sin mλ; its
// disturbing potential is that harmonic alone.
GravityModelData single_harmonic(int n, int m, double c, double s) {
  GravityModelData d;
  d.name = "single";
  d.gm_m3_s2 = 3.986004418e14;
  d.radius_m = 6378137.0;
  d.coefficients = meridian::gravity::SphericalHarmonicCoefficients(std::max(n, 20), std::max(n, 20));
  d.coefficients.set(0, 0, 1, 0);
  const auto& g = GeographicLib::NormalGravity::WGS84();
  for (int k = 2; k <= 20; k += 2) d.coefficients.set(k, 0, -g.DynamicalFormFactor(k) / std::sqrt(2.0 * k + 1), 0);
  d.coefficients.set(n, m, d.coefficients.c(n, m) + c, s);
  return d;
}

struct Harmonic {
  double value, d_dpsi, d_dlambda;  // Σ (a/r)^{n+1} P̄ (C cos + S sin) and its ψ, λ derivatives
};

// Any P̄_nm(sin ψ) and its ψ-derivative, for degrees without a closed form: the forward column
// recursion in long double at a complex latitude ψ + i h, the derivative from the complex
// step Im P̄(ψ + i h)/h (exact to rounding, no difference quotient). Independent of the
// engine's forms of the derivative (the identity away from the poles, its recursion near them).
struct PbarAndDerivative {
  long double value, d_dpsi;
};
PbarAndDerivative pbar_complex_step(int n, int m, double psi) {
  using C = std::complex<long double>;
  const long double h = 1e-300L;
  const C z(psi, h), t = std::sin(z), u = std::cos(z);
  C p = std::sqrt(static_cast<long double>(m == 0 ? 1 : 2));  // P̄_mm = √(2 or 1) Π √((2k+1)/2k) u^m
  for (int k = 1; k <= m; ++k) p *= std::sqrt((2.0L * k + 1) / (2.0L * k)) * u;
  C p1 = p, p2 = 0;
  for (int k = m + 1; k <= n; ++k) {
    const long double a = std::sqrt((2.0L * k - 1) * (2.0L * k + 1) / ((k - m) * static_cast<long double>(k + m)));
    const long double b = k == m + 1 ? 0
                                     : std::sqrt((2.0L * k + 1) * (k + m - 1) * (k - m - 1) /
                                                 ((k - m) * static_cast<long double>(k + m) * (2.0L * k - 3)));
    const C next = a * t * p1 - b * p2;
    p2 = p1;
    p1 = next;
  }
  return {p1.real(), p1.imag() / h};
}

// P̄_32(t) = √105/2 · t u²;  P̄_31 = (3/2)√(7/6)(5t² − 1) u; P̄_nn = √2 Π_k √((2k+1)/2k) · u^n.
double pbar(int n, int m, double psi) {
  const double t = std::sin(psi), u = std::cos(psi);
  if (n == 3 && m == 2) return std::sqrt(105.0) / 2 * t * u * u;
  if (n == 3 && m == 1) return 1.5 * std::sqrt(7.0 / 6) * (5 * t * t - 1) * u;
  if (n > 3 && n != m) return static_cast<double>(pbar_complex_step(n, m, psi).value);
  if (n == m) {
    double logp = 0.5 * std::log(2.0) + n * std::log(u);
    for (int k = 1; k <= n; ++k) logp += 0.5 * std::log((2.0 * k + 1) / (2.0 * k));
    return std::exp(logp);
  }
  return NAN;
}
double dpbar(int n, int m, double psi) {  // d/dψ
  const double t = std::sin(psi), u = std::cos(psi);
  if (n == 3 && m == 2) return std::sqrt(105.0) / 2 * u * (u * u - 2 * t * t);
  if (n == 3 && m == 1) return 1.5 * std::sqrt(7.0 / 6) * (10 * t * u * u - (5 * t * t - 1) * t);
  if (n == m) return -n * t / u * pbar(n, m, psi);
  if (n > 3) return static_cast<double>(pbar_complex_step(n, m, psi).d_dpsi);
  return NAN;
}

// Compare the engine with the closed form at `pts` (none exactly at a pole).
void check_single(int n, int m, double c, double s, const std::vector<TestPoint>& pts) {
  const GravityModelData d = single_harmonic(n, m, c, s);
  const GravityField f(d);
  const auto& g = GeographicLib::NormalGravity::WGS84();
  const double gm = d.gm_m3_s2, a = d.radius_m;
  // The harmonic's largest |P̄|, |dP̄/dψ| and m|P̄|/u over latitude: errors are relative to the
  // size of the function, not to its value at a point (which may be near a zero of it).
  double size_p = 1, size_d = n, size_e = m;
  for (double lat = -89.75; lat < 90; lat += 0.5) {
    const double psi = lat * kDeg;
    size_p = std::max(size_p, std::abs(pbar(n, m, psi)));
    size_d = std::max(size_d, std::abs(dpbar(n, m, psi)));
    size_e = std::max(size_e, m * std::abs(pbar(n, m, psi)) / std::cos(psi));
  }
  // Relative 1e-12, or 20 n ε at high degree (the recursions' rounding grows with n).
  const double rel = std::max(1e-12, 20 * n * std::numeric_limits<double>::epsilon());
  for (const TestPoint& p : pts) {
    SCOPED_TRACE(testing::Message() << "n " << n << " m " << m << " lat " << p.lat_deg << " h " << p.h_m);
    double x, y, z;
    g.Earth().Forward(p.lat_deg, p.lon_deg, p.h_m, x, y, z);
    const double r = std::sqrt(x * x + y * y + z * z), psi = std::atan2(z, std::hypot(x, y)), lam = p.lon_deg * kDeg;
    const double qn = std::pow(a / r, n), trig = c * std::cos(m * lam) + s * std::sin(m * lam);
    const double t = gm / r * qn * pbar(n, m, psi) * trig;
    const double north = gm / (r * r) * qn * dpbar(n, m, psi) * trig;
    const double east = gm / (r * r) * qn * pbar(n, m, psi) / std::cos(psi) * m * (-c * std::sin(m * lam) + s * std::cos(m * lam));
    double gx, gy, gz;
    g.U(x, y, z, gx, gy, gz);
    const double gamma = std::sqrt(gx * gx + gy * gy + gz * gz);
    const FieldValues v = f.evaluate(geodetic(p));
    // Relative `rel` of the harmonic's size, plus a floor for the normal
    // zonal terms (GeographicLib's J_n put in, ours taken out: ~1e-18 each).
    const double scale = gm / r * qn * std::hypot(c, s), floor_t = 1e-10, floor_g = 1e-16;
    // Plus the function's own sensitivity to ψ, which the engine (from t = z/r) and this reference
    // (from atan2) each know to a few ε.
    // Within 1/n of a pole the column recursion's two characteristic roots coalesce at 1 and its
    // rounding grows as n² ε/2 instead of n ε (2e-12 of P̄_n0 at n = 300, 0.1° from the pole).
    const double eps = std::numeric_limits<double>::epsilon();
    const double polar = std::numbers::pi / 2 - std::abs(psi) < 1.0 / n ? n * n * eps / 2 : 0.0;
    const double tol_t = ((rel + polar) * size_p + 4 * eps * std::abs(dpbar(n, m, psi))) * scale + floor_t,
                 tol_n = rel * scale * size_d / r + floor_g, tol_e = rel * scale * std::max(size_d, size_e) / r + floor_g;
    EXPECT_NEAR(v.disturbing_potential_m2_s2, t, tol_t);
    EXPECT_NEAR(v.dT_up_m_s2, -(n + 1) * t / r, (tol_t - floor_t) * (n + 1) / r + floor_g);
    EXPECT_NEAR(v.dT_north_m_s2, north, tol_n);
    EXPECT_NEAR(v.dT_east_m_s2, east, tol_e);
    EXPECT_NEAR(v.xi_rad, -north / gamma, tol_n / gamma);
    EXPECT_NEAR(v.eta_rad, -east / gamma, tol_e / gamma);
    // Geoid: T on the ellipsoid over Somigliana gravity.
    g.Earth().Forward(p.lat_deg, p.lon_deg, 0, x, y, z);
    const double r0 = std::sqrt(x * x + y * y + z * z), psi0 = std::atan2(z, std::hypot(x, y));
    const double t0 = gm / r0 * std::pow(a / r0, n) * pbar(n, m, psi0) * trig;
    EXPECT_NEAR(v.geoid_m, t0 / g.SurfaceGravity(p.lat_deg), tol_t / 9.7 * std::pow(a / r0, n) / qn);
  }
}

std::vector<TestPoint> closed_form_points() {
  return {{0, 0, 0}, {10, 25, 100}, {-33.3, -70.1, 5000}, {60, 150, -500}, {89.99, 10, 0}, {-89.9, -100, 10000}, {45, 45, 1e6}};
}

TEST(GravityClosedForm, TesseralDegree3Order2) { check_single(3, 2, 1e-6, -4e-7, closed_form_points()); }
TEST(GravityClosedForm, TesseralDegree3Order1) { check_single(3, 1, -2e-6, 5e-7, closed_form_points()); }
TEST(GravityClosedForm, SectoralDegree1000) {
  // High order: exercises the scaled sectoral start and the Horner sum.
  check_single(1000, 1000, 1e-6, 2e-6, {{0, 0, 0}, {5, 0.07, 0}, {-10, 33, 3000}, {20, -3, 10000}});
}

// The north derivative on both sides of the latitude where the engine changes its form of the
// derivative (u = cos ψ = 0.1, geocentric ψ ≈ ±84.26°: the identity below, the recursion above;
// gravity/synthesis.cpp), at high degree, against the complex-step reference.
TEST(GravityClosedForm, NorthDerivativeAcrossTheChangeOfForm) {
  const std::vector<TestPoint> pts = {{30, 10, 0},     {60, -40, 200},   {80, 75, 0},     {84.0, 5, 0},
                                      {84.2, 120, 0},  {84.3, -60, 500}, {84.5, 33, 0},   {86, 170, 0},
                                      {89.9, -5, 100}, {-84.2, 45, 0},   {-84.35, -91, 0}, {-70, 12, 3000}};
  check_single(300, 0, 1e-7, 0, pts);
  check_single(300, 7, 2e-7, -1e-7, pts);
  check_single(1500, 40, 1e-8, 3e-8, pts);
}

TEST(GravityStructure, TruncationEqualsZeroedCoefficients) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 200;
  o.seed = 3;
  const GravityModelData full = meridian::gravity::make_synthetic_model(o);
  GravityModelData zeroed = full;
  for (int m = 0; m <= 200; ++m)
    for (int n = std::max(m, 2); n <= 200; ++n)
      if (n > 90 || m > 60) zeroed.coefficients.set(n, m, 0, 0);
  GravityModelData cut = full;
  cut.coefficients = full.coefficients.truncated(90, 60);
  const GravityField fz(zeroed), fc(cut);
  for (const auto& p : test_points(20, 5)) {
    const FieldValues a = fz.evaluate(geodetic(p)), b = fc.evaluate(geodetic(p));
    EXPECT_NEAR(a.xi_rad, b.xi_rad, 1e-15);
    EXPECT_NEAR(a.eta_rad, b.eta_rad, 1e-15);
    EXPECT_NEAR(a.geoid_m, b.geoid_m, 1e-10);
  }
}

TEST(GravityStructure, BatchThreadsAndCircleAgreeWithSinglePoints) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 150;
  const GravityModelData m = meridian::gravity::make_synthetic_model(o);
  const GravityField one(m, {false, 1}), many(m, {false, 3});
  const auto tp = test_points(40, 17);
  std::vector<GeodeticPoint> pts;
  for (const auto& p : tp) pts.push_back(geodetic(p));
  const auto a = one.evaluate(pts), b = many.evaluate(pts);
  ASSERT_EQ(a.size(), pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const FieldValues s = one.evaluate(pts[i]);
    EXPECT_EQ(a[i].xi_rad, b[i].xi_rad);
    EXPECT_EQ(a[i].geoid_m, b[i].geoid_m);
    EXPECT_NEAR(a[i].xi_rad, s.xi_rad, 1e-18);
    EXPECT_NEAR(a[i].eta_rad, s.eta_rad, 1e-18);
    EXPECT_NEAR(a[i].geoid_m, s.geoid_m, 1e-12);
  }
  const meridian::gravity::GravityCircle c(one, 47.5 * kDeg, 800);
  for (double lon = -180; lon <= 180; lon += 30) {
    const FieldValues s = one.evaluate({47.5 * kDeg, lon * kDeg, 800});
    const FieldValues v = c.evaluate(lon * kDeg);
    EXPECT_NEAR(v.xi_rad, s.xi_rad, 1e-15);
    EXPECT_NEAR(v.eta_rad, s.eta_rad, 1e-15);
    EXPECT_NEAR(v.geoid_m, s.geoid_m, 1e-10);
    EXPECT_NEAR(v.anomaly_m_s2, s.anomaly_m_s2, 1e-12);
  }
}

TEST(GravityStructure, RejectsPointsOutsideTheDomain) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 10;
  const GravityField f(meridian::gravity::make_synthetic_model(o));
  EXPECT_THROW(f.evaluate({91 * kDeg, 0, 0}), meridian::InputError);
  EXPECT_THROW(f.evaluate({NAN, 0, 0}), meridian::InputError);
  EXPECT_THROW(f.evaluate({0, 0, -20000}), meridian::InputError);
  EXPECT_THROW(f.evaluate({0, 0, 2e7}), meridian::InputError);
  const std::vector<GeodeticPoint> pts = {{0, 0, 0}, {-1.6, 0, 0}};
  try {
    (void)f.evaluate(pts);
    FAIL() << "no error";
  } catch (const meridian::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("points[1]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("latitude"), std::string::npos) << e.what();
  }
}

}  // namespace
