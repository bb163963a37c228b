#pragma once
/// \file uncertain.hpp
/// A value with its standard deviation, the currency of every result that
/// Meridian reports (gyro north, azimuths, instrument constants, deflections).

namespace meridian {

/// A value and its standard deviation σ, in the same unit (radians for
/// angles). sigma = 0 means the value is taken as exact; sigma is never
/// negative. Errors of different Uncertain values are independent unless a
/// function says otherwise.
struct Uncertain {
  double value = 0.0;
  double sigma = 0.0;
};

}  // namespace meridian
