#include "meridian/gyro/transit_calibration.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {
namespace {

struct TransitData {
  Uncertain amplitude, dt;
};

TransitData transit_data(const DeterminationInput& d, const char* field) {
  try {
    if (d.mode != Mode::NonTracking) throw InputError("must be a non-tracking determination", {"", std::nullopt, "mode"});
    const auto& o = d.nontracking;
    const Crossing* zero = nullptr;
    for (const auto& c : o.crossings)
      if (c.level_div == 0.0) zero = &c;
    if (!zero || zero->times_s.size() < 3)
      throw InputError("three crossings of level 0 are needed", {"", std::nullopt, "crossings"});
    if (o.reversals_div.size() < 2)
      throw InputError("two reversal readings are needed for the amplitude", {"", std::nullopt, "reversals_div"});
    const double ae = o.reversals_div[0], aw = o.reversals_div[1];
    if ((ae > 0) == (aw > 0))
      throw InputError("the two reversal readings must lie on either side of the scale zero",
                       {"", std::nullopt, "reversals_div"});
    TransitData t;
    t.amplitude = {0.5 * (std::fabs(ae) + std::fabs(aw)), o.sigma_reading_div / std::sqrt(2.0)};
    const auto& ts = zero->times_s;
    // Δt for an eastward first transit; a westward first transit flips its sign.
    t.dt = {zero->first_direction * time_difference_s(ts[0], ts[1], ts[2]), o.sigma_time_s * std::sqrt(6.0)};
    return t;
  } catch (Error& e) {
    e.add_context("", std::nullopt, field);
    throw;
  }
}

}  // namespace

TransitFactorCalibration calibrate_transit_factor(const DeterminationInput& first,
                                                  const DeterminationInput& second,
                                                  const Instrument& inst) {
  TransitFactorCalibration r;
  const TransitData a = transit_data(first, "determinations[0]");
  const TransitData b = transit_data(second, "determinations[1]");
  const double dclamp = wrap_signed_rad(second.clamp_reading_rad - first.clamp_reading_rad);
  if (std::fabs(dclamp) < units::kArcminute)
    throw InputError("the two clamp readings must differ (by 10-15' on either side of north)",
                     {"", std::nullopt, "determinations[1].clamp_reading"});
  r.amplitude1_div = a.amplitude;
  r.amplitude2_div = b.amplitude;
  r.dt1_s = a.dt;
  r.dt2_s = b.dt;
  r.factor_rad_per_div_s = gyro::calibrate_transit_factor(first.clamp_reading_rad, a.amplitude, a.dt,
                                                          first.clamp_reading_rad + dclamp,
                                                          b.amplitude, b.dt);
  r.north_rad = wrap_positive_rad(first.clamp_reading_rad +
                                  r.factor_rad_per_div_s.value * a.amplitude.value * a.dt.value);
  const auto& p = first.nontracking.period_s ? first.nontracking.period_s : second.nontracking.period_s;
  if (p) {
    r.computed_rad_per_div_s =
        (1.0 + inst.torsion_ratio.value) * inst.scale_value_rad * units::kPi / (2.0 * p->value);
  } else {
    r.notes.push_back("no period_s given: the computed factor (1+lambda)*tau*pi/(2 T_B) is not shown");
  }
  r.notes.push_back("zero-position correction not part of c: apply it separately (-lambda*tau*alpha_p)");
  return r;
}

}  // namespace meridian::gyro
