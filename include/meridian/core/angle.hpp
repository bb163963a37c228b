#pragma once
/// \file angle.hpp
/// A strong angle type. The value is stored in radians; construction and
/// access name the unit, so a degree can never be mistaken for a radian.

#include <cmath>
#include <compare>

#include "meridian/core/units.hpp"

namespace meridian {

/// A plane angle: a small value type (one double, in radians) that is
/// copied, not shared. Arithmetic keeps the unit; use the named factories
/// and accessors to convert at the edges.
class Angle {
 public:
  constexpr Angle() = default;

  static constexpr Angle radians(double rad) { return Angle(rad); }
  static constexpr Angle degrees(double deg) { return Angle(deg * units::kDegree); }
  static constexpr Angle arcminutes(double amin) { return Angle(amin * units::kArcminute); }
  static constexpr Angle arcseconds(double asec) { return Angle(asec * units::kArcsecond); }
  static constexpr Angle gon(double g) { return Angle(g * units::kGon); }

  constexpr double rad() const { return rad_; }
  constexpr double deg() const { return rad_ / units::kDegree; }
  constexpr double arcmin() const { return rad_ / units::kArcminute; }
  constexpr double arcsec() const { return rad_ / units::kArcsecond; }
  constexpr double gon() const { return rad_ / units::kGon; }

  /// Direction normalised to [0, 2π) — circle readings and azimuths.
  Angle normalized_positive() const;
  /// Angle normalised to [−π, π) — differences of directions.
  Angle normalized_signed() const;

  constexpr Angle operator-() const { return Angle(-rad_); }
  constexpr Angle& operator+=(Angle o) { rad_ += o.rad_; return *this; }
  constexpr Angle& operator-=(Angle o) { rad_ -= o.rad_; return *this; }
  constexpr Angle& operator*=(double s) { rad_ *= s; return *this; }
  constexpr Angle& operator/=(double s) { rad_ /= s; return *this; }
  friend constexpr Angle operator+(Angle a, Angle b) { return Angle(a.rad_ + b.rad_); }
  friend constexpr Angle operator-(Angle a, Angle b) { return Angle(a.rad_ - b.rad_); }
  friend constexpr Angle operator*(Angle a, double s) { return Angle(a.rad_ * s); }
  friend constexpr Angle operator*(double s, Angle a) { return Angle(a.rad_ * s); }
  friend constexpr Angle operator/(Angle a, double s) { return Angle(a.rad_ / s); }
  friend constexpr double operator/(Angle a, Angle b) { return a.rad_ / b.rad_; }
  friend constexpr auto operator<=>(Angle a, Angle b) = default;

 private:
  constexpr explicit Angle(double rad) : rad_(rad) {}
  double rad_ = 0.0;
};

/// Wrap radians to [0, 2π).
double wrap_positive_rad(double rad);
/// Wrap radians to [−π, π).
double wrap_signed_rad(double rad);

}  // namespace meridian
