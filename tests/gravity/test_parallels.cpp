// evaluate_parallels (gravity_circle.hpp): a GravityCircle per row over threads, against the
// model evaluated point by point, and its errors.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <set>
#include <vector>

#include "gravity_test_support.hpp"
#include "meridian/core/error.hpp"
#include "meridian/gravity/gravity_circle.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "test_units.hpp"

namespace {

using namespace gtest_gravity;
using gtest_gravity::kArcsec;
using gtest_gravity::kDeg;
namespace mg = meridian::gravity;

TEST(GravityParallels, EveryNodeAsTheModelGivesItPointByPoint) {
  mg::SyntheticModelOptions o;
  o.max_degree = 60;
  o.seed = 7;
  const mg::GravityField field(mg::make_synthetic_model(o), {false, 1});
  const std::vector<double> lat = {-89.5 * kDeg, -30 * kDeg, 0.0, 12.25 * kDeg, 90 * kDeg};
  const std::vector<double> lon = {-181 * kDeg, 0.0, 33.3 * kDeg, 359 * kDeg};
  const double h = 350;
  for (unsigned threads : {1u, 3u, 8u}) {
    std::mutex m;
    std::set<std::size_t> seen;
    mg::evaluate_parallels(field, lat, lon, h, mg::Quantities::All, threads,
                           [&](std::size_t i, std::span<const mg::FieldValues> v) {
                             const std::lock_guard lock(m);
                             EXPECT_TRUE(seen.insert(i).second) << "row " << i << " twice";
                             ASSERT_EQ(v.size(), lon.size());
                             for (std::size_t j = 0; j < lon.size(); ++j) {
                               const mg::FieldValues p = field.evaluate({lat[i], lon[j], h});
                               EXPECT_NEAR(v[j].xi_rad, p.xi_rad, 1e-12 * kArcsec) << i << "," << j;
                               EXPECT_NEAR(v[j].eta_rad, p.eta_rad, 1e-12 * kArcsec) << i << "," << j;
                               EXPECT_NEAR(v[j].geoid_m, p.geoid_m, 1e-10) << i << "," << j;
                             }
                           });
    EXPECT_EQ(seen.size(), lat.size()) << threads;
  }
}

TEST(GravityParallels, BadInputAndNonFiniteValuesAreErrors) {
  mg::SyntheticModelOptions o;
  o.max_degree = 8;
  const mg::GravityField field(mg::make_synthetic_model(o), {false, 1});
  const std::vector<double> lon = {0.0};
  const auto nothing = [](std::size_t, std::span<const mg::FieldValues>) {};
  const std::vector<double> bad_lat = {0.0, 91 * kDeg};
  EXPECT_THROW(mg::evaluate_parallels(field, bad_lat, lon, 0, mg::Quantities::All, 2, nothing), meridian::InputError);
  // A damaged coefficient (NaN) gives no value: the first node is named.
  mg::GravityModelData damaged = mg::make_synthetic_model(o);
  damaged.coefficients.set(3, 1, std::numeric_limits<double>::quiet_NaN(), 0);
  const mg::GravityField broken(damaged, {false, 1});
  const std::vector<double> lat = {10 * kDeg, 20 * kDeg};
  try {
    mg::evaluate_parallels(broken, lat, lon, 0, mg::Quantities::Deflection, 1, nothing);
    ADD_FAILURE() << "no error";
  } catch (const meridian::NumericalError& e) {
    EXPECT_EQ(e.context().field, "points[0, 0]");
  }
  // Nothing to do: no call of the sink.
  mg::evaluate_parallels(field, {}, lon, 0, mg::Quantities::All, 0, [](std::size_t, std::span<const mg::FieldValues>) {
    ADD_FAILURE() << "sink called";
  });
}

}  // namespace
