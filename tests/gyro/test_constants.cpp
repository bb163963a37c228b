#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/constants.hpp"

using meridian::InputError;
using meridian::units::deg_to_rad;
using namespace meridian::gyro;

namespace {

using meridian::units::kPi;
constexpr double kOmega = 7.292115e-5;  // spec README, written out independently

// A plausible sensitive element: T_A ≈ 8 min and λ ≈ 0.3 at φ = 34°.
PhysicalGyro typical_gyro() { return {0.25, 0.088, 4.5e-6}; }

}  // namespace

TEST(Constants, PeriodsFromPhysicsMatchClosedForms) {
  const PhysicalGyro g = typical_gyro();
  const double phi = deg_to_rad(34.0);
  const GyroPeriods p = periods_from_physics(g, phi);
  const double dk = 0.25 * kOmega * std::cos(phi);
  EXPECT_NEAR(p.directive_torque_Nm_per_rad, dk, 1e-18);
  EXPECT_NEAR(p.tracking_s, 2 * kPi * std::sqrt(0.088 / dk), 1e-9);
  EXPECT_NEAR(p.free_s, 2 * kPi * std::sqrt(0.088 / 4.5e-6), 1e-9);
  EXPECT_NEAR(p.nontracking_s, 2 * kPi * std::sqrt(0.088 / (dk + 4.5e-6)), 1e-9);
  EXPECT_NEAR(p.torsion_ratio, 4.5e-6 / dk, 1e-15);
  // Realistic instrument: 7–10 min tracking period, λ of a few tenths.
  EXPECT_GT(p.tracking_s, 7 * 60.0);
  EXPECT_LT(p.tracking_s, 10 * 60.0);
  EXPECT_NEAR(p.tracking_s, 480.0, 15.0);
  EXPECT_NEAR(p.torsion_ratio, 0.30, 0.05);
  EXPECT_LT(p.nontracking_s, p.tracking_s);
  EXPECT_LT(p.tracking_s, p.free_s);
}

TEST(Constants, PeriodRelationsAreConsistent) {
  for (double lat_deg : {0.0, 20.0, 34.0, -45.0, 70.0}) {
    const GyroPeriods p = periods_from_physics(typical_gyro(), deg_to_rad(lat_deg));
    const double r = p.tracking_s / p.nontracking_s;
    EXPECT_NEAR(r * r, 1.0 + p.torsion_ratio, 1e-12) << lat_deg;
    EXPECT_NEAR(torsion_ratio_from_free_period(p.tracking_s, p.free_s), p.torsion_ratio, 1e-12);
    EXPECT_NEAR(torsion_ratio_from_nontracking_period(p.tracking_s, p.nontracking_s),
                p.torsion_ratio, 1e-12);
  }
}

TEST(Constants, TorsionRatioFromPeriodsSimpleNumbers) {
  EXPECT_DOUBLE_EQ(torsion_ratio_from_free_period(480.0, 960.0), 0.25);
  EXPECT_DOUBLE_EQ(torsion_ratio_from_nontracking_period(500.0, 400.0), 0.5625);
}

TEST(Constants, UncertainTorsionRatioPropagation) {
  const Uncertain ta{480.0, 0.5};
  const Uncertain tb{421.0, 0.4};
  const Uncertain lam = torsion_ratio_from_nontracking_period(ta, tb);
  EXPECT_DOUBLE_EQ(lam.value, torsion_ratio_from_nontracking_period(480.0, 421.0));
  // Numerical partials.
  const double h = 1e-4;
  const double da = (torsion_ratio_from_nontracking_period(480.0 + h, 421.0) -
                     torsion_ratio_from_nontracking_period(480.0 - h, 421.0)) / (2 * h);
  const double db = (torsion_ratio_from_nontracking_period(480.0, 421.0 + h) -
                     torsion_ratio_from_nontracking_period(480.0, 421.0 - h)) / (2 * h);
  EXPECT_NEAR(lam.sigma, std::hypot(da * 0.5, db * 0.4), 1e-9);

  const Uncertain tf{900.0, 3.0};
  const Uncertain lf = torsion_ratio_from_free_period(ta, tf);
  EXPECT_DOUBLE_EQ(lf.value, (480.0 / 900.0) * (480.0 / 900.0));
  const double fa = (torsion_ratio_from_free_period(480.0 + h, 900.0) -
                     torsion_ratio_from_free_period(480.0 - h, 900.0)) / (2 * h);
  const double ff = (torsion_ratio_from_free_period(480.0, 900.0 + h) -
                     torsion_ratio_from_free_period(480.0, 900.0 - h)) / (2 * h);
  EXPECT_NEAR(lf.sigma, std::hypot(fa * 0.5, ff * 3.0), 1e-9);

  EXPECT_EQ(torsion_ratio_from_free_period(Uncertain{480.0, 0.0}, Uncertain{900.0, 0.0}).sigma,
            0.0);
  EXPECT_THROW(torsion_ratio_from_free_period(Uncertain{480.0, -1.0}, tf), InputError);
}

