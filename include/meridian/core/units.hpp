#pragma once
/// \file units.hpp
/// Physical constants and unit conversion factors. Library code works in SI
/// units and radians; these factors are applied only at the edges.

#include <numbers>

namespace meridian::units {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;  ///< radians per turn
inline constexpr double kDegree = kPi / 180.0;            ///< radians per degree
inline constexpr double kArcminute = kDegree / 60.0;      ///< radians per arc-minute
inline constexpr double kArcsecond = kDegree / 3600.0;    ///< radians per arc-second
inline constexpr double kGon = kPi / 200.0;               ///< radians per gon (grad)

/// Earth rotation rate ω_e in rad/s (spec README).
inline constexpr double kEarthRotationRate_rad_s = 7.292115e-5;

constexpr double deg_to_rad(double deg) { return deg * kDegree; }
constexpr double rad_to_deg(double rad) { return rad / kDegree; }
constexpr double arcsec_to_rad(double arcsec) { return arcsec * kArcsecond; }
constexpr double rad_to_arcsec(double rad) { return rad / kArcsecond; }

}  // namespace meridian::units
