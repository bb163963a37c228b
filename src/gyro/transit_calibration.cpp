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

// B and the direction-corrected Δt from the transit method itself, so any
// number of transits and reversals is handled the same way as in reductions.
TransitData transit_data(const DeterminationInput& d, const Instrument& inst, const char* field) {
  try {
    if (d.mode != Mode::NonTracking)
      throw InputError("must be a non-tracking determination", {"", std::nullopt, "mode"});
    const BetaResult r = reduce_nontracking(NonTrackingMethod::Transit, d.nontracking, inst);
    if (!r.amplitude_div || !r.time_difference_s)
      throw NumericalError("the transit method gave no amplitude or time difference");
    return {*r.amplitude_div, *r.time_difference_s};
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
  const TransitData a = transit_data(first, inst, "determinations[0]");
  const TransitData b = transit_data(second, inst, "determinations[1]");
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

TransitFactorCalibration calibrate_transit_factor(const ReduceInput& in) {
  if (in.determinations.size() != 2)
    throw InputError(fmt::format("exactly two determinations (east and west clamp) are needed, got {}",
                                 in.determinations.size()),
                     {"", std::nullopt, "determinations"});
  ResolvedInstrument inst;
  try {
    inst = resolve_instrument(in.instrument, in.latitude_rad);
  } catch (Error& e) {
    e.add_context("", std::nullopt, "instrument");
    throw;
  }
  return calibrate_transit_factor(in.determinations[0], in.determinations[1], inst.instrument);
}

}  // namespace meridian::gyro
