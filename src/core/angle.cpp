#include "meridian/core/angle.hpp"

#include <cmath>

namespace meridian {

double wrap_positive_rad(double rad) {
  const double two_pi = 2.0 * units::kPi;
  double r = std::fmod(rad, two_pi);
  if (r < 0) r += two_pi;
  if (r >= two_pi) r = 0.0;  // fmod of a tiny negative number may round up
  return r;
}

double wrap_signed_rad(double rad) {
  double r = wrap_positive_rad(rad + units::kPi) - units::kPi;
  return r;
}

Angle Angle::normalized_positive() const { return Angle(wrap_positive_rad(rad_)); }
Angle Angle::normalized_signed() const { return Angle(wrap_signed_rad(rad_)); }

}  // namespace meridian
