#pragma once
// Test-only: exact non-tracking observations from (N1) with k = 0, by
// inverting the sinusoid in closed form — the independent reference the
// reductions are checked against.

#include <cmath>

#include "meridian/core/units.hpp"
#include "meridian/gyro/instrument.hpp"
#include "meridian/gyro/nontracking.hpp"

namespace meridian_test {

// Spec §8 scenario 2 truth (β, B in div; T_B, t0 in s).
struct Truth {
  double beta = -0.12;
  double amp = 9.0;
  double period = 440.0;
  double t0 = 50.0;
};

// Passages of `level` from t_from on (k = 0): eastward at θ = ψ + 2πm,
// westward at θ = π − ψ + 2πm, ψ = asin((a − β)/B), t = t0 + T·θ/(2π).
inline meridian::gyro::Crossing passages(const Truth& o, double level, double t_from, int count) {
  using meridian::units::kPi;
  const double psi = std::asin((level - o.beta) / o.amp);
  meridian::gyro::Crossing c;
  c.level_div = level;
  for (int m = static_cast<int>(std::floor((t_from - o.t0) / o.period)) - 1;
       static_cast<int>(c.times_s.size()) < count; ++m) {
    for (int dir : {+1, -1}) {
      const double theta = (dir > 0 ? psi : kPi - psi) + 2.0 * kPi * m;
      const double t = o.t0 + o.period * theta / (2.0 * kPi);
      if (t < t_from || static_cast<int>(c.times_s.size()) >= count) continue;
      if (c.times_s.empty()) c.first_direction = dir;
      c.times_s.push_back(t);
    }
  }
  return c;
}

// Turning points from t_from on: east β + B at θ = π/2 + 2πm, west β − B at 3π/2 + 2πm.
inline void add_reversals(meridian::gyro::NonTrackingObservations& obs, const Truth& o,
                          double t_from, int count) {
  using meridian::units::kPi;
  for (int m = static_cast<int>(std::floor((t_from - o.t0) / o.period)) - 1;
       static_cast<int>(obs.reversals_div.size()) < count; ++m) {
    for (int side : {+1, -1}) {
      const double theta = (side > 0 ? 0.5 * kPi : 1.5 * kPi) + 2.0 * kPi * m;
      const double t = o.t0 + o.period * theta / (2.0 * kPi);
      if (t < t_from || static_cast<int>(obs.reversals_div.size()) >= count) continue;
      obs.reversals_div.push_back(o.beta + side * o.amp);
      obs.reversal_times_s.push_back(t);
    }
  }
}

// λ = 0.30, τ = 600″/div (spec §8.2).
inline meridian::gyro::Instrument scenario_instrument() {
  meridian::gyro::Instrument inst;
  inst.scale_value_rad = 600.0 * meridian::units::kArcsecond;
  inst.torsion_ratio = {0.30, 0.0};
  return inst;
}

}  // namespace meridian_test
