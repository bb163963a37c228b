// The gyro reduce workflow (ReduceInput → process → ReduceResult), method
// names, the station simulator and the transit-factor workflow's input checks.

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/reduce.hpp"
#include "meridian/gyro/station_simulator.hpp"
#include "meridian/gyro/transit_calibration.hpp"

using namespace meridian;
using namespace meridian::gyro;

namespace {
constexpr double kArcsec = units::kArcsecond;

double diff_arcsec(double a, double b) { return wrap_signed_rad(a - b) / kArcsec; }

StationSimulation noise_free(Mode mode) {
  StationSimulation s;
  s.mode = mode;
  s.sigma_time_s = 0;
  s.sigma_reading_div = 0;
  s.sigma_tracking_rad = 0;
  return s;
}
}  // namespace

TEST(GyroMethods, NamesRoundTripPerMode) {
  for (auto m : {NonTrackingMethod::Transit, NonTrackingMethod::TimeDifference, NonTrackingMethod::Direct,
                 NonTrackingMethod::TimedAmplitude1, NonTrackingMethod::TimedAmplitude2,
                 NonTrackingMethod::LeastSquares})
    EXPECT_EQ(method_from_string(Mode::NonTracking, to_string(Method{m})), Method{m});
  for (auto m : {ReversalMethod::TwoPoint, ReversalMethod::Schuler, ReversalMethod::LinearLsq,
                 ReversalMethod::NonlinearLsq})
    EXPECT_EQ(method_from_string(Mode::Tracking, to_string(Method{m})), Method{m});
  // "lsq" names a different method in each mode.
  EXPECT_EQ(method_from_string(Mode::NonTracking, "lsq"), Method{NonTrackingMethod::LeastSquares});
  EXPECT_EQ(method_from_string(Mode::Tracking, "lsq"), Method{ReversalMethod::NonlinearLsq});
  EXPECT_THROW(method_from_string(Mode::Tracking, "transit"), InputError);
  EXPECT_THROW(method_from_string(Mode::NonTracking, "all"), InputError);
  EXPECT_EQ(method_request_name(std::nullopt), "all");
}

TEST(GyroReduce, NoiseFreeStationRecoversTheSimulatedNorth) {
  // Non-tracking: the truth N_G = N' + (1+λ)τβ, computed here independently.
  StationSimulation s = noise_free(Mode::NonTracking);
  s.clamp_rad = 0.25 * units::kDegree;
  s.determinations = 2;
  const SimulatedStation sim = simulate_station(s, 3);
  ASSERT_EQ(sim.input.determinations.size(), 2u);
  const double truth = s.clamp_rad + (1.0 + s.torsion_ratio) * s.scale_value_rad * s.beta_div;
  const ReduceResult r = process(sim.input);
  ASSERT_EQ(r.determinations.size(), 2u);
  for (const auto& d : r.determinations) {
    EXPECT_FALSE(d.method);  // every method, the recommended one reported
    EXPECT_NEAR(diff_arcsec(d.primary.north.north_rad, truth), 0.0, 0.01);
  }
  ASSERT_FALSE(sim.truth.empty());
  EXPECT_NE(sim.truth[0].find("beta = -0.12 div"), std::string::npos);
  // Tracking: N_G = M without a zero position.
  const StationSimulation t = noise_free(Mode::Tracking);
  const ReduceResult rt = process(simulate_station(t, 4).input);
  EXPECT_NEAR(diff_arcsec(rt.determinations[0].primary.north.north_rad, t.centre_rad), 0.0, 0.01);
}

TEST(GyroReduce, ErrorsNameTheDetermination) {
  StationSimulation s = noise_free(Mode::NonTracking);
  s.determinations = 2;
  ReduceInput in = simulate_station(s, 3).input;
  in.determinations[1].method = Method{ReversalMethod::Schuler};  // a tracking method on a non-tracking run
  try {
    (void)process(in);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "determinations[1].method") << e.what();
  }
  in.latitude_rad = 80 * units::kDegree;  // beyond the instrument's latitude limit
  try {
    (void)process(in);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field.rfind("instrument", 0), 0u) << e.what();
  }
}

TEST(GyroTransitFactor, NeedsExactlyTwoDeterminations) {
  StationSimulation s = noise_free(Mode::NonTracking);
  s.determinations = 3;
  try {
    (void)calibrate_transit_factor(simulate_station(s, 1).input);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "determinations");
    EXPECT_NE(std::string(e.what()).find("got 3"), std::string::npos);
  }
}
