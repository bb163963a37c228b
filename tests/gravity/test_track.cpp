// Along-track interpolation against the model evaluated at every point.

#include <gtest/gtest.h>

#include <cmath>

#include "gravity_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/gravity/track.hpp"
#include "test_units.hpp"

namespace {

using namespace gtest_gravity;
using gtest_gravity::kArcsec;
using gtest_gravity::kDeg;
using meridian::gravity::GeodeticPoint;

std::vector<GeodeticPoint> wiggly_track(std::size_t n, double step_m) {
  std::vector<GeodeticPoint> t;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) * step_m;
    t.push_back({(30.0 + 0.05 * std::sin(s / 7000.0)) * kDeg, (100.0 + s / 96000.0) * kDeg, 150 + 140 * std::sin(s / 3000.0)});
  }
  return t;
}

TEST(GravityTrack, InterpolatedValuesStayWithinTheTolerance) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 360;
  o.seed = 8;
  const meridian::gravity::GravityField f(meridian::gravity::make_synthetic_model(o));
  const auto track = wiggly_track(3000, 12.0);  // 36 km every 12 m
  meridian::gravity::TrackOptions to;
  to.tolerance_rad = 1e-4 * kArcsec;
  to.tolerance_geoid_m = 1e-5;
  const auto r = meridian::gravity::evaluate_track(f, track, meridian::gravity::Quantities::All, to);
  const auto exact = f.evaluate(track);
  double exi = 0, eeta = 0, en = 0, ea = 0;
  for (std::size_t i = 0; i < track.size(); ++i) {
    exi = std::max(exi, std::abs(r.values[i].xi_rad - exact[i].xi_rad));
    eeta = std::max(eeta, std::abs(r.values[i].eta_rad - exact[i].eta_rad));
    ea = std::max(ea, std::abs(r.values[i].xi_astro_rad - exact[i].xi_astro_rad));
    en = std::max(en, std::abs(r.values[i].geoid_m - exact[i].geoid_m));
  }
  std::printf("[ track ] %zu points, %zu model evaluations; max error xi %.2e\", eta %.2e\", N %.2e m\n", track.size(),
              r.model_evaluations, exi / kArcsec, eeta / kArcsec, en);
  EXPECT_LT(r.model_evaluations, track.size() / 3);
  EXPECT_LE(exi, 1.5 * to.tolerance_rad);
  EXPECT_LE(eeta, 1.5 * to.tolerance_rad);
  EXPECT_LE(ea, 1.5 * to.tolerance_rad);
  EXPECT_LE(en, 1.5 * to.tolerance_geoid_m);
  EXPECT_LE(r.max_checked_error_rad, to.tolerance_rad);
  // Evaluated points are exact.
  EXPECT_EQ(r.values.front().xi_rad, exact.front().xi_rad);
  EXPECT_EQ(r.values.back().geoid_m, exact.back().geoid_m);
}

TEST(GravityTrack, RejectsBadPointsAndTolerances) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 10;
  const meridian::gravity::GravityField f(meridian::gravity::make_synthetic_model(o));
  std::vector<GeodeticPoint> t = {{0, 0, 0}, {2.0, 0, 0}};
  EXPECT_THROW(meridian::gravity::evaluate_track(f, t), meridian::InputError);
  t[1].lat_rad = 0.001;
  meridian::gravity::TrackOptions bad;
  bad.tolerance_rad = 0;
  EXPECT_THROW(meridian::gravity::evaluate_track(f, t, meridian::gravity::Quantities::All, bad), meridian::InputError);
  EXPECT_EQ(meridian::gravity::evaluate_track(f, t).values.size(), 2u);
  EXPECT_TRUE(meridian::gravity::evaluate_track(f, std::span<const GeodeticPoint>{}).values.empty());
}

}  // namespace
