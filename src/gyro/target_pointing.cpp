#include "meridian/gyro/target_pointing.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"

namespace meridian::gyro {

TargetDirection reduce_target_rounds(const std::vector<TargetRound>& rounds, double sigma_pointing_rad) {
  if (rounds.empty()) throw InputError("no target round", {"", std::nullopt, "target_rounds"});
  if (!(sigma_pointing_rad >= 0.0) || !std::isfinite(sigma_pointing_rad))
    throw InputError("the pointing sigma must be finite and >= 0", {"", std::nullopt, "target_sigma_arcsec"});
  TargetDirection t;
  for (std::size_t i = 0; i < rounds.size(); ++i) {
    const double left = rounds[i].face_left_rad;
    const double right_as_left = rounds[i].face_right_rad - units::kPi;
    const double two_c = wrap_signed_rad(left - right_as_left);
    if (std::fabs(two_c) > units::kDegree)
      throw InputError(fmt::format("face left {} and face right {} are not 180 deg apart (they differ by {} from it): "
                                   "a face or a reading booked wrong",
                                   format_direction_dms(Angle::radians(left)),
                                   format_direction_dms(Angle::radians(rounds[i].face_right_rad)),
                                   format_dms(Angle::radians(two_c))),
                       {"", std::nullopt, fmt::format("target_rounds[{}]", i)});
    t.two_c_rad.push_back(two_c);
    t.round_rad.push_back(wrap_positive_rad(left - two_c / 2.0));
  }
  // Mean about the first round (rounds may straddle 0°).
  const double first = t.round_rad.front();
  double sum = 0.0, lo = 0.0, hi = 0.0;
  for (double r : t.round_rad) {
    const double d = wrap_signed_rad(r - first);
    sum += d;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  const double n = static_cast<double>(t.round_rad.size());
  const double mean = sum / n;
  double sigma = sigma_pointing_rad / std::sqrt(n);
  if (t.round_rad.size() >= 2) {
    double vv = 0.0;
    for (double r : t.round_rad) vv += std::pow(wrap_signed_rad(r - first) - mean, 2);
    sigma = std::max(sigma, std::sqrt(vv / (n * (n - 1.0))));
  }
  t.reading_rad = {wrap_positive_rad(first + mean), sigma};
  t.spread_rad = hi - lo;
  return t;
}

RoundsAgreement rounds_agreement(const TargetDirection& t, double sigma_round_rad) {
  RoundsAgreement a;
  a.spread_limit_rad = std::max(10.0 * units::kArcsecond, 3.0 * std::sqrt(2.0) * sigma_round_rad);
  if (t.two_c_rad.size() < 2) return a;
  const auto [lo, hi] = std::minmax_element(t.two_c_rad.begin(), t.two_c_rad.end());
  a.two_c_variation_rad = *hi - *lo;
  a.agree = t.spread_rad <= a.spread_limit_rad && a.two_c_variation_rad <= kTwoCVariationLimit_rad;
  return a;
}

}  // namespace meridian::gyro
