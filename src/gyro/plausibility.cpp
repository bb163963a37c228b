#include "meridian/gyro/plausibility.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/error.hpp"

namespace meridian::gyro {
namespace {

std::string implied_period_problem(double implied, const NonTrackingObservations& obs) {
  if (obs.period_s) {
    const double stated = obs.period_s->value;
    if (std::fabs(implied / stated - 1.0) <= kPeriodAgreement) return {};
    return fmt::format("the passages imply a period T_B = {:.1f} s, but period_s is {:g} s", implied, stated);
  }
  if (implied >= kMinPlausiblePeriod_s && implied <= kMaxPlausiblePeriod_s) return {};
  return fmt::format("the passages imply a period T_B = {:.1f} s, outside what a gyro-theodolite can do ({:g} to {:g} s)",
                     implied, kMinPlausiblePeriod_s, kMaxPlausiblePeriod_s);
}

}  // namespace

void check_plausible(const NonTrackingObservations& obs) {
  for (std::size_t i = 0; i < obs.crossings.size(); ++i) {
    const auto& t = obs.crossings[i].times_s;
    for (std::size_t k = 0; k + 2 < t.size(); ++k) {
      const std::string problem = implied_period_problem(t[k + 2] - t[k], obs);
      if (problem.empty()) continue;
      throw InputError(fmt::format("{} (passages {} and {}: {} s and {} s). Were the stopwatch times booked as "
                                   "m.ss numbers (4.39 for 4 min 39 s)? Book seconds, or \"m:ss.s\" strings",
                                   problem, k + 1, k + 3, t[k], t[k + 2]),
                       {"", std::nullopt, fmt::format("crossings[{}].times_s", i)});
    }
  }
  for (std::size_t i = 0; i < obs.reversals_div.size(); ++i)
    if (std::fabs(obs.reversals_div[i]) > kMaxScaleReading_div)
      throw InputError(fmt::format("reversal reading {} div is beyond any eyepiece scale (|a| <= {:g} div): "
                                   "check the unit and the booking",
                                   obs.reversals_div[i], kMaxScaleReading_div),
                       {"", std::nullopt, fmt::format("reversals_div[{}]", i)});
}

}  // namespace meridian::gyro