TEST(Constants, RescaleTorsionRatioMatchesPhysics) {
  const double phi0 = deg_to_rad(34.0);
  const double phi = deg_to_rad(62.5);
  const double lam0 = periods_from_physics(typical_gyro(), phi0).torsion_ratio;
  const double lam = periods_from_physics(typical_gyro(), phi).torsion_ratio;
  const Uncertain r = rescale_torsion_ratio({lam0, 0.01}, phi0, phi);
  EXPECT_NEAR(r.value, lam, 1e-12);
  EXPECT_NEAR(r.sigma, 0.01 * std::cos(phi0) / std::cos(phi), 1e-15);
  // Round trip and identity.
  const Uncertain back = rescale_torsion_ratio(r, phi, phi0);
  EXPECT_NEAR(back.value, lam0, 1e-12);
  EXPECT_NEAR(back.sigma, 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(rescale_torsion_ratio({0.3, 0.0}, phi0, phi0).value, 0.3);
  // Southern latitudes behave like northern ones.
  EXPECT_NEAR(rescale_torsion_ratio({0.3, 0.0}, phi0, -phi).value,
              rescale_torsion_ratio({0.3, 0.0}, phi0, phi).value, 1e-15);
  EXPECT_THROW(rescale_torsion_ratio({-0.1, 0.0}, phi0, phi), InputError);
  EXPECT_THROW(rescale_torsion_ratio({0.3, 0.0}, phi0, deg_to_rad(80.0)), InputError);
}

TEST(Constants, RescaleTransitFactorMatchesPhysics) {
  // c = (1+λ)·τ·π/(2 T_B) from the periods the physics gives at each latitude.
  const double tau = 600.0 * meridian::units::kArcsecond;
  auto c_at = [&](double phi) {
    const GyroPeriods p = periods_from_physics(typical_gyro(), phi);
    return (1.0 + p.torsion_ratio) * tau * meridian::units::kPi / (2.0 * p.nontracking_s);
  };
  for (double d : {0.0012, 1.0, 15.0, -20.0}) {
    const double phi0 = deg_to_rad(32.64), phi = deg_to_rad(32.64 + d);
    const double lam0 = periods_from_physics(typical_gyro(), phi0).torsion_ratio;
    const Uncertain c = rescale_transit_factor({c_at(phi0), 0.01 * c_at(phi0)}, lam0, phi0, phi);
    EXPECT_NEAR(c.value / c_at(phi), 1.0, 1e-12) << d;
    EXPECT_NEAR(c.sigma / c.value, 0.01, 1e-12);
  }
  EXPECT_DOUBLE_EQ(rescale_transit_factor({1e-5, 0.0}, 0.2, 0.5, 0.5).value, 1e-5);
  EXPECT_THROW(rescale_transit_factor({-1e-5, 0.0}, 0.2, 0.5, 0.6), InputError);
}

TEST(Constants, LatitudeLimit) {
  try {
    periods_from_physics(typical_gyro(), deg_to_rad(80.0));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "latitude 80.0° is above the usable limit 75.0° (cos φ → 0)");
  }
  EXPECT_NO_THROW(check_latitude(deg_to_rad(75.0)));
  EXPECT_NO_THROW(check_latitude(deg_to_rad(-74.9)));
  EXPECT_THROW(check_latitude(deg_to_rad(-75.1)), InputError);
  EXPECT_THROW(check_latitude(deg_to_rad(75.1)), InputError);
  EXPECT_THROW(check_latitude(std::nan("")), InputError);
  // A configurable limit.
  EXPECT_NO_THROW(check_latitude(deg_to_rad(80.0), deg_to_rad(85.0)));
  EXPECT_NO_THROW(periods_from_physics(typical_gyro(), deg_to_rad(80.0), deg_to_rad(85.0)));
  EXPECT_THROW(check_latitude(deg_to_rad(10.0), deg_to_rad(90.0)), InputError);
  EXPECT_THROW(check_latitude(deg_to_rad(10.0), 0.0), InputError);
  try {
    check_latitude(deg_to_rad(60.0), deg_to_rad(55.0));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "latitude 60.0° is above the usable limit 55.0° (cos φ → 0)");
  }
}

TEST(Constants, InvalidPhysicalInputs) {
  const double phi = deg_to_rad(34.0);
  EXPECT_THROW(periods_from_physics({0.0, 0.088, 4.5e-6}, phi), InputError);
  EXPECT_THROW(periods_from_physics({0.25, -0.088, 4.5e-6}, phi), InputError);
  EXPECT_THROW(periods_from_physics({0.25, 0.088, std::nan("")}, phi), InputError);
  EXPECT_THROW(periods_from_physics({0.25, 0.088, 0.0}, phi), InputError);
  EXPECT_THROW(periods_from_physics({INFINITY, 0.088, 4.5e-6}, phi), InputError);
  try {
    periods_from_physics({0.25, 0.088, -1.0}, phi);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.message(), testing::HasSubstr("D_B"));
  }
}

TEST(Constants, InvalidPeriods) {
  EXPECT_THROW(torsion_ratio_from_free_period(0.0, 900.0), InputError);
  EXPECT_THROW(torsion_ratio_from_free_period(480.0, -900.0), InputError);
  EXPECT_THROW(torsion_ratio_from_nontracking_period(480.0, std::nan("")), InputError);
  EXPECT_THROW(torsion_ratio_from_nontracking_period(480.0, 480.0), InputError);
  try {
    torsion_ratio_from_nontracking_period(420.0, 480.0);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_THAT(e.message(), testing::HasSubstr("must be shorter than the tracking period"));
    EXPECT_THAT(e.message(), testing::HasSubstr("480"));
  }
  EXPECT_THROW(torsion_ratio_from_nontracking_period(Uncertain{420.0, 1.0}, Uncertain{480.0, 1.0}),
               InputError);
}
